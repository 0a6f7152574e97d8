/* The point-to-polygon form factor of the links (hr.h), the same formula as
 * the shared methods/ff_analytic.c, made cheaper for the hundreds of
 * thousands of links a solve makes (5 evaluations each):
 *
 *     F = 1/(2 pi) |sum_k  n . unit(R_k x R_k+1) * angle(R_k, R_k+1)|,
 *     R_k = v_k - p
 *
 * (Lambert's contour integral: Cohen & Wallace, "Radiosity and Realistic
 * Image Synthesis", 1993, eq. 4.14; Baum, Rushmeier & Winget, SIGGRAPH
 * 1989, eq. 6), with the polygon first clipped to the front half-space
 * n . R >= 0 (Sutherland-Hodgman) as there.  Differences, none of which
 * changes F by more than about 1e-8 (tests/unit/test_hr_ff.c):
 *   - the angle atan2(|a x b|, a . b) by a polynomial instead of libm's
 *     atan2 (which took half of the solve's form-factor time): reduced to
 *     atan of a ratio in [0, 1] by the octant identities, then Abramowitz &
 *     Stegun's 4.4.49 (absolute error 2e-8), without branches;
 *   - the vertices relative to p are gathered into a small array first, so
 *     the common case (nothing clipped) is a plain loop;
 *   - il_hr_ff_points_polygon takes a link's 4 points at once, as the lanes
 *     of a vectorized loop, when no vertex needs clipping for any of them.
 * Double precision as in the shared version (nearly parallel edges of far
 * small elements need it). */
#include <math.h>

#include "methods/hr/hr.h"

#define PI_D 3.14159265358979323846

/* GCC vectorizes the lanes' selects (ff_lanes) only when it may assume that
 * floating point does not trap (no effect on the values: nothing traps). */
#if defined(__GNUC__) && !defined(__clang__)
#define IL_HR_NO_TRAPS __attribute__((optimize("no-trapping-math")))
#else
#define IL_HR_NO_TRAPS
#endif

/* atan(t) for t in [0, 1]: Abramowitz & Stegun 4.4.49 (Hastings 1955),
 * an odd polynomial of degree 17, |error| <= 2e-8. */
IL_HR_NO_TRAPS static inline double atan01(double t)
{
    /* Estrin's scheme (pairs, then powers z^2, z^4, z^8) rather than
     * Horner's: the same polynomial with a dependency chain of 4 steps
     * instead of 8, which is what bounds the link's form factors. */
    double z = t * t, z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
    double p01 = 1.0 - 0.3333314528 * z, p23 = 0.1999355085 - 0.1420889944 * z;
    double p45 = 0.1065626393 - 0.0752896400 * z, p67 = 0.0429096138 - 0.0161657367 * z;
    double p03 = p01 + p23 * z2, p47 = p45 + p67 * z2;
    double p = p03 + p47 * z4 + 0.0028662257 * z8;
    return t * p;
}

/* One edge's term n . unit(a x b) * angle(a, b) of the contour sum, the
 * angle atan2(s, c) in [0, pi] (s = |a x b|, c = a . b) from atan of
 * lo / hi in [0, 1] and the octant identities, written as selects (no
 * branch to mispredict, and the loops around it vectorize); one division
 * gives both lo / hi and 1 / s.  A zero-length edge gives 0. */
IL_HR_NO_TRAPS static inline double edge_term(double ax, double ay, double az, double bx,
                                              double by, double bz, double nx, double ny,
                                              double nz)
{
    double x = ay * bz - az * by;
    double y = az * bx - ax * bz;
    double z = ax * by - ay * bx;
    double s = sqrt(x * x + y * y + z * z);
    double c = ax * bx + ay * by + az * bz;
    double ac = c < 0.0 ? -c : c;
    double lo = s < ac ? s : ac, hi = s < ac ? ac : s;
    double den = s * hi;
    bool ok = den > 0.0;
    double inv = 1.0 / (ok ? den : 1.0);
    double r = atan01(lo * s * inv);
    r = s > ac ? 0.5 * PI_D - r : r;
    r = c < 0.0 ? PI_D - r : r;
    double term = (nx * x + ny * y + nz * z) * hi * inv * r;
    return ok ? term : 0.0;
}

/* The contour sum over the closed polygon c[0..m-1] (m <= 6), its edges as
 * the lanes of a vectorized loop (unused lanes: zero-length edges). */
IL_HR_NO_TRAPS static double contour_sum(const double *cx, const double *cy, const double *cz,
                                         uint32_t m, double nx, double ny, double nz)
{
    enum { EDGES = 6 };
    double ax[EDGES], ay[EDGES], az[EDGES], bx[EDGES], by[EDGES], bz[EDGES], t[EDGES];
    for (uint32_t k = 0; k < EDGES; k++) {
        uint32_t ia = k < m ? (k == 0 ? m - 1 : k - 1) : 0, ib = k < m ? k : 0;
        ax[k] = cx[ia], ay[k] = cy[ia], az[k] = cz[ia];
        bx[k] = cx[ib], by[k] = cy[ib], bz[k] = cz[ib];
    }
#pragma omp simd
    for (uint32_t k = 0; k < EDGES; k++)
        t[k] = edge_term(ax[k], ay[k], az[k], bx[k], by[k], bz[k], nx, ny, nz);
    return ((t[0] + t[1]) + (t[2] + t[3])) + (t[4] + t[5]);
}

double il_hr_ff_point_polygon(il_vec3 p, il_vec3 n, const il_vec3 *poly, uint32_t count)
{
    if (count < 3 || count > 4)
        return 0.0;
    double nx = n.x, ny = n.y, nz = n.z;
    double len = sqrt(nx * nx + ny * ny + nz * nz);
    if (len <= 0.0)
        return 0.0;
    nx /= len, ny /= len, nz /= len;
    double rx[4], ry[4], rz[4], d[4];
    uint32_t front = 0;
    for (uint32_t k = 0; k < count; k++) {
        rx[k] = (double)poly[k].x - p.x;
        ry[k] = (double)poly[k].y - p.y;
        rz[k] = (double)poly[k].z - p.z;
        d[k] = nx * rx[k] + ny * ry[k] + nz * rz[k];
        front += d[k] >= 0.0;
    }
    if (front == 0)
        return 0.0;
    /* The contour: the polygon itself, or (some vertex behind) clipped
     * Sutherland-Hodgman style; a triangle or quad gives at most 5. */
    double cx[6], cy[6], cz[6];
    uint32_t m = 0;
    if (front == count) {
        for (uint32_t k = 0; k < count; k++)
            cx[k] = rx[k], cy[k] = ry[k], cz[k] = rz[k];
        m = count;
    } else {
        for (uint32_t k = 0, a = count - 1; k < count; a = k++) {
            if ((d[a] >= 0.0) != (d[k] >= 0.0)) {
                double t = d[a] / (d[a] - d[k]);
                cx[m] = rx[a] + (rx[k] - rx[a]) * t;
                cy[m] = ry[a] + (ry[k] - ry[a]) * t;
                cz[m] = rz[a] + (rz[k] - rz[a]) * t;
                m++;
            }
            if (d[k] >= 0.0) {
                cx[m] = rx[k], cy[m] = ry[k], cz[m] = rz[k];
                m++;
            }
        }
    }
    return fabs(contour_sum(cx, cy, cz, m, nx, ny, nz)) / (2.0 * PI_D);
}

/* Up to 4 points on one plane (normal n) to the same polygon, the points
 * as the lanes of a loop the compiler vectorizes, edge by edge: valid when
 * no vertex of the polygon lies behind any point's tangent plane (nothing
 * to clip), which il_hr_ff_points_polygon checks.  Unused lanes repeat the
 * last point. */
enum { LANES = 4 };

IL_HR_NO_TRAPS static void ff_lanes(const il_vec3 *pts, uint32_t npts, double nx, double ny,
                                    double nz, const il_vec3 *poly, uint32_t count, double *out)
{
    double px[LANES], py[LANES], pz[LANES], sum[LANES] = {0.0, 0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < LANES; i++) {
        const il_vec3 *p = &pts[i < npts ? i : npts - 1];
        px[i] = p->x, py[i] = p->y, pz[i] = p->z;
    }
    for (uint32_t e = 0, a = count - 1; e < count; a = e++) {
        const double vax = poly[a].x, vay = poly[a].y, vaz = poly[a].z;
        const double vbx = poly[e].x, vby = poly[e].y, vbz = poly[e].z;
#pragma omp simd
        for (uint32_t i = 0; i < LANES; i++)
            sum[i] += edge_term(vax - px[i], vay - py[i], vaz - pz[i], vbx - px[i], vby - py[i],
                                vbz - pz[i], nx, ny, nz);
    }
    for (uint32_t i = 0; i < npts; i++)
        out[i] = fabs(sum[i]) / (2.0 * PI_D);
}

void il_hr_ff_points_polygon(const il_vec3 *pts, uint32_t npts, il_vec3 n, const il_vec3 *poly,
                             uint32_t count, double *out)
{
    double nx = n.x, ny = n.y, nz = n.z;
    double len = sqrt(nx * nx + ny * ny + nz * nz);
    bool clip = count < 3 || count > 4 || npts > LANES || !(len > 0.0);
    if (npts == 0)
        return;
    if (!clip) {
        nx /= len, ny /= len, nz /= len;
        for (uint32_t p = 0; p < npts && !clip; p++)
            for (uint32_t k = 0; k < count && !clip; k++)
                clip = nx * ((double)poly[k].x - pts[p].x) + ny * ((double)poly[k].y - pts[p].y) +
                           nz * ((double)poly[k].z - pts[p].z) < 0.0;
    }
    if (clip) {
        for (uint32_t p = 0; p < npts; p++)
            out[p] = il_hr_ff_point_polygon(pts[p], n, poly, count);
        return;
    }
    ff_lanes(pts, npts, nx, ny, nz, poly, count, out);
}
