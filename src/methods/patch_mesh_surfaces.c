/* Radiosity meshing, step 1: scene triangles -> surfaces -> elements.
 *
 * A surface is a set of triangles of one scene mesh (so one material) that
 * are connected through shared edges (vertices matched by exact position
 * within the mesh, as OBJ/glTF files often duplicate vertices) and do not
 * fold by more than IL_PATCH_CREASE_DEG across those edges.  Inside a surface,
 * two triangles that share an edge become one quad element when the four
 * points are coplanar and the quad is convex (greedy: each triangle tries its
 * longest edge first, which is the diagonal of a rectangle split in two);
 * the rest stay triangle elements.  A triangle repeated with the same
 * vertices and winding is meshed once.  Mirror and glass meshes are one
 * non-diffuse surface each whose triangles are copied unsplit. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/patch_mesh_internal.h"

#define IL_PATCH_CREASE_DEG 30.0
/* Coplanarity: the fourth point lies within this fraction of the quad's
 * longest diagonal of the first triangle's plane. */
#define IL_PATCH_PLANAR_TOL 1e-4
/* Convexity: every corner turns by more than asin(this) (no near-straight
 * corners, which would make a triangle-shaped quad). */
#define IL_PATCH_CONVEX_SIN 1e-3
#define NONE UINT32_MAX

typedef struct edge_entry {
    uint64_t key;       /* (min id << 32) | max id */
    uint32_t tri, local;
    bool forward;       /* the triangle runs it from min to max */
} edge_entry;

static int cmp_edge(const void *a, const void *b)
{
    const edge_entry *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->tri < y->tri ? -1 : (x->tri > y->tri);
}

/* A triangle's vertex set (sorted ids) and winding: equal keys are the same
 * triangle given twice. */
typedef struct tri_key {
    uint32_t v[3];
    uint32_t parity;
    uint32_t tri;
} tri_key;

static int cmp_tri_key(const void *a, const void *b)
{
    const tri_key *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->v[k] != y->v[k])
            return x->v[k] < y->v[k] ? -1 : 1;
    if (x->parity != y->parity)
        return x->parity < y->parity ? -1 : 1;
    return x->tri < y->tri ? -1 : (x->tri > y->tri);
}

static bool same_tri(const tri_key *x, const tri_key *y)
{
    return x->v[0] == y->v[0] && x->v[1] == y->v[1] && x->v[2] == y->v[2] && x->parity == y->parity;
}

static tri_key make_tri_key(const uint32_t o[3], uint32_t t)
{
    tri_key k = {{o[0], o[1], o[2]}, 0, t};
    /* Sort by swaps; each swap flips the parity of the permutation. */
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 2 - a; b++)
            if (k.v[b] > k.v[b + 1]) {
                uint32_t tmp = k.v[b];
                k.v[b] = k.v[b + 1];
                k.v[b + 1] = tmp;
                k.parity ^= 1;
            }
    return k;
}

static uint32_t uf_find(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

static void uf_union(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = uf_find(parent, a);
    b = uf_find(parent, b);
    /* The smaller index becomes the root: deterministic surface order. */
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

static uint32_t fbits(float f)
{
    f += 0.0f; /* -0 -> +0 */
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static uint64_t hash_pos(il_vec3 p)
{
    uint64_t h = fbits(p.x) * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) ^ fbits(p.y) * 0xC2B2AE3D27D4EB4Full;
    h ^= (h >> 31) ^ fbits(p.z) * 0x165667B19E3779F9ull;
    return h ^ (h >> 32);
}

static bool same_pos(il_vec3 a, il_vec3 b)
{
    return fbits(a.x) == fbits(b.x) && fbits(a.y) == fbits(b.y) && fbits(a.z) == fbits(b.z);
}

/* canon[v]: the first vertex of the mesh at exactly v's position. */
static il_status weld_mesh(const il_mesh *m, uint32_t *canon, il_error *err)
{
    size_t cap = 16;
    while (cap < 2 * (size_t)m->num_vertices)
        cap *= 2;
    uint32_t *slots = il_malloc(cap * sizeof *slots, err);
    if (!slots)
        return IL_ERR_MEMORY;
    memset(slots, 0xff, cap * sizeof *slots);
    for (uint32_t v = 0; v < m->num_vertices; v++) {
        size_t h = hash_pos(m->positions[v]) & (cap - 1);
        while (slots[h] != NONE && !same_pos(m->positions[slots[h]], m->positions[v]))
            h = (h + 1) & (cap - 1);
        if (slots[h] == NONE)
            slots[h] = v;
        canon[v] = slots[h];
    }
    free(slots);
    return IL_OK;
}

static il_vec3 dsub(il_vec3 a, il_vec3 b) { return v3_sub(a, b); }

static double dlen(il_vec3 a)
{
    return sqrt((double)a.x * a.x + (double)a.y * a.y + (double)a.z * a.z);
}

/* Double-precision cross product of float vectors. */
static void dcross(il_vec3 a, il_vec3 b, double out[3])
{
    out[0] = (double)a.y * b.z - (double)a.z * b.y;
    out[1] = (double)a.z * b.x - (double)a.x * b.z;
    out[2] = (double)a.x * b.y - (double)a.y * b.x;
}

/* Whether q[0..3] (counter-clockwise from the front) is a planar convex quad. */
static bool quad_ok(const il_vec3 q[4])
{
    double n[3];
    dcross(dsub(q[1], q[0]), dsub(q[3], q[0]), n);
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(nl > 0.0))
        return false;
    il_vec3 d = dsub(q[2], q[0]);
    double dist = fabs((d.x * n[0] + d.y * n[1] + d.z * n[2]) / nl);
    double size = fmax(dlen(d), dlen(dsub(q[3], q[1])));
    if (!(dist <= IL_PATCH_PLANAR_TOL * size))
        return false;
    double nq[3];
    dcross(dsub(q[2], q[0]), dsub(q[3], q[1]), nq);
    double nql = sqrt(nq[0] * nq[0] + nq[1] * nq[1] + nq[2] * nq[2]);
    if (!(nql > 0.0))
        return false;
    for (int i = 0; i < 4; i++) {
        il_vec3 a = dsub(q[i], q[(i + 3) % 4]), c = dsub(q[(i + 1) % 4], q[i]);
        double t[3];
        dcross(a, c, t);
        double turn = (t[0] * nq[0] + t[1] * nq[1] + t[2] * nq[2]) / nql;
        if (!(turn > IL_PATCH_CONVEX_SIN * dlen(a) * dlen(c)))
            return false;
    }
    return true;
}

typedef struct mesh_work {
    uint32_t *canon, *o, *parent, *nb, *comp, *order, *start;
    il_vec3 *nf;
    edge_entry *edges;
    tri_key *keys;
    bool *paired;       /* also set for dropped duplicates */
} mesh_work;

static void work_free(mesh_work *w)
{
    free(w->canon), free(w->o), free(w->parent), free(w->nb), free(w->comp);
    free(w->order), free(w->start), free(w->nf), free(w->edges), free(w->keys), free(w->paired);
    memset(w, 0, sizeof *w);
}

/* Surfaces and elements of one diffuse mesh. */
static il_status mesh_elements(const il_scene *scene, uint32_t mi, il_patch_elements *out,
                               il_error *err)
{
    const il_mesh *m = &scene->meshes[mi];
    const uint32_t T = m->num_triangles;
    mesh_work w = {0};
    w.canon = il_malloc(((size_t)m->num_vertices + 1) * sizeof *w.canon, err);
    w.o = il_malloc(3 * (size_t)T * sizeof *w.o, err);
    w.parent = il_malloc((size_t)T * sizeof *w.parent, err);
    w.nb = il_malloc(3 * (size_t)T * sizeof *w.nb, err);
    w.comp = il_malloc((size_t)T * sizeof *w.comp, err);
    w.order = il_malloc((size_t)T * sizeof *w.order, err);
    w.start = il_calloc((size_t)T + 2, sizeof *w.start, err);
    w.nf = il_malloc((size_t)T * sizeof *w.nf, err);
    w.edges = il_malloc(3 * (size_t)T * sizeof *w.edges, err);
    w.paired = il_calloc((size_t)T, sizeof *w.paired, err);
    w.keys = il_malloc(((size_t)T + 1) * sizeof *w.keys, err);
    if (!w.keys || !w.canon || !w.o || !w.parent || !w.nb || !w.comp || !w.order || !w.start ||
        !w.nf || !w.edges || !w.paired) {
        work_free(&w);
        return IL_ERR_MEMORY;
    }
    il_status st = weld_mesh(m, w.canon, err);
    if (st != IL_OK) {
        work_free(&w);
        return st;
    }

    /* Orient every triangle counter-clockwise from its front: the side of
     * the geometric normal as il_scene_surface turns it (to the vertex
     * normals' side when the mesh has normals, else the winding's). */
    const il_vec3 *P = m->positions;
    for (uint32_t t = 0; t < T; t++) {
        uint32_t *o = w.o + 3 * (size_t)t;
        for (int k = 0; k < 3; k++)
            o[k] = w.canon[m->indices[3 * (size_t)t + k]];
        il_surface s;
        il_scene_surface(scene, mi, t, 1.0f / 3.0f, 1.0f / 3.0f, &s);
        il_vec3 nw = v3_cross(v3_sub(P[o[1]], P[o[0]]), v3_sub(P[o[2]], P[o[0]]));
        if (v3_dot(nw, s.ng) < 0.0f) {
            uint32_t tmp = o[1];
            o[1] = o[2];
            o[2] = tmp;
        }
        w.nf[t] = s.ng;
        w.parent[t] = t;
        w.keys[t] = make_tri_key(o, t);
    }

    /* A triangle given twice with the same winding (files have such
     * faces: CornellBox-Original.obj's block "bottoms" repeat a side) is
     * meshed once: two coincident patches would split the light arriving
     * there between them. */
    qsort(w.keys, T, sizeof *w.keys, cmp_tri_key);
    for (uint32_t i = 1; i < T; i++)
        if (same_tri(&w.keys[i], &w.keys[i - 1]))
            w.paired[w.keys[i].tri] = true;
    size_t ne = 0;
    for (uint32_t t = 0; t < T; t++) {
        const uint32_t *o = w.o + 3 * (size_t)t;
        for (int e = 0; e < 3; e++) {
            w.nb[3 * (size_t)t + e] = NONE;
            if (w.paired[t])
                continue;
            uint32_t a = o[e], b = o[(e + 1) % 3];
            uint64_t lo = a < b ? a : b, hi = a < b ? b : a;
            w.edges[ne++] = (edge_entry){(lo << 32) | hi, t, (uint32_t)e, a < b};
        }
    }

    /* Adjacency by sorting the edges: equal keys are one shared edge. */
    const double cos_crease = cos(IL_PATCH_CREASE_DEG * 3.14159265358979323846 / 180.0);
    qsort(w.edges, ne, sizeof *w.edges, cmp_edge);
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && w.edges[j].key == w.edges[i].key)
            j++;
        /* Every smooth pair across the edge joins one surface.  The quad
         * partner across it is the one triangle (if unique) that runs the
         * edge the other way with the same facing: this also pairs the
         * front and the back of a two-sided wall given as 4 triangles. */
        size_t k = j - i;
        for (size_t a = i; a < j; a++) {
            uint32_t ta = w.edges[a].tri, partner = NONE, partners = 0;
            for (size_t b = i; b < j && k <= 16; b++) {
                uint32_t tb = w.edges[b].tri;
                if (b == a || ta == tb)
                    continue;
                float d = v3_dot(w.nf[ta], w.nf[tb]);
                if (b > a && d >= cos_crease)
                    uf_union(w.parent, ta, tb);
                if (w.edges[b].forward != w.edges[a].forward && d >= 0.99f) {
                    partner = tb;
                    partners++;
                }
            }
            if (k > 16 && a + 1 < j && v3_dot(w.nf[ta], w.nf[w.edges[a + 1].tri]) >= cos_crease)
                uf_union(w.parent, ta, w.edges[a + 1].tri);
            if (partners == 1)
                w.nb[3 * (size_t)ta + w.edges[a].local] = partner;
        }
        i = j;
    }

    /* Components in order of their first triangle; triangles grouped by
     * component (counting sort, stable). */
    uint32_t first_surface = out->num_surfaces, ncomp = 0;
    uint32_t kept = 0;
    for (uint32_t t = 0; t < T; t++) {
        if (w.paired[t]) /* a dropped duplicate: alone in its set */
            continue;
        uint32_t r = uf_find(w.parent, t);
        w.comp[t] = r == t ? ncomp++ : w.comp[r];
        w.start[w.comp[t] + 1]++;
        kept++;
    }
    for (uint32_t c = 0; c < ncomp; c++) {
        w.start[c + 1] += w.start[c];
        out->surfaces[out->num_surfaces++] =
            (il_patch_surface){.mesh = mi, .material = m->material, .diffuse = true};
    }
    for (uint32_t t = 0; t < T; t++)
        if (!w.paired[t])
            w.order[w.start[w.comp[t]]++] = t;

    /* Quads: pair each unpaired triangle with a neighbour across its
     * longest possible edge. */
    for (uint32_t i = 0; i < kept; i++) {
        uint32_t t = w.order[i];
        if (w.paired[t])
            continue;
        const uint32_t *o = w.o + 3 * (size_t)t;
        float len[3];
        int by_len[3] = {0, 1, 2};
        for (int e = 0; e < 3; e++)
            len[e] = v3_length2(v3_sub(P[o[(e + 1) % 3]], P[o[e]]));
        for (int a = 0; a < 3; a++)
            for (int b = a + 1; b < 3; b++)
                if (len[by_len[b]] > len[by_len[a]]) {
                    int tmp = by_len[a];
                    by_len[a] = by_len[b];
                    by_len[b] = tmp;
                }
        il_patch_elem el = {.surface = first_surface + w.comp[t], .num_corners = 3,
                          .src = {t, t}};
        for (int k = 0; k < 3; k++) {
            el.id[k] = o[k];
            el.p[k] = P[o[k]];
        }
        for (int r = 0; r < 3; r++) {
            int e = by_len[r];
            uint32_t u = w.nb[3 * (size_t)t + e];
            if (u == NONE || w.paired[u] || w.comp[u] != w.comp[t] ||
                v3_dot(w.nf[t], w.nf[u]) < 0.99f)
                continue;
            /* t = (z, x, y) with shared edge x->y; u has y->x and apex wv:
             * the quad z, x, wv, y is counter-clockwise like both. */
            uint32_t x = o[e], y = o[(e + 1) % 3], z = o[(e + 2) % 3], wv = NONE;
            const uint32_t *ou = w.o + 3 * (size_t)u;
            bool reversed = false;
            for (int k = 0; k < 3; k++) {
                if (ou[k] != x && ou[k] != y)
                    wv = ou[k];
                if (ou[k] == y && ou[(k + 1) % 3] == x)
                    reversed = true;
            }
            if (wv == NONE || !reversed)
                continue;
            il_vec3 q[4] = {P[z], P[x], P[wv], P[y]};
            if (!quad_ok(q))
                continue;
            el.num_corners = 4;
            const uint32_t ids[4] = {z, x, wv, y};
            for (int k = 0; k < 4; k++) {
                el.id[k] = ids[k];
                el.p[k] = q[k];
            }
            el.src[1] = u;
            w.paired[u] = true;
            break;
        }
        w.paired[t] = true;
        out->elems[out->num_elems++] = el;
    }
    work_free(&w);
    return IL_OK;
}

static bool is_diffuse(const il_material *m)
{
    return !IL_MATERIAL_IS_DELTA(m->type);
}

il_status il_patch_elements_build(const il_scene *scene, il_patch_elements *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    size_t diffuse_tris = 0, raw_tris = 0;
    for (uint32_t mi = 0; mi < scene->num_meshes; mi++) {
        const il_mesh *m = &scene->meshes[mi];
        if (is_diffuse(&scene->materials[m->material]))
            diffuse_tris += m->num_triangles;
        else
            raw_tris += m->num_triangles;
    }
    /* At most one surface and one element per triangle (shrunk below). */
    out->elems = il_malloc((diffuse_tris + 1) * sizeof *out->elems, err);
    out->surfaces = il_malloc((diffuse_tris + scene->num_meshes + 1) * sizeof *out->surfaces, err);
    out->raw = il_malloc((raw_tris + 1) * sizeof *out->raw, err);
    if (!out->elems || !out->surfaces || !out->raw) {
        il_patch_elements_free(out);
        return IL_ERR_MEMORY;
    }
    for (uint32_t mi = 0; mi < scene->num_meshes; mi++) {
        const il_mesh *m = &scene->meshes[mi];
        if (m->num_triangles == 0)
            continue;
        if (is_diffuse(&scene->materials[m->material])) {
            il_status st = mesh_elements(scene, mi, out, err);
            if (st != IL_OK) {
                il_patch_elements_free(out);
                return st;
            }
            continue;
        }
        uint32_t s = out->num_surfaces++;
        out->surfaces[s] = (il_patch_surface){.mesh = mi, .material = m->material, .diffuse = false};
        for (uint32_t t = 0; t < m->num_triangles; t++)
            out->raw[out->num_raw++] = (il_patch_raw_tri){s, t};
    }
    il_patch_surface *shrunk = realloc(out->surfaces, (out->num_surfaces + 1) * sizeof *shrunk);
    if (shrunk)
        out->surfaces = shrunk;
    return IL_OK;
}

void il_patch_elements_free(il_patch_elements *e)
{
    free(e->elems);
    free(e->surfaces);
    free(e->raw);
    memset(e, 0, sizeof *e);
}
