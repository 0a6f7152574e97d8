/* Direct light at a surface point by one light sample and a shadow ray
 * (next-event estimation without MIS), for the methods that take indirect
 * light from elsewhere (photon maps, ...) and so never count an emitter
 * reached by a BSDF-sampled ray after a non-delta bounce. */
#ifndef IL_SCENE_DIRECT_H
#define IL_SCENE_DIRECT_H

#include <stdbool.h>
#include <stdint.h>
#include "core/vec.h"
#include "scene/bsdf.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* Radiance reflected towards wo by light arriving straight from the lights:
 * f(wo, wi) Li |cos| / pdf for one light chosen by power (u_select) and one
 * point on it (u), zero when it is occluded (pbrt-v4 13.2.1, the light-
 * sampling half of its estimator).  Zero for a delta BSDF.  Adds the shadow
 * ray it casts to *rays. */
il_vec3 il_direct_light(const il_scene *scene, const il_surface *s, const il_bsdf *b, il_vec3 wo,
                        float u_select, il_vec2 u, uint64_t *rays);

/* The same in two halves, for callers that trace many shadow rays at once:
 * the light sample, its shadow ray (*shadow) and the radiance it gives when
 * nothing blocks the ray (*unblocked); false when there is nothing to trace
 * (the estimate is zero).  il_direct_light is this plus the shadow ray. */
bool il_direct_light_sample(const il_scene *scene, const il_surface *s, const il_bsdf *b, il_vec3 wo,
                            float u_select, il_vec2 u, il_ray *shadow, il_vec3 *unblocked);

#endif
