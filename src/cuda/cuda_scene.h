/* The kernel scene (kernel/kernel_scene.h) on the GPU: its flat arrays
 * copied with cudaMalloc/cudaMemcpy as they are, and the ilk_scene view
 * with device pointers that the kernels take by value.  Shared by the .cu
 * files of the path and photon kernels. */
#ifndef IL_CUDA_SCENE_H
#define IL_CUDA_SCENE_H

#include <string.h>
#include "cuda/cuda_backend.h"
#include "cuda/cuda_util.h"
#include "kernel/kernel_scene.h"

/* Allocates count elements (at least one, so a pointer is always valid)
 * and copies src in. */
template <typename T> static il_status il_cuda_upload(T **dst, const T *src, size_t count, const char *what,
                                                      il_error *err)
{
    *dst = NULL;
    size_t bytes = sizeof(T) * (count ? count : 1);
    il_status st = il_cuda_check(cudaMalloc((void **)dst, bytes), what, err);
    if (st == IL_OK && count)
        st = il_cuda_check(cudaMemcpy(*dst, src, sizeof(T) * count, cudaMemcpyHostToDevice), what, err);
    return st;
}

template <typename T> static il_status il_cuda_alloc(T **dst, size_t count, const char *what, il_error *err)
{
    *dst = NULL;
    return il_cuda_check(cudaMalloc((void **)dst, sizeof(T) * (count ? count : 1)), what, err);
}

typedef struct il_cuda_scene {
    ilk_bvh_node *nodes;
    ilk_tri *tris;
    ilk_material *materials;
    uint32_t *lights;
    float *light_cdf;
    ilk_light *pt_lights;
    float *pt_light_cdf;
    ilk_tri_normals *normals;      /* NULL when the scene has none */
    ilk_tri_uvs *uvs;              /* NULL without textures */
    ilk_texture *textures;
    float *texels;
    float *env_texels;             /* NULL without an environment map */
    float *env_cdf;                /* its sampling table */
    float *tri_light_pmf;          /* NULL when no triangle emits */
    ilk_scene view;                /* ks->view with the device pointers */
} il_cuda_scene;

static inline void il_cuda_scene_free(il_cuda_scene *d)
{
    cudaFree(d->nodes);
    cudaFree(d->tris);
    cudaFree(d->materials);
    cudaFree(d->lights);
    cudaFree(d->light_cdf);
    cudaFree(d->pt_lights);
    cudaFree(d->pt_light_cdf);
    cudaFree(d->normals);
    cudaFree(d->uvs);
    cudaFree(d->textures);
    cudaFree(d->texels);
    cudaFree(d->env_texels);
    cudaFree(d->env_cdf);
    cudaFree(d->tri_light_pmf);
    memset(d, 0, sizeof *d);
}

/* On failure everything is freed. */
static inline il_status il_cuda_scene_upload(const il_kscene *ks, il_cuda_scene *d, il_error *err)
{
    memset(d, 0, sizeof *d);
    il_status st;
    if ((st = il_cuda_upload(&d->nodes, ks->bvh.nodes, ks->bvh.num_nodes, "uploading the BVH", err)) != IL_OK ||
        (st = il_cuda_upload(&d->tris, ks->bvh.tris, ks->bvh.num_tris, "uploading the triangles", err)) != IL_OK ||
        (st = il_cuda_upload(&d->materials, ks->materials, ks->num_materials, "uploading the materials", err)) != IL_OK ||
        (st = il_cuda_upload(&d->lights, ks->lights, ks->num_lights, "uploading the lights", err)) != IL_OK ||
        (st = il_cuda_upload(&d->light_cdf, ks->light_cdf, ks->num_lights + 1, "uploading the light CDF", err)) != IL_OK ||
        (st = il_cuda_upload(&d->pt_lights, ks->pt_lights, ks->num_pt_lights, "uploading the light table", err)) != IL_OK ||
        (st = il_cuda_upload(&d->pt_light_cdf, ks->pt_light_cdf, ks->num_pt_lights + 1, "uploading the light table CDF",
                             err)) != IL_OK ||
        (ks->normals &&
         (st = il_cuda_upload(&d->normals, ks->normals, ks->num_normals, "uploading the vertex normals", err)) != IL_OK) ||
        (ks->uvs &&
         ((st = il_cuda_upload(&d->uvs, ks->uvs, ks->num_uvs, "uploading the texture coordinates", err)) != IL_OK ||
          (st = il_cuda_upload(&d->textures, ks->textures, ks->num_textures, "uploading the textures", err)) != IL_OK ||
          (st = il_cuda_upload(&d->texels, ks->texels, ks->num_texels, "uploading the texels", err)) != IL_OK)) ||
        (ks->env_texels &&
         (st = il_cuda_upload(&d->env_texels, ks->env_texels, 3 * (size_t)ks->env_width * ks->env_height,
                              "uploading the environment map", err)) != IL_OK) ||
        (ks->env_cdf && (st = il_cuda_upload(&d->env_cdf, ks->env_cdf, ks->num_env_cdf,
                                             "uploading the environment's sampling table", err)) != IL_OK) ||
        (ks->tri_light_pmf && (st = il_cuda_upload(&d->tri_light_pmf, ks->tri_light_pmf, ks->bvh.num_tris,
                                                   "uploading the emitters' light probabilities", err)) != IL_OK)) {
        il_cuda_scene_free(d);
        return st;
    }
    d->view = ks->view;
    d->view.bvh.nodes = d->nodes;
    d->view.bvh.tris = d->tris;
    d->view.materials = d->materials;
    d->view.lights = d->lights;
    d->view.light_cdf = d->light_cdf;
    d->view.pt_lights = d->pt_lights;
    d->view.pt_light_cdf = d->pt_light_cdf;
    d->view.normals = d->normals;
    d->view.uvs = d->uvs;
    d->view.textures = d->textures;
    d->view.texels = d->texels;
    d->view.env_texels = d->env_texels;
    d->view.env_cdf = d->env_cdf;
    d->view.tri_light_pmf = d->tri_light_pmf;
    return IL_OK;
}

typedef il_status (*il_kscene_builder)(const il_scene *, uint32_t, uint32_t, uint32_t, uint64_t, il_kscene *,
                                        il_error *);

/* An image render's start: a non-empty image, a usable GPU, the kernel
 * scene built (by `build`: il_kscene_build, or il_kscene_build_pt for the
 * path kernel) and uploaded.  On failure nothing is left to free; on
 * success free d, then ks. */
static inline il_status il_cuda_scene_prepare_with(il_kscene_builder build, const il_scene *scene, uint32_t width,
                                                   uint32_t height, uint32_t max_depth, uint64_t seed, il_kscene *ks,
                                                   il_cuda_scene *d, il_error *err)
{
    if (width == 0 || height == 0)
        return il_fail(err, IL_ERR_INVALID, "CUDA render: empty image");
    il_status st = il_cuda_require_device(err);
    if (st != IL_OK)
        return st;
    if ((st = build(scene, width, height, max_depth, seed, ks, err)) != IL_OK)
        return st;
    if ((st = il_cuda_scene_upload(ks, d, err)) != IL_OK)
        il_kscene_free(ks);
    return st;
}

/* il_cuda_scene_prepare_with il_kscene_build (the photon kernels). */
static inline il_status il_cuda_scene_prepare(const il_scene *scene, uint32_t width, uint32_t height,
                                              uint32_t max_depth, uint64_t seed, il_kscene *ks, il_cuda_scene *d,
                                              il_error *err)
{
    return il_cuda_scene_prepare_with(il_kscene_build, scene, width, height, max_depth, seed, ks, d, err);
}

#endif
