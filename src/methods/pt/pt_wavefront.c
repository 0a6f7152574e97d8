/* The path tracer's camera pass, wavefront style: the paths of a tile
 * advance together one vertex at a time, and each step's rays go to Embree
 * as one stream (il_trace_closest_n, then il_trace_occluded_n for the
 * shadow rays), in the manner of Laine, Karras & Aila 2013, "Megakernels
 * Considered Harmful: Wavefront Path Tracing on GPUs", here on a CPU: the
 * stream calls are cheaper per ray, and tracing and shading each run as one
 * tight loop, which keeps Embree's and the shader's code and branch history
 * warm.
 *
 * Every path runs exactly the estimator of il_pt_radiance (il_pt_step), with
 * the same sample numbers and the same order of additions to its radiance,
 * and the film receives a pixel's samples in increasing index: the shared
 * camera pass (methods/camera_pass.c) runs the tiles, passes, progress
 * reports, time limit and treatment of NaN samples, and this file only the
 * work of a tile (il_camera_pass_tiles), so the film is bit-identical to
 * il_camera_pass with il_pt_radiance, and the same with 1 or N threads. */
#include "methods/camera_pass.h"
#include "methods/pt/pt.h"

/* Paths advanced together: one 16x16 tile at one sample per pixel. */
#define PT_WAVE 256u

typedef struct pt_method {
    const il_scene *scene;
    uint32_t max_depth;
    il_pt_strategy strategy;
} pt_method;

/* One wave: up to PT_WAVE paths with their samplers and pixels, and the
 * gather buffers for the stream calls; one per thread (about 70 KB), the
 * camera pass's scratch memory. */
typedef struct pt_wave {
    il_pt_state st[PT_WAVE];
    il_sampler smp[PT_WAVE];
    uint32_t px[PT_WAVE], py[PT_WAVE];
    uint32_t active[PT_WAVE], shadowed[PT_WAVE];
    il_ray rays[PT_WAVE];
    il_hit hits[PT_WAVE];
    bool occluded[PT_WAVE];
    uint32_t drawing[PT_WAVE];    /* the paths that draw samples at this vertex */
    il_vec2 u[PT_WAVE][3];        /* their three 2D samples, in that order */
} pt_wave;

/* Runs paths 0..n-1 of the wave to their ends. */
static void run_wave(const pt_method *pm, pt_wave *w, uint32_t n)
{
    const il_tracer *tr = pm->scene->tracer;
    uint32_t num_active = n;
    for (uint32_t j = 0; j < n; j++)
        w->active[j] = j;
    while (num_active > 0) {
        for (uint32_t a = 0; a < num_active; a++)
            w->rays[a] = w->st[w->active[a]].ray;
        il_trace_closest_n(tr, w->rays, w->hits, num_active);

        /* The vertex's samples of every path that will draw them (a hit
         * below the maximum depth: see il_pt_step), all drawn together. */
        uint32_t num_drawing = 0;
        for (uint32_t a = 0; a < num_active; a++) {
            uint32_t j = w->active[a];
            if (w->hits[a].mesh != IL_HIT_NONE && w->st[j].depth < pm->max_depth)
                w->drawing[num_drawing++] = j;
        }
        il_sampler_2d_gather(w->smp, w->drawing, num_drawing, 3, &w->u[0][0]);

        uint32_t num_shadow = 0, still = 0, d = 0;
        for (uint32_t a = 0; a < num_active; a++) {
            uint32_t j = w->active[a];
            const il_hit *hit = w->hits[a].mesh != IL_HIT_NONE ? &w->hits[a] : NULL;
            const il_vec2 *u = d < num_drawing && w->drawing[d] == j ? w->u[d++] : NULL;
            bool more = il_pt_step(pm->scene, &w->st[j], hit, &w->smp[j], u, pm->max_depth,
                                   pm->strategy);
            if (w->st[j].shadow) {
                w->shadowed[num_shadow] = j;
                w->rays[num_shadow++] = w->st[j].shadow_ray;
            }
            /* Compaction in place: `still` never passes `a`. */
            if (more)
                w->active[still++] = j;
        }
        if (num_shadow > 0) {
            il_trace_occluded_n(tr, w->rays, w->occluded, num_shadow);
            for (uint32_t k = 0; k < num_shadow; k++)
                il_pt_shadow_result(&w->st[w->shadowed[k]], w->occluded[k]);
        }
        num_active = still;
    }
}

/* The tile's samples in waves taken in the order the camera pass wants them
 * (pixel by pixel, samples in increasing index), and added to the film in
 * that order. */
static void render_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    const pt_method *pm = method;
    pt_wave *w = tile->scratch;
    uint32_t first = tile->first, end = tile->first + tile->count;
    uint32_t x = tile->x0, y = tile->y0, i = first;
    while (y < tile->y1) {
        /* Fill a wave. */
        uint32_t n = 0;
        while (n < PT_WAVE && y < tile->y1) {
            il_vec3 dir = il_camera_sample(ctx, x, y, i, &w->smp[n]);
            il_pt_begin(&w->st[n], ctx->cam.position, dir);
            w->px[n] = x;
            w->py[n] = y;
            n++;
            if (++i == end) {
                i = first;
                if (++x == tile->x1) {
                    x = tile->x0;
                    y++;
                }
            }
        }
        run_wave(pm, w, n);
        for (uint32_t j = 0; j < n; j++) {
            tile->rays += w->st[j].rays;
            il_camera_tile_add(ctx, tile, w->px[j], w->py[j], w->st[j].L);
        }
    }
}

il_status il_pt_wavefront_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               uint32_t max_depth, il_pt_strategy strategy,
                               il_camera_pass_result *out, il_error *err)
{
    pt_method pm = {.scene = scene, .max_depth = max_depth, .strategy = strategy};
    return il_camera_pass_tiles(scene, film, desc, render_tile, &pm, sizeof(pt_wave), out, err);
}
