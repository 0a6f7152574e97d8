/* The many-light method against analytic radiance under a constant sky L
 * (no indirect light in these scenes: a floor cannot see itself).
 *
 *  - An open Lambertian floor sees the whole upper hemisphere:
 *        L_o = rho/pi int_H L cos dw = rho L.
 *  - Under a square occluder of half-size a at height c, centred above the
 *    point, the occluder hides the fraction F of the cosine-weighted
 *    hemisphere, F = 4 F_corner(a/c, a/c), F_corner the view factor from a
 *    plane element to a parallel rectangle with a corner above it (Howell's
 *    catalogue B-3):
 *        F_corner(A, B) = 1/(2 pi) [A/sqrt(1+A^2) atan(B/sqrt(1+A^2))
 *                                 + B/sqrt(1+B^2) atan(A/sqrt(1+B^2))],
 *    so L_o = rho L (1 - F).  a = c: F = 0.55412, L_o = 0.44588 rho L.
 *  - Seen in a mirror of tint t (the reflection needs max_depth 2: one delta
 *    bounce, then the shaded vertex), the open floor is t rho L; with
 *    max_depth 1 the mirror shows only what the path tracer's direct
 *    lighting shows there, nothing.
 *  - A camera ray that escapes sees exactly L.
 * Every light selection converges to these: with N lights the estimate's
 * error is about 1.3/sqrt(N) for random points (the floor: variance 5/3
 * (rho L)^2 per light), far less for Sobol points. */
#include "test_ibl_common.h"

static const il_vec3 RHO = {0.5f, 0.7f, 0.3f};
static const il_vec3 SKY = {1.0f, 2.0f, 0.5f};

static double f_corner(double A, double B)
{
    double sa = sqrt(1.0 + A * A), sb = sqrt(1.0 + B * B);
    return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2.0 * PI_D);
}

static il_scene *floor_scene(bool occluder)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = RHO});
    add_floor(s, 0.0f, 20.0f, m);
    if (occluder) {
        /* A square roof of half-size 1 at height 1, facing down. */
        add_quad(s, v3(0, 1, 0), v3(1, 0, 0), v3(0, 0, 1), 0);
        /* Seen from below the roof, a narrow view of the point under its centre. */
        set_camera(s, v3(0, 0.8f, 1.5f), v3(0, 0, 0), v3(0, 1, 0), 1.0f);
    } else {
        set_camera(s, v3(0, 1, 0), v3(0, 0, 0), v3(0, 0, -1), 40.0f);
    }
    set_sky(s, SKY);
    commit(s);
    return s;
}

static void check_channels(const char *what, const il_image *img, double fraction, double tol)
{
    for (int c = 0; c < 3; c++) {
        double expect = v3_get(RHO, c) * v3_get(SKY, c) * fraction;
        double got = image_mean(img, c);
        if (c == 1)
            printf("%s: %.5f expected %.5f (%+.3f%%)\n", what, got, expect, 100.0 * (got / expect - 1.0));
        CHECK_REL(got, expect, tol);
    }
}

static void test_open_floor(void)
{
    il_scene *s = floor_scene(false);
    static const struct {
        il_ibl_selection sel;
        const char *name;
        uint32_t lights;
        double tol;
    } sets[] = {{IL_IBL_IMPORTANCE_SOBOL, "open floor, importance-sobol", 4096, 0.005},
                {IL_IBL_SOBOL, "open floor, sobol", 4096, 0.005},
                {IL_IBL_IMPORTANCE, "open floor, importance", 65536, 0.02},
                {IL_IBL_RANDOM, "open floor, random", 65536, 0.02}};
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++) {
        il_ibl_desc d = {.lights = sets[k].lights, .selection = sets[k].sel, .batch = 4096};
        il_render_stats st;
        il_image img = render_ibl(s, 16, 16, &d, 1, 3, &st);
        check_channels(sets[k].name, &img, 1.0, sets[k].tol);
        CHECK(st.ibl.lights == sets[k].lights);
        CHECK(st.spp == 1);
        /* Half the lights are below the floor and cast no ray. */
        CHECK(st.ibl.shadow_rays > 0 && st.ibl.shadow_rays < (uint64_t)16 * 16 * sets[k].lights * 6 / 10);
        il_image_free(&img);
    }
    il_scene_release(s);
}

static void test_occluder(void)
{
    double F = 4.0 * f_corner(1.0, 1.0);
    printf("occluder: view factor %.5f, sky fraction %.5f\n", F, 1.0 - F);
    il_scene *s = floor_scene(true);
    il_ibl_desc d = {.lights = 16384, .selection = IL_IBL_SOBOL, .batch = 4096};
    il_image img = render_ibl(s, 8, 8, &d, 1, 1, NULL);
    check_channels("occluder, sobol, rays", &img, 1.0 - F, 0.01);
    il_image_free(&img);

    d.selection = IL_IBL_RANDOM;
    d.lights = 65536;
    img = render_ibl(s, 8, 8, &d, 1, 1, NULL);
    check_channels("occluder, random, rays", &img, 1.0 - F, 0.03);
    il_image_free(&img);

    /* Shadow maps: the roof's shadow edge is blurred by a texel or two in
     * light space, which moves the fraction a little. */
    d = (il_ibl_desc){.lights = 4096, .selection = IL_IBL_SOBOL, .shadows = IL_IBL_SHADOW_MAPS,
                      .batch = 256};
    img = render_ibl(s, 8, 8, &d, 1, 1, NULL);
    check_channels("occluder, sobol, shadow maps", &img, 1.0 - F, 0.02);
    il_image_free(&img);

    /* Without shadows the roof is ignored: the open floor's value. */
    d.shadows = IL_IBL_SHADOW_NONE;
    img = render_ibl(s, 8, 8, &d, 1, 1, NULL);
    check_channels("occluder, sobol, no shadows", &img, 1.0, 0.005);
    il_image_free(&img);
    il_scene_release(s);
}

static void test_mirror_and_sky(void)
{
    /* The camera at height 1 looks along -z at a mirror 1 m away, tilted so
     * that the centre ray goes back and down with slope 0.1: it meets the
     * floor 10 m behind, where the 0.5 m mirror covers under 0.1% of the
     * sky. */
    const il_vec3 tint = {0.8f, 0.6f, 0.9f};
    il_scene *s = new_scene();
    uint32_t floor_m = add_material(s, (il_material_desc){.diffuse = RHO});
    uint32_t mirror = add_material(s, (il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = tint});
    add_floor(s, 0.0f, 40.0f, floor_m);
    il_vec3 n = v3_normalize(v3(0.0f, -0.1f / sqrtf(1.01f), 1.0f / sqrtf(1.01f) + 1.0f));
    /* Front face cross(ex, ey) = n |ex|^2 for ey along cross(n, ex). */
    il_vec3 ex = v3(0.5f, 0, 0), ey = v3_scale(v3_normalize(v3_cross(n, ex)), 0.5f);
    add_quad(s, v3(0, 1, -1), ex, ey, mirror);
    set_camera(s, v3(0, 1, 0), v3(0, 1, -1), v3(0, 1, 0), 3.0f);
    set_sky(s, SKY);
    commit(s);

    il_ibl_desc d = {.lights = 4096, .selection = IL_IBL_SOBOL};
    il_render_desc rd = {.method = IL_METHOD_IBL, .ibl = &d, .max_depth = 2, .seed = 2};
    il_image img = render_desc_image(s, 8, 8, &rd, NULL);
    for (int c = 0; c < 3; c++) {
        double expect = v3_get(tint, c) * v3_get(RHO, c) * v3_get(SKY, c);
        if (c == 0)
            printf("mirror: %.5f expected %.5f\n", image_mean(&img, c), expect);
        CHECK_REL(image_mean(&img, c), expect, 0.01);
    }
    il_image_free(&img);
    rd.max_depth = 0; /* the default, 8 */
    img = render_desc_image(s, 8, 8, &rd, NULL);
    CHECK_REL(image_mean(&img, 1), tint.y * RHO.y * SKY.y, 0.01);
    il_image_free(&img);
    /* max_depth 1: the floor behind the mirror is a second scattering
     * event; nothing is added, as in the path tracer. */
    rd.max_depth = 1;
    img = render_desc_image(s, 8, 8, &rd, NULL);
    CHECK(image_mean(&img, 0) == 0.0 && image_mean(&img, 1) == 0.0);
    il_image_free(&img);
    img = render_pt_direct(s, 8, 8, 4, 1);
    CHECK(image_mean(&img, 1) == 0.0);
    il_image_free(&img);
    il_scene_release(s);

    /* Looking up: every camera ray escapes and sees exactly the sky. */
    s = new_scene();
    add_floor(s, 0.0f, 20.0f, 0);
    set_camera(s, v3(0, 1, 0), v3(0, 2, 0), v3(0, 0, -1), 60.0f);
    set_sky(s, SKY);
    commit(s);
    d = (il_ibl_desc){.lights = 64};
    img = render_ibl(s, 8, 8, &d, 2, 0, NULL);
    bool exact = true;
    for (uint32_t i = 0; i < 64; i++)
        exact &= img.rgb[3 * i] == SKY.x && img.rgb[3 * i + 1] == SKY.y && img.rgb[3 * i + 2] == SKY.z;
    CHECK(exact);
    il_image_free(&img);
    il_scene_release(s);
}

int main(void)
{
    test_open_floor();
    test_occluder();
    test_mirror_and_sky();
    return check_report();
}
