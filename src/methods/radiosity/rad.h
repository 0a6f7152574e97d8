/* Progressive-refinement radiosity (`--method radiosity`): the internals
 * shared by the files of this folder and the tests.  See docs/radiosity.md.
 *
 * Pipeline (rad.c):
 *   scene -> il_patch_mesh_build (methods/patch_mesh.c: surfaces, patches,
 *            its own BVH; shared with the other diffuse methods)
 *         -> il_rad_direct (rad_direct.c: light from point/spot/directional
 *            lights and the sky, as initial unshot radiance)
 *         -> il_rad_solve (rad_solve_shoot.c / rad_solve_gather.c, rows from
 *            il_ff (rad_ff.c, rad_hemicube.c, rad_ff_ray.c) through the row
 *            cache (rad_ff_cache.c))
 *         -> optional adaptive split (rad_adaptive.c) and solve again
 *         -> il_patch_vertex_radiance (methods/patch_vertex.c)
 *         -> il_patch_render_film (methods/patch_render.c) or the bake
 *            (methods/bake.c).
 *
 * Quantities: the solver works in radiance, not radiosity: for a Lambertian
 * patch B = pi L, and the radiosity equation B_i = E_i + rho_i sum_j F_ij B_j
 * holds unchanged for L (divide by pi).  "emission" is emitted radiance Le,
 * "radiance" the patch's total outgoing radiance. */
#ifndef IL_METHODS_RADIOSITY_RAD_H
#define IL_METHODS_RADIOSITY_RAD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/scene.h"
#include "methods/ff_analytic.h"
#include "methods/patch_mesh.h"
#include "trace/trace.h"

#define IL_NO_PATCH UINT32_MAX

/* ------------------------------------------------------------- settings */

/* il_radiosity_desc with every default resolved, plus the common options. */
typedef struct il_rad_settings {
    float patch_size;          /* metres; resolved from the scene when 0 was given */
    uint32_t subdivisions;     /* > 0 overrides patch_size */
    il_form_factor_method form_factors;
    uint32_t hemicube_resolution;
    uint32_t ray_samples;
    il_radiosity_solver solver;
    float tolerance;
    uint32_t max_steps;        /* 0: no limit */
    size_t ff_cache_bytes;
    float adaptive_threshold;
    il_radiosity_step_fn on_step;
    void *on_step_user;
    /* Internal (il_bake_progressive, bake.c): called with the patch mesh
     * just before on_step, with the same radiance (3 floats per patch);
     * false stops the solve.  NULL from il_rad_settings_resolve. */
    bool (*on_patches)(const il_patch_mesh *mesh, const float *radiance, void *user);
    void *on_patches_user;
    /* Per patch, the share of the camera's view it fills (rad_view.c), for
     * the shooting solver's view measure; NULL: none.  Set by the pipeline
     * (rad.c) for each mesh it solves. */
    const float *view_weight;
    uint64_t seed;
    int threads;               /* > 0, resolved */
    /* desc->distrib: the form-factor rows split across processes
     * (rad_solve_distrib.c); on_step is off then. */
    const il_distrib *distrib;
} il_rad_settings;

/* Resolves defaults and checks ranges (clear messages, IL_ERR_INVALID). */
il_status il_rad_settings_resolve(const il_scene *scene, const il_render_desc *desc,
                                  il_rad_settings *out, il_error *err);

/* ---------------------------------------------------------- form factors */

/* A sparse row of the form-factor matrix: F_ij from patch i to the patches j
 * it sees (F_ij > 0 only), in increasing j. */
typedef struct il_ff_row {
    uint32_t count;
    uint32_t *index;
    float *value;
} il_ff_row;

typedef struct il_ff il_ff;          /* shared and read-only once created */
typedef struct il_ff_work il_ff_work; /* one per thread: buffers of one row */

/* The back-end for `method` on a mesh of num_patches: IL_FF_AUTO resolved
 * (hemicube_resolution 0 means the default 256). */
il_form_factor_method il_ff_auto_method(il_form_factor_method method, uint32_t num_patches,
                                        uint32_t hemicube_resolution);
il_status il_ff_create(const il_patch_mesh *mesh, const il_rad_settings *settings, il_ff **out,
                       il_error *err);
il_form_factor_method il_ff_method(const il_ff *ff); /* never IL_FF_AUTO */
void il_ff_release(il_ff *ff);
il_status il_ff_work_create(const il_ff *ff, il_ff_work **out, il_error *err);
void il_ff_work_release(il_ff_work *work);
/* Computes row i; the row points into `work` and stays valid until the next
 * call with the same work.  Deterministic: ray-cast rows draw their random
 * numbers from (seed, i) only, so a recomputed row is bit-identical. */
const il_ff_row *il_ff_compute_row(const il_ff *ff, il_ff_work *work, uint32_t i);

/* The two back-ends behind il_ff (the same contract, for tests). */
typedef struct il_hemicube il_hemicube;
il_status il_hemicube_create(const il_patch_mesh *mesh, uint32_t resolution, il_hemicube **out,
                             il_error *err);
void il_hemicube_release(il_hemicube *hc);
/* Per-thread buffers live inside il_ff_work; these are the stateless parts. */
typedef struct il_hemicube_buffers il_hemicube_buffers;
il_status il_hemicube_buffers_create(const il_hemicube *hc, il_hemicube_buffers **out,
                                     il_error *err);
void il_hemicube_buffers_release(il_hemicube_buffers *b);
void il_hemicube_row(const il_hemicube *hc, il_hemicube_buffers *b, uint32_t i, il_ff_row *out);

/* Ray-cast row into caller-sized scratch (num_patches floats, zeroed on
 * entry and on return) and `out` (capacity num_patches). */
void il_ff_ray_row(const il_patch_mesh *mesh, uint32_t samples, uint64_t seed, uint32_t i,
                   float *scratch, il_ff_row *out);

/* il_ff_point_polygon (Lambert's contour integral) is shared by the diffuse
 * methods: methods/ff_analytic.h. */

/* The row cache with a memory cap: rows beyond the cap are not stored (and
 * are recomputed when needed again).  Thread-safe. */
typedef struct il_ff_cache il_ff_cache;
il_status il_ff_cache_create(uint32_t num_patches, size_t cap_bytes, il_ff_cache **out,
                             il_error *err);
void il_ff_cache_release(il_ff_cache *cache);
/* The cached row i, or NULL. */
const il_ff_row *il_ff_cache_get(const il_ff_cache *cache, uint32_t i);
/* Copies the row in when it fits under the cap; returns whether it did. */
bool il_ff_cache_put(il_ff_cache *cache, uint32_t i, const il_ff_row *row);
size_t il_ff_cache_bytes(const il_ff_cache *cache);

/* ---------------------------------------------------------------- solve */

typedef struct il_rad_solution {
    uint32_t num_patches;
    il_vec3 *radiance;         /* per patch: outgoing radiance (emission included) */
    il_vec3 *unshot;           /* per patch: radiance not yet shot (shooting) */
    il_vec3 *direct;           /* per patch: initial radiance Le + light from
                                  point/spot/directional lights and the sky */
    il_vec3 ambient;           /* Cohen et al. 1988 ambient term (display only) */
    uint32_t steps;
    double unshot_fraction;
    double view_fraction;      /* shooting: the view measure at the end (rad_solve_shoot.c) */
    bool stalled;              /* stopped because the measure no longer fell */
} il_rad_solution;

il_status il_rad_solution_init(il_rad_solution *sol, uint32_t num_patches, il_error *err);
void il_rad_solution_free(il_rad_solution *sol);

/* sol->direct[i] = emission_i + rho_i * (irradiance at patch i from the
 * scene's point, spot and directional lights and its environment) / pi,
 * each averaged over several points of the patch with shadow rays through
 * the scene's tracer.  Deterministic in (seed, patch). */
il_status il_rad_direct(const il_scene *scene, const il_patch_mesh *mesh,
                        const il_rad_settings *settings, il_rad_solution *sol, il_error *err);

/* *weights (NULL when the camera sees no patch): per patch, the share of a
 * coarse 4:3 grid of the scene camera's rays that first hit it (rad_view.c). */
il_status il_rad_view_weights(const il_scene *scene, const il_patch_mesh *mesh, float **weights,
                              il_error *err);

/* Solves from sol->direct (radiance = unshot = direct at the start) with
 * settings->solver until unshot/initial power < tolerance or max_steps.
 * Fills stats (seconds_form_factors, steps, rows_computed, cache_bytes...). */
il_status il_rad_solve(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                       const il_rad_settings *settings, il_rad_solution *sol,
                       il_radiosity_stats *stats, il_error *err);
il_status il_rad_solve_shooting(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                                const il_rad_settings *settings, il_rad_solution *sol,
                                il_radiosity_stats *stats, il_error *err);
il_status il_rad_solve_gathering(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                                 const il_rad_settings *settings, il_rad_solution *sol,
                                 il_radiosity_stats *stats, il_error *err);

/* Patches to split for adaptive subdivision: those whose radiance (luminance)
 * differs from a neighbour's in the same surface (sharing a vertex) by more
 * than threshold * max(own, neighbour's, 1e-6 * brightest).  Returns how
 * many were marked. */
uint32_t il_rad_mark_split(const il_patch_mesh *mesh, const il_rad_solution *sol, float threshold,
                           bool *split);

/* ----------------------------------------------------------- output */

/* The whole method: settings, mesh, direct light, solve (+ adaptive pass),
 * per-vertex radiance.  On success the caller owns *mesh_out and
 * *vertex_radiance_out (free()); stats->radiosity is filled. */
il_status il_rad_run(const il_scene *scene, const il_render_desc *desc, il_patch_mesh **mesh_out,
                     il_rad_solution *sol_out, il_vec3 **vertex_radiance_out,
                     il_render_stats *stats, il_error *err);

/* il_rad_run with settings.on_patches set (il_bake_progressive); on_step
 * must be set too (in desc->radiosity) for the solver to report steps. */
il_status il_rad_run_watched(const il_scene *scene, const il_render_desc *desc,
                             bool (*on_patches)(const il_patch_mesh *mesh, const float *radiance,
                                                void *user),
                             void *on_patches_user, il_patch_mesh **mesh_out,
                             il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err);

/* The il_render entry point for IL_METHOD_RADIOSITY. */
il_status il_rad_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        il_render_stats *stats, il_error *err);

#endif
