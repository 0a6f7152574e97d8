/* With many lights the ibl image converges to the path tracer's direct
 * lighting (`--method pt --max-depth 1`) under the same environment: the
 * light set is a Monte Carlo estimate of the same integral (ibl_lights.c),
 * shaded with the same BSDFs and exact shadow rays.  Checked on a floor
 * with a Phong ball and a Lambertian ball (the whole image's mean and every
 * 8x8 region) under a coloured constant sky, under Grace Cathedral (a
 * 256x128 probe with bright windows) and under Poly Haven's Pedestrian
 * Overpass (1k, a sun 69,000 times brighter than the mean: the hard case),
 * and with the scene's other lights (point, directional, an emissive quad)
 * added to a sky.
 *
 * Both sides are noisy: the path tracer by its samples per pixel, ibl by
 * its light set and its camera samples at silhouettes (16 per pixel here);
 * the tolerances are a few times the spread seen over three pairs of seeds
 * (mean within 0.05% on the constant sky and with the other lights, 0.6% on
 * Grace, 0.2% on the sun map; worst region 0.9%, 2.5% and 1.1%). */
#include "test_ibl_common.h"

#define W 48
#define H 48

static il_scene *balls_scene(void)
{
    il_scene *s = new_scene();
    uint32_t floor_m = add_material(s, (il_material_desc){.diffuse = {0.5f, 0.5f, 0.45f}});
    uint32_t phong = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG,
                                                         .diffuse = {0.5f, 0.2f, 0.1f},
                                                         .specular = {0.3f, 0.3f, 0.3f},
                                                         .exponent = 20.0f});
    uint32_t lambert = add_material(s, (il_material_desc){.diffuse = {0.2f, 0.4f, 0.7f}});
    add_floor(s, 0.0f, 6.0f, floor_m);
    add_ball(s, v3(-0.55f, 0.5f, 0.0f), 0.5f, phong);
    add_ball(s, v3(0.6f, 0.35f, 0.3f), 0.35f, lambert);
    set_camera(s, v3(0, 1.4f, 3.2f), v3(0, 0.35f, 0), v3(0, 1, 0), 45.0f);
    return s;
}

static void compare(const char *what, il_scene *s, uint32_t lights, uint32_t pt_spp, double rel_mean,
                    double rel_region)
{
    il_ibl_desc d = {.lights = lights, .batch = 1024};
    il_render_stats st;
    il_image a = render_ibl(s, W, H, &d, 16, 1, &st);
    il_image b = render_pt_direct(s, W, H, pt_spp, 7);
    CHECK(st.ibl.lights == lights && st.spp == 16 && st.nonfinite_samples == 0);
    CHECK(image_finite(&a));
    compare_regions(what, &a, &b, 8, rel_mean, rel_region, 0.01);
    il_image_free(&a);
    il_image_free(&b);
}

static void test_constant_sky(void)
{
    il_scene *s = balls_scene();
    set_sky(s, v3(0.6f, 0.8f, 1.2f));
    commit(s);
    compare("constant sky", s, 2048, 512, 0.005, 0.02);
    il_scene_release(s);
}

static void test_maps(void)
{
    il_scene *s = balls_scene();
    if (set_map(s, "probulator_grace_256x128.hdr")) {
        commit(s);
        compare("grace", s, 4096, 1024, 0.015, 0.05);
    }
    il_scene_release(s);
    s = balls_scene();
    if (set_map(s, "polyhaven_pedestrian_overpass_1k.hdr")) {
        commit(s);
        compare("pedestrian overpass (sun)", s, 4096, 1024, 0.01, 0.04);
    }
    il_scene_release(s);
}

static void test_other_lights(void)
{
    il_scene *s = balls_scene();
    set_sky(s, v3(0.2f, 0.25f, 0.3f));
    il_light_desc pl = {.type = IL_LIGHT_POINT, .position = {0.5f, 2.0f, 1.0f}, .intensity = {2, 2, 1.5f}};
    il_light_desc dl = {.type = IL_LIGHT_DIRECTIONAL, .direction = {-0.4f, -1.0f, -0.3f},
                        .intensity = {0.5f, 0.4f, 0.3f}};
    CHECK_OK(il_scene_add_light(s, &pl, &g_err), &g_err);
    CHECK_OK(il_scene_add_light(s, &dl, &g_err), &g_err);
    /* An emissive panel above the balls, facing down. */
    uint32_t lamp = add_material(s, (il_material_desc){.emission = {3, 3, 3}});
    add_quad(s, v3(0, 2.2f, -0.5f), v3(0, 0, 0.4f), v3(0.4f, 0, 0), lamp);
    commit(s);
    compare("sky + point + directional + emitter", s, 1024, 1024, 0.005, 0.025);
    il_scene_release(s);
}

int main(void)
{
    test_constant_sky();
    test_maps();
    test_other_lights();
    return check_report();
}
