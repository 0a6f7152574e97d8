/* The light table of a committed scene: point, spot, directional, emissive
 * triangles and the environment, selected in proportion to their power. */
#ifndef IL_SCENE_LIGHTS_H
#define IL_SCENE_LIGHTS_H

#include <stdbool.h>
#include "core/vec.h"
#include "scene/scene.h"

typedef struct il_light_sample {
    il_vec3 wi;            /* unit, from the shading point to the light */
    float dist;            /* to the light point; INFINITY for directional/environment */
    il_vec3 p;             /* the point on the light (finite lights) */
    il_vec3 n;             /* the light's surface normal (area lights), else zero */
    il_vec3 radiance;      /* arriving radiance (delta lights: intensity/dist^2 or irradiance) */
    float pdf;             /* solid angle, including the selection probability;
                              for delta lights just the selection probability */
    bool delta;            /* point, spot, directional: no MIS */
    uint32_t light;        /* index into scene->lights */
} il_light_sample;

/* Builds scene->lights, the selection CDF and the triangle->light map.  Called
 * by il_scene_commit after the bounds are known.  An error when no light. */
il_status il_lights_build(il_scene *scene, il_error *err);
void il_lights_free(il_scene *scene);

/* The light il_light_sample_at picks with u_select (scene->num_lights > 0):
 * by power, through the selection CDF. */
uint32_t il_light_select(const il_scene *scene, float u_select);
/* A directional light's direction for the pair u: `towards` (unit, to the
 * centre of its disc) when it has no disc (cos_half 1), else uniform over
 * its disc of angular radius acos(cos_half).  *scale: what its irradiance
 * (W/m^2 facing it) is multiplied by to be the sample's radiance in
 * il_light_sample's delta convention (E cos, no pdf but the selection),
 * 1 without a disc: the mean over the disc is exactly E cos for a surface
 * no part of the disc is below. */
il_vec3 il_directional_sample(il_vec3 towards, float cos_half, il_vec2 u, float *scale);
/* Samples a light seen from point p: u_select picks the light, u a point on it. */
bool il_light_sample_at(const il_scene *scene, il_vec3 p, float u_select, il_vec2 u,
                        il_light_sample *out);

/* Solid-angle pdf of il_light_sample_at choosing the point p_light (normal
 * n_light) on area light `light` from p: used for MIS when a BSDF ray hits an emitter. */
float il_light_pdf_area(const il_scene *scene, uint32_t light, il_vec3 p, il_vec3 p_light,
                        il_vec3 n_light);
/* Solid-angle pdf of il_light_sample_at choosing direction dir towards the
 * environment from p (the point matters when the scene has portals). */
float il_light_pdf_environment(const il_scene *scene, il_vec3 p, il_vec3 dir);

/* Radiance leaving an emissive surface with geometric normal ng towards w. */
il_vec3 il_emitted_radiance(const il_material *m, il_vec3 ng, il_vec3 w);
/* Radiance arriving from the environment along direction -dir (dir points away from the scene). */
il_vec3 il_environment_radiance(const il_scene *scene, il_vec3 dir);
/* What the camera sees along dir leaving the scene, directly or through
 * mirrors and glass: the environment plus the discs of directional lights
 * (the sun; scene->discs).  Only for paths with no diffuse or glossy vertex
 * yet: after one, light sampling takes a directional light as a delta (it
 * is never found by a BSDF ray), so its disc must not be added there. */
il_vec3 il_background_radiance(const il_scene *scene, il_vec3 dir);
/* Samples a direction towards the environment (pointing away from the
 * scene) for u in [0,1)^2: importance sampled from a map, uniform over the
 * sphere for a constant sky.  Returns the radiance arriving from *dir and
 * sets *pdf, its solid-angle density (without any light-selection
 * probability); *pdf is 0 when the scene has no environment. */
il_vec3 il_environment_sample(const il_scene *scene, il_vec2 u, il_vec3 *dir, float *pdf);
/* The solid-angle density of il_environment_sample choosing dir. */
float il_environment_pdf(const il_scene *scene, il_vec3 dir);
/* The environment sampled from the point p: as il_environment_sample, but
 * when p is on the lit side of a portal (scene/portal.h) a share of the
 * draws is aimed through the portals, and *pdf is the mixture's density.
 * What il_light_sample_at draws for the environment. */
il_vec3 il_environment_sample_at(const il_scene *scene, il_vec3 p, il_vec2 u, il_vec3 *dir,
                                 float *pdf);
/* The solid-angle density of il_environment_sample_at choosing dir from p. */
float il_environment_pdf_at(const il_scene *scene, il_vec3 p, il_vec3 dir);
/* il_environment_radiance(dir), with il_environment_pdf_at(p, dir) in *pdf:
 * the same values, a map looked up once for both. */
il_vec3 il_environment_eval_at(const il_scene *scene, il_vec3 p, il_vec3 dir, float *pdf);
/* The same with il_light_pdf_environment(p, dir) in *light_pdf (what a
 * BSDF ray that escapes needs for MIS). */
il_vec3 il_environment_light_eval(const il_scene *scene, il_vec3 p, il_vec3 dir, float *light_pdf);

#endif
