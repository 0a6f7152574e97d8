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
    il_distrib1d_free(&rsm->choice);
    if (rsm->count == 0)
        return IL_OK;
    double *flux = il_malloc(rsm->count * sizeof *flux, err);
    float *pick = flux ? il_malloc(rsm->count * sizeof *pick, err) : NULL;
    if (!pick) {
        free(flux);
        return IL_ERR_MEMORY;
    }
    double total = 0.0;
    for (uint32_t k = 0; k < rsm->count; k++) {
        const il_rsm_map *m = &rsm->maps[k];
        size_t n = (size_t)m->size * m->size;
        flux[k] = 0.0;
        for (size_t t = 0; t < n; t++)
            flux[k] += (double)il_luminance(m->tex[t].flux);
        total += flux[k];
    }
    double uniform = 1.0 / rsm->count;
    for (uint32_t k = 0; k < rsm->count; k++)
        pick[k] = (float)(total > 0.0 ? 0.5 * flux[k] / total + 0.5 * uniform : uniform);
    il_status st = il_distrib1d_init(&rsm->choice, pick, rsm->count, err);
    free(pick);
    free(flux);
    return st;
}
