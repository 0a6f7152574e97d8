/* The reflective shadow maps themselves (rsm_build.c, rsm_gather.c)
 * against analytic values:
 *  - a spot over a large floor: the texels' reflected flux sums to
 *    rho * Phi_spot = rho 2 pi I (1 - cos^{n+1} theta_c) / (n + 1), their
 *    footprints to the lit disk's area pi (h tan theta_c)^2;
 *  - a point light (six cube faces) and a wide spot (six faces, the empty
 *    ones dropped) inside a closed box: flux rho 4 pi I and rho Phi_spot,
 *    footprints the box's inner area;
 *  - a directional light (an orthographic map): flux rho E A, area A;
 *  - one texel's light at a receiver: Phi/pi cos cos / (r^2 + A/pi) times
 *    the BSDF, zero facing away, zero behind a blocker with the shadow
 *    test (one shadow ray counted);
 *  - projection into a map, the option ranges;
 *  - the choice of maps per shading point: probabilities half by flux and
 *    half uniform, the draws following them, and the estimate from 3 of
 *    12 maps unbiased (its mean over 4000 draws against the exact sum). */
#include <string.h>

#include "check.h"
#include "methods/rsm/rsm.h"
#include "scene_build.h"
#include "scene/scene.h"

static void sums(const il_rsm *r, double flux[3], double *area)
{
    flux[0] = flux[1] = flux[2] = *area = 0.0;
    for (uint32_t k = 0; k < r->count; k++) {
        const il_rsm_map *m = &r->maps[k];
        for (size_t i = 0; i < (size_t)m->size * m->size; i++) {
            const il_rsm_texel *t = &m->tex[i];
            if (v3_is_zero(t->flux))
                continue;
            flux[0] += t->flux.x;
            flux[1] += t->flux.y;
            flux[2] += t->flux.z;
            *area += t->area;
        }
    }
}

static double spot_power(double I, double angle_deg, double n)
{
    double c = cos(angle_deg * PI_D / 180.0);
    return 2.0 * PI_D * I * (1.0 - pow(c, n + 1.0)) / (n + 1.0);
}

static void test_spot_floor(void)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = {0.5f, 0.25f, 0.8f}});
    add_floor(s, 0.0f, 50.0f, m);
    il_light_desc l = {.type = IL_LIGHT_SPOT, .position = v3(0.3f, 2.0f, -0.2f),
                       .direction = v3(0, -1, 0), .intensity = v3(5, 5, 5),
                       .spot_angle = 30.0f, .spot_exponent = 2.0f};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    il_rsm r;
    CHECK_OK(il_rsm_build(s, 256, 1, &r, &g_err), &g_err);
    CHECK(r.count == 1 && !r.maps[0].ortho);
    double flux[3], area;
    sums(&r, flux, &area);
    double phi = spot_power(5.0, 30.0, 2.0);
    printf("spot: flux %.5f (expected %.5f), area %.5f (expected %.5f)\n", flux[0], 0.5 * phi, area,
           PI_D * 4.0 / 3.0);
    CHECK_REL(flux[0], 0.5 * phi, 0.005);
    CHECK_REL(flux[1], 0.25 * phi, 0.005);
    CHECK_REL(flux[2], 0.8 * phi, 0.005);
    CHECK_REL(area, PI_D * 4.0 / 3.0, 0.01); /* h tan 30 = 2 / sqrt 3 */
    /* The spot's axis meets the map's centre. */
    il_vec2 c = il_rsm_project(&r.maps[0], v3(0.3f, 0.0f, -0.2f));
    CHECK_NEAR(c.x, 0.5, 1e-5);
    CHECK_NEAR(c.y, 0.5, 1e-5);
    /* Behind the light: clamped onto the square. */
    c = il_rsm_project(&r.maps[0], v3(3.0f, 5.0f, 0.0f));
    CHECK(c.x >= 0.0f && c.x <= 1.0f && c.y >= 0.0f && c.y <= 1.0f);
    il_rsm_free(&r);
    il_scene_release(s);
}

static void test_box(il_light_desc l, uint32_t maps, double phi)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = {0.6f, 0.6f, 0.6f}});
    add_cube(s, m, true);
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    il_rsm r;
    CHECK_OK(il_rsm_build(s, 128, 0, &r, &g_err), &g_err);
    double flux[3], area;
    sums(&r, flux, &area);
    printf("box (%u maps): flux %.5f (expected %.5f), area %.4f\n", r.count, flux[0], 0.6 * phi, area);
    CHECK(r.count == maps);
    CHECK_REL(flux[0], 0.6 * phi, 0.005);
    if (l.type == IL_LIGHT_POINT)
        CHECK_REL(area, 24.0, 0.005);
    CHECK(il_rsm_bytes(&r) >= (uint64_t)maps * 128 * 128 * sizeof(il_rsm_texel));
    il_rsm_free(&r);
    il_scene_release(s);
}

static void test_directional(void)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = {0.4f, 0.4f, 0.4f}});
    add_floor(s, 0.0f, 1.0f, m);
    il_light_desc l = {.type = IL_LIGHT_DIRECTIONAL, .direction = v3(0.3f, -1, 0.2f),
                       .intensity = v3(2, 2, 2)};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    il_rsm r;
    CHECK_OK(il_rsm_build(s, 512, 0, &r, &g_err), &g_err);
    CHECK(r.count == 1 && r.maps[0].ortho);
    double flux[3], area;
    sums(&r, flux, &area);
    /* E on a surface facing the light; the floor (area 4) takes E cos. */
    double cosi = 1.0 / sqrt(0.09 + 1.0 + 0.04);
    printf("directional: flux %.5f (expected %.5f), area %.4f (expected 4)\n", flux[0],
           0.4 * 2.0 * 4.0 * cosi, area);
    CHECK_REL(flux[0], 0.4 * 2.0 * 4.0 * cosi, 0.01);
    CHECK_REL(area, 4.0, 0.01);
    il_rsm_free(&r);
    il_scene_release(s);
}

static void test_texel_light(void)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = {0.5f, 0.5f, 0.5f}});
    add_floor(s, 0.0f, 1.0f, m);
    il_light_desc l = {.type = IL_LIGHT_POINT, .position = v3(0, 1, 0), .intensity = v3(1, 1, 1)};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    /* A blocker at y = 2.5 between the texel at y = 3 and the receiver. */
    add_quad(s, v3(4.2f, 2.5f, 0), v3(0.5f, 0, 0), v3(0, 0, 0.5f), m);
    commit(s);
    il_bsdf b = {0};
    il_rsm_receiver r = {.p = v3(0, 0, 0), .n = v3(0, 1, 0), .g = v3(0, 1, 0), .wo = v3(0, 1, 0),
                         .kd = v3s(0.5f * IL_INV_PI), .diffuse = true, .bsdf = &b};
    /* Texel 2 m above, tilted 60 degrees, seen at 30 degrees from the normal. */
    il_vec3 p = v3(1.0f, 1.7320508f, 0.0f); /* 2 m away at 30 degrees */
    il_rsm_texel t = {.p = p, .n = v3(0, -1, 0), .flux = v3(3, 3, 3), .area = 0.01f};
    il_rsm_counts cnt = {0};
    il_vec3 L = il_rsm_texel_light(s, &t, &r, false, &cnt);
    double cos_x = 1.7320508 / 2.0, cos_p = cos_x;
    double E = 3.0 / PI_D * cos_x * cos_p / (4.0 + 0.01 / PI_D);
    CHECK_REL(L.x, 0.5 / PI_D * E, 1e-5);
    CHECK(cnt.gathered == 1 && cnt.shadow_rays == 0);
    /* Facing away: nothing. */
    il_rsm_texel away = t;
    away.n = v3(0, 1, 0);
    CHECK(v3_is_zero(il_rsm_texel_light(s, &away, &r, false, &cnt)));
    /* Below the receiver's surface: nothing. */
    il_rsm_texel below = {.p = v3(1, -1, 0), .n = v3(0, 1, 0), .flux = v3s(3), .area = 0.01f};
    CHECK(v3_is_zero(il_rsm_texel_light(s, &below, &r, false, &cnt)));
    /* The shadow test: a texel above the blocker is hidden, one beside is not. */
    il_rsm_texel hidden = {.p = v3(5, 3, 0), .n = v3(-1, 0, 0), .flux = v3s(3), .area = 0.01f};
    cnt = (il_rsm_counts){0};
    CHECK(!v3_is_zero(il_rsm_texel_light(s, &hidden, &r, false, &cnt)));
    CHECK(v3_is_zero(il_rsm_texel_light(s, &hidden, &r, true, &cnt)));
    CHECK(cnt.shadow_rays == 1);
    CHECK(!v3_is_zero(il_rsm_texel_light(s, &t, &r, true, &cnt)));
    CHECK(cnt.shadow_rays == 2);
    il_scene_release(s);
}

static void test_settings(void)
{
    il_rsm_settings st;
    CHECK_OK(il_rsm_settings_resolve(NULL, NULL, &st, &g_err), &g_err);
    CHECK(st.resolution == 512 && st.samples == 400 && st.radius == 1.5f && !st.shadow_test &&
          !st.all_texels && st.max_depth == 8);
    CHECK(st.maps == IL_RSM_DEFAULT_MAPS);
    il_rsm_desc all = {.all_maps = true, .maps = 3};
    CHECK_OK(il_rsm_settings_resolve(&all, NULL, &st, &g_err), &g_err);
    CHECK(st.maps == 0);
    il_rsm_desc bad[] = {{.resolution = 5000}, {.samples = 70000}, {.radius = -1.0f},
                         {.radius = 2.5f}, {.radius = NAN}, {.maps = 5000}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK(il_rsm_settings_resolve(&bad[i], NULL, &st, &g_err) == IL_ERR_INVALID);
    /* And through il_render. */
    il_scene *s = new_scene();
    add_floor(s, 0.0f, 1.0f, 0);
    il_light_desc l = {.type = IL_LIGHT_SPOT, .position = v3(0, 1, 0), .intensity = v3s(1)};
    CHECK_OK(il_scene_add_light(s, &l, &g_err), &g_err);
    commit(s);
    il_film *film = NULL;
    CHECK_OK(il_film_create(8, 8, &film, &g_err), &g_err);
    il_render_desc rd = {.method = IL_METHOD_RSM, .rsm = &bad[0]};
    CHECK(il_render(s, film, &rd, NULL, &g_err) == IL_ERR_INVALID);
    CHECK(strstr(g_err.message, "rsm: resolution") != NULL);
    rd.rsm = NULL;
    il_render_stats rs;
    CHECK_OK(il_render(s, film, &rd, &rs, &g_err), &g_err);
    CHECK(rs.rsm.maps == 1 && rs.rsm.resolution == 512 && rs.rsm.texels > 0 && rs.spp == 16);
    CHECK(rs.rsm.maps_per_point == 1);
    il_film_release(film);
    il_scene_release(s);
}

static void test_map_choice(void)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = {0.6f, 0.6f, 0.6f}});
    add_cube(s, m, true);
    il_light_desc a = {.type = IL_LIGHT_POINT, .position = v3(-0.5f, 0.5f, 0.2f),
                       .intensity = v3(2, 2, 2)};
    il_light_desc b = {.type = IL_LIGHT_POINT, .position = v3(0.6f, -0.3f, -0.4f),
                       .intensity = v3(0.2f, 0.2f, 0.2f)};
    CHECK_OK(il_scene_add_light(s, &a, &g_err), &g_err);
    CHECK_OK(il_scene_add_light(s, &b, &g_err), &g_err);
    commit(s);
    il_rsm r;
    CHECK_OK(il_rsm_build(s, 32, 1, &r, &g_err), &g_err);
    CHECK(r.count == 12);
    CHECK_OK(il_rsm_choice_init(&r, &g_err), &g_err);
    if (r.count != 12 || r.choice.n != 12) {
        il_rsm_free(&r);
        il_scene_release(s);
        return;
    }
    /* pick[k] = 1/2 flux_k / total + 1/2 / 12. */
    double flux[12], total = 0.0;
    for (uint32_t k = 0; k < 12; k++) {
        flux[k] = 0.0;
        for (size_t t = 0; t < 32 * 32; t++)
            flux[k] += il_luminance(r.maps[k].tex[t].flux);
        total += flux[k];
    }
    double sum = 0.0;
    for (uint32_t k = 0; k < 12; k++) {
        double pmf = il_distrib1d_pmf(&r.choice, k);
        CHECK_REL(pmf, 0.5 * flux[k] / total + 0.5 / 12.0, 1e-6); /* float tables */
        sum += pmf;
    }
    CHECK_NEAR(sum, 1.0, 1e-6);
    CHECK(r.choice.cdf[12] == 1.0f);
    /* Draws over an even grid of u hit each map pick[k] of the time. */
    uint32_t hits[12] = {0};
    const uint32_t grid = 100000;
    for (uint32_t i = 0; i < grid; i++)
        hits[il_distrib1d_sample_discrete(&r.choice, (float)((i + 0.5) / grid), NULL, NULL)]++;
    for (uint32_t k = 0; k < 12; k++)
        CHECK_NEAR((double)hits[k] / grid, il_distrib1d_pmf(&r.choice, k), 2.0 / grid);
    CHECK(il_distrib1d_sample_discrete(&r.choice, 0.0f, NULL, NULL) == 0 &&
          il_distrib1d_sample_discrete(&r.choice, 0.99999994f, NULL, NULL) == 11);

    /* A receiver on the floor: every texel of every map is the exact sum;
     * 3 maps drawn per estimate average to it. */
    il_bsdf bsdf = {0};
    il_rsm_receiver rc = {.p = v3(0.2f, -1.0f, 0.1f), .n = v3(0, 1, 0), .g = v3(0, 1, 0),
                          .wo = v3(0, 1, 0), .kd = v3s(0.6f * IL_INV_PI), .diffuse = true,
                          .bsdf = &bsdf};
    il_rsm_counts cnt = {0};
    il_sampler smp;
    il_sampler_start(&smp, IL_SAMPLER_PCG, 1, 0, 0);
    il_vec3 exact = il_rsm_gather(s, &r, NULL, &rc, false, 0, &smp, &cnt);
    il_vec3 same = il_rsm_gather(s, &r, NULL, &rc, false, 12, &smp, &cnt);
    CHECK(exact.y > 0.0f && same.y == exact.y); /* as many as there are: all of them */
    const int n = 4000;
    double mean = 0.0, sq = 0.0;
    for (int i = 0; i < n; i++) {
        il_sampler_start(&smp, IL_SAMPLER_PCG, 7, 0, (uint32_t)i);
        double v = il_rsm_gather(s, &r, NULL, &rc, false, 3, &smp, &cnt).y;
        mean += v;
        sq += v * v;
    }
    mean /= n;
    double se = sqrt(fmax(sq / n - mean * mean, 0.0) / n);
    printf("map choice: 3 of 12 maps, mean %.6f +- %.6f, exact %.6f\n", mean, se, (double)exact.y);
    CHECK(fabs(mean - exact.y) < 4.0 * se + 1e-6 * exact.y);
    CHECK(se < 0.02 * exact.y);
    il_rsm_free(&r);
    il_scene_release(s);
}

int main(void)
{
    test_spot_floor();
    test_box((il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0.1f, 0.2f, -0.3f),
                             .intensity = v3(2, 2, 2)},
             6, 4.0 * PI_D * 2.0);
    /* 75 degrees, pointing down: the +y face gets nothing and is dropped. */
    test_box((il_light_desc){.type = IL_LIGHT_SPOT, .position = v3(0.1f, 0.2f, -0.3f),
                             .direction = v3(0, -1, 0), .intensity = v3(2, 2, 2),
                             .spot_angle = 75.0f, .spot_exponent = 1.0f},
             5, spot_power(2.0, 75.0, 1.0));
    test_directional();
    test_texel_light();
    test_settings();
    test_map_choice();
    return check_report();
}
