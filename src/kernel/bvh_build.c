/* Binned SAH BVH builder (Wald 2007, "On fast Construction of SAH-based
 * Bounding Volume Hierarchies", IEEE RT'07): at each node the primitive
 * centroids are binned into IL_BINS slabs per axis and the plane with the
 * lowest surface area heuristic cost
 *     C = C_trav + (A_L N_L + A_R N_R) / A_P * C_isect
 * (MacDonald & Booth 1990) is taken; a node becomes a leaf when splitting
 * does not pay and it holds few enough triangles.  The output is the flat
 * layout of kernel/kernel_bvh.h, children adjacent, triangles in leaf order. */
#include "kernel/bvh_build.h"

#include <stdlib.h>
#include <string.h>
#include "core/error.h"
#include "scene/scene.h"

#define IL_BINS 16
#define IL_MAX_LEAF 8          /* leaves never hold more, unless depth runs out */
#define IL_COST_TRAV 1.0f
#define IL_COST_ISECT 1.0f

typedef struct aabb { ilk_vec3 lo, hi; } aabb;

typedef struct builder {
    aabb *box;                 /* per triangle */
    ilk_vec3 *centroid;        /* per triangle */
    uint32_t *ref;             /* triangle indices, permuted into leaf order */
    ilk_bvh_node *nodes;
    uint32_t num_nodes;
    uint32_t depth, leaves;
} builder;

static aabb aabb_empty(void)
{
    aabb b;
    b.lo = ilk_v3(INFINITY, INFINITY, INFINITY);
    b.hi = ilk_v3(-INFINITY, -INFINITY, -INFINITY);
    return b;
}
static void aabb_grow(aabb *b, aabb o) { b->lo = ilk_vmin(b->lo, o.lo); b->hi = ilk_vmax(b->hi, o.hi); }
static void aabb_grow_p(aabb *b, ilk_vec3 p) { b->lo = ilk_vmin(b->lo, p); b->hi = ilk_vmax(b->hi, p); }
static float aabb_area(aabb b)
{
    if (b.lo.x > b.hi.x)
        return 0.0f;
    ilk_vec3 d = ilk_sub(b.hi, b.lo);
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

static void set_bounds(ilk_bvh_node *n, aabb b)
{
    n->lo[0] = b.lo.x; n->lo[1] = b.lo.y; n->lo[2] = b.lo.z;
    n->hi[0] = b.hi.x; n->hi[1] = b.hi.y; n->hi[2] = b.hi.z;
}

static void make_leaf(builder *bd, uint32_t node, uint32_t begin, uint32_t end, uint32_t depth)
{
    bd->nodes[node].first = begin;
    bd->nodes[node].count = end - begin;
    bd->leaves++;
    if (depth > bd->depth)
        bd->depth = depth;
}

/* Builds node `node` over ref[begin, end); its bounds are already set. */
static void build_node(builder *bd, uint32_t node, uint32_t begin, uint32_t end, uint32_t depth)
{
    uint32_t n = end - begin;
    aabb cb = aabb_empty();
    for (uint32_t i = begin; i < end; i++)
        aabb_grow_p(&cb, bd->centroid[bd->ref[i]]);
    float leaf_cost = IL_COST_ISECT * (float)n;
    if (n == 1 || depth + 1 >= ILK_BVH_MAX_DEPTH) {
        make_leaf(bd, node, begin, end, depth);
        return;
    }

    /* The best binned plane over the three axes. */
    const ilk_bvh_node *pn = &bd->nodes[node];
    aabb pb;
    pb.lo = ilk_v3(pn->lo[0], pn->lo[1], pn->lo[2]);
    pb.hi = ilk_v3(pn->hi[0], pn->hi[1], pn->hi[2]);
    float parea = aabb_area(pb);
    int best_axis = -1, best_bin = 0;
    float best_cost = INFINITY;
    for (int axis = 0; axis < 3; axis++) {
        float lo = ilk_comp(cb.lo, axis), hi = ilk_comp(cb.hi, axis);
        if (!(hi > lo))
            continue;
        float scale = (float)IL_BINS / (hi - lo);
        aabb bins[IL_BINS];
        uint32_t counts[IL_BINS] = {0};
        for (int b = 0; b < IL_BINS; b++)
            bins[b] = aabb_empty();
        for (uint32_t i = begin; i < end; i++) {
            uint32_t t = bd->ref[i];
            int b = (int)((ilk_comp(bd->centroid[t], axis) - lo) * scale);
            b = b < 0 ? 0 : (b >= IL_BINS ? IL_BINS - 1 : b);
            counts[b]++;
            aabb_grow(&bins[b], bd->box[t]);
        }
        /* Sweep from the right for A_R N_R, then from the left. */
        float right_cost[IL_BINS];
        aabb acc = aabb_empty();
        uint32_t cnt = 0;
        for (int b = IL_BINS - 1; b > 0; b--) {
            aabb_grow(&acc, bins[b]);
            cnt += counts[b];
            right_cost[b] = aabb_area(acc) * (float)cnt;
        }
        acc = aabb_empty();
        cnt = 0;
        for (int b = 0; b < IL_BINS - 1; b++) {
            aabb_grow(&acc, bins[b]);
            cnt += counts[b];
            if (cnt == 0 || cnt == n)
                continue;
            float cost = IL_COST_TRAV + IL_COST_ISECT * (aabb_area(acc) * (float)cnt + right_cost[b + 1]) / parea;
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_bin = b;
            }
        }
    }

    uint32_t mid;
    if (best_axis < 0 || (best_cost >= leaf_cost && n <= IL_MAX_LEAF) || !(parea > 0.0f)) {
        if (n <= IL_MAX_LEAF) {
            make_leaf(bd, node, begin, end, depth);
            return;
        }
        mid = begin + n / 2;   /* coincident centroids: split the list in two */
    } else {
        float lo = ilk_comp(cb.lo, best_axis), hi = ilk_comp(cb.hi, best_axis);
        float scale = (float)IL_BINS / (hi - lo);
        uint32_t i = begin, j = end;
        while (i < j) {
            int b = (int)((ilk_comp(bd->centroid[bd->ref[i]], best_axis) - lo) * scale);
            b = b < 0 ? 0 : (b >= IL_BINS ? IL_BINS - 1 : b);
            if (b <= best_bin) {
                i++;
            } else {
                uint32_t tmp = bd->ref[i];
                bd->ref[i] = bd->ref[--j];
                bd->ref[j] = tmp;
            }
        }
        mid = i;
        if (mid == begin || mid == end)
            mid = begin + n / 2;
    }

    uint32_t left = bd->num_nodes;
    bd->num_nodes += 2;
    bd->nodes[node].first = left;
    bd->nodes[node].count = 0;
    aabb lb = aabb_empty(), rb = aabb_empty();
    for (uint32_t i = begin; i < mid; i++)
        aabb_grow(&lb, bd->box[bd->ref[i]]);
    for (uint32_t i = mid; i < end; i++)
        aabb_grow(&rb, bd->box[bd->ref[i]]);
    set_bounds(&bd->nodes[left], lb);
    set_bounds(&bd->nodes[left + 1], rb);
    build_node(bd, left, begin, mid, depth + 1);
    build_node(bd, left + 1, mid, end, depth + 1);
}

/* Builds over tri[0..n) (n >= 1) with their boxes box[0..n) (taken from
 * the original vertices: v0 + e1 need not round back to v1); both arrays
 * are freed. */
static il_status build_tris(ilk_tri *tri, aabb *box, uint32_t n, il_kbvh *out, il_error *err)
{
    builder bd = {0};
    bd.box = box;
    bd.centroid = il_malloc(sizeof *bd.centroid * n, err);
    bd.ref = il_malloc(sizeof *bd.ref * n, err);
    bd.nodes = il_calloc(2 * (size_t)n, sizeof *bd.nodes, err);
    ilk_tri *ordered = il_malloc(sizeof *ordered * n, err);
    if (!bd.box || !bd.centroid || !bd.ref || !bd.nodes || !ordered) {
        free(tri); free(bd.box); free(bd.centroid); free(bd.ref); free(bd.nodes); free(ordered);
        return IL_ERR_MEMORY;
    }
    aabb root = aabb_empty();
    for (uint32_t k = 0; k < n; k++) {
        aabb bb = bd.box[k];
        bd.centroid[k] = ilk_scale(ilk_add(bb.lo, bb.hi), 0.5f);
        bd.ref[k] = k;
        aabb_grow(&root, bb);
    }
    bd.num_nodes = 1;
    set_bounds(&bd.nodes[0], root);
    build_node(&bd, 0, 0, n, 0);

    for (uint32_t i = 0; i < n; i++)
        ordered[i] = tri[bd.ref[i]];
    free(tri); free(bd.box); free(bd.centroid); free(bd.ref);
    ilk_bvh_node *nodes = realloc(bd.nodes, sizeof *nodes * bd.num_nodes);
    out->nodes = nodes ? nodes : bd.nodes;
    out->num_nodes = bd.num_nodes;
    out->tris = ordered;
    out->num_tris = n;
    out->depth = bd.depth;
    out->num_leaves = bd.leaves;
    return IL_OK;
}

/* The flat triangle (a, b, c) and its box. */
static void make_tri(il_vec3 a, il_vec3 b, il_vec3 c, uint32_t mesh, uint32_t prim, uint32_t pad, ilk_tri *t,
                     aabb *box)
{
    ilk_vec3 v0 = ilk_v3(a.x, a.y, a.z), v1 = ilk_v3(b.x, b.y, b.z), v2 = ilk_v3(c.x, c.y, c.z);
    t->v0 = v0;
    t->e1 = ilk_sub(v1, v0);
    t->e2 = ilk_sub(v2, v0);
    t->mesh = mesh;
    t->prim = prim;
    t->pad = pad;
    *box = aabb_empty();
    aabb_grow_p(box, v0);
    aabb_grow_p(box, v1);
    aabb_grow_p(box, v2);
}

il_status il_kbvh_build_scene(const il_scene *scene, il_kbvh *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    uint64_t total = 0;
    for (uint32_t m = 0; m < scene->num_meshes; m++)
        total += scene->meshes[m].num_triangles;
    if (total == 0)
        return IL_OK;
    if (total > (UINT32_MAX - 1) / 2)
        return il_fail(err, IL_ERR_INVALID, "BVH: %llu triangles is more than the flat layout indexes",
                       (unsigned long long)total);
    uint32_t n = (uint32_t)total;
    ilk_tri *tri = il_malloc(sizeof *tri * n, err);
    aabb *box = il_malloc(sizeof *box * n, err);
    if (!tri || !box) {
        free(tri);
        free(box);
        return IL_ERR_MEMORY;
    }
    uint32_t k = 0;
    for (uint32_t m = 0; m < scene->num_meshes; m++) {
        const il_mesh *mesh = &scene->meshes[m];
        for (uint32_t p = 0; p < mesh->num_triangles; p++, k++) {
            const uint32_t *ix = &mesh->indices[3 * p];
            make_tri(mesh->positions[ix[0]], mesh->positions[ix[1]], mesh->positions[ix[2]], m, p,
                     mesh->material, &tri[k], &box[k]);
        }
    }
    return build_tris(tri, box, n, out, err);
}

il_status il_kbvh_build_indexed(const il_vec3 *positions, const uint32_t *indices, uint32_t num_tris,
                                const uint32_t *pad, il_kbvh *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (num_tris == 0)
        return IL_OK;
    if (num_tris > (UINT32_MAX - 1) / 2)
        return il_fail(err, IL_ERR_INVALID, "BVH: %u triangles is more than the flat layout indexes", num_tris);
    ilk_tri *tri = il_malloc(sizeof *tri * num_tris, err);
    aabb *box = il_malloc(sizeof *box * num_tris, err);
    if (!tri || !box) {
        free(tri);
        free(box);
        return IL_ERR_MEMORY;
    }
    for (uint32_t p = 0; p < num_tris; p++) {
        const uint32_t *ix = &indices[3 * p];
        make_tri(positions[ix[0]], positions[ix[1]], positions[ix[2]], 0, p, pad ? pad[p] : 0, &tri[p], &box[p]);
    }
    return build_tris(tri, box, num_tris, out, err);
}

ilk_bvh il_kbvh_view(const il_kbvh *bvh)
{
    ilk_bvh v;
    v.nodes = bvh->nodes;
    v.tris = bvh->tris;
    v.num_nodes = bvh->num_nodes;
    v.num_tris = bvh->num_tris;
    return v;
}

void il_kbvh_free(il_kbvh *bvh)
{
    free(bvh->nodes);
    free(bvh->tris);
    memset(bvh, 0, sizeof *bvh);
}
