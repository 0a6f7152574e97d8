/* What the wavefront methods (the path tracer, Linespace) share: taking a
 * tile's samples a wave at a time in the camera pass's order, and the
 * surfaces of a wave's hits read together. */
#ifndef IL_METHODS_CAMERA_WAVE_H
#define IL_METHODS_CAMERA_WAVE_H

#include <stdbool.h>
#include <stdint.h>
#include "core/sampler.h"
#include "methods/camera_pass.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* Where the next wave of a tile starts: pixel (x, y), sample i. */
typedef struct il_camera_wave_cursor {
    uint32_t x, y, i;
} il_camera_wave_cursor;

static inline il_camera_wave_cursor il_camera_wave_begin(const il_camera_tile *tile)
{
    return (il_camera_wave_cursor){tile->x0, tile->y0, tile->first};
}

/* The tile's next samples, at most `max`, in the order the camera pass adds
 * them to the film (pixel by pixel, samples in increasing index): their
 * samplers started, their pixels, and their camera ray directions (the first
 * pair of every sampler drawn together, as il_camera_sample draws it).
 * `scratch` holds max entries.  Returns how many (0: the tile is done). */
uint32_t il_camera_wave_fill(const il_camera_pass_ctx *ctx, const il_camera_tile *tile,
                             il_camera_wave_cursor *cur, uint32_t max, il_sampler *smp,
                             uint32_t *px, uint32_t *py, uint32_t *scratch, il_vec2 *u_scratch,
                             il_vec3 *dir);

/* The surfaces of hits[0..n-1] (hits with mesh IL_HIT_NONE are skipped).
 * With prefetch (a scene whose triangle records outgrow the caches: see
 * il_wave_wants_prefetch) the records and the vertices they name are
 * touched for all hits first, so that the memory system fetches them in
 * parallel instead of one miss after the other inside il_scene_surface. */
void il_wave_surfaces(const il_scene *scene, const il_hit *hits, uint32_t n, bool prefetch,
                      il_surface *out);
bool il_wave_wants_prefetch(const il_scene *scene);

#endif
