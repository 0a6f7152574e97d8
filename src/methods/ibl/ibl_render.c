/* The ibl method's driver: the light set, then batch after batch of lights
 * over all tiles, the film rewritten after each batch as the image of the
 * lights so far, progress and time limit between batches.
 *
 * Pixel value after M lights, with spp camera samples s per pixel:
 *     L = 1/spp sum_s [ base_s + 1/M sum_{i<M} f_s(wo, wi_i) w_i cos_s(wi_i) V_s(wi_i) ],
 * w_i = L_env(wi_i) / pdf(wi_i) (ibl_lights.c), base_s what the sample sees
 * without the environment's lights (the environment or emitters seen
 * directly or through mirrors, the scene's other lights). */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/ibl/ibl_shade.h"

/* Shadow maps of one pass over the tiles fit in this much memory: a batch
 * with more is shaded in several passes. */
#define IL_IBL_MAP_BYTES (256u << 20)
/* Most camera samples per tile. */
#define IL_IBL_TILE_SAMPLES 4096u

typedef struct ibl_state {
    il_ibl_job job;
    il_ibl_lights lights;
    il_ibl_scratch *scratch;
    int threads;
} ibl_state;

static void state_free(ibl_state *st)
{
    if (st->scratch) {
        for (int k = 0; k < st->threads; k++) {
            il_ibl_scratch *sc = &st->scratch[k];
            free(sc->vertices);
            free(sc->rays);
            free(sc->contrib);
            free(sc->pixel);
            free(sc->visible);
        }
        free(st->scratch);
    }
    il_ibl_lights_free(&st->lights);
    il_ibl_camera_free(&st->job.cam);
    free(st->job.cache);
    free(st->job.cache_count);
    free(st->job.base);
    free(st->job.acc);
}

static il_status state_init(ibl_state *st, const il_scene *scene, const il_film *film,
                            const il_render_desc *desc, const il_ibl_settings *set,
                            size_t cache_bytes, il_error *err)
{
    il_ibl_job *job = &st->job;
    uint32_t w = il_film_width(film), h = il_film_height(film);
    il_status s = il_ibl_camera_init(&job->cam, scene, desc, w, h, set->max_depth, err);
    if (s != IL_OK)
        return s;
    job->shadows = set->shadows;
    job->spp = set->spp;
    job->tile = 16;
    while (job->tile > 1 && job->tile * job->tile * set->spp > IL_IBL_TILE_SAMPLES)
        job->tile /= 2;
    job->tiles_x = (w + job->tile - 1) / job->tile;
    job->tiles = job->tiles_x * ((h + job->tile - 1) / job->tile);
    job->tile_samples = job->tile * job->tile * set->spp;
    size_t slots = (size_t)job->tiles * job->tile_samples;
    if (slots * sizeof(il_ibl_vertex) <= cache_bytes) {
        /* Without the cache the render still works: no error if it fails. */
        job->cache = malloc(slots * sizeof(il_ibl_vertex));
        job->cache_count = calloc(job->tiles, sizeof(uint32_t));
        if (!job->cache || !job->cache_count) {
            free(job->cache);
            free(job->cache_count);
            job->cache = NULL;
            job->cache_count = NULL;
        }
    }
    job->base = il_calloc((size_t)w * h * 3, sizeof(double), err);
    job->acc = il_calloc((size_t)w * h * 3, sizeof(double), err);
    st->scratch = il_calloc((size_t)st->threads, sizeof(il_ibl_scratch), err);
    if (!job->base || !job->acc || !st->scratch)
        return IL_ERR_MEMORY;
    uint32_t n = job->tile_samples;
    for (int k = 0; k < st->threads; k++) {
        il_ibl_scratch *sc = &st->scratch[k];
        if (!job->cache && !(sc->vertices = il_malloc(n * sizeof(il_ibl_vertex), err)))
            return IL_ERR_MEMORY;
        sc->rays = il_malloc(n * sizeof(il_ray), err);
        sc->contrib = il_malloc(n * sizeof(il_vec3), err);
        sc->pixel = il_malloc(n * sizeof(uint32_t), err);
        sc->visible = il_malloc(n * sizeof(float), err);
        if (!sc->rays || !sc->contrib || !sc->pixel || !sc->visible)
            return IL_ERR_MEMORY;
    }
    return IL_OK;
}

/* Split across processes (il_distrib): tile t is process t mod size's. */
static bool my_tile(const il_distrib *d, uint32_t t)
{
    return !il_distrib_on(d) || t % (uint32_t)d->size == (uint32_t)d->rank;
}

/* The film as the image of the first m lights (split: of this process's
 * tiles; the others' pixels stay zero, so the films add up to one
 * process's). */
static void write_film(const ibl_state *st, il_film *film, uint32_t m, const il_distrib *d)
{
    const il_ibl_job *job = &st->job;
    uint32_t w = il_film_width(film), h = il_film_height(film);
    double inv_m = m ? 1.0 / m : 0.0, inv_spp = 1.0 / job->spp;
    il_film_clear(film);
#pragma omp parallel for schedule(static) num_threads(st->threads)
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            if (!my_tile(d, (y / job->tile) * job->tiles_x + x / job->tile))
                continue;
            size_t p = 3 * ((size_t)y * w + x);
            const double *b = job->base + p, *a = job->acc + p;
            il_vec3 L = v3((float)((b[0] + a[0] * inv_m) * inv_spp),
                           (float)((b[1] + a[1] * inv_m) * inv_spp),
                           (float)((b[2] + a[2] * inv_m) * inv_spp));
            il_film_add_sample(film, x, y, L, 1.0f);
        }
}

/* Builds the shadow maps of lights l0..l1-1 into sm (allocated for them). */
static void build_maps(const il_scene *scene, const il_ibl_lights *ls, uint32_t l0, uint32_t l1,
                       il_ibl_shadow_maps *sm, int threads)
{
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (uint32_t l = l0; l < l1; l++)
        il_ibl_shadow_map_build(scene, &sm->maps[l - l0], sm->size, ls->dir[l - ls->first]);
}

il_status il_ibl_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        il_render_stats *stats, il_error *err)
{
    return il_ibl_render_budget(scene, film, desc, IL_IBL_CACHE_BYTES, stats, err);
}

il_status il_ibl_render_budget(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               size_t cache_bytes, il_render_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (!scene || !film || !desc)
        return il_fail(err, IL_ERR_INVALID, "render: scene, film and options are required");
    il_ibl_settings set;
    il_status s = il_ibl_settings_resolve(desc->ibl, desc, &set, err);
    if (s != IL_OK)
        return s;
    if (!scene->has_environment)
        return il_fail(err, IL_ERR_INVALID,
                       "ibl: the scene has no environment to turn into lights (give one with "
                       "--env FILE, a scene file's \"environment\", or il_scene_set_environment)");

    double t0 = omp_get_wtime();
    ibl_state st;
    memset(&st, 0, sizeof st);
    st.threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    il_ibl_shadow_maps sm;
    memset(&sm, 0, sizeof sm);
    s = state_init(&st, scene, film, desc, &set, cache_bytes, err);
    /* The lights of one batch at a time: a time-limited render may ask
     * for millions. */
    if (s == IL_OK)
        s = il_ibl_lights_alloc(&st.lights, set.batch, err);
    st.job.lights = &st.lights;
    /* Shadow maps for one pass over the tiles: the batch, or as many of its
     * lights as fit in IL_IBL_MAP_BYTES. */
    uint32_t group = set.batch;
    if (s == IL_OK && set.shadows == IL_IBL_SHADOW_MAPS) {
        size_t bytes = (size_t)set.shadow_map_size * set.shadow_map_size * sizeof(float);
        size_t fit = IL_IBL_MAP_BYTES / bytes;
        if (fit < 1)
            fit = 1;
        if (group > fit)
            group = (uint32_t)fit;
        float diagonal = v3_length(v3_sub(scene->bounds_max, scene->bounds_min));
        s = il_ibl_shadow_maps_alloc(&sm, group, set.shadow_map_size, set.pcf_taps,
                                     set.shadow_bias * (diagonal > 0.0f ? diagonal : 1.0f), err);
    }
    if (s != IL_OK) {
        state_free(&st);
        il_ibl_shadow_maps_free(&sm);
        return s;
    }
    double seconds_lights = omp_get_wtime() - t0, seconds = 0.0;

    il_film_clear(film);
    il_ibl_tile_stats total = {0};
    uint32_t done = 0;
    bool first = true;
    while (done < set.lights) {
        uint32_t end = set.lights - done < set.batch ? set.lights : done + set.batch;
        double tl = omp_get_wtime();
        il_ibl_lights_fill(scene, set.selection, desc->seed, done, end - done, st.threads, &st.lights);
        seconds_lights += omp_get_wtime() - tl;
        for (uint32_t g0 = done; g0 < end; g0 += group) {
            uint32_t g1 = end - g0 < group ? end : g0 + group;
            if (set.shadows == IL_IBL_SHADOW_MAPS) {
                double tm = omp_get_wtime();
                build_maps(scene, &st.lights, g0, g1, &sm, st.threads);
                seconds_lights += omp_get_wtime() - tm;
            }
            uint64_t rays = 0, shadow_rays = 0, bad = 0;
            const il_ibl_shadow_maps *maps = set.shadows == IL_IBL_SHADOW_MAPS ? &sm : NULL;
#pragma omp parallel for schedule(dynamic) num_threads(st.threads) \
    reduction(+ : rays, shadow_rays, bad)
            for (uint32_t t = 0; t < st.job.tiles; t++) {
                if (!my_tile(desc->distrib, t))
                    continue;
                il_ibl_tile_stats ts = {0};
                il_ibl_shade_tile(&st.job, t, first, g0, g1, maps, &st.scratch[omp_get_thread_num()],
                                  &ts);
                rays += ts.rays;
                shadow_rays += ts.shadow_rays;
                bad += ts.nonfinite;
            }
            total.rays += rays;
            total.shadow_rays += shadow_rays;
            total.nonfinite += bad;
            first = false;
        }
        done = end;
        write_film(&st, film, done, desc->distrib);
        seconds = omp_get_wtime() - t0;
        if (desc->progress && !il_distrib_on(desc->distrib)) {
            /* For ibl a "pass" is a batch of lights: passes_done counts lights. */
            il_render_progress p = {.passes_done = done,
                                    .passes_total = set.lights,
                                    .seconds = seconds,
                                    .time_limit = desc->time_limit,
                                    .rays = total.rays,
                                    .film = film};
            if (!desc->progress(&p, desc->progress_user))
                break;
        }
        if (desc->time_limit > 0.0 && seconds >= desc->time_limit)
            break;
    }
    if (stats) {
        stats->spp = set.spp;
        stats->rays = total.rays;
        stats->seconds = seconds;
        stats->nonfinite_samples = total.nonfinite;
        stats->ibl.lights = done;
        stats->ibl.shadow_rays = total.shadow_rays;
        stats->ibl.seconds_lights = seconds_lights;
        stats->ibl.seconds_shade = seconds - seconds_lights;
    }
    state_free(&st);
    il_ibl_shadow_maps_free(&sm);
    return IL_OK;
}
