/* Ray casting on a flattened binary BVH, shared by the CPU (gcc) and the GPU
 * (nvcc): the layout that bvh_build.c writes and src/cuda/ copies to the
 * device as it is, Möller–Trumbore ray/triangle intersection, and stack-based
 * closest-hit and any-hit traversal.
 *
 * Layout (little-endian, no pointers, so one memcpy moves it to the GPU):
 *  - nodes: 32 bytes each, the root at index 0.  An interior node has
 *    count == 0 and its two children at first and first+1 (siblings are
 *    adjacent, so one node fetch pair gives both boxes); a leaf has
 *    count >= 1 triangles starting at tris[first].
 *  - tris: 48 bytes each, in leaf order: v0 and the edges e1 = v1 - v0,
 *    e2 = v2 - v0 (what Möller–Trumbore needs, with no index indirection),
 *    and the scene's (mesh, prim) of the triangle and its material in the
 *    padding words. */
#ifndef IL_KERNEL_BVH_H
#define IL_KERNEL_BVH_H

#include "kernel/kernel_math.h"

typedef struct ilk_bvh_node {
    float lo[3];
    uint32_t first;        /* interior: left child (right = first + 1); leaf: first triangle */
    float hi[3];
    uint32_t count;        /* 0: interior; else the number of triangles */
} ilk_bvh_node;

typedef struct ilk_tri {
    ilk_vec3 v0;
    uint32_t mesh;
    ilk_vec3 e1;
    uint32_t prim;
    ilk_vec3 e2;
    uint32_t pad;          /* the mesh's material (kernel_path.h) */
} ilk_tri;

/* The arrays as the traversal sees them (host or device pointers). */
typedef struct ilk_bvh {
    const ilk_bvh_node *nodes;
    const ilk_tri *tris;
    uint32_t num_nodes, num_tris;
} ilk_bvh;

/* Same layout as il_ray (trace/trace.h): dir need not be unit length, t is
 * in units of |dir|, hits count in [tmin, tmax]. */
typedef struct ilk_ray {
    ilk_vec3 org;
    float tmin;
    ilk_vec3 dir;
    float tmax;
} ilk_ray;

typedef struct ilk_hit {
    float t;
    float b1, b2;          /* barycentrics of v1 and v2, as Embree's u, v */
    uint32_t tri;          /* index into tris (leaf order); UINT32_MAX: no hit */
} ilk_hit;

/* The traversal stack holds at most one entry per level; bvh_build.c never
 * builds deeper than this. */
#define ILK_BVH_MAX_DEPTH 64

/* Möller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection",
 * JGT 2(1): Cramer's rule on org + t dir = v0 + b1 e1 + b2 e2, both faces.
 * Returns true with t, b1, b2 when the hit lies in [tmin, tmax]. */
IL_DEVICE_INLINE bool ilk_intersect_tri(const ilk_tri *tri, ilk_vec3 org, ilk_vec3 dir,
                                        float tmin, float tmax, float *t, float *b1, float *b2)
{
    ilk_vec3 p = ilk_cross(dir, tri->e2);
    float det = ilk_dot(tri->e1, p);
    if (det == 0.0f || !(det == det))
        return false;          /* ray parallel to the plane, or a degenerate triangle */
    float inv = 1.0f / det;
    ilk_vec3 s = ilk_sub(org, tri->v0);
    float u = ilk_dot(s, p) * inv;
    if (!(u >= 0.0f && u <= 1.0f))
        return false;
    ilk_vec3 q = ilk_cross(s, tri->e1);
    float v = ilk_dot(dir, q) * inv;
    if (!(v >= 0.0f && u + v <= 1.0f))
        return false;
    float tt = ilk_dot(tri->e2, q) * inv;
    if (!(tt >= tmin && tt <= tmax))
        return false;
    *t = tt;
    *b1 = u;
    *b2 = v;
    return true;
}

/* Slab test (Kay & Kajiya 1986) with the reciprocal direction.  A NaN slab
 * (origin on the plane of a face, direction component zero: 0 * inf) is
 * ignored because ilk_maxf/ilk_minf return their second argument then.  The
 * far distance is widened by 1 + 2 gamma(3) as in Ize 2013, "Robust BVH Ray
 * Traversal" (JCGT 2(2)), so rounding never culls a box the ray touches.
 * Returns the entry distance, or INFINITY when the box is missed. */
IL_DEVICE_INLINE float ilk_box_enter(const ilk_bvh_node *n, ilk_vec3 org, ilk_vec3 idir, float tmin, float tmax)
{
    float t0x = (n->lo[0] - org.x) * idir.x, t1x = (n->hi[0] - org.x) * idir.x;
    float t0y = (n->lo[1] - org.y) * idir.y, t1y = (n->hi[1] - org.y) * idir.y;
    float t0z = (n->lo[2] - org.z) * idir.z, t1z = (n->hi[2] - org.z) * idir.z;
    float tn = ilk_maxf(ilk_minf(t0x, t1x), tmin);
    tn = ilk_maxf(ilk_minf(t0y, t1y), tn);
    tn = ilk_maxf(ilk_minf(t0z, t1z), tn);
    float tf = ilk_minf(ilk_maxf(t0x, t1x), tmax);
    tf = ilk_minf(ilk_maxf(t0y, t1y), tf);
    tf = ilk_minf(ilk_maxf(t0z, t1z), tf);
    return tn <= tf * 1.00000036f ? tn : INFINITY; /* 1 + 2 gamma(3), gamma(n) = n eps / (1 - n eps) */
}

IL_DEVICE_INLINE ilk_vec3 ilk_reciprocal(ilk_vec3 d)
{
    return ilk_v3(1.0f / d.x, 1.0f / d.y, 1.0f / d.z);
}

/* Closest hit in [tmin, tmax]: front-to-back traversal, nearer child first,
 * the farther one on the stack (Wald et al. 2001 / pbrt-v4 section 7.3.5). */
IL_DEVICE_INLINE bool ilk_bvh_closest(const ilk_bvh *bvh, const ilk_ray *ray, ilk_hit *hit)
{
    hit->tri = UINT32_MAX;
    hit->t = ray->tmax;
    hit->b1 = hit->b2 = 0.0f;
    if (bvh->num_nodes == 0)
        return false;
    ilk_vec3 idir = ilk_reciprocal(ray->dir);
    if (ilk_box_enter(&bvh->nodes[0], ray->org, idir, ray->tmin, ray->tmax) == INFINITY)
        return false;
    uint32_t stack[ILK_BVH_MAX_DEPTH];
    int sp = 0;
    uint32_t idx = 0;
    float tmax = ray->tmax;
    for (;;) {
        const ilk_bvh_node *n = &bvh->nodes[idx];
        if (n->count) {
            for (uint32_t i = n->first; i < n->first + n->count; i++) {
                float t, b1, b2;
                if (ilk_intersect_tri(&bvh->tris[i], ray->org, ray->dir, ray->tmin, tmax, &t, &b1, &b2)) {
                    tmax = t;
                    hit->t = t;
                    hit->b1 = b1;
                    hit->b2 = b2;
                    hit->tri = i;
                }
            }
        } else {
            float dl = ilk_box_enter(&bvh->nodes[n->first], ray->org, idir, ray->tmin, tmax);
            float dr = ilk_box_enter(&bvh->nodes[n->first + 1], ray->org, idir, ray->tmin, tmax);
            if (dl != INFINITY && dr != INFINITY) {
                uint32_t near_child = dl <= dr ? n->first : n->first + 1;
                stack[sp++] = dl <= dr ? n->first + 1 : n->first;
                idx = near_child;
                continue;
            }
            if (dl != INFINITY) { idx = n->first; continue; }
            if (dr != INFINITY) { idx = n->first + 1; continue; }
        }
        if (sp == 0)
            break;
        idx = stack[--sp];
    }
    return hit->tri != UINT32_MAX;
}

/* True when any triangle lies on the ray in [tmin, tmax] (shadow rays):
 * depth-first, stops at the first hit. */
IL_DEVICE_INLINE bool ilk_bvh_occluded(const ilk_bvh *bvh, const ilk_ray *ray)
{
    if (bvh->num_nodes == 0)
        return false;
    ilk_vec3 idir = ilk_reciprocal(ray->dir);
    if (ilk_box_enter(&bvh->nodes[0], ray->org, idir, ray->tmin, ray->tmax) == INFINITY)
        return false;
    uint32_t stack[ILK_BVH_MAX_DEPTH];
    int sp = 0;
    uint32_t idx = 0;
    for (;;) {
        const ilk_bvh_node *n = &bvh->nodes[idx];
        if (n->count) {
            for (uint32_t i = n->first; i < n->first + n->count; i++) {
                float t, b1, b2;
                if (ilk_intersect_tri(&bvh->tris[i], ray->org, ray->dir, ray->tmin, ray->tmax, &t, &b1, &b2))
                    return true;
            }
        } else {
            bool l = ilk_box_enter(&bvh->nodes[n->first], ray->org, idir, ray->tmin, ray->tmax) != INFINITY;
            bool r = ilk_box_enter(&bvh->nodes[n->first + 1], ray->org, idir, ray->tmin, ray->tmax) != INFINITY;
            if (l && r) {
                stack[sp++] = n->first + 1;
                idx = n->first;
                continue;
            }
            if (l) { idx = n->first; continue; }
            if (r) { idx = n->first + 1; continue; }
        }
        if (sp == 0)
            return false;
        idx = stack[--sp];
    }
}

#endif
