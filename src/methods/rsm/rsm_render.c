/* The rsm camera pass: the first non-specular surface x a camera ray
 * reaches (through mirrors and glass) takes
 *
 *   L(x) = Le (seen directly or through mirrors and glass; the environment
 *              for rays that escape)
 *        + direct light by next-event estimation, as the path tracer
 *        + one bounce of indirect light from the reflective shadow maps
 *
 * (Dachsbacher & Stamminger 2005; Nilles 2017, section on RSMs).  The
 * indirect term is a path light -> x_p -> x -> camera: two scattering events
 * after the delta bounces, so it needs max_depth >= bounces + 2, as the path
 * tracer's paths of that length. */
#include <math.h>
#include <omp.h>
#include <stdatomic.h>
#include <string.h>

#include "core/error.h"
#include "methods/camera_pass.h"
#include "methods/rsm/rsm.h"
#include "scene/direct.h"
#include "scene/lights.h"
#include "trace/trace.h"

typedef struct rsm_method {
    const il_scene *scene;
    const il_rsm *rsm;
    const il_rsm_pattern *pat;   /* NULL: every texel */
    bool shadow_test;
    uint32_t maps;               /* per shading point; 0: every map */
    uint32_t max_depth;
    _Atomic uint64_t gathered, shadow_rays;
} rsm_method;

/* The first non-delta surface along the ray, through at most max_bounces
 * mirror and glass bounces; adds emission and the environment met on the
 * way to *L.  On success fills s, b, wo, beta and the bounces taken. */
static bool trace_to_diffuse(const il_scene *scene, il_ray ray, il_sampler *smp, uint32_t max_bounces,
                             il_vec3 *L, il_surface *s, il_bsdf *b, il_vec3 *wo, il_vec3 *beta,
                             uint32_t *bounces, uint64_t *rays)
{
    const il_tracer *tr = scene->tracer;
    *beta = v3s(1.0f);
    for (uint32_t depth = 0;; depth++) {
        il_hit hit;
        (*rays)++;
        if (!il_trace_closest(tr, &ray, &hit)) {
            *L = v3_add(*L, v3_mul(*beta, il_background_radiance(scene, ray.dir)));
            return false;
        }
        il_scene_surface(scene, hit.mesh, hit.prim, hit.b1, hit.b2, s);
        *wo = v3_normalize(v3_neg(ray.dir));
        if (!v3_is_zero(s->material->emission))
            *L = v3_add(*L, v3_mul(*beta, il_emitted_radiance(s->material, s->ng, *wo)));
        il_bsdf_init(b, scene, s);
        if (!il_bsdf_is_delta(b)) {
            *bounces = depth;
            return true;
        }
        if (depth >= max_bounces)
            return false;
        float u_lobe = il_sampler_1d(smp);
        il_vec2 u = il_sampler_2d(smp);
        il_bsdf_sample bs;
        if (!il_bsdf_sample_dir(b, *wo, u_lobe, u, &bs) || !il_sides_agree(s, *wo, bs.wi))
            return false;
        *beta = v3_mul(*beta, bs.weight);
        if (v3_is_zero(*beta) || !v3_is_finite(*beta))
            return false;
        ray = (il_ray){.org = il_offset_origin(tr, s->p, s->ng, bs.wi), .tmin = 0.0f,
                       .dir = bs.wi, .tmax = INFINITY};
    }
}

static il_vec3 camera_radiance(const rsm_method *m, il_vec3 org, il_vec3 dir, il_sampler *smp,
                               uint64_t *rays, il_rsm_counts *counts)
{
    il_vec3 L = v3s(0.0f), wo, beta;
    il_surface s;
    il_bsdf b;
    uint32_t bounces = 0;
    il_ray ray = {.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    if (!trace_to_diffuse(m->scene, ray, smp, m->max_depth - 1, &L, &s, &b, &wo, &beta, &bounces,
                          rays))
        return L;
    float u_select = il_sampler_1d(smp);
    il_vec2 u = il_sampler_2d(smp);
    il_vec3 R = il_direct_light(m->scene, &s, &b, wo, u_select, u, rays);
    if (bounces + 2 <= m->max_depth && m->rsm->count > 0) {
        il_rsm_receiver r = {.p = s.p, .wo = wo, .bsdf = &b};
        bool flip = v3_dot(s.ng, wo) < 0.0f;
        r.g = flip ? v3_neg(s.ng) : s.ng;
        r.n = flip ? v3_neg(s.ns) : s.ns;
        r.diffuse = b.type == IL_MATERIAL_DIFFUSE;
        r.kd = v3_scale(b.diffuse, IL_INV_PI);
        R = v3_add(R, il_rsm_gather(m->scene, m->rsm, m->pat, &r, m->shadow_test, m->maps, smp,
                                    counts));
    }
    return v3_add(L, v3_mul(beta, R));
}

static void rsm_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    rsm_method *m = (rsm_method *)method;
    il_rsm_counts counts = {0};
    for (uint32_t y = tile->y0; y < tile->y1; y++)
        for (uint32_t x = tile->x0; x < tile->x1; x++)
            for (uint32_t i = tile->first; i < tile->first + tile->count; i++) {
                il_sampler smp;
                il_vec3 dir = il_camera_sample(ctx, x, y, i, &smp);
                il_vec3 L = camera_radiance(m, ctx->cam.position, dir, &smp, &tile->rays, &counts);
                il_camera_tile_add(ctx, tile, x, y, L);
            }
    tile->rays += counts.shadow_rays;
    atomic_fetch_add(&m->gathered, counts.gathered);
    atomic_fetch_add(&m->shadow_rays, counts.shadow_rays);
}

il_status il_rsm_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    il_rsm_settings rs;
    il_status st = il_rsm_settings_resolve(desc->rsm, desc, &rs, err);
    if (st != IL_OK)
        return st;
    double t0 = omp_get_wtime();
    il_rsm rsm;
    st = il_rsm_build(scene, rs.resolution, desc->threads, &rsm, err);
    if (st != IL_OK)
        return st;
    il_rsm_pattern pat = {0};
    if ((st = il_rsm_choice_init(&rsm, err)) != IL_OK ||
        (!rs.all_texels && (st = il_rsm_pattern_init(&pat, rs.samples, rs.radius, err)) != IL_OK)) {
        il_rsm_free(&rsm);
        return st;
    }
    double t1 = omp_get_wtime();
    rsm_method m = {.scene = scene,
                    .rsm = &rsm,
                    .pat = rs.all_texels ? NULL : &pat,
                    .shadow_test = rs.shadow_test,
                    .maps = rs.maps,
                    .max_depth = rs.max_depth};
    atomic_init(&m.gathered, 0);
    atomic_init(&m.shadow_rays, 0);
    il_camera_pass_result r = {0};
    st = il_camera_pass_tiles(scene, film, desc, rsm_tile, &m, 0, &r, err);
    double t2 = omp_get_wtime();
    il_rsm_stats *o = &stats->rsm;
    o->maps = rsm.count;
    o->maps_per_point = rs.maps && rs.maps < rsm.count ? rs.maps : rsm.count;
    o->resolution = rs.resolution;
    for (uint32_t k = 0; k < rsm.count; k++)
        o->texels += rsm.maps[k].texels;
    o->map_bytes = il_rsm_bytes(&rsm);
    o->gathered = atomic_load(&m.gathered);
    o->shadow_rays = atomic_load(&m.shadow_rays);
    o->seconds_build = t1 - t0;
    o->seconds_gather = t2 - t1;
    stats->spp = r.spp;
    stats->rays = r.rays + rsm.rays;
    stats->nonfinite_samples = r.nonfinite_samples;
    stats->seconds = t2 - t0;
    il_rsm_pattern_free(&pat);
    il_rsm_free(&rsm);
    return st;
}
