/* The path-tracing megakernel: one thread per pixel runs ilk_path_sample
 * (kernel/kernel_path.h, the code the CPU tests check against il_render) for
 * each of its samples and writes the pixel's mean.  The scene's flat arrays
 * are copied with cudaMalloc/cudaMemcpy; nothing is managed memory. */
#include "cuda/cuda_backend.h"
#include "cuda/cuda_util.h"
#include "kernel/kernel_path.h"
#include "kernel/kernel_scene.h"

__global__ static void pt_kernel(ilk_scene sc, uint32_t spp, float *rgb)
{
    uint32_t x = blockIdx.x * blockDim.x + threadIdx.x, y = blockIdx.y * blockDim.y + threadIdx.y;
    if (x >= sc.width || y >= sc.height)
        return;
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint32_t i = 0; i < spp; i++) {
        ilk_vec3 L = ilk_path_sample(&sc, x, y, i);
        /* Drop non-finite samples, as the CPU film does. */
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z)) {
            r += L.x;
            g += L.y;
            b += L.z;
        }
    }
    float inv = 1.0f / (float)spp;
    size_t o = 3 * ((size_t)y * sc.width + x);
    rgb[o] = r * inv;
    rgb[o + 1] = g * inv;
    rgb[o + 2] = b * inv;
}

template <typename T> static il_status upload(T **dst, const T *src, size_t count, const char *what, il_error *err)
{
    *dst = NULL;
    size_t bytes = sizeof(T) * (count ? count : 1);
    il_status st = il_cuda_check(cudaMalloc((void **)dst, bytes), what, err);
    if (st == IL_OK && count)
        st = il_cuda_check(cudaMemcpy(*dst, src, sizeof(T) * count, cudaMemcpyHostToDevice), what, err);
    return st;
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
    ilk_bvh_node *nodes = NULL;
    ilk_tri *tris = NULL;
    ilk_material *mats = NULL;
    uint32_t *lights = NULL;
    float *cdf = NULL, *out = NULL;
    size_t out_bytes = sizeof(float) * 3 * (size_t)width * height;
    if ((st = upload(&nodes, ks.bvh.nodes, ks.bvh.num_nodes, "uploading the BVH", err)) == IL_OK &&
        (st = upload(&tris, ks.bvh.tris, ks.bvh.num_tris, "uploading the triangles", err)) == IL_OK &&
        (st = upload(&mats, ks.materials, ks.num_materials, "uploading the materials", err)) == IL_OK &&
        (st = upload(&lights, ks.lights, ks.num_lights, "uploading the lights", err)) == IL_OK &&
        (st = upload(&cdf, ks.light_cdf, ks.num_lights + 1, "uploading the light CDF", err)) == IL_OK &&
        (st = il_cuda_check(cudaMalloc((void **)&out, out_bytes), "allocating the image", err)) == IL_OK) {
        ilk_scene sc = ks.view;
        sc.bvh.nodes = nodes;
        sc.bvh.tris = tris;
        sc.materials = mats;
        sc.lights = lights;
        sc.light_cdf = cdf;
        dim3 block(8, 8), grid((width + 7) / 8, (height + 7) / 8);
        pt_kernel<<<grid, block>>>(sc, spp ? spp : 16, out);
        if ((st = il_cuda_check(cudaGetLastError(), "launching the path-tracing kernel", err)) == IL_OK &&
            (st = il_cuda_check(cudaDeviceSynchronize(), "the path-tracing kernel", err)) == IL_OK)
            st = il_cuda_check(cudaMemcpy(rgb, out, out_bytes, cudaMemcpyDeviceToHost), "downloading the image", err);
    }
    cudaFree(nodes);
    cudaFree(tris);
    cudaFree(mats);
    cudaFree(lights);
    cudaFree(cdf);
    cudaFree(out);
    il_kscene_free(&ks);
    return st;
}
