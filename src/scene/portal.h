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
#include <stdint.h>
#include "core/vec.h"

typedef struct il_scene il_scene;

/* The share of environment samples drawn through the portals at a point
 * that is on the lit side of at least one. */
#define IL_PORTAL_SHARE 0.8f

/* A crossing nearly in a portal's plane counts for nothing (portal.c). */
#define IL_PORTAL_MIN_COS 1e-3f

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

/* Steering light paths (photons, Linespace injection) through the portals
 * (methods/light_emit.c): for a direction of travel dir, the portal
 * triangles the light enters by are those whose lit side dir points into
 * (cos = dir . n at least IL_PORTAL_MIN_COS, as for the draws above). */

/* Their projected area seen along dir: the sum of area * cos. */
float il_portal_projected_area(const il_scene *scene, il_vec3 dir);

/* A point of them, the triangle drawn by projected area (u.x) and the point
 * uniform in it; projected = il_portal_projected_area(dir) > 0.  The lines
 * along dir through such points have the density k / projected over the
 * plane perpendicular to dir, k the number of portal triangles the line
 * enters by (il_portal_lines_entering).  False when it fails (rounding). */
bool il_portal_sample_point(const il_scene *scene, il_vec3 dir, float projected, il_vec2 u,
                            il_vec3 *x);

/* How many portal triangles the whole line through p along dir (both ways
 * from p) enters by. */
uint32_t il_portal_lines_entering(const il_scene *scene, il_vec3 p, il_vec3 dir);

/* The portals' total area. */
float il_portal_total_area(const il_scene *scene);

/* A uniform point of all the portals (u in [0,1)^2, total = their area):
 * *x, and *n the normal of its triangle, towards the lit side. */
bool il_portal_point(const il_scene *scene, float total, il_vec2 u, il_vec3 *x, il_vec3 *n);

/* Whether the ray org + t dir (unit), t in (0, t_end), enters by a portal
 * triangle (crosses it towards its lit side) and ends more than `margin`
 * beyond the triangle's plane; *t_cross (when not NULL), the first such
 * crossing. */
bool il_portal_entered(const il_scene *scene, il_vec3 org, il_vec3 dir, float t_end, float margin,
                       float *t_cross);

/* The same for leaving by a portal: crossing it away from its lit side. */
bool il_portal_exited(const il_scene *scene, il_vec3 org, il_vec3 dir, float t_end, float margin,
                      float *t_cross);

#endif
