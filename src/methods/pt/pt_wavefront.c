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
 * and the film receives a pixel's samples in increasing index, as in the
 * shared camera pass (methods/camera_pass.c), whose tiles, passes, progress
 * reports, time limit and treatment of NaN samples this follows exactly: so
 * the film is bit-identical to il_camera_pass with il_pt_radiance, and the
 * same with 1 or N threads. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/camera_pass.h"
#include "methods/pt/pt.h"
#include "scene/camera.h"

#define PT_TILE 16            /* as camera_pass.c */
#define PT_PASS_SAMPLES 65536u
#define PT_PASS_MAX_SPP 64u
/* Paths advanced together: one 16x16 tile at one sample per pixel. */
#define PT_WAVE 256u

typedef struct pt_job {
    const il_scene *scene;
    il_film *film;
    il_camera cam;
    uint32_t width, height, tiles_x;
    uint64_t seed;
    il_sampler_type sampler;
    il_filter_type filter;
    uint32_t max_depth;
    il_pt_strategy strategy;
} pt_job;

/* One wave: up to PT_WAVE paths with their samplers and pixels, and the
 * gather buffers for the stream calls. */
typedef struct pt_wave {
    il_pt_state st[PT_WAVE];
    il_sampler smp[PT_WAVE];
    uint32_t px[PT_WAVE], py[PT_WAVE];
    uint32_t active[PT_WAVE], shadowed[PT_WAVE];
    il_ray rays[PT_WAVE];
    il_hit hits[PT_WAVE];
    bool occluded[PT_WAVE];
} pt_wave;

/* Runs paths 0..n-1 of the wave to their ends. */
static void run_wave(const pt_job *job, pt_wave *w, uint32_t n)
{
    const il_tracer *tr = job->scene->tracer;
    uint32_t num_active = n;
    for (uint32_t j = 0; j < n; j++)
        w->active[j] = j;
    while (num_active > 0) {
        for (uint32_t a = 0; a < num_active; a++)
            w->rays[a] = w->st[w->active[a]].ray;
        il_trace_closest_n(tr, w->rays, w->hits, num_active);

        uint32_t num_shadow = 0, still = 0;
        for (uint32_t a = 0; a < num_active; a++) {
            uint32_t j = w->active[a];
            const il_hit *hit = w->hits[a].mesh != IL_HIT_NONE ? &w->hits[a] : NULL;
            bool more = il_pt_step(job->scene, &w->st[j], hit, &w->smp[j], job->max_depth,
                                   job->strategy);
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

/* Samples first..first+count-1 of every pixel of the tile, in waves taken
 * in the order camera_pass.c visits them (pixel by pixel, samples in
 * increasing index), and added to the film in that order. */
static void render_tile(const pt_job *job, pt_wave *w, uint32_t tile, uint32_t first,
                        uint32_t count, uint64_t *rays, uint64_t *bad)
{
    uint32_t x0 = (tile % job->tiles_x) * PT_TILE, y0 = (tile / job->tiles_x) * PT_TILE;
    uint32_t x1 = x0 + PT_TILE < job->width ? x0 + PT_TILE : job->width;
    uint32_t y1 = y0 + PT_TILE < job->height ? y0 + PT_TILE : job->height;
    uint32_t x = x0, y = y0, i = first;
    while (y < y1) {
        /* Fill a wave. */
        uint32_t n = 0;
        while (n < PT_WAVE && y < y1) {
            il_sampler *smp = &w->smp[n];
            il_sampler_start(smp, job->sampler, job->seed, (uint64_t)y * job->width + x, i);
            il_vec2 off = il_filter_offset(job->filter, il_sampler_2d(smp));
            il_vec3 dir = il_camera_ray_dir(&job->cam, (float)x + off.x, (float)y + off.y);
            il_pt_begin(&w->st[n], job->cam.position, dir);
            w->px[n] = x;
            w->py[n] = y;
            n++;
            if (++i == first + count) {
                i = first;
                if (++x == x1) {
                    x = x0;
                    y++;
                }
            }
        }
        run_wave(job, w, n);
        for (uint32_t j = 0; j < n; j++) {
            *rays += w->st[j].rays;
            /* A NaN or Inf would poison the pixel for good: drop the sample. */
            if (!v3_is_finite(w->st[j].L)) {
                (*bad)++;
                continue;
            }
            il_film_add_sample(job->film, w->px[j], w->py[j], w->st[j].L, 1.0f);
        }
    }
}

il_status il_pt_wavefront_pass(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               uint32_t max_depth, il_pt_strategy strategy,
                               il_camera_pass_result *out, il_error *err)
{
    pt_job job;
    memset(&job, 0, sizeof job);
    job.scene = scene;
    job.film = film;
    job.width = il_film_width(film);
    job.height = il_film_height(film);
    job.tiles_x = (job.width + PT_TILE - 1) / PT_TILE;
    job.seed = desc->seed;
    job.sampler = desc->sampler;
    job.filter = desc->filter;
    job.max_depth = max_depth;
    job.strategy = strategy;
    il_camera_init(&job.cam, &scene->camera.desc, job.width, job.height);

    bool timed = desc->time_limit > 0.0;
    uint32_t spp = desc->spp ? desc->spp : (timed ? UINT32_MAX : 16u);
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    uint64_t pixels = (uint64_t)job.width * job.height;
    uint32_t tiles = job.tiles_x * ((job.height + PT_TILE - 1) / PT_TILE);
    uint32_t per_pass = pixels ? (uint32_t)(PT_PASS_SAMPLES / pixels) : 1u;
    per_pass = per_pass < 1 ? 1 : (per_pass > PT_PASS_MAX_SPP ? PT_PASS_MAX_SPP : per_pass);

    /* One wave per thread (about 70 KB each), allocated up front. */
    pt_wave *waves = il_malloc((size_t)threads * sizeof *waves, err);
    if (!waves)
        return IL_ERR_MEMORY;

    il_film_clear(film);
    double t0 = omp_get_wtime(), seconds = 0.0;
    uint64_t rays = 0, bad = 0;
    uint32_t done = 0;
    while (done < spp) {
        uint32_t count = spp - done < per_pass ? spp - done : per_pass;
        uint64_t pass_rays = 0, pass_bad = 0;
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : pass_rays, pass_bad)
        for (uint32_t t = 0; t < tiles; t++)
            render_tile(&job, &waves[omp_get_thread_num()], t, done, count, &pass_rays, &pass_bad);
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
    free(waves);
    return IL_OK;
}
