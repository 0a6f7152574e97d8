/* The CUDA backend's C interface (docs/cuda.md).  Implemented by the .cu
 * files of this folder, which nvcc compiles into the illum_cuda library when
 * the build has -DIL_CUDA=ON; callers test IL_HAVE_CUDA before using it.
 * Every function reports a missing driver, a missing GPU or an out-of-memory
 * device as an il_status with a one-line message; none exits or prints. */
#ifndef IL_CUDA_BACKEND_H
#define IL_CUDA_BACKEND_H

#include <stddef.h>
#include <stdint.h>
#include "illum/illum.h"
#include "kernel/bvh_build.h"
#include "kernel/kernel_photon.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct il_cuda_device {
    char name[256];
    size_t total_memory;           /* bytes */
    int cc_major, cc_minor;        /* compute capability */
    int multiprocessors;
} il_cuda_device;

typedef struct il_cuda_versions {
    int driver;                    /* CUDA version the driver supports, 1000 major + 10 minor; 0: no driver */
    int runtime;                   /* the runtime illum was built with */
} il_cuda_versions;

/* Lists up to max GPUs into devs and their count into *count (0 is not an
 * error: no GPU or no driver, with the reason in *why when why_size > 0). */
il_status il_cuda_query(il_cuda_device *devs, int max, int *count, il_cuda_versions *versions,
                        char *why, size_t why_size, il_error *err);

/* Chooses device 0 and checks that it can run the kernels (a driver new
 * enough, a compute capability the binary carries).  IL_ERR_RUNTIME with a
 * message naming the cause otherwise. */
il_status il_cuda_require_device(il_error *err);

/* Casts n rays through the BVH on the GPU with the shared kernel
 * (kernel/kernel_bvh.h): closest hits into hits and/or occlusion flags into
 * occluded (either may be NULL).  Uploads the BVH with cudaMalloc/cudaMemcpy
 * on every call: a test and measurement entry point, not a renderer's. */
il_status il_cuda_trace_rays(const il_kbvh *bvh, const ilk_ray *rays, uint32_t n, ilk_hit *hits,
                             uint8_t *occluded, il_error *err);

typedef struct il_scene il_scene;

/* How a progressive GPU render (il_cuda_render_pt, the gather of
 * il_cuda_render_photon) runs, and what it did.  It launches a few samples
 * per pixel at a time until spp are done, or time_limit seconds (> 0) have
 * passed since the call, or progress (may be NULL) returns false; progress
 * gets a report after every launch (its film is NULL: the image stays on
 * the GPU).  image_fn (may be NULL), for --write-every, gets the running
 * image after a launch that ends image_every seconds or more after its
 * last call, while the render goes on: the mean so far (width x height x
 * 3 floats, rows top to bottom) and the samples per pixel in it.  The
 * image is the mean of the spp_done samples per pixel rendered, and rays
 * counts the rays they cast. */
typedef void (*il_cuda_image_fn)(const float *rgb, uint32_t width, uint32_t height, uint32_t spp, void *user);
typedef struct il_cuda_run {
    double time_limit;
    il_progress_fn progress;
    void *progress_user;
    double image_every;
    il_cuda_image_fn image_fn;
    void *image_user;
    uint32_t spp_done;             /* out */
    uint64_t rays;                 /* out */
} il_cuda_run;

/* Path traces the committed scene from its camera on the GPU with the
 * shared kernel (kernel/kernel_path.h, one thread per pixel, spp samples
 * each; 0: 16, or no bound with a time limit): rgb receives width x height
 * x 3 floats, the mean radiance per pixel, rows top to bottom.  run may be
 * NULL.  IL_ERR_INVALID for what the kernel does not do yet
 * (il_kscene_build), IL_ERR_RUNTIME / IL_ERR_MEMORY for the GPU. */
il_status il_cuda_render_pt(const il_scene *scene, uint32_t width, uint32_t height, uint32_t spp,
                            uint32_t max_depth, uint64_t seed, float *rgb, il_cuda_run *run, il_error *err);

/* What a GPU photon render measured (GPU event times). */
typedef struct il_cuda_photon_stats {
    uint64_t emitted, stored;      /* photons emitted, records stored */
    double seconds_trace;          /* tracing the photons */
    double seconds_build;          /* keys, radix sort, reorder, cell ranges */
    double seconds_gather;         /* the per-pixel gather, all samples */
} il_cuda_photon_stats;

/* The photon method on the GPU with the shared kernels (kernel/
 * kernel_photon.h, kernel_grid.h, kernel_photon_gather.h): num_emitted
 * photons of at most max_depth records each, the hashed grid with cells of
 * side radius built by a radix sort by cell, and spp camera samples per
 * pixel reading the grid at their first hit (radius: the gather radius).
 * rgb, spp and run as il_cuda_render_pt (run: the gather's samples and
 * camera rays).  stats may be NULL. */
il_status il_cuda_render_photon(const il_scene *scene, uint32_t width, uint32_t height, uint32_t spp,
                                uint32_t max_depth, uint64_t seed, uint32_t num_emitted, float radius,
                                float *rgb, il_cuda_photon_stats *stats, il_cuda_run *run, il_error *err);

/* The GPU's photon map of a kernel scene, downloaded for the tests: photons
 * (num_emitted * max_depth slots, sorted by cell), cell_start and cell_end
 * (il_kgrid_hash_mask(slots) + 1 entries each), *count the stored records.
 * kernel/kernel_photon_map.c builds the same on the CPU. */
typedef struct il_kscene il_kscene;
il_status il_cuda_photon_map(const il_kscene *ks, uint32_t num_emitted, float radius, ilk_photon *photons,
                             uint32_t *cell_start, uint32_t *cell_end, uint32_t *count, il_error *err);

/* What a GPU radiosity solve measured (GPU event times). */
typedef struct il_cuda_radiosity_stats {
    double seconds_form_factors;   /* casting every row's rays */
    double seconds_sweeps;         /* the Jacobi sweeps until convergence */
    bool stalled;                  /* stopped: the sweeps no longer converged */
} il_cuda_radiosity_stats;

/* The Jacobi gathering solve of a packed patch mesh (kernel/
 * kernel_radiosity_scene.h) on the GPU: what il_krad_solve computes on the
 * CPU, with the same arguments; stats may be NULL. */
typedef struct il_krad il_krad;
il_status il_cuda_radiosity_solve(const il_krad *k, float tolerance, uint32_t max_steps, ilk_vec3 *radiance,
                                  uint32_t *steps, double *fraction, il_cuda_radiosity_stats *stats,
                                  il_error *err);

#ifdef __cplusplus
}
#endif

#endif
