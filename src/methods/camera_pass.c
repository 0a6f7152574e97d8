/* The camera pass: passes over 16x16 tiles scheduled by OpenMP.
 *
 * Determinism: a sample's value depends only on (seed, pixel, sample index)
 * (the sampler is keyed by them, never by the thread), every pixel belongs to
 * exactly one tile, a tile is rendered by one thread, and a pass adds each
 * pixel's samples in increasing index; passes run one after the other.  So
 * every pixel's sum is formed in the same order whatever the thread count,
 * and the film is bit-identical with 1 or N threads.  Split across processes
 * (desc->distrib) each renders the tiles it claims (or, without a claim
 * hook, every size-th tile in the same passes): the films add up to one
 * process's. */
#include "methods/camera_pass.h"

#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"

#define IL_TILE 16
/* A pass renders about this many samples, at least 1 and at most 64 per
 * pixel: small images get several samples per pixel per pass so that the
 * per-pass cost (thread start-up, progress callback) stays negligible. */
#define IL_PASS_SAMPLES 65536u
#define IL_PASS_MAX_SPP 64u

il_vec3 il_camera_sample(const il_camera_pass_ctx *ctx, uint32_t x, uint32_t y, uint32_t i,
                         il_sampler *smp)
{
    il_sampler_start(smp, ctx->sampler, ctx->seed, (uint64_t)y * ctx->width + x, i);
    return il_camera_sample_dir(ctx, x, y, il_sampler_2d(smp));
}

il_vec3 il_camera_sample_dir(const il_camera_pass_ctx *ctx, uint32_t x, uint32_t y, il_vec2 u)
{
    il_vec2 off = il_filter_offset(ctx->filter, u);
    return il_camera_ray_dir(&ctx->cam, (float)x + off.x, (float)y + off.y);
}

void il_camera_tile_add(const il_camera_pass_ctx *ctx, il_camera_tile *tile, uint32_t x, uint32_t y,
                        il_vec3 L)
{
    if (!v3_is_finite(L)) {
        tile->nonfinite++;
        return;
    }
    il_film_add_sample(ctx->film, x, y, L, 1.0f);
}

/* ---- the per-sample form: a tile callback that asks for one radiance
 * estimate per sample ---- */

typedef struct sample_method {
    il_camera_radiance_fn radiance;
    const void *method;
} sample_method;

static void sample_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    const sample_method *m = method;
    for (uint32_t y = tile->y0; y < tile->y1; y++)
        for (uint32_t x = tile->x0; x < tile->x1; x++)
            for (uint32_t i = tile->first; i < tile->first + tile->count; i++) {
                il_sampler smp;
                il_vec3 dir = il_camera_sample(ctx, x, y, i, &smp);
                il_vec3 L = m->radiance(m->method, ctx->cam.position, dir, &smp, &tile->rays);
                il_camera_tile_add(ctx, tile, x, y, L);
            }
}

void il_camera_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                    il_camera_radiance_fn radiance, const void *method,
                    il_camera_pass_result *out)
{
    sample_method m = {radiance, method};
    /* Without scratch memory the pass cannot fail. */
    (void)il_camera_pass_tiles(scene, film, desc, sample_tile, &m, 0, out, NULL);
}

/* ---- the pass ---- */

il_camera_pass_ctx il_camera_pass_ctx_make(const il_scene *scene, il_film *film, const il_render_desc *desc)
{
    il_camera_pass_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    ctx.film = film;
    ctx.width = il_film_width(film);
    ctx.height = il_film_height(film);
    ctx.seed = desc->seed;
    ctx.sampler = desc->sampler;
    ctx.filter = desc->filter;
    il_camera_init(&ctx.cam, &scene->camera.desc, ctx.width, ctx.height);
    return ctx;
}

/* The tiles tile0, tile0 + step, ... (n of them), samples first..first +
 * count - 1 each, over the threads; their rays and non-finite samples are
 * added to *rays and *bad. */
typedef struct tile_run {
    const il_camera_pass_ctx *ctx;
    il_camera_tile_fn tile_fn;
    const void *method;
    int threads;
    uint32_t tiles_x;
    unsigned char *scratch;
    size_t stride;
} tile_run;

static void run_tiles(const tile_run *run, uint32_t tile0, uint32_t step, uint32_t n, uint32_t first,
                      uint32_t count, uint64_t *rays, uint64_t *bad)
{
    const il_camera_pass_ctx *ctx = run->ctx;
    uint64_t r = 0, b = 0;
#pragma omp parallel for schedule(dynamic) num_threads(run->threads) reduction(+ : r, b)
    for (uint32_t k = 0; k < n; k++) {
        uint32_t t = tile0 + k * step;
        uint32_t x0 = (t % run->tiles_x) * IL_TILE, y0 = (t / run->tiles_x) * IL_TILE;
        il_camera_tile tile = {
            .x0 = x0,
            .y0 = y0,
            .x1 = x0 + IL_TILE < ctx->width ? x0 + IL_TILE : ctx->width,
            .y1 = y0 + IL_TILE < ctx->height ? y0 + IL_TILE : ctx->height,
            .first = first,
            .count = count,
            .scratch = run->scratch ? run->scratch + (size_t)omp_get_thread_num() * run->stride : NULL,
        };
        run->tile_fn(run->method, ctx, &tile);
        r += tile.rays;
        b += tile.nonfinite;
    }
    *rays += r;
    *bad += b;
}

il_status il_camera_pass_tiles(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               il_camera_tile_fn tile_fn, const void *method, size_t scratch_bytes,
                               il_camera_pass_result *out, il_error *err)
{
    il_camera_pass_ctx ctx = il_camera_pass_ctx_make(scene, film, desc);

    bool timed = desc->time_limit > 0.0;
    uint32_t spp = desc->spp ? desc->spp : (timed ? UINT32_MAX : 16u);
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    uint64_t pixels = (uint64_t)ctx.width * ctx.height;
    uint32_t tiles_x = (ctx.width + IL_TILE - 1) / IL_TILE;
    uint32_t tiles = tiles_x * ((ctx.height + IL_TILE - 1) / IL_TILE);
    uint32_t per_pass = pixels ? (uint32_t)(IL_PASS_SAMPLES / pixels) : 1u;
    per_pass = per_pass < 1 ? 1 : (per_pass > IL_PASS_MAX_SPP ? IL_PASS_MAX_SPP : per_pass);

    /* Each thread's scratch, rounded up to whole cache lines. */
    size_t stride = (scratch_bytes + 63) / 64 * 64;
    unsigned char *scratch = NULL;
    if (stride > 0) {
        scratch = aligned_alloc(64, (size_t)threads * stride);
        if (!scratch)
            return il_fail(err, IL_ERR_MEMORY, "render: out of memory (%zu bytes per thread)",
                           scratch_bytes);
    }
    tile_run run = {&ctx, tile_fn, method, threads, tiles_x, scratch, stride};

    il_film_clear(film);
    double t0 = omp_get_wtime(), seconds = 0.0;
    uint64_t rays = 0, bad = 0;
    uint32_t done = 0;
    const il_distrib *d = desc->distrib;
    if (il_distrib_on(d) && d->claim) {
        /* Split across processes, tiles on demand: each claim takes the
         * next few tiles of the shared counter, rendered with all their
         * samples (a pixel's sums are formed in the same order as in
         * passes: increasing sample index), so the processes' films add up
         * to one process's whatever tiles each got. */
        uint32_t chunk = 2u * (uint32_t)threads;
        for (;;) {
            uint64_t first = d->claim(d->user, chunk);
            if (first >= tiles)
                break;
            uint32_t n = tiles - first < chunk ? (uint32_t)(tiles - first) : chunk;
            run_tiles(&run, (uint32_t)first, 1, n, 0, spp, &rays, &bad);
        }
        done = spp;
    } else {
        /* One process, or split statically: tiles rank, rank + size, ...
         * (a tile's sums do not depend on who renders it). */
        bool split = il_distrib_on(d);
        uint32_t tile0 = split ? (uint32_t)d->rank : 0u, step = split ? (uint32_t)d->size : 1u;
        uint32_t mine = tiles > tile0 ? (tiles - tile0 + step - 1) / step : 0u;
        while (done < spp) {
            uint32_t count = spp - done < per_pass ? spp - done : per_pass;
            run_tiles(&run, tile0, step, mine, done, count, &rays, &bad);
            done += count;
            seconds = omp_get_wtime() - t0;
            if (desc->progress && !split) {
                il_render_progress p = {
                    .passes_done = done,
                    .passes_total = spp == UINT32_MAX ? 0 : spp,
                    .seconds = seconds,
                    .time_limit = desc->time_limit,
                    .rays = rays,
                    .film = film,
                };
                /* Stopping early is not an error: the film holds `done`
                 * complete samples per pixel and the result says so. */
                if (!desc->progress(&p, desc->progress_user))
                    break;
            }
            if (timed && seconds >= desc->time_limit)
                break;
        }
    }
    out->spp = done;
    out->rays = rays;
    out->nonfinite_samples = bad;
    out->seconds = omp_get_wtime() - t0;
    free(scratch);
    return IL_OK;
}
