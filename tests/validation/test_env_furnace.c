/* Furnace test under an environment MAP: a convex diffuse object of albedo
 * rho under a sky of constant radiance L sees that sky over the whole
 * hemisphere above every point and never itself, so it reflects
 * L_o = rho/pi * int L cos dOmega = rho L (the rendering equation with
 * constant incident light; pbrt-v4 13.1).  The sky is given as an image of
 * ones through each of the three mappings (lat-long 64 x 32 turned by 37
 * degrees; an angular map whose border outside the disk is black; a cross
 * whose empty cells hold 100, which must never be seen) and with an
 * intensity; the path tracer, importance-sampling the map with NEE + MIS,
 * must find rho L within 1% over the whole image.  Objects: a cube filling
 * the frame (flat faces) and a flat-shaded ball seen whole through a narrow
 * lens.  The sky itself (camera looking away) must read L exactly. */
#include "pt_scenes.h"
#include "image/envmap.h"

/* An image of ones under `m`; outside the sky (the angular map's corners,
 * the cross's empty cells) `outside`. */
static il_image ones_map(il_env_mapping m, uint32_t w, uint32_t h, float outside)
{
    il_image img = {0};
    CHECK_OK(il_image_alloc(&img, w, h, &g_err), &g_err);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            float v = 1.0f;
            if (m == IL_ENV_ANGULAR) {
                /* Texels wholly outside the disk. */
                float s = 2.0f / w, a0 = -1.0f + s * x, b0 = -1.0f + s * y;
                float a = il_clampf(0.0f, a0, a0 + s), b = il_clampf(0.0f, b0, b0 + s);
                if (a * a + b * b >= 1.0f)
                    v = outside;
            } else if (m == IL_ENV_CROSS) {
                il_vec3 d;
                if (!il_envmap_uv_to_dir(m, v2((x + 0.5f) / w, (y + 0.5f) / h), &d))
                    v = outside;
            }
            float *p = img.rgb + 3 * ((size_t)y * w + x);
            p[0] = p[1] = p[2] = v;
        }
    return img;
}

typedef enum { CUBE, BALL, SKY } object;

static il_scene *scene(object obj, float rho, const il_image *map, il_env_mapping m, float rot, float k)
{
    il_scene *s = new_scene();
    uint32_t mat = add_material(s, (il_material_desc){.diffuse = v3s(rho)});
    if (obj == BALL) {
        /* il_shape_sphere's triangles without its normals: flat facets,
         * so the object is exactly convex as shaded. */
        il_shape_mesh ball;
        CHECK_OK(il_shape_sphere(1.0f, 64, &ball, &g_err), &g_err);
        il_mesh_desc md = {.num_vertices = ball.num_vertices, .num_triangles = ball.num_triangles,
                           .positions = ball.positions, .indices = ball.indices, .material = mat};
        CHECK_OK(il_scene_add_mesh(s, &md, &g_err), &g_err);
        il_shape_free(&ball);
        /* At distance 3 the ball spans 2 asin(1/3) = 39 degrees: a 20
         * degree view (28 on the diagonal) sees nothing else. */
        set_camera(s, v3(1.2f, 1.5f, 2.4f), v3(0, 0, 0), v3(0, 1, 0), 20.0f);
    } else {
        add_cube(s, mat, false); /* [-1,1]^3, faces outwards */
        if (obj == CUBE)   /* 0.5 in front of the +z face, looking at it */
            set_camera(s, v3(0.1f, 0.2f, 1.5f), v3(0.1f, 0.2f, 0.0f), v3(0, 1, 0), 60.0f);
        else               /* looking away from the cube, up into the sky */
            set_camera(s, v3(0, 1.5f, 0), v3(0.3f, 3.0f, -1.0f), v3(0, 1, 0), 90.0f);
    }
    il_environment_desc env = {.map = map, .mapping = m, .rotation = rot, .intensity = k};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    commit(s);
    return s;
}

static void furnace(object obj, float rho, il_env_mapping m, float rot, float k)
{
    uint32_t w = m == IL_ENV_LATLONG ? 64 : (m == IL_ENV_ANGULAR ? 48 : 48);
    uint32_t h = m == IL_ENV_LATLONG ? 32 : (m == IL_ENV_ANGULAR ? 48 : 64);
    il_image map = ones_map(m, w, h, m == IL_ENV_CROSS ? 100.0f : 0.0f);
    il_scene *s = scene(obj, rho, &map, m, rot, k);
    il_render_desc rd = {.spp = 64, .seed = 5};
    il_render_stats st;
    il_image img = render_image(s, 32, 32, &rd, IL_PT_MIS, &st);
    CHECK(img.rgb && image_finite(&img));
    double expect = (obj == SKY ? 1.0 : rho) * (k > 0.0f ? k : 1.0f);
    const char *names[3] = {"cube", "ball", "sky"};
    for (int c = 0; c < 3 && img.rgb; c++) {
        double mean = image_mean(&img, c);
        if (c == 0)
            printf("%s rho %.2f %s rotation %g intensity %g: %.5f expected %.5f (%+.3f%%)\n", names[obj], rho,
                   il_envmap_mapping_name(m), rot, k, mean, expect, 100.0 * (mean / expect - 1.0));
        CHECK_REL(mean, expect, obj == SKY ? 1e-4 : 0.01);
        CHECK_REL(region_mean(&img, 0, 0, 16, 16, c), expect, obj == SKY ? 1e-4 : 0.02);
        CHECK_REL(region_mean(&img, 16, 16, 32, 32, c), expect, obj == SKY ? 1e-4 : 0.02);
    }
    il_image_free(&img);
    il_image_free(&map);
    il_scene_release(s);
}

int main(void)
{
    furnace(CUBE, 0.5f, IL_ENV_LATLONG, 37.0f, 0.0f);
    furnace(CUBE, 0.8f, IL_ENV_LATLONG, 0.0f, 2.0f);
    furnace(BALL, 0.5f, IL_ENV_LATLONG, 37.0f, 0.0f);
    furnace(BALL, 0.5f, IL_ENV_ANGULAR, -20.0f, 0.0f);
    furnace(BALL, 0.8f, IL_ENV_CROSS, 110.0f, 0.5f);
    furnace(CUBE, 0.5f, IL_ENV_CROSS, 0.0f, 0.0f);
    furnace(SKY, 0.5f, IL_ENV_ANGULAR, 10.0f, 0.0f);
    furnace(SKY, 0.5f, IL_ENV_CROSS, 200.0f, 3.0f);
    return check_report();
}
