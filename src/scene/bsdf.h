/* BSDFs of the material model: Lambertian, normalised modified Phong,
 * perfect mirror, smooth dielectric, thin pane.  All directions are world-space unit
 * vectors pointing away from the surface; f excludes the cosine. */
#ifndef IL_SCENE_BSDF_H
#define IL_SCENE_BSDF_H

#include <stdbool.h>
#include "core/vec.h"
#include "scene/scene.h"

typedef struct il_bsdf {
    il_material_type type;
    il_frame frame;        /* shading frame; frame.n is the shading normal */
    il_vec3 ng;            /* geometric normal (unit) */
    il_vec3 diffuse;       /* resolved albedo (texture applied) */
    il_vec3 specular;
    float exponent;
    float ior;
    float pane_tau;        /* THIN_GLASS: il_material's */
    float diffuse_prob;    /* PHONG: probability of sampling the diffuse lobe */
} il_bsdf;

typedef struct il_bsdf_sample {
    il_vec3 wi;
    il_vec3 f;             /* BSDF value (for delta lobes: the delta's weight) */
    il_vec3 weight;        /* f * |cos theta_i| / pdf: the path throughput factor */
    float pdf;             /* solid angle; for delta lobes the lobe's choice probability */
    bool delta;            /* mirror or glass: not reachable by light sampling */
} il_bsdf_sample;

/* A Phong material's exponent as its BSDF uses it (0 means 32). */
static inline float il_phong_exponent(const il_material *m)
{
    return m->exponent > 0.0f ? m->exponent : 32.0f;
}

void il_bsdf_init(il_bsdf *b, const il_scene *scene, const il_surface *s);
/* f(wo, wi) and the pdf of il_bsdf_sample choosing wi; zero for delta BSDFs. */
il_vec3 il_bsdf_eval(const il_bsdf *b, il_vec3 wo, il_vec3 wi, float *pdf);
/* Draws wi; false when the sample carries no energy (absorbed). */
bool il_bsdf_sample_dir(const il_bsdf *b, il_vec3 wo, float u_lobe, il_vec2 u, il_bsdf_sample *out);
/* il_bsdf_sample_dir with il_sample_cosine_hemisphere(u) already computed
 * in *cos_dir (NULL: computed here when needed), for callers that warp
 * many samples at once (il_sample_cosine_hemisphere_n). */
bool il_bsdf_sample_dir_cos(const il_bsdf *b, il_vec3 wo, float u_lobe, il_vec2 u,
                            const il_vec3 *cos_dir, il_bsdf_sample *out);
/* True when every lobe is a delta (MIRROR, DIELECTRIC, THIN_GLASS): skip
 * light sampling. */
bool il_bsdf_is_delta(const il_bsdf *b);

/* Shading normals make the two hemispheres of ng and ns disagree near the
 * silhouette.  A direction pair that is a reflection for one normal and a
 * transmission for the other would leak light through the surface (Veach
 * 1997, 5.3.2): integrators drop such samples. */
static inline bool il_sides_agree(const il_surface *s, il_vec3 wo, il_vec3 wi)
{
    float g = v3_dot(wo, s->ng) * v3_dot(wi, s->ng);
    float n = v3_dot(wo, s->ns) * v3_dot(wi, s->ns);
    return (g > 0.0f) == (n > 0.0f) && g != 0.0f;
}

#endif
