/* The size of the part of a scene the camera sees (view_size.c): the scale
 * of the default search radii of photon mapping. */
#ifndef IL_METHODS_VIEW_SIZE_H
#define IL_METHODS_VIEW_SIZE_H

#include <stdbool.h>

#include "scene/scene.h"

/* The diagonal of the scene's bounding box, or, when the camera sees less
 * than half of that, the diagonal of what it sees: the box between the 5th
 * and the 95th percentile, along each axis, of the points a 32 x 32 grid of
 * camera rays hits.  1 for an empty box. */
float il_view_size(const il_scene *scene);

/* In a scene with portals, the interior they open around what the camera
 * sees: the box of the points a 32 x 32 grid of camera rays hits and of
 * those one diffuse bounce from each reaches, leaving out any seen through
 * a portal from its lit side, and true, when its diagonal is less than
 * half the bounding box's.  Else the bounding box, and false. */
bool il_view_interior(const il_scene *scene, il_vec3 *lo, il_vec3 *hi);

#endif
