/* Reading the Linespace (Nilles 2017, sec. 3.3): the shaft and direction of
 * a lookup, and the in-shaft occlusion test against the shaft's candidate
 * triangles (Keul et al. 2016, sec. 5: a shaft's candidates are all that a
 * ray inside it can hit in its voxel). */
#include <math.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "methods/linespace/ls.h"
#include "trace/trace.h"

/* il_ls_find, then the stored shaft's slot; -1 when there is none. */
static int64_t find(const il_linespace *ls, il_vec3 p, il_vec3 d, uint32_t *dir, float *t_in,
                    float *t_out, uint32_t *voxel)
{
    uint32_t shaft;
    if (!il_ls_find(ls, p, d, voxel, &shaft, dir, t_in, t_out))
        return -1;
    return il_ls_slot(ls, *voxel, shaft);
}

/* The coarse entry of (voxel, shaft, dir), or NULL without a coarse level. */
static inline const il_ls_coarse *coarse_of(const il_linespace *ls, uint32_t voxel, uint32_t shaft,
                                            uint32_t dir)
{
    return ls->coarse ? il_ls_coarse_entry(ls, voxel, ls->coarse_of[shaft], dir) : NULL;
}

il_ls_lookup_status il_ls_lookup(const il_linespace *ls, il_vec3 p, il_vec3 w, il_vec3 *L,
                                 bool *coarse)
{
    if (coarse)
        *coarse = false;
    /* Nudged towards where the light comes from, so a point on a voxel's
     * face reads the voxel on its lit side. */
    il_vec3 q = v3_fma(p, w, 1e-4f * v3_max_comp(ls->vsize));
    uint32_t dir, voxel, shaft;
    float t_in, t_out;
    if (!il_ls_find(ls, q, v3_neg(w), &voxel, &shaft, &dir, &t_in, &t_out))
        return IL_LS_EMPTY;
    int64_t slot = il_ls_slot(ls, voxel, shaft);
    if (slot >= 0 && (ls->recs[slot].info & IL_LS_REC_FILLED(dir))) {
        const il_ls_rec *r = &ls->recs[slot];
        *L = v3(r->rgb[dir][0], r->rgb[dir][1], r->rgb[dir][2]);
        return IL_LS_FOUND;
    }
    const il_ls_coarse *c = coarse_of(ls, voxel, shaft, dir);
    if (!c || !c->filled)
        return IL_LS_EMPTY;
    *L = v3(c->rgb[0], c->rgb[1], c->rgb[2]);
    if (coarse)
        *coarse = true;
    return IL_LS_FOUND;
}

/* Moeller & Trumbore 1997: the ray's distance to the triangle, or -1. */
static inline float ray_triangle(il_vec3 o, il_vec3 d, const il_ls_tri *g)
{
    il_vec3 e1 = g->e1, e2 = g->e2;
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

/* Whether voxel-local triangle k of the voxel whose triangles start at
 * `tris` lies on the ray from org along w within (eps, tmax). */
static inline bool cand_blocks(const il_ls_tri *tris, uint32_t k, il_vec3 org, il_vec3 w, float eps,
                               float tmax, uint32_t self_mesh, uint32_t self_prim)
{
    const il_ls_tri *g = &tris[k];
    if (g->mesh == self_mesh && g->prim == self_prim)
        return false;
    float d = ray_triangle(org, w, g);
    return d > eps && d < tmax;
}

#if defined(__SSE2__)
/* cand_blocks on up to four candidates (idx[0..count-1]) at once:
 * ray_triangle's operations lane by lane, in its order, so the same
 * answers; a lane that is past count or the triangle skipped never hits. */
static inline bool blocks4(const il_ls_tri *tris, const uint8_t *idx, uint32_t count, il_vec3 org,
                           il_vec3 w, float eps, float tmax, uint32_t self_mesh, uint32_t self_prim)
{
    __m128 p[4], a[4], b[4];
    int valid = 0;
    for (uint32_t k = 0; k < 4; k++) {
        const il_ls_tri *g = &tris[idx[k < count ? k : 0]];
        /* 16-byte loads of the 12-byte vectors: the fourth lane is the
         * next field's, transposed into a row never used. */
        p[k] = _mm_loadu_ps(&g->p0.x);
        a[k] = _mm_loadu_ps(&g->e1.x);
        b[k] = _mm_loadu_ps(&g->e2.x);
        valid |= (int)(k < count && !(g->mesh == self_mesh && g->prim == self_prim)) << k;
    }
    if (!valid)
        return false;
    _MM_TRANSPOSE4_PS(p[0], p[1], p[2], p[3]);
    _MM_TRANSPOSE4_PS(a[0], a[1], a[2], a[3]);
    _MM_TRANSPOSE4_PS(b[0], b[1], b[2], b[3]);
    const __m128 dx = _mm_set1_ps(w.x), dy = _mm_set1_ps(w.y), dz = _mm_set1_ps(w.z);
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
#define MUL _mm_mul_ps
#define SUB _mm_sub_ps
#define ADD _mm_add_ps
    /* pv = d x e2, det = e1 . pv */
    __m128 pvx = SUB(MUL(dy, b[2]), MUL(dz, b[1])), pvy = SUB(MUL(dz, b[0]), MUL(dx, b[2])),
           pvz = SUB(MUL(dx, b[1]), MUL(dy, b[0]));
    __m128 det = ADD(ADD(MUL(a[0], pvx), MUL(a[1], pvy)), MUL(a[2], pvz));
    __m128 absdet = _mm_andnot_ps(_mm_set1_ps(-0.0f), det);
    __m128 ok = _mm_cmpnlt_ps(absdet, _mm_set1_ps(1e-20f));
    __m128 inv = _mm_div_ps(one, det);
    __m128 tx = SUB(_mm_set1_ps(org.x), p[0]), ty = SUB(_mm_set1_ps(org.y), p[1]),
           tz = SUB(_mm_set1_ps(org.z), p[2]);
    __m128 u = MUL(ADD(ADD(MUL(tx, pvx), MUL(ty, pvy)), MUL(tz, pvz)), inv);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpnlt_ps(u, zero), _mm_cmpngt_ps(u, one)));
    /* qv = tv x e1 */
    __m128 qx = SUB(MUL(ty, a[2]), MUL(tz, a[1])), qy = SUB(MUL(tz, a[0]), MUL(tx, a[2])),
           qz = SUB(MUL(tx, a[1]), MUL(ty, a[0]));
    __m128 v = MUL(ADD(ADD(MUL(dx, qx), MUL(dy, qy)), MUL(dz, qz)), inv);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpnlt_ps(v, zero), _mm_cmpngt_ps(ADD(u, v), one)));
    __m128 t = MUL(ADD(ADD(MUL(b[0], qx), MUL(b[1], qy)), MUL(b[2], qz)), inv);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(t, _mm_set1_ps(eps)), _mm_cmplt_ps(t, _mm_set1_ps(tmax))));
#undef MUL
#undef SUB
#undef ADD
    return (_mm_movemask_ps(ok) & valid) != 0;
}
#endif

/* The candidates of stored shaft `slot` of `voxel` against the ray from
 * org along w up to tmax. */
static bool shaft_blocks(const il_linespace *ls, const il_scene *scene, const il_ls_rec *r, uint32_t voxel,
                         il_vec3 org, il_vec3 w, float eps, float tmax, uint32_t self_mesh,
                         uint32_t self_prim, uint64_t *rays)
{
    if (!(tmax > eps))
        return false;
    uint32_t info = r->info;
    if (info & IL_LS_REC_OVERFLOW) {
        il_ray ray = {.org = org, .tmin = eps, .dir = w, .tmax = tmax};
        if (rays)
            ++*rays;
        return il_trace_occluded(scene->tracer, &ray);
    }
    const il_ls_tri *tris = ls->tri + ls->tri_base[voxel];
    uint32_t len = (info >> IL_LS_REC_LEN_SHIFT) & IL_LS_REC_LEN_MASK;
    uint32_t in = len < IL_LS_INLINE ? len : IL_LS_INLINE;
    const uint8_t *rest = ls->cand + ls->cand_base[voxel] + (info & IL_LS_REC_START_MASK);
#if defined(__SSE2__)
    _Static_assert(IL_LS_INLINE == 4u, "blocks4 takes the inline candidates at once");
    if (blocks4(tris, r->first, in, org, w, eps, tmax, self_mesh, self_prim))
        return true;
    for (uint32_t k = 0; k + IL_LS_INLINE < len; k += 4u) {
        uint32_t m = len - IL_LS_INLINE - k;
        if (blocks4(tris, rest + k, m < 4u ? m : 4u, org, w, eps, tmax, self_mesh, self_prim))
            return true;
    }
#else
    for (uint32_t k = 0; k < in; k++)
        if (cand_blocks(tris, r->first[k], org, w, eps, tmax, self_mesh, self_prim))
            return true;
    for (uint32_t k = 0; k + IL_LS_INLINE < len; k++)
        if (cand_blocks(tris, rest[k], org, w, eps, tmax, self_mesh, self_prim))
            return true;
#endif
    return false;
}

bool il_ls_occluded(const il_linespace *ls, const il_scene *scene, il_vec3 org, il_vec3 w,
                    uint32_t self_mesh, uint32_t self_prim, uint64_t *rays)
{
    float eps = 1e-4f * v3_max_comp(ls->vsize);
    uint32_t dir, voxel;
    float t_in, t_out;
    int64_t slot = find(ls, v3_fma(org, w, eps), w, &dir, &t_in, &t_out, &voxel);
    if (slot < 0)
        return false;       /* no geometry in the shaft */
    /* Up to the voxel's face, short of it by eps (t_out is from org + eps
     * w): a wall lying in the face is where the shaft's light comes from,
     * not an occluder.  The same range as il_ls_read_probe's. */
    return shaft_blocks(ls, scene, &ls->recs[slot], voxel, org, w, eps, t_out, self_mesh, self_prim, rays);
}

void il_ls_probe_at(const il_linespace *ls, il_vec3 x, il_vec3 w, il_ls_probe *pr)
{
    /* One walk for both: the light's line through x (nudged towards w)
     * travelling along -w; where it enters the voxel is where the ray from
     * x along w leaves it, t_in behind x. */
    float eps = 1e-4f * v3_max_comp(ls->vsize);
    float t_out;
    pr->slot = -1;
    pr->coarse = NULL;
    pr->found = il_ls_find(ls, v3_fma(x, w, eps), v3_neg(w), &pr->voxel, &pr->shaft, &pr->dir, &pr->t_in, &t_out);
    if (pr->found)
        __builtin_prefetch(&ls->words[(size_t)pr->voxel * ls->mask_words + pr->shaft / 64u]);
}

void il_ls_probe_slot(const il_linespace *ls, il_ls_test test, il_ls_probe *pr)
{
    if (!pr->found)
        return;
    const il_ls_word *word = &ls->words[(size_t)pr->voxel * ls->mask_words + pr->shaft / 64u];
    uint64_t bit = 1ull << (pr->shaft % 64u);
    int64_t slot = (word->mask & bit) ? (int64_t)(word->first_slot + il_ls_popcount(word->mask & (bit - 1u))) : -1;
    if (!(word->filled[pr->dir] & bit)) {
        /* An empty entry: without a coarse level it reads as nothing (its
         * record is needed only for the candidates of IL_LS_TEST_ALL);
         * with one, the coarse entry is read instead, and the record only
         * for its candidates. */
        pr->coarse = coarse_of(ls, pr->voxel, pr->shaft, pr->dir);
        if (pr->coarse)
            __builtin_prefetch(pr->coarse);
        /* The record is fetched when the test may run on it: a coarse
         * entry counts as lit here (il_ls_read_probe checks whether it is). */
        if (!il_ls_tested(test, pr->coarse != NULL) || slot < 0)
            return;
    }
    pr->slot = slot;
    __builtin_prefetch(&ls->recs[pr->slot]);
}

il_ls_lookup_status il_ls_read_probe(const il_linespace *ls, const il_scene *scene, const il_ls_probe *pr,
                                     il_vec3 x, il_vec3 w, il_ls_test test, uint32_t self_mesh,
                                     uint32_t self_prim, il_vec3 *L, il_ray *ray)
{
    /* The entry (or the coarse one read instead) first; the occlusion test
     * on the shaft's own candidates (none when it is not stored: nothing
     * in it). */
    const il_ls_rec *r = pr->slot >= 0 ? &ls->recs[pr->slot] : NULL;
    bool lit;
    if (pr->coarse) {
        lit = pr->coarse->filled;
        if (lit)
            *L = v3(pr->coarse->rgb[0], pr->coarse->rgb[1], pr->coarse->rgb[2]);
    } else {
        lit = r && (r->info & IL_LS_REC_FILLED(pr->dir));
        if (lit)
            *L = v3(r->rgb[pr->dir][0], r->rgb[pr->dir][1], r->rgb[pr->dir][2]);
    }
    il_ls_lookup_status open = lit ? IL_LS_FOUND : IL_LS_EMPTY;
    if (!r || !il_ls_tested(test, lit))
        return open;
    float eps = 1e-4f * v3_max_comp(ls->vsize), tmax = -pr->t_in;
    if (ray && (r->info & IL_LS_REC_OVERFLOW) && tmax > eps) {
        /* shaft_blocks's ray, for the caller to trace. */
        *ray = (il_ray){.org = x, .tmin = eps, .dir = w, .tmax = tmax};
        return lit ? IL_LS_TRACE : IL_LS_TRACE_EMPTY;
    }
    if (shaft_blocks(ls, scene, r, pr->voxel, x, w, eps, tmax, self_mesh, self_prim, NULL))
        return IL_LS_OCCLUDED;
    return open;
}
