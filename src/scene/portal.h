/* Environment portals: the openings (windows, skylights, doors) through
 * which the environment's light enters an interior.
 *
 * Seen from inside a room, most directions of the sky are walls, so
 * sampling the environment by its own density sends most shadow rays into
 * them.  A portal is a set of triangles, each lighting the side its normal
 * faces (its corners counter-clockwise seen from there); from a point on
 * that side a direction is drawn towards a uniform point of the portals'
 * area.  (Bitterli et al. 2015, "Portal-Masked Environment Map Sampling",
 * and pbrt-v4 12.5.3 sample the map itself through one rectangle; the
 * portals' area needs no table per portal and takes any number of them.)
 * The environment's
 * strategy keeps a share (IL_PORTAL_SHARE of the draws go through portals),
 * so that points outside, or openings without a portal, are still sampled
 * well; both are combined as one mixture density (one-sample MIS with the
 * balance heuristic, Veach 1997, 9.2.4), which leaves the estimate unbiased
 * whatever the portals cover.  Portals are not geometry: rays pass them. */
#ifndef IL_SCENE_PORTAL_H
#define IL_SCENE_PORTAL_H

#include <stdbool.h>
#include "core/vec.h"

typedef struct il_scene il_scene;

/* The share of environment samples drawn through the portals at a point
 * that is on the lit side of at least one. */
#define IL_PORTAL_SHARE 0.8f

typedef struct il_portal {
    il_vec3 p0, e1, e2;    /* corners p0, p0 + e1, p0 + e2 */
    il_vec3 n;             /* unit normal towards the lit side */
    float area;
} il_portal;

/* The area of the portal triangles whose lit side holds p; 0 when none. */
float il_portal_area_seen(const il_scene *scene, il_vec3 p);

/* A direction from p through a uniform point of the portals that light p,
 * for u in [0,1)^2 and seen = il_portal_area_seen(p) > 0.  False when it
 * fails (a corner of rounding). */
bool il_portal_sample(const il_scene *scene, il_vec3 p, float seen, il_vec2 u, il_vec3 *dir);

/* The solid-angle density of il_portal_sample drawing dir (unit) from p:
 * the sum over the portal triangles lighting p that the ray crosses of
 * d^2 / (seen |cos|) (pbrt-v4 4.2.3's area-to-solid-angle change). */
float il_portal_pdf(const il_scene *scene, il_vec3 p, float seen, il_vec3 dir);

#endif
