/* The per-pixel sampler (Burley 2020 scrambled Sobol pairs, PCG fallback) and
 * the pixel filter's sample placement. */
#include <string.h>

#include "check.h"
#include "core/sampler.h"
#include "methods/camera_pass.h"

/* Each of the 2^k elementary intervals [a/2^j, (a+1)/2^j) x [b/2^(k-j), (b+1)/2^(k-j))
 * of every shape j = 0..k holds exactly one of the 2^k points. */
static bool is_02_net(const il_vec2 *p, uint32_t k)
{
    uint32_t n = 1u << k;
    uint8_t *cells = malloc(n);
    bool ok = true;
    for (uint32_t j = 0; j <= k && ok; j++) {
        memset(cells, 0, n);
        for (uint32_t i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(p[i].x * (float)(1u << j));
            uint32_t b = (uint32_t)(p[i].y * (float)(1u << (k - j)));
            uint32_t cell = (a << (k - j)) | b;
            if (a >= (1u << j) || b >= (1u << (k - j)) || cells[cell]++) {
                ok = false;
                break;
            }
        }
    }
    free(cells);
    return ok;
}

static bool in_unit(float x) { return x >= 0.0f && x < 1.0f; }

int main(void)
{
    enum { K = 10, N = 1 << K };
    il_vec2 *pts = malloc(sizeof(il_vec2) * N);

    /* The plain sequence: van der Corput and the second Sobol dimension. */
    CHECK(il_sobol02(0).x == 0.0f && il_sobol02(0).y == 0.0f);
    CHECK(il_sobol02(1).x == 0.5f && il_sobol02(1).y == 0.5f);
    CHECK(il_sobol02(2).x == 0.25f && il_sobol02(2).y == 0.75f);
    CHECK(il_sobol02(3).x == 0.75f && il_sobol02(3).y == 0.25f);
    for (uint32_t k = 1; k <= K; k++) {
        for (uint32_t i = 0; i < (1u << k); i++)
            pts[i] = il_sobol02(i);
        CHECK(is_02_net(pts, k));
    }
    /* Any aligned block of 2^k points is a (0,k,2)-net too (Sobol's property). */
    for (uint32_t i = 0; i < 256; i++)
        pts[i] = il_sobol02(768 + i);
    CHECK(is_02_net(pts, 8));

    /* Scrambled and shuffled: the first 2^k samples of a pixel still form a
     * (0,k,2)-net, in every dimension pair. */
    const uint64_t seeds[] = {0, 1, 0xdeadbeefull};
    for (int si = 0; si < 3; si++)
        for (uint64_t pixel = 0; pixel < 3; pixel++)
            for (uint32_t pair = 0; pair < 4; pair++)
                for (uint32_t k = 1; k <= K; k += 3) {
                    for (uint32_t i = 0; i < (1u << k); i++) {
                        il_sampler s;
                        il_sampler_start(&s, IL_SAMPLER_SOBOL, seeds[si], pixel * 7919u, i);
                        for (uint32_t d = 0; d < pair; d++)
                            (void)il_sampler_2d(&s);
                        pts[i] = il_sampler_2d(&s);
                    }
                    CHECK(is_02_net(pts, k));
                }
    /* 1D draws: one point in each of the 2^k intervals. */
    {
        uint8_t seen[N] = {0};
        int dup = 0;
        for (uint32_t i = 0; i < N; i++) {
            il_sampler s;
            il_sampler_start(&s, IL_SAMPLER_SOBOL, 42, 5, i);
            (void)il_sampler_2d(&s);
            float x = il_sampler_1d(&s);
            uint32_t c = (uint32_t)(x * N);
            dup += c >= N || seen[c]++;
        }
        CHECK(dup == 0);
    }

    /* The scrambling is not the identity: the scrambled first point differs
     * from (0,0) and differs between pixels and seeds. */
    {
        il_sampler a, b, c;
        il_sampler_start(&a, IL_SAMPLER_SOBOL, 1, 10, 0);
        il_sampler_start(&b, IL_SAMPLER_SOBOL, 1, 11, 0);
        il_sampler_start(&c, IL_SAMPLER_SOBOL, 2, 10, 0);
        il_vec2 pa = il_sampler_2d(&a), pb = il_sampler_2d(&b), pc = il_sampler_2d(&c);
        CHECK(pa.x != 0.0f || pa.y != 0.0f);
        CHECK(pa.x != pb.x && pa.x != pc.x);
        /* Different pairs of one sample differ too. */
        il_vec2 pa2 = il_sampler_2d(&a);
        CHECK(pa2.x != pa.x && pa2.y != pa.y);
    }

    /* Range, determinism and mean over pixels, both samplers. */
    for (int type = IL_SAMPLER_SOBOL; type <= IL_SAMPLER_PCG; type++) {
        double sum = 0.0, sum2 = 0.0;
        long count = 0;
        bool range_ok = true, same = true;
        for (uint64_t pixel = 0; pixel < 4096; pixel++) {
            il_sampler s, t;
            il_sampler_start(&s, (il_sampler_type)type, 99, pixel, (uint32_t)(pixel % 5));
            il_sampler_start(&t, (il_sampler_type)type, 99, pixel, (uint32_t)(pixel % 5));
            for (int d = 0; d < 6; d++) {
                il_vec2 u = il_sampler_2d(&s), v = il_sampler_2d(&t);
                float w = il_sampler_1d(&s), z = il_sampler_1d(&t);
                range_ok &= in_unit(u.x) && in_unit(u.y) && in_unit(w);
                same &= u.x == v.x && u.y == v.y && w == z;
                sum += u.x + u.y + w;
                sum2 += (double)u.x * u.x + (double)u.y * u.y + (double)w * w;
                count += 3;
            }
        }
        CHECK(range_ok);
        CHECK(same);
        /* Across pixels the values are independent uniforms: mean 1/2,
         * second moment 1/3 (standard errors about 0.0011 and 0.0012). */
        CHECK_NEAR(sum / count, 0.5, 0.006);
        CHECK_NEAR(sum2 / count, 1.0 / 3.0, 0.006);
        /* A different seed changes the stream. */
        il_sampler a, b;
        il_sampler_start(&a, (il_sampler_type)type, 1, 3, 4);
        il_sampler_start(&b, (il_sampler_type)type, 2, 3, 4);
        CHECK(il_sampler_1d(&a) != il_sampler_1d(&b));
    }

    /* The inverse error function. */
    for (float x = -2.5f; x <= 2.5f; x += 0.25f)
        CHECK_NEAR(il_erfinv(erff(x)), x, 2e-4);

    /* Filter importance sampling: box offsets are the sample itself; Gaussian
     * offsets lie within 1.5 px of the pixel centre with the truncated
     * Gaussian's moments: mean 0 and variance
     * sigma^2 (1 - 2 a phi(a) / (2 Phi(a) - 1)), a = r/sigma = 3, sigma = 0.5. */
    {
        il_vec2 o = il_filter_offset(IL_FILTER_BOX, v2(0.25f, 0.75f));
        CHECK(o.x == 0.25f && o.y == 0.75f);
        const double a = 3.0, phi = exp(-0.5 * a * a) / sqrt(2.0 * 3.14159265358979323846);
        const double var = 0.25 * (1.0 - 2.0 * a * phi / erf(a / sqrt(2.0)));
        double m = 0.0, v = 0.0, inner = 0.0;
        bool inside = true;
        const uint32_t n = 1u << 16;
        for (uint32_t i = 0; i < n; i++) {
            il_vec2 g = il_filter_offset(IL_FILTER_GAUSSIAN, il_sobol02(i));
            double dx = g.x - 0.5, dy = g.y - 0.5;
            inside &= fabs(dx) <= 1.5 && fabs(dy) <= 1.5;
            m += dx + dy;
            v += dx * dx + dy * dy;
            inner += fabs(dx) < 0.5;
        }
        CHECK(inside);
        CHECK_NEAR(m / (2.0 * n), 0.0, 1e-3);
        CHECK_REL(v / (2.0 * n), var, 0.005);
        /* P(|x| < sigma) of the truncated Gaussian: erf(1/sqrt 2) / erf(3/sqrt 2). */
        CHECK_NEAR(inner / n, erf(1.0 / sqrt(2.0)) / erf(3.0 / sqrt(2.0)), 0.002);
    }

    free(pts);
    return check_report();
}
