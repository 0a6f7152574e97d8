/* The path-tracing megakernel: one thread per pixel runs ilk_path_sample
 * (kernel/kernel_path.h, the code the CPU tests check against il_render)
 * for a batch of its samples and adds them into a float accumulator; the
 * host launches batch after batch (progressive: short launches, which a
 * display GPU's watchdog tolerates, and the same image as one long launch,
 * since every sample's random stream is keyed by its index), then scales by
 * 1 / spp.  The scene's flat arrays are copied with cudaMalloc/cudaMemcpy;
 * nothing is managed memory. */
#include "cuda/cuda_backend.h"
#include "cuda/cuda_scene.h"
#include "kernel/kernel_path.h"

/* Samples per launch. */
#define PT_BATCH 16u

__global__ static void pt_kernel(ilk_scene sc, uint32_t first, uint32_t n, float *sum)
{
    uint32_t x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= sc.width || y >= sc.height)
        return;
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint32_t i = first; i < first + n; i++) {
        ilk_vec3 L = ilk_path_sample(&sc, x, y, i);
        /* Drop non-finite samples, as the CPU film does. */
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z)) {
            r += L.x;
            g += L.y;
            b += L.z;
        }
    }
    float *o = sum + 3 * ((size_t)y * sc.width + x);
    o[0] += r;
    o[1] += g;
    o[2] += b;
}

__global__ static void pt_scale_kernel(float *v, size_t n, float s)
{
    size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n)
        v[i] *= s;
}

extern "C" il_status il_cuda_render_pt(const il_scene *scene, uint32_t width, uint32_t height, uint32_t spp,
                                       uint32_t max_depth, uint64_t seed, float *rgb, il_error *err)
{
    if (width == 0 || height == 0)
        return il_fail(err, IL_ERR_INVALID, "CUDA render: empty image");
    il_status st = il_cuda_require_device(err);
    if (st != IL_OK)
        return st;
    il_kscene ks;
    if ((st = il_kscene_build(scene, width, height, max_depth, seed, &ks, err)) != IL_OK)
        return st;
    il_cuda_scene d;
    if ((st = il_cuda_scene_upload(&ks, &d, err)) != IL_OK) {
        il_kscene_free(&ks);
        return st;
    }
    float *sum = NULL;
    size_t values = 3 * (size_t)width * height;
    if ((st = il_cuda_alloc(&sum, values, "allocating the image", err)) == IL_OK &&
        (st = il_cuda_check(cudaMemset(sum, 0, sizeof(float) * values), "cudaMemset", err)) == IL_OK) {
        uint32_t total = spp ? spp : 16;
        dim3 block(8, 8), grid((width + 7) / 8, (height + 7) / 8);
        for (uint32_t first = 0; first < total && st == IL_OK; first += PT_BATCH) {
            uint32_t n = total - first < PT_BATCH ? total - first : PT_BATCH;
            pt_kernel<<<grid, block>>>(d.view, first, n, sum);
            st = il_cuda_check(cudaGetLastError(), "launching the path-tracing kernel", err);
        }
        if (st == IL_OK) {
            pt_scale_kernel<<<(uint32_t)((values + 255) / 256), 256>>>(sum, values, 1.0f / (float)total);
            if ((st = il_cuda_check(cudaDeviceSynchronize(), "the path-tracing kernel", err)) == IL_OK)
                st = il_cuda_check(cudaMemcpy(rgb, sum, sizeof(float) * values, cudaMemcpyDeviceToHost),
                                   "downloading the image", err);
        }
    }
    cudaFree(sum);
    il_cuda_scene_free(&d);
    il_kscene_free(&ks);
    return st;
}
