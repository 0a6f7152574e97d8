/* Internals of the patch mesher (patch_mesh*.c), not used elsewhere.
 *
 * Meshing runs in three steps:
 *   patch_mesh_surfaces.c  scene triangles -> surfaces and "elements" (a convex
 *                        planar quad made of two scene triangles, or one
 *                        scene triangle), oriented counter-clockwise from the
 *                        front;
 *   patch_mesh_subdivide.c elements -> grids of patches;
 *   patch_mesh.c           the builder that welds vertices inside a surface,
 *                        fills the patches and triangles and builds the BVH;
 *                        il_patch_mesh_build / _refine / _release. */
#ifndef IL_METHODS_RADIOSITY_RAD_MESH_INTERNAL_H
#define IL_METHODS_RADIOSITY_RAD_MESH_INTERNAL_H

#include "methods/patch_mesh.h"

/* More patches than this is an error (memory and form-factor time). */
#define IL_PATCH_MAX_PATCHES 4000000.0

/* A quad (two scene triangles) or a triangle (one) of a diffuse surface. */
typedef struct il_patch_elem {
    uint32_t surface;
    uint32_t num_corners;  /* 3 or 4 */
    uint32_t id[4];        /* the corners' welded vertex ids within the scene
                              mesh: the canonical order of an edge's ends */
    il_vec3 p[4];          /* counter-clockwise seen from the front */
    uint32_t src[2];       /* scene triangles (of the surface's mesh); src[1]
                              == src[0] for a triangle */
} il_patch_elem;

/* A triangle of a mirror/glass surface, copied unsplit. */
typedef struct il_patch_raw_tri {
    uint32_t surface;
    uint32_t prim;
} il_patch_raw_tri;

typedef struct il_patch_elements {
    il_patch_elem *elems;         size_t num_elems;
    il_patch_surface *surfaces;   uint32_t num_surfaces;
    il_patch_raw_tri *raw;        size_t num_raw;
} il_patch_elements;

/* Groups the scene's triangles into surfaces and elements. */
il_status il_patch_elements_build(const il_scene *scene, il_patch_elements *out, il_error *err);
void il_patch_elements_free(il_patch_elements *e);

/* ------------------------------------------------------------- builder */

/* Grows an il_patch_mesh: welded vertices (exact position, per surface),
 * patches and their triangles. */
typedef struct il_patch_builder {
    const il_scene *scene;
    il_patch_mesh *m;
    size_t cap_vertices, cap_patches, cap_tris;
    uint32_t *slots;            /* open-addressing table of vertex ids */
    size_t slot_mask;           /* capacity - 1 (a power of two) */
    il_error *err;
} il_patch_builder;

il_status il_patch_builder_init(il_patch_builder *b, const il_scene *scene, size_t expect_vertices,
                              size_t expect_patches, size_t expect_tris, il_error *err);
/* The vertex of `surface` at exactly p (bitwise, -0 == +0), added when new.
 * UINT32_MAX when out of memory (b->err is set). */
uint32_t il_patch_builder_vertex(il_patch_builder *b, uint32_t surface, il_vec3 p);
/* Adds the patch with corners v (counter-clockwise from the front) of
 * `surface`, computing its centre, normal, area, rho (averaged over points
 * of the patch) and emission; the scene triangles it may lie in are
 * cand[0..num_cand).  A zero-area patch is skipped (returns IL_OK). */
il_status il_patch_builder_patch(il_patch_builder *b, uint32_t surface, uint32_t num_corners,
                               const uint32_t v[4], const uint32_t *cand, uint32_t num_cand);
/* Appends a patch as is with its triangles' source triangles. */
il_status il_patch_builder_copy_patch(il_patch_builder *b, const il_patch *p,
                                    const uint32_t src_mesh[2], const uint32_t src_prim[2]);
/* Appends a triangle that belongs to no patch. */
il_status il_patch_builder_raw_tri(il_patch_builder *b, const uint32_t v[3], uint32_t mesh,
                                 uint32_t prim);
/* Shrinks the arrays, pads positions for Embree, builds the tracer; on
 * success *out owns everything.  Frees the builder either way. */
il_status il_patch_builder_finish(il_patch_builder *b, il_patch_mesh **out);
void il_patch_builder_abort(il_patch_builder *b);

/* A point on the edge from vertex a to vertex b at k/n of the way, computed
 * from the end with the smaller id so both elements sharing an edge get
 * bitwise-equal points (and equal fractions k/n give equal points). */
il_vec3 il_patch_edge_point(uint32_t ida, il_vec3 pa, uint32_t idb, il_vec3 pb, uint32_t k,
                          uint32_t n);

/* ----------------------------------------------------------- subdivide */

/* The grid of an element: nu x nv cells for a quad, n = nu (nv = nu) rows
 * for a triangle (n^2 triangles).  Returns the number of patches as a double
 * (it may be astronomically large for absurd settings). */
double il_patch_elem_grid(const il_patch_elem *e, const il_patch_sizing *s, double *nu, double *nv);
/* Emits the patches of an element's nu x nv grid into the builder.
 * `scratch` holds at least (nu+1)*(nv+1) vertex ids. */
il_status il_patch_elem_emit(il_patch_builder *b, const il_patch_elem *e, uint32_t nu, uint32_t nv,
                           uint32_t *scratch);

#endif
