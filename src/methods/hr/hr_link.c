/* Links (hr.h): facing test, form-factor estimate and visibility.
 *
 * Form factor (the estimate gathered with): F_rs = the mean over the
 * FF_GRID x FF_GRID midpoints of the receiver's parameter square of the
 * unoccluded form factor from a differential area there to the
 * source polygon by Lambert's contour integral (Cohen & Wallace 1993,
 * eq. 4.14; methods/ff_analytic.c); a point behind the source's plane
 * sees its back and counts 0 (sources emit from their front only).  Each
 * point's value is exact and bounded by 1, and a point's form factors to
 * non-overlapping sources sum to at most 1, so gathering never creates
 * energy; averaging over the receiver keeps pairs that straddle each
 * other's plane (a block standing on a floor) from being lost when the
 * receiver's centroid happens to lie behind the source.
 *
 * Refinement oracle (Hanrahan et al. 1991, section 4: the estimate's error
 * grows with the elements' size as seen from each other): err_ff =
 * max(F_rs, the largest of the point values, F_sr A_s / A_r), the last
 * the point estimate from the source's centroid turned into F_rs by
 * reciprocity (A_r F_rs = A_s F_sr).  They agree when the elements are small
 * compared with their distance; where they differ the link needs splitting.
 *
 * Visibility (Hanrahan et al. 1991, section 5; SPLASH-2's 16 rays): vis_rays
 * rays between jittered points on the two elements (stratified on an m x m
 * grid, the source's strata in reverse order), through the patch mesh's
 * tracer: a ray is blocked when anything lies between the lifted end
 * points.  Pairs of points that do not face each other (the elements
 * straddle each other's plane) are not counted.  V = unblocked / counted.
 * Random numbers keyed by (seed, receiver id, source id). */
#include <math.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "methods/ff_analytic.h"
#include "methods/hr/hr.h"

#define RAY_BATCH 64
#define FF_GRID 2 /* form-factor points per receiver: FF_GRID^2 */

static float plane_dist(const il_hr_elem *e, il_vec3 p) { return v3_dot(e->normal, v3_sub(p, e->center)); }

bool il_hr_facing(const il_hr_solver *s, const il_hr_elem *a, const il_hr_elem *b)
{
    float ab = -INFINITY, ba = -INFINITY;
    for (uint32_t k = 0; k < b->num_corners; k++)
        ab = il_maxf(ab, plane_dist(a, b->corners[k]));
    for (uint32_t k = 0; k < a->num_corners; k++)
        ba = il_maxf(ba, plane_dist(b, a->corners[k]));
    return ab > s->plane_eps && ba > s->plane_eps;
}

/* The point at (u, v) of the unit square mapped onto the element. */
static il_vec3 elem_point(const il_hr_elem *e, float u, float v)
{
    const il_vec3 *c = e->corners;
    if (e->num_corners == 4)
        return v3_add(v3_add(v3_scale(c[0], (1 - u) * (1 - v)), v3_scale(c[1], u * (1 - v))),
                      v3_add(v3_scale(c[2], u * v), v3_scale(c[3], (1 - u) * v)));
    il_vec2 b = il_sample_triangle(v2(u, v));
    return v3_add(v3_add(v3_scale(c[0], 1.0f - b.x - b.y), v3_scale(c[1], b.x)),
                  v3_scale(c[2], b.y));
}

static float visibility(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                        const il_hr_elem *src)
{
    uint32_t n = s->set.vis_rays, m = 1;
    while (m * m < n)
        m++;
    il_pcg32 rng = il_pcg32_seed(il_hash_combine(s->set.seed, r->id), src->id);
    const il_tracer *tr = s->mesh->tracer;
    il_ray rays[RAY_BATCH];
    bool blocked[RAY_BATCH];
    uint32_t counted = 0, open = 0;
    for (uint32_t k0 = 0; k0 < n; k0 += RAY_BATCH) {
        uint32_t nb = 0;
        for (uint32_t k = k0; k < n && k < k0 + RAY_BATCH; k++) {
            uint32_t ks = n - 1 - k;
            float u0 = ((float)(k % m) + il_pcg32_float(&rng)) / (float)m;
            float v0 = ((float)(k / m) + il_pcg32_float(&rng)) / (float)m;
            float u1 = ((float)(ks % m) + il_pcg32_float(&rng)) / (float)m;
            float v1 = ((float)(ks / m) + il_pcg32_float(&rng)) / (float)m;
            il_vec3 p = elem_point(r, u0, v0), q = elem_point(src, u1, v1);
            il_vec3 d = v3_sub(q, p);
            if (!(v3_dot(d, r->normal) > 0.0f && v3_dot(d, src->normal) < 0.0f))
                continue;
            rays[nb++] = il_shadow_ray(tr, p, r->normal, q, src->normal);
        }
        if (nb == 0)
            continue;
        il_trace_occluded_n(tr, rays, blocked, nb);
        pool->vis_rays += nb;
        counted += nb;
        for (uint32_t k = 0; k < nb; k++)
            open += !blocked[k];
    }
    return counted ? (float)open / (float)counted : 0.0f;
}

il_hr_link *il_hr_link_make(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                            il_hr_elem *src)
{
    il_hr_link *l = il_hr_pool_link(pool);
    if (!l)
        return NULL;
    /* FF_GRID x FF_GRID midpoints of the receiver's parameter square (a
     * bilinear map for quads, the area-preserving square-to-triangle map
     * for triangles), equal weights. */
    double f_rs = 0.0, f_max = 0.0;
    for (int k = 0; k < FF_GRID * FF_GRID; k++) {
        il_vec3 p = elem_point(r, ((float)(k % FF_GRID) + 0.5f) / FF_GRID,
                               ((float)(k / FF_GRID) + 0.5f) / FF_GRID);
        double f = plane_dist(src, p) > 0.0f
                       ? il_ff_point_polygon(p, r->normal, src->corners, src->num_corners)
                       : 0.0;
        f_rs += f;
        f_max = f > f_max ? f : f_max;
    }
    f_rs /= FF_GRID * FF_GRID;
    double f_sr = plane_dist(r, src->center) > 0.0f
                      ? il_ff_point_polygon(src->center, src->normal, r->corners, r->num_corners)
                      : 0.0;
    double bound = f_sr * (double)src->area / (double)r->area;
    bound = bound > f_max ? bound : f_max;
    l->src = src;
    l->ff = (float)f_rs;
    l->err_ff = (float)(bound > f_rs ? bound : f_rs);
    l->vis = l->err_ff > 0.0f ? visibility(s, pool, r, src) : 0.0f;
    l->next = NULL;
    pool->links_made++;
    return l;
}
