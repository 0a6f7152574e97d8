/* Helpers for the path tracer's validation tests: rendering through the
 * internal strategy switch, image means (scenes: tests/scene_build.h). */
#ifndef IL_TESTS_PT_SCENES_H
#define IL_TESTS_PT_SCENES_H

#include "scene_build.h"
#include "methods/pt/pt.h"
#include "scene/camera.h"

/* Renders with the given strategy into a new image (rgb NULL on failure). */
static inline il_image render_image(const il_scene *s, uint32_t w, uint32_t h, const il_render_desc *rd,
                             il_pt_strategy strategy, il_render_stats *stats)
{
    il_image img = {0};
    il_film *film = NULL;
    CHECK_OK(il_film_create(w, h, &film, &g_err), &g_err);
    if (!film)
        return img;
    CHECK_OK(il_pt_render(s, film, rd, strategy, stats, &g_err), &g_err);
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    il_film_release(film);
    return img;
}

/* Mean of channel c over the pixel rectangle [x0,x1) x [y0,y1). */
static inline double region_mean(const il_image *img, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, int c)
{
    double sum = 0.0;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++)
            sum += img->rgb[3 * ((size_t)y * img->width + x) + c];
    return sum / ((double)(x1 - x0) * (y1 - y0));
}

static inline double image_mean(const il_image *img, int c)
{
    return region_mean(img, 0, 0, img->width, img->height, c);
}

static inline bool image_finite(const il_image *img)
{
    for (size_t i = 0; i < 3 * (size_t)img->width * img->height; i++)
        if (!isfinite(img->rgb[i]))
            return false;
    return true;
}

/* Where the centre of pixel (x, y) looks at the plane y = plane_y (returns
 * false when it misses), through the same camera model as the renderer. */
static inline bool pixel_on_plane(const il_scene *s, uint32_t w, uint32_t h, uint32_t x, uint32_t y,
                           float plane_y, il_vec3 *out)
{
    il_camera_desc d;
    il_scene_get_camera(s, &d);
    il_camera cam;
    il_camera_init(&cam, &d, w, h);
    il_vec3 dir = il_camera_ray_dir(&cam, (float)x + 0.5f, (float)y + 0.5f);
    if (dir.y == 0.0f)
        return false;
    float t = (plane_y - cam.position.y) / dir.y;
    if (!(t > 0.0f))
        return false;
    *out = v3_fma(cam.position, dir, t);
    return true;
}

#endif
