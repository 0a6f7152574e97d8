/* Ray casting on the GPU with the shared kernel (kernel/kernel_bvh.h): one
 * thread per ray, the BVH and triangles copied as they are (the flat layout
 * has no pointers).  The CPU tests run the same ilk_bvh_closest /
 * ilk_bvh_occluded compiled by gcc; tests/cuda/test_cuda_trace.c compares
 * the two on a GPU. */
#include "cuda/cuda_backend.h"
#include "cuda/cuda_util.h"
#include "kernel/kernel_bvh.h"

__global__ static void trace_kernel(ilk_bvh bvh, const ilk_ray *rays, uint32_t n, ilk_hit *hits,
                                    uint8_t *occluded)
{
    uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= n)
        return;
    ilk_ray r = rays[i];
    if (hits) {
        ilk_hit h;
        ilk_bvh_closest(&bvh, &r, &h);
        hits[i] = h;
    }
    if (occluded)
        occluded[i] = ilk_bvh_occluded(&bvh, &r) ? 1 : 0;
}

typedef struct dev_buffers {
    ilk_bvh_node *nodes;
    ilk_tri *tris;
    ilk_ray *rays;
    ilk_hit *hits;
    uint8_t *occ;
} dev_buffers;

static void free_all(dev_buffers *b)
{
    cudaFree(b->nodes);
    cudaFree(b->tris);
    cudaFree(b->rays);
    cudaFree(b->hits);
    cudaFree(b->occ);
}

extern "C" il_status il_cuda_trace_rays(const il_kbvh *bvh, const ilk_ray *rays, uint32_t n, ilk_hit *hits,
                                        uint8_t *occluded, il_error *err)
{
    if (n == 0)
        return IL_OK;
    il_status st = il_cuda_require_device(err);
    if (st != IL_OK)
        return st;
    dev_buffers d = {NULL, NULL, NULL, NULL, NULL};
    size_t nodes_bytes = sizeof(ilk_bvh_node) * bvh->num_nodes, tris_bytes = sizeof(ilk_tri) * bvh->num_tris;
#define TRY(call, what)                                  \
    do {                                                 \
        if ((st = il_cuda_check((call), what, err)) != IL_OK) { \
            free_all(&d);                                \
            return st;                                   \
        }                                                \
    } while (0)
    if (bvh->num_nodes) {
        TRY(cudaMalloc((void **)&d.nodes, nodes_bytes), "cudaMalloc (BVH nodes)");
        TRY(cudaMalloc((void **)&d.tris, tris_bytes), "cudaMalloc (triangles)");
        TRY(cudaMemcpy(d.nodes, bvh->nodes, nodes_bytes, cudaMemcpyHostToDevice), "cudaMemcpy (BVH nodes)");
        TRY(cudaMemcpy(d.tris, bvh->tris, tris_bytes, cudaMemcpyHostToDevice), "cudaMemcpy (triangles)");
    }
    TRY(cudaMalloc((void **)&d.rays, sizeof(ilk_ray) * n), "cudaMalloc (rays)");
    TRY(cudaMemcpy(d.rays, rays, sizeof(ilk_ray) * n, cudaMemcpyHostToDevice), "cudaMemcpy (rays)");
    if (hits)
        TRY(cudaMalloc((void **)&d.hits, sizeof(ilk_hit) * n), "cudaMalloc (hits)");
    if (occluded)
        TRY(cudaMalloc((void **)&d.occ, n), "cudaMalloc (occlusion)");
    ilk_bvh view;
    view.nodes = d.nodes;
    view.tris = d.tris;
    view.num_nodes = bvh->num_nodes;
    view.num_tris = bvh->num_tris;
    const uint32_t block = 128;
    trace_kernel<<<(n + block - 1) / block, block>>>(view, d.rays, n, d.hits, d.occ);
    TRY(cudaGetLastError(), "launching the trace kernel");
    TRY(cudaDeviceSynchronize(), "the trace kernel");
    if (hits)
        TRY(cudaMemcpy(hits, d.hits, sizeof(ilk_hit) * n, cudaMemcpyDeviceToHost), "cudaMemcpy (hits)");
    if (occluded)
        TRY(cudaMemcpy(occluded, d.occ, n, cudaMemcpyDeviceToHost), "cudaMemcpy (occlusion)");
#undef TRY
    free_all(&d);
    return IL_OK;
}
