/* The device-safe Sobol sampler (src/kernel/kernel_sobol.h) against the
 * CPU's (core/sampler.c, IL_SAMPLER_SOBOL): the same numbers, bit for bit,
 * over seeds, pixels, sample indices (small, powers of two, large) and 64
 * dimensions of mixed 1D and 2D draws. */
#include <string.h>
#include "check.h"
#include "core/sampler.h"
#include "kernel/kernel_sobol.h"

int main(void)
{
    const uint64_t seeds[] = {0, 1, 9, 0xdeadbeefcafeULL};
    const uint64_t pixels[] = {0, 1, 511, 262143, 1ULL << 33};
    const uint32_t indices[] = {0, 1, 2, 3, 7, 255, 256, 1000, 65535, 1u << 20, 0xfffffffeu};
    uint64_t draws = 0, differ = 0;
    for (size_t a = 0; a < sizeof seeds / sizeof *seeds; a++)
        for (size_t b = 0; b < sizeof pixels / sizeof *pixels; b++)
            for (size_t c = 0; c < sizeof indices / sizeof *indices; c++) {
                il_sampler cpu;
                il_sampler_start(&cpu, IL_SAMPLER_SOBOL, seeds[a], pixels[b], indices[c]);
                ilk_sobol k = ilk_sobol_start(seeds[a], pixels[b], indices[c]);
                for (uint32_t d = 0; d < 32; d++) {
                    if (d % 3 == 1) {
                        float x = il_sampler_1d(&cpu), y = ilk_sobol_1d(&k);
                        differ += memcmp(&x, &y, sizeof x) != 0;
                        draws++;
                    } else {
                        il_vec2 x = il_sampler_2d(&cpu);
                        float u, v;
                        ilk_sobol_2d(&k, &u, &v);
                        differ += memcmp(&x.x, &u, sizeof u) != 0 || memcmp(&x.y, &v, sizeof v) != 0;
                        draws += 2;
                    }
                }
            }
    /* Stratification that a copy error would break: the first 256 points
     * of one pair fill every cell of a 16 x 16 grid once ((0,2)-net). */
    int cells[16][16];
    memset(cells, 0, sizeof cells);
    for (uint32_t i = 0; i < 256; i++) {
        ilk_sobol k = ilk_sobol_start(3, 77, i);
        float u, v;
        ilk_sobol_2d(&k, &u, &v);
        cells[(int)(u * 16)][(int)(v * 16)]++;
    }
    int once = 1;
    for (int i = 0; i < 16; i++)
        for (int j = 0; j < 16; j++)
            once &= cells[i][j] == 1;
    printf("%llu numbers drawn, %llu differ from core/sampler.c; 16x16 strata filled once each: %s\n",
           (unsigned long long)draws, (unsigned long long)differ, once ? "yes" : "no");
    CHECK(draws > 1000);
    CHECK(differ == 0);
    CHECK(once);
    return check_report();
}
