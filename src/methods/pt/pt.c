/* The path tracer's film loop: passes over 16x16 tiles scheduled by OpenMP.
 *
 * Determinism: a sample's value depends only on (seed, pixel, sample index)
 * (the sampler is keyed by them, never by the thread), every pixel belongs to
 * exactly one tile, a tile is rendered by one thread, and a pass adds each
 * pixel's samples in increasing index; passes run one after the other.  So
 * every pixel's sum is formed in the same order whatever the thread count,
 * and the film is bit-identical with 1 or N threads. */
#include <omp.h>
#include <string.h>

#include "core/error.h"
#include "methods/pt/pt.h"
#include "scene/camera.h"

#define IL_PT_TILE 16
/* A pass renders about this many samples, at least 1 and at most 64 per
 * pixel: small images get several samples per pixel per pass so that the
 * per-pass cost (thread start-up, progress callback) stays negligible. */
#define IL_PT_PASS_SAMPLES 65536u
#define IL_PT_PASS_MAX_SPP 64u

typedef struct pt_job {
    const il_scene *scene;
    il_film *film;
    il_camera cam;
    uint32_t width, height, tiles_x;
    uint32_t max_depth;
    uint64_t seed;
    il_sampler_type sampler;
    il_filter_type filter;
    il_pt_strategy strategy;
} pt_job;

static void render_tile(const pt_job *job, uint32_t tile, uint32_t first, uint32_t count,
                        uint64_t *rays, uint64_t *bad)
{
    uint32_t x0 = (tile % job->tiles_x) * IL_PT_TILE, y0 = (tile / job->tiles_x) * IL_PT_TILE;
    uint32_t x1 = x0 + IL_PT_TILE < job->width ? x0 + IL_PT_TILE : job->width;
    uint32_t y1 = y0 + IL_PT_TILE < job->height ? y0 + IL_PT_TILE : job->height;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++) {
            uint64_t pixel = (uint64_t)y * job->width + x;
            for (uint32_t i = first; i < first + count; i++) {
                il_sampler smp;
                il_sampler_start(&smp, job->sampler, job->seed, pixel, i);
                il_vec2 off = il_pt_filter_offset(job->filter, il_sampler_2d(&smp));
                il_vec3 dir = il_camera_ray_dir(&job->cam, (float)x + off.x, (float)y + off.y);
                il_vec3 L = il_pt_radiance(job->scene, job->cam.position, dir, &smp, job->max_depth,
                                           job->strategy, rays);
                /* A NaN or Inf would poison the pixel for good: drop the sample. */
                if (!v3_is_finite(L)) {
                    (*bad)++;
                    continue;
                }
                il_film_add_sample(job->film, x, y, L, 1.0f);
            }
        }
}

il_status il_pt_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_pt_strategy strategy, il_render_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (!scene || !film || !desc)
        return il_fail(err, IL_ERR_INVALID, "render: scene, film and options are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "render: the scene is not committed (call il_scene_commit)");

    pt_job job;
    memset(&job, 0, sizeof job);
    job.scene = scene;
    job.film = film;
    job.width = il_film_width(film);
    job.height = il_film_height(film);
    job.tiles_x = (job.width + IL_PT_TILE - 1) / IL_PT_TILE;
    job.max_depth = desc->max_depth ? desc->max_depth : 8;
    job.seed = desc->seed;
    job.sampler = desc->sampler;
    job.filter = desc->filter;
    job.strategy = strategy;
    il_camera_init(&job.cam, &scene->camera.desc, job.width, job.height);

    bool timed = desc->time_limit > 0.0;
    uint32_t spp = desc->spp ? desc->spp : (timed ? UINT32_MAX : 16u);
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    uint64_t pixels = (uint64_t)job.width * job.height;
    uint32_t tiles = job.tiles_x * ((job.height + IL_PT_TILE - 1) / IL_PT_TILE);
    uint32_t per_pass = pixels ? (uint32_t)(IL_PT_PASS_SAMPLES / pixels) : 1u;
    per_pass = per_pass < 1 ? 1 : (per_pass > IL_PT_PASS_MAX_SPP ? IL_PT_PASS_MAX_SPP : per_pass);

    il_film_clear(film);
    double t0 = omp_get_wtime(), seconds = 0.0;
    uint64_t rays = 0, bad = 0;
    uint32_t done = 0;
    while (done < spp) {
        uint32_t count = spp - done < per_pass ? spp - done : per_pass;
        uint64_t pass_rays = 0, pass_bad = 0;
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : pass_rays, pass_bad)
        for (uint32_t t = 0; t < tiles; t++)
            render_tile(&job, t, done, count, &pass_rays, &pass_bad);
        done += count;
        rays += pass_rays;
        bad += pass_bad;
        seconds = omp_get_wtime() - t0;
        if (desc->progress) {
            il_render_progress p = {
                .passes_done = done,
                .passes_total = spp == UINT32_MAX ? 0 : spp,
                .seconds = seconds,
                .time_limit = desc->time_limit,
                .rays = rays,
                .film = film,
            };
            /* Stopping early is not an error: the film holds `done` complete
             * samples per pixel and stats.spp says so. */
            if (!desc->progress(&p, desc->progress_user))
                break;
        }
        if (timed && seconds >= desc->time_limit)
            break;
    }
    if (stats) {
        stats->spp = done;
        stats->rays = rays;
        stats->seconds = seconds;
        stats->nonfinite_samples = bad;
    }
    return IL_OK;
}
