/* Emitting one light path (a photon) from the scene's lights and scattering
 * it at a surface (light_emit.c): shared by photon mapping and Linespace
 * light injection. */
#ifndef IL_METHODS_LIGHT_EMIT_H
#define IL_METHODS_LIGHT_EMIT_H

#include <stdbool.h>
#include <stdint.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "core/vec.h"
#include "scene/bsdf.h"
#include "scene/scene.h"
#include "trace/trace.h"

typedef struct il_light_emission {
    il_vec3 p;         /* the point sampled on the light (or on the disk of a
                          directional light or the environment) */
    il_vec3 org;       /* where the photon ray starts: p, lifted off an area
                          light's surface to the side it leaves by */
    il_vec3 n;         /* AREA: the triangle's geometric normal; else zero */
    il_vec3 dir;       /* unit, the way the photon travels */
    il_vec3 power;     /* W: Le cos / (pmf pdf_area pdf_dir), the whole
                          emission as one photon (divide by the photons emitted) */
    uint32_t light;    /* index into scene->lights; IL_NO_LIGHT for the portals' light */
    bool split;        /* the light paths of this scene are split at its portals
                          (methods/portal_light.h): the lights' paths stop where
                          they enter by one, the portals' light brings it */
    bool portal;       /* the portals' light */
    bool scattered;    /* ... from a surface outside: the light has bounced
                          once already (indirect where it arrives) */
    bool caustic;      /* ... and that surface was a delta one */
    uint64_t rays;     /* rays cast to make it (the portals' light looks outside) */
} il_light_emission;

/* The random numbers one emission uses. */
#define IL_LIGHT_EMIT_DIMS 5

/* Picks a light by the scene's table with u[0] (scene->light_pmf and
 * light_cdf: by power, or in a scene with portals by what each brings in
 * by them), a point on it with u[1], u[2] and a direction with u[3], u[4];
 * each u in [0,1).  With portal_share in (0, 1) in a scene with portals
 * and light from outside (scene->portal_light), u[0] first chooses between
 * the lights and the portals' light (methods/portal_light.h; that share of
 * the paths start there), which draws from rng and
 * looks outside with a path-traced sample of max_depth bounces, and a
 * directional light's paths are partly drawn through the portals
 * (light_emit.c, emit_origin); out->split says that the caller must stop
 * the lights' paths where il_portal_light_stops says.  False when the
 * sample carries no power. */
bool il_light_emit(const il_scene *scene, const float u[IL_LIGHT_EMIT_DIMS], float portal_share,
                   il_pcg32 *rng, uint32_t max_depth, il_light_emission *out);

/* As il_light_emit, for a method that keeps the light inside alone
 * (Linespace's injection, methods/portal_light.h): split at the portals,
 * the lights' paths never start at the environment (its own paths would
 * keep nothing: the portals' paths bring its light in), the other lights
 * take its chance in proportion to theirs, and with the environment the
 * only light every path starts at the portals.  Unsplit, the same as
 * il_light_emit. */
bool il_light_emit_inside(const il_scene *scene, const float u[IL_LIGHT_EMIT_DIMS], float portal_share,
                          il_pcg32 *rng, uint32_t max_depth, il_light_emission *out);

/* One bounce of a light path at surface surf with BSDF b, seen from wo:
 * samples a direction with four numbers of rng (always drawn, so the
 * stream stays aligned), applies Russian roulette and sets *power and *ray
 * for the next segment; *delta says whether the bounce was specular.
 * False when the path ends here (absorbed). */
bool il_light_path_scatter(const il_tracer *tracer, const il_surface *surf, const il_bsdf *b,
                           il_vec3 wo, il_pcg32 *rng, il_vec3 *power, il_ray *ray, bool *delta);

#endif
