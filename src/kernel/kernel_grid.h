/* The hashed uniform grid over photon records, shared by the CPU (gcc) and
 * the GPU (src/cuda/photon_kernel.cu), built by sorting photons by cell as
 * in GPU Gems 3, chapter 32 (Le Grand 2007, "Broad-Phase Collision Detection
 * with CUDA"):
 *
 *   1. key[i] = hash of photon i's cell (ILK_GRID_NO_KEY for empty slots),
 *      value[i] = i;                                    ilk_grid_key
 *   2. sort (key, value) by key, stable (the CPU: a comparison sort on
 *      (key, value); the GPU: cub's radix sort, stable, so the same order);
 *   3. photons[i] = slots[value[i]];
 *   4. for each i, where the key changes: cell_start[key] = i and
 *      cell_end[key] = i + 1 on the last one (empty buckets keep 0, 0);
 *                                                       ilk_grid_mark
 *   5. a range query visits every cell overlapping the query's bounding box
 *      and keeps the photons of that very cell (hash collisions share a
 *      bucket, so each photon's own cell is checked) within the radius.
 *
 * Cells are cubes of side cell_size, half the query radius
 * (ilk_grid_cell_size): a query visits the 4-5 cells per axis that its
 * bounding box touches, and on a surface reads about (2.5 r)^2 of area
 * around its disc of pi r^2, where cells as wide as the radius (3 per
 * axis, (3 r)^2) read 45% more photons it then rejects.  On an H200 the
 * gather of 16 passes over the Cornell box took 0.70 s instead of 1.07
 * (a third of the radius: 0.69 s; on the Cornell box with the dragon
 * 0.63 s at a half against 0.68 s at a third and 0.85 s at the radius).
 * The cell hash is Teschner et al. 2003, "Optimized Spatial Hashing for
 * Collision Detection of Deformable Objects". */
#ifndef IL_KERNEL_GRID_H
#define IL_KERNEL_GRID_H

#include "kernel/kernel_photon.h"

#define ILK_GRID_NO_KEY UINT32_MAX

/* The built grid (host or device pointers). */
typedef struct ilk_grid {
    const ilk_photon *photons;     /* sorted by key; the empty ones at the end */
    uint32_t count;                /* photons stored (non-empty) */
    const uint32_t *cell_start;    /* hash_mask + 1 entries each */
    const uint32_t *cell_end;
    uint32_t hash_mask;            /* table size - 1, a power of two */
    float cell_size, inv_cell;
} ilk_grid;

/* The side of the cells for queries of the given radius (above). */
IL_DEVICE_INLINE float ilk_grid_cell_size(float radius) { return 0.5f * radius; }

/* The grid over count sorted photons, cells of side cell_size. */
IL_DEVICE_INLINE ilk_grid ilk_grid_make(const ilk_photon *photons, uint32_t count, const uint32_t *cell_start,
                                        const uint32_t *cell_end, uint32_t hash_mask, float cell_size)
{
    ilk_grid g;
    g.photons = photons;
    g.count = count;
    g.cell_start = cell_start;
    g.cell_end = cell_end;
    g.hash_mask = hash_mask;
    g.cell_size = cell_size;
    g.inv_cell = 1.0f / cell_size;
    return g;
}

typedef struct ilk_cell { int x, y, z; } ilk_cell;

IL_DEVICE_INLINE ilk_cell ilk_grid_cell(float inv_cell, ilk_vec3 p)
{
    ilk_cell c;
    c.x = (int)floorf(p.x * inv_cell);
    c.y = (int)floorf(p.y * inv_cell);
    c.z = (int)floorf(p.z * inv_cell);
    return c;
}

IL_DEVICE_INLINE uint32_t ilk_grid_hash(ilk_cell c, uint32_t hash_mask)
{
    return (((uint32_t)c.x * 73856093u) ^ ((uint32_t)c.y * 19349663u) ^ ((uint32_t)c.z * 83492791u)) & hash_mask;
}

/* Step 1 for one slot.  A photon's first hit (bounces 0, direct light)
 * stays out of the grid, sorted after its records with the empty slots:
 * the gather takes direct light by a shadow ray instead
 * (kernel_photon_gather.h), as the CPU photon method does. */
IL_DEVICE_INLINE uint32_t ilk_grid_key(const ilk_photon *ph, float inv_cell, uint32_t hash_mask)
{
    if (ph->bounces == ILK_PHOTON_EMPTY || ph->bounces == 0)
        return ILK_GRID_NO_KEY;
    return ilk_grid_hash(ilk_grid_cell(inv_cell, ph->p), hash_mask);
}

/* Step 4 for sorted entry i of n; start and end zeroed beforehand.  Each
 * bucket is written by the one entry that begins (ends) its run, so the
 * GPU needs no atomics. */
IL_DEVICE_INLINE void ilk_grid_mark(const uint32_t *sorted_keys, uint32_t n, uint32_t i, uint32_t *cell_start,
                                    uint32_t *cell_end)
{
    uint32_t k = sorted_keys[i];
    if (k == ILK_GRID_NO_KEY)
        return;
    if (i == 0 || sorted_keys[i - 1] != k)
        cell_start[k] = i;
    if (i + 1 == n || sorted_keys[i + 1] != k)
        cell_end[k] = i + 1;
}

/* A range query in progress: for (q = begin; ilk_grid_next(g, &q, &i);). */
typedef struct ilk_grid_query {
    ilk_vec3 p;
    float r2;
    ilk_cell lo, hi, at;           /* the cells to visit; the current one */
    uint32_t next, end;            /* the current cell's remaining entries */
} ilk_grid_query;

IL_DEVICE_INLINE ilk_grid_query ilk_grid_query_begin(const ilk_grid *g, ilk_vec3 p, float radius)
{
    ilk_grid_query q;
    q.p = p;
    q.r2 = radius * radius;
    q.lo = ilk_grid_cell(g->inv_cell, ilk_sub(p, ilk_v3(radius, radius, radius)));
    q.hi = ilk_grid_cell(g->inv_cell, ilk_add(p, ilk_v3(radius, radius, radius)));
    q.at = q.lo;
    q.at.x -= 1;                   /* ilk_grid_next steps onto lo first */
    q.next = q.end = 0;
    return q;
}

/* The next photon (index into g->photons) within the radius; false when
 * the query is done. */
IL_DEVICE_INLINE bool ilk_grid_next(const ilk_grid *g, ilk_grid_query *q, uint32_t *index)
{
    for (;;) {
        while (q->next < q->end) {
            uint32_t i = q->next++;
            const ilk_photon *ph = &g->photons[i];
            ilk_cell c = ilk_grid_cell(g->inv_cell, ph->p);
            if (c.x != q->at.x || c.y != q->at.y || c.z != q->at.z)
                continue;          /* another cell with the same hash */
            ilk_vec3 d = ilk_sub(ph->p, q->p);
            if (ilk_dot(d, d) <= q->r2) {
                *index = i;
                return true;
            }
        }
        /* The next cell, x fastest. */
        if (++q->at.x > q->hi.x) {
            q->at.x = q->lo.x;
            if (++q->at.y > q->hi.y) {
                q->at.y = q->lo.y;
                if (++q->at.z > q->hi.z)
                    return false;
            }
        }
        if (g->count == 0)
            return false;
        uint32_t h = ilk_grid_hash(q->at, g->hash_mask);
        q->next = g->cell_start[h];
        q->end = g->cell_end[h];
    }
}

#endif
