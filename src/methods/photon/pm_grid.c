/* Hashed uniform grid over the photons (Galacz 2013, as in Hachisuka &
 * Jensen 2009's SPPM hash grid): cells as wide as the query radius, cells
 * hashed (Teschner et al. 2003, "Optimized Spatial Hashing for Collision
 * Detection of Deformable Objects") into a power-of-two table, photons
 * sorted by hash with a counting sort.  A query of radius r looks at the
 * 3x3x3 cells around the point; distinct cells that share a hash share a
 * bucket, so the buckets are visited once each and every photon in them is
 * distance-tested: collisions cost time, never photons.  A larger radius
 * looks at more cells (up to 11^3, then at every photon), and k nearest
 * neighbours are answered exactly too (il_pm_grid_knn). */
#include <math.h>
#include <string.h>

#include "methods/photon/pm_internal.h"

/* The cell coordinate uses a cell a little wider than cell_size: a photon
 * passing the float test d2 <= r^2 is within r(1 + 2^-22) per axis, so with
 * this margin (and the coordinate in double) it is never two cells away. */
#define GRID_MARGIN 1.00001

/* The photons' cell coordinates stay below 2^29 in magnitude (the build
 * widens the cell for a huge scene with a tiny radius), far inside int64
 * and with double rounding far below GRID_MARGIN. */
#define GRID_MAX_COORD 1073741824.0

/* A query point far outside the photons (or NaN) is clamped to a cell that
 * holds none of them, rather than overflowing the conversion. */
static inline int64_t cell_of(double inv, float x)
{
    double c = floor((double)x * inv);
    if (!(c > -4.0 * GRID_MAX_COORD))
        c = -4.0 * GRID_MAX_COORD;
    if (c > 4.0 * GRID_MAX_COORD)
        c = 4.0 * GRID_MAX_COORD;
    return (int64_t)c;
}

/* Teschner's hash of the row (y, z) plus x: the cells of a row along x
 * fall in consecutive buckets, so a query's three cells of a row are one
 * contiguous run of photons (and of cell_start). */
static inline uint32_t cell_hash(int64_t x, int64_t y, int64_t z, uint32_t mask)
{
    return (((uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u) + (uint32_t)x) & mask;
}

static inline double grid_inv(const il_pm_map *map)
{
    return 1.0 / ((double)map->cell_size * GRID_MARGIN);
}

il_status il_pm_grid_build(il_pm_map *map, float radius, il_error *err)
{
    if (!(radius > 0.0f) || !isfinite(radius))
        return il_fail(err, IL_ERR_INVALID, "photon map: the grid's radius must be positive (got %g)",
                       (double)radius);
    size_t n = map->count;
    float max_abs = 0.0f;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            max_abs = il_maxf(max_abs, fabsf(map->photons[i].p[c]));
    double cell = radius;
    if ((double)max_abs / cell > GRID_MAX_COORD / 2)
        cell = (double)max_abs / (GRID_MAX_COORD / 2);
    map->cell_size = (float)cell;
    if ((double)map->cell_size < cell)
        map->cell_size = nextafterf(map->cell_size, INFINITY);

    /* A table with at least as many buckets as photons: at most as many
     * occupied cells, so a load factor of 1 or less. */
    size_t size = 1;
    while (size < n && size < ((size_t)1 << 31))
        size <<= 1;
    map->hash_mask = (uint32_t)(size - 1);
    map->cell_start = il_calloc(size + 1, sizeof *map->cell_start, err);
    if (!map->cell_start)
        return IL_ERR_MEMORY;
    if (n == 0)
        return IL_OK;
    uint32_t *dest = il_malloc(n * sizeof *dest, err);
    if (!dest)
        return IL_ERR_MEMORY;

    /* Counting sort by hash, stable so the order is deterministic. */
    double inv = grid_inv(map);
    uint32_t *start = map->cell_start;
    for (size_t i = 0; i < n; i++) {
        const float *p = map->photons[i].p;
        uint32_t h = cell_hash(cell_of(inv, p[0]), cell_of(inv, p[1]), cell_of(inv, p[2]), map->hash_mask);
        dest[i] = h;
        start[h + 1]++;
    }
    for (size_t h = 0; h < size; h++)
        start[h + 1] += start[h];
    /* start[h] is now bucket h's first slot; hand slots out, then restore. */
    for (size_t i = 0; i < n; i++)
        dest[i] = start[dest[i]]++;
    for (size_t h = size; h > 0; h--)
        start[h] = start[h - 1];
    start[0] = 0;
    il_pm_permute(map->photons, dest, n);
    free(dest);
    return IL_OK;
}

/* ------------------------------------------------------------------ queries */

/* The distinct buckets of the cells within `reach` cells of p's, sorted.
 * Returns how many, or 0 when there are more than `cap` cells (the caller
 * then scans every photon). */
static uint32_t gather_buckets(const il_pm_map *map, il_vec3 p, int64_t reach, uint32_t *hs, uint32_t cap)
{
    if (reach > 5)
        return 0;
    int64_t side = 2 * reach + 1;
    if (side * side * side > (int64_t)cap)
        return 0;
    double inv = grid_inv(map);
    int64_t cx = cell_of(inv, p.x), cy = cell_of(inv, p.y), cz = cell_of(inv, p.z);
    uint32_t m = 0;
    for (int64_t dz = -reach; dz <= reach; dz++)
        for (int64_t dy = -reach; dy <= reach; dy++)
            for (int64_t dx = -reach; dx <= reach; dx++) {
                uint32_t h = cell_hash(cx + dx, cy + dy, cz + dz, map->hash_mask);
                /* Insertion into the sorted list, dropping repeats. */
                uint32_t j = m;
                while (j > 0 && hs[j - 1] > h) {
                    hs[j] = hs[j - 1];
                    j--;
                }
                if (j > 0 && hs[j - 1] == h) {
                    memmove(&hs[j], &hs[j + 1], (m - j) * sizeof *hs);
                    continue;
                }
                hs[j] = h;
                m++;
            }
    return m;
}

/* Cells to look at on each side for a query of squared radius d2. */
static int64_t grid_reach(const il_pm_map *map, float d2)
{
    if (d2 <= map->cell_size * map->cell_size)
        return 1;
    double r = sqrt((double)d2) * (1.0 + 1e-6) * grid_inv(map);
    return r < GRID_MAX_COORD ? (int64_t)ceil(r) : (int64_t)GRID_MAX_COORD;
}

#define GRID_MAX_BUCKETS 1331   /* 11^3: a radius up to 5 cells */

/* Calls VISIT(index, d2) for every photon within sqrt(bound) of p. */
#define GRID_TRAVERSE(map, p, query_d2, bound, VISIT)                                        \
    do {                                                                                     \
        const float q_[3] = {(p).x, (p).y, (p).z};                                           \
        uint32_t hs_[GRID_MAX_BUCKETS];                                                      \
        uint32_t cap_ = (map)->hash_mask < GRID_MAX_BUCKETS ? (map)->hash_mask + 1 : GRID_MAX_BUCKETS; \
        uint32_t nb_ = gather_buckets((map), (p), grid_reach((map), (query_d2)), hs_, cap_);   \
        if (nb_ == 0) { /* larger than the table: every photon */                            \
            for (size_t i_ = 0; i_ < (map)->count; i_++) {                                   \
                float d2_ = il_pm_dist2(&(map)->photons[i_], q_);                            \
                if (d2_ <= (bound)) {                                                        \
                    VISIT((uint32_t)i_, d2_);                                                \
                }                                                                            \
            }                                                                                \
        }                                                                                    \
        for (uint32_t b_ = 0; b_ < nb_;) {                                                   \
            /* A run of consecutive buckets is one run of photons. */                        \
            uint32_t first_ = hs_[b_++];                                                     \
            uint32_t last_ = first_;                                                         \
            while (b_ < nb_ && hs_[b_] == last_ + 1)                                         \
                last_ = hs_[b_++];                                                           \
            uint32_t e_ = (map)->cell_start[last_ + 1];                                      \
            for (uint32_t i_ = (map)->cell_start[first_]; i_ < e_; i_++) {                   \
                float d2_ = il_pm_dist2(&(map)->photons[i_], q_);                            \
                if (d2_ <= (bound)) {                                                        \
                    VISIT(i_, d2_);                                                          \
                }                                                                            \
            }                                                                                \
        }                                                                                    \
    } while (0)

bool il_pm_grid_range(const il_pm_map *map, il_vec3 p, float d2, il_pm_buffer *out)
{
    bool ok = true;
    if (map->count == 0)
        return true;
#define RANGE_VISIT(i, dd)                                                                   \
    if (ok && !il_pm_buffer_push(out, (i), (dd)))                                            \
        ok = false;
    GRID_TRAVERSE(map, p, d2, d2, RANGE_VISIT);
#undef RANGE_VISIT
    return ok;
}

/* k nearest on a grid: the cells within sqrt(max_d2) with a bounded heap,
 * so the answer is exact (the same set as the kd-tree's, up to ties), only
 * slower when max_d2 spans many cells. */
uint32_t il_pm_grid_knn(const il_pm_map *map, il_vec3 p, uint32_t k, float max_d2,
                        il_pm_neighbour *out, float *r2)
{
    il_pm_knn_heap h = {out, k, 0, max_d2};
    if (map->count > 0 && k > 0) {
#define KNN_VISIT(i, d2) il_pm_heap_offer(&h, (i), (d2))
        GRID_TRAVERSE(map, p, max_d2, h.bound, KNN_VISIT);
#undef KNN_VISIT
    }
    if (r2)
        *r2 = (k > 0 && h.count == k) ? h.items[0].d2 : max_d2;
    return h.count;
}
