/* Internals shared by the photon map's search structures (pm_kdtree.c,
 * pm_grid.c, pm_map.c): the distance test both structures use, so that a
 * kd-tree and a grid built over the same photons report the same sets, the
 * kd-tree's split axis in the photon's spare bits, a bounded max-heap for
 * k nearest neighbours, and the growing range buffer. */
#ifndef IL_METHODS_PM_INTERNAL_H
#define IL_METHODS_PM_INTERNAL_H

#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "methods/photon/pm.h"

/* Bits 14-15 of il_photon.normal: the kd-tree's split axis (0, 1, 2). */
#define IL_PM_AXIS_SHIFT 14
#define IL_PM_NORMAL_MASK 0x3FFFu

static inline unsigned il_pm_axis(const il_photon *ph) { return ph->normal >> IL_PM_AXIS_SHIFT; }
static inline void il_pm_set_axis(il_photon *ph, unsigned axis)
{
    ph->normal = (uint16_t)((ph->normal & IL_PM_NORMAL_MASK) | (axis << IL_PM_AXIS_SHIFT));
}

/* The photon's normal as the unnormalised v of the 7+7-bit octahedral
 * decode of pm_photon.c (Cigolle et al. 2014, 3.1). */
static inline il_vec3 il_pm_normal_raw(const il_photon *ph)
{
    const float inv = 1.0f / 63.0f;
    float x = (float)((int)(ph->normal & 127u) - 63) * inv;
    float y = (float)((int)((ph->normal >> 7) & 127u) - 63) * inv;
    float z = 1.0f - fabsf(x) - fabsf(y);
    if (z < 0.0f) {
        float ox = x;
        x = (1.0f - fabsf(y)) * (ox >= 0.0f ? 1.0f : -1.0f);
        y = (1.0f - fabsf(ox)) * (y >= 0.0f ? 1.0f : -1.0f);
    }
    return (il_vec3){x, y, z};
}

/* The normal test of the estimates, v3_dot(il_photon_normal(ph), n) >=
 * IL_PM_NORMAL_COS for a unit n, without normalising the decoded normal:
 * dot(v, n) >= c |v| is tested squared. */
static inline bool il_pm_normal_agrees(const il_photon *ph, il_vec3 n)
{
    il_vec3 v = il_pm_normal_raw(ph);
    float d = v.x * n.x + v.y * n.y + v.z * n.z;
    return d >= 0.0f && d * d >= IL_PM_NORMAL_COS * IL_PM_NORMAL_COS * (v.x * v.x + v.y * v.y + v.z * v.z);
}

/* Whether a photon found within radius r of x lies on the query's surface
 * (unit normal n there): its normal agrees (il_pm_normal_agrees), and it
 * lies no farther off the tangent plane at x than the turn of its normal
 * allows, plus IL_PM_DISC_THICKNESS * r.  This compresses the search
 * sphere along the normal into a disc (Jensen 2001, ch. 7), so photons on
 * a parallel surface just behind the query's (the ground a few
 * centimetres under a floor, outside a wall without thickness) do not
 * count.  The turn: a photon at distance d on a plane whose normal is
 * turned by theta from n, through a point of the query's plane, lies at
 * most d sin(theta) off that plane, which covers a tessellated curve's
 * facets as well as a smooth curve (d theta / 2 off its tangent plane);
 * the thickness also covers the degree or so the normal's 14-bit code may
 * be off by. */
static inline bool il_pm_on_surface(const il_photon *ph, il_vec3 n, il_vec3 x, float r)
{
    il_vec3 v = il_pm_normal_raw(ph);
    float vv = v.x * v.x + v.y * v.y + v.z * v.z;
    float d = v.x * n.x + v.y * n.y + v.z * n.z;
    if (!(d >= 0.0f && d * d >= IL_PM_NORMAL_COS * IL_PM_NORMAL_COS * vv))
        return false;
    float ox = ph->p[0] - x.x, oy = ph->p[1] - x.y, oz = ph->p[2] - x.z;
    float beyond = fabsf(ox * n.x + oy * n.y + oz * n.z) - IL_PM_DISC_THICKNESS * r;
    float sin2_turn = 1.0f - d * d / vv;
    return beyond <= 0.0f || beyond * beyond <= sin2_turn * (ox * ox + oy * oy + oz * oz);
}

/* Squared distance from q to the photon.  Every structure uses this one
 * function (and the kd-tree's plane distance is exactly one of its terms),
 * so a photon on the sphere's boundary is in or out for all of them. */
static inline float il_pm_dist2(const il_photon *ph, const float q[3])
{
    float dx = q[0] - ph->p[0], dy = q[1] - ph->p[1], dz = q[2] - ph->p[2];
    return dx * dx + dy * dy + dz * dz;
}

/* ----------------------------------------- bounded max-heap (Jensen 6.3.2) */

/* The k nearest so far in items[0..count-1]; once k are held they form a
 * max-heap on d2 and `bound` is the farthest of them (before that it is the
 * search radius squared).  A candidate is taken when d2 <= bound and, once
 * full, only when strictly nearer than the farthest held. */
typedef struct il_pm_knn_heap {
    il_pm_neighbour *items;
    uint32_t k, count;
    float bound;
} il_pm_knn_heap;

static inline void il_pm_heap_sift_down(il_pm_neighbour *h, uint32_t n, uint32_t i)
{
    il_pm_neighbour x = h[i];
    for (;;) {
        uint32_t c = 2 * i + 1;
        if (c >= n)
            break;
        /* branch-free child choice: the comparison is a coin toss */
        c += (uint32_t)(c + 1 < n && h[c + 1].d2 > h[c].d2);
        if (h[c].d2 <= x.d2)
            break;
        h[i] = h[c];
        i = c;
    }
    h[i] = x;
}

static inline void il_pm_heap_offer(il_pm_knn_heap *h, uint32_t index, float d2)
{
    if (h->count < h->k) {
        h->items[h->count++] = (il_pm_neighbour){index, d2};
        if (h->count == h->k) {
            for (uint32_t i = h->k / 2; i-- > 0;)
                il_pm_heap_sift_down(h->items, h->k, i);
            h->bound = h->items[0].d2;
        }
    } else if (d2 < h->items[0].d2) {
        h->items[0] = (il_pm_neighbour){index, d2};
        il_pm_heap_sift_down(h->items, h->k, 0);
        h->bound = h->items[0].d2;
    }
}

/* Appends one neighbour; false when out of memory. */
static inline bool il_pm_buffer_push(il_pm_buffer *b, uint32_t index, float d2)
{
    if (b->count == b->cap) {
        if (b->cap >= (UINT32_MAX >> 1))
            return false;
        uint32_t cap = b->cap ? 2 * b->cap : 256;
        il_pm_neighbour *items = realloc(b->items, (size_t)cap * sizeof *items);
        if (!items)
            return false;
        b->items = items;
        b->cap = cap;
    }
    b->items[b->count++] = (il_pm_neighbour){index, d2};
    return true;
}

/* Moves photon i to dest[i] for every i, in place by following cycles
 * (dest is a permutation; it is consumed). */
void il_pm_permute(il_photon *photons, uint32_t *dest, size_t n);

/* ------------------------------------------------------------ the kd-tree */

/* Reorders the photons into a left-balanced kd-tree in heap order. */
il_status il_pm_kd_build(il_photon *photons, size_t n, il_error *err);
/* il_pm_kd_build split across the processes of d (every process holds the
 * same photons): the top levels' splits on every process, the subtrees
 * below them built by one process each and exchanged; the same tree, byte
 * for byte.  Maps under IL_PM_KD_SPLIT_MIN photons, or d off: il_pm_kd_build. */
#define IL_PM_KD_SPLIT_MIN 16384u
il_status il_pm_kd_build_split(il_photon *photons, size_t n, const il_distrib *d, il_error *err);
uint32_t il_pm_kd_knn(const il_photon *photons, size_t n, il_vec3 p, uint32_t k, float max_d2,
                      il_pm_neighbour *out, float *r2);
bool il_pm_kd_range(const il_photon *photons, size_t n, il_vec3 p, float d2, il_pm_buffer *out);
/* The nearest photon within sqrt(max_d2) of p whose normal has a cosine of
 * at least IL_PM_NORMAL_COS with nrm; UINT32_MAX when there is none. */
uint32_t il_pm_kd_nearest_normal(const il_photon *photons, size_t n, il_vec3 p, il_vec3 nrm,
                                 float max_d2);

/* --------------------------------------------------------------- the grid */

/* Sorts map->photons by cell hash and fills cell_size, hash_mask, cell_start. */
il_status il_pm_grid_build(il_pm_map *map, float radius, il_error *err);
bool il_pm_grid_range(const il_pm_map *map, il_vec3 p, float d2, il_pm_buffer *out);
uint32_t il_pm_grid_knn(const il_pm_map *map, il_vec3 p, uint32_t k, float max_d2,
                        il_pm_neighbour *out, float *r2);

#endif
