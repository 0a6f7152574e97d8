/* The path-tracing megakernel: one thread per pixel runs ilk_path_sample
 * (kernel/kernel_path.h, the code the CPU tests check against il_render)
 * for a batch of its samples, progressively (cuda/cuda_image.h).  The scene
 * is packed by il_kscene_build_pt (Phong, textures, delta lights, a sky) and
 * its flat arrays are copied with cudaMalloc/cudaMemcpy;
 * nothing is managed memory. */
#include "cuda/cuda_backend.h"
#include "cuda/cuda_image.h"
#include "cuda/cuda_scene.h"
#include "kernel/kernel_path.h"

/* Samples per launch. */
#define PT_BATCH 16u

/* One path sample of a pixel (il_cuda_pixel_kernel's sampler). */
struct pt_sampler {
    ilk_scene sc;
    __device__ ilk_vec3 operator()(uint32_t x, uint32_t y, uint32_t s, uint32_t *rays) const
    {
        return ilk_path_sample(&sc, x, y, s, rays);
    }
};

extern "C" il_status il_cuda_render_pt(const il_scene *scene, uint32_t width, uint32_t height, uint32_t spp,
                                       uint32_t max_depth, uint64_t seed, float *rgb, il_cuda_run *run,
                                       il_error *err)
{
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    il_kscene ks;
    il_cuda_scene d;
    il_status st = il_cuda_scene_prepare_with(il_kscene_build_pt, scene, width, height, max_depth, seed, &ks, &d, err);
    if (st != IL_OK)
        return st;
    st = il_cuda_progressive_image(pt_sampler{d.view}, width, height, il_cuda_spp(spp, run, 16), PT_BATCH, rgb,
                                   NULL, run, &t0, "the path-tracing kernel", err);
    il_cuda_scene_free(&d);
    il_kscene_free(&ks);
    return st;
}
