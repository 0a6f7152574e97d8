/* The camera pass every method shares: passes over image tiles, pixel
 * jitter by the filter, one radiance estimate per sample, the film, progress,
 * time limits and stopping.  A method supplies only the radiance arriving at
 * the camera along a ray. */
#ifndef IL_METHODS_CAMERA_PASS_H
#define IL_METHODS_CAMERA_PASS_H

#include <stdint.h>
#include "core/sampler.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/scene.h"

/* The radiance arriving at the camera at `org` from direction -dir (dir
 * unit), drawn with the sample's sampler (its first 2D sample already went
 * to the pixel jitter).  Adds the rays it casts to *rays. */
typedef il_vec3 (*il_camera_radiance_fn)(const void *method, il_vec3 org, il_vec3 dir,
                                         il_sampler *sampler, uint64_t *rays);

typedef struct il_camera_pass_result {
    uint32_t spp;               /* samples per pixel in the film */
    uint64_t rays;
    uint64_t nonfinite_samples; /* NaN/Inf samples dropped */
    double seconds;
} il_camera_pass_result;

/* Clears the film and renders desc->spp samples per pixel (0: 16, or
 * unlimited with a time limit) through the scene's camera, in passes,
 * calling desc->progress after each (false stops: not an error).  The film
 * is bit-identical whatever desc->threads. */
void il_camera_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                    il_camera_radiance_fn radiance, const void *method,
                    il_camera_pass_result *out);

/* The film offset of a sample within (box) or around (Gaussian) its pixel,
 * relative to the pixel's top-left corner, from u in [0,1)^2 by filter
 * importance sampling (pbrt-v4 8.8): box: uniform in [0,1)^2; Gaussian:
 * sigma 0.5 px truncated at radius 1.5 px around the pixel centre, so the
 * sample weight is 1. */
il_vec2 il_filter_offset(il_filter_type filter, il_vec2 u);

/* Inverse error function (for the Gaussian filter); |x| < 1. */
float il_erfinv(float x);

#endif
