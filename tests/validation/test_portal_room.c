/* Environment portals in a room lit by a uniform sky through a window
 * (scene/portal.h): the room 4 x 3 x 5 m (x in [-2, 2], y in [0, 3],
 * z in [-5, 0]), an open window 2 x 1.2 m in the wall z = 0, and a portal
 * on that window lighting the room.
 * - Direct light (black walls, max depth 1): a sensor on the work plane
 *   reads E = L int cos_s cos_w / r^2 dA over the window (a 600 x 360
 *   midpoint quadrature), with the portal and without; the portal's
 *   standard error is under half the other's at equal samples (0.30 of
 *   it 1 m from the window, 0.08 at the back of the room).
 * - Interreflections (grey walls): the readings with and without the
 *   portal agree within their errors.
 * - The path tracer's image with the portal: light sampling alone, BSDF
 *   sampling alone and both (MIS) agree, and agree with the image without
 *   the portal: the mixture's density is the one MIS weighs with.
 * - Radiosity's direct light from the sky (patch_direct.c) converges to
 *   the same room with the portal; hierarchical radiosity solves
 *   scenes/window-room.json with fine elements (test_hr).
 * - Photon mapping and SPPM light that room through the portal (test_photon),
 *   also with a lamp in it (test_lamp).
 * - Linespace injects the same portals' light into a grid over the room
 *   the camera sees (test_linespace), also with the lamp, and keeps the
 *   light outside out of an L-shaped room's grid (test_l_room). */
#include "mesh_compare.h"
#include "methods/portal_light.h"
#include "methods/view_size.h"
#include "scene/scene.h"

#define PI_D 3.14159265358979323846
#define WIN_X 1.0f   /* half-width */
#define WIN_Y0 0.9f
#define WIN_Y1 2.1f

/* The room's surfaces facing inwards, the wall z = 0 in four pieces around
 * the window; a uniform sky of radiance 1; the portal when asked; a point
 * light of `lamp` W/sr at (0, 2.4, -3) when lamp > 0. */
static il_scene *window_room_lamp(float albedo, bool portal, float lamp)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = v3s(albedo)});
    add_quad(s, v3(0, 0, -2.5f), v3(0, 0, 2.5f), v3(2, 0, 0), m);      /* floor, +y */
    add_quad(s, v3(0, 3, -2.5f), v3(2, 0, 0), v3(0, 0, 2.5f), m);      /* ceiling, -y */
    add_quad(s, v3(0, 1.5f, -5), v3(2, 0, 0), v3(0, 1.5f, 0), m);      /* back, +z */
    add_quad(s, v3(-2, 1.5f, -2.5f), v3(0, 1.5f, 0), v3(0, 0, 2.5f), m); /* left, +x */
    add_quad(s, v3(2, 1.5f, -2.5f), v3(0, 0, 2.5f), v3(0, 1.5f, 0), m);  /* right, -x */
    /* The window wall faces -z: beside the window, below it, above it. */
    add_quad(s, v3(-1.5f, 1.5f, 0), v3(0, 1.5f, 0), v3(0.5f, 0, 0), m);
    add_quad(s, v3(1.5f, 1.5f, 0), v3(0, 1.5f, 0), v3(0.5f, 0, 0), m);
    add_quad(s, v3(0, 0.45f, 0), v3(0, 0.45f, 0), v3(1, 0, 0), m);
    add_quad(s, v3(0, 2.55f, 0), v3(0, 0.45f, 0), v3(1, 0, 0), m);
    il_environment_desc env = {.radiance = v3s(1.0f)};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    if (portal) {
        /* Counter-clockwise seen from the room (from -z). */
        il_vec3 c[6] = {v3(WIN_X, WIN_Y0, 0), v3(-WIN_X, WIN_Y0, 0), v3(-WIN_X, WIN_Y1, 0),
                        v3(WIN_X, WIN_Y0, 0), v3(-WIN_X, WIN_Y1, 0), v3(WIN_X, WIN_Y1, 0)};
        CHECK_OK(il_scene_add_portal(s, c, 2, &g_err), &g_err);
    }
    if (lamp > 0.0f) {
        il_light_desc l = {.type = IL_LIGHT_POINT, .position = v3(0, 2.4f, -3), .intensity = v3s(lamp)};
        CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    }
    set_camera(s, v3(0, 1.5f, -4.8f), v3(0, 1.2f, 0), v3(0, 1, 0), 70.0f);
    commit(s);
    return s;
}

static il_scene *window_room(float albedo, bool portal) { return window_room_lamp(albedo, portal, 0.0f); }

/* E at sensor p facing +y from the window of radiance 1: the midpoint rule
 * on a 600 x 360 grid of the window's 2 x 1.2 m. */
static double window_irradiance(il_vec3 p)
{
    const int nx = 600, ny = 360;
    double dx = 2.0 * WIN_X / nx, dy = (WIN_Y1 - WIN_Y0) / ny, e = 0.0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double x = -WIN_X + (i + 0.5) * dx - p.x, y = WIN_Y0 + (j + 0.5) * dy - p.y, z = -p.z;
            double r2 = x * x + y * y + z * z;
            e += (y / sqrt(r2)) * (z / sqrt(r2)) / r2 * dx * dy;
        }
    return e;
}

static void measure(const il_scene *s, const il_sensor *sn, size_t n, uint32_t depth, il_illuminance *out)
{
    il_illuminance_desc d = {.samples = 2048, .max_depth = depth, .seed = 5, .threads = 2};
    CHECK_OK(il_measure_illuminance(s, sn, n, &d, out, NULL, &g_err), &g_err);
}

static const il_sensor sensors[3] = {
    {{0.0f, 0.85f, -1.0f}, {0, 1, 0}}, {{0.5f, 0.85f, -2.5f}, {0, 1, 0}}, {{-1.5f, 0.85f, -4.5f}, {0, 1, 0}}};

static void test_direct(void)
{
    il_scene *with = window_room(0.0f, true), *without = window_room(0.0f, false);
    il_illuminance a[3], b[3];
    measure(with, sensors, 3, 1, a);
    measure(without, sensors, 3, 1, b);
    for (int k = 0; k < 3; k++) {
        /* lux = 683 x the irradiance's luminance (1 for grey radiance 1) */
        double want = window_irradiance(sensors[k].position);
        double ea = a[k].irradiance.y, eb = b[k].irradiance.y;
        double sa = a[k].lux_error / 683.0, sb = b[k].lux_error / 683.0;
        printf("sensor %d: E %.5f, portal %.5f +- %.5f, no portal %.5f +- %.5f\n", k, want, ea, sa, eb, sb);
        CHECK_NEAR(ea, want, 4.0 * sa + 1e-3 * want);
        CHECK_NEAR(eb, want, 4.0 * sb + 1e-3 * want);
        CHECK(sa < 0.5 * sb);
    }
    il_scene_release(with);
    il_scene_release(without);
}

static void test_interreflected(void)
{
    il_scene *with = window_room(0.6f, true), *without = window_room(0.6f, false);
    il_illuminance a[3], b[3];
    measure(with, sensors, 3, 0, a);
    measure(without, sensors, 3, 0, b);
    for (int k = 0; k < 3; k++) {
        printf("sensor %d, walls 0.6: portal %.2f +- %.2f lx, no portal %.2f +- %.2f lx\n", k,
               (double)a[k].lux, (double)a[k].lux_error, (double)b[k].lux, (double)b[k].lux_error);
        double tol = 4.0 * sqrt((double)a[k].lux_error * a[k].lux_error + (double)b[k].lux_error * b[k].lux_error);
        CHECK_NEAR(a[k].lux, b[k].lux, tol);
        CHECK(a[k].lux_error < b[k].lux_error);
    }
    il_scene_release(with);
    il_scene_release(without);
}

static void test_path_tracer(void)
{
    il_scene *with = window_room(0.6f, true), *without = window_room(0.6f, false);
    il_render_desc rd = {.spp = 256, .max_depth = 4, .seed = 9, .threads = 2};
    il_image mis = render_image(with, 48, 36, &rd, IL_PT_MIS, NULL);
    il_image nee = render_image(with, 48, 36, &rd, IL_PT_NEE_ONLY, NULL);
    il_image bsdf = render_image(with, 48, 36, &rd, IL_PT_BSDF_ONLY, NULL);
    rd.spp = 1024;
    il_image ref = render_image(without, 48, 36, &rd, IL_PT_MIS, NULL);
    double m = image_mean(&mis, 1), n = image_mean(&nee, 1), b = image_mean(&bsdf, 1), r = image_mean(&ref, 1);
    printf("path tracer with the portal: MIS %.5f, light sampling %.5f, BSDF sampling %.5f; "
           "without it (1024 spp) %.5f\n", m, n, b, r);
    CHECK_REL(m, r, 0.01);
    CHECK_REL(n, r, 0.01);
    CHECK_REL(b, r, 0.02);
    CHECK(image_finite(&mis) && image_finite(&nee));
    il_image_free(&mis);
    il_image_free(&nee);
    il_image_free(&bsdf);
    il_image_free(&ref);
    il_scene_release(with);
    il_scene_release(without);
}

/* A lamp in the room (2 W/sr, 25 W): the light table chooses between it
 * and the sky by what the sky brings in by the portal (scene/lights.c,
 * interior_weights), pi L A = 7.5 W, not by the sky's power over the
 * scene's bounding disk (480 W), so the lamp gets 77% of the light
 * samples instead of 5%.  The path tracer's image stays the same: with the
 * portal (MIS, and light sampling alone) against the room without it. */
static void test_path_tracer_lamp(void)
{
    il_scene *with = window_room_lamp(0.6f, true, 2.0f), *without = window_room_lamp(0.6f, false, 2.0f);
    uint32_t lamp = with->environment_light == 0 ? 1 : 0;
    printf("lamp and sky: the lamp's share of the light samples %.3f with the portal, %.3f without\n",
           (double)with->light_pmf[lamp], (double)without->light_pmf[lamp]);
    CHECK_REL(with->light_pmf[lamp], 8.0 * PI_D / (8.0 * PI_D + PI_D * 2.4), 1e-4);
    CHECK(without->light_pmf[lamp] < 0.1f);
    il_render_desc rd = {.spp = 256, .max_depth = 4, .seed = 9, .threads = 2};
    il_image mis = render_image(with, 48, 36, &rd, IL_PT_MIS, NULL);
    il_image nee = render_image(with, 48, 36, &rd, IL_PT_NEE_ONLY, NULL);
    rd.spp = 1024;
    il_image ref = render_image(without, 48, 36, &rd, IL_PT_MIS, NULL);
    double m = image_mean(&mis, 1), n = image_mean(&nee, 1), r = image_mean(&ref, 1);
    printf("path tracer, lamp and sky, with the portal: MIS %.5f, light sampling %.5f; without it "
           "(1024 spp) %.5f\n", m, n, r);
    CHECK_REL(m, r, 0.01);
    CHECK_REL(n, r, 0.01);
    il_image_free(&mis);
    il_image_free(&nee);
    il_image_free(&ref);
    il_scene_release(with);
    il_scene_release(without);
}

static void test_radiosity(void)
{
    il_scene *with = window_room(0.6f, true), *without = window_room(0.6f, false);
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .spp = 4, .seed = 2, .threads = 2};
    il_image a = render_desc_image(with, 48, 36, &rd, NULL);
    il_image b = render_desc_image(without, 48, 36, &rd, NULL);
    double ma = image_mean(&a, 1), mb = image_mean(&b, 1);
    printf("radiosity: with the portal %.5f, without %.5f\n", ma, mb);
    CHECK_REL(ma, mb, 0.03);
    il_image_free(&a);
    il_image_free(&b);
    il_scene_release(with);
    il_scene_release(without);
}

/* Hierarchical radiosity refines the elements of scenes/window-room.json
 * beside the window.  The window wall's points lie 1e-17 m in front of the
 * portal's plane (the rounding of its rotation), where the portal's
 * density at grazing crossings reached 8e23 and overflowed the power
 * heuristic to a NaN that spread through the whole solve: it was reported
 * as a stall, and the image was half as bright. */
static void test_hr(void)
{
    il_scene *s = load_committed(IL_SOURCE_DIR "/scenes/window-room.json");
    if (!s)
        return;
    il_hr_desc hd = {.area_eps = 1e-4f};
    il_render_desc rd = {.method = IL_METHOD_HR, .hr = &hd, .spp = 4, .seed = 2, .threads = 2};
    il_render_stats st = {0};
    il_image a = render_desc_image(s, 48, 36, &rd, &st);
    il_render_desc pt = {.spp = 256, .seed = 2, .threads = 2};
    il_image b = render_desc_image(s, 48, 36, &pt, NULL);
    double ma = image_mean(&a, 1), mb = image_mean(&b, 1);
    printf("window room: hr (area_eps 1e-4) %.5f (%llu elements, converged %d), path tracer %.5f\n", ma,
           (unsigned long long)st.hr.elements, (int)st.hr.converged, mb);
    CHECK(st.hr.converged && !st.hr.stalled && image_finite(&a));
    CHECK_REL(ma, mb, 0.05);
    il_image_free(&a);
    il_image_free(&b);
    il_scene_release(s);
}

/* The default radii's scale (methods/view_size.h): the room the camera of
 * scenes/window-room.json looks at (4 x 3 x 5 m, diagonal 7.1 m), not the
 * 80 m ground's 113 m; a Cornell box, seen whole, keeps its box's
 * diagonal exactly; a view that sees nothing keeps it too. */
static void test_view_size(void)
{
    il_scene *s = load_committed(IL_SOURCE_DIR "/scenes/window-room.json");
    if (s) {
        float v = il_view_size(s);
        printf("window room: view size %.3f m, bounding box diagonal %.3f m\n", v,
               v3_length(v3_sub(s->bounds_max, s->bounds_min)));
        CHECK(v > 4.0f && v < 8.0f);
        /* The interior in view: the room's walls, floor and ceiling bound
         * it, the window wall z = 0 too (the ground seen through the
         * window is left out), and the back wall behind the camera, which
         * the bounces from what it sees reach. */
        il_vec3 lo, hi;
        CHECK(il_view_interior(s, &lo, &hi));
        printf("window room: interior in view (%.3f %.3f %.3f) to (%.3f %.3f %.3f)\n", lo.x, lo.y, lo.z,
               hi.x, hi.y, hi.z);
        CHECK(il_portal_light_wanted(s));
        const double room_lo[3] = {-2, 0, -5}, room_hi[3] = {2, 3, 0};
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(v3_get(lo, k), room_lo[k], 1e-3);
            CHECK_NEAR(v3_get(hi, k), room_hi[k], 1e-3);
        }
        /* 10 cm from the right wall, looking at it: still the room. */
        s->camera.desc.position = v3(1.9f, 0.2f, -0.1f);
        s->camera.desc.target = v3(2.0f, 0.2f, -0.1f);
        CHECK(il_view_interior(s, &lo, &hi));
        printf("window room, a wall close up: interior (%.3f %.3f %.3f) to (%.3f %.3f %.3f)\n", lo.x, lo.y,
               lo.z, hi.x, hi.y, hi.z);
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(v3_get(lo, k), room_lo[k], 1e-3);
            CHECK_NEAR(v3_get(hi, k), room_hi[k], 1e-3);
        }
        /* From the garden the light paths are not split. */
        s->camera.desc.position = v3(0.0f, 1.5f, 12.0f);
        s->camera.desc.target = v3(0.0f, 1.5f, 0.0f);
        CHECK(!il_portal_light_wanted(s));
        il_scene_release(s);
    }
    s = load_committed("cornell");
    if (s) {
        CHECK(il_view_size(s) == v3_length(v3_sub(s->bounds_max, s->bounds_min)));
        il_vec3 lo, hi;
        CHECK(!il_view_interior(s, &lo, &hi));   /* no portals */
        CHECK(lo.x == s->bounds_min.x && lo.z == s->bounds_min.z && hi.y == s->bounds_max.y);
        il_scene_release(s);
    }
    il_scene *sky = new_scene();
    add_quad(sky, v3(0, -1, 0), v3(5, 0, 0), v3(0, 0, -5), 0);
    set_camera(sky, v3(0, 0, 0), v3(0, 1, 0), v3(0, 0, 1), 40.0f);   /* looking up */
    il_environment_desc env = {.radiance = v3s(1.0f)};
    CHECK_OK(il_scene_set_environment(sky, &env, &g_err), &g_err);
    commit(sky);
    CHECK(il_view_size(sky) == v3_length(v3_sub(sky->bounds_max, sky->bounds_min)));
    il_scene_release(sky);
}

/* Linespace at 32 spp and the path tracer at 512 spp (the reference of
 * the tests below), 64 x 48. */
static il_image linespace_image(il_scene *s, il_linespace_desc *ld, il_render_stats *st)
{
    il_render_desc rd = {.method = IL_METHOD_LINESPACE, .linespace = ld, .spp = 32, .seed = 2, .threads = 2};
    return render_desc_image(s, 64, 48, &rd, st);
}

static il_image reference_image(il_scene *s)
{
    il_render_desc pt = {.spp = 512, .seed = 2, .threads = 2};
    return render_desc_image(s, 64, 48, &pt, NULL);
}

/* Photon mapping of scenes/window-room.json, where photons enter the room
 * only by the window (methods/portal_light.c): the portals' light carries
 * what the sky and the ground outside send in, so most photons land in the
 * room (of 10^6 photons, 716 did before, and the room read 9% dark), and
 * every wall, the floor and the ceiling come within 5% of the path tracer.
 * The default radius is 2% of what the camera sees (methods/view_size.h),
 * the room, not of the 80 m ground's diagonal: 11 cm, not 2.3 m.  SPPM
 * lights the room the same way. */
static void test_photon(void)
{
    il_scene *s = load_committed(IL_SOURCE_DIR "/scenes/window-room.json");
    if (!s)
        return;
    CHECK(s->portal_light);
    il_photon_desc pd = {.photons = 300000};
    il_render_desc rd = {.method = IL_METHOD_PHOTON, .photon = &pd, .spp = 32, .seed = 2, .threads = 2};
    il_render_stats st = {0};
    il_image a = render_desc_image(s, 64, 48, &rd, &st);
    il_image b = reference_image(s);
    printf("window room: photon %.5f (%llu global photons of %llu), path tracer %.5f\n", image_mean(&a, 1),
           (unsigned long long)st.photon.stored_global, (unsigned long long)st.photon.emitted,
           image_mean(&b, 1));
    CHECK(st.photon.stored_global > st.photon.emitted / 2);
    CHECK(compare_mesh_means(s, &a, &b, 0.05, 0.0, "photon", "pt") >= 5);
    CHECK_REL(image_mean(&a, 1), image_mean(&b, 1), 0.03);
    il_image_free(&a);

    il_photon_desc sd = {.photons = 50000};
    il_render_desc sp = {.method = IL_METHOD_SPPM, .photon = &sd, .spp = 32, .seed = 2, .threads = 2};
    a = render_desc_image(s, 64, 48, &sp, &st);
    printf("window room: sppm %.5f (%llu photons stored of %llu)\n", image_mean(&a, 1),
           (unsigned long long)st.photon.stored, (unsigned long long)st.photon.emitted);
    CHECK(st.photon.stored > st.photon.emitted / 2);
    CHECK(compare_mesh_means(s, &a, &b, 0.05, 0.0, "sppm", "pt") >= 5);
    CHECK_REL(image_mean(&a, 1), image_mean(&b, 1), 0.03);
    il_image_free(&a);
    il_image_free(&b);
    il_scene_release(s);
}

/* The same room with a lamp hanging in it (a point light of 2 W/sr at
 * 2.4 m, which brightens the room by half).  The light table weighs the
 * sky by what it brings in by the window (scene/lights.c), not by its
 * power over the 80 m ground, so the lamp gets more than half of the light
 * samples and of the lights' photons instead of 1 in 12,000 (whose rare
 * samples, 12,000 times too bright, made every method read the room 9%
 * dark at these samples, the path tracer too).  Photon mapping, SPPM and
 * Linespace come within 2% of the path tracer (measured -0.1%, -0.1% and
 * +0.2%). */
static void test_lamp(void)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(IL_SOURCE_DIR "/scenes/window-room.json", NULL, &s, &g_err), &g_err);
    if (!s)
        return;
    il_light_desc lamp = {.type = IL_LIGHT_POINT, .position = v3(0, 2.4f, -3), .intensity = v3s(2.0f)};
    CHECK_OK(il_scene_add_light(s, &lamp, &g_err), &g_err);
    commit(s);
    uint32_t li = s->lights[0].kind == IL_LIGHTK_POINT ? 0 : s->num_lights - 1;
    printf("window room with a lamp: the lamp's share of the light samples %.3f\n", (double)s->light_pmf[li]);
    CHECK(s->lights[li].kind == IL_LIGHTK_POINT && s->light_pmf[li] > 0.5f);
    il_image ref = reference_image(s);
    il_photon_desc pd = {.photons = 300000};
    il_render_desc rd = {.method = IL_METHOD_PHOTON, .photon = &pd, .spp = 32, .seed = 2, .threads = 2};
    il_image a = render_desc_image(s, 64, 48, &rd, NULL);
    il_photon_desc sd = {.photons = 50000};
    il_render_desc sp = {.method = IL_METHOD_SPPM, .photon = &sd, .spp = 32, .seed = 2, .threads = 2};
    il_image b = render_desc_image(s, 64, 48, &sp, NULL);
    il_linespace_desc ld = {0};
    il_image c = linespace_image(s, &ld, NULL);
    printf("window room with a lamp: photon %.5f, sppm %.5f, linespace %.5f, path tracer %.5f\n",
           image_mean(&a, 1), image_mean(&b, 1), image_mean(&c, 1), image_mean(&ref, 1));
    CHECK_REL(image_mean(&a, 1), image_mean(&ref, 1), 0.02);
    CHECK_REL(image_mean(&b, 1), image_mean(&ref, 1), 0.02);
    CHECK_REL(image_mean(&c, 1), image_mean(&ref, 1), 0.02);
    il_image_free(&a);
    il_image_free(&b);
    il_image_free(&c);
    il_image_free(&ref);
    il_scene_release(s);
}

/* Linespace of scenes/window-room.json: its portals' light is injected
 * (methods/portal_light.c) and the grid lies over the room the camera sees
 * (il_view_interior), so no voxel mixes the daylit outside with the room.
 * Every wall, the floor and the ceiling come within 5% of the path tracer,
 * the image mean within 3% (measured: +0.2%).  Over the whole scene,
 * without the portals' light, its 10 m voxels read the room 18% bright. */
static void test_linespace(void)
{
    il_scene *s = load_committed(IL_SOURCE_DIR "/scenes/window-room.json");
    if (!s)
        return;
    il_linespace_desc ld = {0};
    il_render_stats st = {0};
    il_image a = linespace_image(s, &ld, &st), b = reference_image(s);
    printf("window room: linespace %.5f (grid %ux%ux%u over the interior %d, %llu deposits, %llu "
           "vertices outside), path tracer %.5f\n",
           image_mean(&a, 1), st.linespace.grid[0], st.linespace.grid[1], st.linespace.grid[2],
           (int)st.linespace.interior, (unsigned long long)st.linespace.injected_segments,
           (unsigned long long)st.linespace.outside, image_mean(&b, 1));
    CHECK(st.linespace.interior);
    CHECK_NEAR(st.linespace.grid_max[2], 0.0, 1e-2);
    CHECK(st.linespace.injected_segments > st.linespace.inject_rays / 2);
    CHECK(compare_mesh_means(s, &a, &b, 0.05, 0.0, "linespace", "pt") >= 5);
    CHECK_REL(image_mean(&a, 1), image_mean(&b, 1), 0.03);
    il_image_free(&a);

    /* Without: the whole scene's grid, the lights' paths alone. */
    ld.no_portal_light = true;
    a = linespace_image(s, &ld, &st);
    printf("window room: linespace without the portals' light %.5f (grid %ux%ux%u)\n", image_mean(&a, 1),
           st.linespace.grid[0], st.linespace.grid[1], st.linespace.grid[2]);
    CHECK(!st.linespace.interior && st.linespace.outside == 0);
    CHECK(st.linespace.grid_min[0] < -39.0f && st.linespace.grid_max[2] > 59.0f);
    il_image_free(&a);
    il_image_free(&b);
    il_scene_release(s);
}

/* Linespace of scenes/l-room.json: the window room with an alcove, whose
 * grid over the whole L spans the yard in the crook of the L, so voxels
 * straddle the walls round it.  Only the light inside is injected (the
 * sky's and the sun's paths outside, and the lights' paths once they leave
 * by the window, keep nothing: ls_inject.c); with the outside's light in
 * those voxels the right wall read twice as bright.  The four surfaces
 * the camera sees most of come within 8% of the path tracer (measured:
 * 0.3-3.6% low), the image mean within 4% (measured: 1.9% low). */
static void test_l_room(void)
{
    il_scene *s = load_committed(IL_SOURCE_DIR "/scenes/l-room.json");
    if (!s)
        return;
    il_linespace_desc ld = {0};
    il_render_stats st = {0};
    il_image a = linespace_image(s, &ld, &st), b = reference_image(s);
    printf("L-shaped room: linespace %.5f (grid %ux%ux%u over the interior %d, x up to %.2f), path tracer %.5f\n",
           image_mean(&a, 1), st.linespace.grid[0], st.linespace.grid[1], st.linespace.grid[2],
           (int)st.linespace.interior, st.linespace.grid_max[0], image_mean(&b, 1));
    CHECK(st.linespace.interior);
    CHECK_NEAR(st.linespace.grid_max[0], 5.0, 1e-2);   /* the alcove's end wall: the crook is inside */
    CHECK(compare_mesh_means(s, &a, &b, 0.08, 0.0, "linespace", "pt") >= 4);
    CHECK_REL(image_mean(&a, 1), image_mean(&b, 1), 0.04);
    il_image_free(&a);
    il_image_free(&b);
    il_scene_release(s);
}

int main(void)
{
    test_direct();
    test_interreflected();
    test_path_tracer();
    test_path_tracer_lamp();
    test_radiosity();
    test_hr();
    test_view_size();
    test_photon();
    test_lamp();
    test_linespace();
    test_l_room();
    return check_report();
}
