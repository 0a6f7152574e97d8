/* Links (hr.h): facing test, form-factor estimate and visibility.
 *
 * Form factor (the estimate gathered with): the mean over the FF_GRID x
 * FF_GRID midpoints of one element's parameter square of the unoccluded
 * form factor from a differential area there to the other element's
 * polygon by Lambert's contour integral (Cohen & Wallace 1993, eq. 4.14;
 * hr_ff.c, the formula of methods/ff_analytic.c, the 4 points at once),
 * which clips the polygon to the point's front half-space; a point behind
 * the other's plane counts 0 (elements emit and receive on their front
 * only).  The integration runs over the
 * element that lies wholly in front of the other's plane, or else the
 * smaller one, and F_sr becomes F_rs by reciprocity (A_r F_rs = A_s F_sr).
 * Each point's value is exact and bounded by 1, so a point's form factors
 * to non-overlapping sources sum to at most 1.
 *
 * Refinement oracle (Hanrahan et al. 1991, section 4: the estimate's error
 * grows with the elements' size as seen from each other): err_ff =
 * max(F_rs, the largest point value, the point estimate from the other
 * element's centroid), all as F_rs.  They agree when the elements are small
 * compared with their distance; where they differ the link needs splitting.
 *
 * Visibility (Hanrahan et al. 1991, section 5; SPLASH-2's 16 rays): vis_rays
 * rays between jittered points on the two elements (stratified on an m x m
 * grid in il_hr_vis_strata's order, the source's strata in reverse order),
 * through the patch mesh's tracer: a ray is blocked when anything lies
 * between the lifted end points.  Pairs of points that do not face each
 * other (the elements straddle each other's plane) are not counted but
 * drawn again, up to VIS_ATTEMPTS n draws.  V = unblocked / counted.
 * Rays are cast when the refinement first meets the link (it knows then
 * whether the link is split), and fewer of them where they settle it
 * (with the default 16, whose first 4 are a 2 x 2 stratified set):
 *   - a link that the oracle splits as soon as any ray passes (F B / B_ref
 *     above bf_eps with V = 1) stops at the first 4 when one of them
 *     passed: its V is never gathered, only its children's;
 *   - a link whose parent link had every ray pass (HSA section 5 gives
 *     the children of a fully visible link full visibility without rays)
 *     casts 4 and takes V = 1 when all 4 pass, else casts the rest.
 *     Inheriting V = 1 outright made the closed test room 1.3% too bright
 *     (a shadow that the parent's 16 rays missed is lost for the whole
 *     subtree); re-checking with 4 fresh rays per level keeps every
 *     accuracy test where it was (docs/hierarchical-radiosity.md).
 * The refinement oracle does not use V itself but an upper bound of the
 * visibility the link's sub-links can have: 1 when any ray passed (a
 * partly hidden pair has fully visible parts: the shadow's edge must be
 * resolved as if nothing blocked), and when every ray was blocked the 95%
 * upper confidence bound 1 - 0.05^(1/n) (about 3/n, the "rule of three"):
 * n blocked rays do not prove a pair hidden, and a link that is never split
 * loses the light reaching the part the rays missed (a quarter of the
 * Cornell box's floor, in the blocks' shadow but for a corner, lost its
 * direct light that way).
 * Random numbers keyed by (seed, receiver id, source id). */
#include <math.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "methods/hr/hr.h"

#define RAY_BATCH 64
#define VIS_ATTEMPTS 4
#define VIS_CHECK 4 /* rays that check a link under a fully visible parent */
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

/* How many of the n rays nothing blocks. */
static uint32_t unblocked(const il_tracer *tr, const il_ray *rays, uint32_t n)
{
    bool blocked[RAY_BATCH];
    if (n == 0)
        return 0;
    il_trace_occluded_n(tr, rays, blocked, n);
    uint32_t open = 0;
    for (uint32_t k = 0; k < n; k++)
        open += !blocked[k];
    return open;
}

void il_hr_vis_strata(uint32_t n, uint32_t *m_out, bool *pow2_out, uint32_t *strata)
{
    uint32_t m = 1, log2m = 0;
    while (m * m < n)
        m++;
    if (m * m == n && (m & (m - 1)) == 0)
        while ((1u << log2m) < m)
            log2m++;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t cx = k % m, cy = k / m;
        if (log2m) {
            cx = cy = 0;
            for (uint32_t b = 0; b < log2m; b++) {
                cx |= ((k >> (2 * b)) & 1u) << (log2m - 1 - b);
                cy |= ((k >> (2 * b + 1)) & 1u) << (log2m - 1 - b);
            }
        }
        strata[k] = cx | cy << 16;
    }
    *m_out = m;
    *pow2_out = log2m > 0;
}

/* Casts the link's visibility rays and sets l->vis and l->vis_bound.
 * first > 0: after the first `first` counted rays, stop when all of them
 * passed (all_open) or when any passed (any_open). */
static void visibility(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                       const il_hr_elem *src, uint32_t first, bool all_open, bool any_open,
                       il_hr_link *l)
{
    const uint32_t n = s->set.vis_rays, *strata = s->vis_strata;
    const float inv_m = 1.0f / (float)s->vis_m;
    il_pcg32 rng = il_pcg32_seed(il_hash_combine(s->set.seed, r->id), src->id);
    const il_tracer *tr = s->mesh->tracer;
    il_ray rays[RAY_BATCH];
    uint32_t counted = 0, open = 0, nb = 0;
    /* Pairs that do not face each other are drawn again, up to
     * VIS_ATTEMPTS n draws in all, so that elements which straddle each
     * other's plane (a block's side and the floor it stands on) still get
     * n rays through the part that matters. */
    for (uint32_t a = 0; a < VIS_ATTEMPTS * n && counted < n; a++) {
        uint32_t k = a % n, s0 = strata[k], s1 = strata[n - 1 - k];
        float u0 = ((float)(s0 & 0xffffu) + il_pcg32_float(&rng)) * inv_m;
        float v0 = ((float)(s0 >> 16) + il_pcg32_float(&rng)) * inv_m;
        float u1 = ((float)(s1 & 0xffffu) + il_pcg32_float(&rng)) * inv_m;
        float v1 = ((float)(s1 >> 16) + il_pcg32_float(&rng)) * inv_m;
        il_vec3 p = il_hr_elem_point(r, u0, v0), q = il_hr_elem_point(src, u1, v1);
        il_vec3 d = v3_sub(q, p);
        if (!(v3_dot(d, r->normal) > 0.0f && v3_dot(d, src->normal) < 0.0f))
            continue;
        rays[nb++] = il_shadow_ray(tr, p, r->normal, q, src->normal);
        counted++;
        if (nb == RAY_BATCH || counted == first) {
            open += unblocked(tr, rays, nb);
            nb = 0;
        }
        if (counted == first && ((all_open && open == first) || (any_open && open > 0)))
            break;
    }
    open += unblocked(tr, rays, nb);
    pool->vis_rays += counted;
    l->vis = counted ? (float)open / (float)counted : 0.0f;
    /* No facing pair found: nothing is known, so the oracle assumes the
     * worst (bound 1) and the link gathers nothing until split. */
    l->vis_bound = counted == 0 || open > 0 ? 1.0f : 1.0f - powf(0.05f, 1.0f / (float)counted);
}

/* The mean and the largest of the unoccluded point form factors from the
 * FF_GRID x FF_GRID midpoints of a's parameter square (a bilinear map for
 * quads, the area-preserving square-to-triangle map for triangles) to the
 * polygon b; a point behind b's plane counts 0. */
static void ff_from_points(const il_hr_elem *a, const il_hr_elem *b, double *mean, double *max)
{
    const int g = FF_GRID;
    il_vec3 pts[FF_GRID * FF_GRID];
    double f[FF_GRID * FF_GRID];
    uint32_t np = 0;
    for (int k = 0; k < g * g; k++) {
        il_vec3 p = il_hr_elem_point(a, ((float)(k % g) + 0.5f) / g, ((float)(k / g) + 0.5f) / g);
        if (plane_dist(b, p) > 0.0f)
            pts[np++] = p;
    }
    il_hr_ff_points_polygon(pts, np, a->normal, b->corners, b->num_corners, f);
    double sum = 0.0, top = 0.0;
    for (uint32_t k = 0; k < np; k++) {
        sum += f[k];
        top = f[k] > top ? f[k] : top;
    }
    *mean = sum / (g * g);
    *max = top;
}

/* The point form factor from a's centroid to b (0 behind b's plane). */
static double ff_from_center(const il_hr_elem *a, const il_hr_elem *b)
{
    return plane_dist(b, a->center) > 0.0f
               ? il_hr_ff_point_polygon(a->center, a->normal, b->corners, b->num_corners)
               : 0.0;
}

/* Whether a lies wholly in front of b's plane (no point of a behind it). */
static bool in_front(const il_hr_solver *s, const il_hr_elem *a, const il_hr_elem *b)
{
    for (uint32_t k = 0; k < a->num_corners; k++)
        if (plane_dist(b, a->corners[k]) < -s->plane_eps)
            return false;
    return true;
}

/* Which element to integrate over: one that lies wholly in front of the
 * other's plane, so that no sample point falls behind it (the points of a
 * floor element that a block's side cuts may all lie behind the side while
 * a sliver of it faces the side: integrated over the floor element, the
 * link would get F = 0); if both or neither do, the smaller one, where
 * points sample the integrand most finely relative to the distance. */
static bool integrate_over_receiver(const il_hr_solver *s, const il_hr_elem *r, const il_hr_elem *src)
{
    bool r_front = in_front(s, r, src), s_front = in_front(s, src, r);
    if (r_front != s_front)
        return r_front;
    return r->area <= src->area;
}

void il_hr_link_visibility(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                           il_hr_link *l, bool parent_visible, bool split_if_visible)
{
    /* VIS_CHECK rays first when they can settle it (a 2 x 2 stratified
     * set, the grid allowing): under a fully visible parent link, all of
     * them passing gives V = 1; for a link that is split as soon as any
     * ray passes, one passing settles the split (its children cast their
     * own rays, and its V is never gathered). */
    bool staged = s->vis_pow2 && s->set.vis_rays > VIS_CHECK;
    bool all_open = staged && parent_visible, any_open = staged && split_if_visible;
    visibility(s, pool, r, l->src, all_open || any_open ? VIS_CHECK : 0u, all_open, any_open, l);
}

il_hr_link *il_hr_link_make(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                            il_hr_elem *src)
{
    il_hr_link *l = il_hr_pool_link(pool);
    if (!l)
        return NULL;
    il_hr_link_fill(s, r, src, l);
    pool->links_made++;
    return l;
}

void il_hr_link_fill(const il_hr_solver *s, const il_hr_elem *r, il_hr_elem *src, il_hr_link *l)
{
    /* Integrate over one element with the exact point form factor to the
     * other; turn F_sr into F_rs by reciprocity (A_r F_rs = A_s F_sr). */
    double mean, max, other, f_rs;
    if (integrate_over_receiver(s, r, src)) {
        ff_from_points(r, src, &mean, &max);
        f_rs = mean;
        other = ff_from_center(src, r) * (double)src->area / (double)r->area;
    } else {
        double to_r = (double)src->area / (double)r->area;
        ff_from_points(src, r, &mean, &max);
        f_rs = mean * to_r;
        max *= to_r;
        other = ff_from_center(r, src);
    }
    double bound = other > max ? other : max;
    l->src = src;
    l->ff = (float)f_rs;
    l->err_ff = (float)(bound > f_rs ? bound : f_rs);
    /* Visibility comes later (il_hr_link_visibility), when the refinement
     * knows whether the link is split; nothing to cast when F is 0. */
    l->vis = l->err_ff > 0.0f ? -1.0f : 0.0f;
    l->vis_bound = 0.0f;
    /* A link whose larger element is already at the smallest size is never
     * split: err_ff 0 lets the refinement skip it without reading src. */
    const il_hr_elem *big = r->area >= src->area ? r : src;
    if (!(big->area > s->area_min && big->level < IL_HR_MAX_LEVEL))
        l->err_ff = 0.0f;
    l->next = NULL;
}
