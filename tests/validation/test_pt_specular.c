/* Delta BSDFs: a mirror facing an emitter shows the emitter's radiance times
 * its tint; a glass slab in front of an emitter transmits
 * (1 - R) / (1 + R) of it (the sum over all internal reflections of a
 * non-absorbing slab, R the Fresnel reflectance: at normal incidence
 * R = ((n - 1) / (n + 1))^2 = 0.04 for n = 1.5; Hecht, Optics, 4.6);
 * emitters shine from their front face only. */
#include "pt_scenes.h"

static const il_vec3 LE = {1.0f, 2.0f, 3.0f};

static void test_mirror(void)
{
    const il_vec3 tint = {0.9f, 0.5f, 0.2f};
    il_scene *s = new_scene();
    uint32_t mirror = add_material(s, (il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = tint});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = LE});
    add_floor(s, 0.0f, 20.0f, mirror);
    add_quad(s, v3(0, 2, 0), v3(20, 0, 0), v3(0, 0, 20), lamp); /* faces down, onto the mirror */
    set_camera(s, v3(0, 1, 0), v3(0, 0, 0), v3(0, 0, -1), 40.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.spp = 4, .seed = 2};
    il_image img = render_image(s, 16, 16, &rd, IL_PT_MIS, NULL);
    for (int c = 0; c < 3; c++) {
        double expect = v3_get(tint, c) * v3_get(LE, c);
        printf("mirror: channel %d %.6f expected %.6f\n", c, image_mean(&img, c), expect);
        CHECK_REL(image_mean(&img, c), expect, 1e-5);
        CHECK_REL(img.rgb[c], expect, 1e-5);
    }
    il_image_free(&img);
    /* Max depth 1 (one bounce) still shows the emitter in the mirror. */
    rd.max_depth = 1;
    img = render_image(s, 16, 16, &rd, IL_PT_MIS, NULL);
    CHECK_REL(image_mean(&img, 0), v3_get(tint, 0) * v3_get(LE, 0), 1e-5);
    il_image_free(&img);
    il_scene_release(s);

    /* The emitter's back face (seen from above) emits nothing; two-sided it does. */
    for (int two = 0; two < 2; two++) {
        s = new_scene();
        lamp = add_material(s, (il_material_desc){.emission = LE, .two_sided = two != 0});
        add_quad(s, v3(0, 0, 0), v3(20, 0, 0), v3(0, 0, 20), lamp); /* faces down */
        set_camera(s, v3(0, 1, 0), v3(0, 0, 0), v3(0, 0, -1), 40.0f);
        CHECK_OK(il_scene_commit(s, &g_err), &g_err);
        rd.max_depth = 0;
        img = render_image(s, 8, 8, &rd, IL_PT_MIS, NULL);
        CHECK_NEAR(image_mean(&img, 2), two ? LE.z : 0.0, 1e-6);
        il_image_free(&img);
        il_scene_release(s);
    }
}

static void test_glass_slab(void)
{
    il_scene *s = new_scene();
    uint32_t glass = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = LE});
    /* The slab 0 <= y <= 0.1: top faces up, bottom faces down. */
    add_quad(s, v3(0, 0.1f, 0), v3(0, 0, 20), v3(20, 0, 0), glass);
    add_quad(s, v3(0, 0, 0), v3(20, 0, 0), v3(0, 0, 20), glass);
    add_floor(s, -1.0f, 40.0f, lamp); /* faces up, towards the slab */
    set_camera(s, v3(0, 1, 0), v3(0, 0, 0), v3(0, 0, -1), 10.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.spp = 256, .max_depth = 32, .seed = 4};
    il_image img = render_image(s, 16, 16, &rd, IL_PT_MIS, NULL);
    const double R = 0.04, T = (1.0 - R) / (1.0 + R);
    /* Within 7 degrees of normal incidence R stays within 1e-4 of 0.04.
     * Each sample is a Bernoulli-like (1 or 0 times Le): with 65536 samples
     * the standard error is about 0.1%. */
    for (int c = 0; c < 3; c++) {
        double mean = image_mean(&img, c);
        printf("glass slab: channel %d %.5f expected %.5f\n", c, mean, T * v3_get(LE, c));
        CHECK_REL(mean, T * v3_get(LE, c), 0.005);
    }
    CHECK(image_finite(&img));
    il_image_free(&img);
    il_scene_release(s);
}

int main(void)
{
    test_mirror();
    test_glass_slab();
    return check_report();
}
