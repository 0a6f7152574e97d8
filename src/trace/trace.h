/* Ray casting: the only place that knows about Embree.  Closest hit and
 * occlusion, for one ray and for streams of rays. */
#ifndef IL_TRACE_TRACE_H
#define IL_TRACE_TRACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "core/vec.h"

typedef struct il_scene il_scene;
typedef struct il_tracer il_tracer;

typedef struct il_ray {
    il_vec3 org;
    float tmin;
    il_vec3 dir;           /* need not be unit length; t is in units of |dir| */
    float tmax;
} il_ray;

typedef struct il_hit {
    float t;
    uint32_t mesh;         /* UINT32_MAX: no hit */
    uint32_t prim;
    float b1, b2;          /* barycentrics of vertices 1 and 2 */
    il_vec3 ng;            /* unnormalised geometric normal, as Embree gives it */
} il_hit;

#define IL_HIT_NONE UINT32_MAX

/* Builds the BVH over the scene's meshes (each mesh one Embree geometry, its
 * index the geometry id).  Threads: Embree's own. */
il_status il_tracer_create(const il_scene *scene, il_tracer **out, il_error *err);
/* Builds the BVH over one triangle set (hits report mesh 0 and the triangle's
 * index as prim).  The arrays are used in place and must outlive the tracer;
 * `positions` needs room for one more float after the last vertex (Embree
 * reads 16 bytes per vertex). */
il_status il_tracer_create_triangles(const il_vec3 *positions, uint32_t num_vertices,
                                     const uint32_t *indices, uint32_t num_triangles,
                                     il_tracer **out, il_error *err);
/* The same with thin panes among the triangles: panes[i] is triangle i's
 * (ior 0: not a pane), used in place like the other arrays. */
typedef struct il_trace_pane {
    float ior, tau;        /* il_material's ior and pane_tau (scene/pane.h) */
} il_trace_pane;
il_status il_tracer_create_triangles_panes(const il_vec3 *positions, uint32_t num_vertices,
                                           const uint32_t *indices, uint32_t num_triangles,
                                           const il_trace_pane *panes, il_tracer **out,
                                           il_error *err);
void il_tracer_release(il_tracer *tracer);

/* Returns true and fills hit when the ray hits something in [tmin, tmax]. */
bool il_trace_closest(const il_tracer *tracer, const il_ray *ray, il_hit *hit);
/* Thin panes (IL_MATERIAL_THIN_GLASS) pass light on a straight line
 * (trace.c, pane_filter): il_trace_closest and il_trace_closest_n let a ray
 * through a pane with its transmittance T at the ray's incidence (a draw
 * that depends on the ray and the triangle only) and otherwise report the
 * pane, whose BSDF reflects; il_trace_visibility weighs a ray by the T of
 * every pane it passes; il_trace_occluded sees only opaque surfaces. */

/* True when an opaque surface blocks the ray in [tmin, tmax] (panes let it
 * through: hours of sun, the Linespace's in-shaft test, link visibility). */
bool il_trace_occluded(const il_tracer *tracer, const il_ray *ray);
/* The fraction of light that passes along the ray in [tmin, tmax]: 0 when
 * an opaque surface blocks it, else the product of the panes' T (1 when it
 * meets none).  What a light sample's shadow ray needs. */
float il_trace_visibility(const il_tracer *tracer, const il_ray *ray);

/* Streams: n independent rays at once (Embree's rtcIntersect1M/rtcOccluded1M),
 * cheaper per ray for coherent batches. */
void il_trace_closest_n(const il_tracer *tracer, const il_ray *rays, il_hit *hits, size_t n);
/* The same for rays that start close together and point alike (camera rays
 * of neighbouring pixels): Embree's coherent traversal order. */
void il_trace_closest_n_coherent(const il_tracer *tracer, const il_ray *rays, il_hit *hits,
                                 size_t n);
void il_trace_occluded_n(const il_tracer *tracer, const il_ray *rays, bool *occluded, size_t n);
void il_trace_visibility_n(const il_tracer *tracer, const il_ray *rays, float *visibility, size_t n);

/* The distance by which secondary rays leave a surface: scaled to the scene
 * (a fixed fraction of its extent) so millimetre and metre scenes behave alike. */
float il_trace_epsilon(const il_tracer *tracer);

/* A ray origin lifted off the surface at p (unit geometric normal ng) to the
 * side that `dir` points to, so the ray does not hit its own triangle. */
il_vec3 il_offset_origin(const il_tracer *tracer, il_vec3 p, il_vec3 ng, il_vec3 dir);

/* A shadow ray from p (lifted as above) to the point q (lifted the other way
 * when the unit normal nq is not zero); tmax stops just short of q. */
il_ray il_shadow_ray(const il_tracer *tracer, il_vec3 p, il_vec3 ng, il_vec3 q, il_vec3 nq);

#endif
