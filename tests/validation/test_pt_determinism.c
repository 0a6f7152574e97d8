/* Determinism (the same seed gives a bit-identical film with 1 or 2 threads,
 * another seed a different one), progressive rendering (progress callback,
 * early stop, time limit) and the checking of render options. */
#include "pt_scenes.h"

enum { W = 40, H = 24 }; /* not a multiple of the 16-pixel tiles */

/* Every kind of light and material at once. */
static il_scene *mixed_scene(bool commit)
{
    il_scene *s = new_scene();
    uint32_t phong = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG, .diffuse = v3(0.3f, 0.3f, 0.2f),
                                                         .specular = v3s(0.4f), .exponent = 50.0f});
    uint32_t red = add_material(s, (il_material_desc){.diffuse = v3(0.6f, 0.1f, 0.1f)});
    uint32_t mirror = add_material(s, (il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = v3(0.9f, 0.9f, 0.7f)});
    uint32_t glass = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3(5, 5, 4)});
    add_floor(s, 0.0f, 2.0f, phong);
    add_quad(s, v3(-2, 1, 0), v3(0, 1, 0), v3(0, 0, 2), red);            /* left wall, faces +x */
    add_quad(s, v3(0, 1, -2), v3(1, 0, 0), v3(0, 1, 0), mirror);         /* back mirror, faces +z */
    add_quad(s, v3(0.5f, 0.5f, 0), v3(0.3f, 0, 0), v3(0, 0.3f, 0), glass); /* a glass pane */
    add_quad(s, v3(0, 1.9f, 0), v3(0.3f, 0, 0), v3(0, 0, 0.3f), lamp);  /* faces down */
    il_light_desc pl = {.type = IL_LIGHT_POINT, .position = {1, 1, 1}, .intensity = {0.5f, 0.5f, 0.5f}};
    il_light_desc sl = {.type = IL_LIGHT_SPOT, .position = {-1, 1.5f, 0}, .intensity = {2, 1, 1},
                        .spot_angle = 25, .spot_exponent = 2};
    il_light_desc dl = {.type = IL_LIGHT_DIRECTIONAL, .direction = {0.3f, -1, -0.2f}, .intensity = {0.3f, 0.3f, 0.3f}};
    CHECK_OK(il_scene_add_light(s, &pl, &g_err), &g_err);
    CHECK_OK(il_scene_add_light(s, &sl, &g_err), &g_err);
    CHECK_OK(il_scene_add_light(s, &dl, &g_err), &g_err);
    il_environment_desc env = {.radiance = v3(0.1f, 0.1f, 0.15f)};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    set_camera(s, v3(0.3f, 1.2f, 3.5f), v3(0, 0.7f, 0), v3(0, 1, 0), 55.0f);
    if (commit)
        CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

static il_image render_public(const il_scene *s, const il_render_desc *rd, il_render_stats *stats)
{
    il_image img = {0};
    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &g_err), &g_err);
    CHECK_OK(il_render(s, film, rd, stats, &g_err), &g_err);
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    il_film_release(film);
    return img;
}

static void check_threads(const il_scene *s, il_sampler_type sampler, il_filter_type filter)
{
    il_render_desc rd = {.spp = 8, .seed = 77, .threads = 1, .sampler = sampler, .filter = filter};
    il_render_stats st1, st2, st3;
    il_image a = render_public(s, &rd, &st1);
    rd.threads = 2;
    il_image b = render_public(s, &rd, &st2);
    rd.seed = 78;
    il_image c = render_public(s, &rd, &st3);
    CHECK(images_identical(&a, &b));
    CHECK(!images_identical(&a, &c));
    CHECK(st1.rays == st2.rays && st1.rays > (uint64_t)W * H * 8);
    CHECK(st1.spp == 8 && st2.spp == 8);
    CHECK(image_finite(&a) && st1.nonfinite_samples == 0);
    CHECK(image_mean(&a, 0) > 0.0);
    il_image_free(&a);
    il_image_free(&b);
    il_image_free(&c);
}

typedef struct progress_log {
    uint32_t calls, stop_after, last_done;
    bool film_ok, increasing;
} progress_log;

static bool on_progress(const il_render_progress *p, void *user)
{
    progress_log *log = user;
    log->calls++;
    log->increasing &= p->passes_done > log->last_done;
    log->last_done = p->passes_done;
    log->film_ok &= p->film != NULL && il_film_width(p->film) == W;
    return log->calls < log->stop_after;
}

static void expect_invalid(const il_scene *s, il_render_desc rd, const char *word)
{
    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &g_err), &g_err);
    il_error err = {0};
    il_render_stats st;
    CHECK(il_render(s, film, &rd, &st, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, word) != NULL);
    if (!strstr(err.message, word))
        fprintf(stderr, "message '%s' does not name '%s'\n", err.message, word);
    il_film_release(film);
}

int main(void)
{
    il_scene *s = mixed_scene(true);
    check_threads(s, IL_SAMPLER_SOBOL, IL_FILTER_BOX);
    check_threads(s, IL_SAMPLER_PCG, IL_FILTER_GAUSSIAN);

    /* Progress: called after every pass with a complete film; returning
     * false stops early with IL_OK and the samples done so far. */
    {
        progress_log log = {.stop_after = 2, .film_ok = true, .increasing = true};
        il_render_desc rd = {.spp = 1000, .seed = 1, .progress = on_progress, .progress_user = &log};
        il_render_stats st;
        il_image img = render_public(s, &rd, &st);
        CHECK(log.calls == 2 && log.increasing && log.film_ok);
        CHECK(st.spp == log.last_done && st.spp > 0 && st.spp < 1000);
        CHECK(image_mean(&img, 1) > 0.0);
        il_image_free(&img);
        /* Run to the end: passes_done reaches spp exactly. */
        log = (progress_log){.stop_after = 1000000, .film_ok = true, .increasing = true};
        rd.spp = 100;
        img = render_public(s, &rd, &st);
        CHECK(log.last_done == 100 && st.spp == 100 && log.increasing);
        il_image_free(&img);
    }
    /* A time limit always renders at least one pass. */
    {
        il_render_desc rd = {.time_limit = 1e-9, .seed = 1};
        il_render_stats st;
        il_image img = render_public(s, &rd, &st);
        CHECK(st.spp >= 1 && st.spp < 1000000);
        il_image_free(&img);
    }
    /* The default spp is 16. */
    {
        il_render_desc rd = {0};
        il_render_stats st;
        il_image img = render_public(s, &rd, &st);
        CHECK(st.spp == 16);
        il_image_free(&img);
    }

    /* Absurd options: IL_ERR_INVALID and a message naming the option. */
    expect_invalid(s, (il_render_desc){.spp = 0xffffffffu}, "spp");
    expect_invalid(s, (il_render_desc){.max_depth = 100000}, "max depth");
    expect_invalid(s, (il_render_desc){.threads = -1}, "threads");
    expect_invalid(s, (il_render_desc){.time_limit = -1.0}, "time limit");
    expect_invalid(s, (il_render_desc){.time_limit = NAN}, "time limit");
    expect_invalid(s, (il_render_desc){.sampler = (il_sampler_type)7}, "sampler");
    expect_invalid(s, (il_render_desc){.filter = (il_filter_type)9}, "filter");
    expect_invalid(s, (il_render_desc){.method = (il_method)42}, "method");
    il_scene *raw = mixed_scene(false);
    expect_invalid(raw, (il_render_desc){0}, "not committed");
    il_scene_release(raw);
    {
        il_film *film = NULL;
        CHECK_OK(il_film_create(W, H, &film, &g_err), &g_err);
        il_error err = {0};
        CHECK(il_render(s, film, NULL, NULL, &err) == IL_ERR_INVALID);
        CHECK(il_render(NULL, film, &(il_render_desc){0}, NULL, &err) == IL_ERR_INVALID);
        il_film_release(film);
    }

    il_scene_release(s);
    return check_report();
}
