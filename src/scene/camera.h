/* The pinhole camera: primary rays from an il_camera_desc.
 *
 * Conventions: right-handed, y up.  The camera looks from `position` towards
 * `target`; image x grows to the camera's right, right = cross(forward, up);
 * image y grows downwards (rows top to bottom, as il_image stores them).
 * fov_y is the full vertical field of view; the horizontal extent follows
 * from the aspect ratio width / height (pbrt-v4 5.2.1, PerspectiveCamera). */
#ifndef IL_SCENE_CAMERA_H
#define IL_SCENE_CAMERA_H

#include <stdint.h>
#include "core/vec.h"

typedef struct il_camera {
    il_vec3 position;
    il_vec3 forward, right, up;  /* orthonormal */
    float tan_half_y;            /* tan(fov_y / 2) */
    float tan_half_x;            /* tan_half_y * aspect */
    float inv_width, inv_height;
} il_camera;

/* Sets up the camera for an image of width x height pixels.  A zero up means
 * +y and a zero fov_y means 40 degrees, as in il_camera_desc. */
void il_camera_init(il_camera *cam, const il_camera_desc *desc, uint32_t width, uint32_t height);

/* The unit direction of the ray through the film position (fx, fy), in pixels:
 * (0, 0) is the top-left corner of the image, (width, height) the bottom-right;
 * the centre of pixel (x, y) is (x + 0.5, y + 0.5). */
il_vec3 il_camera_ray_dir(const il_camera *cam, float fx, float fy);

#endif
