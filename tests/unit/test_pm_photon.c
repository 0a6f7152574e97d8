/* The stored photon (src/methods/photon/pm_photon.c): its size, RGBE power
 * rounded to nearest (error bound over many decades, no bias, zero,
 * negative, NaN and huge inputs), octahedral directions (angular error
 * bounds for 8 and 7 bits, exact axes) and a bit-exact position. */
#include <float.h>
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "methods/photon/pm.h"

#define DEG(x) ((x) * 180.0 / 3.14159265358979323846)

static il_vec3 random_dir(il_pcg32 *r)
{
    for (;;) {
        il_vec3 v = v3(2.0f * il_pcg32_float(r) - 1.0f, 2.0f * il_pcg32_float(r) - 1.0f,
                       2.0f * il_pcg32_float(r) - 1.0f);
        float l2 = v3_length2(v);
        if (l2 > 1e-4f && l2 <= 1.0f)
            return v3_scale(v, 1.0f / sqrtf(l2));
    }
}

static double angle_between(il_vec3 a, il_vec3 b)
{
    double d = (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z;
    double la = sqrt((double)a.x * a.x + (double)a.y * a.y + (double)a.z * a.z);
    double lb = sqrt((double)b.x * b.x + (double)b.y * b.y + (double)b.z * b.z);
    double c = d / (la * lb);
    return acos(c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c));
}

static void test_rgbe(void)
{
    il_pcg32 r = il_pcg32_seed(1, 2);
    /* Round trip over 60 decades: the largest channel within half a step
     * of its mantissa 128..255, i.e. 2^-8 relative (2^-9 is out of reach
     * for an 8-bit mantissa whose leading bit is not implicit); the other
     * channels within half a step too: 2^-8 of the largest, or 1/255 when
     * the largest rounded up to the next exponent (255.5+ -> 256). */
    double worst_max = 0.0, worst_other = 0.0;
    for (int i = 0; i < 200000; i++) {
        double scale = pow(10.0, -30.0 + 60.0 * il_pcg32_float(&r));
        il_vec3 c = v3((float)(scale * il_pcg32_float(&r)), (float)(scale * il_pcg32_float(&r)),
                       (float)(scale * il_pcg32_float(&r)));
        float m = v3_max_comp(c);
        if (!(m > 0.0f))
            continue;
        il_vec3 d = il_rgbe_unpack(il_rgbe_pack(c));
        for (int k = 0; k < 3; k++) {
            double e = fabs((double)v3_get(d, k) - v3_get(c, k)) / m;
            if (v3_get(c, k) == m)
                worst_max = fmax(worst_max, e);
            else
                worst_other = fmax(worst_other, e);
        }
    }
    CHECK(worst_max <= 0x1p-8 * (1.0 + 1e-6));
    CHECK(worst_other <= 1.0 / 255.0);
    /* ... and the bound is tight enough to catch truncation, which errs by
     * up to a whole step (2^-7). */
    CHECK(worst_max > 0x1p-9);

    /* Round to nearest is unbiased: the mean signed error of many values,
     * in units of the step, is near zero (truncation would give -0.5). */
    double sum = 0.0;
    int n = 0;
    for (int i = 0; i < 100000; i++) {
        float v = 1.0f + il_pcg32_float(&r);                /* exponent 1: step 2^-7 */
        il_vec3 d = il_rgbe_unpack(il_rgbe_pack(v3(v, 0.5f * v, 0.25f)));
        sum += ((double)d.x - v) / 0x1p-7;
        sum += ((double)d.y - 0.5 * v) / 0x1p-7;
        n += 2;
    }
    CHECK_NEAR(sum / n, 0.0, 0.01);

    /* Exact values stay exact; zero, negatives and NaN give 0. */
    il_vec3 e = il_rgbe_unpack(il_rgbe_pack(v3(1.0f, 0.5f, 0.0f)));
    CHECK(e.x == 1.0f && e.y == 0.5f && e.z == 0.0f);
    e = il_rgbe_unpack(il_rgbe_pack(v3(255.0f, 3.0f, 128.0f)));
    CHECK(e.x == 255.0f && e.y == 3.0f && e.z == 128.0f);
    CHECK(il_rgbe_pack(v3s(0.0f)) == 0);
    CHECK(il_rgbe_pack(v3(-1.0f, -2.0f, -0.0f)) == 0);
    CHECK(il_rgbe_pack(v3(NAN, -1.0f, 0.0f)) == 0);
    e = il_rgbe_unpack(il_rgbe_pack(v3(-3.0f, 2.0f, NAN)));
    CHECK(e.x == 0.0f && e.y == 2.0f && e.z == 0.0f);
    il_vec3 z = il_rgbe_unpack(0);
    CHECK(z.x == 0.0f && z.y == 0.0f && z.z == 0.0f);
    /* Far below the smallest exponent: zero, not garbage. */
    CHECK(il_rgbe_pack(v3(1e-45f, 0.0f, 0.0f)) == 0);
    /* 255.6 rounds to 256, which needs the next exponent: 256 exactly. */
    e = il_rgbe_unpack(il_rgbe_pack(v3(255.6f, 1.0f, 0.0f)));
    CHECK(e.x == 256.0f && e.y == 2.0f);
    /* Huge values clamp to the largest finite value, keeping the hue. */
    e = il_rgbe_unpack(il_rgbe_pack(v3(FLT_MAX, 0.5f * FLT_MAX, 0.0f)));
    CHECK(isfinite(e.x) && e.x > 1e38f);
    CHECK_REL(e.y / e.x, 0.5, 0.01);
    e = il_rgbe_unpack(il_rgbe_pack(v3(INFINITY, 1.0f, 0.0f)));
    CHECK(isfinite(e.x) && e.x > 1e38f && e.y == 0.0f);
}

static void test_oct(void)
{
    il_pcg32 r = il_pcg32_seed(3, 4);
    double worst8 = 0.0, worst7 = 0.0, mean8 = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; i++) {
        il_vec3 d = random_dir(&r);
        il_vec3 d8 = il_oct_unpack(il_oct_pack(d, 8), 8);
        il_vec3 d7 = il_oct_unpack(il_oct_pack(d, 7), 7);
        CHECK_NEAR(v3_length(d8), 1.0, 1e-5);
        double a8 = angle_between(d, d8), a7 = angle_between(d, d7);
        worst8 = fmax(worst8, a8);
        worst7 = fmax(worst7, a7);
        mean8 += a8 / n;
    }
    /* 127 steps per half side of the square (1/127 apart).  Near the pole
     * a step turns the direction by ~1/127 rad = 0.45 deg; near the middle
     * of an octahedron face the projection stretches it by up to ~sqrt(3)
     * (and the folded lower half shears it); rounding each coordinate (not
     * searching for the nearest grid point) adds up to half a diagonal step.
     * Measured with this encoder over 200k directions: 0.938 and 1.908 deg
     * (mean 0.34). */
    printf("octahedral: worst 8-bit %.3f deg (mean %.3f), worst 7-bit %.3f deg\n", DEG(worst8),
           DEG(mean8), DEG(worst7));
    CHECK(DEG(worst8) < 1.0);
    CHECK(DEG(worst7) < 2.0);
    CHECK(DEG(mean8) < 0.36);
    CHECK(DEG(worst8) < DEG(worst7));
    /* The axes (every Cornell-box wall normal) are exact. */
    const il_vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int i = 0; i < 6; i++) {
        for (unsigned bits = 7; bits <= 8; bits++) {
            il_vec3 a = il_oct_unpack(il_oct_pack(axes[i], bits), bits);
            CHECK(a.x == axes[i].x && a.y == axes[i].y && a.z == axes[i].z);
        }
    }
    /* Codes fit their bits; a zero or NaN vector encodes something valid. */
    CHECK(il_oct_pack(v3(-0.3f, -0.9f, -0.3f), 7) < (1u << 14));
    il_vec3 zz = il_oct_unpack(il_oct_pack(v3s(0.0f), 8), 8);
    CHECK_NEAR(v3_length(zz), 1.0, 1e-5);
    zz = il_oct_unpack(il_oct_pack(v3(NAN, 0.0f, 1.0f), 7), 7);
    CHECK_NEAR(v3_length(zz), 1.0, 1e-5);
    /* Not normalised on input: the same code as the unit vector. */
    il_vec3 u = v3_normalize(v3(0.3f, -0.2f, 0.7f));
    CHECK(il_oct_pack(v3_scale(u, 7.0f), 8) == il_oct_pack(u, 8));
}

static void test_photon(void)
{
    CHECK(sizeof(il_photon) == 20);
    il_pcg32 r = il_pcg32_seed(5, 6);
    for (int i = 0; i < 10000; i++) {
        il_vec3 p = v3((il_pcg32_float(&r) - 0.5f) * 1e4f, il_pcg32_float(&r) * 1e-3f,
                       -il_pcg32_float(&r));
        il_vec3 power = v3(il_pcg32_float(&r), il_pcg32_float(&r), il_pcg32_float(&r));
        il_vec3 dir = random_dir(&r), nrm = random_dir(&r);
        il_photon ph = il_photon_pack(p, power, dir, nrm);
        il_vec3 q = il_photon_pos(&ph);
        CHECK(memcmp(&q.x, &p.x, sizeof(float)) == 0 && memcmp(&q.y, &p.y, sizeof(float)) == 0 &&
              memcmp(&q.z, &p.z, sizeof(float)) == 0);
        CHECK((ph.normal >> 14) == 0);
        il_vec3 n0 = il_photon_normal(&ph);
        CHECK(DEG(angle_between(n0, nrm)) < 2.0);
        CHECK(DEG(angle_between(il_photon_dir(&ph), dir)) < 1.0);
        il_vec3 pw = il_photon_power(&ph);
        CHECK_NEAR(pw.x, power.x, v3_max_comp(power) * 0x1p-8);
        /* The kd-tree's axis bits do not disturb the normal. */
        for (unsigned axis = 0; axis < 3; axis++) {
            il_photon t = ph;
            t.normal = (uint16_t)(t.normal | axis << 14);
            il_vec3 n1 = il_photon_normal(&t);
            CHECK(n1.x == n0.x && n1.y == n0.y && n1.z == n0.z);
        }
    }
}

int main(void)
{
    test_rgbe();
    test_oct();
    test_photon();
    return check_report();
}
