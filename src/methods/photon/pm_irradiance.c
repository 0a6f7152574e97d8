/* Precomputed irradiance (Christensen 1999, "Faster Photon Map Global
 * Illumination", JGT 4(3), sections 2-3): once the global map is built, the
 * irradiance estimate is computed at every few photons and stored with a
 * kd-tree of its own.  A Lambertian surface then reads the global map by
 * finding the one nearest precomputed point whose normal agrees with its
 * own, and reflects rho/pi * E; a k-nearest estimate per camera or gather
 * hit becomes a 1-nearest search.  Christensen's paper uses every fourth
 * photon and reports the images indistinguishable from the full estimate
 * where it is read through final gathering. */
#include <omp.h>
#include <stdatomic.h>
#include <string.h>

#include "core/error.h"
#include "methods/photon/pm_internal.h"

il_status il_pm_irradiance_build(il_pm_map *map, const il_pm_lookup *q, uint32_t stride,
                                 int threads, il_error *err)
{
    free(map->irr);
    map->irr = NULL;
    map->irr_count = 0;
    if (map->count == 0)
        return IL_OK;
    if (stride == 0)
        stride = 1;
    if (threads <= 0)
        threads = omp_get_max_threads();
    size_t m = (map->count + stride - 1) / stride;
    il_photon *irr = il_malloc(m * sizeof *irr, err);
    if (!irr)
        return IL_ERR_MEMORY;
    atomic_int oom = 0;
    /* Each point's estimate depends only on the map, so the values are the
     * same for any thread count and schedule. */
#pragma omp parallel num_threads(threads) if (m >= 1024)
    {
        il_pm_scratch scratch = {0};
#pragma omp for schedule(dynamic, 256)
        for (int64_t i = 0; i < (int64_t)m; i++) {
            const il_photon *ph = &map->photons[(size_t)i * stride];
            il_vec3 n = il_photon_normal(ph);
            il_vec3 E = v3s(0.0f);
            if (il_pm_irradiance_estimate(map, q, il_photon_pos(ph), n, &scratch, &E, NULL) != IL_OK)
                atomic_store(&oom, 1);
            il_photon *o = &irr[i];
            memcpy(o->p, ph->p, sizeof o->p);
            o->power = il_rgbe_pack(E);
            o->dir = 0;
            o->normal = (uint16_t)(ph->normal & IL_PM_NORMAL_MASK);
        }
        il_pm_scratch_free(&scratch);
    }
    il_status st = atomic_load(&oom)
                       ? il_fail(err, IL_ERR_MEMORY, "photon map: out of memory precomputing irradiance")
                       : il_pm_kd_build(irr, m, err);
    if (st != IL_OK) {
        free(irr);
        return st;
    }
    map->irr = irr;
    map->irr_count = m;
    return IL_OK;
}

bool il_pm_irradiance_lookup(const il_pm_map *map, il_vec3 p, il_vec3 n, float max_d2, il_vec3 *E)
{
    *E = v3s(0.0f);
    if (!map->irr || map->irr_count == 0)
        return false;
    uint32_t i = il_pm_kd_nearest_normal(map->irr, map->irr_count, p, n, max_d2);
    if (i == UINT32_MAX)
        return false;
    *E = il_rgbe_unpack(map->irr[i].power);
    return true;
}
