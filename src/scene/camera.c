/* Pinhole camera; see camera.h. */
#include "scene/camera.h"

void il_camera_init(il_camera *cam, const il_camera_desc *d, uint32_t width, uint32_t height)
{
    il_vec3 up = v3_is_zero(d->up) ? v3(0.0f, 1.0f, 0.0f) : d->up;
    float fov = d->fov_y > 0.0f ? d->fov_y : 40.0f;
    cam->position = d->position;
    cam->forward = v3_normalize(v3_sub(d->target, d->position));
    cam->right = v3_normalize(v3_cross(cam->forward, up));
    cam->up = v3_cross(cam->right, cam->forward);
    cam->tan_half_y = tanf(0.5f * fov * IL_PI / 180.0f);
    float aspect = height > 0 ? (float)width / (float)height : 1.0f;
    cam->tan_half_x = cam->tan_half_y * aspect;
    cam->inv_width = width > 0 ? 1.0f / (float)width : 1.0f;
    cam->inv_height = height > 0 ? 1.0f / (float)height : 1.0f;
}

il_vec3 il_camera_ray_dir(const il_camera *cam, float fx, float fy)
{
    /* Normalised device coordinates in [-1, 1], y up. */
    float sx = (2.0f * fx * cam->inv_width - 1.0f) * cam->tan_half_x;
    float sy = (1.0f - 2.0f * fy * cam->inv_height) * cam->tan_half_y;
    il_vec3 d = v3_add(cam->forward, v3_add(v3_scale(cam->right, sx), v3_scale(cam->up, sy)));
    return v3_normalize(d);
}
