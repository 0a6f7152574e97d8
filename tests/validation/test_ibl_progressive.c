/* The ibl method's bookkeeping: the film after k batches is exactly the
 * image of k * batch lights (every pixel's sum takes the lights in index
 * order, so batching does not change it), stopping from the progress
 * callback or by the time limit leaves such a film, the same seed gives the
 * same film for 1 and 2 threads (with ray-cast shadows and with shadow
 * maps) and with or without the camera vertices kept between batches, and
 * absurd options are refused. */
#include "test_ibl_common.h"

#define W 32
#define H 32

static il_scene *scene(void)
{
    il_scene *s = new_scene();
    uint32_t phong = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG,
                                                         .diffuse = {0.5f, 0.3f, 0.2f},
                                                         .specular = {0.2f, 0.2f, 0.2f}});
    add_floor(s, 0.0f, 4.0f, 0);
    add_ball(s, v3(0, 0.5f, 0), 0.5f, phong);
    /* An emitter too: its light is sampled per camera sample. */
    uint32_t lamp = add_material(s, (il_material_desc){.emission = {2, 2, 2}});
    add_quad(s, v3(0.8f, 1.5f, 0), v3(0, 0, 0.2f), v3(0.2f, 0, 0), lamp);
    set_camera(s, v3(0, 1.2f, 2.5f), v3(0, 0.4f, 0), v3(0, 1, 0), 50.0f);
    set_sky(s, v3(0.7f, 0.8f, 1.0f));
    commit(s);
    return s;
}

typedef struct snapshot {
    uint32_t at;              /* lights at which to copy the film */
    uint32_t stop_at;         /* return false once this many lights are done (0: never) */
    il_image img;
    uint32_t calls, last_done, total;
    bool increasing;
} snapshot;

static bool on_progress(const il_render_progress *p, void *user)
{
    snapshot *s = user;
    s->increasing &= p->passes_done > s->last_done && p->film != NULL;
    s->last_done = p->passes_done;
    s->total = p->passes_total;
    s->calls++;
    if (p->passes_done == s->at)
        CHECK_OK(il_film_resolve(p->film, &s->img, &g_err), &g_err);
    return !(s->stop_at && p->passes_done >= s->stop_at);
}

static il_image render(const il_scene *s, const il_ibl_desc *d, uint32_t spp, int threads,
                       snapshot *snap, il_render_stats *st)
{
    il_render_desc rd = {.method = IL_METHOD_IBL, .spp = spp, .seed = 4, .threads = threads, .ibl = d,
                         .progress = snap ? on_progress : NULL, .progress_user = snap};
    return render_desc_image(s, W, H, &rd, st);
}

static void test_progressive(il_ibl_shadows shadows, uint32_t spp)
{
    il_scene *s = scene();
    il_ibl_desc d = {.lights = 256, .batch = 32, .shadows = shadows, .shadow_map_size = 128};
    snapshot snap = {.at = 96, .increasing = true};
    il_render_stats st;
    il_image full = render(s, &d, spp, 2, &snap, &st);
    CHECK(st.ibl.lights == 256 && snap.calls == 8 && snap.total == 256 && snap.increasing);
    CHECK(st.spp == spp);

    /* 96 lights in one batch, and in batches of 32: the film after 3 batches. */
    il_ibl_desc d96 = d;
    d96.lights = 96;
    d96.batch = 96;
    il_image one = render(s, &d96, spp, 1, NULL, NULL);
    d96.batch = 32;
    il_image three = render(s, &d96, spp, 2, NULL, NULL);
    CHECK(images_identical(&snap.img, &one));
    CHECK(images_identical(&snap.img, &three));
    CHECK(!images_identical(&snap.img, &full));

    /* Thread count: the same film. */
    il_image full1 = render(s, &d, spp, 1, NULL, NULL);
    CHECK(images_identical(&full, &full1));

    /* Stopped by the callback after 64 lights: the 64-light image. */
    snapshot stop = {.stop_at = 64, .increasing = true};
    il_image stopped = render(s, &d, spp, 2, &stop, &st);
    il_ibl_desc d64 = d;
    d64.lights = 64;
    il_image ref64 = render(s, &d64, spp, 2, NULL, NULL);
    CHECK(st.ibl.lights == 64 && stop.calls == 2);
    CHECK(images_identical(&stopped, &ref64));

    printf("shadows %d, spp %u: snapshot %s, threads %s, stop %s\n", (int)shadows, spp,
           images_identical(&snap.img, &one) ? "equal" : "DIFFERENT",
           images_identical(&full, &full1) ? "equal" : "DIFFERENT",
           images_identical(&stopped, &ref64) ? "equal" : "DIFFERENT");
    il_image_free(&full);
    il_image_free(&full1);
    il_image_free(&one);
    il_image_free(&three);
    il_image_free(&snap.img);
    il_image_free(&stopped);
    il_image_free(&ref64);
    il_scene_release(s);
}

/* Camera vertices traced again for every batch (no cache) give the same
 * film as vertices kept from the first batch. */
static void test_no_cache(void)
{
    il_scene *s = scene();
    il_ibl_desc d = {.lights = 96, .batch = 32};
    il_render_desc rd = {.method = IL_METHOD_IBL, .spp = 2, .seed = 4, .ibl = &d};
    il_image img[2];
    for (int k = 0; k < 2; k++) {
        il_film *film = NULL;
        CHECK_OK(il_film_create(W, H, &film, &g_err), &g_err);
        il_render_stats st;
        CHECK_OK(il_ibl_render_budget(s, film, &rd, k ? 0 : IL_IBL_CACHE_BYTES, &st, &g_err), &g_err);
        CHECK(st.ibl.lights == 96);
        CHECK_OK(il_film_resolve(film, &img[k], &g_err), &g_err);
        il_film_release(film);
    }
    printf("no cache: %s\n", images_identical(&img[0], &img[1]) ? "equal" : "DIFFERENT");
    CHECK(images_identical(&img[0], &img[1]));
    il_image_free(&img[0]);
    il_image_free(&img[1]);
    il_scene_release(s);
}

static void test_time_and_seed(void)
{
    il_scene *s = scene();
    /* A time limit far below one batch: the first batch is still rendered. */
    il_ibl_desc d = {.lights = 1024, .batch = 16};
    il_render_desc rd = {.method = IL_METHOD_IBL, .seed = 4, .ibl = &d, .time_limit = 1e-6};
    il_render_stats st;
    il_image timed = render_desc_image(s, W, H, &rd, &st);
    CHECK(st.ibl.lights == 16);
    il_ibl_desc d16 = {.lights = 16};
    il_image ref = render(s, &d16, 1, 0, NULL, NULL);
    CHECK(images_identical(&timed, &ref));
    /* Another seed, another light set and other camera samples. */
    rd = (il_render_desc){.method = IL_METHOD_IBL, .seed = 5, .ibl = &d16};
    il_image other = render_desc_image(s, W, H, &rd, NULL);
    CHECK(!images_identical(&other, &ref));
    il_image_free(&timed);
    il_image_free(&ref);
    il_image_free(&other);
    il_scene_release(s);
}

static void expect_invalid(const il_scene *s, const il_render_desc *rd, const char *what)
{
    il_film *film = NULL;
    CHECK_OK(il_film_create(8, 8, &film, &g_err), &g_err);
    il_error err = {0};
    il_status st = il_render(s, film, rd, NULL, &err);
    printf("%s: %s\n", what, err.message);
    CHECK(st == IL_ERR_INVALID && err.message[0] != '\0');
    il_film_release(film);
}

static void test_bad_options(void)
{
    il_scene *s = scene();
    il_ibl_desc d = {.pcf_taps = 4};
    il_render_desc rd = {.method = IL_METHOD_IBL, .ibl = &d};
    expect_invalid(s, &rd, "even pcf");
    d = (il_ibl_desc){.shadow_bias = NAN};
    expect_invalid(s, &rd, "NaN bias");
    d = (il_ibl_desc){.shadow_bias = 2.0f};
    expect_invalid(s, &rd, "bias 2");
    d = (il_ibl_desc){.lights = (1u << 24) + 1};
    expect_invalid(s, &rd, "too many lights");
    d = (il_ibl_desc){.selection = (il_ibl_selection)7};
    expect_invalid(s, &rd, "unknown selection");
    d = (il_ibl_desc){.shadows = (il_ibl_shadows)9};
    expect_invalid(s, &rd, "unknown shadows");
    d = (il_ibl_desc){.shadow_map_size = 100000};
    expect_invalid(s, &rd, "huge shadow map");
    d = (il_ibl_desc){0};
    rd.spp = 5000;
    expect_invalid(s, &rd, "spp 5000");
    il_scene_release(s);

    /* A scene without an environment has nothing to turn into lights. */
    s = new_scene();
    add_floor(s, 0.0f, 1.0f, 0);
    il_light_desc pl = {.type = IL_LIGHT_POINT, .position = {0, 1, 0}, .intensity = {1, 1, 1}};
    CHECK_OK(il_scene_add_light(s, &pl, &g_err), &g_err);
    commit(s);
    rd = (il_render_desc){.method = IL_METHOD_IBL};
    expect_invalid(s, &rd, "no environment");
    il_scene_release(s);
}

int main(void)
{
    test_progressive(IL_IBL_SHADOW_RAYS, 1);
    test_progressive(IL_IBL_SHADOW_RAYS, 3);
    test_progressive(IL_IBL_SHADOW_MAPS, 2);
    test_no_cache();
    test_time_and_seed();
    test_bad_options();
    return check_report();
}
