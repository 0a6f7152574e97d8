/* Radiosity meshing, step 3: the builder that grows an il_patch_mesh.
 *
 * Vertices are welded by exact position within one surface (a hash table of
 * vertex ids keyed by surface and position bits); the subdivision computes
 * shared points bitwise-equal on purpose (il_patch_edge_point), so no tolerance
 * is needed, and vertices of different surfaces are never merged. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/patch_mesh_internal.h"
#include "scene/bsdf.h"

#define NONE UINT32_MAX

static uint32_t fbits(float f)
{
    f += 0.0f; /* -0 -> +0 */
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static size_t hash_key(uint32_t surface, il_vec3 p)
{
    uint64_t h = (surface + 1) * 0xD6E8FEB86659FD93ull;
    h ^= fbits(p.x) * 0x9E3779B97F4A7C15ull;
    h ^= (h >> 29) ^ fbits(p.y) * 0xC2B2AE3D27D4EB4Full;
    h ^= (h >> 31) ^ fbits(p.z) * 0x165667B19E3779F9ull;
    return (size_t)(h ^ (h >> 32));
}

static bool same_key(const il_patch_mesh *m, uint32_t id, uint32_t surface, il_vec3 p)
{
    il_vec3 q = m->positions[id];
    return m->vertex_surface[id] == surface && fbits(q.x) == fbits(p.x) &&
           fbits(q.y) == fbits(p.y) && fbits(q.z) == fbits(p.z);
}

/* The slot holding (surface, p), or the empty slot where it belongs. */
static size_t find_slot(const il_patch_builder *b, uint32_t surface, il_vec3 p)
{
    size_t h = hash_key(surface, p) & b->slot_mask;
    while (b->slots[h] != NONE && !same_key(b->m, b->slots[h], surface, p))
        h = (h + 1) & b->slot_mask;
    return h;
}

static bool grow(void **ptr, size_t *cap, size_t need, size_t elem, il_patch_builder *b)
{
    if (need <= *cap)
        return true;
    size_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *p = realloc(*ptr, c * elem);
    if (!p) {
        il_fail(b->err, IL_ERR_MEMORY, "radiosity: out of memory while meshing");
        return false;
    }
    *ptr = p;
    *cap = c;
    return true;
}

static bool rehash(il_patch_builder *b, size_t cap)
{
    uint32_t *slots = malloc(cap * sizeof *slots);
    if (!slots) {
        il_fail(b->err, IL_ERR_MEMORY, "radiosity: out of memory while meshing");
        return false;
    }
    memset(slots, 0xff, cap * sizeof *slots);
    free(b->slots);
    b->slots = slots;
    b->slot_mask = cap - 1;
    for (uint32_t v = 0; v < b->m->num_vertices; v++) {
        size_t h = find_slot(b, b->m->vertex_surface[v], b->m->positions[v]);
        if (b->slots[h] == NONE)
            b->slots[h] = v;
    }
    return true;
}

il_status il_patch_builder_init(il_patch_builder *b, const il_scene *scene, size_t expect_vertices,
                              size_t expect_patches, size_t expect_tris, il_error *err)
{
    memset(b, 0, sizeof *b);
    b->scene = scene;
    b->err = err;
    b->m = il_calloc(1, sizeof *b->m, err);
    if (!b->m)
        return IL_ERR_MEMORY;
    il_patch_mesh *m = b->m;
    size_t nv = expect_vertices + 2, np = expect_patches + 1, nt = expect_tris + 1;
    m->positions = il_malloc(nv * sizeof *m->positions, err);
    m->vertex_surface = il_malloc(nv * sizeof *m->vertex_surface, err);
    m->patches = il_malloc(np * sizeof *m->patches, err);
    m->tri_indices = il_malloc(3 * nt * sizeof *m->tri_indices, err);
    m->tri_patch = il_malloc(nt * sizeof *m->tri_patch, err);
    m->tri_src_mesh = il_malloc(nt * sizeof *m->tri_src_mesh, err);
    m->tri_src_prim = il_malloc(nt * sizeof *m->tri_src_prim, err);
    if (!m->positions || !m->vertex_surface || !m->patches || !m->tri_indices || !m->tri_patch ||
        !m->tri_src_mesh || !m->tri_src_prim) {
        il_patch_builder_abort(b);
        return IL_ERR_MEMORY;
    }
    b->cap_vertices = nv;
    b->cap_patches = np;
    b->cap_tris = nt;
    size_t cap = 64;
    while (cap < 2 * nv)
        cap *= 2;
    if (!rehash(b, cap)) {
        il_patch_builder_abort(b);
        return IL_ERR_MEMORY;
    }
    return IL_OK;
}

uint32_t il_patch_builder_vertex(il_patch_builder *b, uint32_t surface, il_vec3 p)
{
    il_patch_mesh *m = b->m;
    size_t h = find_slot(b, surface, p);
    if (b->slots[h] != NONE)
        return b->slots[h];
    if (m->num_vertices >= UINT32_MAX - 2) {
        il_fail(b->err, IL_ERR_MEMORY, "radiosity: too many vertices");
        return NONE;
    }
    size_t need = (size_t)m->num_vertices + 2; /* one spare for Embree's padding */
    if (need > b->cap_vertices) {
        size_t cv = b->cap_vertices, cs = b->cap_vertices;
        if (!grow((void **)&m->positions, &cv, need, sizeof *m->positions, b) ||
            !grow((void **)&m->vertex_surface, &cs, need, sizeof *m->vertex_surface, b))
            return NONE; /* both grow to the same capacity */
        b->cap_vertices = cv;
    }
    uint32_t id = m->num_vertices++;
    m->positions[id] = p;
    m->vertex_surface[id] = surface;
    if (2 * (size_t)m->num_vertices > b->slot_mask + 1) {
        if (!rehash(b, 2 * (b->slot_mask + 1)))
            return NONE;
    } else {
        b->slots[h] = id;
    }
    return id;
}

static bool reserve_tris(il_patch_builder *b, size_t more)
{
    il_patch_mesh *m = b->m;
    size_t need = (size_t)m->num_tris + more;
    if (need <= b->cap_tris)
        return true;
    size_t c0 = b->cap_tris, c1 = c0, c2 = c0, ci = 3 * c0;
    if (!grow((void **)&m->tri_patch, &c0, need, sizeof(uint32_t), b) ||
        !grow((void **)&m->tri_src_mesh, &c1, c0, sizeof(uint32_t), b) ||
        !grow((void **)&m->tri_src_prim, &c2, c0, sizeof(uint32_t), b) ||
        !grow((void **)&m->tri_indices, &ci, 3 * c0, sizeof(uint32_t), b))
        return false;
    b->cap_tris = c0;
    return true;
}

static void push_tri(il_patch_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t patch,
                     uint32_t mesh, uint32_t prim)
{
    uint32_t t = m->num_tris++;
    m->tri_indices[3 * (size_t)t] = a;
    m->tri_indices[3 * (size_t)t + 1] = b;
    m->tri_indices[3 * (size_t)t + 2] = c;
    m->tri_patch[t] = patch;
    m->tri_src_mesh[t] = mesh;
    m->tri_src_prim[t] = prim;
}

/* Barycentrics (b1, b2) of p in scene triangle (mesh, prim), by least squares
 * in the triangle's plane (Ericson, "Real-Time Collision Detection", 2005,
 * section 3.4); returns the smallest of b0, b1, b2 (>= 0 inside). */
static double barycentric(const il_mesh *sm, uint32_t prim, il_vec3 p, double *b1, double *b2)
{
    const uint32_t *t = sm->indices + 3 * (size_t)prim;
    il_vec3 a = sm->positions[t[0]], e1 = v3_sub(sm->positions[t[1]], a),
            e2 = v3_sub(sm->positions[t[2]], a), d = v3_sub(p, a);
    double d11 = (double)v3_dot(e1, e1), d12 = (double)v3_dot(e1, e2), d22 = (double)v3_dot(e2, e2);
    double dp1 = (double)v3_dot(d, e1), dp2 = (double)v3_dot(d, e2);
    double den = d11 * d22 - d12 * d12;
    if (!(den > 0.0)) {
        *b1 = *b2 = 1.0 / 3.0;
        return -1e30;
    }
    *b1 = (d22 * dp1 - d12 * dp2) / den;
    *b2 = (d11 * dp2 - d12 * dp1) / den;
    return fmin(1.0 - *b1 - *b2, fmin(*b1, *b2));
}

/* The candidate scene triangle that contains p best, and p's barycentrics
 * in it (clamped into the triangle). */
static uint32_t locate(const il_mesh *sm, const uint32_t *cand, uint32_t num_cand, il_vec3 p,
                       float *b1, float *b2)
{
    uint32_t best = cand[0];
    double best_score = -1e300, bb1 = 1.0 / 3.0, bb2 = 1.0 / 3.0;
    for (uint32_t c = 0; c < num_cand; c++) {
        double x1, x2, score = barycentric(sm, cand[c], p, &x1, &x2);
        if (score > best_score) {
            best_score = score;
            best = cand[c];
            bb1 = x1;
            bb2 = x2;
        }
    }
    bb1 = fmin(fmax(bb1, 0.0), 1.0);
    bb2 = fmin(fmax(bb2, 0.0), 1.0 - bb1);
    *b1 = (float)bb1;
    *b2 = (float)bb2;
    return best;
}

/* The diffuse albedo the path tracer uses at p (il_bsdf_init: texture,
 * clamping, Phong energy scaling). */
static il_vec3 albedo_at(const il_scene *scene, uint32_t mesh, const uint32_t *cand,
                         uint32_t num_cand, il_vec3 p)
{
    float b1, b2;
    uint32_t prim = locate(&scene->meshes[mesh], cand, num_cand, p, &b1, &b2);
    il_surface s;
    il_scene_surface(scene, mesh, prim, b1, b2, &s);
    il_bsdf bsdf;
    il_bsdf_init(&bsdf, scene, &s);
    return bsdf.diffuse;
}

static il_vec3 dvec(const double d[3]) { return v3((float)d[0], (float)d[1], (float)d[2]); }

static void dcross(il_vec3 a, il_vec3 b, double out[3])
{
    out[0] = (double)a.y * b.z - (double)a.z * b.y;
    out[1] = (double)a.z * b.x - (double)a.x * b.z;
    out[2] = (double)a.x * b.y - (double)a.y * b.x;
}

static double dnorm(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

il_status il_patch_builder_patch(il_patch_builder *b, uint32_t surface, uint32_t num_corners,
                               const uint32_t v[4], const uint32_t *cand, uint32_t num_cand)
{
    il_patch_mesh *m = b->m;
    const il_scene *scene = b->scene;
    const il_patch_surface *surf = &m->surfaces[surface];
    il_vec3 c[4];
    for (uint32_t k = 0; k < num_corners; k++)
        c[k] = m->positions[v[k]];

    /* Area and normal: half the cross product of the edges (triangle) or of
     * the diagonals (planar quad); centre: the area-weighted centroid of the
     * quad's two triangles. */
    double n[3], center[3];
    if (num_corners == 3) {
        dcross(v3_sub(c[1], c[0]), v3_sub(c[2], c[0]), n);
        for (int k = 0; k < 3; k++)
            center[k] = ((double)v3_get(c[0], k) + v3_get(c[1], k) + v3_get(c[2], k)) / 3.0;
    } else {
        dcross(v3_sub(c[2], c[0]), v3_sub(c[3], c[1]), n);
        double t1[3], t2[3];
        dcross(v3_sub(c[1], c[0]), v3_sub(c[2], c[0]), t1);
        dcross(v3_sub(c[2], c[0]), v3_sub(c[3], c[0]), t2);
        double a1 = dnorm(t1), a2 = dnorm(t2);
        if (!(a1 + a2 > 0.0))
            return IL_OK;
        for (int k = 0; k < 3; k++) {
            double p0 = v3_get(c[0], k), p2 = v3_get(c[2], k);
            center[k] = (a1 * (p0 + v3_get(c[1], k) + p2) + a2 * (p0 + p2 + v3_get(c[3], k))) /
                        (3.0 * (a1 + a2));
        }
    }
    double len = dnorm(n);
    float area = (float)(0.5 * len);
    if (!(area > 0.0f) || !isfinite(area))
        return IL_OK; /* zero-area patch: skipped, never divided by */

    il_patch p = {.num_corners = num_corners, .surface = surface};
    memcpy(p.v, v, num_corners * sizeof *v);
    p.normal = v3((float)(n[0] / len), (float)(n[1] / len), (float)(n[2] / len));
    p.area = area;
    p.center = dvec(center);

    /* rho: the albedo averaged over 4 points (the centroids of the 4
     * midpoint children of a triangle; the 2x2 stratified points of a quad,
     * weighted by the bilinear map's Jacobian).  One look-up suffices
     * without a texture. */
    const il_material *mat = &scene->materials[surf->material];
    const il_mesh *sm = &scene->meshes[surf->mesh];
    if (mat->diffuse_texture == 0 || !sm->uvs) {
        p.rho = albedo_at(scene, surf->mesh, cand, num_cand, p.center);
    } else if (num_corners == 3) {
        static const float w[4][3] = {{4, 1, 1}, {1, 4, 1}, {1, 1, 4}, {2, 2, 2}};
        il_vec3 sum = v3s(0.0f);
        for (int s = 0; s < 4; s++) {
            il_vec3 q = v3_scale(v3_add(v3_add(v3_scale(c[0], w[s][0]), v3_scale(c[1], w[s][1])),
                                        v3_scale(c[2], w[s][2])), 1.0f / 6.0f);
            sum = v3_add(sum, albedo_at(scene, surf->mesh, cand, num_cand, q));
        }
        p.rho = v3_scale(sum, 0.25f);
    } else {
        il_vec3 sum = v3s(0.0f);
        float wsum = 0.0f;
        for (int s = 0; s < 4; s++) {
            float u = (s & 1) ? 0.75f : 0.25f, vv = (s & 2) ? 0.75f : 0.25f;
            il_vec3 q = v3_add(
                v3_add(v3_scale(c[0], (1 - u) * (1 - vv)), v3_scale(c[1], u * (1 - vv))),
                v3_add(v3_scale(c[2], u * vv), v3_scale(c[3], (1 - u) * vv)));
            /* dP/du and dP/dv of the bilinear map. */
            il_vec3 du = v3_add(v3_scale(v3_sub(c[1], c[0]), 1 - vv),
                                v3_scale(v3_sub(c[2], c[3]), vv));
            il_vec3 dv = v3_add(v3_scale(v3_sub(c[3], c[0]), 1 - u),
                                v3_scale(v3_sub(c[2], c[1]), u));
            float jac = v3_length(v3_cross(du, dv));
            sum = v3_fma(sum, albedo_at(scene, surf->mesh, cand, num_cand, q), jac);
            wsum += jac;
        }
        p.rho = wsum > 0.0f ? v3_scale(sum, 1.0f / wsum)
                            : albedo_at(scene, surf->mesh, cand, num_cand, p.center);
    }
    /* Emission from the front only, also for two-sided emitters: a patch
     * has one side (their back would need a second, opposite patch). */
    p.emission = mat->emission;

    uint32_t src[2];
    float b1, b2;
    if (num_corners == 3) {
        src[0] = locate(sm, cand, num_cand, p.center, &b1, &b2);
        src[1] = src[0];
    } else {
        il_vec3 g0 = v3_scale(v3_add(v3_add(c[0], c[1]), c[2]), 1.0f / 3.0f);
        il_vec3 g1 = v3_scale(v3_add(v3_add(c[0], c[2]), c[3]), 1.0f / 3.0f);
        src[0] = locate(sm, cand, num_cand, g0, &b1, &b2);
        src[1] = locate(sm, cand, num_cand, g1, &b1, &b2);
    }
    const uint32_t src_mesh[2] = {surf->mesh, surf->mesh};
    return il_patch_builder_copy_patch(b, &p, src_mesh, src);
}

il_status il_patch_builder_copy_patch(il_patch_builder *b, const il_patch *p,
                                    const uint32_t src_mesh[2], const uint32_t src_prim[2])
{
    il_patch_mesh *m = b->m;
    if (m->num_patches >= UINT32_MAX - 1)
        return il_fail(b->err, IL_ERR_MEMORY, "radiosity: too many patches");
    if (!grow((void **)&m->patches, &b->cap_patches, (size_t)m->num_patches + 1, sizeof *m->patches,
              b) ||
        !reserve_tris(b, 2))
        return IL_ERR_MEMORY;
    uint32_t id = m->num_patches++;
    m->patches[id] = *p;
    push_tri(m, p->v[0], p->v[1], p->v[2], id, src_mesh[0], src_prim[0]);
    if (p->num_corners == 4)
        push_tri(m, p->v[0], p->v[2], p->v[3], id, src_mesh[1], src_prim[1]);
    return IL_OK;
}

il_status il_patch_builder_raw_tri(il_patch_builder *b, const uint32_t v[3], uint32_t mesh,
                                 uint32_t prim)
{
    if (!reserve_tris(b, 1))
        return IL_ERR_MEMORY;
    push_tri(b->m, v[0], v[1], v[2], IL_NO_PATCH, mesh, prim);
    return IL_OK;
}

static void *shrink(void *p, size_t bytes)
{
    void *q = realloc(p, bytes ? bytes : 1);
    return q ? q : p;
}

/* The triangles' panes (thin_glass), for the tracer and the hemicube;
 * none allocated when the scene has no pane. */
static il_status mesh_panes(const il_scene *scene, il_patch_mesh *m, il_error *err)
{
    bool any = false;
    for (uint32_t i = 0; i < scene->num_materials; i++)
        any |= scene->materials[i].type == IL_MATERIAL_THIN_GLASS;
    if (!any)
        return IL_OK;
    m->tri_panes = il_calloc((size_t)m->num_tris + 1, sizeof *m->tri_panes, err);
    if (!m->tri_panes)
        return IL_ERR_MEMORY;
    for (uint32_t t = 0; t < m->num_tris; t++) {
        const il_material *mat = &scene->materials[scene->meshes[m->tri_src_mesh[t]].material];
        if (mat->type == IL_MATERIAL_THIN_GLASS)
            m->tri_panes[t] = (il_trace_pane){.ior = mat->ior, .tau = mat->pane_tau};
    }
    return IL_OK;
}

il_status il_patch_builder_finish(il_patch_builder *b, il_patch_mesh **out)
{
    il_patch_mesh *m = b->m;
    free(b->slots);
    b->slots = NULL;
    m->positions = shrink(m->positions, ((size_t)m->num_vertices + 1) * sizeof *m->positions);
    m->positions[m->num_vertices] = v3s(0.0f); /* Embree's padding */
    m->vertex_surface = shrink(m->vertex_surface, (size_t)m->num_vertices * sizeof(uint32_t));
    m->patches = shrink(m->patches, (size_t)m->num_patches * sizeof *m->patches);
    m->tri_indices = shrink(m->tri_indices, 3 * (size_t)m->num_tris * sizeof(uint32_t));
    m->tri_patch = shrink(m->tri_patch, (size_t)m->num_tris * sizeof(uint32_t));
    m->tri_src_mesh = shrink(m->tri_src_mesh, (size_t)m->num_tris * sizeof(uint32_t));
    m->tri_src_prim = shrink(m->tri_src_prim, (size_t)m->num_tris * sizeof(uint32_t));
    il_status st = mesh_panes(b->scene, m, b->err);
    if (st == IL_OK)
        st = il_tracer_create_triangles_panes(m->positions, m->num_vertices, m->tri_indices,
                                              m->num_tris, m->tri_panes, &m->tracer, b->err);
    b->m = NULL;
    if (st != IL_OK) {
        il_patch_mesh_release(m);
        *out = NULL;
        return st;
    }
    *out = m;
    return IL_OK;
}

void il_patch_builder_abort(il_patch_builder *b)
{
    free(b->slots);
    il_patch_mesh_release(b->m);
    memset(b, 0, sizeof *b);
}
