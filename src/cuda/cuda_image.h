/* A progressive image on the GPU, shared by the path and photon kernels:
 * one thread per pixel adds a batch of its samples into a float sum, the
 * host launches batch after batch (short launches, which a display GPU's
 * watchdog tolerates, and the same image as one long launch, since every
 * sample's random stream is keyed by its index), then scales by 1 / spp
 * and downloads the image. */
#ifndef IL_CUDA_IMAGE_H
#define IL_CUDA_IMAGE_H

#include "cuda/cuda_util.h"
#include "kernel/kernel_path.h"

/* Sampler: a struct with `__device__ ilk_vec3 operator()(x, y, s) const`,
 * the radiance of sample s of pixel (x, y). */
template <typename Sampler>
__global__ static void il_cuda_pixel_kernel(Sampler sample, uint32_t width, uint32_t height, uint32_t first,
                                            uint32_t n, float *sum)
{
    uint32_t x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= width || y >= height)
        return;
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint32_t s = first; s < first + n; s++) {
        ilk_vec3 L = sample(x, y, s);
        /* Drop non-finite samples, as the CPU film does. */
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z)) {
            r += L.x;
            g += L.y;
            b += L.z;
        }
    }
    float *o = sum + 3 * ((size_t)y * width + x);
    o[0] += r;
    o[1] += g;
    o[2] += b;
}

__global__ static void il_cuda_scale_kernel(float *v, size_t n, float s)
{
    size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n)
        v[i] *= s;
}

/* Renders `spp` samples per pixel in launches of `batch` into rgb (host,
 * 3 * width * height floats).  *seconds (may be NULL) gets the GPU time of
 * the sampling launches; `what` names the kernel in error messages. */
template <typename Sampler>
static il_status il_cuda_progressive_image(Sampler sample, uint32_t width, uint32_t height, uint32_t spp,
                                           uint32_t batch, float *rgb, double *seconds, const char *what,
                                           il_error *err)
{
    float *sum = NULL;
    size_t values = 3 * (size_t)width * height;
    il_status st = il_cuda_check(cudaMalloc((void **)&sum, sizeof(float) * values), "allocating the image", err);
    if (st == IL_OK)
        st = il_cuda_check(cudaMemset(sum, 0, sizeof(float) * values), "cudaMemset", err);
    if (st != IL_OK) {
        cudaFree(sum);
        return st;
    }
    cudaEvent_t e0, e1;
    cudaEventCreate(&e0);
    cudaEventCreate(&e1);
    dim3 block(8, 8), grid((width + 7) / 8, (height + 7) / 8);
    cudaEventRecord(e0);
    for (uint32_t first = 0; first < spp && st == IL_OK; first += batch) {
        uint32_t n = spp - first < batch ? spp - first : batch;
        il_cuda_pixel_kernel<<<grid, block>>>(sample, width, height, first, n, sum);
        st = il_cuda_check(cudaGetLastError(), what, err);
    }
    cudaEventRecord(e1);
    if (st == IL_OK) {
        il_cuda_scale_kernel<<<(uint32_t)((values + 255) / 256), 256>>>(sum, values, 1.0f / (float)spp);
        if ((st = il_cuda_check(cudaDeviceSynchronize(), what, err)) == IL_OK)
            st = il_cuda_check(cudaMemcpy(rgb, sum, sizeof(float) * values, cudaMemcpyDeviceToHost),
                               "downloading the image", err);
        float ms = 0.0f;
        cudaEventElapsedTime(&ms, e0, e1);
        if (seconds)
            *seconds = 1e-3 * ms;
    }
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    cudaFree(sum);
    return st;
}

#endif
