/* Linespace shaft indexing (methods/linespace/ls_shaft.c):
 * - for N = 1..4 the 15 N^4 shafts are enumerated once each: every pair of
 *   patches on different faces maps to a distinct index below 15 N^4, the
 *   inverse gives the pair back, and both directions share the index;
 * - random segments inside a box map to the shaft whose hull holds them:
 *   the line's entry point lies in the entry patch and its exit point in the
 *   exit patch (the hull of two patches holds every segment between them,
 *   so the whole chord, and the segment on it, is inside);
 * - the shaft measures add up to 2 pi V before scaling (quadrature within
 *   2%), and agree with a Monte Carlo count of random (point, direction)
 *   pairs falling into each shaft;
 * - the coarse level (N_c = N / its smallest prime factor): each shaft's
 *   coarse shaft joins the same two faces through the coarse patches that
 *   hold its own (corners inside them), every coarse shaft holds
 *   (N / N_c)^4 shafts, and its measure, integrated at N_c, is the sum of
 *   theirs integrated at N (on the same midpoints, 24 per face side, so
 *   equal but for rounding: a shaft counted in the wrong coarse one
 *   shows). */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "methods/linespace/ls.h"

static float rnd(il_pcg32 *r) { return il_pcg32_float(r); }

/* Whether q lies on face f of the box within patch p (tolerance tol). */
static bool in_patch(il_vec3 lo, il_vec3 size, uint32_t n, uint32_t f, uint32_t p, il_vec3 q, float tol)
{
    il_vec3 c[4];
    il_ls_patch_corners(lo, size, n, f, p, c);
    il_vec3 a = v3_min(c[0], c[3]), b = v3_max(c[0], c[3]);
    return q.x >= a.x - tol && q.x <= b.x + tol && q.y >= a.y - tol && q.y <= b.y + tol &&
           q.z >= a.z - tol && q.z <= b.z + tol;
}

int main(void)
{
    /* Enumeration. */
    for (uint32_t n = 1; n <= 4; n++) {
        uint32_t ns = il_ls_num_shafts(n), n2 = n * n;
        uint8_t *seen = calloc(ns, 1);
        uint32_t pairs = 0, bad = 0;
        for (uint32_t fa = 0; fa < 6; fa++)
            for (uint32_t fb = fa + 1; fb < 6; fb++)
                for (uint32_t pa = 0; pa < n2; pa++)
                    for (uint32_t pb = 0; pb < n2; pb++) {
                        uint32_t d0, d1;
                        uint32_t s = il_ls_shaft_index(n, fa, pa, fb, pb, &d0);
                        uint32_t t = il_ls_shaft_index(n, fb, pb, fa, pa, &d1);
                        pairs++;
                        if (s >= ns || s != t || d0 != 0 || d1 != 1) {
                            bad++;
                            continue;
                        }
                        seen[s]++;
                        uint32_t a, p, b, q;
                        il_ls_shaft_patches(n, s, &a, &p, &b, &q);
                        bad += !(a == fa && p == pa && b == fb && q == pb);
                    }
        uint32_t once = 0;
        for (uint32_t s = 0; s < ns; s++)
            once += seen[s] == 1;
        printf("N=%u: %u pairs, %u shafts, %u seen once\n", n, pairs, ns, once);
        CHECK(pairs == 15u * n2 * n2);
        CHECK(once == ns);
        CHECK(bad == 0);
        free(seen);
    }

    /* Random segments inside a non-cubic box. */
    il_pcg32 rng = il_pcg32_seed(7, 1);
    il_vec3 lo = v3(-1.0f, 2.0f, 0.5f), size = v3(0.7f, 1.1f, 0.9f);
    for (uint32_t n = 1; n <= 4; n++) {
        uint32_t bad = 0, count = 0;
        for (int i = 0; i < 20000; i++) {
            il_vec3 a = v3(lo.x + size.x * rnd(&rng), lo.y + size.y * rnd(&rng), lo.z + size.z * rnd(&rng));
            il_vec3 b = v3(lo.x + size.x * rnd(&rng), lo.y + size.y * rnd(&rng), lo.z + size.z * rnd(&rng));
            il_vec3 d = v3_normalize(v3_sub(b, a));
            uint32_t fi, pi, fo, po;
            float tin, tout;
            if (!il_ls_locate(lo, size, n, a, d, &fi, &pi, &fo, &po, &tin, &tout)) {
                bad++;
                continue;
            }
            count++;
            il_vec3 qi = v3_fma(a, d, tin), qo = v3_fma(a, d, tout);
            float tol = 1e-4f;
            /* The segment a..b lies on the chord qi..qo (tin <= 0, |b-a| <= tout). */
            bool ok = fi != fo && tin <= 1e-6f && v3_length(v3_sub(b, a)) <= tout + 1e-5f &&
                      in_patch(lo, size, n, fi, pi, qi, tol) && in_patch(lo, size, n, fo, po, qo, tol);
            /* Locating from b, or from the segment's midpoint, finds the same shaft. */
            uint32_t fi2, pi2, fo2, po2, d1, d2;
            il_vec3 mid = v3_scale(v3_add(a, b), 0.5f);
            il_ls_locate(lo, size, n, mid, d, &fi2, &pi2, &fo2, &po2, &tin, &tout);
            uint32_t s1 = il_ls_shaft_index(n, fi, pi, fo, po, &d1);
            uint32_t s2 = il_ls_shaft_index(n, fi2, pi2, fo2, po2, &d2);
            /* The reversed line: same shaft, other direction. */
            uint32_t fi3, pi3, fo3, po3, d3;
            il_ls_locate(lo, size, n, b, v3_neg(d), &fi3, &pi3, &fo3, &po3, &tin, &tout);
            uint32_t s3 = il_ls_shaft_index(n, fi3, pi3, fo3, po3, &d3);
            ok = ok && s1 == s2 && d1 == d2 && s3 == s1 && d3 != d1;
            bad += !ok;
        }
        printf("N=%u: %u random segments, %u outside their shaft\n", n, count, bad);
        CHECK(count > 19000);
        /* A chord through a patch corner may be rounded to its neighbour. */
        CHECK(bad <= count / 2000);
    }

    /* Shaft measures. */
    for (uint32_t n = 1; n <= 4; n++) {
        uint32_t ns = il_ls_num_shafts(n);
        float *m = malloc(ns * sizeof(float));
        uint32_t k = 24u / n;
        double raw = il_ls_shaft_measures(size, n, k, m);
        double v = (double)size.x * size.y * size.z, sum = 0.0;
        for (uint32_t s = 0; s < ns; s++)
            sum += m[s];
        printf("N=%u: quadrature sum %.5f, 2 pi V %.5f (%+.2f%%)\n", n, raw, 2.0 * IL_PI * v,
               100.0 * (raw / (2.0 * IL_PI * v) - 1.0));
        CHECK_REL(raw, 2.0 * IL_PI * v, 0.02);
        CHECK_REL(sum, 2.0 * IL_PI * v, 1e-4);
        if (n == 2) {
            /* Monte Carlo: uniform points in the box, uniform directions. */
            uint32_t *hits = calloc(ns, sizeof(uint32_t));
            const uint32_t samples = 4000000;
            for (uint32_t i = 0; i < samples; i++) {
                il_vec3 p = v3(lo.x + size.x * rnd(&rng), lo.y + size.y * rnd(&rng), lo.z + size.z * rnd(&rng));
                il_vec3 d = il_sample_uniform_sphere(v2(rnd(&rng), rnd(&rng)));
                uint32_t fi, pi, fo, po, dir;
                float a, b;
                if (il_ls_locate(lo, size, n, p, d, &fi, &pi, &fo, &po, &a, &b))
                    hits[il_ls_shaft_index(n, fi, pi, fo, po, &dir)]++;
            }
            /* Each direction of a shaft holds M of the V 4 pi measure. */
            uint32_t checked = 0, bad = 0;
            double worst = 0.0;
            for (uint32_t s = 0; s < ns; s++) {
                double mc = (double)hits[s] / samples * v * 4.0 * IL_PI / 2.0;
                if (hits[s] < 4000)
                    continue;   /* too few for a 5% check */
                checked++;
                double e = fabs(mc / m[s] - 1.0);
                worst = e > worst ? e : worst;
                bad += e > 0.06;
            }
            printf("N=2: %u shafts checked against Monte Carlo, worst %.2f%%\n", checked, 100.0 * worst);
            CHECK(checked > 100);
            CHECK(bad == 0);
            free(hits);
        }
        free(m);
    }

    /* The coarse level. */
    CHECK(il_ls_coarse_n(1) == 0 && il_ls_coarse_n(2) == 1 && il_ls_coarse_n(3) == 1 &&
          il_ls_coarse_n(4) == 2 && il_ls_coarse_n(6) == 3 && il_ls_coarse_n(8) == 4);
    const uint32_t fine_n[4] = {2, 4, 6, 8};
    for (int t = 0; t < 4; t++) {
        uint32_t n = fine_n[t], nc = il_ls_coarse_n(n), ns = il_ls_num_shafts(n), ncs = il_ls_num_shafts(nc);
        uint32_t k = n / nc, *children = calloc(ncs, sizeof(uint32_t)), bad = 0;
        float *m = malloc(ns * sizeof(float)), *mc = malloc(ncs * sizeof(float));
        double *sum = calloc(ncs, sizeof(double));
        il_ls_shaft_measures(size, n, 24u / n, m);
        il_ls_shaft_measures(size, nc, 24u / nc, mc);
        for (uint32_t sh = 0; sh < ns; sh++) {
            uint32_t c = il_ls_coarse_shaft(n, sh);
            if (c >= ncs) {
                bad++;
                continue;
            }
            children[c]++;
            sum[c] += m[sh];
            uint32_t fa, pa, fb, pb, ca, qa, cb, qb;
            il_ls_shaft_patches(n, sh, &fa, &pa, &fb, &pb);
            il_ls_shaft_patches(nc, c, &ca, &qa, &cb, &qb);
            il_vec3 corners[4];
            bool inside = ca == fa && cb == fb;
            il_ls_patch_corners(lo, size, n, fa, pa, corners);
            for (int q = 0; q < 4; q++)
                inside = inside && in_patch(lo, size, nc, ca, qa, corners[q], 1e-5f);
            il_ls_patch_corners(lo, size, n, fb, pb, corners);
            for (int q = 0; q < 4; q++)
                inside = inside && in_patch(lo, size, nc, cb, qb, corners[q], 1e-5f);
            bad += !inside;
        }
        uint32_t wrong_count = 0;
        double worst = 0.0;
        for (uint32_t c = 0; c < ncs; c++) {
            wrong_count += children[c] != k * k * k * k;
            double e = fabs(sum[c] / mc[c] - 1.0);
            worst = e > worst ? e : worst;
        }
        printf("N=%u -> %u: %u shafts outside their coarse shaft, %u coarse shafts with other than %u, "
               "measure sums within %.3f%%\n",
               n, nc, bad, wrong_count, k * k * k * k, 100.0 * worst);
        CHECK(bad == 0);
        CHECK(wrong_count == 0);
        CHECK(worst < 1e-4);
        free(children);
        free(m);
        free(mc);
        free(sum);
    }
    return check_report();
}
