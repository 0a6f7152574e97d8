/* Thin panes of glass (IL_MATERIAL_THIN_GLASS, scene/pane.h):
 * - the optics: a clear pane of index 1.5 transmits (1 - F0) / (1 + F0) =
 *   0.923077 at normal incidence and 0.848128 at 60 degrees (the Fresnel
 *   terms per polarisation summed over the slab's inter-reflections, worked
 *   by hand: r_s = 0.176571, r_p = 0.001802), reflects the rest, and with
 *   absorption less; il_pane_tau_for inverts the normal transmittance;
 * - bad panes are refused (a tint, ior 1, a transmittance above clear glass);
 * - the sun through a horizontal pane: E = E0 cos(theta) T(theta), exactly
 *   (shadow rays weigh the pane's T: il_trace_visibility);
 * - a uniform sky through the pane: E = 2 pi L int T(cos) cos sin, by
 *   quadrature; and the sky the pane reflects onto a sensor above it (a
 *   black floor under the pane): 2 pi L int R(cos) cos sin, which only the
 *   reflected rays can find (closest-hit rays stop at the pane with
 *   probability 1 - T and reflect R / (1 - T));
 * - the path tracer looking through a pane at an emitter sees T Le; a floor
 *   lit by a lamp through a pane gets the same light from light sampling,
 *   from BSDF sampling and from both (MIS): the pane is no vertex, so the
 *   two estimators count the path once between them;
 * - the direct light of radiosity, photon mapping, SPPM and the RSM passes
 *   the pane too;
 * - the false-colour view's sensors go on the floor behind a pane;
 * - the Linespace's in-shaft occlusion test lets a pane through;
 * - the rays meet panes the same whatever the thread count. */
#include "pt_scenes.h"
#include "methods/linespace/ls.h"
#include "scene/pane.h"
#include "scene/scene.h"

static double pane_T(float ior, float tau, double cos_i)
{
    float R, T;
    il_pane_optics(ior, tau, (float)cos_i, &R, &T);
    return T;
}

static double pane_R(float ior, float tau, double cos_i)
{
    float R, T;
    il_pane_optics(ior, tau, (float)cos_i, &R, &T);
    return R;
}

static void test_optics(void)
{
    float R, T;
    il_pane_optics(1.5f, 1.0f, 1.0f, &R, &T);
    printf("clear pane, normal incidence: R %.6f T %.6f\n", (double)R, (double)T);
    CHECK_NEAR(T, 0.923077, 1e-5);
    CHECK_NEAR(R, 0.076923, 1e-5);
    CHECK_NEAR(il_pane_clear_transmittance(1.5f), 0.923077, 1e-5);
    il_pane_optics(1.5f, 1.0f, 0.5f, &R, &T);
    printf("clear pane, 60 degrees: R %.6f T %.6f\n", (double)R, (double)T);
    CHECK_NEAR(T, 0.848128, 1e-5);
    CHECK_NEAR(R, 0.151872, 1e-5);
    /* Without absorption nothing is lost, at any angle; grazing light is
     * all reflected. */
    for (int k = 1; k <= 20; k++) {
        il_pane_optics(1.52f, 1.0f, (float)k / 20.0f, &R, &T);
        CHECK_NEAR(R + T, 1.0, 1e-5);
    }
    il_pane_optics(1.5f, 1.0f, 0.0f, &R, &T);
    CHECK_NEAR(T, 0.0, 1e-6);
    CHECK_NEAR(R, 1.0, 1e-6);
    /* A tinted pane of 60% light transmittance: tau0 from the quadratic,
     * T(normal) back, and some light absorbed; more at a slant, where the
     * path through the glass is longer. */
    float tau = il_pane_tau_for(1.5f, 0.6f);
    il_pane_optics(1.5f, tau, 1.0f, &R, &T);
    printf("tau0 %.6f for T 0.6: T %.6f R %.6f\n", (double)tau, (double)T, (double)R);
    CHECK_NEAR(T, 0.6, 1e-5);
    CHECK(tau > 0.6f && tau < 0.7f && R + T < 0.7f);
    float R60, T60;
    il_pane_optics(1.5f, tau, 0.5f, &R60, &T60);
    CHECK(T60 < T && 1.0f - R60 - T60 > 1.0f - R - T);
    CHECK_NEAR(il_pane_tau_for(1.5f, il_pane_clear_transmittance(1.5f)), 1.0, 1e-5);
}

static void test_bad_panes(void)
{
    il_scene *s = new_scene();
    const il_material_desc bad[] = {
        {.name = "green", .type = IL_MATERIAL_THIN_GLASS, .specular = {0.5f, 1.0f, 0.5f}},
        {.name = "ior one", .type = IL_MATERIAL_THIN_GLASS, .ior = 1.0f},
        {.name = "too clear", .type = IL_MATERIAL_THIN_GLASS, .transmittance = 0.95f},
        {.name = "negative", .type = IL_MATERIAL_THIN_GLASS, .transmittance = -0.1f},
        {.name = "nan", .type = IL_MATERIAL_THIN_GLASS, .transmittance = NAN},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        il_error e = {0};
        CHECK(il_scene_add_material(s, &bad[i], NULL, &e) == IL_ERR_INVALID);
        printf("refused: %s\n", e.message);
    }
    /* Clear by default, white tint allowed, the darkest 0+. */
    il_material_desc good = {.name = "ok", .type = IL_MATERIAL_THIN_GLASS, .specular = v3s(1.0f),
                             .transmittance = 0.1f};
    CHECK_OK(il_scene_add_material(s, &good, NULL, &g_err), &g_err);
    il_scene_release(s);
}

static uint32_t pane_material(il_scene *s, float transmittance)
{
    return add_material(s, (il_material_desc){.type = IL_MATERIAL_THIN_GLASS,
                                              .transmittance = transmittance});
}

static void measure(const il_scene *s, il_sensor sn, uint32_t samples, il_illuminance *out)
{
    il_illuminance_desc d = {.samples = samples, .seed = 3, .threads = 2};
    CHECK_OK(il_measure_illuminance(s, &sn, 1, &d, out, NULL, &g_err), &g_err);
}

static void test_sun_through_pane(void)
{
    const float E0 = 2.0f;
    for (int tinted = 0; tinted < 2; tinted++) {
        for (int a = 0; a < 2; a++) {
            double theta = a ? 60.0 * IL_PI / 180.0 : 0.0;
            il_scene *s = new_scene();
            uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
            add_floor(s, -0.01f, 50.0f, black);
            uint32_t glass = pane_material(s, tinted ? 0.5f : 0.0f);
            add_floor(s, 1.0f, 50.0f, glass);
            CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_DIRECTIONAL,
                                                            .direction = v3((float)sin(theta), -(float)cos(theta), 0),
                                                            .intensity = v3s(E0)},
                                        &g_err), &g_err);
            commit(s);
            il_illuminance r;
            measure(s, (il_sensor){v3(0, 0, 0), v3(0, 1, 0)}, 64, &r);
            float tau = tinted ? il_pane_tau_for(1.5f, 0.5f) : 1.0f;
            double expect = E0 * cos(theta) * pane_T(1.5f, tau, cos(theta));
            printf("sun at %.0f degrees through a %s pane: E %.6f, expected %.6f\n",
                   theta * 180.0 / IL_PI, tinted ? "50%" : "clear", (double)r.irradiance.y, expect);
            CHECK_NEAR(r.irradiance.y, expect, 1e-4 * expect);
            il_scene_release(s);
        }
    }
}

/* 2 pi int_0^{pi/2} f(cos t) cos t sin t dt, by the midpoint rule. */
static double hemisphere_integral(double (*f)(float, float, double), float ior, float tau)
{
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double c = (i + 0.5) / n;          /* substitute u = cos t: int f(u) u du */
        sum += f(ior, tau, c) * c;
    }
    return 2.0 * IL_PI * sum / n;
}

static void test_sky_through_and_off_pane(void)
{
    const float L = 1.0f;
    il_scene *s = new_scene();
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
    add_floor(s, -0.01f, 200.0f, black);
    add_floor(s, 1.0f, 200.0f, pane_material(s, 0.0f));
    CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = v3s(L)}, &g_err), &g_err);
    commit(s);
    il_illuminance below, above;
    measure(s, (il_sensor){v3(0, 0, 0), v3(0, 1, 0)}, 16384, &below);
    measure(s, (il_sensor){v3(0, 2, 0), v3(0, -1, 0)}, 65536, &above);
    double e_t = L * hemisphere_integral(pane_T, 1.5f, 1.0f);
    double e_r = L * hemisphere_integral(pane_R, 1.5f, 1.0f);
    printf("sky under a clear pane: E %.5f +- %.5f, expected %.5f (pi L %.5f)\n",
           (double)below.irradiance.y, (double)below.lux_error / 683.0, e_t, IL_PI * L);
    printf("sky reflected by the pane: E %.5f +- %.5f, expected %.5f\n", (double)above.irradiance.y,
           (double)above.lux_error / 683.0, e_r);
    CHECK_NEAR(below.irradiance.y, e_t, 0.01 * e_t);
    CHECK_NEAR(above.irradiance.y, e_r, 0.05 * e_r);
    il_scene_release(s);
}

/* A camera looking along -z through a pane at z = 0 at an emitter at z = -1
 * that fills its narrow view. */
static void test_camera_through_pane(void)
{
    il_scene *s = new_scene();
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3(2.0f, 1.0f, 0.5f)});
    add_quad(s, v3(0, 0, -1), v3(10, 0, 0), v3(0, 10, 0), lamp);
    add_quad(s, v3(0, 0, 0), v3(10, 0, 0), v3(0, 10, 0), pane_material(s, 0.0f));
    set_camera(s, v3(0, 0, 3), v3(0, 0, 0), v3(0, 1, 0), 4.0f);
    commit(s);
    il_render_desc rd = {.spp = 64, .max_depth = 4, .seed = 5, .threads = 2};
    il_image img = render_image(s, 32, 32, &rd, IL_PT_MIS, NULL);
    double T = pane_T(1.5f, 1.0f, 1.0);
    printf("emitter through a pane: %.5f %.5f %.5f, expected T Le = %.5f %.5f %.5f\n",
           image_mean(&img, 0), image_mean(&img, 1), image_mean(&img, 2), 2.0 * T, T, 0.5 * T);
    CHECK_NEAR(image_mean(&img, 0), 2.0 * T, 0.01 * 2.0 * T);
    CHECK_NEAR(image_mean(&img, 2), 0.5 * T, 0.01 * 0.5 * T);
    il_image_free(&img);
    il_scene_release(s);
}

/* A grey floor under a pane, a square lamp above the pane, seen from above
 * the lamp's side: light sampling alone, BSDF sampling alone and MIS. */
static il_scene *lamp_pane_floor(void)
{
    il_scene *s = new_scene();
    uint32_t grey = add_material(s, (il_material_desc){.diffuse = v3s(0.5f)});
    add_floor(s, 0.0f, 3.0f, grey);
    add_floor(s, 1.0f, 3.0f, pane_material(s, 0.6f));
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3s(4.0f)});
    add_quad(s, v3(0, 2, 0), v3(0.5f, 0, 0), v3(0, 0, 0.5f), lamp); /* faces down */
    set_camera(s, v3(0, 0.6f, 2.9f), v3(0, 0, 0), v3(0, 1, 0), 40.0f);
    commit(s);
    return s;
}

static void test_strategies_agree(void)
{
    il_scene *s = lamp_pane_floor();
    il_render_desc rd = {.spp = 256, .max_depth = 1, .seed = 7, .threads = 2};
    il_image nee = render_image(s, 32, 32, &rd, IL_PT_NEE_ONLY, NULL);
    il_image bsdf = render_image(s, 32, 32, &rd, IL_PT_BSDF_ONLY, NULL);
    il_image mis = render_image(s, 32, 32, &rd, IL_PT_MIS, NULL);
    /* The floor below the lamp: the lower half of the image. */
    double m_nee = region_mean(&nee, 0, 20, 32, 32, 1), m_bsdf = region_mean(&bsdf, 0, 20, 32, 32, 1),
           m_mis = region_mean(&mis, 0, 20, 32, 32, 1);
    printf("floor under the pane, direct light: light sampling %.5f, BSDF sampling %.5f, MIS %.5f\n",
           m_nee, m_bsdf, m_mis);
    CHECK(m_nee > 0.01);
    CHECK_NEAR(m_mis, m_nee, 0.02 * m_nee);
    CHECK_NEAR(m_bsdf, m_nee, 0.04 * m_nee);
    /* Thread counts: the same image. */
    rd.threads = 1;
    il_image one = render_image(s, 32, 32, &rd, IL_PT_MIS, NULL);
    CHECK(memcmp(one.rgb, mis.rgb, 3 * sizeof(float) * 32 * 32) == 0);
    il_image_free(&one);
    il_image_free(&nee);
    il_image_free(&bsdf);
    il_image_free(&mis);
    il_scene_release(s);
}

/* The sun on a floor through a pane, for the methods whose direct light is
 * their own (radiosity's patch_direct, il_direct_light of photon mapping,
 * SPPM and the RSM): the floor's radiance rho E0 T / pi. */
static void test_methods_sun_through_pane(void)
{
    il_scene *s = new_scene();
    uint32_t grey = add_material(s, (il_material_desc){.diffuse = v3s(0.5f)});
    add_floor(s, 0.0f, 1.0f, grey);
    /* High above, so that the pane's reflection of the lit floor (R 8% of
     * light it sees under a solid angle of about A / (2 h)^2) adds nothing
     * measurable for the methods that follow it (photon mapping, SPPM). */
    add_floor(s, 20.0f, 60.0f, pane_material(s, 0.0f));
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_DIRECTIONAL,
                                                    .direction = v3(0, -1, 0), .intensity = v3s(3.0f)},
                                &g_err), &g_err);
    set_camera(s, v3(0, 0.5f, 0.001f), v3(0, 0, 0), v3(0, 0, -1), 30.0f);
    commit(s);
    const il_method methods[] = {IL_METHOD_RADIOSITY, IL_METHOD_PHOTON, IL_METHOD_SPPM, IL_METHOD_RSM};
    const char *names[] = {"radiosity", "photon", "sppm", "rsm"};
    for (int k = 0; k < 4; k++) {
        il_render_desc rd = {.method = methods[k], .spp = 4, .max_depth = 4, .seed = 1, .threads = 2};
        il_film *film = NULL;
        CHECK_OK(il_film_create(16, 16, &film, &g_err), &g_err);
        CHECK_OK(il_render(s, film, &rd, NULL, &g_err), &g_err);
        il_image img = {0};
        CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
        double expect = 0.5 * 3.0 * pane_T(1.5f, 1.0f, 1.0) / IL_PI;
        printf("%s, sun through a pane: floor %.5f, expected %.5f\n", names[k], image_mean(&img, 1),
               expect);
        CHECK_NEAR(image_mean(&img, 1), expect, 0.01 * expect);
        il_image_free(&img);
        il_film_release(film);
    }
    il_scene_release(s);
}

/* The false-colour view's sensors go on what lies behind a pane: every
 * pixel of a camera looking down through a pane at a floor. */
static void test_camera_sensors_look_through(void)
{
    il_scene *s = new_scene();
    add_floor(s, 0.0f, 5.0f, add_material(s, (il_material_desc){.diffuse = v3s(0.5f)}));
    add_floor(s, 1.0f, 5.0f, pane_material(s, 0.3f));
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_DIRECTIONAL,
                                                    .direction = v3(0, -1, 0), .intensity = v3s(1.0f)},
                                &g_err), &g_err);
    set_camera(s, v3(0, 3, 0.001f), v3(0, 0, 0), v3(0, 0, -1), 40.0f);
    commit(s);
    il_sensor sn[16 * 16];
    bool seen[16 * 16];
    CHECK_OK(il_camera_sensors(s, 16, 16, sn, seen, &g_err), &g_err);
    int on_floor = 0;
    for (int i = 0; i < 16 * 16; i++)
        on_floor += seen[i] && fabsf(sn[i].position.y) < 1e-3f && sn[i].normal.y > 0.99f;
    printf("camera sensors through a pane: %d of 256 on the floor\n", on_floor);
    CHECK(on_floor == 256);
    il_scene_release(s);
}

/* The Linespace's in-shaft occlusion test lets a pane through (its
 * candidate lists leave panes out), as il_trace_occluded does; a diffuse
 * sheet in the same place blocks. */
static void test_linespace_shafts(void)
{
    for (int pane = 0; pane < 2; pane++) {
        il_scene *s = new_scene();
        uint32_t grey = add_material(s, (il_material_desc){.diffuse = v3s(0.5f)});
        add_floor(s, 0.0f, 1.0f, grey);
        add_floor(s, 0.3f, 1.0f, pane ? pane_material(s, 0.0f) : grey);
        CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 0.9f, 0),
                                                        .intensity = v3s(1.0f)}, &g_err), &g_err);
        commit(s);
        il_linespace ls;
        il_ls_settings set = {.grid = 2, .n = 2};
        CHECK_OK(il_ls_build(s, &set, 1, &ls, &g_err), &g_err);
        /* Up from the floor's middle, slightly slanted, through the sheet
         * at y = 0.3 inside the floor's voxel (the grid's voxels are 1 m). */
        bool blocked = il_ls_occluded(&ls, s, v3(0.2f, 0.0f, 0.2f), v3_normalize(v3(0.1f, 1.0f, 0.05f)),
                                      0, 0, NULL);
        printf("linespace shaft through a %s: %s\n", pane ? "pane" : "diffuse sheet",
               blocked ? "blocked" : "clear");
        CHECK(blocked == !pane);
        il_ls_free(&ls);
        il_scene_release(s);
    }
}

int main(void)
{
    test_optics();
    test_bad_panes();
    test_sun_through_pane();
    test_sky_through_and_off_pane();
    test_camera_through_pane();
    test_strategies_agree();
    test_methods_sun_through_pane();
    test_camera_sensors_look_through();
    test_linespace_shafts();
    return check_report();
}
