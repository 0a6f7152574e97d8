/* Radiosity meshing: il_patch_mesh_build, il_patch_mesh_refine, il_patch_mesh_release.
 * The steps live in patch_mesh_surfaces.c (surfaces, quads), patch_mesh_subdivide.c
 * (grids) and patch_mesh_builder.c (welding, patch attributes, BVH); see
 * patch_mesh_internal.h. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/patch_mesh_internal.h"

/* The patch count of the whole scene, before anything big is allocated. */
static il_status check_count(const il_patch_elements *el, const il_patch_sizing *s, double *total,
                             uint32_t *max_cells, il_error *err)
{
    double sum = 0.0, biggest = 0.0;
    for (size_t i = 0; i < el->num_elems; i++) {
        double nu, nv, n = il_patch_elem_grid(&el->elems[i], s, &nu, &nv);
        sum += n;
        double g = (nu + 1.0) * (nv + 1.0);
        biggest = g > biggest ? g : biggest;
    }
    if (!(sum <= IL_PATCH_MAX_PATCHES)) {
        if (s->subdivisions > 0)
            return il_fail(err, IL_ERR_INVALID,
                           "radiosity: %u subdivision levels give %.0f patches (more than "
                           "4,000,000); use fewer levels",
                           s->subdivisions, sum);
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: patch size %g m gives %.0f patches (more than 4,000,000); use "
                       "a larger --patch-size",
                       (double)s->patch_size, sum);
    }
    *total = sum;
    *max_cells = (uint32_t)biggest;
    return IL_OK;
}

il_status il_patch_mesh_build(const il_scene *scene, const il_patch_sizing *settings,
                            il_patch_mesh **out, il_error *err)
{
    *out = NULL;
    if (settings->subdivisions == 0 &&
        !(settings->patch_size > 0.0f && isfinite(settings->patch_size)))
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: the patch size must be a positive number of metres (got %g)",
                       (double)settings->patch_size);
    il_patch_elements el;
    il_status st = il_patch_elements_build(scene, &el, err);
    if (st != IL_OK)
        return st;
    if (el.num_elems == 0) {
        il_patch_elements_free(&el);
        return il_fail(err, IL_ERR_INVALID, "radiosity: the scene has no diffuse surface to mesh");
    }
    double total = 0.0;
    uint32_t max_cells = 0;
    if ((st = check_count(&el, settings, &total, &max_cells, err)) != IL_OK) {
        il_patch_elements_free(&el);
        return st;
    }

    /* Every quad patch is 2 triangles; a guess of the vertices (grids share
     * their edges), the arrays grow when needed. */
    size_t patches = (size_t)total, tris = 2 * patches + el.num_raw;
    il_patch_builder b;
    uint32_t *scratch = il_malloc((size_t)max_cells * sizeof *scratch, err);
    if (!scratch || (st = il_patch_builder_init(&b, scene, patches + patches / 4 + 3 * el.num_raw,
                                              patches, tris, err)) != IL_OK) {
        free(scratch);
        il_patch_elements_free(&el);
        return scratch ? st : IL_ERR_MEMORY;
    }
    b.m->surfaces = el.surfaces;
    b.m->num_surfaces = el.num_surfaces;
    el.surfaces = NULL;

    for (size_t i = 0; i < el.num_elems && st == IL_OK; i++) {
        double nu, nv;
        il_patch_elem_grid(&el.elems[i], settings, &nu, &nv);
        st = il_patch_elem_emit(&b, &el.elems[i], (uint32_t)nu, (uint32_t)nv, scratch);
    }
    /* Mirror and glass triangles: copied with the scene's vertex order,
     * their vertices welded within their own surface. */
    for (size_t i = 0; i < el.num_raw && st == IL_OK; i++) {
        uint32_t s = el.raw[i].surface, prim = el.raw[i].prim, mi = b.m->surfaces[s].mesh;
        const il_mesh *sm = &scene->meshes[mi];
        uint32_t v[3];
        for (int k = 0; k < 3 && st == IL_OK; k++)
            if ((v[k] = il_patch_builder_vertex(&b, s, sm->positions[sm->indices[3 * (size_t)prim + k]]))
                == UINT32_MAX)
                st = IL_ERR_MEMORY;
        if (st == IL_OK)
            st = il_patch_builder_raw_tri(&b, v, mi, prim);
    }
    free(scratch);
    il_patch_elements_free(&el);
    if (st == IL_OK && b.m->num_patches == 0)
        st = il_fail(err, IL_ERR_INVALID, "radiosity: the scene has no diffuse surface to mesh");
    if (st != IL_OK) {
        il_patch_builder_abort(&b);
        return st;
    }
    return il_patch_builder_finish(&b, out);
}

/* The 4 children of patch p by a midpoint split (quads 2x2 through the
 * centre, triangles into 4 by their edge midpoints), counter-clockwise as
 * the parent.  Midpoints come from il_patch_edge_point so neighbours that are
 * split too share them. */
static il_status split_patch(il_patch_builder *b, const il_patch *p, const uint32_t *v,
                             const uint32_t *cand, uint32_t num_cand)
{
    const il_vec3 *P;
    uint32_t n = p->num_corners, mid[4];
    for (uint32_t k = 0; k < n; k++) {
        P = b->m->positions; /* re-read: adding vertices may move the array */
        uint32_t a = v[k], c = v[(k + 1) % n];
        il_vec3 q = il_patch_edge_point(a, P[a], c, P[c], 1, 2);
        if ((mid[k] = il_patch_builder_vertex(b, p->surface, q)) == UINT32_MAX)
            return IL_ERR_MEMORY;
    }
    il_status st = IL_OK;
    if (n == 3) {
        const uint32_t kids[4][4] = {{v[0], mid[0], mid[2]}, {mid[0], v[1], mid[1]},
                                     {mid[2], mid[1], v[2]}, {mid[0], mid[1], mid[2]}};
        for (int k = 0; k < 4 && st == IL_OK; k++)
            st = il_patch_builder_patch(b, p->surface, 3, kids[k], cand, num_cand);
        return st;
    }
    P = b->m->positions;
    double c[3] = {0, 0, 0};
    for (uint32_t k = 0; k < 4; k++)
        for (int d = 0; d < 3; d++)
            c[d] += 0.25 * v3_get(P[v[k]], d);
    uint32_t ctr = il_patch_builder_vertex(b, p->surface, v3((float)c[0], (float)c[1], (float)c[2]));
    if (ctr == UINT32_MAX)
        return IL_ERR_MEMORY;
    const uint32_t kids[4][4] = {{v[0], mid[0], ctr, mid[3]}, {mid[0], v[1], mid[1], ctr},
                                 {ctr, mid[1], v[2], mid[2]}, {mid[3], ctr, mid[2], v[3]}};
    for (int k = 0; k < 4 && st == IL_OK; k++)
        st = il_patch_builder_patch(b, p->surface, 4, kids[k], cand, num_cand);
    return st;
}

/* Children replace their parent in place: the new patch order is the old
 * one with every split patch's 4 children where it was, so a surface's
 * patches stay together.  Old vertices keep their indices. */
il_status il_patch_mesh_refine(const il_scene *scene, const il_patch_mesh *mesh, const bool *split,
                             il_patch_mesh **out, il_error *err)
{
    *out = NULL;
    size_t nsplit = 0;
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        nsplit += split[i];
    size_t patches = mesh->num_patches + 3 * nsplit;
    if ((double)patches > IL_PATCH_MAX_PATCHES)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: refining gives %zu patches (more than 4,000,000); use a "
                       "larger adaptive threshold",
                       patches);
    uint32_t *first_tri = il_malloc(((size_t)mesh->num_patches + 1) * sizeof *first_tri, err);
    uint32_t *remap = il_malloc(((size_t)mesh->num_vertices + 1) * sizeof *remap, err);
    il_patch_surface *surfaces = il_malloc(((size_t)mesh->num_surfaces + 1) * sizeof *surfaces, err);
    il_patch_builder b;
    il_status st = IL_ERR_MEMORY;
    if (!first_tri || !remap || !surfaces ||
        (st = il_patch_builder_init(&b, scene, mesh->num_vertices + 5 * nsplit, patches,
                                  mesh->num_tris + 6 * nsplit, err)) != IL_OK) {
        free(first_tri), free(remap), free(surfaces);
        return st;
    }
    memcpy(surfaces, mesh->surfaces, mesh->num_surfaces * sizeof *surfaces);
    b.m->surfaces = surfaces;
    b.m->num_surfaces = mesh->num_surfaces;

    /* Old vertices first (the same indices, as they are unique per surface
     * and position), then the patches' triangles found by tri_patch. */
    for (uint32_t v = 0; v < mesh->num_vertices && st == IL_OK; v++)
        if ((remap[v] = il_patch_builder_vertex(&b, mesh->vertex_surface[v], mesh->positions[v])) ==
            UINT32_MAX)
            st = IL_ERR_MEMORY;
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        first_tri[i] = UINT32_MAX;
    for (uint32_t t = mesh->num_tris; t-- > 0;)
        if (mesh->tri_patch[t] != IL_NO_PATCH)
            first_tri[mesh->tri_patch[t]] = t;

    for (uint32_t i = 0; i < mesh->num_patches && st == IL_OK; i++) {
        const il_patch *p = &mesh->patches[i];
        uint32_t t0 = first_tri[i];
        uint32_t t1 = (p->num_corners == 4 && t0 + 1 < mesh->num_tris &&
                       mesh->tri_patch[t0 + 1] == i) ? t0 + 1 : t0;
        if (t0 == UINT32_MAX) /* no triangle: cannot happen for our meshes */
            continue;
        uint32_t v[4];
        for (uint32_t k = 0; k < p->num_corners; k++)
            v[k] = remap[p->v[k]];
        if (!split[i]) {
            il_patch q = *p;
            memcpy(q.v, v, sizeof v);
            const uint32_t sm[2] = {mesh->tri_src_mesh[t0], mesh->tri_src_mesh[t1]};
            const uint32_t sp[2] = {mesh->tri_src_prim[t0], mesh->tri_src_prim[t1]};
            st = il_patch_builder_copy_patch(&b, &q, sm, sp);
        } else {
            const uint32_t cand[2] = {mesh->tri_src_prim[t0], mesh->tri_src_prim[t1]};
            st = split_patch(&b, p, v, cand, cand[0] == cand[1] ? 1 : 2);
        }
    }
    for (uint32_t t = 0; t < mesh->num_tris && st == IL_OK; t++) {
        if (mesh->tri_patch[t] != IL_NO_PATCH)
            continue;
        const uint32_t *ti = mesh->tri_indices + 3 * (size_t)t;
        const uint32_t v[3] = {remap[ti[0]], remap[ti[1]], remap[ti[2]]};
        st = il_patch_builder_raw_tri(&b, v, mesh->tri_src_mesh[t], mesh->tri_src_prim[t]);
    }
    free(first_tri);
    free(remap);
    if (st != IL_OK) {
        il_patch_builder_abort(&b);
        return st;
    }
    return il_patch_builder_finish(&b, out);
}

void il_patch_mesh_release(il_patch_mesh *mesh)
{
    if (!mesh)
        return;
    il_tracer_release(mesh->tracer);
    free(mesh->patches);
    free(mesh->surfaces);
    free(mesh->positions);
    free(mesh->vertex_surface);
    free(mesh->tri_indices);
    free(mesh->tri_patch);
    free(mesh->tri_src_mesh);
    free(mesh->tri_src_prim);
    free(mesh->tri_panes);
    free(mesh);
}
