/* Vector maths of core/vec.h: products, normalisation, helpers, and the
 * orthonormal frame (Duff et al. 2017) for many normals, including the
 * troublesome (0,0,-1) and near-(0,0,+-1) ones; to/from local round trips. */
#include "check.h"
#include "core/rng.h"
#include "core/vec.h"

static void test_basic(void)
{
    il_vec3 a = v3(1.0f, 2.0f, 3.0f), b = v3(-4.0f, 5.0f, 0.5f);
    CHECK_NEAR(v3_dot(a, b), -4.0 + 10.0 + 1.5, 1e-6);
    il_vec3 c = v3_cross(a, b);
    CHECK_NEAR(c.x, 2.0 * 0.5 - 3.0 * 5.0, 1e-6);
    CHECK_NEAR(c.y, 3.0 * -4.0 - 1.0 * 0.5, 1e-6);
    CHECK_NEAR(c.z, 1.0 * 5.0 - 2.0 * -4.0, 1e-6);
    /* The cross product is orthogonal to both and anti-commutative. */
    CHECK_NEAR(v3_dot(c, a), 0.0, 1e-5);
    CHECK_NEAR(v3_dot(c, b), 0.0, 1e-5);
    il_vec3 c2 = v3_cross(b, a);
    CHECK(c2.x == -c.x && c2.y == -c.y && c2.z == -c.z);
    /* Right-handed: x cross y = z. */
    il_vec3 z = v3_cross(v3(1, 0, 0), v3(0, 1, 0));
    CHECK(z.x == 0.0f && z.y == 0.0f && z.z == 1.0f);

    CHECK_NEAR(v3_length(v3(3.0f, 4.0f, 12.0f)), 13.0, 1e-6);
    CHECK_NEAR(v3_length2(v3(3.0f, 4.0f, 12.0f)), 169.0, 1e-4);
    il_vec3 n = v3_normalize(v3(3.0f, 4.0f, 12.0f));
    CHECK_NEAR(n.x, 3.0 / 13.0, 1e-7);
    CHECK_NEAR(n.z, 12.0 / 13.0, 1e-7);
    CHECK_NEAR(v3_length(n), 1.0, 1e-6);
    /* Normalising zero gives zero, not NaN. */
    il_vec3 zero = v3_normalize(v3s(0.0f));
    CHECK(v3_is_zero(zero));
    /* Tiny and huge vectors normalise too. */
    CHECK_NEAR(v3_length(v3_normalize(v3(1e-18f, 2e-18f, 0.0f))), 1.0, 1e-5);
    CHECK_NEAR(v3_length(v3_normalize(v3(1e18f, -1e18f, 1e18f))), 1.0, 1e-5);

    il_vec3 s = v3_add(a, b), d = v3_sub(a, b), m = v3_mul(a, b);
    CHECK(s.x == -3.0f && s.y == 7.0f && s.z == 3.5f);
    CHECK(d.x == 5.0f && d.y == -3.0f && d.z == 2.5f);
    CHECK(m.x == -4.0f && m.y == 10.0f && m.z == 1.5f);
    il_vec3 f = v3_fma(a, b, 2.0f);
    CHECK(f.x == -7.0f && f.y == 12.0f && f.z == 4.0f);
    il_vec3 ng = v3_neg(a);
    CHECK(ng.x == -1.0f && ng.y == -2.0f && ng.z == -3.0f);
    il_vec3 lo = v3_min(a, b), hi = v3_max(a, b);
    CHECK(lo.x == -4.0f && lo.y == 2.0f && lo.z == 0.5f);
    CHECK(hi.x == 1.0f && hi.y == 5.0f && hi.z == 3.0f);
    CHECK(v3_max_comp(b) == 5.0f);
    CHECK_NEAR(v3_avg(a), 2.0, 1e-6);
    CHECK(v3_get(a, 0) == 1.0f && v3_get(a, 1) == 2.0f && v3_get(a, 2) == 3.0f);
    CHECK(v3_is_finite(a));
    CHECK(!v3_is_finite(v3(1.0f, NAN, 0.0f)));
    CHECK(!v3_is_finite(v3(INFINITY, 0.0f, 0.0f)));
    /* Rec.709 luminance of white is 1, the weights sum to 1. */
    CHECK_NEAR(il_luminance(v3s(1.0f)), 1.0, 1e-6);
    CHECK_NEAR(il_luminance(v3(0.0f, 1.0f, 0.0f)), 0.7152, 1e-6);
    CHECK(il_clampf(2.0f, 0.0f, 1.0f) == 1.0f && il_clampf(-1.0f, 0.0f, 1.0f) == 0.0f);
    CHECK(il_clampf(0.25f, 0.0f, 1.0f) == 0.25f);
    CHECK_NEAR(il_lerpf(2.0f, 4.0f, 0.25f), 2.5, 1e-7);
    CHECK_NEAR(IL_PI * IL_INV_PI, 1.0, 1e-7);
    CHECK_NEAR(2.0f * IL_PI * IL_INV_2PI, 1.0, 1e-7);
    CHECK_NEAR(4.0f * IL_PI * IL_INV_4PI, 1.0, 1e-7);
}

/* Orthonormal, right-handed (s x t = n), n unchanged; the worst deviation over
 * the frame's dot products goes to *err. */
static bool frame_ok(il_vec3 n, double *err)
{
    il_frame f = il_frame_from_normal(n);
    double e = 0.0;
    e = fmax(e, fabs(v3_length(f.s) - 1.0));
    e = fmax(e, fabs(v3_length(f.t) - 1.0));
    e = fmax(e, fabs(v3_dot(f.s, f.t)));
    e = fmax(e, fabs(v3_dot(f.s, f.n)));
    e = fmax(e, fabs(v3_dot(f.t, f.n)));
    il_vec3 c = v3_cross(f.s, f.t);
    e = fmax(e, v3_length(v3_sub(c, n)));
    bool same = f.n.x == n.x && f.n.y == n.y && f.n.z == n.z;
    *err = e;
    return same && v3_is_finite(f.s) && v3_is_finite(f.t) && e < 1e-5;
}

static void test_frames(void)
{
    double err;
    const il_vec3 special[] = {
        {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
        {1e-7f, 0, -1}, {0, 1e-7f, -1}, {-1e-7f, -1e-7f, -1}, {1e-7f, 1e-7f, 1},
        {1, 0, -0.0f}, {0.6f, -0.8f, -0.0f},   /* z = -0: sign -1, a = -1/(-1 - 0) */
    };
    for (size_t i = 0; i < sizeof special / sizeof special[0]; i++) {
        il_vec3 n = v3_normalize(special[i]);
        if (v3_is_zero(n))
            continue;
        bool ok = frame_ok(n, &err);
        if (!ok)
            fprintf(stderr, "frame for (%g, %g, %g): error %g\n", n.x, n.y, n.z, err);
        CHECK(ok);
    }
    /* The pole opposite +z, where the naive formula divides by zero. */
    il_frame fz = il_frame_from_normal(v3(0.0f, 0.0f, -1.0f));
    CHECK(v3_is_finite(fz.s) && v3_is_finite(fz.t));

    il_pcg32 rng = il_pcg32_seed(2024, 1);
    int bad = 0;
    double worst = 0.0, worst_rt = 0.0;
    for (int i = 0; i < 100000; i++) {
        /* Uniform directions, plus a share hugging the poles. */
        float z = 1.0f - 2.0f * il_pcg32_float(&rng);
        if (i % 4 == 0)
            z = copysignf(1.0f - 1e-6f * il_pcg32_float(&rng), z);
        float r = sqrtf(fmaxf(0.0f, 1.0f - z * z)), phi = 2.0f * IL_PI * il_pcg32_float(&rng);
        il_vec3 n = v3_normalize(v3(r * cosf(phi), r * sinf(phi), z));
        if (!frame_ok(n, &err))
            bad++;
        worst = fmax(worst, err);
        /* World -> local -> world round trip, and n maps to +z. */
        il_frame f = il_frame_from_normal(n);
        il_vec3 v = v3(il_pcg32_float(&rng) - 0.5f, il_pcg32_float(&rng) - 0.5f, il_pcg32_float(&rng) - 0.5f);
        il_vec3 l = il_frame_to_local(&f, v);
        il_vec3 back = il_frame_to_world(&f, l);
        worst_rt = fmax(worst_rt, v3_length(v3_sub(back, v)));
        /* The local frame preserves lengths and the normal component. */
        worst_rt = fmax(worst_rt, fabs(v3_length(l) - v3_length(v)));
        worst_rt = fmax(worst_rt, fabs(l.z - v3_dot(v, n)));
        il_vec3 nz = il_frame_to_local(&f, n);
        worst_rt = fmax(worst_rt, v3_length(v3_sub(nz, v3(0, 0, 1))));
    }
    if (bad)
        fprintf(stderr, "%d frames not orthonormal, worst error %g\n", bad, worst);
    CHECK(bad == 0);
    CHECK(worst < 1e-5);
    CHECK(worst_rt < 1e-5);

    /* An explicit example: the local axes are where the frame says. */
    il_frame f = il_frame_from_normal(v3_normalize(v3(1, 2, 2)));
    il_vec3 ex = il_frame_to_world(&f, v3(1, 0, 0));
    CHECK_NEAR(ex.x, f.s.x, 1e-7);
    CHECK_NEAR(ex.z, f.s.z, 1e-7);
    il_vec3 ez = il_frame_to_world(&f, v3(0, 0, 1));
    CHECK_NEAR(ez.x, 1.0 / 3.0, 1e-6);
    CHECK_NEAR(ez.y, 2.0 / 3.0, 1e-6);
}

int main(void)
{
    test_basic();
    test_frames();
    return check_report();
}
