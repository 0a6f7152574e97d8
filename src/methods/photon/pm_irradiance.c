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
#include "methods/distrib.h"
#include "methods/photon/pm_internal.h"

/* Points computed between two reports to a watch. */
#define POINTS_PER_ROUND 65536

/* The points [lo, hi) of the map's every stride-th photon into irr[0..hi-lo),
 * a round at a time; *stopped when the watch stopped it between rounds. */
static il_status estimate_points(const il_pm_map *map, const il_pm_lookup *q, uint32_t stride,
                                 int threads, size_t lo, size_t hi, il_photon *irr,
                                 il_pm_watch *watch, bool *stopped, il_error *err)
{
    atomic_int oom = 0;
    *stopped = false;
    for (size_t r0 = lo; r0 < hi && !atomic_load(&oom); r0 += POINTS_PER_ROUND) {
        if (!il_pm_watch_report(watch, IL_PHOTON_IRRADIANCE, r0 - lo, hi - lo)) {
            *stopped = true;
            break;
        }
        size_t r1 = hi - r0 < POINTS_PER_ROUND ? hi : r0 + POINTS_PER_ROUND;
        /* Each point's estimate depends only on the map, so the values are the
         * same for any thread count and schedule. */
#pragma omp parallel num_threads(threads) if (r1 - r0 >= 1024)
        {
            il_pm_scratch scratch = {0};
#pragma omp for schedule(dynamic, 256)
            for (int64_t i = (int64_t)r0; i < (int64_t)r1; i++) {
                const il_photon *ph = &map->photons[(size_t)i * stride];
                il_vec3 n = il_photon_normal(ph);
                il_vec3 E = v3s(0.0f);
                if (il_pm_irradiance_estimate(map, q, il_photon_pos(ph), n, &scratch, &E, NULL) != IL_OK)
                    atomic_store(&oom, 1);
                il_photon *o = &irr[(size_t)i - lo];
                memcpy(o->p, ph->p, sizeof o->p);
                o->power = il_rgbe_pack(E);
                o->dir = 0;
                o->normal = (uint16_t)(ph->normal & IL_PM_NORMAL_MASK);
            }
            il_pm_scratch_free(&scratch);
        }
    }
    if (atomic_load(&oom))
        return il_fail(err, IL_ERR_MEMORY, "photon map: out of memory precomputing irradiance");
    return IL_OK;
}

il_status il_pm_irradiance_build(il_pm_map *map, const il_pm_lookup *q, uint32_t stride,
                                 int threads, il_error *err)
{
    return il_pm_irradiance_build_split(map, q, stride, threads, NULL, NULL, err);
}

il_status il_pm_irradiance_build_split(il_pm_map *map, const il_pm_lookup *q, uint32_t stride,
                                       int threads, const il_distrib *d, il_pm_watch *watch,
                                       il_error *err)
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
    il_photon *irr = NULL;
    il_status st;
    bool stopped = false;
    if (!il_distrib_on(d)) {
        irr = il_malloc(m * sizeof *irr, err);
        if (!irr)
            return IL_ERR_MEMORY;
        st = estimate_points(map, q, stride, threads, 0, m, irr, watch, &stopped, err);
        if (st == IL_OK && stopped) { /* left out: full estimates instead */
            free(irr);
            return IL_OK;
        }
    } else {
        /* This process's contiguous part, then all parts in rank order. */
        uint64_t lo, hi;
        il_distrib_range(m, d->rank, d->size, &lo, &hi);
        il_photon *part = il_malloc((hi > lo ? hi - lo : 1) * sizeof *part, err);
        if (!part)
            return IL_ERR_MEMORY;
        /* No watch: a process stopping alone would leave the others waiting. */
        st = estimate_points(map, q, stride, threads, (size_t)lo, (size_t)hi, part, NULL,
                             &stopped, err);
        size_t *counts = st == IL_OK ? il_calloc((size_t)d->size, sizeof *counts, err) : NULL;
        if (st == IL_OK && !counts)
            st = IL_ERR_MEMORY;
        void *all = NULL;
        if (st == IL_OK)
            st = il_distrib_allgather(d, part, (hi - lo) * sizeof *part, &all, counts, err);
        size_t total = 0;
        for (int r = 0; st == IL_OK && r < d->size; r++)
            total += counts[r];
        if (st == IL_OK && total != m * sizeof *irr)
            st = il_fail(err, IL_ERR_RUNTIME,
                         "photon map: the processes sent %zu bytes of irradiance, not %zu", total,
                         m * sizeof *irr);
        free(part);
        free(counts);
        if (st != IL_OK) {
            free(all);
            return st;
        }
        irr = all;
    }
    if (st == IL_OK)
        st = il_pm_kd_build_split(irr, m, d, err);
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
