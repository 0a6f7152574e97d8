/* (Moved from radiosity/rad_ff_analytic.c to be shared with hierarchical
 * radiosity.)  The unoccluded form factor from a differential area to a polygon by
 * Lambert's contour integral (Cohen & Wallace, "Radiosity and Realistic Image
 * Synthesis", 1993, eq. 4.14; Baum, Rushmeier & Winget, "Improving Radiosity
 * Solutions Through the Use of Analytically Determined Form-Factors",
 * SIGGRAPH 1989, eq. 6):
 *
 *     F = 1/(2 pi) sum_k  n . Gamma_k,
 *     Gamma_k = unit(R_k x R_k+1) * angle(R_k, R_k+1),  R_k = v_k - p.
 *
 * The formula needs the whole polygon above the tangent plane of p, so the
 * polygon is first clipped to n.(x - p) >= 0 (Sutherland-Hodgman), streamed
 * edge by edge so no buffer is needed.  Double precision throughout. */
#include <math.h>
#include <stdbool.h>

#include "methods/ff_analytic.h"

typedef struct { double x, y, z; } dvec3;

typedef struct contour {
    dvec3 n;
    dvec3 first, prev;
    bool has_first;
    double sum;
} contour;

static dvec3 dsub(il_vec3 a, il_vec3 p) { return (dvec3){(double)a.x - p.x, (double)a.y - p.y, (double)a.z - p.z}; }
static double ddot(dvec3 a, dvec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static dvec3 dcross(dvec3 a, dvec3 b)
{
    return (dvec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/* One edge's term n . unit(a x b) * angle(a, b); the angle by atan2, which
 * stays accurate for nearly parallel and nearly opposite vectors. */
static double edge_term(dvec3 n, dvec3 a, dvec3 b)
{
    dvec3 c = dcross(a, b);
    double s = sqrt(ddot(c, c));
    if (s <= 0.0)
        return 0.0;
    return ddot(n, c) / s * atan2(s, ddot(a, b));
}

static void emit(contour *c, dvec3 v)
{
    if (!c->has_first) {
        c->first = v;
        c->has_first = true;
    } else {
        c->sum += edge_term(c->n, c->prev, v);
    }
    c->prev = v;
}

static dvec3 lerp_plane(dvec3 a, dvec3 b, double da, double db)
{
    double t = da / (da - db);
    return (dvec3){a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t};
}

double il_ff_point_polygon(il_vec3 p, il_vec3 n, const il_vec3 *poly, uint32_t count)
{
    if (count < 3)
        return 0.0;
    contour c = {.n = {n.x, n.y, n.z}, .has_first = false, .sum = 0.0};
    double len = sqrt(ddot(c.n, c.n));
    if (len <= 0.0)
        return 0.0;
    c.n = (dvec3){c.n.x / len, c.n.y / len, c.n.z / len};
    /* Sutherland-Hodgman against the plane n.R >= 0, emitting output vertices
     * (relative to p) straight into the contour sum. */
    dvec3 a = dsub(poly[count - 1], p);
    double da = ddot(c.n, a);
    for (uint32_t k = 0; k < count; k++) {
        dvec3 b = dsub(poly[k], p);
        double db = ddot(c.n, b);
        if (da >= 0.0) {
            if (db >= 0.0)
                emit(&c, b);
            else
                emit(&c, lerp_plane(a, b, da, db));
        } else if (db >= 0.0) {
            emit(&c, lerp_plane(a, b, da, db));
            emit(&c, b);
        }
        a = b;
        da = db;
    }
    if (!c.has_first)
        return 0.0;
    c.sum += edge_term(c.n, c.prev, c.first);
    /* Counter-clockwise seen from the polygon's front, with the front facing
     * p, makes the sum negative; the magnitude is the form factor whichever
     * side faces p (the sign only encodes the orientation). */
    return fabs(c.sum) / (2.0 * 3.14159265358979323846);
}
