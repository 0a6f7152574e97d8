/* The reference path tracer (`--method pt`): unidirectional path tracing with
 * next-event estimation and multiple importance sampling.  See
 * docs/path-tracer.md for the estimator, its options and its guarantees. */
#ifndef IL_METHODS_PT_H
#define IL_METHODS_PT_H

#include <stdint.h>
#include "core/sampler.h"
#include "methods/camera_pass.h"
#include "methods/diffuse_wave.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* Which estimator of direct light to use.  Only IL_PT_MIS is offered to
 * users; the other two exist so tests can check that all three agree. */
typedef enum il_pt_strategy {
    IL_PT_MIS = 0,    /* light sampling and BSDF sampling, power heuristic */
    IL_PT_NEE_ONLY,   /* emitters reached by BSDF sampling are ignored (unless
                         after a delta bounce); light sampling has weight 1 */
    IL_PT_BSDF_ONLY   /* area lights and the environment are found only by
                         BSDF sampling; delta lights are still sampled */
} il_pt_strategy;

/* Renders into the film (cleared first).  `desc` need not be validated (see
 * il_render for that); zero fields get their defaults.  stats may be NULL. */
il_status il_pt_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_pt_strategy strategy, il_render_stats *stats, il_error *err);

/* ---- internals, shared by the files of this folder and the tests ---- */

/* The radiance arriving at `org` from direction -dir along one sampled path
 * (dir unit).  Counts rays cast in *rays. */
il_vec3 il_pt_radiance(const il_scene *scene, il_vec3 org, il_vec3 dir, il_sampler *sampler,
                       uint32_t max_depth, il_pt_strategy strategy, uint64_t *rays);

/* The radiance that the surface of `hit`, found by the ray org + t dir,
 * scatters back along it: il_pt_radiance's estimate of that ray less what
 * the surface emits itself (methods/portal_light.c: what a portal lets in
 * from a surface outside, whose own emission its photons bring). */
il_vec3 il_pt_radiance_scattered(const il_scene *scene, const il_hit *hit, il_vec3 org, il_vec3 dir,
                                 il_sampler *sampler, uint32_t max_depth, uint64_t *rays);

/* The camera pass of il_pt_render (pt_wavefront.c): what il_camera_pass
 * does with il_pt_radiance, bit for bit, with the paths of a tile traced
 * together through the stream calls.  Fails only when out of memory. */
il_status il_pt_wavefront_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               uint32_t max_depth, il_pt_strategy strategy,
                               il_camera_pass_result *out, il_error *err);
/* One tile of il_pt_wavefront_pass for a caller that runs its own tiles
 * (methods/render_region.c): tile->scratch must hold
 * il_pt_wavefront_scratch_bytes() (64-byte aligned). */
size_t il_pt_wavefront_scratch_bytes(void);
void il_pt_wavefront_tile(const il_scene *scene, uint32_t max_depth, il_pt_strategy strategy,
                          const il_camera_pass_ctx *ctx, il_camera_tile *tile);

/* The same estimator one vertex at a time, so that a caller can trace the
 * rays of many paths together (pt_wavefront.c): il_pt_begin starts a path
 * with the camera ray in st->ray; the caller traces st->ray and passes the
 * hit (NULL on a miss) to il_pt_step, which adds what the vertex sees to
 * st->L, may leave a shadow ray in st->shadow_ray (st->shadow true), whose
 * outcome the caller reports with il_pt_shadow_result before the next
 * step, and returns false when the path ends (after its shadow ray).
 * A step at a hit with st->depth < max_depth draws the vertex's three 2D
 * samples from the sampler first thing, and from the fourth bounce on
 * (depth >= 3) one 1D roulette number last, when the path gets that far. */
typedef struct il_pt_state {
    il_vec3 L, beta;
    il_vec3 prev_p;        /* the previous vertex */
    float prev_pdf;        /* solid-angle pdf of the BSDF sample that led here */
    bool specular;         /* the ray left a delta lobe (or the camera) */
    bool camera_chain;     /* ... and so did every ray before it: the camera sees what it finds */
    bool shadow;           /* shadow_ray must be traced */
    uint32_t depth;        /* scattering events before st->ray */
    il_ray ray;
    il_ray shadow_ray;
    il_vec3 shadow_L;      /* added to L when shadow_ray is unoccluded */
    uint64_t rays;         /* rays cast or to be cast so far */
} il_pt_state;

/* What a caller that shades many paths at once computed for one step ahead
 * of time, with the values the step would compute itself, bit for bit. */
typedef struct il_pt_drawn {
    il_vec2 u[4];          /* the vertex's three 2D samples, in the order
                              il_pt_step draws them; u[3].x the roulette number */
    il_vec3 cos_dir;       /* il_sample_cosine_hemisphere(u[2]) */
    bool roulette;         /* u[3] holds the roulette number (a Sobol sampler's
                              next pair, whose first member il_sampler_1d gives) */
    il_diffuse_out diffuse; /* a Lambertian or Phong vertex's light sample and next ray,
                              made with the wave's others (il_diffuse_wave) */
} il_pt_drawn;

void il_pt_begin(il_pt_state *st, il_vec3 org, il_vec3 dir);
bool il_pt_step(const il_scene *scene, il_pt_state *st, const il_hit *hit, il_sampler *sampler,
                uint32_t max_depth, il_pt_strategy strategy);
/* il_pt_step with the hit's surface already known (il_scene_surface of
 * hit; surf NULL on a miss) and, when `drawn` is not NULL, the vertex's
 * samples already drawn (the sampler advanced past them). */
bool il_pt_step_at(const il_scene *scene, il_pt_state *st, const il_hit *hit,
                   const il_surface *surf, const il_pt_drawn *drawn, il_sampler *sampler,
                   uint32_t max_depth, il_pt_strategy strategy);
/* visibility: il_trace_visibility of the shadow ray (0 blocked, 1 clear,
 * between: through panes). */
static inline void il_pt_shadow_result(il_pt_state *st, float visibility)
{
    if (visibility == 1.0f)
        st->L = v3_add(st->L, st->shadow_L);
    else if (visibility > 0.0f)
        st->L = v3_fma(st->L, st->shadow_L, visibility);
    st->shadow = false;
}

/* Paths a wavefront advances together: one 16x16 tile at one sample per
 * pixel (pt_wavefront.c), or as many sensor paths. */
#define IL_PT_WAVE 256u

/* Irradiance (W/m^2) at p on a surface facing the unit normal n, from one
 * sampled path (pt_path.c: the radiance of a white Lambertian surface there,
 * times pi).  Counts rays cast in *rays. */
il_vec3 il_pt_sensor_irradiance(const il_scene *scene, il_vec3 p, il_vec3 n, il_sampler *sampler,
                                uint32_t max_depth, uint64_t *rays);
/* The path's start: the state, the sensor's surface and the hit standing
 * for it, which il_pt_step_at takes as the first vertex. */
void il_pt_sensor_begin(il_pt_state *st, il_vec3 p, il_vec3 n, il_surface *surf, il_hit *hit);
/* il_pt_sensor_irradiance for paths k < count (at most IL_PT_WAVE), traced
 * together through the stream calls (pt_wavefront.c): out[k], bit for bit
 * the scalar value, from sensor (p[k], n[k]) with sampler smp[k]; scratch
 * holds il_pt_wavefront_scratch_bytes() (64-byte aligned); prefetch is
 * il_wave_wants_prefetch(scene), decided once by the caller. */
void il_pt_sensor_wave(const il_scene *scene, uint32_t max_depth, bool prefetch, void *scratch,
                       const il_vec3 *p, const il_vec3 *n, const il_sampler *smp, uint32_t count,
                       il_vec3 *out, uint64_t *rays);

#endif
