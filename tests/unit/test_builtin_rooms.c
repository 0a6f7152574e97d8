/* The radiosity rooms (simple-room, shadow-room, box-room): counts, bounds,
 * reflectances, emitter area and radiance, winding (walls face into the
 * room, boxes and the slab outwards), the slab at half height, the camera
 * inside with the red wall on the left, as docs/builtin-scenes.md says. */
#include <string.h>

#include "check.h"
#include "scene/builtin.h"
#include "scene/scene.h"

static il_scene *load(const char *name)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(name, NULL, &s, &err), &err);
    if (s)
        CHECK_OK(il_scene_commit(s, &err), &err);
    return s;
}

static const il_mesh *find_mesh(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_meshes; i++)
        if (strcmp(s->meshes[i].name, name) == 0)
            return &s->meshes[i];
    return NULL;
}

static il_vec3 tri_normal(const il_mesh *m, uint32_t t, il_vec3 *centroid, float *area)
{
    const uint32_t *i = m->indices + 3 * t;
    il_vec3 a = m->positions[i[0]], b = m->positions[i[1]], c = m->positions[i[2]];
    *centroid = v3_scale(v3_add(v3_add(a, b), c), 1.0f / 3.0f);
    il_vec3 n = v3_cross(v3_sub(b, a), v3_sub(c, a));
    *area = 0.5f * v3_length(n);
    return v3_normalize(n);
}

static void mesh_bounds(const il_mesh *m, il_vec3 *lo, il_vec3 *hi)
{
    *lo = v3s(INFINITY);
    *hi = v3s(-INFINITY);
    for (uint32_t v = 0; v < m->num_vertices; v++) {
        *lo = v3_min(*lo, m->positions[v]);
        *hi = v3_max(*hi, m->positions[v]);
    }
}

/* Every triangle of the mesh faces towards `ref` (sign +1) or away (-1), with
 * a unit normal along one axis (the rooms are axis-aligned). */
static bool faces(const il_mesh *m, il_vec3 ref, float sign)
{
    if (!m || m->num_triangles == 0)
        return false;
    for (uint32_t t = 0; t < m->num_triangles; t++) {
        il_vec3 c;
        float area;
        il_vec3 n = tri_normal(m, t, &c, &area);
        if (!(sign * v3_dot(n, v3_sub(ref, c)) > 0.0f) || !(area > 0.0f))
            return false;
        if (fabsf(fabsf(n.x) + fabsf(n.y) + fabsf(n.z) - 1.0f) > 1e-6f)
            return false;
    }
    return true;
}

/* Emissive area and the emitted radiance (all emitters alike). */
static double emitter_area(const il_scene *s, il_vec3 *radiance)
{
    double area = 0.0;
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        const il_mesh *m = &s->meshes[i];
        const il_material *mat = &s->materials[m->material];
        if (v3_is_zero(mat->emission))
            continue;
        *radiance = mat->emission;
        for (uint32_t t = 0; t < m->num_triangles; t++) {
            il_vec3 c;
            float a;
            tri_normal(m, t, &c, &a);
            area += a;
        }
    }
    return area;
}

static void check_vec(il_vec3 a, float x, float y, float z)
{
    CHECK_NEAR(a.x, x, 1e-6);
    CHECK_NEAR(a.y, y, 1e-6);
    CHECK_NEAR(a.z, z, 1e-6);
}

/* The room shared by all three: bounds, wall colours and winding, camera. */
static void check_room(const il_scene *s)
{
    il_scene_info in;
    il_scene_get_info(s, &in);
    check_vec(in.bounds_min, -2.0f, 0.0f, -2.0f);
    check_vec(in.bounds_max, 2.0f, 3.0f, 2.0f);
    const il_vec3 centre = {0.0f, 1.5f, 0.0f};
    const char *walls[] = {"floor", "back_wall", "front_wall", "left_wall_red", "right_wall_green"};
    for (int i = 0; i < 5; i++) {
        const il_mesh *m = find_mesh(s, walls[i]);
        CHECK(m != NULL);
        if (!m)
            continue;
        CHECK(m->num_triangles == 2);
        CHECK(faces(m, centre, +1.0f));
        const il_material *mat = &s->materials[m->material];
        CHECK(mat->type == IL_MATERIAL_DIFFUSE);
        CHECK(v3_is_zero(mat->emission));
        if (i < 3)
            check_vec(mat->diffuse, 0.75f, 0.75f, 0.75f);
    }
    const il_mesh *red = find_mesh(s, "left_wall_red"), *green = find_mesh(s, "right_wall_green");
    if (!red || !green)
        return;
    check_vec(s->materials[red->material].diffuse, 0.75f, 0.1f, 0.1f);
    check_vec(s->materials[green->material].diffuse, 0.1f, 0.75f, 0.1f);
    il_vec3 lo, hi;
    mesh_bounds(red, &lo, &hi);
    CHECK(lo.x == -2.0f && hi.x == -2.0f);
    mesh_bounds(green, &lo, &hi);
    CHECK(lo.x == 2.0f && hi.x == 2.0f);

    /* The camera is inside; right = forward x up, the red wall on its left. */
    il_camera_desc cam;
    CHECK(il_scene_get_camera(s, &cam));
    CHECK(cam.position.x > -2.0f && cam.position.x < 2.0f && cam.position.y > 0.0f &&
          cam.position.y < 3.0f && cam.position.z > -2.0f && cam.position.z < 2.0f);
    il_vec3 fwd = v3_normalize(v3_sub(cam.target, cam.position));
    il_vec3 right = v3_cross(fwd, cam.up);
    CHECK(v3_dot(v3_sub(v3(-2.0f, 1.5f, 0.0f), cam.position), right) < 0.0f);
    CHECK(v3_dot(v3_sub(v3(2.0f, 1.5f, 0.0f), cam.position), right) > 0.0f);
    CHECK(fwd.z < -0.9f); /* looking at the back wall */
}

static void test_names(void)
{
    CHECK(il_builtin_exists("simple-room"));
    CHECK(il_builtin_exists("shadow-room"));
    CHECK(il_builtin_exists("box-room"));
    CHECK(!il_builtin_exists("simple_room"));
    il_error err = {0};
    il_scene *s = NULL;
    CHECK(il_scene_load("no-such-room", NULL, &s, &err) != IL_OK);
    CHECK(s == NULL);
    il_scene_create(&s, &err);
    CHECK(il_builtin_load(s, "no-such-room", &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "simple-room") != NULL && strstr(err.message, "box-room") != NULL);
    il_scene_release(s);
}

static void test_simple_room(void)
{
    il_scene *s = load("simple-room");
    if (!s)
        return;
    il_scene_info in;
    il_scene_get_info(s, &in);
    CHECK(in.num_meshes == 6);
    CHECK(in.num_triangles == 12); /* 6 quads: 6 * 4^5 = 6,144 patches at level 5 */
    CHECK(in.num_emissive_triangles == 2);
    CHECK(in.num_lights == 0);
    CHECK(!in.has_environment);
    check_room(s);
    const il_mesh *c = find_mesh(s, "ceiling_light");
    CHECK(c && faces(c, v3(0.0f, 1.5f, 0.0f), +1.0f));
    il_vec3 le = {0};
    CHECK_NEAR(emitter_area(s, &le), 16.0, 1e-5);
    check_vec(le, 1.0f, 1.0f, 1.0f);
    if (c)
        check_vec(s->materials[c->material].diffuse, 0.75f, 0.75f, 0.75f);
    il_scene_release(s);
}

static void test_shadow_room(void)
{
    il_scene *s = load("shadow-room");
    if (!s)
        return;
    il_scene_info in;
    il_scene_get_info(s, &in);
    CHECK(in.num_meshes == 7);
    CHECK(in.num_triangles == 24);
    check_room(s);
    il_vec3 le = {0};
    CHECK_NEAR(emitter_area(s, &le), 16.0, 1e-5);
    check_vec(le, 1.0f, 1.0f, 1.0f);

    const il_mesh *slab = find_mesh(s, "slab");
    CHECK(slab != NULL);
    if (slab) {
        CHECK(slab->num_triangles == 12); /* closed: 6 faces */
        il_vec3 lo, hi;
        mesh_bounds(slab, &lo, &hi);
        CHECK_NEAR(0.5f * (lo.y + hi.y), 1.5, 1e-6);  /* half of the 3 m height */
        CHECK_NEAR(hi.y - lo.y, 0.02, 1e-6);          /* 2 cm thick */
        CHECK_NEAR(lo.z, -1.99, 1e-6);                /* the back two thirds */
        CHECK_NEAR(hi.z, 2.0 / 3.0, 1e-6);
        CHECK_NEAR(lo.x, -1.99, 1e-6);
        CHECK_NEAR(hi.x, 1.99, 1e-6);
        CHECK(faces(slab, v3_scale(v3_add(lo, hi), 0.5f), -1.0f)); /* outwards */
        check_vec(s->materials[slab->material].diffuse, 0.75f, 0.75f, 0.75f);
        /* The camera is below the slab, so the dark space under it is in view. */
        il_camera_desc cam;
        il_scene_get_camera(s, &cam);
        CHECK(cam.position.y < lo.y);
    }
    il_scene_release(s);
}

static void test_box_room(void)
{
    il_scene *s = load("box-room");
    if (!s)
        return;
    il_scene_info in;
    il_scene_get_info(s, &in);
    CHECK(in.num_meshes == 11);
    CHECK(in.num_triangles == 58); /* 5 walls + 4 ceiling quads + 4 boxes of 5 faces */
    CHECK(in.num_emissive_triangles == 2);
    check_room(s);

    const il_mesh *lamp = find_mesh(s, "lamp"), *ceiling = find_mesh(s, "ceiling");
    CHECK(lamp && ceiling);
    if (!lamp || !ceiling)
        return;
    il_vec3 le = {0};
    CHECK_NEAR(emitter_area(s, &le), 4.0, 1e-5); /* a quarter of 4 x 4 m */
    check_vec(le, 4.0f, 4.0f, 4.0f);
    CHECK(faces(lamp, v3(0.0f, 1.5f, 0.0f), +1.0f));
    CHECK(faces(ceiling, v3(0.0f, 1.5f, 0.0f), +1.0f));
    CHECK(ceiling->num_triangles == 6);
    il_vec3 lo, hi;
    mesh_bounds(lamp, &lo, &hi);
    check_vec(lo, -2.0f, 3.0f, -2.0f);
    check_vec(hi, 0.0f, 3.0f, 0.0f);

    const char *boxes[4] = {"box_blue", "box_yellow", "box_white", "box_cyan"};
    il_vec3 blo[4], bhi[4];
    for (int i = 0; i < 4; i++) {
        const il_mesh *b = find_mesh(s, boxes[i]);
        CHECK(b != NULL);
        if (!b)
            return;
        CHECK(b->num_triangles == 10); /* 5 faces, no bottom */
        mesh_bounds(b, &blo[i], &bhi[i]);
        CHECK(blo[i].y == 0.0f); /* standing on the floor */
        CHECK(bhi[i].y > 0.0f && bhi[i].y < 3.0f);
        CHECK(blo[i].x > -2.0f && bhi[i].x < 2.0f && blo[i].z > -2.0f && bhi[i].z < 2.0f);
        CHECK(faces(b, v3_scale(v3_add(blo[i], bhi[i]), 0.5f), -1.0f));
        const il_material *mat = &s->materials[b->material];
        CHECK(v3_is_zero(mat->emission));
        CHECK(v3_max_comp(mat->diffuse) <= 0.75f && v3_max_comp(mat->diffuse) > 0.0f);
        for (int j = 0; j < i; j++) /* no two boxes overlap */
            CHECK(bhi[i].x <= blo[j].x || bhi[j].x <= blo[i].x || bhi[i].z <= blo[j].z ||
                  bhi[j].z <= blo[i].z);
    }
    il_scene_release(s);
}

int main(void)
{
    test_names();
    test_simple_room();
    test_shadow_room();
    test_box_room();
    return check_report();
}
