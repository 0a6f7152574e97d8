/* The Lambertian and Phong vertices of a wave, eight at a time: what the
 * wavefront methods (the path tracer, Linespace) compute at such a hit before they
 * trace on, a light sample with its shadow ray and a BSDF sample with the
 * next ray, made for many vertices together and bit for bit as the scalar
 * code makes it one vertex at a time (il_light_sample_at, il_bsdf_eval,
 * il_shadow_ray, il_bsdf_sample_dir_cos, il_offset_origin): see
 * diffuse_wave.c. */
#ifndef IL_METHODS_DIFFUSE_WAVE_H
#define IL_METHODS_DIFFUSE_WAVE_H

#include <stdbool.h>
#include <stdint.h>
#include "core/vec.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* One vertex: where the path hit (with its material), the direction back
 * along the path, the throughput so far, its light-choice number, its
 * lobe-choice number (a Phong surface's: il_bsdf_sample_dir_cos's u_lobe),
 * the point sample on the light, and the cosine-weighted direction drawn
 * for its BSDF pair (il_sample_cosine_hemisphere). */
typedef struct il_diffuse_in {
    const il_surface *surf;
    il_vec3 wo, beta;
    float u_select, u_lobe;
    il_vec2 u_light;
    il_vec3 cos_dir;
} il_diffuse_in;

/* How the light sample is weighted. */
typedef enum il_diffuse_nee {
    /* The path tracer's (pt_path.c): the power heuristic against the BSDF's
     * pdf, shadow_L = beta f Le |cos| w / pdf. */
    IL_DIFFUSE_NEE_MIS,
    /* il_direct_light_sample's (scene/direct.c): light sampling alone,
     * shadow_L = f Le |cos| / pdf, the throughput left to the caller. */
    IL_DIFFUSE_NEE_PLAIN
} il_diffuse_nee;

/* What was computed.  nee_done: the light sample was taken (the light
 * picked is a triangle of a mesh without authored normals, a point or spot
 * light, a directional light or the environment: see il_light_rec; for a
 * triangle of a mesh with normals the caller samples the light itself), and
 * `shadow` says
 * whether it casts shadow_ray carrying shadow_L.
 * next_done: the BSDF sample was taken (on a CPU with AVX2: always for a
 * Lambertian vertex, for a Phong one when u_lobe picks its diffuse lobe, the
 * glossy lobe's sample being left to the caller); next_ok when il_bsdf_sample_dir_cos succeeded and
 * il_sides_agree holds, then next_beta = beta times the sample's weight,
 * next_pdf its pdf and next_ray the ray the path continues with. */
typedef struct il_diffuse_out {
    bool nee_done, shadow, next_done, next_ok;
    il_ray shadow_ray;
    il_vec3 shadow_L;
    il_vec3 next_beta;
    float next_pdf;
    il_ray next_ray;
} il_diffuse_out;

/* For each in[i] whose material is Lambertian or Phong (IL_MATERIAL_DIFFUSE,
 * IL_MATERIAL_PHONG) fills *out[i]; the flags of the others are false. */
void il_diffuse_wave(const il_scene *scene, const il_diffuse_in *in, il_diffuse_out *const *out,
                     uint32_t n, il_diffuse_nee nee);

#endif
