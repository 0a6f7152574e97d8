/* Reflective shadow maps (`--method rsm`): Dachsbacher & Stamminger 2005,
 * "Reflective Shadow Maps" (I3D), with the sampling pattern and the shadow
 * test of Nilles 2017, "Light-Injection und Global Illumination mittels GPU
 * und der Linespace Datenstruktur" (eq. 11-14).  docs/rsm.md derives every
 * formula below.
 *
 * A map per light (rsm_build.c): texels ray cast from the light through a
 * perspective grid (spot; six cube faces for a point light or a wide spot)
 * or an orthographic one (directional light).  Each texel holds the first
 * surface its ray meets: position x_p, normal n_p (towards the light), the
 * area A_p of its footprint, and the flux it reflects,
 *     Phi_p = rho_p * (flux through the texel),
 * flux through the texel = I(w) dw (perspective) or E A_perp (orthographic).
 * Every texel is a small Lambertian emitter of radiance Phi_p / (pi A_p).
 *
 * The camera pass (rsm_render.c) shades the first non-specular surface x:
 * emission seen, direct light by next-event estimation as the path tracer,
 * and one bounce of indirect light (rsm_gather.c),
 *     L_ind(x, wo) = sum_p f(x, wo, w_p) E_p(x),
 *     E_p(x) = Phi_p / pi * cos_p cos_x / (r^2 + A_p / pi)
 * (Dachsbacher & Stamminger eq. 1 with the 1/pi of a Lambertian emitter and
 * the disk form factor of Wallace et al. 1989 that keeps it finite as r -> 0),
 * summed over every texel or estimated with the polar sampling pattern. */
#ifndef IL_METHODS_RSM_H
#define IL_METHODS_RSM_H

#include <stdbool.h>
#include <stdint.h>
#include "core/sampler.h"
#include "core/sampling.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/bsdf.h"
#include "scene/scene.h"

/* Renders into the film (cleared first); desc->rsm may be NULL (defaults).
 * stats may be NULL. */
il_status il_rsm_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        il_render_stats *stats, il_error *err);

/* ---- internals, shared by the files of this folder and the tests ---- */

#define IL_RSM_MAX_RESOLUTION 4096u
#define IL_RSM_MAX_SAMPLES 65536u
#define IL_RSM_MAX_RADIUS 2.0f
#define IL_RSM_MAX_MAPS 4096u
#define IL_RSM_DEFAULT_MAPS 8u
/* A spot whose cut-off half-angle exceeds this (degrees) gets six cube faces
 * instead of one perspective map (tan 60 = 1.73: texels at the edge of one
 * map would be 4 times the solid angle of those at its centre). */
#define IL_RSM_MAX_SPOT_ANGLE 60.0f

/* The options with their defaults resolved (rsm_settings.c). */
typedef struct il_rsm_settings {
    uint32_t resolution;
    uint32_t samples;
    float radius;
    bool all_texels;
    uint32_t maps;        /* per shading point; 0: every map */
    bool shadow_test;
    uint32_t max_depth;
} il_rsm_settings;

/* Checks desc (NULL: all defaults) and fills *out. */
il_status il_rsm_settings_resolve(const il_rsm_desc *desc, const il_render_desc *rd,
                                  il_rsm_settings *out, il_error *err);

/* One texel: the surface its ray met.  flux is zero where the ray missed,
 * met a mirror or glass, or carried no light (outside a spot's cone). */
typedef struct il_rsm_texel {
    il_vec3 p;            /* x_p */
    il_vec3 n;            /* n_p: unit, on the side the light came from */
    il_vec3 flux;         /* Phi_p, W */
    float area;           /* A_p, m^2 */
} il_rsm_texel;

/* One map (a spot, a cube face or a directional light's view).  Texel
 * (i, j) covers [i, i+1) x [j, j+1) / size of the map's (s, t) square; its
 * ray goes through the centre.  Perspective: from org along
 * w + (2s - 1) half u + (2t - 1) half v.  Orthographic: from
 * org + ((2s - 1) u + (2t - 1) v) half along w. */
typedef struct il_rsm_map {
    bool ortho;
    il_vec3 org;
    il_vec3 u, v, w;      /* orthonormal; w the axis (the way light travels) */
    float half;           /* perspective: tan of the half field; ortho: half side, m */
    uint32_t size;
    uint32_t light;       /* index into scene->lights */
    uint64_t texels;      /* texels with flux */
    il_rsm_texel *tex;    /* size * size, row j at tex + j * size */
} il_rsm_map;

typedef struct il_rsm {
    uint32_t count;
    il_rsm_map *maps;
    uint64_t rays;        /* cast building them */
    il_distrib1d choice;  /* count bins: the maps' probabilities in the choice of
                             il_rsm_gather (il_rsm_choice_init); n == 0: none */
} il_rsm;

/* Builds a map for every spot, point and directional light of the scene
 * (faces that no light reaches are left out); threads: OpenMP, 0 means all
 * cores.  Deterministic: texel rays go through texel centres. */
il_status il_rsm_build(const il_scene *scene, uint32_t resolution, int threads, il_rsm *out,
                       il_error *err);
void il_rsm_free(il_rsm *rsm);
uint64_t il_rsm_bytes(const il_rsm *rsm);

/* The shading point the maps light. */
typedef struct il_rsm_receiver {
    il_vec3 p;
    il_vec3 n;            /* shading normal, on wo's side */
    il_vec3 g;            /* geometric normal, on wo's side */
    il_vec3 wo;
    il_vec3 kd;           /* Lambertian: albedo / pi (the whole f); else unused */
    bool diffuse;
    const il_bsdf *bsdf;  /* for the other materials */
} il_rsm_receiver;

/* The sampling pattern shared by all shading points (rsm_gather.c): point
 * k of the (0,2)-sequence, xi_k = (xi1, xi2), as xi1 and the unit vector
 * (sin 2 pi xi2, cos 2 pi xi2); each shading point shifts it (Cranley &
 * Patterson 1976) by its own random numbers. */
typedef struct il_rsm_pattern {
    uint32_t count;
    float radius;
    float *xi1;
    il_vec2 *dir;
} il_rsm_pattern;

il_status il_rsm_pattern_init(il_rsm_pattern *pat, uint32_t count, float radius, il_error *err);
void il_rsm_pattern_free(il_rsm_pattern *pat);

/* What a gather counts. */
typedef struct il_rsm_counts {
    uint64_t gathered;
    uint64_t shadow_rays;
} il_rsm_counts;

/* Map m's (s, t) coordinates of x, clamped to the unit square (docs/rsm.md:
 * a point outside the map's view gathers around the nearest edge). */
il_vec2 il_rsm_project(const il_rsm_map *m, il_vec3 x);

/* Radiance reflected at the receiver towards wo by the light of texel t
 * (f E_p), zero when they face away from each other, or, with the shadow
 * test, when something lies between them. */
il_vec3 il_rsm_texel_light(const il_scene *scene, const il_rsm_texel *t, const il_rsm_receiver *r,
                           bool shadow_test, il_rsm_counts *counts);

/* The probabilities of the map choice (rsm_choice.c): half in proportion
 * to each map's reflected flux (the luminance of its texels' Phi_p summed),
 * half uniform, so no map that holds light is left out. */
il_status il_rsm_choice_init(il_rsm *rsm, il_error *err);

/* One bounce of indirect light at the receiver from the maps: the sum over
 * all texels (pat NULL), or the sampling pattern's estimate of it around
 * each map's projection of r->p, shifted by one 2D sample per map.  With
 * 0 < maps < rsm->count (and the choice initialised), the sum over maps is
 * estimated by `maps` maps drawn from rsm->choice, each weighted by
 * 1 / (maps pmf[m]). */
il_vec3 il_rsm_gather(const il_scene *scene, const il_rsm *rsm, const il_rsm_pattern *pat,
                      const il_rsm_receiver *r, bool shadow_test, uint32_t maps,
                      il_sampler *smp, il_rsm_counts *counts);

#endif
