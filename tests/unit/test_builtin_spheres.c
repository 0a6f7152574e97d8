/* The built-in caustics scene "cornell-spheres": the Cornell box's walls,
 * light and camera, and a mirror ball and a glass ball of radius 0.1 m
 * resting on the floor where docs/builtin-scenes.md says. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "scene/builtin.h"
#include "scene/scene.h"

static const il_mesh *find_mesh(const il_scene *s, const char *name)
{
    for (uint32_t i = 0; i < s->num_meshes; i++)
        if (strcmp(s->meshes[i].name, name) == 0)
            return &s->meshes[i];
    return NULL;
}

/* The ball's material, its lowest point and its centre (the mean of the
 * bounding box) against the documented placement. */
static void check_ball(const il_scene *s, const char *name, il_material_type type, float cx, float cz)
{
    const il_mesh *m = find_mesh(s, name);
    CHECK(m != NULL);
    if (!m)
        return;
    CHECK(s->materials[m->material].type == type);
    CHECK(m->normals != NULL);
    il_vec3 lo = v3s(INFINITY), hi = v3s(-INFINITY);
    for (uint32_t v = 0; v < m->num_vertices; v++) {
        lo = v3_min(lo, m->positions[v]);
        hi = v3_max(hi, m->positions[v]);
        /* every vertex on the sphere of radius 0.1 m */
        il_vec3 c = v3(cx, 0.1f, cz);
        CHECK_NEAR(v3_length(v3_sub(m->positions[v], c)), 0.1f, 1e-5);
    }
    CHECK_NEAR(lo.y, 0.0f, 1e-5);
    CHECK_NEAR(hi.y, 0.2f, 1e-5);
    CHECK_NEAR(0.5f * (lo.x + hi.x), cx, 1e-3);
    CHECK_NEAR(0.5f * (lo.z + hi.z), cz, 1e-3);
}

int main(void)
{
    il_error err = {0};
    CHECK(il_builtin_exists("cornell-spheres"));
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    CHECK_OK(il_builtin_load(s, "cornell-spheres", &err), &err);
    CHECK_OK(il_scene_commit(s, &err), &err);
    if (!s || !s->committed)
        return check_report();
    /* 5 walls, the light, 2 balls; no blocks. */
    CHECK(s->num_meshes == 8);
    CHECK(find_mesh(s, "short_block") == NULL && find_mesh(s, "tall_block") == NULL);
    CHECK(find_mesh(s, "light") != NULL && find_mesh(s, "left_wall_red") != NULL);
    check_ball(s, "mirror_sphere", IL_MATERIAL_MIRROR, 0.185f, 0.370f);
    check_ball(s, "glass_sphere", IL_MATERIAL_DIELECTRIC, 0.380f, 0.180f);
    const il_mesh *glass = find_mesh(s, "glass_sphere");
    CHECK(glass && s->materials[glass->material].ior == 1.5f);
    /* One area light per light triangle, nothing else. */
    CHECK(s->num_lights == 2);
    il_camera_desc cam;
    il_scene_get_camera(s, &cam);
    CHECK_NEAR(cam.position.z, -0.8f, 1e-6);
    il_scene_release(s);
    return check_report();
}
