/* Many-light image-based lighting (`--method ibl`): the environment becomes N
 * directional lights (Kemmer 2005; Agarwal et al. 2003, "Structured
 * Importance Sampling of Environment Maps"; Debevec 2005, "A Median Cut
 * Algorithm for Light Probe Sampling"), each camera sample's first
 * non-specular surface sums their light with exact (ray-cast) or shadow-map
 * visibility, and lights are added in batches so the film is a complete,
 * correctly normalised image after every batch.  docs/ibl.md explains the
 * estimator, its options and how it converges to the path tracer. */
#ifndef IL_METHODS_IBL_H
#define IL_METHODS_IBL_H

#include <stdbool.h>
#include <stdint.h>
#include "core/sampler.h"
#include "core/sampling.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "methods/camera_pass.h"
#include "scene/bsdf.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* Renders into the film (cleared first); desc->ibl may be NULL (defaults).
 * stats may be NULL. */
il_status il_ibl_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        il_render_stats *stats, il_error *err);

/* ---- internals, shared by the files of this folder and the tests ---- */

/* il_ibl_render keeps the camera vertices between batches when they fit in
 * this many bytes (about 170 each: 44 MB at 512x512 and 1 spp), else traces
 * them again for every batch. */
#define IL_IBL_CACHE_BYTES ((size_t)256 << 20)

/* il_ibl_render with another budget for that cache (0: none), so that tests
 * can check both ways give the same film. */
il_status il_ibl_render_budget(const il_scene *scene, il_film *film, const il_render_desc *desc,
                               size_t cache_bytes, il_render_stats *stats, il_error *err);

/* The options with their defaults resolved (ibl_settings.c). */
typedef struct il_ibl_settings {
    uint32_t lights;           /* N */
    uint32_t batch;
    il_ibl_selection selection;
    il_ibl_shadows shadows;
    uint32_t shadow_map_size;
    float shadow_bias;         /* fraction of the scene's diagonal */
    uint32_t pcf_taps;
    uint32_t spp;              /* camera samples per pixel */
    uint32_t max_depth;        /* scattering events: delta bounces + the shaded vertex */
} il_ibl_settings;

#define IL_IBL_MAX_LIGHTS (1u << 24)
#define IL_IBL_MAX_SPP 4096u
#define IL_IBL_MAX_MAP 8192u
#define IL_IBL_MAX_PCF 15u

/* Checks desc (NULL: all defaults) and the render options ibl cares about
 * (spp at most IL_IBL_MAX_SPP) and fills *out. */
il_status il_ibl_settings_resolve(const il_ibl_desc *desc, const il_render_desc *rd,
                                  il_ibl_settings *out, il_error *err);

/* The light set (ibl_lights.c).  Light i has unit direction wi_i (from the
 * scene towards the sky) and weight w_i = L(wi_i) / pdf(wi_i); the image of
 * the first M lights is the Monte Carlo estimator
 *     L_o = 1/M sum_i f(wo, wi_i) w_i cos(theta_i) V(wi_i),
 * so the set's first M lights are themselves a complete M-light set.  An
 * il_ibl_lights holds the run first..first+count-1 of the set (a batch):
 * light l is dir[l - first], weight[l - first]. */
typedef struct il_ibl_lights {
    uint32_t first, count, capacity;
    il_vec3 *dir;
    il_vec3 *weight;
} il_ibl_lights;

/* Light i of the set the selection and seed define (it does not depend on
 * how many lights the set has).  *weight is zero where the environment is
 * black or the density is zero. */
void il_ibl_light(const il_scene *scene, il_ibl_selection selection, uint64_t seed, uint32_t i,
                  il_vec3 *dir, il_vec3 *weight);
/* Room for `capacity` lights. */
il_status il_ibl_lights_alloc(il_ibl_lights *out, uint32_t capacity, il_error *err);
/* Lights first..first+count-1 (count <= capacity) into out; threads:
 * OpenMP, 0 means all cores. */
void il_ibl_lights_fill(const il_scene *scene, il_ibl_selection selection, uint64_t seed,
                        uint32_t first, uint32_t count, int threads, il_ibl_lights *out);
/* Both: lights 0..count-1. */
il_status il_ibl_lights_build(const il_scene *scene, il_ibl_selection selection, uint64_t seed,
                              uint32_t count, int threads, il_ibl_lights *out, il_error *err);
void il_ibl_lights_free(il_ibl_lights *l);

/* One camera sample's shaded vertex (ibl_camera.c): the first non-delta
 * surface the camera ray reaches through perfect mirrors and glass. */
typedef struct il_ibl_vertex {
    il_vec3 org;               /* shadow-ray origin: the point lifted along g */
    il_vec3 n;                 /* shading normal, turned to wo's side */
    il_vec3 g;                 /* geometric normal, turned to wo's side */
    il_vec3 kd;                /* diffuse: beta * albedo / pi (the whole f) */
    uint32_t pixel;            /* y * width + x */
    bool diffuse;              /* Lambertian: f = kd, no il_bsdf_eval needed */
    il_vec3 wo;                /* unit, towards the camera side */
    il_vec3 beta;              /* throughput of the delta bounces before it */
    il_bsdf bsdf;              /* for the other materials */
} il_ibl_vertex;

/* What a camera sample needs besides the vertex. */
typedef struct il_ibl_camera {
    const il_scene *scene;
    il_camera_pass_ctx ctx;    /* camera, image size, seed, sampler, filter (no film) */
    uint32_t max_depth;
    /* The scene's lights other than the environment (ibl_direct.c). */
    uint32_t num_delta;        /* point, spot, directional: exact */
    uint32_t *delta;           /* their indices into scene->lights */
    uint32_t num_area;         /* emissive triangles: one sample per camera sample */
    uint32_t *area;
    il_distrib1d area_pick;    /* over num_area, by power */
} il_ibl_camera;

il_status il_ibl_camera_init(il_ibl_camera *c, const il_scene *scene, const il_render_desc *rd,
                             uint32_t width, uint32_t height, uint32_t max_depth, il_error *err);
void il_ibl_camera_free(il_ibl_camera *c);

/* Camera sample i of pixel (x, y): follows the ray through delta bounces.
 * Adds to *base what does not depend on the environment's lights: the
 * environment seen directly or in mirrors, emitters seen, and (when
 * with_lights) the direct light of the scene's other lights at the vertex.
 * Returns true and fills *v when the path ends on a surface that the
 * environment's lights shade.  Counts rays (camera, bounces, shadow). */
bool il_ibl_camera_vertex(const il_ibl_camera *c, uint32_t x, uint32_t y, uint32_t i,
                          bool with_lights, il_ibl_vertex *v, il_vec3 *base, uint64_t *rays);

/* Direct light at the vertex from the scene's point, spot and directional
 * lights (every one, exactly) and emissive triangles (one sample chosen by
 * power, from u_select and u), with shadow rays (ibl_direct.c). */
il_vec3 il_ibl_other_lights(const il_ibl_camera *c, const il_ibl_vertex *v, float u_select,
                            il_vec2 u, uint64_t *rays);

/* f(wo, wi) |cos theta_i| at the vertex for a light from wi: zero below
 * either hemisphere (ibl_shade.c). */
static inline il_vec3 il_ibl_f_cos(const il_ibl_vertex *v, il_vec3 wi)
{
    float cg = v3_dot(v->g, wi), cn = v3_dot(v->n, wi);
    if (!(cg > 0.0f) || !(cn > 1e-7f))
        return v3s(0.0f);
    if (v->diffuse)
        return v3_scale(v->kd, cn);
    il_vec3 f = il_bsdf_eval(&v->bsdf, v->wo, wi, NULL);
    return v3_scale(v3_mul(v->beta, f), cn);
}

/* Orthographic shadow maps, one per directional light (ibl_shadowmap.c). */
typedef struct il_ibl_shadow_map {
    il_vec3 du, dv, dz;        /* map axes: du, dv across, dz = the light direction */
    float u0, v0;              /* the map's corner in (du, dv) coordinates */
    float inv_texel;           /* texels per unit length */
    float texel;
    uint32_t size;
    float *depth;              /* size*size: largest dot(p, dz) (nearest the light)
                                  of the scene's surfaces per texel, -inf where none */
} il_ibl_shadow_map;

typedef struct il_ibl_shadow_maps {
    uint32_t count, size, taps;
    float bias;                /* absolute, scene units */
    il_ibl_shadow_map *maps;
    float *memory;
} il_ibl_shadow_maps;

/* Room for `count` maps of size^2 texels. */
il_status il_ibl_shadow_maps_alloc(il_ibl_shadow_maps *sm, uint32_t count, uint32_t size,
                                   uint32_t taps, float bias, il_error *err);
void il_ibl_shadow_maps_free(il_ibl_shadow_maps *sm);
/* Rasterises the scene into map k for the light from direction dir. */
void il_ibl_shadow_map_build(const il_scene *scene, il_ibl_shadow_map *m, uint32_t size,
                             il_vec3 dir);
/* Fraction of the light from map m's direction reaching the vertex:
 * percentage-closer filtering over taps x taps texels with a receiver-plane
 * depth bias. */
float il_ibl_shadow_map_lookup(const il_ibl_shadow_maps *sm, const il_ibl_shadow_map *m,
                               const il_ibl_vertex *v);

#endif
