/* Radiosity gathering on the GPU with the shared kernel (kernel/
 * kernel_radiosity.h), the packing of kernel/kernel_radiosity_scene.c:
 *
 *   rows    one thread per ILK_RAD_ROW_PART rays of a row (the CPU
 *           solver's rays, the generator advanced to the part's first)
 *           writes the patch each ray sees;
 *   sweep   one warp per patch: the Jacobi sweep in increments
 *           (kernel_radiosity.h): the patch's change from the previous
 *           sweep's changes (two device buffers, swapped), added to its
 *           radiance, and the power it carries;
 *   reduce  one block sums the changes in a fixed order (deterministic, in
 *           double), and only that number goes back to the host, to decide
 *           whether to stop.
 *
 * The radiance stays on the device until the solve ends (no per-sweep
 * write-back through the host, which the seed program's gather had). */
#include "cuda/cuda_backend.h"
#include "cuda/cuda_scene.h"
#include "kernel/kernel_radiosity_scene.h"
#include "methods/radiosity/rad_stall.h"

#define REDUCE_THREADS 1024

/* One thread per ILK_RAD_ROW_PART samples of a row. */
__global__ static void rad_row_kernel(ilk_rad_scene sc, uint32_t parts, uint32_t *hits)
{
    uint64_t t = (uint64_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (t >= (uint64_t)sc.num_patches * parts)
        return;
    uint32_t i = (uint32_t)(t / parts), first = (uint32_t)(t % parts) * ILK_RAD_ROW_PART;
    ilk_rad_row_part(&sc, i, first, ILK_RAD_ROW_PART, hits + (size_t)i * sc.samples + first);
}

/* One warp per patch: each lane sums a strided share of the row's hits,
 * the lanes' sums are added by shuffles, lane 0 writes the change and adds
 * it to the radiance (L is only read by its own patch's lane 0). */
__global__ static void rad_sweep_kernel(ilk_rad_scene sc, const uint32_t *hits, const ilk_vec3 *delta,
                                        ilk_vec3 *L, ilk_vec3 *next, float *change)
{
    uint32_t i = (uint32_t)(((uint64_t)blockIdx.x * blockDim.x + threadIdx.x) / 32u), lane = threadIdx.x % 32u;
    if (i >= sc.num_patches)
        return;            /* whole warps leave together: blockDim is a multiple of 32 */
    ilk_vec3 s = ilk_rad_sum(&sc, hits + (size_t)i * sc.samples, lane, 32u, delta);
    for (int off = 16; off > 0; off /= 2) {
        s.x += __shfl_down_sync(0xffffffffu, s.x, off);
        s.y += __shfl_down_sync(0xffffffffu, s.y, off);
        s.z += __shfl_down_sync(0xffffffffu, s.z, off);
    }
    if (lane == 0) {
        ilk_vec3 d = ilk_rad_bounce(&sc, i, s);
        next[i] = d;
        L[i] = ilk_add(L[i], d);
        change[i] = ilk_rad_change(&sc.patches[i], d);
    }
}

/* One block: each thread sums a strided share, then a tree in shared
 * memory; the same order every time. */
__global__ static void rad_reduce_kernel(const float *change, uint32_t n, double *sum)
{
    __shared__ double part[REDUCE_THREADS];
    double s = 0.0;
    for (uint32_t i = threadIdx.x; i < n; i += REDUCE_THREADS)
        s += change[i];
    part[threadIdx.x] = s;
    __syncthreads();
    for (uint32_t w = REDUCE_THREADS / 2; w > 0; w /= 2) {
        if (threadIdx.x < w)
            part[threadIdx.x] += part[threadIdx.x + w];
        __syncthreads();
    }
    if (threadIdx.x == 0)
        *sum = part[0];
}

extern "C" il_status il_cuda_radiosity_solve(const il_krad *k, float tolerance, uint32_t max_steps,
                                             ilk_vec3 *radiance, uint32_t *steps, double *fraction,
                                             il_cuda_radiosity_stats *stats, il_error *err)
{
    il_status st = il_cuda_require_device(err);
    if (st != IL_OK)
        return st;
    const ilk_rad_scene *h = &k->view;
    uint32_t n = h->num_patches;
    ilk_bvh_node *nodes = NULL;
    ilk_tri *tris = NULL;
    ilk_patch *patches = NULL;
    ilk_vec3 *delta = NULL, *L = NULL, *next = NULL;
    uint32_t *hits = NULL;
    float *change = NULL;
    double *sum = NULL;
    uint32_t step = 0;
    double frac = k->initial_power > 0.0 ? 1.0 : 0.0;
    il_rad_stall stall;
    il_rad_stall_start(&stall, 1);
    bool stuck = false;
    cudaEvent_t e0, e1, e2;
    cudaEventCreate(&e0);
    cudaEventCreate(&e1);
    cudaEventCreate(&e2);
    if ((st = il_cuda_upload(&nodes, k->bvh.nodes, k->bvh.num_nodes, "uploading the BVH", err)) == IL_OK &&
        (st = il_cuda_upload(&tris, k->bvh.tris, k->bvh.num_tris, "uploading the triangles", err)) == IL_OK &&
        (st = il_cuda_upload(&patches, k->patches, n, "uploading the patches", err)) == IL_OK &&
        (st = il_cuda_upload(&delta, k->direct, n, "uploading the direct light", err)) == IL_OK &&
        (st = il_cuda_upload(&L, k->direct, n, "uploading the radiance", err)) == IL_OK &&
        (st = il_cuda_alloc(&next, n, "allocating the sweep changes", err)) == IL_OK &&
        (st = il_cuda_alloc(&hits, (size_t)n * h->samples, "allocating the form-factor rows", err)) == IL_OK &&
        (st = il_cuda_alloc(&change, n, "allocating the changes' power", err)) == IL_OK &&
        (st = il_cuda_alloc(&sum, 1, "allocating the sweep sum", err)) == IL_OK && n > 0) {
        ilk_rad_scene sc = *h;
        sc.bvh.nodes = nodes;
        sc.bvh.tris = tris;
        sc.patches = patches;
        const uint32_t parts = (h->samples + ILK_RAD_ROW_PART - 1) / ILK_RAD_ROW_PART, block = 128;
        const uint64_t row_threads = (uint64_t)n * parts, sweep_threads = 32u * (uint64_t)n;
        const uint32_t row_blocks = (uint32_t)((row_threads + block - 1) / block);
        const uint32_t blocks = (uint32_t)((sweep_threads + block - 1) / block);
        cudaEventRecord(e0);
        rad_row_kernel<<<row_blocks, block>>>(sc, parts, hits);
        cudaEventRecord(e1);
        st = il_cuda_check(cudaGetLastError(), "launching the form-factor kernel", err);
        while (st == IL_OK && k->initial_power > 0.0 && (max_steps == 0 || step < max_steps)) {
            rad_sweep_kernel<<<blocks, block>>>(sc, hits, delta, L, next, change);
            rad_reduce_kernel<<<1, REDUCE_THREADS>>>(change, n, sum);
            double s = 0.0;
            if ((st = il_cuda_check(cudaGetLastError(), "launching the gather kernel", err)) != IL_OK ||
                (st = il_cuda_check(cudaMemcpy(&s, sum, sizeof s, cudaMemcpyDeviceToHost), "the gather kernel",
                                    err)) != IL_OK)
                break;
            ilk_vec3 *t = delta;
            delta = next;
            next = t;
            frac = s / k->initial_power;
            step++;
            if (frac < tolerance || (stuck = il_rad_stalled(&stall, step, frac)))
                break;
        }
        cudaEventRecord(e2);
        if (st == IL_OK)
            st = il_cuda_check(cudaMemcpy(radiance, L, sizeof(ilk_vec3) * n, cudaMemcpyDeviceToHost),
                               "downloading the radiance", err);
        if (st == IL_OK && stats) {
            float ms_ff = 0.0f, ms_solve = 0.0f;
            cudaEventSynchronize(e2);
            cudaEventElapsedTime(&ms_ff, e0, e1);
            cudaEventElapsedTime(&ms_solve, e1, e2);
            stats->seconds_form_factors = 1e-3 * ms_ff;
            stats->seconds_sweeps = 1e-3 * ms_solve;
            stats->stalled = stuck;
        }
    }
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    cudaEventDestroy(e2);
    cudaFree(nodes);
    cudaFree(tris);
    cudaFree(patches);
    cudaFree(delta);
    cudaFree(L);
    cudaFree(next);
    cudaFree(hits);
    cudaFree(change);
    cudaFree(sum);
    if (steps)
        *steps = step;
    if (fraction)
        *fraction = frac;
    return st;
}
