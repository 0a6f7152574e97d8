/* Stochastic progressive photon mapping (Hachisuka & Jensen 2009,
 * "Stochastic Progressive Photon Mapping"; the same bookkeeping as pbrt-v3
 * 16.2).  Every pass:
 *
 *  1. a camera sample per pixel, followed through mirrors and glass to its
 *     first non-delta hit: the pixel's visible point for this pass; the
 *     light it sees directly (emitters, a shadow ray) goes to the pixel's
 *     direct sum;
 *  2. a batch of photons; those left after at least one bounce are put in
 *     a map (kd-tree or grid) over which every visible point collects the
 *     photons within its pixel's radius r:  phi = sum f(wo, wi_p) power_p;
 *  3. per pixel (M photons found, N accumulated so far, eq. 8-10 of the
 *     paper):  N' = N + alpha M,  r' = r sqrt(N' / (N + M)),
 *     tau' = (tau + beta phi) r'^2 / r^2.
 *
 * The image after pass i is  direct / i + tau / (i * photons * pi r^2).
 * The radii shrink so that the estimate's bias goes to zero while its
 * variance does too: the method converges to the path tracer's answer.
 *
 * Determinism: the visible points and photons depend only on the seed,
 * the pixel and the pass; each pixel's update is done by one thread over
 * photons in the map's order, so the image is the same for any thread
 * count.  Split across processes (il_distrib): process r takes the pixel
 * rows y mod N = r, the photons are traced in parts and exchanged into the
 * very map a single process builds (pm_distrib.c), so every pixel sees the
 * same updates and the processes' films sum to the single-process film. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/camera_pass.h"
#include "methods/distrib.h"
#include "methods/photon/pm.h"
#include "methods/photon/pm_internal.h"
#include "scene/direct.h"
#include "scene/lights.h"
#include "trace/trace.h"

typedef struct sppm_pixel {
    il_pm_vertex vp;           /* this pass's visible point */
    bool valid;                /* the camera path found a non-delta surface */
    double direct[3];          /* emitted + direct light, summed over passes */
    double tau[3];             /* the flux of the photons kept, Hachisuka eq. 10 */
    double n;                  /* photons accumulated (N) */
    float r;                   /* the current radius */
} sppm_pixel;

typedef struct sppm {
    const il_scene *scene;
    const il_render_desc *desc;
    il_pm_settings ps;
    uint32_t max_depth;
    il_camera_pass_ctx ctx;
    sppm_pixel *px;
    size_t num_px;
    int threads;
    const il_distrib *distrib; /* split across processes: pixel rows y with
                                  y mod size == rank are this process's */
} sppm;

/* Whether pixel row y is this process's (every row in a single process). */
static bool owns_row(const sppm *s, uint32_t y)
{
    return !il_distrib_on(s->distrib) || y % (uint32_t)s->distrib->size == (uint32_t)s->distrib->rank;
}

/* The largest r_max of all processes (a maximum is exact in any order). */
static il_status max_over_processes(const il_distrib *d, float *r_max, il_error *err)
{
    if (!il_distrib_on(d))
        return IL_OK;
    void *all = NULL;
    il_status st = il_distrib_allgather(d, r_max, sizeof *r_max, &all, NULL, err);
    if (st != IL_OK)
        return st;
    for (int r = 0; r < d->size; r++) {
        float v;
        memcpy(&v, (const unsigned char *)all + (size_t)r * sizeof v, sizeof v);
        *r_max = il_maxf(*r_max, v);
    }
    free(all);
    return IL_OK;
}

/* Step 1: the visible points of pass `pass`; returns the largest radius
 * among the pixels that have one (0 when none) and counts rays. */
static float visible_points(sppm *s, uint32_t pass, uint64_t *rays_out)
{
    uint64_t rays = 0;
    float r_max = 0.0f;
    const uint32_t w = s->ctx.width, h = s->ctx.height;
#pragma omp parallel for schedule(dynamic, 4) num_threads(s->threads) reduction(+ : rays) \
    reduction(max : r_max)
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w && owns_row(s, y); x++) {
            sppm_pixel *p = &s->px[(size_t)y * w + x];
            il_sampler smp;
            il_vec3 dir = il_camera_sample(&s->ctx, x, y, pass, &smp);
            il_ray ray = {.org = s->ctx.cam.position, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
            il_vec3 L = v3(0.0f, 0.0f, 0.0f);
            p->valid = il_pm_trace_to_diffuse(s->scene, ray, &smp, s->max_depth - 1, &L, &p->vp, &rays);
            if (p->valid) {
                float u_select = il_sampler_1d(&smp);
                il_vec2 u = il_sampler_2d(&smp);
                il_vec3 d = il_direct_light(s->scene, &p->vp.s, &p->vp.bsdf, p->vp.wo, u_select, u, &rays);
                L = v3_add(L, v3_mul(p->vp.beta, d));
                r_max = il_maxf(r_max, p->r);
            }
            if (v3_is_finite(L)) {
                p->direct[0] += L.x;
                p->direct[1] += L.y;
                p->direct[2] += L.z;
            }
        }
    *rays_out += rays;
    return r_max;
}

/* Steps 2 and 3 for one pixel. */
static il_status collect(const il_pm_map *map, sppm_pixel *p, float alpha, il_pm_buffer *buf,
                         il_error *err)
{
    buf->count = 0;
    il_status st = il_pm_range(map, p->vp.s.p, p->r * p->r, buf, err);
    if (st != IL_OK)
        return st;
    double phi[3] = {0.0, 0.0, 0.0};
    uint32_t m = 0;
    for (uint32_t k = 0; k < buf->count; k++) {
        const il_photon *ph = &map->photons[buf->items[k].index];
        if (!il_pm_on_surface(ph, p->vp.n, p->vp.s.p, p->r))
            continue;
        float pdf_unused;
        il_vec3 f = il_bsdf_eval(&p->vp.bsdf, p->vp.wo, il_photon_dir(ph), &pdf_unused);
        il_vec3 c = v3_mul(f, il_photon_power(ph));
        phi[0] += c.x;
        phi[1] += c.y;
        phi[2] += c.z;
        m++;
    }
    if (m == 0)
        return IL_OK;
    double n_new = p->n + alpha * m;
    double ratio = n_new / (p->n + m);     /* r'^2 / r^2 */
    il_vec3 beta = p->vp.beta;
    p->tau[0] = (p->tau[0] + beta.x * phi[0]) * ratio;
    p->tau[1] = (p->tau[1] + beta.y * phi[1]) * ratio;
    p->tau[2] = (p->tau[2] + beta.z * phi[2]) * ratio;
    p->n = n_new;
    p->r = p->r * (float)sqrt(ratio);
    return IL_OK;
}

/* The progress report's convergence figure: the mean current radius of the
 * pixels whose visible point this pass found (the others keep the initial
 * radius forever and would hide the shrinking of eq. 8-10 above). */
static double mean_radius(const sppm *s)
{
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < s->num_px; i++)
        if (s->px[i].valid) {
            sum += s->px[i].r;
            n++;
        }
    return n ? sum / (double)n : 0.0;
}

static il_status photon_pass(sppm *s, uint32_t pass, float r_max, il_photon_stats *st, il_error *err)
{
    double t0 = omp_get_wtime();
    il_pm_photons ph = {0};
    il_pm_trace_desc td = {.first = (uint64_t)pass * s->ps.photons,
                           .count = s->ps.photons,
                           .seed = s->desc->seed,
                           .max_depth = s->ps.max_photon_depth,
                           .threads = s->threads,
                           .split = false,
                           .at_portals = s->ps.portal_light};
    il_status status = s->ps.max_photon_depth > 0
                           ? il_pm_trace_split(s->scene, &td, s->distrib, &ph, err)
                           : IL_OK;
    if (status != IL_OK)
        return status;
    free(ph.caustic);
    il_pm_report_photons(s->desc->photon, ph.global, ph.num_global, 2);
    st->emitted += s->ps.photons;
    st->stored += ph.num_global;
    st->photon_rays += ph.rays;
    double t1 = omp_get_wtime();
    st->seconds_trace += t1 - t0;

    il_pm_map map = {0};
    status = il_pm_map_build_split(&map, ph.global, ph.num_global, 1.0f, s->ps.lookup.lookup,
                                   r_max > 0.0f ? r_max : s->ps.initial_radius, s->distrib, err);
    if (status != IL_OK)
        return status;
    double t2 = omp_get_wtime();
    st->seconds_build += t2 - t1;
    size_t bytes = il_pm_map_bytes(&map);
    if (bytes > st->map_bytes)
        st->map_bytes = bytes;

    int failed = 0;
    if (map.count > 0) {
#pragma omp parallel num_threads(s->threads) reduction(| : failed)
        {
            il_pm_buffer buf = {0};
#pragma omp for schedule(dynamic, 256)
            for (size_t i = 0; i < s->num_px; i++)
                if (s->px[i].valid && !failed && owns_row(s, (uint32_t)(i / s->ctx.width)) &&
                    collect(&map, &s->px[i], s->ps.alpha, &buf, NULL) != IL_OK)
                    failed = 1;
            il_pm_buffer_free(&buf);
        }
    }
    il_pm_map_free(&map);
    st->seconds_render += omp_get_wtime() - t2;
    if (failed)
        return il_fail(err, IL_ERR_MEMORY, "sppm: out of memory collecting photons");
    return IL_OK;
}

/* The image after `passes` passes. */
static void write_film(const sppm *s, il_film *film, uint32_t passes)
{
    il_film_clear(film);
    double photons = (double)passes * (double)s->ps.photons;
    for (uint32_t y = 0; y < s->ctx.height; y++)
        for (uint32_t x = 0; x < s->ctx.width && owns_row(s, y); x++) {
            const sppm_pixel *p = &s->px[(size_t)y * s->ctx.width + x];
            double area = IL_PI * (double)p->r * p->r;
            double k = p->n > 0.0 && area > 0.0 ? 1.0 / (photons * area) : 0.0;
            il_vec3 L = v3((float)(p->direct[0] / passes + p->tau[0] * k),
                           (float)(p->direct[1] / passes + p->tau[1] * k),
                           (float)(p->direct[2] / passes + p->tau[2] * k));
            il_film_add_sample(film, x, y, L, 1.0f);
        }
}

il_status il_sppm_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                         il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    sppm s = {.scene = scene, .desc = desc, .max_depth = desc->max_depth ? desc->max_depth : 8u};
    il_status st = il_pm_settings_resolve(scene, desc->photon, s.max_depth, true, &s.ps, err);
    if (st == IL_OK)
        st = il_distrib_check(desc->distrib, desc, "sppm", err);
    if (st != IL_OK)
        return st;
    s.distrib = desc->distrib;
    s.threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    s.ctx.film = film;
    s.ctx.width = il_film_width(film);
    s.ctx.height = il_film_height(film);
    s.ctx.seed = desc->seed;
    s.ctx.sampler = desc->sampler;
    s.ctx.filter = desc->filter;
    il_camera_init(&s.ctx.cam, &scene->camera.desc, s.ctx.width, s.ctx.height);
    s.num_px = (size_t)s.ctx.width * s.ctx.height;
    s.px = il_calloc(s.num_px, sizeof *s.px, err);
    if (!s.px)
        return IL_ERR_MEMORY;
    for (size_t i = 0; i < s.num_px; i++)
        s.px[i].r = s.ps.initial_radius;

    bool timed = desc->time_limit > 0.0;
    uint32_t passes = desc->spp ? desc->spp : (timed ? UINT32_MAX : 16u);
    il_photon_stats *ps = &stats->photon;
    ps->bytes_per_photon = (uint32_t)sizeof(il_photon);
    double t0 = omp_get_wtime();
    uint64_t rays = 0;
    uint32_t done = 0;
    while (done < passes) {
        double tv = omp_get_wtime();
        float r_max = visible_points(&s, done, &rays);
        ps->seconds_render += omp_get_wtime() - tv;
        /* The grid's cell size must be the same on every process. */
        if ((st = max_over_processes(s.distrib, &r_max, err)) != IL_OK)
            break;
        if ((st = photon_pass(&s, done, r_max, ps, err)) != IL_OK)
            break;
        done++;
        write_film(&s, film, done);
        double seconds = omp_get_wtime() - t0;
        /* Split across processes the film is this process's rows only:
         * no progress (il_distrib). */
        if (desc->progress && !il_distrib_on(s.distrib)) {
            il_render_progress p = {.passes_done = done,
                                    .passes_total = passes == UINT32_MAX ? 0 : passes,
                                    .seconds = seconds,
                                    .time_limit = desc->time_limit,
                                    .rays = rays + ps->photon_rays,
                                    .film = film,
                                    .radius = mean_radius(&s)};
            if (!desc->progress(&p, desc->progress_user))
                break;
        }
        if (timed && seconds >= desc->time_limit)
            break;
    }
    ps->passes = done;
    stats->spp = done;
    stats->rays = rays + ps->photon_rays;
    stats->seconds = omp_get_wtime() - t0;
    free(s.px);
    return st;
}
