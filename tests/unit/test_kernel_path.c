/* The shared path-tracing kernel (src/kernel/kernel_path.h, compiled here by
 * gcc exactly as nvcc compiles it for the GPU megakernel, the scene packed
 * by il_kscene_build_pt) against the CPU path tracer (il_render, method pt)
 * on the Cornell box, on the Cornell box with the Stanford dragon (47,794
 * triangles: the kernel's own BVH against Embree), on a small scene with
 * Phong, mirror and glass surfaces and vertex normals lit by a point light,
 * a spot light, the sun and a uniform sky or an emissive panel, and on the
 * 248k-triangle atrium: the same image within noise, over the whole image
 * and over 8x8-pixel blocks; on the scenes lit by an environment map the
 * kernel's noise is bounded too (its importance sampling at work); and the
 * scenes the kernels cannot render yet are refused with IL_ERR_INVALID. */
#include <stdlib.h>
#include <string.h>
#include "scene_build.h"
#include "kernel/kernel_scene.h"
#include "scene/scene.h"

#define B 8

#define DRAGON IL_SOURCE_DIR "/bench/scenes/cornell-dragon.json"

/* A comparison's image size, samples per pixel and bounces. */
typedef struct setup {
    uint32_t w, h, spp, max_depth;
    double tol_mean;       /* relative, per channel, on the image means */
    /* When > 0, a bound on the kernel's noise (compare_scene): on the two
     * map-lit scenes the map's importance sampling with MIS gives 0.95 and
     * 1.02 where BSDF sampling alone gave 2.7 and 2.3 (2026-11-28). */
    double max_noise;
} setup;

/* Renders the committed scene s with the kernel on the CPU (packed by
 * il_kscene_build_pt) and with il_render's path tracer, and compares. */
static void compare_scene(il_scene *s, const char *label, setup q)
{
    il_error err = {0};
    const uint32_t W = q.w, H = q.h, SPP = q.spp, NBX = W / B, NBY = H / B;
    il_kscene ks;
    il_status built = il_kscene_build_pt(s, W, H, q.max_depth, 5, &ks, &err);
    CHECK_OK(built, &err);
    if (built != IL_OK)
        return;
    /* Per pixel: the mean of each channel; per 8x8 block: the mean and
     * variance of the samples' channel sum, for a z-test. */
    float *k = calloc(3 * (size_t)W * H, sizeof *k);
    double *bsum = calloc((size_t)NBX * NBY, sizeof *bsum), *bsq = calloc((size_t)NBX * NBY, sizeof *bsq);
    uint64_t odd_counts = 0; /* samples whose ray count is out of bounds */
    double pixel_var = 0.0;  /* the samples' variance within each pixel, summed over pixels */
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double acc[3] = {0, 0, 0}, psum = 0.0, psq = 0.0;
            uint32_t bi = (y / B) * NBX + x / B;
            for (uint32_t i = 0; i < SPP; i++) {
                uint32_t r = 0;
                ilk_vec3 L = ilk_path_sample(&ks.view, x, y, i, &r);
                /* The camera ray, and at most a shadow ray and a next ray
                 * per bounce. */
                odd_counts += r < 1 || r > 2 * q.max_depth + 1;
                acc[0] += L.x; acc[1] += L.y; acc[2] += L.z;
                double v = (double)L.x + L.y + L.z;
                bsum[bi] += v;
                bsq[bi] += v * v;
                psum += v;
                psq += v * v;
            }
            pixel_var += fmax(psq / SPP - (psum / SPP) * (psum / SPP), 0.0);
            for (int c = 0; c < 3; c++)
                k[3 * (y * W + x) + c] = (float)(acc[c] / SPP);
        }
    CHECK(odd_counts == 0);

    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &err), &err);
    il_render_desc rd = {.method = IL_METHOD_PT, .spp = SPP, .max_depth = q.max_depth, .seed = 9};
    CHECK_OK(il_render(s, film, &rd, NULL, &err), &err);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    if (!img.rgb) {
        free(k);
        free(bsum);
        free(bsq);
        il_film_release(film);
        il_kscene_free(&ks);
        return;
    }

    /* Whole image, per channel, and per block: the difference in units of
     * the kernel's standard error, times sqrt(2) for the CPU image's own
     * noise (the Sobol sampler's is lower, so this is conservative). */
    double mk[3] = {0, 0, 0}, mc[3] = {0, 0, 0}, worst_z = 0, all_sum = 0, all_sq = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 0; c < 3; c++) {
            mk[c] += k[3 * i + c] / (W * H);
            mc[c] += img.rgb[3 * i + c] / (W * H);
        }
    const double nb = (double)B * B * SPP;
    for (uint32_t by = 0; by < NBY; by++)
        for (uint32_t bx = 0; bx < NBX; bx++) {
            double cpu = 0;
            for (uint32_t y = by * B; y < (by + 1) * B; y++)
                for (uint32_t x = bx * B; x < (bx + 1) * B; x++)
                    for (int c = 0; c < 3; c++)
                        cpu += img.rgb[3 * (y * W + x) + c];
            cpu /= B * B;
            double bs = bsum[by * NBX + bx], bq = bsq[by * NBX + bx];
            double mean = bs / nb, var = fmax(bq / nb - mean * mean, 0.0);
            double se = sqrt(2.0 * var / nb) + 1e-6;
            double z = fabs(mean - cpu) / se;
            if (z > worst_z)
                worst_z = z;
            all_sum += bs;
            all_sq += bq;
        }
    double n_all = nb * NBX * NBY, m_all = all_sum / n_all;
    double se_all = sqrt(2.0 * fmax(all_sq / n_all - m_all * m_all, 0.0) / n_all);
    double z_all = fabs(m_all - (mc[0] + mc[1] + mc[2])) / se_all;
    /* The noise: one sample's RMS deviation from its pixel's mean,
     * relative to the image's mean (of the channel sum). */
    double noise = sqrt(pixel_var / ((double)W * H)) / m_all;
    printf("%s, %ux%u, %u spp, max depth %u: mean kernel (%.5f %.5f %.5f) cpu pt (%.5f %.5f %.5f): z %.2f "
           "(se %.2g%%); worst of %u 8x8 blocks z %.2f; noise %.3f\n", label, W, H, SPP, q.max_depth, mk[0], mk[1],
           mk[2], mc[0], mc[1], mc[2], z_all, 100.0 * se_all / m_all, NBX * NBY, worst_z, noise);
    if (q.max_noise > 0.0)
        CHECK(noise < q.max_noise);
    for (int c = 0; c < 3; c++) {
        CHECK(mc[c] > 0.01);
        CHECK_REL(mk[c], mc[c], q.tol_mean);
    }
    CHECK(z_all < 4.0);
    CHECK(worst_z < 4.5);
    il_image_free(&img);
    il_film_release(film);
    free(k);
    free(bsum);
    free(bsq);
    il_kscene_free(&ks);
}

static void compare(const char *scene, setup q)
{
    il_scene *s = load_committed(scene);
    if (!s)
        return;
    compare_scene(s, strstr(scene, "dragon") ? "dragon" : scene, q);
    il_scene_release(s);
}

/* The lights of the small open scene below. */
typedef enum test_light {
    POINT_LIGHT, SPOT_LIGHT, SUN_AND_SKY, GLASS_AND_MIRROR, TEXTURED, LATLONG_MAP, ANGULAR_MAP, WIDE_PANEL
} test_light;

/* A small open scene: a glossy Phong floor, a diffuse back wall and a
 * smooth-shaded (vertex normals) Phong sphere, lit by one kind of light;
 * GLASS_AND_MIRROR makes the sphere glass and the wall a mirror, lit by the
 * sun, the sky and an emissive panel (caustics and emitters seen through
 * delta surfaces); TEXTURED puts a checker texture on the floor (Phong)
 * and on the wall (diffuse), lit by a point light; LATLONG_MAP and
 * ANGULAR_MAP light it by an environment map alone (a bright patch in a
 * blue-to-brown gradient, turned 40 degrees about +y); WIDE_PANEL lights
 * it by a 4 x 3 m emissive panel 1.2 m above a sharp Phong floor (exponent
 * 300), where light sampling alone is poor and BSDF sampling finds the
 * panel's reflection (MIS). */
static il_scene *small_scene(test_light kind)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    if (!s)
        return NULL;
    uint32_t floor_m, wall_m, ball_m, checker = 0;
    if (kind == TEXTURED) {
        /* 8x8 texels in squares of 2: a bright warm and a dark cool colour. */
        float tx[8 * 8 * 3];
        for (int i = 0; i < 64; i++)
            for (int c = 0; c < 3; c++)
                tx[3 * i + c] = ((i % 8) / 2 + (i / 8) / 2) % 2 ? 0.9f - 0.2f * c : 0.1f + 0.15f * c;
        CHECK_OK(il_scene_add_texture(s, 8, 8, tx, &checker, &err), &err);
    }
    /* Textured, its kd + ks exceeds 1 where the checker is bright: scaled
     * down per hit (il_bsdf_init, ilk_material_at). */
    il_material_desc floor = {.name = "floor", .type = IL_MATERIAL_PHONG, .diffuse = {0.5f, 0.45f, 0.4f},
                              .specular = {0.3f, 0.3f, 0.3f}, .exponent = 20.0f, .diffuse_texture = checker};
    if (kind == WIDE_PANEL) {
        floor.specular = (il_vec3){0.5f, 0.5f, 0.5f};
        floor.exponent = 300.0f;
    }
    if (kind == TEXTURED)
        floor.diffuse = (il_vec3){1.0f, 0.9f, 0.8f};
    CHECK_OK(il_scene_add_material(s, &floor, &floor_m, &err), &err);
    il_material_desc wall = {.name = "wall", .diffuse = {0.3f, 0.6f, 0.3f}, .diffuse_texture = checker};
    il_material_desc ball = {.name = "ball", .type = IL_MATERIAL_PHONG, .diffuse = {0.2f, 0.1f, 0.05f},
                             .specular = {0.6f, 0.45f, 0.2f}, .exponent = 60.0f};
    if (kind == GLASS_AND_MIRROR) {
        wall = (il_material_desc){.name = "wall", .type = IL_MATERIAL_MIRROR, .specular = {0.9f, 0.85f, 0.8f}};
        ball = (il_material_desc){.name = "ball", .type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f};
    }
    CHECK_OK(il_scene_add_material(s, &wall, &wall_m, &err), &err);
    CHECK_OK(il_scene_add_material(s, &ball, &ball_m, &err), &err);
    float floor_p[] = {-3, 0, -2, 3, 0, -2, 3, 0, 3, -3, 0, 3};
    float wall_p[] = {-3, 0, -2, 3, 0, -2, 3, 3, -2, -3, 3, -2};
    /* The checker repeats (the texture wraps) 3 times across the floor. */
    float floor_uv[] = {0, 0, 3, 0, 3, 2.5f, 0, 2.5f}, wall_uv[] = {0, 0, 2, 0, 2, 1, 0, 1};
    uint32_t quad_up[] = {0, 2, 1, 0, 3, 2}, quad_front[] = {0, 1, 2, 0, 2, 3};
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = floor_p,
                                                   .uvs = floor_uv, .indices = quad_up, .material = floor_m},
                               &err), &err);
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = wall_p,
                                                   .uvs = wall_uv, .indices = quad_front, .material = wall_m},
                               &err), &err);
    /* A UV sphere of radius 0.8 at (0, 0.8, 0): rows of latitude, outward
     * normals, counter-clockwise seen from outside. */
    enum { ROWS = 10, COLS = 16 };
    float sp[3 * (ROWS + 1) * (COLS + 1)], sn[3 * (ROWS + 1) * (COLS + 1)];
    uint32_t si[6 * ROWS * COLS], nt = 0;
    for (int r = 0; r <= ROWS; r++)
        for (int c = 0; c <= COLS; c++) {
            float th = 3.14159265f * r / ROWS, ph = 2.0f * 3.14159265f * c / COLS;
            float n[3] = {sinf(th) * cosf(ph), cosf(th), -sinf(th) * sinf(ph)};
            int v = r * (COLS + 1) + c;
            for (int k2 = 0; k2 < 3; k2++)
                sn[3 * v + k2] = n[k2];
            sp[3 * v] = 0.8f * n[0];
            sp[3 * v + 1] = 0.8f + 0.8f * n[1];
            sp[3 * v + 2] = 0.8f * n[2];
        }
    for (int r = 0; r < ROWS; r++)
        for (int c = 0; c < COLS; c++) {
            uint32_t a = r * (COLS + 1) + c, b = a + 1, d = a + COLS + 1, e = d + 1;
            uint32_t t[6] = {a, d, e, a, e, b};
            for (int k2 = 0; k2 < 6; k2++)
                si[3 * nt + k2] = t[k2];
            nt += 2;
        }
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = (ROWS + 1) * (COLS + 1), .num_triangles = nt,
                                                   .positions = sp, .normals = sn, .indices = si,
                                                   .material = ball_m}, &err), &err);
    if (kind == GLASS_AND_MIRROR || kind == WIDE_PANEL) {
        /* A one-sided panel facing down over the sphere: small and high,
         * or wide and low. */
        uint32_t lamp;
        CHECK_OK(il_scene_add_material(s, &(il_material_desc){.name = "panel", .emission = {6, 6, 5}}, &lamp,
                                       &err), &err);
        float pp[] = {-0.6f, 2.6f, -0.4f, 0.6f, 2.6f, -0.4f, 0.6f, 2.6f, 0.6f, -0.6f, 2.6f, 0.6f};
        float wide[] = {-2.0f, 1.2f, -1.5f, 2.0f, 1.2f, -1.5f, 2.0f, 1.2f, 1.5f, -2.0f, 1.2f, 1.5f};
        if (kind == WIDE_PANEL)
            memcpy(pp, wide, sizeof pp);
        CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 4, .num_triangles = 2, .positions = pp,
                                                       .indices = quad_front, .material = lamp}, &err), &err);
    }
    il_light_desc l = {0};
    if (kind == LATLONG_MAP || kind == ANGULAR_MAP) {
        /* 32 x 16 (latitude-longitude) or 16 x 16 (angular) texels; the
         * patch is a few texels near the top. */
        enum { MW = 32, MH = 16 };
        float px[MW * MH * 3];
        uint32_t w = kind == LATLONG_MAP ? MW : MH;
        for (uint32_t y = 0; y < MH; y++)
            for (uint32_t x = 0; x < w; x++) {
                float t = (float)y / MH, *p = px + 3 * (y * w + x);
                bool patch = y >= 3 && y < 5 && x >= w / 4 && x < w / 4 + 3;
                p[0] = patch ? 12.0f : 0.2f + 0.4f * t;
                p[1] = patch ? 11.0f : 0.3f + 0.1f * t;
                p[2] = patch ? 9.0f : 0.6f - 0.4f * t;
            }
        il_image map = {.width = w, .height = MH, .rgb = px};
        CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.map = &map, .rotation = 40.0f,
                                          .mapping = kind == LATLONG_MAP ? IL_ENV_LATLONG : IL_ENV_ANGULAR},
                                          &err), &err);
    }
    switch (kind) {
    case LATLONG_MAP:
    case ANGULAR_MAP:
    case WIDE_PANEL:
        break;
    case TEXTURED:
    case POINT_LIGHT:
        l = (il_light_desc){.type = IL_LIGHT_POINT, .position = {1.5f, 2.5f, 1.5f}, .intensity = {8, 7, 6}};
        break;
    case SPOT_LIGHT:
        l = (il_light_desc){.type = IL_LIGHT_SPOT, .position = {-0.5f, 2.8f, 1.5f},
                            .direction = {0.3f, -2.8f, -1.5f}, .intensity = {20, 18, 15},
                            .spot_angle = 35.0f, .spot_exponent = 4.0f};
        break;
    case GLASS_AND_MIRROR:
    case SUN_AND_SKY:
        /* A sun with a wide disc: soft shadows, drawn across it. */
        l = (il_light_desc){.type = IL_LIGHT_DIRECTIONAL, .direction = {-0.5f, -1.0f, -0.6f},
                            .intensity = {3.0f, 2.8f, 2.5f}, .diameter = 8.0f};
        CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = {0.2f, 0.3f, 0.5f}}, &err),
                 &err);
        break;
    }
    if (kind != LATLONG_MAP && kind != ANGULAR_MAP && kind != WIDE_PANEL)
        CHECK_OK(il_scene_add_light(s, &l, &err), &err);
    /* Glass: closer, so that the sphere (and its Fresnel rim) fills the view. */
    il_camera_desc cam = {.position = {0.5f, 2.2f, 5.0f}, .target = {0, 0.7f, 0}, .fov_y = 45.0f};
    if (kind == GLASS_AND_MIRROR)
        cam = (il_camera_desc){.position = {0.3f, 1.5f, 2.4f}, .target = {0, 0.8f, 0}, .fov_y = 40.0f};
    CHECK_OK(il_scene_set_camera(s, &cam, &err), &err);
    CHECK_OK(il_scene_commit(s, &err), &err);
    return s;
}

static void compare_small(test_light kind, const char *label, setup q)
{
    il_scene *s = small_scene(kind);
    if (!s)
        return;
    compare_scene(s, label, q);
    il_scene_release(s);
}

/* A one-triangle lamp plus one more material (mat), an optional point
 * light and an optional environment map, committed; and whether
 * il_kscene_build (photon kernels) and il_kscene_build_pt (path kernel)
 * take it, the refusal's message containing `says`. */
static void check_refusal(const il_material_desc *mat, bool point_light, bool env_map, bool photon_ok, bool path_ok,
                          const char *says)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    if (!s)
        return;
    il_material_desc md = *mat;
    if (md.diffuse_texture) {
        float texel[] = {0.5f, 0.5f, 0.5f};
        CHECK_OK(il_scene_add_texture(s, 1, 1, texel, &md.diffuse_texture, &err), &err);
    }
    uint32_t other, lamp;
    CHECK_OK(il_scene_add_material(s, &md, &other, &err), &err);
    CHECK_OK(il_scene_add_material(s, &(il_material_desc){.name = "l", .emission = {1, 1, 1}}, &lamp, &err), &err);
    float p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t ix[] = {0, 1, 2};
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 3, .num_triangles = 1, .positions = p,
                                                   .indices = ix, .material = lamp}, &err), &err);
    float q[] = {0, 0, 1, 1, 0, 1, 0, 1, 1};
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 3, .num_triangles = 1, .positions = q,
                                                   .indices = ix, .material = other}, &err), &err);
    if (point_light)
        CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .intensity = {1, 1, 1}}, &err),
                 &err);
    if (env_map) {
        float px[] = {1, 1, 1, 2, 2, 2};
        il_image map = {.width = 2, .height = 1, .rgb = px};
        CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.map = &map}, &err), &err);
    }
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_kscene ks;
    il_error e1 = {0}, e2 = {0};
    il_status photon = il_kscene_build(s, 8, 8, 4, 0, &ks, &e1);
    if (photon == IL_OK)
        il_kscene_free(&ks);
    il_status path = il_kscene_build_pt(s, 8, 8, 4, 0, &ks, &e2);
    if (path == IL_OK)
        il_kscene_free(&ks);
    CHECK(photon == (photon_ok ? IL_OK : IL_ERR_INVALID));
    CHECK(path == (path_ok ? IL_OK : IL_ERR_INVALID));
    if (!path_ok)
        CHECK(strstr(e2.message, says) != NULL);
    else if (!photon_ok)
        CHECK(strstr(e1.message, says) != NULL);
    il_scene_release(s);
}

/* What a kernel does not do yet is refused, not rendered wrong. */
static void test_refused(void)
{
    il_material_desc diffuse = {.name = "d"}, phong = {.name = "p", .type = IL_MATERIAL_PHONG, .exponent = 10};
    il_material_desc mirror = {.name = "m", .type = IL_MATERIAL_MIRROR};
    il_material_desc glass = {.name = "g", .type = IL_MATERIAL_DIELECTRIC};
    il_material_desc textured = {.name = "t", .diffuse = {1, 1, 1}, .diffuse_texture = 1};
    check_refusal(&diffuse, false, false, true, true, "");
    check_refusal(&phong, false, false, false, true, "'p'");
    check_refusal(&diffuse, true, false, false, true, "point");
    check_refusal(&mirror, false, false, false, true, "'m'");
    check_refusal(&glass, false, false, false, true, "'g'");
    il_material_desc pane = {.name = "w", .type = IL_MATERIAL_THIN_GLASS};
    check_refusal(&pane, false, false, false, false, "'w': thin_glass panes do not run on the GPU");
    check_refusal(&textured, false, false, false, true, "'t'");
    check_refusal(&diffuse, false, true, false, true, "environment");
}

int main(void)
{
    setup cornell = {48, 48, 256, 8, 0.03, 0};
    compare("cornell", (setup){48, 48, 256, 1, 0.03, 0});
    compare("cornell", cornell);
    compare(DRAGON, cornell);
    compare_small(POINT_LIGHT, "phong + point light", (setup){32, 32, 256, 8, 0.03, 0});
    compare_small(SPOT_LIGHT, "phong + spot light", (setup){32, 32, 256, 8, 0.03, 0});
    compare_small(SUN_AND_SKY, "phong + sun + sky", (setup){32, 32, 256, 8, 0.03, 0});
    /* 1024 spp: the sun's disc seen through the glass and in the mirror
     * (il_background_radiance) makes its pixels the noisiest of all. */
    compare_small(GLASS_AND_MIRROR, "glass + mirror + panel + sun + sky", (setup){32, 32, 1024, 8, 0.03, 0});
    compare_small(TEXTURED, "textured phong + diffuse, point light", (setup){32, 32, 256, 8, 0.03, 0});
    compare_small(LATLONG_MAP, "latitude-longitude map", (setup){32, 32, 256, 8, 0.03, 1.5});
    compare_small(ANGULAR_MAP, "angular map (resampled)", (setup){32, 32, 1024, 8, 0.03, 1.5});
    compare_small(WIDE_PANEL, "wide panel over a sharp phong floor", (setup){32, 32, 256, 8, 0.03, 3.0});
    compare("atrium", (setup){32, 24, 64, 8, 0.05, 0});
    test_refused();
    return check_report();
}
