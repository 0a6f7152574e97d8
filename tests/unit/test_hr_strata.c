/* The order of hierarchical radiosity's visibility strata (hr_link.c,
 * il_hr_vis_strata): every stratum of the m x m grid exactly once; for 16
 * and 64 rays each run of 4 draws from a multiple of 4 covers the four
 * quadrants, for the receiver (draw k) and the source (draw n - 1 - k), so
 * the first 4 rays of a link are a 2 x 2 stratified set; other counts go
 * row by row. */
#include <stdlib.h>

#include "check.h"
#include "methods/hr/hr.h"

static void check_order(uint32_t n, uint32_t want_m, bool want_pow2)
{
    uint32_t strata[4096], m = 0;
    bool pow2 = false;
    il_hr_vis_strata(n, &m, &pow2, strata);
    CHECK(m == want_m);
    CHECK(pow2 == want_pow2);
    bool seen[4096] = {false};
    for (uint32_t k = 0; k < n; k++) {
        uint32_t x = strata[k] & 0xffffu, y = strata[k] >> 16;
        CHECK(x < m && y < m);
        if (x < m && y < m) {
            CHECK(!seen[y * m + x]);
            seen[y * m + x] = true;
        }
    }
    if (!pow2) {
        for (uint32_t k = 0; k < n; k++)
            CHECK(strata[k] == ((k % m) | (k / m) << 16));
        return;
    }
    for (uint32_t base = 0; base < n; base += 4) {
        unsigned quads_r = 0, quads_s = 0;
        for (uint32_t k = base; k < base + 4; k++) {
            uint32_t r = strata[k], s = strata[n - 1 - k];
            quads_r |= 1u << ((2 * (r >> 16) >= m) * 2 + (2 * (r & 0xffffu) >= m));
            quads_s |= 1u << ((2 * (s >> 16) >= m) * 2 + (2 * (s & 0xffffu) >= m));
        }
        CHECK(quads_r == 15u);
        CHECK(quads_s == 15u);
    }
}

int main(void)
{
    check_order(16, 4, true);
    check_order(64, 8, true);
    check_order(4, 2, true);
    check_order(10, 4, false);
    check_order(9, 3, false);
    check_order(1, 1, false);
    return check_report();
}
