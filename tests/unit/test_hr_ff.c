/* Hierarchical radiosity's point-to-polygon form factor (hr_ff.c) against
 * the shared one (methods/ff_analytic.c, itself tested against Howell's
 * closed forms in test_rad_formfactor.c) and against closed forms: random
 * points, normals and triangles / quads, some cut by the point's tangent
 * plane, agree within 1e-6 relative plus 1e-8 absolute (the arctangent's
 * relative error, 2e-8, times the angles summed, which can cancel to a much
 * smaller F for a polygon seen edge-on); a polygon wholly
 * behind gives 0; Howell B-3 (a rectangle seen from below one corner). */
#include <math.h>

#include "check.h"
#include "core/rng.h"
#include "methods/ff_analytic.h"
#include "methods/hr/hr.h"

#define PI_D 3.14159265358979323846

/* Howell B-3: dA parallel to an a x b rectangle at distance c, on the normal
 * through one of its corners. */
static double ff_point_rect_corner(double a, double b, double c)
{
    double A = a / c, B = b / c;
    return (A / sqrt(1 + A * A) * atan(B / sqrt(1 + A * A)) +
            B / sqrt(1 + B * B) * atan(A / sqrt(1 + B * B))) / (2 * PI_D);
}

static il_vec3 rand_vec(il_pcg32 *r, float scale)
{
    return v3(scale * (2 * il_pcg32_float(r) - 1), scale * (2 * il_pcg32_float(r) - 1),
              scale * (2 * il_pcg32_float(r) - 1));
}

int main(void)
{
    il_pcg32 rng = il_pcg32_seed(17, 3);
    int clipped = 0, compared = 0;
    double worst = 0.0;
    for (int i = 0; i < 20000; i++) {
        il_vec3 p = rand_vec(&rng, 1.0f), n = v3_normalize(rand_vec(&rng, 1.0f));
        uint32_t count = 3 + (uint32_t)(i & 1);
        /* A planar polygon: a parallelogram (or its half) at a random place,
         * sometimes tiny and far (nearly parallel edges). */
        float size = (i % 7 == 0) ? 1e-3f : 0.5f;
        il_vec3 o = rand_vec(&rng, 2.0f), u = rand_vec(&rng, size), v = rand_vec(&rng, size);
        il_vec3 poly[4] = {o, v3_add(o, u), v3_add(v3_add(o, u), v), v3_add(o, v)};
        if (count == 3)
            poly[2] = v3_add(o, v);
        double ref = il_ff_point_polygon(p, n, poly, count);
        double got = il_hr_ff_point_polygon(p, n, poly, count);
        int behind = 0;
        for (uint32_t k = 0; k < count; k++)
            behind += v3_dot(n, v3_sub(poly[k], p)) < 0.0f;
        clipped += behind > 0 && behind < (int)count;
        double e = fabs(got - ref);
        worst = fmax(worst, e);
        CHECK(e <= 1e-6 * ref + 1e-8);
        compared++;
    }
    printf("%d polygons (%d clipped), worst difference %.2e\n", compared, clipped, worst);
    CHECK(clipped > 1000);

    /* Closed form and the trivial cases. */
    il_vec3 o = v3(0, 0, 0), up = v3(0, 1, 0);
    il_vec3 rect[4] = {v3(0, 1.5f, 0), v3(0, 1.5f, 3), v3(2, 1.5f, 3), v3(2, 1.5f, 0)};
    CHECK_REL(il_hr_ff_point_polygon(o, up, rect, 4), ff_point_rect_corner(2, 3, 1.5), 1e-6);
    il_vec3 below[4] = {v3(0, -1, 0), v3(1, -1, 0), v3(1, -1, 1), v3(0, -1, 1)};
    CHECK_NEAR(il_hr_ff_point_polygon(o, up, below, 4), 0.0, 0.0);
    CHECK_NEAR(il_hr_ff_point_polygon(o, up, rect, 2), 0.0, 0.0);
    /* A huge polygon just above: the whole hemisphere, F -> 1. */
    il_vec3 huge[4] = {v3(-1e4f, 1, -1e4f), v3(-1e4f, 1, 1e4f), v3(1e4f, 1, 1e4f), v3(1e4f, 1, -1e4f)};
    CHECK_NEAR(il_hr_ff_point_polygon(o, up, huge, 4), 1.0, 1e-3);
    return check_report();
}
