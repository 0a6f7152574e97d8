/* Reading the Linespace (Nilles 2017, sec. 3.3): the shaft and direction of
 * a lookup, and the in-shaft occlusion test against the shaft's candidate
 * triangles (Keul et al. 2016, sec. 5: a shaft's candidates are all that a
 * ray inside it can hit in its voxel). */
#include <math.h>

#include "methods/linespace/ls.h"
#include "trace/trace.h"

/* The Linespace holding p and the line's shaft and direction for light
 * travelling along d; false when there is none. */
static bool locate(const il_linespace *ls, il_vec3 p, il_vec3 d, uint32_t *voxel, uint32_t *shaft,
                   uint32_t *dir, float *t_in, float *t_out)
{
    uint32_t c[3];
    if (!il_ls_cell_of(ls, p, c))
        return false;
    int32_t v = ls->cell[c[0] + (size_t)ls->res[0] * (c[1] + (size_t)ls->res[1] * c[2])];
    if (v < 0)
        return false;
    il_vec3 lo;
    il_ls_cell_box(ls, c, &lo);
    uint32_t fi, pi, fo, po;
    if (!il_ls_locate(lo, ls->vsize, ls->n, p, d, &fi, &pi, &fo, &po, t_in, t_out))
        return false;
    *shaft = il_ls_shaft_index(ls->n, fi, pi, fo, po, dir);
    *voxel = (uint32_t)v;
    return true;
}

/* locate, then the stored shaft's slot; -1 when there is none. */
static int64_t find(const il_linespace *ls, il_vec3 p, il_vec3 d, uint32_t *dir, float *t_in,
                    float *t_out, uint32_t *voxel)
{
    uint32_t shaft;
    if (!locate(ls, p, d, voxel, &shaft, dir, t_in, t_out))
        return -1;
    return il_ls_slot(ls, *voxel, shaft);
}

il_ls_lookup_status il_ls_lookup(const il_linespace *ls, il_vec3 p, il_vec3 w, il_vec3 *L)
{
    /* Nudged towards where the light comes from, so a point on a voxel's
     * face reads the voxel on its lit side. */
    il_vec3 q = v3_fma(p, w, 1e-4f * v3_max_comp(ls->vsize));
    uint32_t dir, voxel;
    float t_in, t_out;
    int64_t slot = find(ls, q, v3_neg(w), &dir, &t_in, &t_out, &voxel);
    if (slot < 0)
        return IL_LS_EMPTY;
    const il_ls_entry *e = &ls->entries[2u * (uint64_t)slot + dir];
    if (e->count == 0)
        return IL_LS_EMPTY;
    *L = v3(e->rgb[0], e->rgb[1], e->rgb[2]);
    return IL_LS_FOUND;
}

/* Moeller & Trumbore 1997: the ray's distance to the triangle, or -1. */
static float ray_triangle(il_vec3 o, il_vec3 d, const il_tri_geom *g)
{
    il_vec3 e1 = v3_sub(g->p1, g->p0), e2 = v3_sub(g->p2, g->p0);
    il_vec3 pv = v3_cross(d, e2);
    float det = v3_dot(e1, pv);
    if (fabsf(det) < 1e-20f)
        return -1.0f;
    float inv = 1.0f / det;
    il_vec3 tv = v3_sub(o, g->p0);
    float u = v3_dot(tv, pv) * inv;
    if (u < 0.0f || u > 1.0f)
        return -1.0f;
    il_vec3 qv = v3_cross(tv, e1);
    float v = v3_dot(d, qv) * inv;
    if (v < 0.0f || u + v > 1.0f)
        return -1.0f;
    return v3_dot(e2, qv) * inv;
}

/* The candidates of stored shaft `slot` of `voxel` against the ray from
 * org along w up to tmax. */
static bool shaft_blocks(const il_linespace *ls, const il_scene *scene, int64_t slot, uint32_t voxel,
                         il_vec3 org, il_vec3 w, float eps, float tmax, uint32_t self_mesh,
                         uint32_t self_prim)
{
    if (!(tmax > eps))
        return false;
    uint64_t base = ls->cand_base[voxel];
    uint32_t start = (uint64_t)slot == ls->first_shaft[voxel] ? 0u : ls->cand_end[slot - 1];
    uint32_t end = ls->cand_end[slot];
    if (ls->cand[base + start] == IL_LS_OVERFLOW) {
        il_ray r = {.org = org, .tmin = eps, .dir = w, .tmax = tmax};
        return il_trace_occluded(scene->tracer, &r);
    }
    uint64_t t0 = ls->first_tri[voxel];
    for (uint32_t k = start; k < end; k++) {
        uint64_t t = t0 + ls->cand[base + k];
        uint32_t m = ls->tri_mesh[t], p = ls->tri_prim[t];
        if (m == self_mesh && p == self_prim)
            continue;
        float d = ray_triangle(org, w, &scene->meshes[m].geom[p]);
        if (d > eps && d < tmax)
            return true;
    }
    return false;
}

bool il_ls_occluded(const il_linespace *ls, const il_scene *scene, il_vec3 org, il_vec3 w,
                    uint32_t self_mesh, uint32_t self_prim)
{
    float eps = 1e-4f * v3_max_comp(ls->vsize);
    uint32_t dir, voxel;
    float t_in, t_out;
    int64_t slot = find(ls, v3_fma(org, w, eps), w, &dir, &t_in, &t_out, &voxel);
    if (slot < 0)
        return false;       /* no geometry in the shaft */
    /* Up to the voxel's face, short of it: a wall lying in the face is
     * where the shaft's light comes from, not an occluder. */
    return shaft_blocks(ls, scene, slot, voxel, org, w, eps, t_out - eps, self_mesh, self_prim);
}

void il_ls_probe_at(const il_linespace *ls, il_vec3 x, il_vec3 w, il_ls_probe *pr)
{
    /* One walk for both: the light's line through x (nudged towards w)
     * travelling along -w; where it enters the voxel is where the ray from
     * x along w leaves it, t_in behind x. */
    float eps = 1e-4f * v3_max_comp(ls->vsize);
    float t_out;
    pr->slot = -1;
    pr->found = locate(ls, v3_fma(x, w, eps), v3_neg(w), &pr->voxel, &pr->shaft, &pr->dir, &pr->t_in, &t_out);
    if (pr->found)
        __builtin_prefetch(&ls->words[(size_t)pr->voxel * ls->mask_words + pr->shaft / 64u]);
}

void il_ls_probe_slot(const il_linespace *ls, bool occlusion_test, il_ls_probe *pr)
{
    if (!pr->found)
        return;
    pr->slot = il_ls_slot(ls, pr->voxel, pr->shaft);
    if (pr->slot < 0)
        return;
    __builtin_prefetch(&ls->entries[2u * (uint64_t)pr->slot + pr->dir]);
    if (occlusion_test)
        __builtin_prefetch(&ls->cand_end[pr->slot > 0 ? pr->slot - 1 : 0]);
}

il_ls_lookup_status il_ls_read_probe(const il_linespace *ls, const il_scene *scene, const il_ls_probe *pr,
                                     il_vec3 x, il_vec3 w, bool occlusion_test, uint32_t self_mesh,
                                     uint32_t self_prim, il_vec3 *L)
{
    if (pr->slot < 0)
        return IL_LS_EMPTY;
    /* The entry first, the occlusion test only for an entry holding light
     * (an empty entry gives nothing either way). */
    const il_ls_entry *e = &ls->entries[2u * (uint64_t)pr->slot + pr->dir];
    if (e->count == 0)
        return IL_LS_EMPTY;
    float eps = 1e-4f * v3_max_comp(ls->vsize);
    if (occlusion_test &&
        shaft_blocks(ls, scene, pr->slot, pr->voxel, x, w, eps, -pr->t_in, self_mesh, self_prim))
        return IL_LS_OCCLUDED;
    *L = v3(e->rgb[0], e->rgb[1], e->rgb[2]);
    return IL_LS_FOUND;
}
