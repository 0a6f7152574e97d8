/* The sampling pass (Nilles 2017, sec. 3.3) and the method's entry point.
 *
 * A backward path tracer: mirrors and glass are followed; at a non-delta
 * hit x direct light is taken by a light sample and a shadow ray
 * (scene/direct.h, as the photon mapper does), then one direction wi is
 * drawn from the BSDF and, instead of tracing on, the Linespace is read:
 *
 *   L(x -> wo) = Le + L_direct + f(wo, wi) |cos| / pdf(wi) * L_ls(x, wi)
 *
 * where L_ls is the radiance (W m^-2 sr^-1) stored for the shaft and
 * direction of the line through x along -wi (ls_inject.c).  It holds the
 * light that scattered at least once, so nothing is counted twice: emitters
 * reached by the drawn direction are never added after a non-delta bounce.
 *
 * Variants: the lookup point jittered on a disk of radius `blur` about x in
 * the tangent plane (the thesis's blur); the in-shaft occlusion test (the
 * shaft's candidate triangles between x and the voxel's face: then x does
 * not see what the shaft holds); the fallback (an empty or occluded shaft
 * traces on, as the path tracer, instead of giving nothing).  Phong lobes
 * sharper than n2 always trace on, below n1 read the Linespace; between,
 * the Linespace is read with probability (n2 - e) / (n2 - n1), which blends
 * the two estimates linearly. */
#include <math.h>
#include <stdatomic.h>
#include <string.h>

#include <omp.h>

#include "core/error.h"
#include "core/sampling.h"
#include "methods/camera_pass.h"
#include "methods/linespace/ls.h"
#include "scene/bsdf.h"
#include "scene/direct.h"
#include "scene/lights.h"
#include "trace/trace.h"

typedef struct ls_counts {
    uint64_t lookups, hits, empty, occluded;
} ls_counts;

typedef struct ls_method {
    const il_scene *scene;
    const il_linespace *ls;
    il_ls_settings set;
    float blur_radius;             /* world units */
    _Atomic uint64_t lookups, hits, empty, occluded;
} ls_method;

/* How likely a hit reads the Linespace rather than tracing on. */
static float lookup_probability(const ls_method *m, const il_bsdf *b)
{
    if (b->type == IL_MATERIAL_DIFFUSE)
        return 1.0f;
    if (b->type != IL_MATERIAL_PHONG)
        return 0.0f;
    if (b->exponent <= m->set.n1)
        return 1.0f;
    if (b->exponent >= m->set.n2)
        return 0.0f;
    return (m->set.n2 - b->exponent) / (m->set.n2 - m->set.n1);
}

static il_vec3 radiance(const ls_method *m, il_vec3 org, il_vec3 dir, il_sampler *smp, uint64_t *rays,
                        ls_counts *cnt)
{
    const il_scene *s = m->scene;
    const il_tracer *tr = s->tracer;
    il_vec3 L = v3s(0.0f), beta = v3s(1.0f);
    bool specular = true;
    il_ray ray = {.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    for (uint32_t depth = 0;; depth++) {
        il_hit hit;
        (*rays)++;
        if (!il_trace_closest(tr, &ray, &hit)) {
            if (specular)
                L = v3_add(L, v3_mul(beta, il_environment_radiance(s, ray.dir)));
            break;
        }
        il_surface surf;
        il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
        il_vec3 wo = v3_neg(ray.dir);
        const il_material *mat = surf.material;
        if (specular && !v3_is_zero(mat->emission))
            L = v3_add(L, v3_mul(beta, il_emitted_radiance(mat, surf.ng, wo)));
        if (depth >= m->set.max_depth)
            break;
        il_bsdf b;
        il_bsdf_init(&b, s, &surf);
        /* Four pairs per vertex, always drawn in this order (a fifth for
         * the blur, when a lookup is made). */
        il_vec2 u[4];
        il_sampler_2d_n(smp, u, 4);
        il_bsdf_sample bs;
        if (il_bsdf_is_delta(&b)) {
            if (!il_bsdf_sample_dir(&b, wo, u[0].y, u[2], &bs) || !il_sides_agree(&surf, wo, bs.wi))
                break;
            beta = v3_mul(beta, bs.weight);
            specular = true;
        } else {
            L = v3_add(L, v3_mul(beta, il_direct_light(s, &surf, &b, wo, u[0].x, u[1], rays)));
            if (!il_bsdf_sample_dir(&b, wo, u[0].y, u[2], &bs) || !il_sides_agree(&surf, wo, bs.wi))
                break;
            il_vec3 next = v3_mul(beta, bs.weight);
            if (u[3].x < lookup_probability(m, &b)) {
                cnt->lookups++;
                il_ls_lookup_status r;
                il_vec3 Li = v3s(0.0f);
                if (m->blur_radius > 0.0f) {
                    bool occluded = m->set.occlusion_test &&
                                    il_ls_occluded(m->ls, s, surf.p, bs.wi, surf.mesh, surf.prim);
                    il_frame f = il_frame_from_normal(surf.ns);
                    il_vec2 d = il_sample_concentric_disk(il_sampler_2d(smp));
                    il_vec3 q = v3_fma(v3_fma(surf.p, f.s, m->blur_radius * d.x), f.t, m->blur_radius * d.y);
                    r = occluded ? IL_LS_OCCLUDED : il_ls_lookup(m->ls, q, bs.wi, &Li);
                } else {
                    r = il_ls_read(m->ls, s, surf.p, bs.wi, m->set.occlusion_test, surf.mesh, surf.prim, &Li);
                }
                if (r == IL_LS_FOUND) {
                    cnt->hits++;
                    L = v3_add(L, v3_mul(next, Li));
                    break;
                }
                if (r == IL_LS_OCCLUDED)
                    cnt->occluded++;
                else
                    cnt->empty++;
                if (!m->set.fallback)
                    break;
            }
            beta = next;
            specular = false;
        }
        if (v3_is_zero(beta) || !v3_is_finite(beta))
            break;
        ray = (il_ray){.org = il_offset_origin(tr, surf.p, surf.ng, bs.wi), .tmin = 0.0f, .dir = bs.wi,
                       .tmax = INFINITY};
        /* Russian roulette after the third vertex (pbrt-v4 13.4.4). */
        if (depth >= 3) {
            float q = il_minf(v3_max_comp(beta), 0.95f);
            if (!(u[3].y < q))
                break;
            beta = v3_scale(beta, 1.0f / q);
        }
    }
    return L;
}

static void ls_tile(const void *method, const il_camera_pass_ctx *ctx, il_camera_tile *tile)
{
    ls_method *m = (ls_method *)method;
    ls_counts cnt = {0};
    for (uint32_t y = tile->y0; y < tile->y1; y++)
        for (uint32_t x = tile->x0; x < tile->x1; x++)
            for (uint32_t i = tile->first; i < tile->first + tile->count; i++) {
                il_sampler smp;
                il_vec3 dir = il_camera_sample(ctx, x, y, i, &smp);
                il_vec3 L = radiance(m, ctx->cam.position, dir, &smp, &tile->rays, &cnt);
                il_camera_tile_add(ctx, tile, x, y, L);
            }
    atomic_fetch_add(&m->lookups, cnt.lookups);
    atomic_fetch_add(&m->hits, cnt.hits);
    atomic_fetch_add(&m->empty, cnt.empty);
    atomic_fetch_add(&m->occluded, cnt.occluded);
}

il_status il_ls_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    il_ls_settings set;
    il_status s = il_ls_settings_resolve(desc->linespace, desc->max_depth, &set, err);
    if (s != IL_OK)
        return s;
    il_linespace_stats *st = &stats->linespace;
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();

    double t0 = omp_get_wtime();
    il_linespace ls;
    s = il_ls_build(scene, &set, threads, &ls, err);
    if (s != IL_OK)
        return s;
    double t1 = omp_get_wtime();
    il_ls_inject_result ir;
    s = il_ls_inject(scene, &set, desc->seed, threads, &ls, &ir, err);
    double t2 = omp_get_wtime();
    st->grid[0] = ls.res[0];
    st->grid[1] = ls.res[1];
    st->grid[2] = ls.res[2];
    st->n = ls.n;
    st->voxels = ls.num_voxels;
    st->shafts = ls.num_stored;
    st->candidates = ls.num_cand;
    st->overflow_shafts = ls.num_overflow;
    st->memory_bytes = il_ls_memory(&ls);
    st->inject_rays = set.inject_rays;
    st->injected_segments = ir.deposits;
    st->seconds_build = t1 - t0;
    st->seconds_inject = t2 - t1;
    if (s != IL_OK) {
        il_ls_free(&ls);
        return s;
    }

    ls_method mm;
    memset(&mm, 0, sizeof mm);
    ls_method *m = &mm;
    m->scene = scene;
    m->ls = &ls;
    m->set = set;
    m->blur_radius = set.blur * il_minf(ls.vsize.x, il_minf(ls.vsize.y, ls.vsize.z));
    il_camera_pass_result r = {0};
    s = il_camera_pass_tiles(scene, film, desc, ls_tile, m, 0, &r, err);
    st->seconds_sample = omp_get_wtime() - t2;
    st->lookups = atomic_load(&m->lookups);
    st->lookup_hits = atomic_load(&m->hits);
    st->lookup_empty = atomic_load(&m->empty);
    st->lookup_occluded = atomic_load(&m->occluded);
    il_ls_free(&ls);
    if (s != IL_OK)
        return s;
    stats->spp = r.spp;
    stats->rays = r.rays + ir.rays;
    stats->seconds = omp_get_wtime() - t0;
    stats->nonfinite_samples = r.nonfinite_samples;
    return IL_OK;
}
