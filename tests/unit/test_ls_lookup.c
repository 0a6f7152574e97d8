/* The Linespace lookup's fast paths (methods/linespace/ls_shaft.c,
 * ls_lookup.c, ls_build.c) against the plain definitions:
 * - il_ls_find gives exactly what il_ls_cell_of, il_ls_cell_box,
 *   il_ls_locate and il_ls_shaft_index give in turn (voxel, shaft,
 *   direction, distances), for random points and directions, directions
 *   along an axis or in an axis plane, and points on voxel faces;
 * - il_ls_walk, the injection's voxel walk, reports exactly the crossings
 *   (voxel, shaft, direction, chord) of the walk through that plain chain,
 *   for random segments (inside and outside the grid, finite and not), and
 *   a segment as entering a voxel exactly when it starts before the voxel
 *   or on the face its line enters by (segments from random points of
 *   voxel faces and of voxel interiors);
 * - the in-shaft occlusion test, which reads each shaft's candidate list
 *   from its 32-byte record (the first candidates inline, the rest in the
 *   voxel's array), agrees with a brute-force test of the ray against every
 *   triangle of the scene up to the voxel's face, on the Cornell box at
 *   two grids and N (short and long lists);
 * - the coarse level after an injection (Cornell box, grid 8, N 4 and 3):
 *   each coarse entry is the measure-weighted mean of the entries of its
 *   stored shafts (an entry holds sum / (P M) whether or not it counts as
 *   filled), filled when one of them got a deposit;
 * - the wave's three-step lookup (probe, slot, read) gives what
 *   il_ls_lookup and il_ls_occluded give, bit for bit, coarse or fine, in
 *   each occlusion-test mode (none, entries holding light, every stored
 *   entry), for random points on the scene's triangles, without a coarse
 *   level (N 4 and 2) and with one (the fine threshold at 1 and 32). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "methods/linespace/ls.h"
#include "scene_build.h"

static float rnd(il_pcg32 *r) { return il_pcg32_float(r); }

/* Moeller & Trumbore 1997, in double: the distance along d, or -1; *edge
 * set when the line passes so close to an edge (barycentric 1e-5) that
 * rounding may decide. */
static double hit_dist(il_vec3 o, il_vec3 d, const il_tri_geom *g, bool *edge)
{
    double e1[3] = {g->p1.x - g->p0.x, g->p1.y - g->p0.y, g->p1.z - g->p0.z};
    double e2[3] = {g->p2.x - g->p0.x, g->p2.y - g->p0.y, g->p2.z - g->p0.z};
    double dd[3] = {d.x, d.y, d.z}, tv[3] = {o.x - g->p0.x, o.y - g->p0.y, o.z - g->p0.z};
    double pv[3] = {dd[1] * e2[2] - dd[2] * e2[1], dd[2] * e2[0] - dd[0] * e2[2], dd[0] * e2[1] - dd[1] * e2[0]};
    double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    *edge = false;
    if (fabs(det) < 1e-20)
        return -1.0;
    double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    double qv[3] = {tv[1] * e1[2] - tv[2] * e1[1], tv[2] * e1[0] - tv[0] * e1[2], tv[0] * e1[1] - tv[1] * e1[0]};
    double v = (dd[0] * qv[0] + dd[1] * qv[1] + dd[2] * qv[2]) / det;
    const double tol = 1e-5;
    *edge = u > -tol && v > -tol && u + v < 1.0 + tol && (u < tol || v < tol || u + v > 1.0 - tol);
    if (u < 0.0 || v < 0.0 || u + v > 1.0)
        return -1.0;
    return (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
}

/* A random direction; one in four along an axis, one in four in an axis
 * plane (the slab method's parallel case). */
static il_vec3 random_dir(il_pcg32 *r)
{
    il_vec3 d = il_sample_uniform_sphere(v2(rnd(r), rnd(r)));
    uint32_t kind = il_pcg32_next(r) % 4u, axis = il_pcg32_next(r) % 3u;
    float c[3] = {d.x, d.y, d.z};
    if (kind == 0) {
        float s = c[axis] < 0.0f ? -1.0f : 1.0f;
        c[0] = c[1] = c[2] = 0.0f;
        c[axis] = s;
    } else if (kind == 1) {
        c[axis] = 0.0f;
    }
    return v3_normalize(v3(c[0], c[1], c[2]));
}

static void check_find(const il_linespace *ls, il_pcg32 *r)
{
    uint32_t count = 0, bad = 0;
    for (uint32_t i = 0; i < 200000; i++) {
        float u[3] = {rnd(r), rnd(r), rnd(r)};
        if (i % 4u == 0) /* on a voxel face */
            u[i % 3u] = (float)(il_pcg32_next(r) % (ls->res[i % 3u] + 1u)) / (float)ls->res[i % 3u];
        il_vec3 p = v3(ls->lo.x + (ls->hi.x - ls->lo.x) * u[0], ls->lo.y + (ls->hi.y - ls->lo.y) * u[1],
                       ls->lo.z + (ls->hi.z - ls->lo.z) * u[2]);
        il_vec3 d = random_dir(r);
        uint32_t c[3], fi, pi, fo, po, dir = 0, shaft = 0;
        float tin = 0.0f, tout = 0.0f;
        bool want = il_ls_cell_of(ls, p, c);
        int32_t v = -1;
        if (want) {
            v = ls->cell[c[0] + ls->res[0] * (c[1] + ls->res[1] * c[2])];
            il_vec3 lo;
            il_ls_cell_box(ls, c, &lo);
            want = v >= 0 && il_ls_locate(lo, ls->vsize, ls->n, p, d, &fi, &pi, &fo, &po, &tin, &tout);
            if (want)
                shaft = il_ls_shaft_index(ls->n, fi, pi, fo, po, &dir);
        }
        uint32_t voxel2 = 0, shaft2 = 0, dir2 = 0;
        float tin2 = 0.0f, tout2 = 0.0f;
        bool got = il_ls_find(ls, p, d, &voxel2, &shaft2, &dir2, &tin2, &tout2);
        count += want;
        if (got != want || (want && ((int32_t)voxel2 != v || shaft2 != shaft || dir2 != dir ||
                                     tin2 != tin || tout2 != tout)))
            bad++;
    }
    printf("il_ls_find: %u of 200000 lines in a Linespace, %u differ from the plain chain\n", count, bad);
    CHECK(count > 10000);
    CHECK(bad == 0);
}

/* Crossings of one segment, as il_ls_walk reports them. */
typedef struct crossing {
    uint32_t voxel, shaft, dir;
    float chord;
    bool entered;
} crossing;
typedef struct crossings {
    crossing c[4096];
    uint32_t n;
} crossings;

static void record(void *user, uint32_t voxel, uint32_t shaft, uint32_t dir, float chord, bool entered)
{
    crossings *cs = user;
    if (cs->n < 4096)
        cs->c[cs->n++] = (crossing){voxel, shaft, dir, chord, entered};
}

/* The walk as first written: every cell through il_ls_cell_of,
 * il_ls_cell_box, il_ls_locate and il_ls_shaft_index. */
static void plain_walk(const il_linespace *ls, il_vec3 o, il_vec3 d, float t_end, float start_tol,
                       crossings *out)
{
    float t0 = 0.0f, t1 = t_end;
    for (int i = 0; i < 3; i++) {
        float di = v3_get(d, i), oi = v3_get(o, i);
        float lo = v3_get(ls->lo, i), hi = v3_get(ls->hi, i);
        if (di == 0.0f) {
            if (oi < lo || oi > hi)
                return;
            continue;
        }
        float a = (lo - oi) / di, b = (hi - oi) / di;
        t0 = il_maxf(t0, a < b ? a : b);
        t1 = il_minf(t1, a < b ? b : a);
    }
    if (!(t1 > t0))
        return;
    const float step_eps = 1e-5f * v3_max_comp(ls->vsize);
    float t = t0;
    for (int guard = 0; t < t1 && guard < 100000; guard++) {
        il_vec3 p = v3_fma(o, d, il_minf(t + step_eps, 0.5f * (t + t1)));
        uint32_t cc[3], fi, pi, fo, po;
        if (!il_ls_cell_of(ls, p, cc))
            return;
        il_vec3 lo;
        il_ls_cell_box(ls, cc, &lo);
        float tin, tout;
        if (!il_ls_locate(lo, ls->vsize, ls->n, p, d, &fi, &pi, &fo, &po, &tin, &tout))
            return;
        float t_next = il_minf(t1, v3_dot(v3_sub(p, o), d) + tout);
        if (!(t_next > t))
            t_next = t + step_eps;
        int32_t v = ls->cell[cc[0] + (size_t)ls->res[0] * (cc[1] + (size_t)ls->res[1] * cc[2])];
        if (v >= 0) {
            uint32_t dir, shaft = il_ls_shaft_index(ls->n, fi, pi, fo, po, &dir);
            /* Entered: the cell's entry point is not behind o, or o lies
             * on the entry face's plane (within the tolerance). */
            int axis = (int)(fi / 2u);
            float plane = v3_get(lo, axis) + ((fi & 1u) ? v3_get(ls->vsize, axis) : 0.0f);
            bool entered = v3_dot(v3_sub(p, o), d) + tin >= -step_eps ||
                           fabsf(v3_get(o, axis) - plane) <= 1e-4f * v3_max_comp(ls->vsize) + start_tol;
            record(out, (uint32_t)v, shaft, dir, tout - tin, entered);
        }
        t = t_next;
    }
}

static void check_walk(const il_linespace *ls, il_pcg32 *r)
{
    static crossings want, got;
    uint64_t total = 0;
    uint32_t bad = 0;
    il_vec3 size = v3_sub(ls->hi, ls->lo);
    for (uint32_t i = 0; i < 20000; i++) {
        /* Origins in a box 1.5 times the grid's (some outside it). */
        il_vec3 o = v3(ls->lo.x + size.x * (1.5f * rnd(r) - 0.25f), ls->lo.y + size.y * (1.5f * rnd(r) - 0.25f),
                       ls->lo.z + size.z * (1.5f * rnd(r) - 0.25f));
        il_vec3 d = random_dir(r);
        float t_end = i % 3u == 0 ? INFINITY : v3_length(size) * rnd(r);
        want.n = got.n = 0;
        plain_walk(ls, o, d, t_end, 0.0f, &want);
        il_ls_walk(ls, o, d, t_end, 0.0f, record, &got);
        total += want.n;
        bool same = want.n == got.n;
        for (uint32_t k = 0; same && k < want.n; k++)
            same = want.c[k].voxel == got.c[k].voxel && want.c[k].shaft == got.c[k].shaft &&
                   want.c[k].dir == got.c[k].dir && want.c[k].chord == got.c[k].chord &&
                   want.c[k].entered == got.c[k].entered;
        bad += !same;
    }
    printf("il_ls_walk: %llu crossings of 20000 segments, %u segments differ from the plain walk\n",
           (unsigned long long)total, bad);
    CHECK(total > 10000);
    CHECK(bad == 0);
    /* Entering: a segment from a point of a voxel's face into the voxel
     * (offset off the face by up to the tolerance) enters it, one from a
     * point well inside does not; every later voxel is entered. */
    uint32_t face_starts = 0, face_bad = 0, inside_bad = 0, later_bad = 0;
    const float tol = 1e-3f * v3_max_comp(ls->vsize);
    for (uint32_t i = 0; i < 20000; i++) {
        uint32_t cc[3] = {il_pcg32_next(r) % ls->res[0], il_pcg32_next(r) % ls->res[1], il_pcg32_next(r) % ls->res[2]};
        if (ls->cell[cc[0] + (size_t)ls->res[0] * (cc[1] + (size_t)ls->res[1] * cc[2])] < 0)
            continue;
        il_vec3 lo;
        il_ls_cell_box(ls, cc, &lo);
        il_vec3 d = random_dir(r);
        bool on_face = i % 2u == 0;
        float f[3] = {0.1f + 0.8f * rnd(r), 0.1f + 0.8f * rnd(r), 0.1f + 0.8f * rnd(r)};
        int axis = (int)(il_pcg32_next(r) % 3u);
        if (on_face) { /* the face on the side d comes from, o just inside */
            float di = v3_get(d, axis);
            if (fabsf(di) < 0.05f)
                continue;
            float off = rnd(r) * tol / v3_get(ls->vsize, axis);
            f[axis] = di > 0.0f ? off : 1.0f - off;
            face_starts++;
        }
        il_vec3 o = v3(lo.x + ls->vsize.x * f[0], lo.y + ls->vsize.y * f[1], lo.z + ls->vsize.z * f[2]);
        got.n = 0;
        il_ls_walk(ls, o, d, INFINITY, tol, record, &got);
        if (got.n == 0 || got.c[0].voxel != (uint32_t)ls->cell[cc[0] + (size_t)ls->res[0] * (cc[1] + (size_t)ls->res[1] * cc[2])])
            continue; /* o's own voxel comes first */
        /* The face at o is the entry face only if the line enters by it:
         * a start in a face's corner region may enter by another face. */
        uint32_t fi, pi, fo, po;
        float tin, tout;
        il_ls_locate(lo, ls->vsize, ls->n, o, d, &fi, &pi, &fo, &po, &tin, &tout);
        if (on_face && (int)(fi / 2u) == axis)
            face_bad += !got.c[0].entered;
        else if (!on_face)
            inside_bad += got.c[0].entered;
        /* Later voxels; the walk may step through the last one again in
         * slivers (where the grid's box ends a hair past it): not entered. */
        for (uint32_t k = 1; k < got.n; k++)
            later_bad += got.c[k].voxel != got.c[k - 1].voxel && !got.c[k].entered;
    }
    printf("il_ls_walk entering: %u starts on a face, %u not entered; %u starts inside entered; %u later voxels "
           "not entered\n",
           face_starts, face_bad, inside_bad, later_bad);
    CHECK(face_starts > 3000);
    CHECK(face_bad == 0 && inside_bad == 0 && later_bad == 0);
}

static void check_occlusion(const il_scene *s, uint32_t grid, uint32_t n, il_pcg32 *r)
{
    il_ls_settings set = {.grid = grid, .n = n};
    il_linespace ls;
    if (il_ls_build(s, &set, 1, &ls, &g_err) != IL_OK) {
        CHECK(false);
        return;
    }
    check_find(&ls, r);
    check_walk(&ls, r);
    /* Lists past the inline candidates are what this exercises. */
    uint64_t long_lists = 0;
    for (uint64_t k = 0; k < ls.num_stored; k++) {
        uint32_t info = ls.recs[k].info;
        long_lists += !(info & IL_LS_REC_OVERFLOW) &&
                      ((info >> IL_LS_REC_LEN_SHIFT) & IL_LS_REC_LEN_MASK) > IL_LS_INLINE;
    }
    float eps = 1e-4f * v3_max_comp(ls.vsize);
    uint32_t tests = 0, blocked = 0, bad = 0;
    for (uint32_t i = 0; i < 100000; i++) {
        uint32_t m = il_pcg32_next(r) % s->num_meshes;
        uint32_t t = il_pcg32_next(r) % s->meshes[m].num_triangles;
        const il_tri_geom *g = &s->meshes[m].geom[t];
        float a = rnd(r), b = rnd(r);
        if (a + b > 1.0f) {
            a = 1.0f - a;
            b = 1.0f - b;
        }
        il_vec3 x = v3_fma(v3_fma(g->p0, v3_sub(g->p1, g->p0), a), v3_sub(g->p2, g->p0), b);
        il_vec3 w = il_sample_uniform_sphere(v2(rnd(r), rnd(r)));
        uint32_t voxel, shaft, dir;
        float tin, tout;
        if (!il_ls_find(&ls, v3_fma(x, w, eps), w, &voxel, &shaft, &dir, &tin, &tout))
            continue;
        /* Brute force, up to the face short of eps (il_ls_occluded's range:
         * tout is from x + eps w);
         * a hit within a margin of either end or of a triangle's edge is
         * left out, rounding may decide it. */
        double tmax = (double)tout, margin = 1e-4 * eps;
        bool want = false, unsure = false;
        for (uint32_t mm = 0; mm < s->num_meshes; mm++)
            for (uint32_t tt = 0; tt < s->meshes[mm].num_triangles; tt++) {
                if (mm == m && tt == t)
                    continue;
                bool edge;
                double h = hit_dist(x, w, &s->meshes[mm].geom[tt], &edge);
                want |= h > eps && h < tmax;
                unsure |= fabs(h - eps) < margin || fabs(h - tmax) < margin || edge;
            }
        if (unsure)
            continue;
        bool got = il_ls_occluded(&ls, s, x, w, m, t, NULL);
        tests++;
        blocked += want;
        bad += got != want;
    }
    printf("grid %u, N %u: %llu of %llu shafts with lists past the record; %u occlusion tests, %u "
           "blocked, %u differ from brute force\n",
           grid, n, (unsigned long long)long_lists, (unsigned long long)ls.num_stored, tests, blocked, bad);
    CHECK(long_lists > 0);
    CHECK(tests > 50000);
    CHECK(blocked > 1000);
    CHECK(bad == 0);
    il_ls_free(&ls);
}

/* A random point on a random triangle of the scene, and which triangle. */
static il_vec3 random_surface_point(const il_scene *s, il_pcg32 *r, uint32_t *mesh, uint32_t *prim)
{
    *mesh = il_pcg32_next(r) % s->num_meshes;
    *prim = il_pcg32_next(r) % s->meshes[*mesh].num_triangles;
    const il_tri_geom *g = &s->meshes[*mesh].geom[*prim];
    float a = rnd(r), b = rnd(r);
    if (a + b > 1.0f) {
        a = 1.0f - a;
        b = 1.0f - b;
    }
    return v3_fma(v3_fma(g->p0, v3_sub(g->p1, g->p0), a), v3_sub(g->p2, g->p0), b);
}

typedef struct wave_counts {
    uint32_t looked, found, from_coarse, occluded, occluded_empty, differ;
} wave_counts;

/* The wave's lookup (il_ls_probe_at, il_ls_probe_slot, il_ls_read_probe)
 * against the plain one (il_ls_lookup, then il_ls_occluded where the test
 * mode says) at random surface points and directions, for each of the
 * three occlusion-test modes. */
static wave_counts compare_wave_lookup(const il_linespace *ls, const il_scene *s, il_pcg32 *r)
{
    wave_counts c = {0};
    for (uint32_t i = 0; i < 40000; i++) {
        uint32_t m, t;
        il_vec3 x = random_surface_point(s, r, &m, &t);
        il_vec3 w = il_sample_uniform_sphere(v2(rnd(r), rnd(r)));
        for (il_ls_test test = IL_LS_TEST_NONE; test <= IL_LS_TEST_ALL; test++) {
            il_vec3 L1 = v3s(0.0f), L2 = v3s(0.0f);
            bool coarse = false;
            il_ls_lookup_status read = il_ls_lookup(ls, x, w, &L1, &coarse), want = read;
            if (il_ls_tested(test, read == IL_LS_FOUND) && il_ls_occluded(ls, s, x, w, m, t, NULL))
                want = IL_LS_OCCLUDED;
            il_ls_probe pr;
            il_ls_probe_at(ls, x, w, &pr);
            il_ls_probe_slot(ls, test, &pr);
            il_ls_lookup_status got = il_ls_read_probe(ls, s, &pr, x, w, test, m, t, &L2, NULL);
            bool same = got == want && (read != IL_LS_FOUND || (L1.x == L2.x && L1.y == L2.y && L1.z == L2.z &&
                                                                 coarse == (pr.coarse != NULL)));
            c.differ += !same;
            c.looked++;
            c.found += want == IL_LS_FOUND;
            c.from_coarse += want == IL_LS_FOUND && coarse;
            c.occluded += want == IL_LS_OCCLUDED;
            c.occluded_empty += want == IL_LS_OCCLUDED && read == IL_LS_EMPTY;
        }
    }
    return c;
}

/* Without a coarse level: every test mode reads as the plain lookup does,
 * and IL_LS_TEST_ALL finds empty entries occluded too. */
static void check_wave(const il_scene *s, uint32_t n, il_pcg32 *r)
{
    il_ls_settings set = {.grid = 8, .n = n, .inject_rays = 100000, .inject_depth = 3, .solid_angle = true};
    il_linespace ls;
    il_ls_inject_result ir;
    if (il_ls_build(s, &set, 2, &ls, &g_err) != IL_OK || il_ls_inject(s, &set, 7, 2, &ls, &ir, &g_err) != IL_OK) {
        CHECK(false);
        return;
    }
    wave_counts c = compare_wave_lookup(&ls, s, r);
    printf("wave lookups, N %u, no coarse level: %u lookups, %u found, %u occluded (%u of them empty), %u "
           "differ between the wave's and the plain lookup\n",
           n, c.looked, c.found, c.occluded, c.occluded_empty, c.differ);
    CHECK(c.found > 0 && c.occluded > c.occluded_empty && c.occluded_empty > 0);
    CHECK(c.differ == 0);
    il_ls_free(&ls);
}

static void check_coarse(const il_scene *s, uint32_t n, uint32_t below, il_pcg32 *r)
{
    il_ls_settings set = {.grid = 8, .n = n, .inject_rays = 100000, .inject_depth = 3, .coarse = true,
                          .coarse_below = below, .solid_angle = true};
    il_linespace ls;
    il_ls_inject_result ir;
    if (il_ls_build(s, &set, 2, &ls, &g_err) != IL_OK || il_ls_inject(s, &set, 7, 2, &ls, &ir, &g_err) != IL_OK) {
        CHECK(false);
        return;
    }
    CHECK(ls.coarse && ls.coarse_n == il_ls_coarse_n(n));
    /* The coarse entries from the fine ones. */
    double *sum = calloc((size_t)ls.num_coarse * 7u, sizeof(double));
    uint32_t bad_value = 0, bad_filled = 0, filled = 0;
    for (uint32_t v = 0; sum && v < ls.num_voxels; v++) {
        memset(sum, 0, (size_t)ls.num_coarse * 7u * sizeof(double));
        for (uint32_t sh = 0; sh < ls.num_shafts; sh++) {
            int64_t slot = il_ls_slot(&ls, v, sh);
            if (slot < 0)
                continue;
            double *c = sum + 7u * ls.coarse_of[sh], m = ls.measure[sh];
            const il_ls_rec *rec = &ls.recs[slot];
            c[0] += m;
            for (int dir = 0; dir < 2; dir++)
                for (int k = 0; k < 3; k++)
                    c[1 + 3 * dir + k] += m * rec->rgb[dir][k];
        }
        for (uint32_t c = 0; c < ls.num_coarse; c++)
            for (uint32_t dir = 0; dir < 2; dir++) {
                const il_ls_coarse *e = il_ls_coarse_entry(&ls, v, c, dir);
                filled += e->filled != 0;
                bad_filled += (e->filled != 0) != (sum[7u * c + 1 + 3 * dir] + sum[7u * c + 2 + 3 * dir] +
                                                       sum[7u * c + 3 + 3 * dir] > 0.0);
                for (int k = 0; k < 3; k++) {
                    double want = sum[7u * c] > 0.0 ? sum[7u * c + 1 + 3 * dir + k] / sum[7u * c] : 0.0;
                    bad_value += fabs((double)e->rgb[k] - want) > 1e-5 * fabs(want) + 1e-30;
                }
            }
    }
    free(sum);
    /* The wave's lookup against the plain one. */
    wave_counts c = compare_wave_lookup(&ls, s, r);
    printf("coarse level, N %u -> %u, fine below %u deposits: %u of %u coarse entries filled, %u values and "
           "%u flags differ from the fine entries'; %u lookups, %u found (%u coarse), %u occluded, %u "
           "differ between the wave's and the plain lookup\n",
           n, ls.coarse_n, below, filled, ls.num_voxels * ls.num_coarse * 2u, bad_value, bad_filled, c.looked,
           c.found, c.from_coarse, c.occluded, c.differ);
    CHECK(filled > 0);
    CHECK(bad_value == 0 && bad_filled == 0);
    CHECK(c.from_coarse > 0 && c.occluded > 0);
    if (below == 1) /* 10^5 paths leave few entries with 32 deposits */
        CHECK(c.found > c.from_coarse);
    CHECK(c.differ == 0);
    il_ls_free(&ls);
}

int main(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    il_pcg32 r = il_pcg32_seed(17, 3);
    check_occlusion(s, 8, 4, &r);
    check_occlusion(s, 3, 2, &r);
    check_wave(s, 4, &r);
    check_wave(s, 2, &r);
    check_coarse(s, 4, 1, &r);
    check_coarse(s, 4, 32, &r);
    check_coarse(s, 3, 32, &r);
    il_scene_release(s);
    return check_report();
}
