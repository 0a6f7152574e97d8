/* Gathering one bounce of indirect light from the maps: every texel a small
 * Lambertian emitter (Dachsbacher & Stamminger 2005, eq. 1), all of them or
 * a sample by the polar pattern of their section 3.1 (Nilles 2017, eq.
 * 12-14), with the optional shadow test of Nilles 2017, eq. 11.  The
 * weights are derived in docs/rsm.md, "Gathering". */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "methods/rsm/rsm.h"
#include "trace/trace.h"

il_status il_rsm_pattern_init(il_rsm_pattern *pat, uint32_t count, float radius, il_error *err)
{
    pat->count = count;
    pat->radius = radius;
    pat->xi1 = il_malloc(count * sizeof *pat->xi1, err);
    pat->dir = il_malloc(count * sizeof *pat->dir, err);
    if (!pat->xi1 || !pat->dir) {
        il_rsm_pattern_free(pat);
        return IL_ERR_MEMORY;
    }
    for (uint32_t k = 0; k < count; k++) {
        il_vec2 xi = il_sobol02(k);
        pat->xi1[k] = xi.x;
        pat->dir[k] = v2(sinf(2.0f * IL_PI * xi.y), cosf(2.0f * IL_PI * xi.y));
    }
    return IL_OK;
}

void il_rsm_pattern_free(il_rsm_pattern *pat)
{
    free(pat->xi1);
    free(pat->dir);
    pat->xi1 = NULL;
    pat->dir = NULL;
    pat->count = 0;
}

il_vec2 il_rsm_project(const il_rsm_map *m, il_vec3 x)
{
    il_vec3 d = v3_sub(x, m->org);
    float a = v3_dot(d, m->u), b = v3_dot(d, m->v);
    float scale = 1.0f / m->half;
    if (!m->ortho) {
        /* Behind the light (or level with it): towards the edge in the
         * direction of (a, b), where the clamp below puts it. */
        float z = fmaxf(v3_dot(d, m->w), 1e-6f * v3_length(d) + 1e-30f);
        scale /= z;
    }
    float s = 0.5f * (a * scale + 1.0f), t = 0.5f * (b * scale + 1.0f);
    return v2(il_clampf(s, 0.0f, 1.0f), il_clampf(t, 0.0f, 1.0f));
}

il_vec3 il_rsm_texel_light(const il_scene *scene, const il_rsm_texel *t, const il_rsm_receiver *r,
                           bool shadow_test, il_rsm_counts *counts)
{
    il_vec3 d = v3_sub(t->p, r->p);
    float r2 = v3_dot(d, d);
    float cos_x = v3_dot(r->n, d), cos_p = -v3_dot(t->n, d);
    /* max(0, n . (x_p - x)) max(0, n_p . (x - x_p)), and x_p above the
     * receiver's geometric surface too (no light through it). */
    if (!(cos_x > 0.0f) || !(cos_p > 0.0f) || !(v3_dot(r->g, d) > 0.0f) || !(r2 > 0.0f))
        return v3s(0.0f);
    counts->gathered++;
    /* E_p = Phi_p / pi * cos_x cos_p / (r^2 + A_p / pi), the cosines of unit
     * vectors: here cos_x cos_p are of the unnormalised d, so over r^2. */
    float e = cos_x * cos_p / (r2 * (IL_PI * r2 + t->area));
    il_vec3 f;
    if (r->diffuse) {
        f = r->kd;
    } else {
        il_vec3 wi = v3_scale(d, 1.0f / sqrtf(r2));
        f = il_bsdf_eval(r->bsdf, r->wo, wi, NULL);
        if (v3_is_zero(f))
            return v3s(0.0f);
    }
    if (shadow_test) {
        /* Nilles 2017, eq. 11: the pixel light counts only when nothing
         * lies between x and x_p. */
        const il_tracer *tr = scene->tracer;
        il_ray ray = il_shadow_ray(tr, r->p, r->g, t->p, t->n);
        counts->shadow_rays++;
        e *= il_trace_visibility(tr, &ray);
        if (e == 0.0f)
            return v3s(0.0f);
    }
    return v3_scale(v3_mul(f, t->flux), e);
}

/* The sum over every texel of map m. */
static il_vec3 gather_all(const il_scene *scene, const il_rsm_map *m, const il_rsm_receiver *r,
                          bool shadow_test, il_rsm_counts *counts)
{
    il_vec3 sum = v3s(0.0f);
    size_t n = (size_t)m->size * m->size;
    for (size_t k = 0; k < n; k++) {
        const il_rsm_texel *t = &m->tex[k];
        if (!v3_is_zero(t->flux))
            sum = v3_add(sum, il_rsm_texel_light(scene, t, r, shadow_test, counts));
    }
    return sum;
}

/* The pattern's estimate of the sum over the texels of map m within r_max
 * of the projection c: sample k at c + r_max xi1 (sin 2 pi xi2,
 * cos 2 pi xi2) (Dachsbacher & Stamminger, section 3.1), xi shifted modulo 1
 * by `shift`.  Its density in the (s, t) square is 1 / (2 pi r_max^2 xi1)
 * (polar coordinates, r = r_max xi1 uniform: dA = r dr dphi), a texel covers
 * 1 / size^2 of it, so the sum is estimated by
 *     1/N sum_k g(texel_k) 2 pi r_max^2 xi1_k size^2,
 * the weight growing linearly with xi1 (the paper's xi1^2 over-weights the
 * outer samples, docs/rsm.md). */
static il_vec3 gather_pattern(const il_scene *scene, const il_rsm_map *m, const il_rsm_pattern *pat,
                              const il_rsm_receiver *r, bool shadow_test, il_vec2 shift,
                              il_rsm_counts *counts)
{
    il_vec2 c = il_rsm_project(m, r->p);
    float phi = 2.0f * IL_PI * shift.y, cs = cosf(phi), sn = sinf(phi);
    float size = (float)m->size, rmax = pat->radius;
    float wscale = 2.0f * IL_PI * rmax * rmax * size * size / (float)pat->count;
    il_vec3 sum = v3s(0.0f);
    for (uint32_t k = 0; k < pat->count; k++) {
        float xi1 = pat->xi1[k] + shift.x;
        if (xi1 >= 1.0f)
            xi1 -= 1.0f;
        /* (sin, cos) of 2 pi (xi2 + shift.y). */
        il_vec2 d = pat->dir[k];
        float ds = d.x * cs + d.y * sn, dc = d.y * cs - d.x * sn;
        float s = c.x + rmax * xi1 * ds, t = c.y + rmax * xi1 * dc;
        if (!(s >= 0.0f && s < 1.0f && t >= 0.0f && t < 1.0f))
            continue;
        uint32_t i = (uint32_t)(s * size), j = (uint32_t)(t * size);
        if (i >= m->size)
            i = m->size - 1;
        if (j >= m->size)
            j = m->size - 1;
        const il_rsm_texel *tx = &m->tex[(size_t)j * m->size + i];
        if (v3_is_zero(tx->flux))
            continue;
        il_vec3 g = il_rsm_texel_light(scene, tx, r, shadow_test, counts);
        sum = v3_fma(sum, g, xi1);
    }
    return v3_scale(sum, wscale);
}

/* Map m's term: every texel, or the pattern's estimate. */
static il_vec3 gather_map(const il_scene *scene, const il_rsm_map *m, const il_rsm_pattern *pat,
                          const il_rsm_receiver *r, bool shadow_test, il_sampler *smp,
                          il_rsm_counts *counts)
{
    if (!pat)
        return gather_all(scene, m, r, shadow_test, counts);
    il_vec2 shift = il_sampler_2d(smp);
    return gather_pattern(scene, m, pat, r, shadow_test, shift, counts);
}

il_vec3 il_rsm_gather(const il_scene *scene, const il_rsm *rsm, const il_rsm_pattern *pat,
                      const il_rsm_receiver *r, bool shadow_test, uint32_t maps,
                      il_sampler *smp, il_rsm_counts *counts)
{
    il_vec3 L = v3s(0.0f);
    if (maps == 0 || maps >= rsm->count || rsm->choice.n != rsm->count) {
        for (uint32_t k = 0; k < rsm->count; k++)
            L = v3_add(L, gather_map(scene, &rsm->maps[k], pat, r, shadow_test, smp, counts));
        return L;
    }
    /* Sum_m G_m estimated by 1/K sum_k G_{m_k} / pick[m_k] (importance
     * sampling over the maps, Veach 1997 section 2.5.2). */
    for (uint32_t k = 0; k < maps; k++) {
        float pmf;
        uint32_t m = il_distrib1d_sample_discrete(&rsm->choice, il_sampler_1d(smp), &pmf, NULL);
        il_vec3 g = gather_map(scene, &rsm->maps[m], pat, r, shadow_test, smp, counts);
        L = v3_fma(L, g, 1.0f / ((float)maps * pmf));
    }
    return L;
}
