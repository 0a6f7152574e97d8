/* Environment portals: sampling a direction through them and its density
 * (see portal.h). */
#include "scene/portal.h"

#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "core/sampling.h"
#include "scene/scene.h"

/* p lies on the lit side of portal q: strictly, so a point on the portal's
 * own plane (the wall around a window) is not lit through it. */
static bool lights(const il_portal *q, il_vec3 p)
{
    return v3_dot(v3_sub(p, q->p0), q->n) > 0.0f;
}

/* The light travelling along dir enters by q (portal.h). */
static bool enters_by(const il_portal *q, il_vec3 dir)
{
    return v3_dot(dir, q->n) >= IL_PORTAL_MIN_COS;
}

/* How a portal triangle is drawn: by area among those lighting a point v,
 * by projected area among those a direction v enters by, or by area among
 * all; weight() is what q counts for (0: not drawn). */
typedef enum { BY_LIT_AREA, BY_PROJECTED_AREA, BY_AREA } pick_rule;

static float weight(const il_portal *q, pick_rule rule, il_vec3 v)
{
    switch (rule) {
    case BY_LIT_AREA: return lights(q, v) ? q->area : 0.0f;
    case BY_PROJECTED_AREA: return enters_by(q, v) ? q->area * v3_dot(v, q->n) : 0.0f;
    default: return q->area;
    }
}

static float total_weight(const il_scene *s, pick_rule rule, il_vec3 v)
{
    float total = 0.0f;
    for (uint32_t i = 0; i < s->num_portals; i++) {
        float w = weight(&s->portals[i], rule, v);
        if (w > 0.0f)
            total += w;
    }
    return total;
}

/* The triangle drawn by u.x among the weights (total: their sum), u.x then
 * rescaled to [0,1) within it, and a uniform point *at of it; NULL when no
 * triangle weighs anything. */
static const il_portal *pick(const il_scene *s, pick_rule rule, il_vec3 v, float total, il_vec2 u,
                             il_vec3 *at)
{
    float x = u.x * total, w = 0.0f;
    const il_portal *q = NULL;
    for (uint32_t i = 0; i < s->num_portals; i++) {
        const il_portal *c = &s->portals[i];
        float wc = weight(c, rule, v);
        if (!(wc > 0.0f))
            continue;
        q = c;
        w = wc;
        if (x < w)
            break;
        x -= w;
    }
    if (!q)
        return NULL;
    u.x = il_clampf(x / w, 0.0f, 0x1.fffffep-1f);
    il_vec2 b = il_sample_triangle(u);
    *at = v3_add(q->p0, v3_add(v3_scale(q->e1, b.x), v3_scale(q->e2, b.y)));
    return q;
}

float il_portal_area_seen(const il_scene *s, il_vec3 p)
{
    return total_weight(s, BY_LIT_AREA, p);
}

/* Möller & Trumbore 1997 (JGT 2(1)): whether the line through p along dir
 * crosses portal q, and where (*t along dir, either sign).  The edges are
 * inclusive. */
static bool line_crosses(const il_portal *q, il_vec3 p, il_vec3 dir, float *t)
{
    il_vec3 pv = v3_cross(dir, q->e2);
    float det = v3_dot(q->e1, pv);
    if (det == 0.0f || !isfinite(det))
        return false;
    float inv = 1.0f / det;
    il_vec3 sv = v3_sub(p, q->p0);
    float b1 = v3_dot(sv, pv) * inv;
    if (!(b1 >= 0.0f && b1 <= 1.0f))
        return false;
    il_vec3 qv = v3_cross(sv, q->e1);
    float b2 = v3_dot(dir, qv) * inv;
    if (!(b2 >= 0.0f && b1 + b2 <= 1.0f))
        return false;
    *t = v3_dot(q->e2, qv) * inv;
    return true;
}

/* The distance along the unit dir from p to portal q, or 0 when the ray
 * misses it. */
static float cross_at(const il_portal *q, il_vec3 p, il_vec3 dir)
{
    float t;
    return line_crosses(q, p, dir, &t) && t > 0.0f ? t : 0.0f;
}

/* A crossing nearly in the portal's plane counts for nothing: its density
 * d^2 / (A cos) grows without bound, and squared by the power heuristic it
 * overflowed to inf / inf (a NaN that spread through a hierarchical
 * radiosity solve from the elements beside a window).  il_portal_sample
 * drops a draw whose own crossing is such, so the draws kept are exactly
 * distributed as il_portal_pdf says and MIS stays unbiased; what is left
 * out has almost no projected area. */
#define IL_PORTAL_MAX_TERM 1e12f

/* Portal q's part of the density of direction dir from p (0: missed, or
 * left out as above). */
static float density_term(const il_portal *q, il_vec3 p, float seen, il_vec3 dir)
{
    float t = cross_at(q, p, dir);
    float cos_q = fabsf(v3_dot(dir, q->n));
    float term = t > 0.0f && cos_q >= IL_PORTAL_MIN_COS ? t * t / (seen * cos_q) : 0.0f;
    return term <= IL_PORTAL_MAX_TERM ? term : 0.0f;
}

bool il_portal_sample(const il_scene *s, il_vec3 p, float seen, il_vec2 u, il_vec3 *dir)
{
    il_vec3 at;
    const il_portal *q = pick(s, BY_LIT_AREA, p, seen, u, &at);
    if (!q)
        return false;
    il_vec3 d = v3_sub(at, p);
    float len = v3_length(d);
    if (!(len > 0.0f))
        return false;
    *dir = v3_scale(d, 1.0f / len);
    return density_term(q, p, seen, *dir) > 0.0f;
}

float il_portal_pdf(const il_scene *s, il_vec3 p, float seen, il_vec3 dir)
{
    if (!(seen > 0.0f))
        return 0.0f;
    float pdf = 0.0f;
    for (uint32_t i = 0; i < s->num_portals; i++)
        if (lights(&s->portals[i], p))
            pdf += density_term(&s->portals[i], p, seen, dir);
    return pdf;
}

float il_portal_projected_area(const il_scene *s, il_vec3 dir)
{
    return total_weight(s, BY_PROJECTED_AREA, dir);
}

bool il_portal_sample_point(const il_scene *s, il_vec3 dir, float projected, il_vec2 u, il_vec3 *x)
{
    return pick(s, BY_PROJECTED_AREA, dir, projected, u, x) != NULL;
}

uint32_t il_portal_lines_entering(const il_scene *s, il_vec3 p, il_vec3 dir)
{
    uint32_t k = 0;
    float t;
    for (uint32_t i = 0; i < s->num_portals; i++)
        if (enters_by(&s->portals[i], dir) && line_crosses(&s->portals[i], p, dir, &t))
            k++;
    return k;
}

float il_portal_total_area(const il_scene *s)
{
    return total_weight(s, BY_AREA, v3s(0.0f));
}

bool il_portal_point(const il_scene *s, float total, il_vec2 u, il_vec3 *x, il_vec3 *n)
{
    const il_portal *q = pick(s, BY_AREA, v3s(0.0f), total, u, x);
    if (q)
        *n = q->n;
    return q != NULL;
}

/* The first crossing of a portal triangle by org + t dir, t in (0, t_end),
 * towards its lit side (side > 0) or away from it (side < 0), that ends
 * more than `margin` beyond the triangle's plane. */
static bool first_crossing(const il_scene *s, il_vec3 org, il_vec3 dir, float t_end, float margin,
                           float side, float *t_cross)
{
    bool found = false;
    float first = INFINITY;
    for (uint32_t i = 0; i < s->num_portals; i++) {
        const il_portal *q = &s->portals[i];
        float c = side * v3_dot(dir, q->n), t;
        if (c > 0.0f && line_crosses(q, org, dir, &t) && t > 0.0f && t < t_end &&
            (t_end - t) * c > margin && t < first) {
            first = t;
            found = true;
        }
    }
    if (t_cross)
        *t_cross = first;
    return found;
}

bool il_portal_entered(const il_scene *s, il_vec3 org, il_vec3 dir, float t_end, float margin,
                       float *t_cross)
{
    return first_crossing(s, org, dir, t_end, margin, 1.0f, t_cross);
}

bool il_portal_exited(const il_scene *s, il_vec3 org, il_vec3 dir, float t_end, float margin,
                      float *t_cross)
{
    return first_crossing(s, org, dir, t_end, margin, -1.0f, t_cross);
}

il_status il_scene_add_portal(il_scene *s, const il_vec3 *corners, uint32_t num_triangles,
                              il_error *err)
{
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    if (num_triangles == 0 || !corners)
        return il_fail(err, IL_ERR_INVALID, "portal: no triangles");
    il_portal *grown = realloc(s->portals, sizeof *grown * ((size_t)s->num_portals + num_triangles));
    if (!grown)
        return il_fail(err, IL_ERR_MEMORY, "portal: out of memory");
    s->portals = grown;
    for (uint32_t t = 0; t < num_triangles; t++) {
        il_vec3 a = corners[3 * t], b = corners[3 * t + 1], c = corners[3 * t + 2];
        if (!v3_is_finite(a) || !v3_is_finite(b) || !v3_is_finite(c))
            return il_fail(err, IL_ERR_INVALID, "portal: triangle %u has a NaN or infinite corner", t);
        il_portal q = {.p0 = a, .e1 = v3_sub(b, a), .e2 = v3_sub(c, a)};
        il_vec3 n = v3_cross(q.e1, q.e2);
        float len = v3_length(n);
        /* A sliver (area below 1e-6 of its longest edge squared) has no
         * usable normal. */
        float edge2 = fmaxf(v3_length2(q.e1), fmaxf(v3_length2(q.e2), v3_length2(v3_sub(c, b))));
        if (!(len > 2e-6f * edge2) || !isfinite(len))
            return il_fail(err, IL_ERR_INVALID, "portal: triangle %u has no area", t);
        q.n = v3_scale(n, 1.0f / len);
        q.area = 0.5f * len;
        s->portals[s->num_portals + t] = q;
    }
    s->num_portals += num_triangles;
    return IL_OK;
}
