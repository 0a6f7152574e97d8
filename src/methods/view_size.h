/* The size of the part of a scene the camera sees (view_size.c): the scale
 * of the default search radii of photon mapping. */
#ifndef IL_METHODS_VIEW_SIZE_H
#define IL_METHODS_VIEW_SIZE_H

#include "scene/scene.h"

/* The diagonal of the scene's bounding box, or, when the camera sees less
 * than half of that, the diagonal of what it sees: the box between the 5th
 * and the 95th percentile, along each axis, of the points a 32 x 32 grid of
 * camera rays hits.  1 for an empty box. */
float il_view_size(const il_scene *scene);

#endif
