/* Packs a patch mesh (methods/patch_mesh.h) and its initial radiance into
 * the flat arrays of kernel/kernel_radiosity.h, and solves it on the CPU
 * with the shared kernel (the reference for src/cuda/radiosity_kernel.cu,
 * which takes the same packing). */
#ifndef IL_KERNEL_RADIOSITY_SCENE_H
#define IL_KERNEL_RADIOSITY_SCENE_H

#include "illum/illum.h"
#include "kernel/bvh_build.h"
#include "kernel/kernel_radiosity.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct il_patch_mesh il_patch_mesh;

typedef struct il_krad {
    il_kbvh bvh;               /* over the mesh's triangles, pad = patch */
    ilk_patch *patches;
    ilk_vec3 *direct;          /* Ld per patch: emission + light from lights and sky */
    double initial_power;      /* sum A_i lum(Ld_i), the convergence reference */
    ilk_rad_scene view;        /* host pointers */
} il_krad;

/* samples: rays per patch (> 0); direct: one il_vec3 per patch (the
 * solver's il_rad_solution.direct). */
il_status il_krad_build(const il_patch_mesh *mesh, const il_vec3 *direct, uint32_t samples, uint64_t seed,
                        il_krad *out, il_error *err);
void il_krad_free(il_krad *k);

/* The solve of methods/radiosity/rad_solve_gather.c (Jacobi) with the
 * shared kernel: all rows, then sweeps from L = Ld until the changed power
 * over the initial power is below tolerance or max_steps (0: no limit)
 * sweeps were made, or the solve stalled (methods/radiosity/rad_stall.h).
 * radiance: one per patch.  *steps, *fraction and *stalled (each may be
 * NULL) receive the sweeps made, the last fraction and whether it stalled. */
il_status il_krad_solve(const il_krad *k, float tolerance, uint32_t max_steps, ilk_vec3 *radiance,
                        uint32_t *steps, double *fraction, bool *stalled, il_error *err);

#ifdef __cplusplus
}
#endif

#endif
