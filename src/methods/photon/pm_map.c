/* A photon map: the photons and the search structure built over them
 * (pm_kdtree.c or pm_grid.c), and the queries that dispatch to it. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "methods/photon/pm_internal.h"

il_status il_pm_map_build(il_pm_map *map, il_photon *photons, size_t count, float power_scale,
                          il_photon_lookup lookup, float radius, il_error *err)
{
    return il_pm_map_build_split(map, photons, count, power_scale, lookup, radius, NULL, err);
}

il_status il_pm_map_build_split(il_pm_map *map, il_photon *photons, size_t count, float power_scale,
                                il_photon_lookup lookup, float radius, const il_distrib *d,
                                il_error *err)
{
    memset(map, 0, sizeof *map);
    map->photons = photons;
    map->count = photons ? count : 0;
    map->power_scale = power_scale;
    map->lookup = lookup;
    for (int c = 0; c < 3; c++) {
        map->lo[c] = INFINITY;
        map->hi[c] = -INFINITY;
    }
    il_status st = IL_OK;
    if (map->count > UINT32_MAX) {
        st = il_fail(err, IL_ERR_INVALID, "photon map: %zu photons, at most %u fit one map",
                     map->count, UINT32_MAX);
    } else if (!isfinite(power_scale) || power_scale < 0.0f) {
        st = il_fail(err, IL_ERR_INVALID, "photon map: power scale %g is not a finite non-negative number",
                     (double)power_scale);
    } else if (lookup != IL_PHOTON_KDTREE && lookup != IL_PHOTON_GRID) {
        st = il_fail(err, IL_ERR_INVALID, "photon map: unknown lookup structure %d", (int)lookup);
    } else {
        /* A NaN coordinate would make the median selection's order meaningless. */
        for (size_t i = 0; i < map->count; i++) {
            const float *p = photons[i].p;
            if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
                st = il_fail(err, IL_ERR_INVALID, "photon map: photon %zu has a non-finite position", i);
                break;
            }
            for (int c = 0; c < 3; c++) {
                map->lo[c] = p[c] < map->lo[c] ? p[c] : map->lo[c];
                map->hi[c] = p[c] > map->hi[c] ? p[c] : map->hi[c];
            }
        }
    }
    if (st == IL_OK)
        st = lookup == IL_PHOTON_KDTREE ? il_pm_kd_build_split(map->photons, map->count, d, err)
                                        : il_pm_grid_build(map, radius, err);
    if (st != IL_OK)
        il_pm_map_free(map);
    return st;
}

void il_pm_map_free(il_pm_map *map)
{
    if (!map)
        return;
    free(map->photons);
    free(map->cell_start);
    free(map->irr);
    memset(map, 0, sizeof *map);
}

size_t il_pm_map_bytes(const il_pm_map *map)
{
    size_t b = map->count * sizeof(il_photon);
    if (map->cell_start)
        b += ((size_t)map->hash_mask + 2) * sizeof *map->cell_start;
    b += map->irr_count * sizeof(il_photon);
    return b;
}

/* A grid map answers k-NN too, exactly (pm_grid.c), scanning the cells
 * within sqrt(max_d2): slower than the kd-tree when that spans many cells. */
uint32_t il_pm_knn(const il_pm_map *map, il_vec3 p, uint32_t k, float max_d2, il_pm_neighbour *out,
                   float *r2)
{
    if (map->count == 0 || k == 0) {
        if (r2)
            *r2 = max_d2;
        return 0;
    }
    if (map->lookup == IL_PHOTON_GRID)
        return il_pm_grid_knn(map, p, k, max_d2, out, r2);
    return il_pm_kd_knn(map->photons, map->count, p, k, max_d2, out, r2);
}

il_status il_pm_range(const il_pm_map *map, il_vec3 p, float d2, il_pm_buffer *out, il_error *err)
{
    if (map->count == 0)
        return IL_OK;
    bool ok = map->lookup == IL_PHOTON_GRID ? il_pm_grid_range(map, p, d2, out)
                                            : il_pm_kd_range(map->photons, map->count, p, d2, out);
    return ok ? IL_OK : il_fail(err, IL_ERR_MEMORY, "photon map: out of memory for a range query's photons");
}

void il_pm_buffer_free(il_pm_buffer *b)
{
    if (!b)
        return;
    free(b->items);
    memset(b, 0, sizeof *b);
}
