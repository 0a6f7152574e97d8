/* Building the grid of Linespaces (Nilles 2017, sec. 3.1; Keul et al. 2016,
 * sec. 4): a uniform grid over the scene's bounds, the triangles binned into
 * its voxels, and in every non-empty voxel the shafts that may contain
 * geometry with their candidate triangles.
 *
 * The candidate test is conservative (it may keep a triangle that misses
 * the shaft, never drops one that touches it): a triangle is kept unless
 * the bounding box of the shaft's convex hull (the hull of its two patches)
 * misses the triangle's bounding box clipped to the voxel, or the hull's
 * eight corners all lie strictly on one side of the triangle's plane.
 * Those are two of the separating axes of the exact test (Akenine-Moeller
 * 2001); the edge-cross-product axes are left out.
 *
 * Layout: no allocation per shaft.  Per voxel a bitmask of its stored
 * shafts with a rank per 64-bit word (a shaft's slot is the voxel's first
 * slot + rank + popcount below it), and per stored shaft a 32-byte record
 * (il_ls_rec: both directions' radiance and the start of its candidate
 * list with its first four candidates), the candidates past those in one
 * array. */
#define _DEFAULT_SOURCE /* madvise's MADV_HUGEPAGE (Linux) */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "methods/linespace/ls.h"
#include "methods/portal_light.h"
#include "methods/view_size.h"

typedef struct hull {
    il_vec3 lo, hi;          /* bounding box, voxel-local */
    il_vec3 c[8];            /* the patches' corners, voxel-local */
} hull;

typedef struct tri_local {
    il_vec3 lo, hi;          /* bounding box clipped to the voxel */
    il_vec3 n;               /* plane: n.x = d */
    float d;
} tri_local;

/* What one voxel's pass produces before the layout is compacted. */
typedef struct voxel_tmp {
    uint64_t *mask;
    uint32_t stored;
    uint32_t *ends;          /* per stored shaft, local end into cands */
    uint16_t *cands;
    uint32_t num_cands;
    bool oom;
} voxel_tmp;

void il_ls_free(il_linespace *ls)
{
    free(ls->cell);
    free(ls->voxel_cell);
    free(ls->words);
    free(ls->first_shaft);
    free(ls->recs);
    free(ls->cand_base);
    free(ls->cand);
    free(ls->first_tri);
    free(ls->tri_mesh);
    free(ls->tri_prim);
    free(ls->tri_base);
    free(ls->tri);
    free(ls->measure);
    free(ls->coarse_of);
    free(ls->coarse);
    memset(ls, 0, sizeof *ls);
}

uint64_t il_ls_memory(const il_linespace *ls)
{
    uint64_t cells = (uint64_t)ls->res[0] * ls->res[1] * ls->res[2];
    uint64_t v = ls->num_voxels;
    uint64_t ntri = v ? ls->tri_base[v] : 0;
    uint64_t ncand = v ? ls->cand_base[v] : 0;
    return cells * sizeof(int32_t) + v * sizeof(uint32_t) +
           v * ls->mask_words * sizeof(il_ls_word) +
           (v + 1) * sizeof(uint64_t) * 4 + ls->num_stored * sizeof(il_ls_rec) +
           ncand * sizeof(uint8_t) + ntri * sizeof(il_ls_tri) +
           (uint64_t)ls->num_shafts * sizeof(float) +
           (ls->coarse ? (uint64_t)ls->num_shafts * sizeof(uint16_t) +
                             v * ls->num_coarse * 2u * sizeof(il_ls_coarse)
                       : 0u);
}

int64_t il_ls_slot(const il_linespace *ls, uint32_t voxel, uint32_t shaft)
{
    size_t w = (size_t)voxel * ls->mask_words + shaft / 64u;
    uint64_t bit = 1ull << (shaft % 64u);
    il_ls_word word = ls->words[w];
    if (!(word.mask & bit))
        return -1;
    return (int64_t)(word.first_slot + il_ls_popcount(word.mask & (bit - 1u)));
}

/* Triangle-box overlap, conservative: bounding boxes and the plane of the
 * triangle against the box's corners (Akenine-Moeller 2001, two of its
 * axis families). */
static bool tri_box(const il_vec3 v[3], il_vec3 blo, il_vec3 bhi)
{
    il_vec3 tlo = v3_min(v[0], v3_min(v[1], v[2])), thi = v3_max(v[0], v3_max(v[1], v[2]));
    if (tlo.x > bhi.x || tlo.y > bhi.y || tlo.z > bhi.z || thi.x < blo.x || thi.y < blo.y || thi.z < blo.z)
        return false;
    il_vec3 n = v3_cross(v3_sub(v[1], v[0]), v3_sub(v[2], v[0]));
    float d = v3_dot(n, v[0]);
    /* The box's extreme corners along n. */
    il_vec3 pmax = v3(n.x >= 0 ? bhi.x : blo.x, n.y >= 0 ? bhi.y : blo.y, n.z >= 0 ? bhi.z : blo.z);
    il_vec3 pmin = v3(n.x >= 0 ? blo.x : bhi.x, n.y >= 0 ? blo.y : bhi.y, n.z >= 0 ? blo.z : bhi.z);
    return v3_dot(n, pmax) >= d && v3_dot(n, pmin) <= d;
}

static bool hull_touches(const hull *h, const tri_local *t, float eps)
{
    if (t->lo.x > h->hi.x + eps || t->lo.y > h->hi.y + eps || t->lo.z > h->hi.z + eps ||
        t->hi.x < h->lo.x - eps || t->hi.y < h->lo.y - eps || t->hi.z < h->lo.z - eps)
        return false;
    int above = 0, below = 0;
    for (int k = 0; k < 8; k++) {
        float s = v3_dot(t->n, h->c[k]) - t->d;
        above += s > eps;
        below += s < -eps;
    }
    return above < 8 && below < 8;
}

/* Zeroed room for `stored` records, 64-byte aligned so that no record
 * straddles two cache lines.  The lookups read them at random, which on 4
 * KiB pages costs a TLB miss nearly every time: a large array is asked to
 * be backed by 2 MiB pages (transparent huge pages, where the kernel has
 * them; a hint, nothing changes where it does not). */
static il_ls_rec *alloc_records(uint64_t stored)
{
    const size_t huge = (size_t)2 << 20;
    size_t bytes = ((size_t)stored * sizeof(il_ls_rec) + 63u) / 64u * 64u + 64u;
    size_t align = bytes >= huge ? huge : 64u;
    bytes = (bytes + align - 1u) / align * align;
    il_ls_rec *r = aligned_alloc(align, bytes);
    if (!r)
        return NULL;
#ifdef MADV_HUGEPAGE
    if (align == huge)
        madvise(r, bytes, MADV_HUGEPAGE);
#endif
    memset(r, 0, bytes);
    return r;
}

/* arr with room for at least `need` elements of size elem: doubled as
 * often as needed (*cap updated); NULL when out of memory (arr kept). */
static void *grow(void *arr, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return arr;
    size_t c = *cap;
    while (c < need)
        c *= 2;
    void *p = realloc(arr, c * elem);
    if (p)
        *cap = c;
    return p;
}

static void voxel_pass(const il_linespace *ls, const il_scene *scene, const hull *hulls, uint32_t v,
                       voxel_tmp *out)
{
    const uint32_t ns = ls->num_shafts;
    uint64_t t0 = ls->first_tri[v], nt = ls->first_tri[v + 1] - t0;
    out->mask = calloc(ls->mask_words, sizeof(uint64_t));
    bool dense = nt > IL_LS_DENSE;
    size_t cap = 1024, ends_cap = 256;
    out->ends = malloc(ends_cap * sizeof(uint32_t));
    out->cands = malloc(cap * sizeof(uint16_t));
    tri_local *tl = dense ? NULL : malloc((size_t)nt * sizeof(tri_local) + 1);
    if (!out->mask || !out->ends || !out->cands || (!dense && !tl)) {
        out->oom = true;
        free(tl);
        return;
    }
    uint32_t c[3] = {ls->voxel_cell[v] % ls->res[0], (ls->voxel_cell[v] / ls->res[0]) % ls->res[1],
                     ls->voxel_cell[v] / (ls->res[0] * ls->res[1])};
    il_vec3 vlo;
    il_ls_cell_box(ls, c, &vlo);
    float eps = 1e-5f * v3_max_comp(ls->vsize);
    for (uint64_t k = 0; !dense && k < nt; k++) {
        const il_tri_geom *g = &scene->meshes[ls->tri_mesh[t0 + k]].geom[ls->tri_prim[t0 + k]];
        il_vec3 a = v3_sub(g->p0, vlo), b = v3_sub(g->p1, vlo), cc = v3_sub(g->p2, vlo);
        tri_local *t = &tl[k];
        t->lo = v3_max(v3_min(a, v3_min(b, cc)), v3s(0.0f));
        t->hi = v3_min(v3_max(a, v3_max(b, cc)), ls->vsize);
        t->n = v3_normalize(v3_cross(v3_sub(b, a), v3_sub(cc, a)));
        t->d = v3_dot(t->n, a);
    }
    uint32_t stored = 0, num = 0;
    for (uint32_t s = 0; s < ns; s++) {
        uint32_t here = 0;
        bool overflow = dense;
        for (uint64_t k = 0; !dense && k < nt; k++) {
            if (!hull_touches(&hulls[s], &tl[k], eps))
                continue;
            if (here == IL_LS_MAX_CAND || nt >= IL_LS_OVERFLOW) {
                overflow = true;
                break;
            }
            uint16_t *p = grow(out->cands, &cap, num + here + 1, sizeof *p);
            if (!p)
                goto oom;
            out->cands = p;
            out->cands[num + here++] = (uint16_t)k;
        }
        if (overflow) {
            uint16_t *p = grow(out->cands, &cap, num + 1, sizeof *p);
            if (!p)
                goto oom;
            out->cands = p;
            out->cands[num] = IL_LS_OVERFLOW;
            here = 1;
        }
        if (here == 0)
            continue;   /* no geometry in this shaft: nothing stored */
        num += here;
        out->mask[s / 64u] |= 1ull << (s % 64u);
        uint32_t *e = grow(out->ends, &ends_cap, (size_t)stored + 1, sizeof *e);
        if (!e)
            goto oom;
        out->ends = e;
        out->ends[stored++] = num;
    }
    out->stored = stored;
    out->num_cands = num;
    free(tl);
    return;
oom:
    out->oom = true;
    free(tl);
}

/* Bins every triangle into the cells it overlaps: counts, then fills. */
static il_status bin_triangles(const il_scene *scene, il_linespace *ls, uint32_t **cell_first_out,
                               il_error *err)
{
    const uint64_t cells = (uint64_t)ls->res[0] * ls->res[1] * ls->res[2];
    uint32_t *count = calloc(cells + 1, sizeof(uint32_t));
    if (!count)
        return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory for the grid");
    uint32_t *tm = NULL, *tp = NULL;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t m = 0; m < scene->num_meshes; m++) {
            const il_mesh *mesh = &scene->meshes[m];
            /* A window pane is no occluder to a shaft: light passes it on a
             * straight line (trace.c), so the in-shaft test lets it through,
             * as il_trace_occluded does for shafts without candidate lists. */
            if (scene->materials[mesh->material].type == IL_MATERIAL_THIN_GLASS)
                continue;
            for (uint32_t t = 0; t < mesh->num_triangles; t++) {
                const il_tri_geom *g = &mesh->geom[t];
                il_vec3 v[3] = {g->p0, g->p1, g->p2};
                il_vec3 tlo = v3_min(v[0], v3_min(v[1], v[2])), thi = v3_max(v[0], v3_max(v[1], v[2]));
                uint32_t c0[3], c1[3];
                /* A grid over part of the scene takes the part of a
                 * triangle's box inside it. */
                if (!(tlo.x <= ls->hi.x && tlo.y <= ls->hi.y && tlo.z <= ls->hi.z && thi.x >= ls->lo.x &&
                      thi.y >= ls->lo.y && thi.z >= ls->lo.z))
                    continue;
                tlo = v3_max(tlo, ls->lo);
                thi = v3_min(thi, ls->hi);
                if (!il_ls_cell_of(ls, tlo, c0) || !il_ls_cell_of(ls, thi, c1))
                    continue;
                for (uint32_t z = c0[2]; z <= c1[2]; z++)
                    for (uint32_t y = c0[1]; y <= c1[1]; y++)
                        for (uint32_t x = c0[0]; x <= c1[0]; x++) {
                            uint32_t cc[3] = {x, y, z};
                            il_vec3 blo;
                            il_ls_cell_box(ls, cc, &blo);
                            il_vec3 pad = v3_scale(ls->vsize, 1e-4f);
                            if (!tri_box(v, v3_sub(blo, pad), v3_add(v3_add(blo, ls->vsize), pad)))
                                continue;
                            uint64_t id = x + (uint64_t)ls->res[0] * (y + (uint64_t)ls->res[1] * z);
                            if (pass == 0) {
                                count[id + 1]++;
                            } else {
                                uint32_t at = count[id]++;
                                tm[at] = m;
                                tp[at] = t;
                            }
                        }
            }
        }
        if (pass == 0) {
            for (uint64_t i = 0; i < cells; i++)
                count[i + 1] += count[i];
            uint64_t total = count[cells];
            tm = malloc(total * sizeof(uint32_t) + 4);
            tp = malloc(total * sizeof(uint32_t) + 4);
            if (!tm || !tp) {
                free(count);
                free(tm);
                free(tp);
                return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory binning triangles");
            }
        }
    }
    /* count[i] now holds the end of cell i: shift back to starts. */
    for (uint64_t i = cells; i > 0; i--)
        count[i] = count[i - 1];
    count[0] = 0;
    ls->tri_mesh = tm;
    ls->tri_prim = tp;
    *cell_first_out = count;
    return IL_OK;
}

/* The coarse level's table (each shaft's coarse shaft) and its entries,
 * zero until the injection fills them; none for N = 1 or when not asked. */
static il_status build_coarse(il_linespace *ls, const il_ls_settings *st, il_error *err)
{
    ls->coarse_n = st->coarse ? il_ls_coarse_n(ls->n) : 0u;
    if (ls->coarse_n == 0)
        return IL_OK;
    ls->num_coarse = il_ls_num_shafts(ls->coarse_n);
    ls->coarse_of = malloc(ls->num_shafts * sizeof(uint16_t));
    ls->coarse = calloc((size_t)ls->num_voxels * ls->num_coarse * 2u + 1u, sizeof(il_ls_coarse));
    if (!ls->coarse_of || !ls->coarse) {
        il_ls_free(ls);
        return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory for the coarse level");
    }
    _Static_assert(15u * (IL_LS_MAX_N / 2u) * (IL_LS_MAX_N / 2u) * (IL_LS_MAX_N / 2u) * (IL_LS_MAX_N / 2u) <=
                       65536u, "il_linespace.coarse_of: a coarse shaft fits 16 bits");
    for (uint32_t sh = 0; sh < ls->num_shafts; sh++)
        ls->coarse_of[sh] = (uint16_t)il_ls_coarse_shaft(ls->n, sh);
    return IL_OK;
}

il_status il_ls_build(const il_scene *scene, const il_ls_settings *st, int threads, il_linespace *ls,
                      il_error *err)
{
    memset(ls, 0, sizeof *ls);
    il_vec3 lo = scene->bounds_min, hi = scene->bounds_max;
    /* A shaft's entry is the mean over all its lines: in a voxel that
     * straddles a wall, the daylit lines outside are averaged with the
     * room's, and a room on a large ground got voxels of 10 m, read 18%
     * bright (docs/linespace.md, "Windows").  Where the portals' light is
     * injected (a camera inside), the grid covers the interior around what
     * the camera sees instead (il_view_interior: what it sees other than
     * through the portals, and one bounce from there), whose faces lie in
     * a box-shaped room's walls.  A point outside it traces on. */
    ls->portal_light = st->portal_light && il_portal_light_wanted(scene);
    if (ls->portal_light && il_view_interior(scene, &lo, &hi))
        ls->partial = true;
    il_vec3 ext = v3_sub(hi, lo);
    float longest = v3_max_comp(ext);
    if (!(longest > 0.0f) || !isfinite(longest))
        return il_fail(err, IL_ERR_INVALID, "linespace: the scene has no extent");
    /* A little padding, and some thickness for a flat scene. */
    il_vec3 pad = v3s(1e-4f * longest);
    for (int i = 0; i < 3; i++)
        if (v3_get(ext, i) < 1e-3f * longest) {
            float e = 0.5e-3f * longest;
            if (i == 0) { pad.x = e; }
            if (i == 1) { pad.y = e; }
            if (i == 2) { pad.z = e; }
        }
    lo = v3_sub(lo, pad);
    hi = v3_add(hi, pad);
    ext = v3_sub(hi, lo);
    longest = v3_max_comp(ext);
    ls->lo = lo;
    ls->hi = hi;
    for (int i = 0; i < 3; i++) {
        uint32_t r = (uint32_t)ceilf((float)st->grid * v3_get(ext, i) / longest - 1e-4f);
        ls->res[i] = r < 1 ? 1 : r;
    }
    ls->vsize = v3(ext.x / (float)ls->res[0], ext.y / (float)ls->res[1], ext.z / (float)ls->res[2]);
    ls->inv_vsize = v3(1.0f / ls->vsize.x, 1.0f / ls->vsize.y, 1.0f / ls->vsize.z);
    ls->n = st->n;
    ls->patch_scale = v3((float)ls->n / ls->vsize.x, (float)ls->n / ls->vsize.y, (float)ls->n / ls->vsize.z);
    ls->num_shafts = il_ls_num_shafts(st->n);
    ls->mask_words = (ls->num_shafts + 63u) / 64u;

    const uint64_t cells = (uint64_t)ls->res[0] * ls->res[1] * ls->res[2];
    uint32_t *cell_first = NULL;
    il_status s = bin_triangles(scene, ls, &cell_first, err);
    if (s != IL_OK)
        return s;
    ls->cell = malloc(cells * sizeof(int32_t));
    ls->measure = malloc(ls->num_shafts * sizeof(float));
    uint32_t nv = 0;
    for (uint64_t i = 0; i < cells; i++)
        nv += cell_first[i + 1] > cell_first[i];
    ls->num_voxels = nv;
    /* About 36 bytes per shaft (a 32-byte record, a few candidates past it):
     * refuse an upper bound beyond 4 GiB rather than be killed for it. */
    uint64_t bound = (uint64_t)nv * ls->num_shafts;
    if (bound > (1ull << 31) || bound * 36u > (4ull << 30)) {
        free(cell_first);
        il_ls_free(ls);
        return il_fail(err, IL_ERR_INVALID,
                       "linespace: %u non-empty voxels x %u shafts could take %.1f GB (limit 4; "
                       "lower --grid or --linespace-n)",
                       nv, il_ls_num_shafts(st->n), (double)bound * 36.0 / 1e9);
    }
    ls->voxel_cell = malloc((size_t)nv * sizeof(uint32_t) + 4);
    ls->first_tri = malloc(((size_t)nv + 1) * sizeof(uint64_t));
    hull *hulls = malloc(ls->num_shafts * sizeof(hull));
    voxel_tmp *tmp = calloc((size_t)nv + 1, sizeof(voxel_tmp));
    if (!ls->cell || !ls->measure || !ls->voxel_cell || !ls->first_tri || !hulls || !tmp) {
        free(cell_first);
        free(hulls);
        free(tmp);
        il_ls_free(ls);
        return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory for the grid");
    }
    /* Triangles re-indexed per Linespace (their order already is by cell). */
    nv = 0;
    for (uint64_t i = 0; i < cells; i++) {
        if (cell_first[i + 1] > cell_first[i]) {
            ls->cell[i] = (int32_t)nv;
            ls->voxel_cell[nv] = (uint32_t)i;
            ls->first_tri[nv] = cell_first[i];
            nv++;
        } else {
            ls->cell[i] = -1;
        }
    }
    ls->first_tri[nv] = cell_first[cells];
    free(cell_first);

    /* Every shaft's hull, voxel-local: the same in every voxel. */
    for (uint32_t sh = 0; sh < ls->num_shafts; sh++) {
        uint32_t fa, pa, fb, pb;
        il_ls_shaft_patches(ls->n, sh, &fa, &pa, &fb, &pb);
        hull *h = &hulls[sh];
        il_ls_patch_corners(v3s(0.0f), ls->vsize, ls->n, fa, pa, h->c);
        il_ls_patch_corners(v3s(0.0f), ls->vsize, ls->n, fb, pb, h->c + 4);
        h->lo = h->hi = h->c[0];
        for (int k = 1; k < 8; k++) {
            h->lo = v3_min(h->lo, h->c[k]);
            h->hi = v3_max(h->hi, h->c[k]);
        }
    }
    uint32_t k = 24u / ls->n;
    il_ls_shaft_measures(ls->vsize, ls->n, k < 2 ? 2 : k, ls->measure);

#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (int64_t v = 0; v < (int64_t)nv; v++)
        voxel_pass(ls, scene, hulls, (uint32_t)v, &tmp[v]);
    free(hulls);

    /* Compact: prefix sums over the voxels, then copy. */
    bool oom = false;
    uint64_t stored = 0, cands = 0, extra = 0, overflow = 0;
    for (uint32_t v = 0; v < nv; v++) {
        oom |= tmp[v].oom;
        stored += tmp[v].stored;
        cands += tmp[v].num_cands;
        for (uint32_t i = 0; !tmp[v].oom && i < tmp[v].stored; i++) {
            uint32_t len = tmp[v].ends[i] - (i ? tmp[v].ends[i - 1] : 0u);
            extra += len > IL_LS_INLINE ? len - IL_LS_INLINE : 0u;
        }
    }
    ls->words = malloc((size_t)nv * ls->mask_words * sizeof(il_ls_word) + sizeof(il_ls_word));
    ls->first_shaft = malloc(((size_t)nv + 1) * sizeof(uint64_t));
    ls->cand_base = malloc(((size_t)nv + 1) * sizeof(uint64_t));
    ls->recs = alloc_records(stored);
    ls->cand = malloc(extra * sizeof(uint8_t) + 1);
    ls->tri_base = malloc(((size_t)nv + 1) * sizeof(uint64_t));
    uint64_t ntl = 0;
    for (uint32_t v = 0; ls->tri_base && v <= nv; v++) {
        ls->tri_base[v] = ntl;
        uint64_t nt = v < nv ? ls->first_tri[v + 1] - ls->first_tri[v] : 0;
        ntl += nt <= IL_LS_DENSE ? nt : 0;
    }
    ls->tri = malloc((size_t)ntl * sizeof(il_ls_tri) + sizeof(il_ls_tri));
    if (oom || !ls->words || !ls->first_shaft || !ls->cand_base || !ls->recs || !ls->cand ||
        !ls->tri_base || !ls->tri) {
        for (uint32_t v = 0; v < nv; v++) {
            free(tmp[v].mask);
            free(tmp[v].ends);
            free(tmp[v].cands);
        }
        free(tmp);
        il_ls_free(ls);
        return il_fail(err, IL_ERR_MEMORY,
                       "linespace: out of memory for %llu shafts (lower --grid or --linespace-n)",
                       (unsigned long long)stored);
    }
    for (uint32_t v = 0; v < nv; v++) {
        uint64_t t0 = ls->first_tri[v], nt = ls->first_tri[v + 1] - t0;
        for (uint64_t q = 0; nt <= IL_LS_DENSE && q < nt; q++) {
            uint32_t m = ls->tri_mesh[t0 + q], p = ls->tri_prim[t0 + q];
            const il_tri_geom *g = &scene->meshes[m].geom[p];
            ls->tri[ls->tri_base[v] + q] = (il_ls_tri){g->p0, v3_sub(g->p1, g->p0), v3_sub(g->p2, g->p0), m, p};
        }
    }
    uint64_t sbase = 0, cbase = 0;
    for (uint32_t v = 0; v < nv; v++) {
        voxel_tmp *t = &tmp[v];
        ls->first_shaft[v] = sbase;
        ls->cand_base[v] = cbase;
        uint64_t slot = sbase;
        for (uint32_t w = 0; w < ls->mask_words; w++) {
            ls->words[(size_t)v * ls->mask_words + w] = (il_ls_word){t->mask[w], slot, {0, 0}};
            slot += (uint64_t)__builtin_popcountll(t->mask[w]);
        }
        uint32_t rest = 0; /* the voxel's candidates past the inline ones so far */
        for (uint32_t i = 0; i < t->stored; i++) {
            uint32_t start = i ? t->ends[i - 1] : 0u, len = t->ends[i] - start;
            il_ls_rec *r = &ls->recs[sbase + i];
            if (t->cands[start] == IL_LS_OVERFLOW) {
                r->info = IL_LS_REC_OVERFLOW;
                overflow++;
                continue;
            }
            r->info = rest | (len << IL_LS_REC_LEN_SHIFT);
            for (uint32_t q = 0; q < len; q++) {
                if (q < IL_LS_INLINE)
                    r->first[q] = (uint8_t)t->cands[start + q];
                else
                    ls->cand[cbase + rest++] = (uint8_t)t->cands[start + q];
            }
        }
        sbase += t->stored;
        cbase += rest;
        free(t->mask);
        free(t->ends);
        free(t->cands);
    }
    ls->first_shaft[nv] = sbase;
    ls->cand_base[nv] = cbase;
    free(tmp);
    /* The lookups read tri; the triangles' numbers served the build. */
    free(ls->tri_mesh);
    free(ls->tri_prim);
    ls->tri_mesh = ls->tri_prim = NULL;
    ls->num_stored = stored;
    ls->num_cand = cands;
    ls->num_overflow = overflow;
    return build_coarse(ls, st, err);
}
