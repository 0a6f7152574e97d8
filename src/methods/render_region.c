/* il_render_region: one rectangle of the path tracer's film, all its samples
 * at once: the work unit of a render split across processes
 * (src/cli/mpi/cmd_render_mpi.c, docs/distributed.md).
 *
 * Bit-identity with il_render: the path tracer's camera pass
 * (camera_pass.c, pt_wavefront.c) adds to every pixel its samples
 * 0, 1, ..., spp-1 in increasing index, pass after pass, and each sample's
 * radiance depends only on (seed, pixel, sample index) (il_camera_sample,
 * il_pt_radiance: the wavefront gives the same bits).  Here the wavefront's
 * tile work (il_pt_wavefront_tile) runs on 16x16 tiles of the rectangle with
 * all samples at once: it adds a pixel's samples in increasing index too, so
 * every pixel's four sums are the same doubles; pixels outside are not
 * touched. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "illum/illum.h"
#include "methods/camera_pass.h"
#include "methods/pt/pt.h"
#include "scene/scene.h"

#define IL_REGION_MAX_SPP (1u << 24)
#define IL_REGION_MAX_DEPTH 1024u
#define IL_REGION_TILE 16u
#define IL_REGION_MAX_THREADS 4096

il_status il_render_region(const il_scene *scene, il_film *film, const il_render_desc *desc,
                           const il_render_rect *region, il_render_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (!scene || !film || !desc || !region)
        return il_fail(err, IL_ERR_INVALID, "render region: scene, film, options and region are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID,
                       "render region: the scene is not committed (call il_scene_commit first)");
    if (desc->method != IL_METHOD_PT)
        return il_fail(err, IL_ERR_INVALID,
                       "render region: only the path tracer (pt) renders by regions");
    if (desc->time_limit != 0.0)
        return il_fail(err, IL_ERR_INVALID,
                       "render region: a region renders a sample count, not for a time");
    if (desc->spp > IL_REGION_MAX_SPP || desc->max_depth > IL_REGION_MAX_DEPTH ||
        desc->threads < 0 || desc->threads > IL_REGION_MAX_THREADS || (unsigned)desc->sampler > IL_SAMPLER_PCG ||
        (unsigned)desc->filter > IL_FILTER_GAUSSIAN)
        return il_fail(err, IL_ERR_INVALID, "render region: an option is out of range (see il_render)");
    uint32_t w = il_film_width(film), h = il_film_height(film);
    if (region->x0 >= region->x1 || region->y0 >= region->y1 || region->x1 > w || region->y1 > h)
        return il_fail(err, IL_ERR_INVALID,
                       "render region: [%u,%u)x[%u,%u) is empty or outside the %ux%u film",
                       region->x0, region->x1, region->y0, region->y1, w, h);

    il_camera_pass_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    ctx.film = film;
    ctx.width = w;
    ctx.height = h;
    ctx.seed = desc->seed;
    ctx.sampler = desc->sampler;
    ctx.filter = desc->filter;
    il_camera_init(&ctx.cam, &scene->camera.desc, w, h);
    uint32_t spp = desc->spp ? desc->spp : 16u;
    uint32_t max_depth = desc->max_depth ? desc->max_depth : 8u;
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();

    /* The wavefront's 16x16 tiles within the region, each with all its
     * samples, each on one thread with its own scratch. */
    size_t stride = (il_pt_wavefront_scratch_bytes() + 63) / 64 * 64;
    unsigned char *scratch = aligned_alloc(64, (size_t)threads * stride);
    if (!scratch)
        return il_fail(err, IL_ERR_MEMORY, "render region: out of memory (%zu bytes per thread)",
                       stride);
    double t0 = omp_get_wtime();
    uint64_t rays = 0, bad = 0;
    uint32_t tx = (region->x1 - region->x0 + IL_REGION_TILE - 1) / IL_REGION_TILE;
    uint32_t ty = (region->y1 - region->y0 + IL_REGION_TILE - 1) / IL_REGION_TILE;
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : rays, bad)
    for (uint32_t t = 0; t < tx * ty; t++) {
        uint32_t x0 = region->x0 + t % tx * IL_REGION_TILE, y0 = region->y0 + t / tx * IL_REGION_TILE;
        il_camera_tile tile = {
            .x0 = x0,
            .y0 = y0,
            .x1 = x0 + IL_REGION_TILE < region->x1 ? x0 + IL_REGION_TILE : region->x1,
            .y1 = y0 + IL_REGION_TILE < region->y1 ? y0 + IL_REGION_TILE : region->y1,
            .first = 0,
            .count = spp,
            .scratch = scratch + (size_t)omp_get_thread_num() * stride,
        };
        il_pt_wavefront_tile(scene, max_depth, IL_PT_MIS, &ctx, &tile);
        rays += tile.rays;
        bad += tile.nonfinite;
    }
    free(scratch);
    if (stats) {
        stats->spp = spp;
        stats->rays = rays;
        stats->nonfinite_samples = bad;
        stats->seconds = omp_get_wtime() - t0;
    }
    return IL_OK;
}
