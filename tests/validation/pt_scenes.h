/* Helpers for the path tracer's validation tests: scenes built through the
 * public API, rendering through the internal strategy switch, image means. */
#ifndef IL_TESTS_PT_SCENES_H
#define IL_TESTS_PT_SCENES_H

#include <string.h>

#include "check.h"
#include "methods/pt/pt.h"
#include "scene/camera.h"

#define PI_D 3.14159265358979323846

static il_error g_err;

static inline uint32_t add_material(il_scene *s, il_material_desc d)
{
    uint32_t idx = 0;
    CHECK_OK(il_scene_add_material(s, &d, &idx, &g_err), &g_err);
    return idx;
}

/* A quad: centre c, half-extents ex and ey; its front face (normal) is cross(ex, ey). */
static inline void add_quad(il_scene *s, il_vec3 c, il_vec3 ex, il_vec3 ey, uint32_t mat)
{
    float p[12];
    const float sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; i++) {
        p[3 * i + 0] = c.x + sx[i] * ex.x + sy[i] * ey.x;
        p[3 * i + 1] = c.y + sx[i] * ex.y + sy[i] * ey.y;
        p[3 * i + 2] = c.z + sx[i] * ex.z + sy[i] * ey.z;
    }
    const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    il_mesh_desc m = {.num_vertices = 4, .num_triangles = 2, .positions = p, .indices = idx, .material = mat};
    CHECK_OK(il_scene_add_mesh(s, &m, &g_err), &g_err);
}

/* A horizontal square of half-size h at height y, facing up. */
static inline void add_floor(il_scene *s, float y, float h, uint32_t mat)
{
    add_quad(s, v3(0, y, 0), v3(0, 0, h), v3(h, 0, 0), mat);
}

static inline il_scene *new_scene(void)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &g_err), &g_err);
    return s;
}

static inline void set_camera(il_scene *s, il_vec3 pos, il_vec3 target, il_vec3 up, float fov)
{
    il_camera_desc c = {.position = pos, .target = target, .up = up, .fov_y = fov};
    CHECK_OK(il_scene_set_camera(s, &c, &g_err), &g_err);
}

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
