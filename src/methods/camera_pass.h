/* The camera pass every method shares: passes over image tiles, pixel
 * jitter by the filter, one radiance estimate per sample, the film, progress,
 * time limits and stopping.  A method supplies either the radiance arriving
 * at the camera along a ray (il_camera_pass), or the work of a whole tile
 * (il_camera_pass_tiles), for a method that traces a tile's samples together
 * (the path tracer's wavefront, methods/pt/pt_wavefront.c). */
#ifndef IL_METHODS_CAMERA_PASS_H
#define IL_METHODS_CAMERA_PASS_H

#include <stdint.h>
#include "core/sampler.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/camera.h"
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

/* ---- the per-tile form ---- */

/* What the pass hands every tile: the film, the camera and the sample stream
 * settings of the render. */
typedef struct il_camera_pass_ctx {
    il_film *film;
    il_camera cam;
    uint32_t width, height;
    uint64_t seed;
    il_sampler_type sampler;
    il_filter_type filter;
} il_camera_pass_ctx;

/* The pass context of film and desc (camera of the scene's camera). */
il_camera_pass_ctx il_camera_pass_ctx_make(const il_scene *scene, il_film *film, const il_render_desc *desc);

/* One tile of one pass: samples first..first+count-1 of every pixel of
 * [x0, x1) x [y0, y1).  The callback adds what it counts to rays and
 * nonfinite (il_camera_tile_add does the latter). */
typedef struct il_camera_tile {
    uint32_t x0, y0, x1, y1;
    uint32_t first, count;
    void *scratch;              /* this thread's scratch_bytes (NULL when 0) */
    uint64_t rays;              /* rays cast (the callback adds them) */
    uint64_t nonfinite;         /* NaN/Inf samples dropped */
} il_camera_tile;

/* Renders a tile.  For the film to be bit-identical whatever the thread
 * count, it adds the samples with il_camera_tile_add pixel by pixel in row
 * order, each pixel's samples in increasing index; each sample's estimate
 * depends only on (seed, pixel, sample index) through il_camera_sample. */
typedef void (*il_camera_tile_fn)(const void *method, const il_camera_pass_ctx *ctx,
                                  il_camera_tile *tile);

/* Starts sample i of pixel (x, y): *sampler keyed by (seed, pixel, i), its
 * first 2D sample spent on the pixel jitter; returns the unit direction of
 * the camera ray (its origin is ctx->cam.position). */
il_vec3 il_camera_sample(const il_camera_pass_ctx *ctx, uint32_t x, uint32_t y, uint32_t i,
                         il_sampler *sampler);

/* The second half of il_camera_sample: the camera ray's direction through
 * pixel (x, y) jittered by the 2D sample u (the sampler's first draw), for
 * a caller that starts many samplers and draws their first pairs at once
 * (il_sampler_2d_gather). */
il_vec3 il_camera_sample_dir(const il_camera_pass_ctx *ctx, uint32_t x, uint32_t y, il_vec2 u);

/* Adds sample radiance L to pixel (x, y), or drops it (counted in
 * tile->nonfinite) when NaN or Inf, which would poison the pixel for good. */
void il_camera_tile_add(const il_camera_pass_ctx *ctx, il_camera_tile *tile, uint32_t x, uint32_t y,
                        il_vec3 L);

/* il_camera_pass with a tile callback: the same tiles, passes, progress,
 * time limit and result; with desc->distrib, this process's share of the
 * tiles and no progress calls.  Each thread gets scratch_bytes of its own
 * (64-byte aligned, allocated before the film is cleared; 0: none).  Fails
 * only when that allocation does. */
il_status il_camera_pass_tiles(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               il_camera_tile_fn tile, const void *method, size_t scratch_bytes,
                               il_camera_pass_result *out, il_error *err);

/* The film offset of a sample within (box) or around (Gaussian) its pixel,
 * relative to the pixel's top-left corner, from u in [0,1)^2 by filter
 * importance sampling (pbrt-v4 8.8): box: uniform in [0,1)^2; Gaussian:
 * sigma 0.5 px truncated at radius 1.5 px around the pixel centre, so the
 * sample weight is 1. */
il_vec2 il_filter_offset(il_filter_type filter, il_vec2 u);

/* Inverse error function (for the Gaussian filter); |x| < 1. */
float il_erfinv(float x);

#endif
