/* A progressive image on the GPU, shared by the path and photon kernels:
 * one thread per pixel adds a batch of its samples into a double sum (as
 * the CPU film does: a float sum of batches stops growing once a batch is
 * below half its ulp, after about 2^28 samples of a pixel, and rounds every
 * batch long before; an hour at 512x512 on an H200 is 10^7 samples), the
 * host launches batch after batch (short launches, which a display GPU's
 * watchdog tolerates, and the same image as one long launch, since every
 * sample's random stream is keyed by its index), waits for each to report
 * progress and to stop on time or on request (il_cuda_run), then scales by
 * 1 / samples done and downloads the image. */
#ifndef IL_CUDA_IMAGE_H
#define IL_CUDA_IMAGE_H

#include <time.h>
#include "cuda/cuda_backend.h"
#include "cuda/cuda_util.h"
#include "kernel/kernel_path.h"

/* Sampler: a struct with `__device__ ilk_vec3 operator()(x, y, s, rays)
 * const`, the radiance of sample s of pixel (x, y), adding the rays it
 * casts to *rays.  Each thread adds its rays to *ray_total once. */
template <typename Sampler>
__global__ static void il_cuda_pixel_kernel(Sampler sample, uint32_t width, uint32_t height, uint32_t first,
                                            uint32_t n, double *sum, unsigned long long *ray_total)
{
    uint32_t x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= width || y >= height)
        return;
    float r = 0.0f, g = 0.0f, b = 0.0f;
    uint32_t rays = 0;
    for (uint32_t s = first; s < first + n; s++) {
        ilk_vec3 L = sample(x, y, s, &rays);
        /* Drop non-finite samples, as the CPU film does. */
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z)) {
            r += L.x;
            g += L.y;
            b += L.z;
        }
    }
    double *o = sum + 3 * ((size_t)y * width + x);
    o[0] += r;
    o[1] += g;
    o[2] += b;
    atomicAdd(ray_total, (unsigned long long)rays);
}

/* out = sum * scale, in float. */
__global__ static void il_cuda_resolve_kernel(const double *sum, float *out, size_t n, double scale)
{
    size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n)
        out[i] = (float)(sum[i] * scale);
}

/* The sums divided by the samples done, into the host's rgb (through the
 * device buffer out). */
static inline il_status il_cuda_resolve(const double *sum, float *out, size_t values, uint32_t done, float *rgb,
                                        const char *what, il_error *err)
{
    il_cuda_resolve_kernel<<<(uint32_t)((values + 255) / 256), 256>>>(sum, out, values, 1.0 / (double)done);
    il_status st = il_cuda_check(cudaGetLastError(), what, err);
    if (st == IL_OK)
        st = il_cuda_check(cudaMemcpy(rgb, out, sizeof(float) * values, cudaMemcpyDeviceToHost), what, err);
    return st;
}

/* The samples per pixel a render asks for: spp, or when 0 no bound with a
 * time limit and `fallback` without. */
static inline uint32_t il_cuda_spp(uint32_t spp, const il_cuda_run *run, uint32_t fallback)
{
    if (spp)
        return spp;
    return run && run->time_limit > 0.0 ? UINT32_MAX : fallback;
}

static inline double il_cuda_seconds_since(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return (double)(t1.tv_sec - t0->tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0->tv_nsec);
}

/* The running image: the sums so far divided by the samples, as the final
 * image is, downloaded into rgb (the caller's host buffer for the final
 * image), then handed to run->image_fn. */
static inline il_status il_cuda_running_image(const double *sum, float *out, size_t values, uint32_t done,
                                              uint32_t width, uint32_t height, float *rgb, const il_cuda_run *run,
                                              il_error *err)
{
    il_status st = il_cuda_resolve(sum, out, values, done, rgb, "downloading the running image", err);
    if (st != IL_OK)
        return st;
    run->image_fn(rgb, width, height, done, run->image_user);
    return IL_OK;
}

/* Renders up to `spp` samples per pixel in launches of `batch` into rgb
 * (host, 3 * width * height floats), as `run` says (may be NULL; started
 * at t0).  *seconds (may be NULL) gets the GPU time of the sampling
 * launches; `what` names the kernel in error messages. */
template <typename Sampler>
static il_status il_cuda_progressive_image(Sampler sample, uint32_t width, uint32_t height, uint32_t spp,
                                           uint32_t batch, float *rgb, double *seconds, il_cuda_run *run,
                                           const struct timespec *t0, const char *what, il_error *err)
{
    double *sum = NULL;
    float *out = NULL;
    unsigned long long *ray_total = NULL, rays = 0;
    size_t values = 3 * (size_t)width * height;
    il_status st = il_cuda_check(cudaMalloc((void **)&sum, sizeof(double) * values), "allocating the image", err);
    if (st == IL_OK)
        st = il_cuda_check(cudaMalloc((void **)&out, sizeof(float) * values), "allocating the image", err);
    if (st == IL_OK)
        st = il_cuda_check(cudaMalloc((void **)&ray_total, sizeof *ray_total), "allocating the ray count", err);
    if (st == IL_OK)
        st = il_cuda_check(cudaMemset(sum, 0, sizeof(double) * values), "cudaMemset", err);
    if (st == IL_OK)
        st = il_cuda_check(cudaMemset(ray_total, 0, sizeof *ray_total), "cudaMemset", err);
    if (st != IL_OK) {
        cudaFree(sum);
        cudaFree(out);
        cudaFree(ray_total);
        return st;
    }
    cudaEvent_t e0, e1;
    cudaEventCreate(&e0);
    cudaEventCreate(&e1);
    dim3 block(8, 8), grid((width + 7) / 8, (height + 7) / 8);
    uint32_t done = 0;
    bool go_on = true;
    double next_image = run ? run->image_every : 0.0;
    cudaEventRecord(e0);
    while (done < spp && go_on && st == IL_OK) {
        uint32_t n = spp - done < batch ? spp - done : batch;
        il_cuda_pixel_kernel<<<grid, block>>>(sample, width, height, done, n, sum, ray_total);
        st = il_cuda_check(cudaGetLastError(), what, err);
        if (st == IL_OK && run)
            /* Wait for the launch: the report and the clock count finished samples. */
            st = il_cuda_check(cudaMemcpy(&rays, ray_total, sizeof rays, cudaMemcpyDeviceToHost), what, err);
        if (st != IL_OK)
            break;
        done += n;
        if (!run)
            continue;
        double s = il_cuda_seconds_since(t0);
        il_render_progress p = {};
        p.passes_done = done;
        p.passes_total = run->time_limit > 0.0 ? 0 : spp;
        p.seconds = s;
        p.time_limit = run->time_limit;
        p.rays = rays;
        if (run->progress && !run->progress(&p, run->progress_user))
            go_on = false;
        if (run->time_limit > 0.0 && s >= run->time_limit)
            go_on = false;
        if (run->image_fn && run->image_every > 0.0 && go_on && done < spp && s >= next_image) {
            while (next_image <= s)
                next_image += run->image_every;
            st = il_cuda_running_image(sum, out, values, done, width, height, rgb, run, err);
        }
    }
    cudaEventRecord(e1);
    if (st == IL_OK) {
        if ((st = il_cuda_resolve(sum, out, values, done ? done : 1, rgb, "downloading the image", err)) == IL_OK)
            st = il_cuda_check(cudaMemcpy(&rays, ray_total, sizeof rays, cudaMemcpyDeviceToHost),
                               "downloading the ray count", err);
        float ms = 0.0f;
        cudaEventElapsedTime(&ms, e0, e1);
        if (seconds)
            *seconds = 1e-3 * ms;
        if (run) {
            run->spp_done = done;
            run->rays = rays;
        }
    }
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    cudaFree(sum);
    cudaFree(out);
    cudaFree(ray_total);
    return st;
}

#endif
