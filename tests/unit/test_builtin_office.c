/* The built-in office (hierarchical radiosity's test room): polygon count in
 * the documented range, bounds, the lamps' area, radiance and orientation,
 * the room facing inwards and every furniture box outwards, reflectances,
 * the camera inside, and the partition's shadow, as docs/builtin-scenes.md
 * says. */
#include <string.h>

#include "check.h"
#include "scene/builtin.h"
#include "scene/scene.h"
#include "trace/trace.h"

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

static double mesh_area(const il_mesh *m)
{
    double area = 0.0;
    for (uint32_t t = 0; t < m->num_triangles; t++) {
        il_vec3 c;
        float a;
        tri_normal(m, t, &c, &a);
        area += a;
    }
    return area;
}

/* Every triangle has an axis-aligned unit normal and faces towards `ref`. */
static bool faces_towards(const il_mesh *m, il_vec3 ref)
{
    if (!m || m->num_triangles == 0)
        return false;
    for (uint32_t t = 0; t < m->num_triangles; t++) {
        il_vec3 c;
        float area;
        il_vec3 n = tri_normal(m, t, &c, &area);
        if (!(v3_dot(n, v3_sub(ref, c)) > 0.0f) || !(area > 0.0f))
            return false;
        if (fabsf(fabsf(n.x) + fabsf(n.y) + fabsf(n.z) - 1.0f) > 1e-6f)
            return false;
    }
    return true;
}

/* The mesh is a run of boxes of `faces` rectangles each (2 triangles and 4
 * unshared vertices per rectangle, in order): every triangle faces away
 * from the centre of its own box.  Returns the number of boxes, 0 when one
 * faces inwards. */
static uint32_t boxes_face_out(const il_mesh *m, uint32_t faces)
{
    if (!m || m->num_triangles == 0 || m->num_triangles % (2 * faces) != 0 ||
        m->num_vertices != 2 * m->num_triangles)
        return 0;
    const uint32_t n = m->num_triangles / (2 * faces);
    for (uint32_t b = 0; b < n; b++) {
        il_vec3 centre = v3s(0.0f);
        for (uint32_t v = 0; v < 4 * faces; v++)
            centre = v3_add(centre, m->positions[b * 4 * faces + v]);
        centre = v3_scale(centre, 1.0f / (float)(4 * faces));
        for (uint32_t t = b * 2 * faces; t < (b + 1) * 2 * faces; t++) {
            il_vec3 c;
            float area;
            il_vec3 nrm = tri_normal(m, t, &c, &area);
            if (!(v3_dot(nrm, v3_sub(c, centre)) > 0.0f) || !(area > 0.0f))
                return 0;
        }
    }
    return n;
}

static void check_vec(il_vec3 a, float x, float y, float z)
{
    CHECK_NEAR(a.x, x, 1e-6);
    CHECK_NEAR(a.y, y, 1e-6);
    CHECK_NEAR(a.z, z, 1e-6);
}

static void test_names(void)
{
    CHECK(il_builtin_exists("office"));
    il_error err = {0};
    il_scene *s = NULL;
    il_scene_create(&s, &err);
    CHECK(il_builtin_load(s, "offices", &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "office, cornell-spheres)") != NULL);
    il_scene_release(s);
}

/* Counts, bounds, materials and the lamps. */
static void test_contents(const il_scene *s)
{
    il_scene_info in;
    il_scene_get_info(s, &in);
    CHECK(in.num_meshes == 13);
    CHECK(in.num_triangles == 2 * 537); /* 537 rectangles: the HR patches */
    CHECK(in.num_triangles / 2 >= 300 && in.num_triangles / 2 <= 1000);
    CHECK(in.dropped_triangles == 0);
    CHECK(in.num_emissive_triangles == 12);
    CHECK(in.num_lights == 0);
    CHECK(!in.has_environment);
    check_vec(in.bounds_min, -4.0f, 0.0f, -3.0f);
    check_vec(in.bounds_max, 4.0f, 3.0f, 3.0f);

    /* Rectangles per mesh, as the table in docs/builtin-scenes.md. */
    static const struct { const char *name; uint32_t rects; } counts[] = {
        {"floor", 12},      {"ceiling", 12},    {"walls", 28},      {"lamps", 6},
        {"desk_tops", 36},  {"desk_legs", 96},  {"chairs", 66},     {"chair_legs", 96},
        {"partition", 5},   {"shelves", 90},    {"books_red", 30},  {"books_green", 30},
        {"books_blue", 30},
    };
    uint32_t total = 0;
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        const il_mesh *m = find_mesh(s, counts[i].name);
        CHECK(m != NULL);
        if (!m)
            continue;
        CHECK(m->num_triangles == 2 * counts[i].rects);
        total += m->num_triangles / 2;
        const il_material *mat = &s->materials[m->material];
        CHECK(mat->type == IL_MATERIAL_DIFFUSE);
        CHECK(v3_max_comp(mat->diffuse) <= 0.8f && mat->diffuse.x > 0.0f && mat->diffuse.y > 0.0f &&
              mat->diffuse.z > 0.0f);
        CHECK(v3_is_zero(mat->emission) == (strcmp(counts[i].name, "lamps") != 0));
    }
    CHECK(total == 537);

    /* Six 1.2 x 0.6 m lamps, radiance 10, facing down 1 cm below the ceiling. */
    const il_mesh *lamps = find_mesh(s, "lamps");
    if (lamps) {
        CHECK_NEAR(mesh_area(lamps), 6 * 1.2 * 0.6, 1e-5);
        check_vec(s->materials[lamps->material].emission, 10.0f, 10.0f, 10.0f);
        CHECK(!s->materials[lamps->material].two_sided);
        for (uint32_t t = 0; t < lamps->num_triangles; t++) {
            il_vec3 c;
            float a;
            il_vec3 n = tri_normal(lamps, t, &c, &a);
            check_vec(n, 0.0f, -1.0f, 0.0f);
            CHECK_NEAR(c.y, 2.99, 1e-6);
        }
    }
    /* The desk tops cover 6 x 1.4 x 0.7 m (top faces) out of 36 rectangles. */
    const il_mesh *desks = find_mesh(s, "desk_tops");
    if (desks) {
        const double top = 1.4 * 0.7, side = 1.4 * 0.03, end = 0.7 * 0.03;
        CHECK_NEAR(mesh_area(desks), 6 * (2 * top + 2 * side + 2 * end), 1e-4);
    }
}

/* The shell faces into the room, furniture outwards. */
static void test_orientation(const il_scene *s)
{
    const il_vec3 centre = {0.0f, 1.5f, 0.0f};
    CHECK(faces_towards(find_mesh(s, "floor"), centre));
    CHECK(faces_towards(find_mesh(s, "ceiling"), centre));
    CHECK(faces_towards(find_mesh(s, "walls"), centre));
    CHECK(boxes_face_out(find_mesh(s, "desk_tops"), 6) == 6);
    CHECK(boxes_face_out(find_mesh(s, "desk_legs"), 4) == 24);
    CHECK(boxes_face_out(find_mesh(s, "chair_legs"), 4) == 24);
    CHECK(boxes_face_out(find_mesh(s, "partition"), 5) == 1);
    CHECK(boxes_face_out(find_mesh(s, "books_red"), 5) == 6);
    CHECK(boxes_face_out(find_mesh(s, "books_blue"), 5) == 6);
    /* The check can fail: the walls, taken as one box, face in. */
    CHECK(boxes_face_out(find_mesh(s, "walls"), 28) == 0);

    /* The partition's big faces look along -x and +x. */
    const il_mesh *p = find_mesh(s, "partition");
    if (p) {
        int along_x = 0;
        for (uint32_t t = 0; t < p->num_triangles; t++) {
            il_vec3 c;
            float a;
            il_vec3 n = tri_normal(p, t, &c, &a);
            if (fabsf(n.x) > 0.99f && a > 1.0f)
                along_x++;
        }
        CHECK(along_x == 4); /* 2 faces x 2 triangles, 3.6 x 1.8 m each */
    }

    il_camera_desc cam;
    CHECK(il_scene_get_camera(s, &cam));
    CHECK(cam.position.x > -4.0f && cam.position.x < 4.0f && cam.position.y > 0.0f &&
          cam.position.y < 3.0f && cam.position.z > -3.0f && cam.position.z < 3.0f);
    CHECK(v3_normalize(v3_sub(cam.target, cam.position)).z < -0.9f);
}

/* A ray from the centre of the lamp at (0, 2.99, -1.5) to the floor behind
 * the partition hits the partition; from the lamp at x = 2.5, on the same
 * side as the point, nothing is in the way. */
static void test_partition_shadow(const il_scene *s)
{
    CHECK(s->tracer != NULL);
    if (!s->tracer)
        return;
    const il_vec3 behind = {1.5f, 0.01f, -1.5f};
    const il_vec3 shadowed_lamp = {0.0f, 2.98f, -1.5f}, clear_lamp = {2.5f, 2.98f, -1.5f};
    il_ray r = {.org = shadowed_lamp, .tmin = 0.0f, .dir = v3_sub(behind, shadowed_lamp), .tmax = 0.999f};
    CHECK(il_trace_occluded(s->tracer, &r));
    il_hit hit;
    CHECK(il_trace_closest(s->tracer, &r, &hit));
    CHECK(hit.mesh < s->num_meshes && strcmp(s->meshes[hit.mesh].name, "partition") == 0);
    il_vec3 p = v3_fma(r.org, r.dir, hit.t);
    CHECK_NEAR(p.x, 0.97, 1e-4); /* its -x face */
    CHECK(p.y > 0.0f && p.y < 1.8f);

    il_ray clear = {.org = clear_lamp, .tmin = 0.0f, .dir = v3_sub(behind, clear_lamp), .tmax = 0.999f};
    CHECK(!il_trace_occluded(s->tracer, &clear));
    /* ...and the point itself lies on the floor: the ray a bit longer hits it. */
    clear.tmax = 1.01f;
    CHECK(il_trace_closest(s->tracer, &clear, &hit));
    CHECK(hit.mesh < s->num_meshes && strcmp(s->meshes[hit.mesh].name, "floor") == 0);
}

/* Built twice, the same numbers: nothing depends on the run. */
static void test_deterministic(const il_scene *a)
{
    il_error err = {0};
    il_scene *b = NULL;
    CHECK_OK(il_scene_load("office", NULL, &b, &err), &err);
    if (!b)
        return;
    CHECK(a->num_meshes == b->num_meshes);
    for (uint32_t i = 0; i < a->num_meshes && i < b->num_meshes; i++) {
        CHECK(a->meshes[i].num_vertices == b->meshes[i].num_vertices);
        CHECK(memcmp(a->meshes[i].positions, b->meshes[i].positions,
                     a->meshes[i].num_vertices * sizeof(il_vec3)) == 0);
    }
    il_scene_release(b);
}

int main(void)
{
    test_names();
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("office", NULL, &s, &err), &err);
    if (s) {
        CHECK_OK(il_scene_commit(s, &err), &err);
        test_contents(s);
        test_orientation(s);
        test_partition_shadow(s);
        test_deterministic(s);
        il_scene_release(s);
    }
    return check_report();
}
