/* The sun's disc seen by the camera (il_background_radiance).  A
 * directional light with a diameter is a disc of uniform radiance
 * L = E / (pi sin^2 a) (E its irradiance facing it, a its angular radius):
 * - looked at, every method shows it with the light's energy: the pixels'
 *   radiance summed over their solid angles (less the sky's) is
 *   int L dw = L 2 pi (1 - cos a) = 2 E / (1 + cos a);
 * - in a mirror the same times the mirror's tint;
 * - after a diffuse vertex it is light sampling's alone: a floor beside a
 *   mirror that reflects the sun gets no fireflies from rays that find the
 *   disc through the mirror (the sun's mirror caustic is left to photon
 *   mapping, as it always was for a delta light). */
#include "pt_scenes.h"
#include "scene/scene.h"

enum { W = 64, H = 64 };
#define FOV 20.0f
#define DIAMETER 4.0f

static const il_vec3 E = {3.0f, 2.0f, 1.0f};
static const il_vec3 SKY = {0.05f, 0.05f, 0.05f};

/* Towards the sun: 30 degrees up, towards -z. */
static il_vec3 towards(void) { return v3(0.0f, 0.5f, -0.8660254f); }

/* A grey floor, a mirror (tint 0.8) beside it, the sun and a faint sky. */
static il_scene *sun_scene(il_vec3 cam_pos, il_vec3 cam_dir)
{
    il_scene *s = new_scene();
    uint32_t grey = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIFFUSE, .diffuse = {0.5f, 0.5f, 0.5f}});
    uint32_t mirror = add_material(s, (il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = {0.8f, 0.8f, 0.8f}});
    add_quad(s, v3(0, 0, 0), v3(0, 0, 4), v3(4, 0, 0), grey);
    /* A mirror floor off to the side (x = 20), for the sun's reflection. */
    add_quad(s, v3(20, 0, 0), v3(0, 0, 4), v3(4, 0, 0), mirror);
    /* A mirror wall at z = 4 facing -z: from the grey floor, rays going up
     * along +z at 30 degrees meet it and leave towards the sun. */
    add_quad(s, v3(0, 2, 4), v3(0, 2, 0), v3(4, 0, 0), mirror);
    il_light_desc sun = {.type = IL_LIGHT_DIRECTIONAL, .direction = v3_neg(towards()), .intensity = E,
                         .diameter = DIAMETER};
    CHECK_OK(il_scene_add_light(s, &sun, &g_err), &g_err);
    CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = SKY}, &g_err), &g_err);
    set_camera(s, cam_pos, v3_add(cam_pos, cam_dir), v3(0, 1, 0), FOV);
    commit(s);
    return s;
}

/* Sum over the pixels of (radiance - sky) times the pixel's solid angle,
 * channel c: the pinhole's pixel at image-plane (u, v) (distance 1)
 * subtends side^2 cos^3 theta, cos theta = 1 / sqrt(1 + u^2 + v^2). */
static double disc_energy(const il_image *img, int c, double sky_scale)
{
    double side = 2.0 * tan(0.5 * FOV * PI_D / 180.0) / H, sum = 0.0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double u = ((x + 0.5) - 0.5 * W) * side, v = ((y + 0.5) - 0.5 * H) * side;
            double ct = 1.0 / sqrt(1.0 + u * u + v * v);
            double L = img->rgb[3 * (y * W + x) + c] - sky_scale * (&SKY.x)[c];
            sum += L * side * side * ct * ct * ct;
        }
    return sum;
}

static double expected_energy(int c, double tint)
{
    double a = 0.5 * DIAMETER * PI_D / 180.0;
    return tint * 2.0 * (&E.x)[c] / (1.0 + cos(a));
}

static void check_method(const il_scene *s, il_method method, const char *label, double tint)
{
    il_render_desc rd = {.method = method, .spp = 64, .max_depth = 4, .seed = 3};
    il_photon_desc pd = {.photons = 20000};
    rd.photon = &pd;
    il_render_stats st;
    il_image img = render_desc_image(s, W, H, &rd, &st);
    if (!img.rgb)
        return;
    CHECK(image_finite(&img));
    for (int c = 0; c < 3; c++) {
        double got = disc_energy(&img, c, tint), want = expected_energy(c, tint);
        if (c == 0)
            printf("%-10s channel R: the disc's energy %.5f (expected %.5f)\n", label, got, want);
        CHECK_REL(got, want, 0.02);
    }
    il_image_free(&img);
}

static void test_seen(void)
{
    /* Looking straight at the sun from above the floor (out of view). */
    il_scene *s = sun_scene(v3(0, 1, 0), towards());
    const struct { il_method m; const char *name; } methods[] = {
        {IL_METHOD_PT, "pt"}, {IL_METHOD_RADIOSITY, "radiosity"}, {IL_METHOD_HR, "hr"},
        {IL_METHOD_PHOTON, "photon"}, {IL_METHOD_SPPM, "sppm"}, {IL_METHOD_IBL, "ibl"},
        {IL_METHOD_LINESPACE, "linespace"}, {IL_METHOD_RSM, "rsm"}};
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++)
        check_method(s, methods[i].m, methods[i].name, 1.0);
    il_scene_release(s);

    /* The sun's reflection in the mirror floor, looked down at. */
    il_vec3 t = towards();
    s = sun_scene(v3(20, 2, -2.0f / t.y * t.z), v3(t.x, -t.y, t.z));
    check_method(s, IL_METHOD_PT, "pt, mirror", 0.8);
    check_method(s, IL_METHOD_PHOTON, "photon, mirror", 0.8);
    il_scene_release(s);
}

/* The floor in front of the mirror wall, seen from above: a BSDF ray
 * from the floor that the mirror turns into the disc must add nothing
 * (light sampling took the sun there).  Its brightest pixel stays near the
 * floor's direct light E cos / pi * 0.5 (red 0.24), where one such ray
 * would add 0.5 * 0.8 * L / spp (L = 717 in red: 18 at 16 spp). */
static void test_no_fireflies(void)
{
    il_scene *s = sun_scene(v3(0, 3, -1), v3(0, -1, 0.001f));
    il_render_desc rd = {.method = IL_METHOD_PT, .spp = 16, .max_depth = 4, .seed = 1};
    il_image img = render_desc_image(s, W, H, &rd, NULL);
    if (img.rgb) {
        float most = 0.0f;
        for (size_t i = 0; i < (size_t)W * H; i++)
            most = fmaxf(most, img.rgb[3 * i]);
        double direct = 0.5 / PI_D * E.x * towards().y;
        printf("floor by the mirror: brightest red %.4f (its direct light %.4f)\n", (double)most, direct);
        CHECK(most < 3.0 * direct);
        il_image_free(&img);
    }
    il_scene_release(s);
}

int main(void)
{
    test_seen();
    test_no_fireflies();
    return check_report();
}
