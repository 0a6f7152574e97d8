/* Scenes cut into patches for the diffuse methods (radiosity, hierarchical
 * radiosity): meshing, per-vertex radiance, and the camera pass that shows a
 * per-vertex solution.  Shared by the methods, so it lives beside them at
 * the root of methods/ (no method reaches into another's folder). */
#ifndef IL_METHODS_PATCH_MESH_H
#define IL_METHODS_PATCH_MESH_H

#include <stdbool.h>
#include <stdint.h>
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/scene.h"
#include "trace/trace.h"

#define IL_NO_PATCH UINT32_MAX

/* --------------------------------------------------------------- meshing */

/* A patch: a planar triangle or convex quad of one surface.  Vertices are in
 * counter-clockwise order seen from the front (the side `normal` points to). */
typedef struct il_patch {
    uint32_t num_corners;      /* 3 or 4 */
    uint32_t v[4];             /* indices into il_patch_mesh.positions */
    il_vec3 center;            /* centroid */
    il_vec3 normal;            /* unit */
    float area;
    uint32_t surface;          /* index into il_patch_mesh.surfaces */
    il_vec3 rho;               /* diffuse reflectance (texture averaged over the patch) */
    il_vec3 emission;          /* emitted radiance Le, front side */
} il_patch;

/* A surface: connected triangles of one scene mesh and one material, split
 * at creases.  Vertices are shared only inside one surface, so light never
 * bleeds across a room's corner. */
typedef struct il_patch_surface {
    uint32_t mesh;             /* the scene mesh */
    uint32_t material;
    bool diffuse;              /* false: mirror/glass, kept unsplit, no patches */
} il_patch_surface;

/* The meshed scene.  Every patch becomes 1 or 2 triangles of `tri_*`; the
 * triangles of non-diffuse surfaces are copied unsplit (same vertex order as
 * in the scene, so barycentrics carry over).  `tracer` is built over these
 * triangles: a hit's prim indexes tri_*. */
typedef struct il_patch_mesh {
    il_patch *patches;      uint32_t num_patches;
    il_patch_surface *surfaces;   uint32_t num_surfaces;
    il_vec3 *positions;         uint32_t num_vertices;  /* padded for Embree */
    uint32_t *vertex_surface;   /* per vertex */
    uint32_t *tri_indices;      uint32_t num_tris;      /* 3 per triangle */
    uint32_t *tri_patch;        /* per triangle: patch or IL_NO_PATCH */
    uint32_t *tri_src_mesh;     /* per triangle: the scene triangle it lies in */
    uint32_t *tri_src_prim;
    il_trace_pane *tri_panes;   /* per triangle, its pane (ior 0: none); NULL when the
                                   scene has no thin_glass: the tracer lets rays
                                   through them as the scene's does */
    il_tracer *tracer;
} il_patch_mesh;

/* How finely to mesh: uniform levels, or else the largest patch edge. */
typedef struct il_patch_sizing {
    float patch_size;          /* metres; used when subdivisions is 0 */
    uint32_t subdivisions;     /* > 0: uniform levels, each splits every element into 4 */
} il_patch_sizing;

/* Meshes the committed scene by sizing->subdivisions or patch_size.
 * An error (IL_ERR_INVALID) when it would exceed 4,000,000 patches or has no
 * diffuse surface. */
il_status il_patch_mesh_build(const il_scene *scene, const il_patch_sizing *sizing,
                            il_patch_mesh **out, il_error *err);
/* A new mesh where every patch with split[i] is replaced by its 4 children
 * (midpoint split); other patches are kept.  Rebuilds the tracer. */
il_status il_patch_mesh_refine(const il_scene *scene, const il_patch_mesh *mesh, const bool *split,
                             il_patch_mesh **out, il_error *err);
void il_patch_mesh_release(il_patch_mesh *mesh);

/* ----------------------------------------------------------- output */

/* Per-vertex radiance: the area-weighted mean of the patches around each
 * vertex (vertices belong to one surface only).  out has num_vertices. */
void il_patch_vertex_radiance(const il_patch_mesh *mesh, const il_vec3 *patch_radiance,
                            il_vec3 *out);

/* Camera pass: rays hit the meshed scene; on diffuse surfaces the radiance
 * interpolated from the vertices is the answer; mirror and glass continue the
 * path by BSDF sampling as the path tracer does; Phong surfaces add their
 * glossy lobe by sampling it.  desc->spp samples per pixel (jittered).
 * stats (may be NULL): spp is set, rays and nonfinite_samples are added to. */
il_status il_patch_render_film(const il_scene *scene, const il_patch_mesh *mesh,
                               const il_vec3 *vertex_radiance, il_film *film,
                               const il_render_desc *desc, il_render_stats *stats, il_error *err);

/* A patch method's solve: the meshed scene and its per-vertex radiance
 * (the caller frees both), the method's stats filled. */
typedef il_status (*il_patch_solve_fn)(const il_scene *scene, const il_render_desc *desc,
                                       il_patch_mesh **mesh_out, il_vec3 **vertex_radiance_out,
                                       il_render_stats *stats, il_error *err);

/* The il_render entry of a patch method: solve, then il_patch_render_film.
 * stats must not be NULL; after the camera pass, *seconds_render gets its
 * time (a field of the method's stats) and stats->seconds the total. */
il_status il_patch_solve_and_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                                    il_patch_solve_fn solve, il_render_stats *stats,
                                    double *seconds_render, il_error *err);

#endif
