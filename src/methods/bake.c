/* il_bake: light written onto the geometry.  Radiosity or hierarchical
 * radiosity solves the scene and gives per-vertex radiance on its patch mesh; here the meshed triangles are
 * grouped back by the scene mesh they came from (tri_src_mesh), one
 * il_bake_mesh per scene mesh, with their own compact vertex arrays.
 *
 * Per vertex: the radiance interpolated from the patches (patch_vertex.c), zero
 * on mirror/glass triangles (they have no patch); the normal is the
 * area-weighted mean of the normals of its triangles: the patch normal, or
 * for a triangle without a patch the scene triangle's geometric normal.
 * Per triangle: its patch (il_bake_mesh.patches), for drawing patch outlines. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "illum/illum.h"
#include "methods/hr/hr.h"
#include "methods/radiosity/rad.h"
#include "scene/scene.h"

static const char *method_name(il_method m)
{
    switch (m) {
    case IL_METHOD_PT:
        return "pt";
    case IL_METHOD_RADIOSITY:
        return "radiosity";
    case IL_METHOD_HR:
        return "hr";
    case IL_METHOD_PHOTON:
        return "photon";
    case IL_METHOD_SPPM:
        return "sppm";
    case IL_METHOD_IBL:
        return "ibl";
    case IL_METHOD_LINESPACE:
        return "linespace";
    case IL_METHOD_RSM:
        return "rsm";
    }
    return NULL;
}

void il_bake_release(il_bake_result *bake)
{
    if (!bake)
        return;
    if (bake->meshes)
        for (uint32_t i = 0; i < bake->num_meshes; i++) {
            il_bake_mesh *m = &bake->meshes[i];
            free(m->positions);
            free(m->normals);
            free(m->radiance);
            free(m->indices);
            free(m->patches);
        }
    free(bake->meshes);
    free(bake);
}

static il_vec3 scene_triangle_normal(const il_scene *scene, uint32_t mesh, uint32_t prim)
{
    const il_mesh *m = &scene->meshes[mesh];
    const uint32_t *t = m->indices + 3 * (size_t)prim;
    il_vec3 a = m->positions[t[0]], b = m->positions[t[1]], c = m->positions[t[2]];
    return v3_normalize(v3_cross(v3_sub(b, a), v3_sub(c, a)));
}

/* Scratch shared by the meshes of one bake. */
typedef struct bake_scratch {
    uint32_t *order;      /* triangles sorted by scene mesh (counting sort) */
    uint32_t *start;      /* num_meshes + 1 offsets into order */
    uint32_t *local;      /* per rad vertex: its index in the current bake mesh */
    uint32_t *stamp;      /* per rad vertex: 1 + the bake mesh `local` belongs to */
    uint32_t *global;     /* per local vertex: the rad vertex */
    bool *lit;            /* per local vertex: touched by a patch triangle */
} bake_scratch;

static il_status fill_mesh(const il_scene *scene, const il_patch_mesh *rm, const il_vec3 *vr,
                           uint32_t m, bake_scratch *s, il_bake_mesh *out, il_error *err)
{
    const il_mesh *sm = &scene->meshes[m];
    snprintf(out->name, sizeof out->name, "%s", sm->name[0] ? sm->name : "mesh");
    out->material = sm->material;
    uint32_t first = s->start[m], nt = s->start[m + 1] - first;

    /* Compact vertex numbering in order of first use. */
    uint32_t nv = 0;
    for (uint32_t k = 0; k < nt; k++) {
        const uint32_t *tri = rm->tri_indices + 3 * (size_t)s->order[first + k];
        for (int c = 0; c < 3; c++) {
            uint32_t v = tri[c];
            if (s->stamp[v] != m + 1) {
                s->stamp[v] = m + 1;
                s->local[v] = nv;
                s->global[nv++] = v;
            }
        }
    }
    out->num_vertices = nv;
    out->num_triangles = nt;
    size_t nv1 = nv ? nv : 1u, nt1 = nt ? nt : 1u;
    out->positions = il_calloc(nv1 * 3, sizeof(float), err);
    out->normals = il_calloc(nv1 * 3, sizeof(float), err);
    out->radiance = il_calloc(nv1 * 3, sizeof(float), err);
    out->indices = il_calloc(nt1 * 3, sizeof(uint32_t), err);
    out->patches = il_malloc(nt1 * sizeof(uint32_t), err);
    if (!out->positions || !out->normals || !out->radiance || !out->indices || !out->patches)
        return IL_ERR_MEMORY;
    memset(s->lit, 0, nv1 * sizeof *s->lit);

    for (uint32_t k = 0; k < nt; k++) {
        uint32_t t = s->order[first + k];
        const uint32_t *tri = rm->tri_indices + 3 * (size_t)t;
        uint32_t patch = rm->tri_patch[t];
        out->patches[k] = patch;     /* IL_NO_PATCH is UINT32_MAX, as documented */
        il_vec3 a = rm->positions[tri[0]], b = rm->positions[tri[1]], c = rm->positions[tri[2]];
        float area = 0.5f * v3_length(v3_cross(v3_sub(b, a), v3_sub(c, a)));
        il_vec3 n = patch != IL_NO_PATCH
                        ? rm->patches[patch].normal
                        : scene_triangle_normal(scene, rm->tri_src_mesh[t], rm->tri_src_prim[t]);
        for (int q = 0; q < 3; q++) {
            uint32_t l = s->local[tri[q]];
            out->indices[3 * (size_t)k + q] = l;
            out->normals[3 * (size_t)l + 0] += n.x * area;
            out->normals[3 * (size_t)l + 1] += n.y * area;
            out->normals[3 * (size_t)l + 2] += n.z * area;
            if (patch != IL_NO_PATCH)
                s->lit[l] = true;
        }
    }
    for (uint32_t l = 0; l < nv; l++) {
        uint32_t v = s->global[l];
        float *p = out->positions + 3 * (size_t)l, *n = out->normals + 3 * (size_t)l,
              *L = out->radiance + 3 * (size_t)l;
        p[0] = rm->positions[v].x;
        p[1] = rm->positions[v].y;
        p[2] = rm->positions[v].z;
        il_vec3 nn = v3(n[0], n[1], n[2]);
        /* A vertex of degenerate triangles only: any unit normal will do. */
        nn = v3_length2(nn) > 0.0f ? v3_normalize(nn) : v3(0.0f, 1.0f, 0.0f);
        n[0] = nn.x;
        n[1] = nn.y;
        n[2] = nn.z;
        if (s->lit[l]) {
            L[0] = vr[v].x;
            L[1] = vr[v].y;
            L[2] = vr[v].z;
        }
    }
    return IL_OK;
}

static il_status convert(const il_scene *scene, const il_patch_mesh *rm, const il_vec3 *vr,
                         il_bake_result *res, il_error *err)
{
    uint32_t nm = scene->num_meshes;
    res->meshes = il_calloc(nm ? nm : 1u, sizeof *res->meshes, err);
    if (!res->meshes)
        return IL_ERR_MEMORY;
    res->num_meshes = nm;

    bake_scratch s;
    size_t nv1 = rm->num_vertices ? rm->num_vertices : 1u;
    s.order = il_malloc((size_t)(rm->num_tris ? rm->num_tris : 1u) * sizeof *s.order, err);
    s.start = il_calloc((size_t)nm + 1, sizeof *s.start, err);
    s.local = il_malloc(nv1 * sizeof *s.local, err);
    s.stamp = il_calloc(nv1, sizeof *s.stamp, err);
    s.global = il_malloc(nv1 * sizeof *s.global, err);
    s.lit = il_malloc(nv1 * sizeof *s.lit, err);
    il_status st = IL_OK;
    if (!s.order || !s.start || !s.local || !s.stamp || !s.global || !s.lit) {
        st = IL_ERR_MEMORY;
        goto done;
    }
    /* Counting sort of the triangles by their scene mesh (stable). */
    for (uint32_t t = 0; t < rm->num_tris; t++) {
        uint32_t m = rm->tri_src_mesh[t];
        if (m >= nm) {
            st = il_fail(err, IL_ERR_RUNTIME, "bake: a meshed triangle names scene mesh %u of %u",
                         m, nm);
            goto done;
        }
        s.start[m + 1]++;
    }
    for (uint32_t m = 0; m < nm; m++)
        s.start[m + 1] += s.start[m];
    {
        uint32_t *cursor = il_malloc(((size_t)nm + 1) * sizeof *cursor, err);
        if (!cursor) {
            st = IL_ERR_MEMORY;
            goto done;
        }
        memcpy(cursor, s.start, ((size_t)nm + 1) * sizeof *cursor);
        for (uint32_t t = 0; t < rm->num_tris; t++)
            s.order[cursor[rm->tri_src_mesh[t]]++] = t;
        free(cursor);
    }
    for (uint32_t m = 0; m < nm && st == IL_OK; m++)
        st = fill_mesh(scene, rm, vr, m, &s, &res->meshes[m], err);
    if (st == IL_ERR_MEMORY)
        il_fail(err, IL_ERR_MEMORY, "bake: out of memory for the baked meshes");
done:
    free(s.order);
    free(s.start);
    free(s.local);
    free(s.stamp);
    free(s.global);
    free(s.lit);
    return st;
}

/* il_bake_progressive's look at a solve: per-patch radiance to per-vertex
 * meshes, as at the end of il_bake, handed to the caller's callback. */
typedef struct bake_watch {
    const il_scene *scene;
    il_bake_step_fn on_step;
    void *user;
} bake_watch;

static bool watch_patches(const il_patch_mesh *mesh, const float *radiance, void *user)
{
    const bake_watch *w = user;
    il_error err = {0};
    size_t nv = mesh->num_vertices ? mesh->num_vertices : 1u;
    size_t np = mesh->num_patches ? mesh->num_patches : 1u;
    il_vec3 *pr = il_malloc(np * sizeof *pr, &err), *vr = il_malloc(nv * sizeof *vr, &err);
    il_bake_result cur = {0};
    bool go = true;
    if (pr && vr) {
        for (uint32_t i = 0; i < mesh->num_patches; i++)
            pr[i] = v3(radiance[3 * (size_t)i], radiance[3 * (size_t)i + 1],
                       radiance[3 * (size_t)i + 2]);
        il_patch_vertex_radiance(mesh, pr, vr);
        if (convert(w->scene, mesh, vr, &cur, &err) == IL_OK)
            go = w->on_step(&cur, w->user);
    }
    /* Without memory for a look the solve goes on unseen. */
    free(pr);
    free(vr);
    if (cur.meshes)
        for (uint32_t i = 0; i < cur.num_meshes; i++) {
            free(cur.meshes[i].positions);
            free(cur.meshes[i].normals);
            free(cur.meshes[i].radiance);
            free(cur.meshes[i].indices);
            free(cur.meshes[i].patches);
        }
    free(cur.meshes);
    return go;
}

/* Radiosity reports steps only to an on_step: one that goes on. */
static bool keep_going(const il_radiosity_progress *p, void *user)
{
    (void)p;
    (void)user;
    return true;
}

il_status il_bake(const il_scene *scene, const il_render_desc *desc, il_bake_result **out,
                  il_error *err)
{
    return il_bake_progressive(scene, desc, NULL, NULL, out, err);
}

il_status il_bake_progressive(const il_scene *scene, const il_render_desc *desc,
                              il_bake_step_fn on_step, void *user, il_bake_result **out,
                              il_error *err)
{
    if (!out)
        return il_fail(err, IL_ERR_INVALID, "bake: no result pointer given");
    *out = NULL;
    if (!scene)
        return il_fail(err, IL_ERR_INVALID, "bake: no scene given");
    if (!desc)
        return il_fail(err, IL_ERR_INVALID, "bake: no render options given");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID,
                       "bake: the scene is not committed (call il_scene_commit first)");
    const char *name = method_name(desc->method);
    if (!name)
        return il_fail(err, IL_ERR_INVALID, "bake: unknown method %d", (int)desc->method);
    if (desc->method != IL_METHOD_RADIOSITY && desc->method != IL_METHOD_HR)
        return il_fail(err, IL_ERR_INVALID,
                       "bake: method %s cannot bake (radiosity and hr can)", name);

    il_bake_result *res = il_calloc(1, sizeof *res, err);
    if (!res)
        return IL_ERR_MEMORY;
    il_patch_mesh *mesh = NULL;
    il_vec3 *vr = NULL;
    /* Both diffuse methods end in (patch mesh, per-vertex radiance). */
    il_status st;
    if (on_step) {
        bake_watch w = {scene, on_step, user};
        il_render_desc d = *desc;
        il_radiosity_desc rd = {0};
        if (desc->radiosity)
            rd = *desc->radiosity;
        if (!rd.on_step)
            rd.on_step = keep_going;
        d.radiosity = &rd;
        st = desc->method == IL_METHOD_HR
                 ? il_hr_run_watched(scene, &d, watch_patches, &w, &mesh, &vr, &res->stats, err)
                 : il_rad_run_watched(scene, &d, watch_patches, &w, &mesh, &vr, &res->stats, err);
    } else {
        st = desc->method == IL_METHOD_HR
                 ? il_hr_run(scene, desc, &mesh, &vr, &res->stats, err)
                 : il_rad_run(scene, desc, &mesh, NULL, &vr, &res->stats, err);
    }
    if (st == IL_OK)
        st = convert(scene, mesh, vr, res, err);
    if (mesh)
        il_patch_mesh_release(mesh);
    free(vr);
    if (st != IL_OK) {
        il_bake_release(res);
        return st;
    }
    *out = res;
    return IL_OK;
}
