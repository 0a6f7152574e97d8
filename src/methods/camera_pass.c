/* The camera pass: passes over 16x16 tiles scheduled by OpenMP.
 *
 * Determinism: a sample's value depends only on (seed, pixel, sample index)
 * (the sampler is keyed by them, never by the thread), every pixel belongs to
 * exactly one tile, a tile is rendered by one thread, and a pass adds each
 * pixel's samples in increasing index; passes run one after the other.  So
 * every pixel's sum is formed in the same order whatever the thread count,
 * and the film is bit-identical with 1 or N threads. */
#include "methods/camera_pass.h"

#include <omp.h>
#include <string.h>

#include "scene/camera.h"

#define IL_TILE 16
/* A pass renders about this many samples, at least 1 and at most 64 per
 * pixel: small images get several samples per pixel per pass so that the
 * per-pass cost (thread start-up, progress callback) stays negligible. */
#define IL_PASS_SAMPLES 65536u
#define IL_PASS_MAX_SPP 64u

typedef struct pass_job {
    il_film *film;
    il_camera cam;
    uint32_t width, height, tiles_x;
    uint64_t seed;
    il_sampler_type sampler;
    il_filter_type filter;
    il_camera_radiance_fn radiance;
    const void *method;
} pass_job;

static void render_tile(const pass_job *job, uint32_t tile, uint32_t first, uint32_t count,
                        uint64_t *rays, uint64_t *bad)
{
    uint32_t x0 = (tile % job->tiles_x) * IL_TILE, y0 = (tile / job->tiles_x) * IL_TILE;
    uint32_t x1 = x0 + IL_TILE < job->width ? x0 + IL_TILE : job->width;
    uint32_t y1 = y0 + IL_TILE < job->height ? y0 + IL_TILE : job->height;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++) {
            uint64_t pixel = (uint64_t)y * job->width + x;
            for (uint32_t i = first; i < first + count; i++) {
                il_sampler smp;
                il_sampler_start(&smp, job->sampler, job->seed, pixel, i);
                il_vec2 off = il_filter_offset(job->filter, il_sampler_2d(&smp));
                il_vec3 dir = il_camera_ray_dir(&job->cam, (float)x + off.x, (float)y + off.y);
                il_vec3 L = job->radiance(job->method, job->cam.position, dir, &smp, rays);
                /* A NaN or Inf would poison the pixel for good: drop the sample. */
                if (!v3_is_finite(L)) {
                    (*bad)++;
                    continue;
                }
                il_film_add_sample(job->film, x, y, L, 1.0f);
            }
        }
}

void il_camera_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                    il_camera_radiance_fn radiance, const void *method,
                    il_camera_pass_result *out)
{
    pass_job job;
    memset(&job, 0, sizeof job);
    job.film = film;
    job.width = il_film_width(film);
    job.height = il_film_height(film);
    job.tiles_x = (job.width + IL_TILE - 1) / IL_TILE;
    job.seed = desc->seed;
    job.sampler = desc->sampler;
    job.filter = desc->filter;
    job.radiance = radiance;
    job.method = method;
    il_camera_init(&job.cam, &scene->camera.desc, job.width, job.height);

    bool timed = desc->time_limit > 0.0;
    uint32_t spp = desc->spp ? desc->spp : (timed ? UINT32_MAX : 16u);
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    uint64_t pixels = (uint64_t)job.width * job.height;
    uint32_t tiles = job.tiles_x * ((job.height + IL_TILE - 1) / IL_TILE);
    uint32_t per_pass = pixels ? (uint32_t)(IL_PASS_SAMPLES / pixels) : 1u;
    per_pass = per_pass < 1 ? 1 : (per_pass > IL_PASS_MAX_SPP ? IL_PASS_MAX_SPP : per_pass);

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
             * samples per pixel and the result says so. */
            if (!desc->progress(&p, desc->progress_user))
                break;
        }
        if (timed && seconds >= desc->time_limit)
            break;
    }
    out->spp = done;
    out->rays = rays;
    out->nonfinite_samples = bad;
    out->seconds = seconds;
}
