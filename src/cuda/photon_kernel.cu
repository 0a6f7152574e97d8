/* Photon tracing, the hashed grid and the per-pixel gather on the GPU, with
 * the shared kernels that the CPU tests run (kernel/kernel_photon.h,
 * kernel_grid.h, kernel_photon_gather.h):
 *
 *   trace   one thread per photon, max_depth record slots each;
 *   key     one thread per slot: cell hash (empty slots: ILK_GRID_NO_KEY);
 *   sort    cub::DeviceRadixSort::SortPairs on (key, slot), stable, so the
 *           order is the CPU's (kernel/kernel_photon_map.c sorts by key,
 *           then slot);
 *   gather  photons[i] = slots[value[i]], then cell start/end where the
 *           sorted key changes (no atomics);
 *   render  one thread per pixel, one launch per batch of samples added
 *           into a double accumulator (progressive: short launches).
 *
 * Plain cudaMalloc/cudaMemcpy; nothing returns to the host between the
 * steps but the stored-photon count. */
#include <cub/device/device_radix_sort.cuh>
#include "cuda/cuda_backend.h"
#include "cuda/cuda_image.h"
#include "cuda/cuda_scene.h"
#include "kernel/kernel_photon_gather.h"
#include "kernel/kernel_photon_map.h"

__global__ static void photon_trace_kernel(ilk_scene sc, uint32_t num_emitted, ilk_photon *slots)
{
    uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < num_emitted)
        ilk_photon_trace(&sc, i, num_emitted, slots + (size_t)i * sc.max_depth);
}

__global__ static void photon_key_kernel(const ilk_photon *slots, uint32_t n, float inv_cell, uint32_t mask,
                                         uint32_t *keys, uint32_t *values)
{
    uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n)
        return;
    keys[i] = ilk_grid_key(&slots[i], inv_cell, mask);
    values[i] = i;
}

__global__ static void photon_reorder_kernel(const ilk_photon *slots, const uint32_t *sorted_keys,
                                             const uint32_t *values, uint32_t n, ilk_photon *photons,
                                             uint32_t *cell_start, uint32_t *cell_end, uint32_t *count)
{
    uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n)
        return;
    photons[i] = slots[values[i]];
    ilk_grid_mark(sorted_keys, n, i, cell_start, cell_end);
    /* The first slot without a key (empty, or a first hit) is the count. */
    if (sorted_keys[i] != ILK_GRID_NO_KEY && (i + 1 == n || sorted_keys[i + 1] == ILK_GRID_NO_KEY))
        *count = i + 1;
}

/* One gathered sample of a pixel (il_cuda_pixel_kernel's sampler). */
struct photon_sampler {
    ilk_scene sc;
    ilk_grid g;
    float radius;
    __device__ ilk_vec3 operator()(uint32_t x, uint32_t y, uint32_t s, uint32_t *rays) const
    {
        return ilk_photon_pixel_sample(&sc, &g, radius, x, y, s, rays);
    }
};

/* The device photon map. */
typedef struct dev_map {
    ilk_photon *slots, *photons;
    uint32_t *keys, *keys_sorted, *values, *values_sorted, *cell_start, *cell_end, *count;
    void *temp;
    uint64_t num_slots;
    ilk_grid grid;                 /* device pointers */
} dev_map;

static void dev_map_free(dev_map *m)
{
    cudaFree(m->slots);
    cudaFree(m->photons);
    cudaFree(m->keys);
    cudaFree(m->keys_sorted);
    cudaFree(m->values);
    cudaFree(m->values_sorted);
    cudaFree(m->cell_start);
    cudaFree(m->cell_end);
    cudaFree(m->count);
    cudaFree(m->temp);
    memset(m, 0, sizeof *m);
}

static uint32_t blocks_for(uint64_t n, uint32_t block) { return (uint32_t)((n + block - 1) / block); }

/* Traces and builds on the device; the stats' times when stats is given. */
static il_status build_map(const il_cuda_scene *d, uint32_t num_emitted, float radius, dev_map *m,
                           il_cuda_photon_stats *stats, il_error *err)
{
    memset(m, 0, sizeof *m);
    if (num_emitted == 0)
        return il_fail(err, IL_ERR_INVALID, "photon kernel: no photons to emit");
    if (!(radius > 0.0f) || !isfinite(radius))
        return il_fail(err, IL_ERR_INVALID, "photon kernel: the gather radius must be positive (got %g)",
                       (double)radius);
    uint64_t n = (uint64_t)num_emitted * d->view.max_depth;
    if (n > INT32_MAX)
        return il_fail(err, IL_ERR_INVALID, "photon kernel: %u photons x %u bounces is more than 2^31 records",
                       num_emitted, d->view.max_depth);
    uint32_t mask = il_kgrid_hash_mask(n);
    float cell = ilk_grid_cell_size(radius), inv_cell = 1.0f / cell;
    il_status st;
    cudaEvent_t e0, e1, e2;
    cudaEventCreate(&e0);
    cudaEventCreate(&e1);
    cudaEventCreate(&e2);
    size_t temp_bytes = 0;
    if ((st = il_cuda_alloc(&m->slots, n, "allocating the photon slots", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->photons, n, "allocating the sorted photons", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->keys, n, "allocating the grid keys", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->keys_sorted, n, "allocating the grid keys", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->values, n, "allocating the grid values", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->values_sorted, n, "allocating the grid values", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->cell_start, (size_t)mask + 1, "allocating the grid cells", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->cell_end, (size_t)mask + 1, "allocating the grid cells", err)) == IL_OK &&
        (st = il_cuda_alloc(&m->count, 1, "allocating the photon count", err)) == IL_OK &&
        (st = il_cuda_check(cub::DeviceRadixSort::SortPairs(NULL, temp_bytes, m->keys, m->keys_sorted, m->values,
                                                           m->values_sorted, (int)n),
                            "sizing the radix sort", err)) == IL_OK &&
        (st = il_cuda_check(cudaMalloc(&m->temp, temp_bytes ? temp_bytes : 1), "allocating the radix sort", err)) ==
            IL_OK &&
        (st = il_cuda_check(cudaMemset(m->cell_start, 0, sizeof(uint32_t) * ((size_t)mask + 1)), "cudaMemset", err)) ==
            IL_OK &&
        (st = il_cuda_check(cudaMemset(m->cell_end, 0, sizeof(uint32_t) * ((size_t)mask + 1)), "cudaMemset", err)) ==
            IL_OK &&
        (st = il_cuda_check(cudaMemset(m->count, 0, sizeof(uint32_t)), "cudaMemset", err)) == IL_OK) {
        const uint32_t block = 128;
        cudaEventRecord(e0);
        photon_trace_kernel<<<blocks_for(num_emitted, block), block>>>(d->view, num_emitted, m->slots);
        cudaEventRecord(e1);
        photon_key_kernel<<<blocks_for(n, block), block>>>(m->slots, (uint32_t)n, inv_cell, mask, m->keys, m->values);
        if ((st = il_cuda_check(cudaGetLastError(), "launching the photon kernels", err)) == IL_OK &&
            (st = il_cuda_check(cub::DeviceRadixSort::SortPairs(m->temp, temp_bytes, m->keys, m->keys_sorted,
                                                               m->values, m->values_sorted, (int)n),
                                "the radix sort by cell", err)) == IL_OK) {
            photon_reorder_kernel<<<blocks_for(n, block), block>>>(m->slots, m->keys_sorted, m->values_sorted,
                                                                   (uint32_t)n, m->photons, m->cell_start,
                                                                   m->cell_end, m->count);
            cudaEventRecord(e2);
            uint32_t count = 0;
            if ((st = il_cuda_check(cudaGetLastError(), "launching the grid kernel", err)) == IL_OK &&
                (st = il_cuda_check(cudaMemcpy(&count, m->count, sizeof count, cudaMemcpyDeviceToHost),
                                    "the photon kernels", err)) == IL_OK) {
                m->num_slots = n;
                m->grid = ilk_grid_make(m->photons, count, m->cell_start, m->cell_end, mask, cell);
                if (stats) {
                    float ms_trace = 0.0f, ms_build = 0.0f;
                    cudaEventElapsedTime(&ms_trace, e0, e1);
                    cudaEventElapsedTime(&ms_build, e1, e2);
                    stats->emitted = num_emitted;
                    stats->stored = count;
                    stats->seconds_trace = 1e-3 * ms_trace;
                    stats->seconds_build = 1e-3 * ms_build;
                }
            }
        }
    }
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    cudaEventDestroy(e2);
    if (st != IL_OK)
        dev_map_free(m);
    return st;
}

extern "C" il_status il_cuda_photon_map(const il_kscene *ks, uint32_t num_emitted, float radius,
                                        ilk_photon *photons, uint32_t *cell_start, uint32_t *cell_end,
                                        uint32_t *count, il_error *err)
{
    il_status st = il_cuda_require_device(err);
    if (st != IL_OK)
        return st;
    il_cuda_scene d;
    if ((st = il_cuda_scene_upload(ks, &d, err)) != IL_OK)
        return st;
    dev_map m;
    if ((st = build_map(&d, num_emitted, radius, &m, NULL, err)) == IL_OK) {
        size_t cells = (size_t)m.grid.hash_mask + 1;
        *count = m.grid.count;
        if ((st = il_cuda_check(cudaMemcpy(photons, m.photons, sizeof(ilk_photon) * m.num_slots,
                                           cudaMemcpyDeviceToHost), "downloading the photons", err)) == IL_OK &&
            (st = il_cuda_check(cudaMemcpy(cell_start, m.cell_start, sizeof(uint32_t) * cells,
                                           cudaMemcpyDeviceToHost), "downloading the grid", err)) == IL_OK)
            st = il_cuda_check(cudaMemcpy(cell_end, m.cell_end, sizeof(uint32_t) * cells, cudaMemcpyDeviceToHost),
                               "downloading the grid", err);
        dev_map_free(&m);
    }
    il_cuda_scene_free(&d);
    return st;
}

extern "C" il_status il_cuda_render_photon(const il_scene *scene, uint32_t width, uint32_t height, uint32_t spp,
                                           uint32_t max_depth, uint64_t seed, uint32_t num_emitted, float radius,
                                           float *rgb, il_cuda_photon_stats *stats, il_cuda_run *run,
                                           il_error *err)
{
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    il_kscene ks;
    il_cuda_scene d;
    il_status st = il_cuda_scene_prepare(scene, width, height, max_depth, seed, &ks, &d, err);
    if (st != IL_OK)
        return st;
    il_cuda_photon_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    dev_map m;
    if ((st = build_map(&d, num_emitted, radius, &m, stats, err)) == IL_OK) {
        /* Launches of a few samples each. */
        st = il_cuda_progressive_image(photon_sampler{d.view, m.grid, radius}, width, height,
                                       il_cuda_spp(spp, run, 16), 4, rgb, &stats->seconds_gather, run, &t0,
                                       "the gather kernel", err);
        dev_map_free(&m);
    }
    il_cuda_scene_free(&d);
    il_kscene_free(&ks);
    return st;
}
