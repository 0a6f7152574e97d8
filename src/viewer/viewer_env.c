/* The mesh view's background on the CPU: the library's own camera and
 * background lookup (il_camera_ray_dir, il_background_radiance), one
 * direction per pixel centre, so the environment looks as `illum render`
 * shows it where a camera ray escapes. */
#include "viewer/viewer_env.h"

#include <stdlib.h>

#include "scene/camera.h"
#include "scene/lights.h"
#include "scene/scene.h"

bool il_view_has_environment(const il_scene *scene)
{
    return scene->has_environment || scene->num_discs > 0;
}

float *il_view_environment_pixels(const il_scene *scene, const il_camera_desc *camera, int w,
                                  int h)
{
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof *rgb + 1);
    if (!rgb)
        return NULL;
    il_camera cam;
    il_camera_init(&cam, camera, (uint32_t)w, (uint32_t)h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            il_vec3 d = il_camera_ray_dir(&cam, (float)x + 0.5f, (float)y + 0.5f);
            il_vec3 L = il_background_radiance(scene, d);
            float *p = rgb + ((size_t)y * (size_t)w + (size_t)x) * 3;
            p[0] = L.x;
            p[1] = L.y;
            p[2] = L.z;
        }
    return rgb;
}
