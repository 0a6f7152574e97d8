/* The reference path tracer (`--method pt`): unidirectional path tracing with
 * next-event estimation and multiple importance sampling.  See
 * docs/path-tracer.md for the estimator, its options and its guarantees. */
#ifndef IL_METHODS_PT_H
#define IL_METHODS_PT_H

#include <stdint.h>
#include "core/sampler.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/scene.h"

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

#endif
