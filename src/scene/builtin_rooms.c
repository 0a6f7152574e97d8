/* The built-in radiosity rooms ("simple-room", "shadow-room", "box-room"),
 * after the test rooms of Nielsen 2018 ("Realtime Radiosity mit Nvidia
 * CUDA"): closed 4 x 3 x 4 m rooms lit by the ceiling, with a red left wall
 * and a green right wall.  Built only through the public API; every
 * dimension, reflectance and radiance is listed in docs/builtin-scenes.md and
 * checked by tests/unit/test_builtin_rooms.c.
 *
 * Frame: metres, y up; the room spans x in [-2, 2], y in [0, 3], z in [-2, 2].
 * The camera stands near the front wall (z = +2) looking along -z, so +x is
 * on the right of the image (right = forward x up = (0,0,-1) x (0,1,0) =
 * (1,0,0)): the red wall (x = -2) is on the left, the green wall (x = +2) on
 * the right.
 *
 * Every surface is made of axis-aligned rectangles, each 4 vertices and 2
 * triangles, counter-clockwise seen from its front: room walls face into the
 * room, boxes and the slab face outwards.  Surfaces are separate meshes, so
 * a uniform subdivision of level k gives 4^k patches per rectangle. */
#include "scene/builtin.h"

#include <string.h>

#include "core/vec.h"

#define ROOM_HALF_W 2.0f /* x in [-2, 2] */
#define ROOM_H 3.0f      /* y in [0, 3] */
#define ROOM_HALF_D 2.0f /* z in [-2, 2] */

#define ROOM_GREY 0.75f
#define ROOM_MAX_RECTS 6

/* An axis-aligned rectangle in the plane coordinate[axis] = at, spanning
 * [lo1, hi1] along axis (axis+1)%3 and [lo2, hi2] along (axis+2)%3, facing
 * +axis (sign > 0) or -axis (sign < 0). */
typedef struct room_rect {
    int axis;
    float at;
    float lo1, hi1, lo2, hi2;
    float sign;
} room_rect;

static void set_axis(float *p, int axis, float v) { p[axis] = v; }

/* Adds `n` rectangles as one mesh.  With a = axis, b = (a+1)%3, c = (a+2)%3,
 * e_b x e_c = +e_a, so the corners (lo1,lo2) (hi1,lo2) (hi1,hi2) (lo1,hi2)
 * are counter-clockwise seen from +a; for sign < 0 they are taken in the
 * reverse order. */
static il_status add_rects(il_scene *scene, const char *name, const room_rect *r, int n,
                           uint32_t material, il_error *err)
{
    float pos[ROOM_MAX_RECTS * 4 * 3];
    uint32_t idx[ROOM_MAX_RECTS * 6];
    for (int q = 0; q < n; q++) {
        const int a = r[q].axis, b = (a + 1) % 3, c = (a + 2) % 3;
        const float uv[4][2] = {{r[q].lo1, r[q].lo2}, {r[q].hi1, r[q].lo2},
                                {r[q].hi1, r[q].hi2}, {r[q].lo1, r[q].hi2}};
        for (int v = 0; v < 4; v++) {
            int k = r[q].sign > 0.0f ? v : 3 - v;
            float *p = pos + (q * 4 + v) * 3;
            set_axis(p, a, r[q].at);
            set_axis(p, b, uv[k][0]);
            set_axis(p, c, uv[k][1]);
        }
        uint32_t base = (uint32_t)q * 4;
        const uint32_t tri[6] = {base, base + 1, base + 2, base, base + 2, base + 3};
        memcpy(idx + q * 6, tri, sizeof tri);
    }
    il_mesh_desc md = {
        .name = name,
        .num_vertices = (uint32_t)n * 4,
        .num_triangles = (uint32_t)n * 2,
        .positions = pos,
        .indices = idx,
        .material = material,
    };
    return il_scene_add_mesh(scene, &md, err);
}

static il_status add_material(il_scene *scene, const char *name, il_vec3 diffuse, il_vec3 emission,
                              uint32_t *out, il_error *err)
{
    il_material_desc m = {.name = name, .type = IL_MATERIAL_DIFFUSE, .diffuse = diffuse,
                          .emission = emission};
    return il_scene_add_material(scene, &m, out, err);
}

typedef struct room_materials {
    uint32_t grey, red, green;
} room_materials;

static il_status add_room_materials(il_scene *scene, room_materials *m, il_error *err)
{
    il_status st;
    if ((st = add_material(scene, "grey", v3s(ROOM_GREY), v3s(0.0f), &m->grey, err)) != IL_OK ||
        (st = add_material(scene, "red", v3(0.75f, 0.1f, 0.1f), v3s(0.0f), &m->red, err)) != IL_OK ||
        (st = add_material(scene, "green", v3(0.1f, 0.75f, 0.1f), v3s(0.0f), &m->green, err)) != IL_OK)
        return st;
    return IL_OK;
}

/* Floor, back, front, left (red) and right (green) walls, facing inwards.
 * The ceiling is the caller's (it differs between rooms). */
static il_status add_walls(il_scene *scene, const room_materials *m, il_error *err)
{
    const float W = ROOM_HALF_W, H = ROOM_H, D = ROOM_HALF_D;
    /* axis 1 (y): spans z then x; axis 2 (z): spans x then y; axis 0 (x): spans y then z. */
    const room_rect floor_r = {1, 0.0f, -D, D, -W, W, +1.0f};
    const room_rect back = {2, -D, -W, W, 0.0f, H, +1.0f};
    const room_rect front = {2, D, -W, W, 0.0f, H, -1.0f};
    const room_rect left = {0, -W, 0.0f, H, -D, D, +1.0f};
    const room_rect right = {0, W, 0.0f, H, -D, D, -1.0f};
    il_status st;
    if ((st = add_rects(scene, "floor", &floor_r, 1, m->grey, err)) != IL_OK ||
        (st = add_rects(scene, "back_wall", &back, 1, m->grey, err)) != IL_OK ||
        (st = add_rects(scene, "front_wall", &front, 1, m->grey, err)) != IL_OK ||
        (st = add_rects(scene, "left_wall_red", &left, 1, m->red, err)) != IL_OK ||
        (st = add_rects(scene, "right_wall_green", &right, 1, m->green, err)) != IL_OK)
        return st;
    return IL_OK;
}

static il_status set_camera(il_scene *scene, il_vec3 position, il_vec3 target, float fov_y,
                            il_error *err)
{
    il_camera_desc cam = {.position = position, .target = target, .up = {0.0f, 1.0f, 0.0f},
                          .fov_y = fov_y};
    return il_scene_set_camera(scene, &cam, err);
}

/* The whole ceiling (y = 3, facing down) as one rectangle. */
static il_status add_full_ceiling(il_scene *scene, uint32_t material, il_error *err)
{
    const room_rect ceiling = {1, ROOM_H, -ROOM_HALF_D, ROOM_HALF_D, -ROOM_HALF_W, ROOM_HALF_W, -1.0f};
    return add_rects(scene, "ceiling_light", &ceiling, 1, material, err);
}

/* The ceiling emits radiance 1 (white) and, like the walls, reflects 0.75. */
static il_status add_simple_room(il_scene *scene, room_materials *m, il_error *err)
{
    uint32_t light;
    il_status st;
    if ((st = add_room_materials(scene, m, err)) != IL_OK ||
        (st = add_material(scene, "ceiling_light", v3s(ROOM_GREY), v3s(1.0f), &light, err)) != IL_OK ||
        (st = add_walls(scene, m, err)) != IL_OK ||
        (st = add_full_ceiling(scene, light, err)) != IL_OK)
        return st;
    return IL_OK;
}

il_status il_builtin_simple_room(il_scene *scene, il_error *err)
{
    room_materials m;
    il_status st = add_simple_room(scene, &m, err);
    if (st != IL_OK)
        return st;
    return set_camera(scene, v3(0.0f, 1.5f, 1.95f), v3(0.0f, 1.5f, -2.0f), 60.0f, err);
}

/* The slab: a closed 2 cm box centred at half height (y 1.49 .. 1.51) over
 * the back two thirds of the room (z -1.99 .. 2/3), 1 cm clear of the side
 * and back walls so that none of its faces lies in a wall's plane. */
#define SLAB_Y0 1.49f
#define SLAB_Y1 1.51f
#define SLAB_X 1.99f
#define SLAB_Z0 -1.99f
#define SLAB_Z1 (2.0f / 3.0f)

il_status il_builtin_shadow_room(il_scene *scene, il_error *err)
{
    room_materials m;
    il_status st;
    if ((st = add_simple_room(scene, &m, err)) != IL_OK)
        return st;
    const room_rect slab[6] = {
        {1, SLAB_Y1, SLAB_Z0, SLAB_Z1, -SLAB_X, SLAB_X, +1.0f}, /* top */
        {1, SLAB_Y0, SLAB_Z0, SLAB_Z1, -SLAB_X, SLAB_X, -1.0f}, /* underside */
        {2, SLAB_Z1, -SLAB_X, SLAB_X, SLAB_Y0, SLAB_Y1, +1.0f}, /* front edge */
        {2, SLAB_Z0, -SLAB_X, SLAB_X, SLAB_Y0, SLAB_Y1, -1.0f}, /* back edge */
        {0, SLAB_X, SLAB_Y0, SLAB_Y1, SLAB_Z0, SLAB_Z1, +1.0f}, /* right edge */
        {0, -SLAB_X, SLAB_Y0, SLAB_Y1, SLAB_Z0, SLAB_Z1, -1.0f}, /* left edge */
    };
    if ((st = add_rects(scene, "slab", slab, 6, m.grey, err)) != IL_OK)
        return st;
    /* Below the slab's height, looking slightly up: the dark space under the
     * slab and the lit front third are both in view. */
    return set_camera(scene, v3(0.0f, 1.1f, 1.95f), v3(0.0f, 1.3f, -2.0f), 60.0f, err);
}

/* A box standing on the floor: top and four sides (no bottom), facing out. */
typedef struct room_box {
    const char *name;
    float x0, x1, z0, z1, h;
    il_vec3 colour;
} room_box;

static const room_box room_boxes[4] = {
    {"box_blue", -1.4f, -0.6f, -1.2f, -0.4f, 0.8f, {0.1f, 0.2f, 0.7f}},
    {"box_yellow", 0.5f, 1.3f, -1.5f, -0.7f, 1.2f, {0.75f, 0.7f, 0.1f}},
    {"box_white", -0.3f, 0.3f, -0.3f, 0.3f, 0.5f, {0.75f, 0.75f, 0.75f}},
    {"box_cyan", 0.9f, 1.6f, -0.2f, 0.5f, 0.4f, {0.1f, 0.6f, 0.6f}},
};

static il_status add_box(il_scene *scene, const room_box *b, uint32_t material, il_error *err)
{
    const room_rect faces[5] = {
        {1, b->h, b->z0, b->z1, b->x0, b->x1, +1.0f},  /* top */
        {2, b->z1, b->x0, b->x1, 0.0f, b->h, +1.0f},   /* front (+z) */
        {2, b->z0, b->x0, b->x1, 0.0f, b->h, -1.0f},   /* back (-z) */
        {0, b->x1, 0.0f, b->h, b->z0, b->z1, +1.0f},   /* right (+x) */
        {0, b->x0, 0.0f, b->h, b->z0, b->z1, -1.0f},   /* left (-x) */
    };
    return add_rects(scene, b->name, faces, 5, material, err);
}

/* The lamp: the ceiling quarter x in [-2, 0], z in [-2, 0] (back left seen
 * from the camera), radiance 4 so the room receives the same power as the
 * simple room's whole ceiling at radiance 1.  The other three quarters are
 * one grey mesh. */
il_status il_builtin_box_room(il_scene *scene, il_error *err)
{
    room_materials m;
    uint32_t lamp;
    il_status st;
    if ((st = add_room_materials(scene, &m, err)) != IL_OK ||
        (st = add_material(scene, "lamp", v3s(ROOM_GREY), v3s(4.0f), &lamp, err)) != IL_OK ||
        (st = add_walls(scene, &m, err)) != IL_OK)
        return st;
    const float H = ROOM_H, W = ROOM_HALF_W, D = ROOM_HALF_D;
    /* axis 1 spans z then x; facing down. */
    const room_rect lamp_r = {1, H, -D, 0.0f, -W, 0.0f, -1.0f};
    const room_rect rest[3] = {
        {1, H, 0.0f, D, -W, 0.0f, -1.0f},
        {1, H, -D, 0.0f, 0.0f, W, -1.0f},
        {1, H, 0.0f, D, 0.0f, W, -1.0f},
    };
    if ((st = add_rects(scene, "ceiling", rest, 3, m.grey, err)) != IL_OK ||
        (st = add_rects(scene, "lamp", &lamp_r, 1, lamp, err)) != IL_OK)
        return st;
    for (int i = 0; i < 4; i++) {
        uint32_t mat;
        if ((st = add_material(scene, room_boxes[i].name, room_boxes[i].colour, v3s(0.0f), &mat, err)) !=
                IL_OK ||
            (st = add_box(scene, &room_boxes[i], mat, err)) != IL_OK)
            return st;
    }
    /* A wider view, so the lamp and all four boxes are in the picture. */
    return set_camera(scene, v3(0.0f, 1.6f, 1.95f), v3(0.0f, 1.1f, -2.0f), 75.0f, err);
}
