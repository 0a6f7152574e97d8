/* il_rad_settings_resolve: defaults, and every bad value an IL_ERR_INVALID
 * whose message names the option; the same errors through il_render and
 * il_bake; il_bake refuses methods that cannot bake; what IL_FF_AUTO
 * chooses. */
#include "rad_scenes.h"

static il_scene *room(void)
{
    il_scene *s = coloured_room();
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

static void test_defaults(const il_scene *s)
{
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .seed = 42};
    il_rad_settings set;
    CHECK_OK(il_rad_settings_resolve(s, &rd, &set, &g_err), &g_err);
    /* Diffuse area of the room: 6 walls of 1 m^2 and the lamp 0.09 m^2. */
    CHECK_REL(set.patch_size, sqrt(6.09 / 4000.0), 1e-4);
    CHECK(set.subdivisions == 0);
    CHECK(set.form_factors == IL_FF_AUTO); /* resolved per mesh, below */
    CHECK(set.hemicube_resolution == 256);
    CHECK(set.ray_samples == 4096);
    CHECK(set.solver == IL_SOLVER_SHOOTING);
    CHECK_NEAR(set.tolerance, 0.01, 1e-7);
    CHECK(set.max_steps == 0);
    CHECK(set.ff_cache_bytes == (size_t)1024 << 20);
    CHECK(set.adaptive_threshold == 0.0f);
    CHECK(set.on_step == NULL);
    CHECK(set.seed == 42);
    CHECK(set.threads >= 1);

    il_radiosity_desc rad = {.patch_size = 0.1f, .subdivisions = 3, .form_factors = IL_FF_RAYCAST,
                             .hemicube_resolution = 64, .ray_samples = 100,
                             .solver = IL_SOLVER_GAUSS_SEIDEL, .tolerance = 0.5f, .max_steps = 9,
                             .ff_cache_mb = 3, .adaptive_threshold = 0.25f};
    rd.radiosity = &rad;
    rd.threads = 3;
    CHECK_OK(il_rad_settings_resolve(s, &rd, &set, &g_err), &g_err);
    CHECK(set.patch_size == 0.1f && set.subdivisions == 3 && set.form_factors == IL_FF_RAYCAST);
    CHECK(set.hemicube_resolution == 64 && set.ray_samples == 100);
    CHECK(set.solver == IL_SOLVER_GAUSS_SEIDEL && set.tolerance == 0.5f && set.max_steps == 9);
    CHECK(set.ff_cache_bytes == (size_t)3 << 20 && set.adaptive_threshold == 0.25f);
    CHECK(set.threads == 3);
}

typedef struct bad_case {
    const char *option;
    il_radiosity_desc rad;
    int threads;
} bad_case;

static void test_bad_values(il_scene *s)
{
    const bad_case cases[] = {
        {"patch_size", {.patch_size = -1.0f}, 0},
        {"patch_size", {.patch_size = NAN}, 0},
        {"patch_size", {.patch_size = INFINITY}, 0},
        {"subdivisions", {.subdivisions = 11}, 0},
        {"subdivisions", {.subdivisions = UINT32_MAX}, 0},
        {"hemicube_resolution", {.hemicube_resolution = 7}, 0},
        {"hemicube_resolution", {.hemicube_resolution = 4097}, 0},
        {"ray_samples", {.ray_samples = (1u << 24) + 1}, 0},
        {"tolerance", {.tolerance = -0.1f}, 0},
        {"tolerance", {.tolerance = 1.5f}, 0},
        {"tolerance", {.tolerance = NAN}, 0},
        {"ff_cache_mb", {.ff_cache_mb = (1u << 20) + 1}, 0},
        {"adaptive_threshold", {.adaptive_threshold = -0.5f}, 0},
        {"adaptive_threshold", {.adaptive_threshold = NAN}, 0},
        {"form_factors", {.form_factors = (il_form_factor_method)7}, 0},
        {"solver", {.solver = (il_radiosity_solver)9}, 0},
        {"threads", {.patch_size = 0.0f}, -2},
    };
    il_film *film = NULL;
    CHECK_OK(il_film_create(8, 8, &film, &g_err), &g_err);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .radiosity = &cases[k].rad,
                             .threads = cases[k].threads};
        il_rad_settings set;
        il_error e = {0};
        il_status st = il_rad_settings_resolve(s, &rd, &set, &e);
        CHECK(st == IL_ERR_INVALID);
        if (!strstr(e.message, cases[k].option))
            fprintf(stderr, "case %zu: message \"%s\" does not name %s\n", k, e.message,
                    cases[k].option);
        CHECK(strstr(e.message, cases[k].option) != NULL);
        /* The same through the public entry points. */
        il_error e2 = {0};
        CHECK(il_render(s, film, &rd, NULL, &e2) == IL_ERR_INVALID);
        CHECK(strlen(e2.message) > 0);
        il_bake_result *bake = (il_bake_result *)&e2; /* must be reset to NULL */
        il_error e3 = {0};
        CHECK(il_bake(s, &rd, &bake, &e3) == IL_ERR_INVALID);
        CHECK(bake == NULL);
        CHECK(strstr(e3.message, cases[k].option) != NULL);
    }
    il_film_release(film);

    /* Bake: a method that cannot bake, an unknown one, no options. */
    il_bake_result *bake = NULL;
    il_error e = {0};
    il_render_desc pt = {.method = IL_METHOD_PT};
    CHECK(il_bake(s, &pt, &bake, &e) == IL_ERR_INVALID);
    CHECK(strstr(e.message, "method pt cannot bake") != NULL);
    il_render_desc unknown = {.method = (il_method)17};
    CHECK(il_bake(s, &unknown, &bake, &e) == IL_ERR_INVALID);
    CHECK(strstr(e.message, "unknown method") != NULL);
    CHECK(il_bake(s, NULL, &bake, &e) == IL_ERR_INVALID);
    CHECK(bake == NULL);
    il_film *f2 = NULL;
    CHECK_OK(il_film_create(4, 4, &f2, &g_err), &g_err);
    CHECK(il_render(s, f2, &unknown, NULL, &e) == IL_ERR_INVALID);
    il_film_release(f2);
}

/* One shot of a solve, for the back-end it reports. */
static il_radiosity_stats one_step(const il_scene *s, uint32_t subdivisions,
                                   il_form_factor_method method, uint32_t hemicube_resolution)
{
    il_radiosity_desc rad = {.subdivisions = subdivisions, .form_factors = method,
                             .hemicube_resolution = hemicube_resolution, .ray_samples = 64,
                             .max_steps = 1};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .spp = 1, .radiosity = &rad};
    il_film *film = NULL;
    CHECK_OK(il_film_create(8, 8, &film, &g_err), &g_err);
    il_render_stats st;
    CHECK_OK(il_render(s, film, &rd, &st, &g_err), &g_err);
    il_film_release(film);
    return st.radiosity;
}

/* IL_FF_AUTO: the hemicube up to 3N^2/4 patches (4 of its 3N^2 pixels a
 * patch), ray-cast above; an explicit choice is kept whatever the size. */
static void test_auto_form_factors(const il_scene *s)
{
    CHECK(il_ff_auto_method(IL_FF_AUTO, 0, 0) == IL_FF_HEMICUBE);
    CHECK(il_ff_auto_method(IL_FF_AUTO, 49152, 0) == IL_FF_HEMICUBE);
    CHECK(il_ff_auto_method(IL_FF_AUTO, 49153, 0) == IL_FF_RAYCAST);
    CHECK(il_ff_auto_method(IL_FF_AUTO, 49152, 256) == IL_FF_HEMICUBE);
    CHECK(il_ff_auto_method(IL_FF_AUTO, 768, 32) == IL_FF_HEMICUBE);
    CHECK(il_ff_auto_method(IL_FF_AUTO, 769, 32) == IL_FF_RAYCAST);
    CHECK(il_ff_auto_method(IL_FF_AUTO, 12582912, 4096) == IL_FF_HEMICUBE);
    CHECK(il_ff_auto_method(IL_FF_AUTO, UINT32_MAX, 4096) == IL_FF_RAYCAST);
    CHECK(il_ff_auto_method(IL_FF_HEMICUBE, UINT32_MAX, 8) == IL_FF_HEMICUBE);
    CHECK(il_ff_auto_method(IL_FF_RAYCAST, 1, 0) == IL_FF_RAYCAST);

    /* The room's 7 quads at 4 levels: 1,792 patches, more than the 1,728 of
     * a 48-pixel hemicube and fewer than the 1,800 of a 49-pixel one. */
    il_radiosity_stats a = one_step(s, 4, IL_FF_AUTO, 48);
    CHECK(a.num_patches == 7 * 256 && a.form_factors == IL_FF_RAYCAST);
    il_radiosity_stats b = one_step(s, 4, IL_FF_AUTO, 49);
    CHECK(b.num_patches == 7 * 256 && b.form_factors == IL_FF_HEMICUBE);
    CHECK(one_step(s, 4, IL_FF_HEMICUBE, 8).form_factors == IL_FF_HEMICUBE);
    CHECK(one_step(s, 1, IL_FF_RAYCAST, 0).form_factors == IL_FF_RAYCAST);
}

/* A scene that is all mirror has no diffuse surface: a clear error. */
static void test_no_diffuse(void)
{
    il_scene *s = new_scene();
    il_material_desc mirror = {.type = IL_MATERIAL_MIRROR};
    uint32_t m = add_material(s, mirror);
    add_floor(s, 0.0f, 1.0f, m);
    il_light_desc l = {.type = IL_LIGHT_POINT, .position = v3(0, 1, 0), .intensity = v3s(1)};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY};
    il_bake_result *bake = NULL;
    il_error e = {0};
    CHECK(il_bake(s, &rd, &bake, &e) == IL_ERR_INVALID);
    CHECK(bake == NULL);
    CHECK(strlen(e.message) > 0);
    il_scene_release(s);
}

int main(void)
{
    il_scene *s = room();
    test_defaults(s);
    test_bad_values(s);
    test_auto_form_factors(s);
    il_scene_release(s);
    test_no_diffuse();
    return check_report();
}
