/* The background's radiance (the sky and the sun's disc) through every
 * pixel centre of a camera (viewer_env.c): the mesh view's background.
 * Apart from the window's files, which do not see the library's internal
 * headers. */
#ifndef IL_VIEWER_ENV_H
#define IL_VIEWER_ENV_H

#include <stdbool.h>
#include "illum/illum.h"

/* Whether the scene has an environment (a sky or a map) or a sun's disc to show. */
bool il_view_has_environment(const il_scene *scene);
/* w x h pixels, rows top to bottom, 3 floats each (W/(sr m^2)); NULL without
 * memory.  The caller frees it. */
float *il_view_environment_pixels(const il_scene *scene, const il_camera_desc *camera, int w,
                                  int h);

#endif
