/* Two-pass photon mapping (Jensen 2001, "Realistic Image Synthesis Using
 * Photon Mapping", chapter 9): photons into a global and a caustic map,
 * then a camera pass that splits the light at the first non-delta hit x:
 *
 *   L(x) = Le (seen directly or through mirrors and glass)
 *        + direct light by a shadow ray      (paths L D E)
 *        + the caustic map's estimate        (L S+ D E: only mirrors and glass
 *                                             since the light)
 *        + indirect light                    (L ... D S* D E)
 *
 * where the last term is the global map's estimate at x (it holds every
 * stored photon the caustic map does not), or, with final gathering
 * (Jensen 2001, 9.3.2), the mean over N BSDF-sampled rays, followed through
 * mirrors and glass, of what their first non-delta hit x' reflects towards
 * x: direct light at x' by a shadow ray plus the global and caustic
 * estimates at x'.  At Lambertian
 * surfaces the global map is read from the irradiance precomputed at every
 * 4th photon (Christensen 1999, pm_irradiance.c).  Direct-light
 * photons are never stored (pm_trace.c), so no path is counted twice. */
#include <math.h>
#include <omp.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/camera_pass.h"
#include "methods/distrib.h"
#include "methods/photon/pm.h"
#include "scene/direct.h"
#include "trace/trace.h"

typedef struct pm_method {
    const il_scene *scene;
    const il_pm_map *global, *caustic;
    il_pm_lookup lookup;
    uint32_t final_gather;
    uint32_t max_depth;
    atomic_int *out_of_memory;     /* set when an estimate could not allocate */
} pm_method;

static il_vec3 estimate(const pm_method *m, const il_pm_map *map, const il_pm_vertex *v,
                        il_pm_scratch *scratch)
{
    il_vec3 L = v3(0.0f, 0.0f, 0.0f);
    if (map->count == 0)
        return L;
    if (il_pm_estimate(map, &m->lookup, &v->bsdf, v->s.p, v->n, v->wo, scratch, &L, NULL) != IL_OK)
        atomic_store(m->out_of_memory, 1);
    return L;
}

/* The global map: from the precomputed irradiance at a Lambertian surface
 * when it was built (pm_irradiance.c), a full estimate otherwise. */
static il_vec3 estimate_global(const pm_method *m, const il_pm_vertex *v, il_pm_scratch *scratch)
{
    il_vec3 L = v3(0.0f, 0.0f, 0.0f);
    if (m->global->count == 0)
        return L;
    if (il_pm_estimate_global(m->global, &m->lookup, &v->bsdf, v->s.p, v->n, v->wo, scratch, &L,
                              NULL) != IL_OK)
        atomic_store(m->out_of_memory, 1);
    return L;
}

/* Light reflected at a gather hit towards the previous vertex: direct,
 * global and caustic, no emission (that is direct light at x). */
static il_vec3 gather_hit(const pm_method *m, const il_pm_vertex *v, il_sampler *smp,
                          il_pm_scratch *scratch, uint64_t *rays)
{
    float u_select = il_sampler_1d(smp);
    il_vec2 u = il_sampler_2d(smp);
    il_vec3 L = il_direct_light(m->scene, &v->s, &v->bsdf, v->wo, u_select, u, rays);
    L = v3_add(L, estimate_global(m, v, scratch));
    L = v3_add(L, estimate(m, m->caustic, v, scratch));
    return v3_mul(v->beta, L);
}

static il_vec3 indirect(const pm_method *m, const il_pm_vertex *x, il_sampler *smp,
                        il_pm_scratch *scratch, uint64_t *rays)
{
    if (m->final_gather == 0)
        return estimate_global(m, x, scratch);
    const il_tracer *tr = m->scene->tracer;
    il_vec3 sum = v3(0.0f, 0.0f, 0.0f);
    uint32_t budget = m->max_depth > x->depth + 1 ? m->max_depth - x->depth - 1 : 0;
    for (uint32_t j = 0; j < m->final_gather; j++) {
        float u_lobe = il_sampler_1d(smp);
        il_vec2 u = il_sampler_2d(smp);
        il_bsdf_sample bs;
        if (!il_bsdf_sample_dir(&x->bsdf, x->wo, u_lobe, u, &bs) || !il_sides_agree(&x->s, x->wo, bs.wi))
            continue;
        il_ray ray = {.org = il_offset_origin(tr, x->s.p, x->s.ng, bs.wi), .tmin = 0.0f,
                      .dir = bs.wi, .tmax = INFINITY};
        il_pm_vertex y;
        if (il_pm_trace_to_diffuse(m->scene, ray, smp, budget, NULL, &y, rays))
            sum = v3_add(sum, v3_mul(bs.weight, gather_hit(m, &y, smp, scratch, rays)));
    }
    return v3_scale(sum, 1.0f / (float)m->final_gather);
}

static il_vec3 camera_radiance(const pm_method *m, il_vec3 org, il_vec3 dir, il_sampler *smp,
                               il_pm_scratch *scratch, uint64_t *rays)
{
    il_vec3 L = v3(0.0f, 0.0f, 0.0f);
    il_pm_vertex x;
    il_ray ray = {.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    if (!il_pm_trace_to_diffuse(m->scene, ray, smp, m->max_depth - 1, &L, &x, rays))
        return L;
    float u_select = il_sampler_1d(smp);
    il_vec2 u = il_sampler_2d(smp);
    il_vec3 R = il_direct_light(m->scene, &x.s, &x.bsdf, x.wo, u_select, u, rays);
    R = v3_add(R, estimate(m, m->caustic, &x, scratch));
    R = v3_add(R, indirect(m, &x, smp, scratch, rays));
    return v3_add(L, v3_mul(x.beta, R));
}

static void pm_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    const pm_method *m = method;
    il_pm_scratch scratch = {0};
    for (uint32_t y = tile->y0; y < tile->y1; y++)
        for (uint32_t x = tile->x0; x < tile->x1; x++)
            for (uint32_t i = tile->first; i < tile->first + tile->count; i++) {
                il_sampler smp;
                il_vec3 dir = il_camera_sample(ctx, x, y, i, &smp);
                il_vec3 L = camera_radiance(m, ctx->cam.position, dir, &smp, &scratch, &tile->rays);
                il_camera_tile_add(ctx, tile, x, y, L);
            }
    il_pm_scratch_free(&scratch);
}

/* Traces the photons and builds both maps. */
static il_status build_maps(const il_scene *scene, const il_render_desc *desc,
                            const il_pm_settings *ps, il_pm_map *global, il_pm_map *caustic,
                            il_photon_stats *st, il_error *err)
{
    il_pm_photons ph = {0};
    double t0 = omp_get_wtime();
    /* Progress and a stop (il_photon_step_fn), for one process alone. */
    il_pm_watch watch = {.t0 = t0};
    if (desc->photon && !il_distrib_on(desc->distrib)) {
        watch.fn = desc->photon->on_step;
        watch.user = desc->photon->on_step_user;
    }
    if (ps->max_photon_depth > 0) {
        il_pm_trace_desc td = {.first = 0,
                               .count = ps->photons,
                               .seed = desc->seed,
                               .max_depth = ps->max_photon_depth,
                               .threads = desc->threads,
                               .split = true,
                               .at_portals = ps->portal_light,
                               .watch = &watch};
        il_status s = il_pm_trace_split(scene, &td, desc->distrib, &ph, err);
        if (s != IL_OK)
            return s;
    }
    il_pm_report_photons(desc->photon, ph.global, ph.num_global, 0);
    il_pm_report_photons(desc->photon, ph.caustic, ph.num_caustic, 1);
    double t1 = omp_get_wtime();
    /* Power per emitted photon: Jensen 2001, section 5.1 (the lights'
     * power over the number emitted, here those actually traced). */
    uint64_t emitted = ps->max_photon_depth > 0 ? ph.emitted : ps->photons;
    float scale = emitted > 0 ? 1.0f / (float)emitted : 0.0f;
    il_status s = il_pm_map_build_split(global, ph.global, ph.num_global, scale, ps->lookup.lookup,
                                        ps->lookup.radius, desc->distrib, err);
    if (s == IL_OK)
        s = il_pm_map_build_split(caustic, ph.caustic, ph.num_caustic, scale, ps->lookup.lookup,
                                  ps->lookup.radius, desc->distrib, err);
    else
        free(ph.caustic);
    /* Christensen 1999: irradiance at every 4th global photon, so that a
     * Lambertian hit reads the global map with one nearest-point search. */
    if (s == IL_OK && !(desc->photon && desc->photon->no_precomputed_irradiance) &&
        !watch.stopped)
        s = il_pm_irradiance_build_split(global, &ps->lookup, IL_PM_IRRADIANCE_STRIDE, desc->threads,
                                         desc->distrib, &watch, err);
    st->emitted = emitted;
    st->stopped = watch.stopped;
    st->stored_global = ph.num_global;
    st->stored_caustic = ph.num_caustic;
    st->photon_rays = ph.rays;
    st->passes = 1;
    st->seconds_trace = t1 - t0;
    st->seconds_build = omp_get_wtime() - t1;
    st->map_bytes = il_pm_map_bytes(global) + il_pm_map_bytes(caustic);
    st->bytes_per_photon = (uint32_t)sizeof(il_photon);
    return s;
}

il_status il_pm_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    uint32_t max_depth = desc->max_depth ? desc->max_depth : 8u;
    il_pm_settings ps;
    il_status s = il_pm_settings_resolve(scene, desc->photon, max_depth, false, &ps, err);
    if (s == IL_OK)
        s = il_distrib_check(desc->distrib, desc, "photon", err);
    if (s != IL_OK)
        return s;
    double t0 = omp_get_wtime();
    il_pm_map global = {0}, caustic = {0};
    s = build_maps(scene, desc, &ps, &global, &caustic, &stats->photon, err);
    if (s == IL_OK) {
        atomic_int oom = 0;
        pm_method m = {.scene = scene,
                       .global = &global,
                       .caustic = &caustic,
                       .lookup = ps.lookup,
                       .final_gather = ps.final_gather,
                       .max_depth = max_depth,
                       .out_of_memory = &oom};
        il_camera_pass_result r = {0};
        double t1 = omp_get_wtime();
        /* Split across processes: this process's tiles (camera_pass.c). */
        s = il_camera_pass_tiles(scene, film, desc, pm_tile, &m, 0, &r, err);
        stats->photon.seconds_render = omp_get_wtime() - t1;
        if (s == IL_OK && atomic_load(&oom))
            s = il_fail(err, IL_ERR_MEMORY, "photon: out of memory gathering photons");
        stats->spp = r.spp;
        stats->rays = r.rays + stats->photon.photon_rays;
        stats->nonfinite_samples = r.nonfinite_samples;
    }
    stats->seconds = omp_get_wtime() - t0;
    il_pm_map_free(&global);
    il_pm_map_free(&caustic);
    return s;
}
