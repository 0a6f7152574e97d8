/* Which maps a shading point gathers when a scene has many (a point light
 * has six, and every light its own): il_rsm_gather draws `maps` of them and
 * weights each by 1 / (maps x its probability), so the estimate of the sum
 * over all maps stays unbiased (importance sampling, Veach 1997 section
 * 2.5.2).  The probability of map m is
 *     pick[m] = 1/2 flux_m / sum_k flux_k + 1/2 1 / count,
 * flux_m the luminance of the reflected flux its texels hold: the maps that
 * carry most light are gathered most often, and the uniform half (a
 * defensive mixture, Hesterberg 1995) bounds every weight by 2 count / maps,
 * so a map that is dim overall but bright near the receiver (a lamp beside
 * it, the sun far brighter elsewhere) is not a source of rare huge values. */
#include <stdlib.h>

#include "core/error.h"
#include "methods/rsm/rsm.h"

il_status il_rsm_choice_init(il_rsm *rsm, il_error *err)
{
    free(rsm->pick);
    free(rsm->pick_cdf);
    rsm->pick = rsm->pick_cdf = NULL;
    if (rsm->count == 0)
        return IL_OK;
    rsm->pick = il_malloc(rsm->count * sizeof *rsm->pick, err);
    rsm->pick_cdf = rsm->pick ? il_malloc(rsm->count * sizeof *rsm->pick_cdf, err) : NULL;
    if (!rsm->pick_cdf) {
        free(rsm->pick);
        rsm->pick = NULL;
        return IL_ERR_MEMORY;
    }
    double total = 0.0;
    for (uint32_t k = 0; k < rsm->count; k++) {
        const il_rsm_map *m = &rsm->maps[k];
        size_t n = (size_t)m->size * m->size;
        double flux = 0.0;
        for (size_t t = 0; t < n; t++)
            flux += (double)il_luminance(m->tex[t].flux);
        rsm->pick[k] = flux > 0.0 ? flux : 0.0;
        total += rsm->pick[k];
    }
    double uniform = 1.0 / rsm->count, sum = 0.0;
    for (uint32_t k = 0; k < rsm->count; k++) {
        rsm->pick[k] = total > 0.0 ? 0.5 * rsm->pick[k] / total + 0.5 * uniform : uniform;
        sum += rsm->pick[k];
        rsm->pick_cdf[k] = sum;
    }
    /* Rounding: the search below must end inside the array. */
    rsm->pick_cdf[rsm->count - 1] = 1.0;
    return IL_OK;
}

uint32_t il_rsm_choose(const il_rsm *rsm, double u)
{
    /* The first k with u < cdf[k]. */
    uint32_t lo = 0, hi = rsm->count - 1;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (u < rsm->pick_cdf[mid])
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}
