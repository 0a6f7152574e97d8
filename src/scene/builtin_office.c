/* The built-in furnished office ("office"), a test room for hierarchical
 * radiosity sized like the classic HSA/SPLASH-2 rooms (several hundred input
 * polygons): an 8 x 3 x 6 m windowless room with six desks and chairs, three
 * bookshelves with books, a free-standing partition that shadows the back
 * right corner, and six ceiling lamps.  Built only through the public API;
 * every dimension, reflectance and radiance is listed in
 * docs/builtin-scenes.md and checked by tests/unit/test_builtin_office.c.
 *
 * Frame: metres, y up; the room spans x in [-4, 4], y in [0, 3], z in
 * [-3, 3].  The camera stands near the front wall (z = +3) looking along -z.
 *
 * Every polygon is an axis-aligned rectangle (4 vertices, 2 triangles, no
 * shared vertices), counter-clockwise seen from its front: the room's
 * surfaces face into the room, furniture boxes face outwards.  Faces that
 * would touch another surface (a leg's top under a desk, a book's bottom on
 * its shelf, a shelf board's ends against the side panels) are left out, so
 * no two polygons overlap in one plane.  One mesh per kind of object. */
#include "scene/builtin.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/vec.h"

#define OFFICE_HALF_W 4.0f /* x in [-4, 4] */
#define OFFICE_H 3.0f      /* y in [0, 3] */
#define OFFICE_HALF_D 3.0f /* z in [-3, 3] */
#define OFFICE_MAX_QUADS 160

/* Face bits of an axis-aligned box: bit 2*axis for the +axis face, bit
 * 2*axis+1 for the -axis face. */
#define F_PX 0x01u
#define F_NX 0x02u
#define F_PY 0x04u
#define F_NY 0x08u
#define F_PZ 0x10u
#define F_NZ 0x20u
#define F_ALL 0x3fu
#define F_NO_BOTTOM (F_ALL & ~F_NY)
#define F_SIDES (F_PX | F_NX | F_PZ | F_NZ)

/* The rectangles of one mesh, gathered before il_scene_add_mesh. */
typedef struct quad_list {
    int n;
    bool overflow;
    float pos[OFFICE_MAX_QUADS * 4 * 3];
    uint32_t idx[OFFICE_MAX_QUADS * 6];
} quad_list;

/* A rectangle in the plane coordinate[a] = at, spanning [lo[b], hi[b]] and
 * [lo[c], hi[c]] with b = (a+1)%3, c = (a+2)%3, facing +a (sign > 0) or -a.
 * As e_b x e_c = +e_a, the corners (lo,lo) (hi,lo) (hi,hi) (lo,hi) in (b,c)
 * are counter-clockwise seen from +a; for sign < 0 they are reversed. */
static void add_rect(quad_list *q, int a, float at, const float lo[3], const float hi[3], float sign)
{
    if (q->n == OFFICE_MAX_QUADS) {
        q->overflow = true;
        return;
    }
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const float uv[4][2] = {{lo[b], lo[c]}, {hi[b], lo[c]}, {hi[b], hi[c]}, {lo[b], hi[c]}};
    for (int v = 0; v < 4; v++) {
        const int k = sign > 0.0f ? v : 3 - v;
        float *p = q->pos + (q->n * 4 + v) * 3;
        p[a] = at;
        p[b] = uv[k][0];
        p[c] = uv[k][1];
    }
    const uint32_t base = (uint32_t)q->n * 4;
    const uint32_t tri[6] = {base, base + 1, base + 2, base, base + 2, base + 3};
    memcpy(q->idx + q->n * 6, tri, sizeof tri);
    q->n++;
}

/* The faces of the box [lo, hi] named by `faces`, facing outwards. */
static void add_box(quad_list *q, il_vec3 lo, il_vec3 hi, unsigned faces)
{
    const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    for (int a = 0; a < 3; a++) {
        if (faces & (1u << (2 * a)))
            add_rect(q, a, h[a], l, h, +1.0f);
        if (faces & (1u << (2 * a + 1)))
            add_rect(q, a, l[a], l, h, -1.0f);
    }
}

/* One side of the room: the rectangle [lo, hi] (flat along axis a) cut into
 * nb x nc equal rectangles facing `sign`. */
static void add_grid(quad_list *q, int a, il_vec3 lo, il_vec3 hi, int nb, int nc, float sign)
{
    const float l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int i = 0; i < nb; i++)
        for (int j = 0; j < nc; j++) {
            float cl[3], ch[3];
            cl[a] = ch[a] = l[a];
            cl[b] = l[b] + (h[b] - l[b]) * (float)i / (float)nb;
            ch[b] = l[b] + (h[b] - l[b]) * (float)(i + 1) / (float)nb;
            cl[c] = l[c] + (h[c] - l[c]) * (float)j / (float)nc;
            ch[c] = l[c] + (h[c] - l[c]) * (float)(j + 1) / (float)nc;
            add_rect(q, a, l[a], cl, ch, sign);
        }
}

static il_status add_material(il_scene *scene, const char *name, il_vec3 diffuse, il_vec3 emission,
                              uint32_t *out, il_error *err)
{
    il_material_desc m = {.name = name, .type = IL_MATERIAL_DIFFUSE, .diffuse = diffuse,
                          .emission = emission};
    return il_scene_add_material(scene, &m, out, err);
}

static il_status add_mesh(il_scene *scene, const char *name, const quad_list *q, uint32_t material,
                          il_error *err)
{
    if (q->overflow) /* a programming error: OFFICE_MAX_QUADS is too small */
        return il_fail(err, IL_ERR_INVALID, "office: mesh %s has more than %d rectangles", name,
                       OFFICE_MAX_QUADS);
    il_mesh_desc md = {
        .name = name,
        .num_vertices = (uint32_t)q->n * 4,
        .num_triangles = (uint32_t)q->n * 2,
        .positions = q->pos,
        .indices = q->idx,
        .material = material,
    };
    return il_scene_add_mesh(scene, &md, err);
}

/* Desks: a 1.4 x 0.7 m top, 3 cm thick, at 0.72-0.75 m, on four 5 cm legs
 * inset 5 cm from its corners.  Chairs stand on the +z side of their desk. */
static const float office_desks[6][2] = {
    {-2.6f, -1.6f}, {-0.8f, -1.6f}, {-2.6f, 0.6f}, {-0.8f, 0.6f}, {2.6f, -1.6f}, {2.6f, 0.6f},
};

static void build_desk(quad_list *tops, quad_list *legs, float cx, float cz)
{
    add_box(tops, v3(cx - 0.7f, 0.72f, cz - 0.35f), v3(cx + 0.7f, 0.75f, cz + 0.35f), F_ALL);
    for (int i = 0; i < 4; i++) {
        const float x = cx + (i & 1 ? 0.6f : -0.65f), z = cz + (i & 2 ? 0.25f : -0.3f);
        add_box(legs, v3(x, 0.0f, z), v3(x + 0.05f, 0.72f, z + 0.05f), F_SIDES);
    }
}

/* A chair: a 0.45 m square seat (0.42-0.47 m), a backrest on its +z edge up
 * to 0.95 m standing on the seat, four 4 cm legs under the seat's corners. */
static void build_chair(quad_list *seats, quad_list *legs, float cx, float cz)
{
    const float x0 = cx - 0.225f, x1 = cx + 0.225f, z0 = cz - 0.225f, z1 = cz + 0.225f;
    add_box(seats, v3(x0, 0.42f, z0), v3(x1, 0.47f, z1), F_ALL);
    add_box(seats, v3(x0, 0.47f, z1 - 0.04f), v3(x1, 0.95f, z1), F_NO_BOTTOM);
    for (int i = 0; i < 4; i++) {
        const float x = i & 1 ? x1 - 0.06f : x0 + 0.02f, z = i & 2 ? z1 - 0.06f : z0 + 0.02f;
        add_box(legs, v3(x, 0.0f, z), v3(x + 0.04f, 0.42f, z + 0.04f), F_SIDES);
    }
}

/* A bookshelf against a wall, built in its own frame: u along the wall, y
 * up, w out of the wall.  World axis au = origin_u + su * u and
 * aw = origin_w + sw * w (the third world axis is y). */
typedef struct shelf_frame {
    int au, aw;
    float origin_u, su, origin_w, sw;
} shelf_frame;

/* The box u in [u0, u1], y in [y0, y1], w in [w0, w1] in world space, with
 * the local faces (bits as F_*: x = u, z = w) mapped onto world faces. */
static void shelf_box(quad_list *q, const shelf_frame *f, float u0, float u1, float y0, float y1,
                      float w0, float w1, unsigned faces)
{
    float lo[3], hi[3];
    const float ua = f->origin_u + f->su * u0, ub = f->origin_u + f->su * u1;
    const float wa = f->origin_w + f->sw * w0, wb = f->origin_w + f->sw * w1;
    lo[f->au] = il_minf(ua, ub);
    hi[f->au] = il_maxf(ua, ub);
    lo[f->aw] = il_minf(wa, wb);
    hi[f->aw] = il_maxf(wa, wb);
    lo[1] = y0;
    hi[1] = y1;
    unsigned world = faces & (F_PY | F_NY);
    const unsigned up = faces & F_PX ? 1u : 0u, un = faces & F_NX ? 1u : 0u;
    const unsigned wp = faces & F_PZ ? 1u : 0u, wn = faces & F_NZ ? 1u : 0u;
    /* +u is +au when su > 0, else -au (and likewise for w). */
    world |= (f->su > 0.0f ? up : un) << (2 * f->au);
    world |= (f->su > 0.0f ? un : up) << (2 * f->au + 1);
    world |= (f->sw > 0.0f ? wp : wn) << (2 * f->aw);
    world |= (f->sw > 0.0f ? wn : wp) << (2 * f->aw + 1);
    add_box(q, v3(lo[0], lo[1], lo[2]), v3(hi[0], hi[1], hi[2]), world);
}

#define SHELF_W 1.2f   /* along the wall */
#define SHELF_D 0.35f  /* out of the wall */
#define SHELF_H 1.9f

/* Board bottoms; boards are 3 cm thick, between the 2 cm side panels. */
static const float shelf_boards[5] = {0.05f, 0.50f, 0.95f, 1.40f, 1.87f};

/* Books stand on boards 1 and 2, three each, 1 cm apart: u start, width,
 * height, and colour (0 red, 1 green, 2 blue), 24 cm deep from w = 0.05. */
typedef struct shelf_book {
    float u, width, height;
    int colour;
} shelf_book;

static const shelf_book shelf_books[2][3] = {
    {{0.10f, 0.05f, 0.28f, 0}, {0.16f, 0.07f, 0.24f, 1}, {0.24f, 0.04f, 0.30f, 2}},
    {{0.55f, 0.06f, 0.26f, 2}, {0.62f, 0.05f, 0.30f, 0}, {0.68f, 0.08f, 0.22f, 1}},
};

static void build_shelf(quad_list *wood, quad_list *books[3], const shelf_frame *f)
{
    shelf_box(wood, f, 0.0f, 0.02f, 0.0f, SHELF_H, 0.0f, SHELF_D, F_NO_BOTTOM);
    shelf_box(wood, f, SHELF_W - 0.02f, SHELF_W, 0.0f, SHELF_H, 0.0f, SHELF_D, F_NO_BOTTOM);
    for (int k = 0; k < 5; k++)
        shelf_box(wood, f, 0.02f, SHELF_W - 0.02f, shelf_boards[k], shelf_boards[k] + 0.03f, 0.0f,
                  SHELF_D, F_PY | F_NY | F_PZ | F_NZ);
    for (int k = 0; k < 2; k++) {
        const float y0 = shelf_boards[k + 1] + 0.03f;
        for (int i = 0; i < 3; i++) {
            const shelf_book *b = &shelf_books[k][i];
            shelf_box(books[b->colour], f, b->u, b->u + b->width, y0, y0 + b->height, 0.05f, 0.29f,
                      F_NO_BOTTOM);
        }
    }
}

/* Lamps: 1.2 x 0.6 m panels 1 cm below the ceiling, facing down, radiance
 * 10 W/(sr m^2); in two rows of three. */
#define LAMP_Y 2.99f
#define LAMP_RADIANCE 10.0f
static const float office_lamps[6][2] = {
    {-2.5f, -1.5f}, {0.0f, -1.5f}, {2.5f, -1.5f}, {-2.5f, 1.5f}, {0.0f, 1.5f}, {2.5f, 1.5f},
};

typedef struct office_material {
    const char *name;
    il_vec3 diffuse;
} office_material;

/* Linear Rec.709 reflectances. */
enum { M_WALL, M_CEILING, M_FLOOR, M_DESK, M_METAL, M_FABRIC, M_DARK, M_PARTITION, M_SHELF,
       M_BOOK_RED, M_BOOK_GREEN, M_BOOK_BLUE, M_COUNT };
static const office_material office_materials[M_COUNT] = {
    {"wall", {0.70f, 0.68f, 0.63f}},      {"ceiling", {0.80f, 0.80f, 0.80f}},
    {"carpet", {0.25f, 0.27f, 0.30f}},    {"desk_wood", {0.55f, 0.40f, 0.25f}},
    {"metal", {0.30f, 0.30f, 0.32f}},     {"chair_fabric", {0.12f, 0.20f, 0.50f}},
    {"chair_frame", {0.08f, 0.08f, 0.08f}}, {"partition", {0.40f, 0.45f, 0.50f}},
    {"shelf_wood", {0.65f, 0.55f, 0.40f}}, {"book_red", {0.60f, 0.10f, 0.08f}},
    {"book_green", {0.10f, 0.45f, 0.15f}}, {"book_blue", {0.10f, 0.15f, 0.55f}},
};

/* Everything but the room shell; q[0..4] are scratch lists. */
static il_status add_furniture(il_scene *scene, const uint32_t *mat, quad_list *q, il_error *err)
{
    quad_list *q2 = q + 1;
    il_status st;
    /* Desks (tops and legs) and chairs (seats with backrests, and legs). */
    q->n = q2->n = 0;
    for (int i = 0; i < 6; i++)
        build_desk(q, q2, office_desks[i][0], office_desks[i][1]);
    if ((st = add_mesh(scene, "desk_tops", q, mat[M_DESK], err)) != IL_OK ||
        (st = add_mesh(scene, "desk_legs", q2, mat[M_METAL], err)) != IL_OK)
        return st;
    q->n = q2->n = 0;
    for (int i = 0; i < 6; i++)
        build_chair(q, q2, office_desks[i][0], office_desks[i][1] + 0.7f);
    if ((st = add_mesh(scene, "chairs", q, mat[M_FABRIC], err)) != IL_OK ||
        (st = add_mesh(scene, "chair_legs", q2, mat[M_DARK], err)) != IL_OK)
        return st;

    /* The partition: 6 cm thick, 1.8 m high, z in [-2.4, 1.2] at x = 1,
     * screening the back right desks from the lamps at x <= 0. */
    q->n = 0;
    add_box(q, v3(0.97f, 0.0f, -2.4f), v3(1.03f, 1.8f, 1.2f), F_NO_BOTTOM);
    if ((st = add_mesh(scene, "partition", q, mat[M_PARTITION], err)) != IL_OK)
        return st;

    /* Three bookshelves, 1 cm clear of their wall: two on the back wall
     * (u = x), one on the right wall facing -x (u = z). */
    const shelf_frame frames[3] = {
        {0, 2, -3.6f, 1.0f, -OFFICE_HALF_D + 0.01f, 1.0f},
        {0, 2, -1.4f, 1.0f, -OFFICE_HALF_D + 0.01f, 1.0f},
        {2, 0, -2.0f, 1.0f, OFFICE_HALF_W - 0.01f, -1.0f},
    };
    quad_list *books[3] = {q + 2, q + 3, q + 4};
    for (int i = 0; i < 5; i++)
        q[i].n = 0;
    for (int s = 0; s < 3; s++)
        build_shelf(q, books, &frames[s]);
    static const char *const book_meshes[3] = {"books_red", "books_green", "books_blue"};
    if ((st = add_mesh(scene, "shelves", q, mat[M_SHELF], err)) != IL_OK)
        return st;
    for (int colour = 0; colour < 3; colour++)
        if ((st = add_mesh(scene, book_meshes[colour], books[colour], mat[M_BOOK_RED + colour], err)) !=
            IL_OK)
            return st;
    return IL_OK;
}

il_status il_builtin_office(il_scene *scene, il_error *err)
{
    uint32_t mat[M_COUNT], lamp;
    il_status st;
    for (int i = 0; i < M_COUNT; i++)
        if ((st = add_material(scene, office_materials[i].name, office_materials[i].diffuse,
                               v3s(0.0f), &mat[i], err)) != IL_OK)
            return st;
    if ((st = add_material(scene, "lamp", v3s(0.8f), v3s(LAMP_RADIANCE), &lamp, err)) != IL_OK)
        return st;

    /* Five lists of up to OFFICE_MAX_QUADS rectangles (about 60 KB): on the heap. */
    quad_list *q = calloc(5, sizeof *q);
    if (!q)
        return il_fail(err, IL_ERR_MEMORY, "office: out of memory");
    const float W = OFFICE_HALF_W, H = OFFICE_H, D = OFFICE_HALF_D;

    /* The shell, facing into the room: floor and ceiling in 2 x 2 m
     * squares, the walls in 2 x 1.5 m rectangles. */
    q->n = 0;
    add_grid(q, 1, v3(-W, 0.0f, -D), v3(W, 0.0f, D), 3, 4, +1.0f);
    st = add_mesh(scene, "floor", q, mat[M_FLOOR], err);
    if (st == IL_OK) {
        q->n = 0;
        add_grid(q, 1, v3(-W, H, -D), v3(W, H, D), 3, 4, -1.0f);
        st = add_mesh(scene, "ceiling", q, mat[M_CEILING], err);
    }
    if (st == IL_OK) {
        q->n = 0;
        add_grid(q, 2, v3(-W, 0.0f, -D), v3(W, H, -D), 4, 2, +1.0f); /* back, z = -3 */
        add_grid(q, 2, v3(-W, 0.0f, D), v3(W, H, D), 4, 2, -1.0f);   /* front, z = +3 */
        add_grid(q, 0, v3(-W, 0.0f, -D), v3(-W, H, D), 2, 3, +1.0f); /* left, x = -4 */
        add_grid(q, 0, v3(W, 0.0f, -D), v3(W, H, D), 2, 3, -1.0f);   /* right, x = +4 */
        st = add_mesh(scene, "walls", q, mat[M_WALL], err);
    }
    if (st == IL_OK) {
        q->n = 0;
        for (int i = 0; i < 6; i++) {
            const float lo[3] = {office_lamps[i][0] - 0.6f, LAMP_Y, office_lamps[i][1] - 0.3f};
            const float hi[3] = {office_lamps[i][0] + 0.6f, LAMP_Y, office_lamps[i][1] + 0.3f};
            add_rect(q, 1, LAMP_Y, lo, hi, -1.0f);
        }
        st = add_mesh(scene, "lamps", q, lamp, err);
    }
    if (st == IL_OK)
        st = add_furniture(scene, mat, q, err);
    free(q);
    if (st != IL_OK)
        return st;
    /* From the front left corner, over the chairs, towards the back right:
     * the partition, its shadow and the shelves are in view. */
    il_camera_desc cam = {.position = {-1.0f, 1.7f, 2.85f}, .target = {0.6f, 0.9f, -3.0f},
                          .up = {0.0f, 1.0f, 0.0f}, .fov_y = 70.0f};
    return il_scene_set_camera(scene, &cam, err);
}
