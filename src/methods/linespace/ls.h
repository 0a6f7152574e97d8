/* Linespace light injection (`--method linespace`): Nilles 2017, "Light-
 * Injection und Global Illumination mittels GPU und der Linespace
 * Datenstruktur", on the Linespace of Keul, Lemke & Mueller 2016
 * ("Accelerating spatial data structures in ray tracing through
 * precomputed line space visibility").  docs/linespace.md explains the
 * estimator, its units and the fixes made to the thesis.
 *
 * Private to this folder and its tests. */
#ifndef IL_METHODS_LS_H
#define IL_METHODS_LS_H

#include <stdbool.h>
#include <stdint.h>

#include "core/vec.h"
#include "illum/illum.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* ------------------------------------------------------------ settings */

/* Renders into the film (cleared first): builds the grid, injects, then
 * the sampling pass.  `desc` is validated by il_render. */
il_status il_ls_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err);

#define IL_LS_MAX_N 8u
#define IL_LS_MAX_GRID 256u

typedef struct il_ls_settings {
    uint32_t grid;          /* voxels along the longest side */
    uint32_t n;             /* patches per face side */
    uint64_t inject_rays;
    uint32_t inject_depth;  /* bounces of a light path (segments after the first hit) */
    float blur;             /* fraction of the smallest voxel side */
    bool occlusion_test, solid_angle;
    bool fallback;          /* an occluded entry traces on */
    bool fallback_empty;    /* so does an empty one (else it reads as no light) */
    bool coarse;            /* build a coarse level, read where an entry has */
    uint32_t coarse_below;  /* fewer deposits than this (they count as empty) */
    bool trace_first_bounce; /* read only after one non-delta bounce was traced */
    float n1, n2;           /* glossy thresholds on the Phong exponent */
    uint32_t max_depth;     /* of the camera paths */
    bool portal_light;      /* in a scene with portals and light from outside: the
                               portals' light (methods/portal_light.h) injected, the
                               grid over the interior the camera sees (ls_build.c) */
    il_linespace_step_fn on_step; /* the injection's progress and stop; NULL: none */
    void *on_step_user;
} il_ls_settings;

il_status il_ls_settings_resolve(const il_linespace_desc *d, uint32_t max_depth, il_ls_settings *out,
                                 il_error *err);

/* ----------------------------------------------------- shaft indexing */

/* Faces of a voxel: 0 -x, 1 +x, 2 -y, 3 +y, 4 -z, 5 +z (face f lies on axis
 * f/2, on the high side when f is odd).  A patch of face f is (i, j) on the
 * face's two other axes in increasing order, index i*N + j.  A shaft is an
 * unordered pair of patches on different faces: C(6N^2, 2) - 6 C(N^2, 2) =
 * 15 N^4 of them (Keul et al. 2016, sec. 3), numbered by face pair (15
 * pairs fa < fb in lexicographic order), then patch on fa, then patch on fb. */
static inline uint32_t il_ls_num_shafts(uint32_t n) { return 15u * n * n * n * n; }

/* The index of the face pair fa < fb among the 15. */
uint32_t il_ls_face_pair(uint32_t fa, uint32_t fb);

/* The shaft joining patch pa of face fa and patch pb of face fb (fa != fb,
 * either order); *dir is 0 when light travels from the lower face to the
 * higher one, 1 the other way, when (fa, pa) is where it enters. */
uint32_t il_ls_shaft_index(uint32_t n, uint32_t fa, uint32_t pa, uint32_t fb, uint32_t pb,
                           uint32_t *dir);
/* The inverse: the two faces (fa < fb) and their patches. */
void il_ls_shaft_patches(uint32_t n, uint32_t shaft, uint32_t *fa, uint32_t *pa, uint32_t *fb,
                         uint32_t *pb);

/* The line through p (inside or on the box [lo, lo+size]) travelling along
 * d: the face and patch where it enters the box and where it leaves, by the
 * slab method (Kay & Kajiya 1986).  Also the distances from p, t_in <= 0 <=
 * t_out.  False for a zero direction. */
bool il_ls_locate(il_vec3 lo, il_vec3 size, uint32_t n, il_vec3 p, il_vec3 d, uint32_t *face_in,
                  uint32_t *patch_in, uint32_t *face_out, uint32_t *patch_out, float *t_in,
                  float *t_out);

/* The four corners of patch `patch` of face f of the box. */
void il_ls_patch_corners(il_vec3 lo, il_vec3 size, uint32_t n, uint32_t face, uint32_t patch,
                         il_vec3 corners[4]);

/* Of every shaft of a box of the given size: the measure of the (point,
 * direction) pairs inside the box whose line runs through it in one
 * direction, M = int_A int_B cos(a) cos(b) / r dA dB (the chord length r
 * times the throughput cos cos / r^2 dA dB, Sbert 1996 / Santalo's line
 * measure), by the midpoint rule on k x k points per patch.  The measures
 * of all shafts add up to 2 pi V (every point, half the directions): the
 * table is scaled to that sum, and the quadrature's own sum, before that
 * scaling, is returned for the tests. */
double il_ls_shaft_measures(il_vec3 size, uint32_t n, uint32_t k, float *out);

/* ----------------------------------------------------- the structure */

/* Candidate lists hold voxel-local triangle numbers (a byte each: a voxel
 * has at most IL_LS_DENSE triangles); a shaft with more candidates than
 * IL_LS_MAX_CAND, or a voxel with more than IL_LS_DENSE triangles, is
 * marked IL_LS_REC_OVERFLOW instead: its occlusion test casts a ray
 * clipped to the voxel through the scene's BVH. */
#define IL_LS_MAX_CAND 16u
#define IL_LS_DENSE 96u
#define IL_LS_OVERFLOW 0xffffu      /* the build's marker for such a list */

/* One stored shaft, everything a lookup reads in 32 bytes (half a cache
 * line, the array 64-byte aligned: one line per lookup): the radiance
 * (W m^-2 sr^-1) of its two directions once injected, whether each holds
 * any deposit, and its candidate list, the first IL_LS_INLINE candidates
 * here and the rest in the voxel's part of `cand`. */
#define IL_LS_INLINE 4u
typedef struct il_ls_rec {
    float rgb[2][3];
    uint32_t info;                 /* IL_LS_REC_* fields below */
    uint8_t first[IL_LS_INLINE];   /* the first candidates */
} il_ls_rec;
#define IL_LS_REC_START_BITS 20u                 /* bits 0-19: start of the rest in cand, from cand_base */
#define IL_LS_REC_START_MASK ((1u << IL_LS_REC_START_BITS) - 1u)
#define IL_LS_REC_LEN_SHIFT 20u                  /* bits 20-24: the list's length, 1 to 16 */
#define IL_LS_REC_LEN_MASK 31u
#define IL_LS_REC_OVERFLOW (1u << 25)            /* no list: the occlusion test traces */
#define IL_LS_REC_FILLED(dir) (1u << (26u + (dir))) /* direction dir holds deposits (with a
                                                       coarse level: coarse_below or more) */
/* Every voxel's rest of the lists fits the 20 bits of the start. */
_Static_assert(15ull * IL_LS_MAX_N * IL_LS_MAX_N * IL_LS_MAX_N * IL_LS_MAX_N * (IL_LS_MAX_CAND - IL_LS_INLINE) <=
                   (1ull << IL_LS_REC_START_BITS),
               "il_ls_rec: candidate start out of range");
_Static_assert(IL_LS_MAX_CAND <= IL_LS_REC_LEN_MASK, "il_ls_rec: length out of range");
_Static_assert(IL_LS_DENSE <= 256u, "il_ls_rec: a candidate is one byte");
_Static_assert(sizeof(il_ls_rec) == 32u, "il_ls_rec: two per cache line");

/* 64 shafts of one Linespace: a bit per shaft stored, and the slot of the
 * first of them (the slot of a stored shaft is first_slot + the stored
 * shafts below it in the word), and per direction a bit per shaft whose
 * entry holds deposits (set by the injection, as IL_LS_REC_FILLED), so that
 * a lookup of an empty entry ends here without reading its record.  32
 * bytes: two per cache line. */
typedef struct il_ls_word {
    uint64_t mask;
    uint64_t first_slot;
    uint64_t filled[2];
} il_ls_word;

/* The bits set in x (a library call for __builtin_popcountll where the
 * target lacks the instruction: Hacker's Delight 5-1 instead). */
static inline uint32_t il_ls_popcount(uint64_t x)
{
#if defined(__POPCNT__)
    return (uint32_t)__builtin_popcountll(x);
#else
    x -= (x >> 1) & 0x5555555555555555ull;
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return (uint32_t)((x * 0x0101010101010101ull) >> 56);
#endif
}

/* A triangle of a voxel as the occlusion test wants it: its corner p0 and
 * edges e1 = p1 - p0, e2 = p2 - p0, and which triangle of the scene. */
typedef struct il_ls_tri {
    il_vec3 p0, e1, e2;
    uint32_t mesh, prim;
} il_ls_tri;

/* The coarse level (docs/linespace.md, "Coarse level"): the same voxels
 * with N_c = N / (N's smallest prime factor) patches per face side, so each
 * patch lies inside one coarse patch and each shaft inside one coarse shaft
 * (the same pair of faces).  A coarse entry holds the radiance of all the
 * light the injection left in its stored shafts, over their summed
 * measure: the mean over more lines, read where a shaft's own entry got
 * too few deposits, so that fewer lookups read an empty or noisy entry. */
typedef struct il_ls_coarse {
    float rgb[3];
    uint32_t filled;               /* 1 when some deposit reached it */
} il_ls_coarse;
/* N_c for N patches per side; 0 for N = 1 (no coarser level). */
uint32_t il_ls_coarse_n(uint32_t n);
/* The coarse shaft (at N_c = il_ls_coarse_n(n)) holding shaft `shaft` of
 * N (N > 1). */
uint32_t il_ls_coarse_shaft(uint32_t n, uint32_t shaft);

typedef struct il_linespace {
    il_vec3 lo, hi;              /* the grid's box */
    bool portal_light;           /* the portals' light is injected (st->portal_light
                                    and il_portal_light_wanted) */
    bool partial;                /* it covers only part of the scene (il_view_interior):
                                    a point outside has no Linespace */
    il_vec3 vsize;               /* one voxel */
    il_vec3 inv_vsize;           /* 1 / vsize per axis */
    il_vec3 patch_scale;         /* n / vsize per axis: patches per unit length */
    uint32_t res[3];
    uint32_t n, num_shafts, mask_words;
    int32_t *cell;               /* res[0]*res[1]*res[2]: Linespace index or -1 */
    uint32_t num_voxels;         /* Linespaces (non-empty voxels) */
    uint32_t *voxel_cell;        /* the cell of each Linespace */
    il_ls_word *words;           /* num_voxels * mask_words: shafts stored */
    uint64_t *first_shaft;       /* num_voxels + 1: prefix sums of stored shafts */
    il_ls_rec *recs;             /* per stored shaft (slot), 64-byte aligned */
    uint64_t *cand_base;         /* num_voxels + 1: prefix sums into cand */
    uint8_t *cand;               /* the lists' candidates past the first
                                    IL_LS_INLINE: voxel-local triangle numbers */
    uint64_t *first_tri;         /* num_voxels + 1: prefix sums of the triangles
                                    overlapping each voxel */
    uint32_t *tri_mesh, *tri_prim; /* those triangles, during the build only
                                    (NULL after il_ls_build) */
    uint64_t *tri_base;          /* num_voxels + 1: prefix sums into tri */
    il_ls_tri *tri;              /* the triangles of each voxel that has candidate
                                    lists (at most IL_LS_DENSE), for the
                                    occlusion test; none for a denser one */
    float *measure;              /* num_shafts: il_ls_shaft_measures of a voxel */
    uint32_t coarse_n;           /* the coarse level's patches per side; 0: none */
    uint32_t num_coarse;         /* its shafts per voxel, 15 coarse_n^4 */
    uint16_t *coarse_of;         /* num_shafts: the coarse shaft holding each shaft */
    il_ls_coarse *coarse;        /* num_voxels * num_coarse * 2: [voxel][shaft][dir] */
    uint64_t num_stored, num_cand, num_overflow;
} il_linespace;

/* The coarse entry of coarse shaft c, direction dir, of Linespace `voxel`. */
static inline il_ls_coarse *il_ls_coarse_entry(const il_linespace *ls, uint32_t voxel, uint32_t c,
                                               uint32_t dir)
{
    return &ls->coarse[((size_t)voxel * ls->num_coarse + c) * 2u + dir];
}

/* Builds the grid over the scene's bounds (or, with the portals' light,
 * the interior the camera sees: il_view_interior), bins the triangles into
 * the voxels and, in every non-empty voxel, keeps the shafts whose convex hull
 * the voxel's triangles may touch with their candidate lists. */
il_status il_ls_build(const il_scene *scene, const il_ls_settings *s, int threads, il_linespace *ls,
                      il_error *err);
void il_ls_free(il_linespace *ls);
uint64_t il_ls_memory(const il_linespace *ls);

/* The cell holding p (clamped to the grid); false outside the grid box. */
static inline bool il_ls_cell_of(const il_linespace *ls, il_vec3 p, uint32_t c[3])
{
    const float pp[3] = {p.x, p.y, p.z}, lo[3] = {ls->lo.x, ls->lo.y, ls->lo.z},
                inv[3] = {ls->inv_vsize.x, ls->inv_vsize.y, ls->inv_vsize.z};
    for (int i = 0; i < 3; i++) {
        float x = (pp[i] - lo[i]) * inv[i];
        if (!(x >= -1e-3f && x <= (float)ls->res[i] + 1e-3f))
            return false;
        int k = (int)x; /* truncation: x >= -1e-3 here, and a negative k clamps to 0 */
        c[i] = (uint32_t)(k < 0 ? 0 : (k >= (int)ls->res[i] ? (int)ls->res[i] - 1 : k));
    }
    return true;
}
/* Whether p lies in the grid's box. */
static inline bool il_ls_inside(const il_linespace *ls, il_vec3 p)
{
    return p.x >= ls->lo.x && p.y >= ls->lo.y && p.z >= ls->lo.z && p.x <= ls->hi.x && p.y <= ls->hi.y &&
           p.z <= ls->hi.z;
}
/* The stored-shaft number of (voxel, shaft), or -1 when not stored. */
int64_t il_ls_slot(const il_linespace *ls, uint32_t voxel, uint32_t shaft);
/* The box of cell c. */
static inline void il_ls_cell_box(const il_linespace *ls, const uint32_t c[3], il_vec3 *lo)
{
    *lo = v3(ls->lo.x + ls->vsize.x * (float)c[0], ls->lo.y + ls->vsize.y * (float)c[1],
             ls->lo.z + ls->vsize.z * (float)c[2]);
}
/* The Linespace holding p, and the shaft and direction of the line through
 * p travelling along d in it, with il_ls_locate's t_in and t_out; false
 * when p is outside the grid or its voxel is empty.  The same as
 * il_ls_cell_of, il_ls_cell_box, il_ls_locate and il_ls_shaft_index in
 * turn, in one pass without branches on the direction (the lookups' hot
 * path). */
bool il_ls_find(const il_linespace *ls, il_vec3 p, il_vec3 d, uint32_t *voxel, uint32_t *shaft,
                uint32_t *dir, float *t_in, float *t_out);


/* ----------------------------------------------------- injection */

/* What il_ls_walk reports for each voxel with triangles the segment
 * crosses: the voxel, the shaft and direction its line runs through there,
 * the line's chord through the voxel (from face to face, wherever the
 * segment starts or ends), and whether the segment entered the voxel
 * through its boundary: it starts before the voxel, or on (within `tol`
 * of) the face its line enters by, as light leaving a wall that lies in
 * that face does.  A segment starting inside carries light that arose in
 * the voxel (docs/linespace.md, "Injection"). */
typedef void (*il_ls_visit)(void *user, uint32_t voxel, uint32_t shaft, uint32_t dir, float chord,
                            bool entered);
/* Walks the segment o + t d, t in [0, t_end] (d unit; t_end may be
 * infinite), clipped to the grid, voxel by voxel in order, and calls
 * visit for each voxel with triangles (empty ones are crossed silently).
 * A cell's exit point decides the next cell, nudged 1e-5 voxel along d.
 * `start_tol`: how far o may lie off the surface it leaves (the ray
 * offset); a start that close to the entry face, or 10^-4 voxel closer
 * (the occlusion test's margin), counts as entering. */
void il_ls_walk(const il_linespace *ls, il_vec3 o, il_vec3 d, float t_end, float start_tol,
                il_ls_visit visit, void *user);

typedef struct il_ls_inject_result {
    uint64_t deposits;
    uint64_t rays;
    uint64_t injected;      /* light paths: s->inject_rays unless s->on_step stopped it */
    bool stopped;
} il_ls_inject_result;

/* Traces s->inject_rays light paths (keyed by seed and path index) and
 * finishes the entries: radiance = sum(flux x chord) / (paths x measure)
 * over the segments that entered each voxel (il_ls_visit). */
il_status il_ls_inject(const il_scene *scene, const il_ls_settings *s, uint64_t seed, int threads,
                       il_linespace *ls, il_ls_inject_result *out, il_error *err);

/* ----------------------------------------------------- lookup */

typedef enum il_ls_lookup_status {
    IL_LS_FOUND = 0,
    IL_LS_EMPTY,            /* outside the grid, no Linespace, shaft not stored or no deposit
                               (with a coarse level: too few, and none in the coarse entry) */
    IL_LS_OCCLUDED,         /* the in-shaft occlusion test found geometry first */
    IL_LS_TRACE,            /* il_ls_read_probe: found, unless the occlusion ray it
                               left to the caller hits something (then occluded) */
    IL_LS_TRACE_EMPTY       /* the same for an empty entry (IL_LS_TEST_ALL): empty
                               unless that ray hits something */
} il_ls_lookup_status;

/* Which entries the in-shaft occlusion test runs on: none, those holding
 * light (an empty one gives nothing either way), or every stored one (the
 * default fallback: an empty entry reads as no light unless it is
 * occluded, when it traces on as an occluded lit one does). */
typedef enum il_ls_test { IL_LS_TEST_NONE = 0, IL_LS_TEST_LIT, IL_LS_TEST_ALL } il_ls_test;
/* Whether `test` runs the occlusion test on an entry that holds light
 * (lit) or not. */
static inline bool il_ls_tested(il_ls_test test, bool lit)
{
    return test == IL_LS_TEST_ALL || (test == IL_LS_TEST_LIT && lit);
}

/* The radiance arriving at p from direction w (unit, pointing away from p)
 * as the Linespace holds it: the shaft and direction of the line through p
 * along -w in p's voxel, or its coarse entry when that one has too few
 * deposits (*coarse, when not NULL, says which was read). */
il_ls_lookup_status il_ls_lookup(const il_linespace *ls, il_vec3 p, il_vec3 w, il_vec3 *L,
                                 bool *coarse);

/* The in-shaft occlusion test: whether a triangle of the shaft's candidate
 * list (or, for an overflowing shaft, anything in the scene) lies on the
 * ray from org along w before it leaves org's voxel.  Skips triangle
 * (self_mesh, self_prim).  *rays (when not NULL) counts the ray it casts
 * for an overflowing shaft. */
bool il_ls_occluded(const il_linespace *ls, const il_scene *scene, il_vec3 org, il_vec3 w,
                    uint32_t self_mesh, uint32_t self_prim, uint64_t *rays);
/* il_ls_lookup at x and, as `test` says, il_ls_occluded from x, with
 * one walk, in three steps, each done for a whole wave of lookups before the next
 * (the sampling pass): il_ls_probe_at finds the voxel,
 * shaft and direction of (x, w) and starts fetching the shaft's bit word;
 * il_ls_probe_slot finds its slot, when its entry holds deposits (or, when
 * it holds none and the coarse level is built, the coarse entry to read
 * instead, and the slot too for the shaft's candidates), and starts
 * fetching them; il_ls_read_probe, called with the same x and w,
 * finishes the read.  The lookup is bound by cache misses on the
 * Linespace's large arrays, which a wave's probes overlap.  Given `ray`,
 * il_ls_read_probe leaves an occlusion test that must trace the scene (a
 * shaft without a candidate list) to the caller, who traces it with the
 * wave's others: it returns IL_LS_TRACE (IL_LS_TRACE_EMPTY for an empty
 * entry) with *ray and *L set. */
typedef struct il_ls_probe {
    bool found;                  /* a voxel and shaft for the line */
    uint32_t voxel, shaft, dir;
    int64_t slot;                /* -1: no record to read (none stored, or its
                                    entry empty and no coarse entry to read) */
    const il_ls_coarse *coarse;  /* the coarse entry read instead of an empty one, or NULL */
    float t_in;
} il_ls_probe;
void il_ls_probe_at(const il_linespace *ls, il_vec3 x, il_vec3 w, il_ls_probe *pr);
void il_ls_probe_slot(const il_linespace *ls, il_ls_test test, il_ls_probe *pr);
il_ls_lookup_status il_ls_read_probe(const il_linespace *ls, const il_scene *scene, const il_ls_probe *pr,
                                     il_vec3 x, il_vec3 w, il_ls_test test, uint32_t self_mesh,
                                     uint32_t self_prim, il_vec3 *L, il_ray *ray);

#endif
