/* The built-in scenes: Cornell box counts, bounds, colours, winding and camera
 * (the red wall on the left of the image); the atrium's size, lights and
 * validity. */
#include <string.h>

#include "check.h"
#include "scene/builtin.h"
#include "scene/camera.h"
#include "scene/scene.h"

static const il_mesh *find_mesh(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_meshes; i++)
        if (strcmp(s->meshes[i].name, name) == 0)
            return &s->meshes[i];
    return NULL;
}

static const il_material *find_material(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_materials; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return &s->materials[i];
    return NULL;
}

/* Unnormalised geometric normal (front side: counter-clockwise) and centroid. */
static il_vec3 tri_normal(const il_mesh *m, uint32_t t, il_vec3 *centroid)
{
    const uint32_t *i = m->indices + 3 * t;
    il_vec3 a = m->positions[i[0]], b = m->positions[i[1]], c = m->positions[i[2]];
    if (centroid)
        *centroid = v3_scale(v3_add(v3_add(a, b), c), 1.0f / 3.0f);
    return v3_cross(v3_sub(b, a), v3_sub(c, a));
}

static il_vec3 mesh_centre(const il_mesh *m)
{
    il_vec3 lo = v3s(INFINITY), hi = v3s(-INFINITY);
    for (uint32_t v = 0; v < m->num_vertices; v++) {
        lo = v3_min(lo, m->positions[v]);
        hi = v3_max(hi, m->positions[v]);
    }
    return v3_scale(v3_add(lo, hi), 0.5f);
}

/* Every triangle of `m` faces `ref` (sign +1) or faces away from it (-1). */
static bool faces(const il_mesh *m, il_vec3 ref, float sign)
{
    if (!m || m->num_triangles == 0)
        return false;
    for (uint32_t t = 0; t < m->num_triangles; t++) {
        il_vec3 c, n = tri_normal(m, t, &c);
        if (!(sign * v3_dot(n, v3_sub(ref, c)) > 0.0f))
            return false;
    }
    return true;
}

static void test_names(void)
{
    CHECK(il_builtin_exists("cornell"));
    CHECK(il_builtin_exists("atrium"));
    CHECK(!il_builtin_exists("Cornell"));
    CHECK(!il_builtin_exists("cornell.obj"));
    CHECK(!il_builtin_exists(""));
    CHECK(!il_builtin_exists(NULL));

    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    if (!s)
        return;
    CHECK(il_builtin_load(s, "no-such-scene", &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "no-such-scene") != NULL);
    il_scene_release(s);
}

static void test_cornell(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    if (!s)
        return;
    CHECK_OK(il_builtin_load(s, "cornell", &err), &err);

    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.num_triangles == 32);
    CHECK(info.num_emissive_triangles == 2);
    CHECK(info.num_meshes == 8);
    CHECK(info.dropped_triangles == 0);
    CHECK(info.num_lights == 0); /* the light is the emissive quad */
    CHECK_NEAR(info.bounds_min.x, 0.0, 1e-6);
    CHECK_NEAR(info.bounds_min.y, 0.0, 1e-6);
    CHECK_NEAR(info.bounds_min.z, 0.0, 1e-6);
    CHECK_NEAR(info.bounds_max.x, 0.556, 1e-5);
    CHECK_NEAR(info.bounds_max.y, 0.5488, 1e-5);
    CHECK_NEAR(info.bounds_max.z, 0.5592, 1e-5);

    /* Colours from the spectra: white about 0.7-0.75 and grey; red and green
     * dominated by their own channel; the light as renderers commonly use it
     * (about RGB (17, 12, 4)): luminance 10-15, R > G > B. */
    const il_material *white = find_material(s, "white"), *red = find_material(s, "red");
    const il_material *green = find_material(s, "green"), *light = find_material(s, "light");
    CHECK(white && red && green && light);
    if (white && red && green && light) {
        il_vec3 w = white->diffuse;
        CHECK(w.x > 0.68f && w.x < 0.77f && w.y > 0.68f && w.y < 0.77f && w.z > 0.68f && w.z < 0.77f);
        CHECK(v3_max_comp(w) - fminf(w.x, fminf(w.y, w.z)) < 0.05f);
        CHECK(red->diffuse.x > red->diffuse.y && red->diffuse.x > red->diffuse.z);
        CHECK(red->diffuse.x > 0.3f && red->diffuse.y < 0.15f);
        CHECK(green->diffuse.y > green->diffuse.x && green->diffuse.y > green->diffuse.z);
        CHECK(green->diffuse.y > 0.25f);
        il_vec3 e = light->emission;
        float lum = il_luminance(e);
        CHECK(lum > 10.0f && lum < 15.0f);
        CHECK(e.x > e.y && e.y > e.z && e.z > 0.0f);
        CHECK_REL(e.x, 17.0, 0.15);
        CHECK_REL(e.y, 12.0, 0.15);
        CHECK(!light->two_sided);
        CHECK(v3_is_zero(white->emission));
    }

    /* Winding: walls face the box's interior, the blocks face out of their own
     * centres, the light faces down, just below the ceiling. */
    const il_vec3 box = v3(0.278f, 0.2744f, 0.2796f);
    const char *walls[5] = {"floor", "ceiling", "back_wall", "right_wall_green", "left_wall_red"};
    for (int i = 0; i < 5; i++) {
        const il_mesh *m = find_mesh(s, walls[i]);
        CHECK(m && m->num_triangles == 2);
        CHECK(faces(m, box, 1.0f));
    }
    const il_mesh *sb = find_mesh(s, "short_block"), *tb = find_mesh(s, "tall_block");
    CHECK(sb && sb->num_triangles == 10 && tb && tb->num_triangles == 10);
    if (sb && tb) {
        CHECK(faces(sb, mesh_centre(sb), -1.0f));
        CHECK(faces(tb, mesh_centre(tb), -1.0f));
    }
    const il_mesh *lm = find_mesh(s, "light");
    CHECK(lm && lm->num_triangles == 2);
    if (lm) {
        CHECK(s->materials[lm->material].emission.x > 0.0f);
        double area = 0.0;
        for (uint32_t t = 0; t < lm->num_triangles; t++) {
            il_vec3 n = tri_normal(lm, t, NULL);
            CHECK(n.y < 0.0f && fabsf(n.x) < 1e-9f && fabsf(n.z) < 1e-9f);
            area += 0.5 * v3_length(n);
        }
        CHECK_NEAR(area, 0.130 * 0.105, 1e-6);
        for (uint32_t v = 0; v < lm->num_vertices; v++)
            CHECK(lm->positions[v].y < 0.5488f && lm->positions[v].y > 0.548f);
    }

    /* The published camera, and the red wall on the left of the image. */
    il_camera_desc cd;
    CHECK(il_scene_get_camera(s, &cd));
    CHECK_NEAR(cd.fov_y, 39.3077, 0.001);
    CHECK_NEAR(cd.position.x, 0.278, 1e-6);
    CHECK_NEAR(cd.position.y, 0.273, 1e-6);
    CHECK_NEAR(cd.position.z, -0.8, 1e-6);
    il_camera cam;
    il_camera_init(&cam, &cd, 512, 512);
    CHECK_NEAR(cam.forward.z, 1.0, 1e-6);
    const il_mesh *rw = find_mesh(s, "left_wall_red"), *gw = find_mesh(s, "right_wall_green");
    if (rw && gw) {
        /* Horizontal image coordinate in [-1, 1], positive to the right. */
        il_vec3 dr = v3_sub(mesh_centre(rw), cd.position), dg = v3_sub(mesh_centre(gw), cd.position);
        float xr = v3_dot(dr, cam.right) / (v3_dot(dr, cam.forward) * cam.tan_half_x);
        float xg = v3_dot(dg, cam.right) / (v3_dot(dg, cam.forward) * cam.tan_half_x);
        CHECK(xr < -0.3f && xr > -1.0f);
        CHECK(xg > 0.3f && xg < 1.0f);
    }
    /* It commits: a light and a valid scene. */
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_scene_release(s);
}

static void test_atrium(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    if (!s)
        return;
    CHECK_OK(il_builtin_load(s, "atrium", &err), &err);
    il_scene_info info;
    il_scene_get_info(s, &info);
    printf("atrium: %llu triangles in %u meshes, %u lights\n", (unsigned long long)info.num_triangles,
           info.num_meshes, info.num_lights);
    CHECK(info.num_triangles >= 200000 && info.num_triangles <= 300000);
    CHECK(info.dropped_triangles == 0);
    CHECK(info.num_warnings == 0);
    CHECK(info.has_environment);

    int directional = 0, points = 0;
    for (uint32_t i = 0; i < s->num_user_lights; i++) {
        const il_light_desc *l = &s->user_lights[i];
        if (l->type == IL_LIGHT_DIRECTIONAL) {
            directional++;
            CHECK(l->direction.y < -0.5f); /* from the sky, downwards */
            CHECK(il_luminance(l->intensity) > 5.0f && il_luminance(l->intensity) < 20.0f);
        } else if (l->type == IL_LIGHT_POINT) {
            points++;
            CHECK(l->position.y > 0.5f && l->position.y < 5.4f); /* under the gallery */
        }
    }
    CHECK(directional >= 1);
    CHECK(points >= 3);

    /* Sensible bounds: about 29 x 10.5 x 39 m, standing on y = 0. */
    CHECK_NEAR(info.bounds_min.y, 0.0, 1e-4);
    CHECK(info.bounds_max.y > 9.0f && info.bounds_max.y < 15.0f);
    CHECK(info.bounds_max.x - info.bounds_min.x > 20.0f && info.bounds_max.x - info.bounds_min.x < 40.0f);
    CHECK(info.bounds_max.z - info.bounds_min.z > 30.0f && info.bounds_max.z - info.bounds_min.z < 50.0f);

    /* Every triangle valid, every normal unit length. */
    uint64_t bad = 0;
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        const il_mesh *m = &s->meshes[i];
        CHECK(m->normals != NULL);
        for (uint32_t t = 0; t < m->num_triangles; t++) {
            il_vec3 n = tri_normal(m, t, NULL);
            if (!(v3_length(n) > 1e-10f) || !v3_is_finite(n))
                bad++;
            /* The winding agrees with the vertex normals (front side). */
            const uint32_t *ix = m->indices + 3 * t;
            il_vec3 ns = v3_add(v3_add(m->normals[ix[0]], m->normals[ix[1]]), m->normals[ix[2]]);
            if (!(v3_dot(n, ns) > 0.0f))
                bad++;
        }
    }
    CHECK(bad == 0);

    /* The camera stands inside the courtyard, below the roof, looking along it. */
    il_camera_desc cd;
    CHECK(il_scene_get_camera(s, &cd));
    CHECK(cd.position.x > info.bounds_min.x && cd.position.x < info.bounds_max.x);
    CHECK(cd.position.z > info.bounds_min.z && cd.position.z < info.bounds_max.z);
    CHECK(cd.position.y > 1.0f && cd.position.y < 2.5f);
    CHECK(fabsf(cd.target.z - cd.position.z) > 20.0f);

    /* The sky is open over the courtyard: nothing above the camera. */
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        const il_mesh *m = &s->meshes[i];
        for (uint32_t v = 0; v < m->num_vertices; v++) {
            il_vec3 p = m->positions[v];
            if (fabsf(p.x) < 5.0f && fabsf(p.z) < 10.0f && p.y > 0.1f)
                bad++;
        }
    }
    CHECK(bad == 0);

    /* Deterministic: a second build is identical. */
    il_scene *s2 = NULL;
    CHECK_OK(il_scene_create(&s2, &err), &err);
    if (s2) {
        CHECK_OK(il_builtin_load(s2, "atrium", &err), &err);
        bool same = s2->num_meshes == s->num_meshes;
        for (uint32_t i = 0; same && i < s->num_meshes; i++)
            same = s->meshes[i].num_vertices == s2->meshes[i].num_vertices &&
                   memcmp(s->meshes[i].positions, s2->meshes[i].positions,
                          s->meshes[i].num_vertices * sizeof(il_vec3)) == 0;
        CHECK(same);
        il_scene_release(s2);
    }
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_scene_release(s);
}

int main(void)
{
    test_names();
    test_cornell();
    test_atrium();
    return check_report();
}
