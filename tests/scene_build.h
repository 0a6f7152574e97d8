/* Scenes built through the public API for the tests (unit and validation):
 * materials, quads, balls, the camera, committing, rendering to an image.
 * Every call is checked; g_err holds the last error. */
#ifndef IL_TESTS_SCENE_BUILD_H
#define IL_TESTS_SCENE_BUILD_H

#include <string.h>

#include "check.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "scene/loader.h"

#define PI_D 3.14159265358979323846

static il_error g_err;

static inline il_scene *new_scene(void)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &g_err), &g_err);
    return s;
}

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

/* The six faces of the cube [-1,1]^3, facing inwards (a closed box) or
 * outwards (a solid block): the same quads, their half-extents swapped. */
static inline void add_cube(il_scene *s, uint32_t m, bool inward)
{
    static const il_vec3 faces[6][3] = {
        {{0, -1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}},
    };
    for (int f = 0; f < 6; f++)
        add_quad(s, faces[f][0], faces[f][inward ? 1 : 2], faces[f][inward ? 2 : 1], m);
}

/* A ball of radius r centred at c: il_shape_sphere's UV sphere of 96
 * segments with smooth normals. */
static inline void add_ball(il_scene *s, il_vec3 c, float r, uint32_t mat)
{
    il_shape_mesh ball;
    CHECK_OK(il_shape_sphere(r, 96, &ball, &g_err), &g_err);
    if (!ball.positions)
        return;
    for (uint32_t v = 0; v < ball.num_vertices; v++) {
        ball.positions[3 * v + 0] += c.x;
        ball.positions[3 * v + 1] += c.y;
        ball.positions[3 * v + 2] += c.z;
    }
    il_mesh_desc md = {.num_vertices = ball.num_vertices, .num_triangles = ball.num_triangles,
                       .positions = ball.positions, .normals = ball.normals, .indices = ball.indices,
                       .material = mat};
    CHECK_OK(il_scene_add_mesh(s, &md, &g_err), &g_err);
    il_shape_free(&ball);
}

static inline void set_camera(il_scene *s, il_vec3 pos, il_vec3 target, il_vec3 up, float fov)
{
    il_camera_desc c = {.position = pos, .target = target, .up = up, .fov_y = fov};
    CHECK_OK(il_scene_set_camera(s, &c, &g_err), &g_err);
}

static inline void commit(il_scene *s)
{
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
}

/* A built-in scene (or a file), loaded and committed; NULL on failure. */
static inline il_scene *load_committed(const char *name)
{
    il_scene *s = NULL;
    il_status st = il_scene_load(name, NULL, &s, &g_err);
    if (st == IL_OK)
        st = il_scene_commit(s, &g_err);
    CHECK_OK(st, &g_err);
    if (st != IL_OK) {
        il_scene_release(s);
        return NULL;
    }
    return s;
}

/* Whether two images have the same size and the same bits. */
static inline bool images_identical(const il_image *a, const il_image *b)
{
    return a->rgb && b->rgb && a->width == b->width && a->height == b->height &&
           memcmp(a->rgb, b->rgb, sizeof(float) * 3 * (size_t)a->width * a->height) == 0;
}

/* Renders with rd through il_render into a new w x h image (rgb NULL on failure). */
static inline il_image render_desc_image(const il_scene *s, uint32_t w, uint32_t h,
                                         const il_render_desc *rd, il_render_stats *stats)
{
    il_film *film = NULL;
    il_image img = {0};
    CHECK_OK(il_film_create(w, h, &film, &g_err), &g_err);
    if (!film)
        return img;
    CHECK_OK(il_render(s, film, rd, stats, &g_err), &g_err);
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    il_film_release(film);
    return img;
}

#endif
