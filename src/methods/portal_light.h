/* Light entering by the portals, as a light of its own for the light paths
 * of photon mapping, SPPM and Linespace's injection (portal_light.c). */
#ifndef IL_METHODS_PORTAL_LIGHT_H
#define IL_METHODS_PORTAL_LIGHT_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "methods/light_emit.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* The most and (1 - it) the least share of the light paths that start at
 * the portals, in a scene where scene->portal_light is set. */
#define IL_PORTAL_LIGHT_SHARE_MAX 0.8f

/* The share of the light paths of photon mapping, SPPM and Linespace's
 * injection that start at the portals: the environment's weight in the
 * scene's light table, what the sky brings in by the portals
 * (scene/lights.c), against the lights' (a sun through a window, lamps
 * inside), whose own paths bring their light in; within
 * [1 - IL_PORTAL_LIGHT_SHARE_MAX, IL_PORTAL_LIGHT_SHARE_MAX].  In the
 * window room under a sun (0.2 instead of 0.8) Linespace's error fell from
 * 0.061 to 0.020, photon mapping's from 0.043 to 0.018; with a lamp (0.46)
 * from 0.0086 to 0.0055 and from 0.012 to 0.0069 (docs/photon-mapping.md,
 * "Windows": photon mapping could take it only once its search left out
 * the photons on the ground beside a wall without thickness). */
float il_portal_light_share(const il_scene *scene);

/* A light path from a uniform point of the portals into their lit side,
 * carrying what arrives there from outside (portal_light.c).  u_choice,
 * u_pos and u_dir in [0,1); rng feeds the look outside, a path-traced
 * sample of max_depth bounces; share: the share of the light paths drawn
 * so.  False when the draw carries nothing. */
bool il_portal_light_emit(const il_scene *scene, float u_choice, il_vec2 u_pos, il_vec2 u_dir,
                          il_pcg32 *rng, uint32_t max_depth, float share, il_light_emission *out);

/* Whether a render from the scene's camera splits its light paths at the
 * portals: the scene has portals and light from outside
 * (scene->portal_light), and the camera looks from the lit side of one,
 * from inside.  A camera outside sees light from outside, which the
 * lights' own paths bring: there the split wastes most paths (the window
 * room seen from its garden: photon mapping 20 times slower and no better,
 * Linespace 14 times the error). */
bool il_portal_light_wanted(const il_scene *scene);

/* Whether light path e ends on its segment `seg` (0: the one leaving the
 * light), the ray up to t_end (INFINITY when it leaves the scene), because
 * it enters by a portal there: the portals' light holds what it would
 * bring.  *t_cross (when not NULL): where it enters. */
bool il_portal_light_stops(const il_scene *scene, const il_light_emission *e, uint32_t seg,
                           const il_ray *ray, float t_end, float *t_cross);

/* For a method that keeps the interior's light alone (Linespace's
 * injection: the light outside, deposited in voxels that a wall splits,
 * would be read inside).  Whether light path e, whose first segment is
 * ray up to t_end, starts inside: always when its paths are not split;
 * from the portals, and from a point, spot or area light on a portal's lit
 * side (il_portal_area_seen, a hair along the path), yes; from a directional light or a lamp
 * elsewhere only when that segment enters by a portal (the sun, a street
 * lamp, through a window); from the environment never (its paths stop
 * where they enter). */
bool il_portal_light_starts_inside(const il_scene *scene, const il_light_emission *e,
                                   const il_ray *ray, float t_end);

/* Whether the segment ray up to t_end leaves by a portal (crosses one away
 * from its lit side, at *t_cross when not NULL) or enters by one, ending
 * past its plane (il_portal_exited, il_portal_entered, with the margin of
 * il_portal_light_stops). */
bool il_portal_light_leaves(const il_scene *scene, const il_ray *ray, float t_end, float *t_cross);
bool il_portal_light_enters(const il_scene *scene, const il_ray *ray, float t_end);

#endif
