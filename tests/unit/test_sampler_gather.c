/* il_sampler_2d_gather (many samplers at once, AVX2 lanes where the CPU has
 * them) gives every sampler the numbers il_sampler_2d_n gives it, bit for
 * bit, and leaves it where il_sampler_2d_n would; with Sobol and PCG
 * samplers mixed, lane counts that do not fill a group of eight, and
 * samplers at different dimensions. */
#include <string.h>

#include "check.h"
#include "core/sampler.h"

enum { N = 37, PAIRS = 3 };

int main(void)
{
    for (int round = 0; round < 3; round++) {
        il_sampler a[N], b[N];
        uint32_t idx[N];
        uint32_t n = 0;
        for (uint32_t k = 0; k < N; k++) {
            /* round 0: all Sobol; 1: every third PCG; 2: all PCG */
            il_sampler_type t = round == 0 ? IL_SAMPLER_SOBOL
                              : round == 2 ? IL_SAMPLER_PCG
                              : (k % 3 == 0 ? IL_SAMPLER_PCG : IL_SAMPLER_SOBOL);
            il_sampler_start(&a[k], t, 7, 1000 + 17 * k, k * 5 + (k > 20 ? 1u << 20 : 0));
            /* Different dimensions: k % 4 pairs already drawn. */
            for (uint32_t j = 0; j < k % 4; j++)
                il_sampler_2d(&a[k]);
            b[k] = a[k];
            /* Every sampler but the multiples of 5 takes part, in reverse order. */
            if (k % 5 != 0)
                idx[n++] = N - 1 - k;
        }
        il_vec2 got[N * PAIRS];
        memset(got, 0, sizeof got);
        il_sampler_2d_gather(a, idx, n, PAIRS, got);
        for (uint32_t m = 0; m < n; m++) {
            il_vec2 want[PAIRS];
            il_sampler_2d_n(&b[idx[m]], want, PAIRS);
            for (uint32_t j = 0; j < PAIRS; j++) {
                CHECK(memcmp(&got[m * PAIRS + j].x, &want[j].x, sizeof(float)) == 0);
                CHECK(memcmp(&got[m * PAIRS + j].y, &want[j].y, sizeof(float)) == 0);
                CHECK(got[m * PAIRS + j].x >= 0.0f && got[m * PAIRS + j].x < 1.0f);
            }
        }
        /* Afterwards each sampler continues exactly as the reference. */
        for (uint32_t k = 0; k < N; k++) {
            il_vec2 x = il_sampler_2d(&a[k]), y = il_sampler_2d(&b[k]);
            CHECK(x.x == y.x && x.y == y.y);
        }
    }
    /* Nothing to do is fine. */
    il_sampler_2d_gather(NULL, NULL, 0, 3, NULL);
    return check_report();
}
