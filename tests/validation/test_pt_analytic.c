/* Analytic direct lighting of a Lambertian plane (radiance = rho/pi * E for
 * irradiance E, pbrt-v4 4.3.1 / 9.2):
 *  - under a uniform sky L: E = pi L, so radiance rho L; rays that miss see L;
 *  - point light of intensity I at height h: E = I h / (h^2 + r^2)^(3/2);
 *  - spot light: the same times cos^n of the angle to its axis, 0 beyond
 *    the cut-off;
 *  - directional light of irradiance E at angle theta: E cos(theta).
 * Nothing else is in these scenes, so there is no indirect light: the plane
 * cannot see itself. */
#include "pt_scenes.h"

static const il_vec3 RHO = {0.5f, 0.7f, 0.3f};

/* A big diffuse floor at y = 0 seen from (0, H, 0) straight down. */
static il_scene *floor_scene(float cam_height, float fov)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = RHO});
    add_floor(s, 0.0f, 20.0f, m);
    set_camera(s, v3(0, cam_height, 0), v3(0, 0, 0), v3(0, 0, -1), fov);
    return s;
}

static void test_sky(void)
{
    const il_vec3 L = {1.0f, 2.0f, 0.5f};
    il_scene *s = floor_scene(1.0f, 40.0f);
    il_environment_desc env = {.radiance = L};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.spp = 64, .seed = 11};
    il_image img = render_image(s, 32, 32, &rd, IL_PT_MIS, NULL);
    for (int c = 0; c < 3; c++) {
        double expect = v3_get(RHO, c) * v3_get(L, c);
        printf("sky: channel %d mean %.5f expected %.5f\n", c, image_mean(&img, c), expect);
        CHECK_REL(image_mean(&img, c), expect, 0.01);
        CHECK_REL(region_mean(&img, 0, 0, 16, 16, c), expect, 0.02);
        CHECK_REL(region_mean(&img, 16, 16, 32, 32, c), expect, 0.02);
    }
    il_image_free(&img);
    /* BSDF sampling alone must agree (every ray escapes to the sky). */
    img = render_image(s, 32, 32, &rd, IL_PT_BSDF_ONLY, NULL);
    CHECK_REL(image_mean(&img, 1), RHO.y * L.y, 0.01);
    il_image_free(&img);
    il_scene_release(s);

    /* Looking up, every camera ray misses: exactly L in every pixel. */
    s = new_scene();
    add_floor(s, 0.0f, 20.0f, 0);
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    set_camera(s, v3(0, 1, 0), v3(0, 2, 0), v3(0, 0, -1), 60.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    rd.spp = 2;
    img = render_image(s, 16, 16, &rd, IL_PT_MIS, NULL);
    bool exact = true;
    for (uint32_t i = 0; i < 16 * 16; i++)
        exact &= img.rgb[3 * i] == L.x && img.rgb[3 * i + 1] == L.y && img.rgb[3 * i + 2] == L.z;
    CHECK(exact);
    il_image_free(&img);
    il_scene_release(s);
}

/* Compares every pixel whose centre sees the floor at distance r from the
 * foot of a light at height h with the expected radiance f(r, h) (returns
 * how many pixels were compared; f < 0 means "skip this pixel"). */
typedef double (*radiance_fn)(double r, double h, int channel);

static int compare_pixels(const il_scene *s, const il_image *img, double h, radiance_fn f, double tol)
{
    int compared = 0, bad = 0;
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++) {
            il_vec3 q;
            if (!pixel_on_plane(s, img->width, img->height, x, y, 0.0f, &q))
                continue;
            double r = sqrt((double)q.x * q.x + (double)q.z * q.z);
            for (int c = 0; c < 3; c++) {
                double expect = f(r, h, c);
                if (expect < 0.0)
                    continue;
                double got = img->rgb[3 * ((size_t)y * img->width + x) + c];
                compared++;
                if (fabs(got - expect) > tol * expect + 1e-7) {
                    if (bad++ < 5)
                        fprintf(stderr, "pixel (%u,%u) r %.4f channel %d: %.6g expected %.6g\n", x, y, r,
                                c, got, expect);
                }
            }
        }
    CHECK(bad == 0);
    return compared;
}

static const il_vec3 I_POINT = {10.0f, 5.0f, 2.5f};

static double point_radiance(double r, double h, int c)
{
    double d2 = h * h + r * r;
    return v3_get(RHO, c) / PI_D * v3_get(I_POINT, c) * h / (d2 * sqrt(d2));
}

static void test_point(void)
{
    const float h = 2.0f;
    il_scene *s = floor_scene(4.0f, 30.0f);
    il_light_desc l = {.type = IL_LIGHT_POINT, .position = {0, h, 0}, .intensity = I_POINT};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.spp = 16, .seed = 5};
    il_image img = render_image(s, 33, 33, &rd, IL_PT_MIS, NULL);
    /* The central pixel sees the foot: rho/pi * I / h^2. */
    double foot = img.rgb[3 * (16 * 33 + 16)];
    printf("point: foot %.6f expected %.6f\n", foot, RHO.x / PI_D * I_POINT.x / (h * h));
    CHECK_REL(foot, RHO.x / PI_D * I_POINT.x / (h * h), 0.002);
    /* Every pixel follows the inverse-square and cosine law (the pixel's
     * box average differs from its centre by well under 0.5%). */
    CHECK(compare_pixels(s, &img, h, point_radiance, 0.005) == 33 * 33 * 3);
    il_image_free(&img);
    il_scene_release(s);
}

static const il_vec3 I_SPOT = {4.0f, 4.0f, 4.0f};
#define SPOT_ANGLE 30.0
#define SPOT_N 8.0

static double spot_radiance(double r, double h, int c)
{
    double theta = atan2(r, h) * 180.0 / PI_D;
    if (theta > SPOT_ANGLE - 1.5 && theta < SPOT_ANGLE + 1.5)
        return -1.0; /* pixels straddling the cut-off: skipped */
    if (theta >= SPOT_ANGLE)
        return 0.0;
    double d2 = h * h + r * r, cos_t = h / sqrt(d2);
    return v3_get(RHO, c) / PI_D * v3_get(I_SPOT, c) * pow(cos_t, SPOT_N) * cos_t / d2;
}

static void test_spot(void)
{
    const float h = 2.0f;
    il_scene *s = floor_scene(4.0f, 50.0f);
    il_light_desc l = {.type = IL_LIGHT_SPOT, .position = {0, h, 0}, .direction = {0, -1, 0},
                       .intensity = I_SPOT, .spot_angle = (float)SPOT_ANGLE, .spot_exponent = (float)SPOT_N};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.spp = 16, .seed = 5};
    il_image img = render_image(s, 48, 48, &rd, IL_PT_MIS, NULL);
    int n = compare_pixels(s, &img, h, spot_radiance, 0.01);
    printf("spot: %d pixel channels compared\n", n);
    CHECK(n > 48 * 48 * 3 / 2);
    /* The corners lie outside the cone: black. */
    CHECK(img.rgb[0] == 0.0f && img.rgb[3 * (48 * 48 - 1)] == 0.0f);
    /* The falloff itself: a pixel about 20 degrees off the axis against the
     * foot, (cos^(n+3) law: n for the profile, 1 for the surface, 2 for distance). */
    uint32_t x20 = 0;
    for (uint32_t x = 24; x < 48; x++) {
        il_vec3 q = v3s(0.0f);
        pixel_on_plane(s, 48, 48, x, 24, 0.0f, &q);
        if (atan2(fabs(q.x), h) * 180.0 / PI_D >= 20.0) {
            x20 = x;
            break;
        }
    }
    il_vec3 q20 = v3s(0.0f), q0 = v3s(0.0f);
    pixel_on_plane(s, 48, 48, x20, 24, 0.0f, &q20);
    pixel_on_plane(s, 48, 48, 24, 24, 0.0f, &q0);
    double c20 = h / sqrt(h * h + q20.x * q20.x + q20.z * q20.z);
    double c0 = h / sqrt(h * h + q0.x * q0.x + q0.z * q0.z);
    double ratio = img.rgb[3 * (24 * 48 + x20)] / img.rgb[3 * (24 * 48 + 24)];
    printf("spot: falloff ratio %.5f expected %.5f\n", ratio, pow(c20 / c0, SPOT_N + 3.0));
    CHECK_REL(ratio, pow(c20 / c0, SPOT_N + 3.0), 0.01);
    il_image_free(&img);
    il_scene_release(s);
}

static void test_directional(void)
{
    const double theta = 60.0 * PI_D / 180.0;
    const il_vec3 E = {2.0f, 1.0f, 3.0f};
    il_scene *s = floor_scene(1.0f, 40.0f);
    il_light_desc l = {.type = IL_LIGHT_DIRECTIONAL, .direction = {(float)sin(theta), (float)-cos(theta), 0},
                       .intensity = E};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.spp = 4, .seed = 1};
    il_image img = render_image(s, 16, 16, &rd, IL_PT_MIS, NULL);
    for (int c = 0; c < 3; c++) {
        double expect = v3_get(RHO, c) / PI_D * v3_get(E, c) * cos(theta);
        printf("directional: channel %d %.6f expected %.6f\n", c, image_mean(&img, c), expect);
        CHECK_REL(image_mean(&img, c), expect, 1e-4);
        CHECK_REL(img.rgb[c], expect, 1e-4);
    }
    il_image_free(&img);
    il_scene_release(s);
}

int main(void)
{
    test_sky();
    test_point();
    test_spot();
    test_directional();
    return check_report();
}
