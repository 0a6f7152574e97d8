/* The public scene API: defaults, validation of what goes in, errors out,
 * the default camera, and the library example of docs/library.md. */
#include <string.h>

#include "check.h"
#include "illum/illum.h"

static void test_defaults_and_validation(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    il_scene_info in;
    il_scene_get_info(s, &in);
    CHECK(in.num_materials == 1);     /* the default material */
    CHECK(in.num_triangles == 0);
    CHECK(!in.has_camera);

    /* Bad materials are refused with a message naming them. */
    CHECK(il_scene_add_material(s, &(il_material_desc){.name = "neg", .diffuse = {-1, 0, 0}}, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "neg") != NULL);
    CHECK(il_scene_add_material(s, &(il_material_desc){.diffuse_texture = 3}, NULL, &err) == IL_ERR_INVALID);
    CHECK(il_scene_add_material(s, &(il_material_desc){.ior = NAN}, NULL, &err) == IL_ERR_INVALID);

    /* A committed scene with no triangle is an error; so is one with no light. */
    CHECK(il_scene_commit(s, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "empty") != NULL);

    float p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, NAN, 0, 0, 2, 0, 0};
    uint32_t idx[] = {0, 1, 2,   0, 1, 3,   0, 1, 4,   0, 1, 7};
    /* Triangle 2 (NaN), 3 (collinear) and 4 (index out of range) are dropped. */
    CHECK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 5, .num_triangles = 4, .positions = p,
                                                .indices = idx, .material = 9}, &err) == IL_ERR_INVALID);
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.name = "m", .num_vertices = 5, .num_triangles = 4,
                                                   .positions = p, .indices = idx}, &err), &err);
    il_scene_get_info(s, &in);
    CHECK(in.num_triangles == 1);
    CHECK(in.dropped_triangles == 3);
    CHECK(in.num_warnings == 1);
    CHECK(il_scene_warning(s, 0) && strstr(il_scene_warning(s, 0), "dropped 3 of 4") != NULL);
    CHECK(il_scene_warning(s, 1) == NULL);
    /* A coordinate beyond +-1e15 is dropped like a NaN (Embree aborts the
     * program on a ray from so far). */
    float far[] = {0, 0, 0, 1, 0, 0, 0, 2e15f, 0};
    uint32_t tri[] = {0, 1, 2};
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.name = "far", .num_vertices = 3, .num_triangles = 1,
                                                   .positions = far, .indices = tri}, &err), &err);
    il_scene_get_info(s, &in);
    CHECK(in.num_triangles == 1 && in.dropped_triangles == 4);

    CHECK(il_scene_commit(s, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "light") != NULL);

    /* Lights and cameras are validated. */
    CHECK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_SPOT, .spot_angle = 200}, &err) == IL_ERR_INVALID);
    CHECK(il_scene_add_light(s, &(il_light_desc){.intensity = {INFINITY, 0, 0}}, &err) == IL_ERR_INVALID);
    CHECK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {-1e30f, 0, 0},
                                                 .intensity = {1, 1, 1}}, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "out of range") != NULL);
    CHECK(il_scene_set_camera(s, &(il_camera_desc){.position = {0, 0, 2e15f}, .target = {0, 0, 0}}, &err) ==
          IL_ERR_INVALID);
    CHECK(il_scene_set_camera(s, &(il_camera_desc){.position = {1, 1, 1}, .target = {1, 1, 1}}, &err) == IL_ERR_INVALID);
    CHECK(il_scene_set_camera(s, &(il_camera_desc){.position = {0, 0, 0}, .target = {0, 1, 0}}, &err) == IL_ERR_INVALID);
    CHECK(il_scene_set_camera(s, &(il_camera_desc){.target = {0, 0, -1}, .fov_y = 180}, &err) == IL_ERR_INVALID);

    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 0, 1},
                                                    .intensity = {1, 1, 1}}, &err), &err);
    CHECK_OK(il_scene_commit(s, &err), &err);

    /* The default camera frames the bounds from +z with a 40-degree fov. */
    il_camera_desc cam;
    CHECK(il_scene_get_camera(s, &cam));
    CHECK_NEAR(cam.fov_y, 40.0, 1e-6);
    CHECK_NEAR(cam.target.x, 0.5, 1e-6);
    CHECK_NEAR(cam.target.y, 0.5, 1e-6);
    CHECK(cam.position.z > 0.0f);
    float radius = sqrtf(0.5f);   /* half the diagonal of the unit square */
    CHECK_NEAR(cam.position.z, radius / sinf(20.0f * 3.14159265f / 180.0f), 1e-4);

    /* A committed scene no longer changes (the camera may). */
    CHECK(il_scene_add_light(s, &(il_light_desc){.intensity = {1, 1, 1}}, &err) == IL_ERR_INVALID);
    CHECK(il_scene_add_material(s, &(il_material_desc){0}, NULL, &err) == IL_ERR_INVALID);
    CHECK_OK(il_scene_set_camera(s, &(il_camera_desc){.position = {0, 0, 3}, .target = {0, 0, 0}}, &err), &err);
    il_scene_release(s);
}

/* The "build a scene in code" example of docs/library.md, rendered: the
 * centre of the floor under a point light has radiance rho/pi * I / h^2. */
static void test_library_example(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    uint32_t white, lamp;
    CHECK_OK(il_scene_add_material(s, &(il_material_desc){.diffuse = {0.7f, 0.7f, 0.7f}}, &white, &err), &err);
    CHECK_OK(il_scene_add_material(s, &(il_material_desc){.emission = {10, 10, 10}}, &lamp, &err), &err);
    float quad[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    uint32_t tris[] = {0, 2, 1, 0, 3, 2};
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = quad,
                                                   .indices = tris, .material = white}, &err), &err);
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = {0, 1, 0},
                                                    .intensity = {5, 5, 5}}, &err), &err);
    /* Looking straight down at the floor's centre from just below the lamp. */
    CHECK_OK(il_scene_set_camera(s, &(il_camera_desc){.position = {0, 0.5f, 0}, .target = {0, 0, 0},
                                                      .up = {0, 0, -1}, .fov_y = 2}, &err), &err);
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_film *film = NULL;
    CHECK_OK(il_film_create(4, 4, &film, &err), &err);
    il_render_desc rd = {.spp = 4, .max_depth = 1};
    il_render_stats st;
    CHECK_OK(il_render(s, film, &rd, &st, &err), &err);
    CHECK(st.spp == 4);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    /* max_depth 1: direct light only.  The 2-degree view covers a spot of
     * radius ~0.009 around the centre, where cos^3 falloff is < 0.02% off. */
    double expected = 0.7 / 3.14159265358979 * 5.0 / 1.0;
    for (uint32_t i = 0; i < 16; i++)
        CHECK_REL(img.rgb[3 * i + 1], expected, 1e-3);
    il_image_free(&img);
    il_film_release(film);
    il_scene_release(s);
}

int main(void)
{
    test_defaults_and_validation();
    test_library_example();
    return check_report();
}
