/* The shared path-tracing kernel (src/kernel/kernel_path.h, compiled here by
 * gcc exactly as nvcc compiles it for the GPU megakernel) against the CPU
 * path tracer (il_render, method pt) on the Cornell box and on the Cornell
 * box with the Stanford dragon (47,794 triangles: the kernel's own BVH
 * against Embree): the same image within noise, over the whole image and
 * over 8x8-pixel blocks, for direct light only and for 8 bounces; and the
 * scenes the kernel cannot render yet are refused with IL_ERR_INVALID. */
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "kernel/kernel_scene.h"
#include "scene/scene.h"

#define W 48
#define H 48
#define SPP 256
#define B 8

#define DRAGON IL_SOURCE_DIR "/bench/scenes/cornell-dragon.json"

static void compare(const char *scene, uint32_t max_depth, double tol_mean)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(scene, NULL, &s, &err), &err);
    if (!s)
        return;
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_kscene ks;
    CHECK_OK(il_kscene_build(s, W, H, max_depth, 5, &ks, &err), &err);
    /* Per pixel: the mean of each channel; per 8x8 block: the mean and
     * variance of the samples' channel sum, for a z-test. */
    float *k = calloc(3 * W * H, sizeof *k);
    double bsum[H / B][W / B], bsq[H / B][W / B];
    memset(bsum, 0, sizeof bsum);
    memset(bsq, 0, sizeof bsq);
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double acc[3] = {0, 0, 0};
            for (uint32_t i = 0; i < SPP; i++) {
                ilk_vec3 L = ilk_path_sample(&ks.view, x, y, i);
                acc[0] += L.x; acc[1] += L.y; acc[2] += L.z;
                double v = (double)L.x + L.y + L.z;
                bsum[y / B][x / B] += v;
                bsq[y / B][x / B] += v * v;
            }
            for (int c = 0; c < 3; c++)
                k[3 * (y * W + x) + c] = (float)(acc[c] / SPP);
        }

    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &err), &err);
    il_render_desc rd = {.method = IL_METHOD_PT, .spp = SPP, .max_depth = max_depth, .seed = 9};
    CHECK_OK(il_render(s, film, &rd, NULL, &err), &err);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    if (!img.rgb) {
        free(k);
        il_kscene_free(&ks);
        il_scene_release(s);
        return;
    }

    /* Whole image, per channel, and per block: the difference in units of
     * the kernel's standard error, times sqrt(2) for the CPU image's own
     * noise (the Sobol sampler's is lower, so this is conservative). */
    double mk[3] = {0, 0, 0}, mc[3] = {0, 0, 0}, worst_z = 0, all_sum = 0, all_sq = 0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            mk[c] += k[3 * i + c] / (W * H);
            mc[c] += img.rgb[3 * i + c] / (W * H);
        }
    const double nb = (double)B * B * SPP;
    for (int by = 0; by < H / B; by++)
        for (int bx = 0; bx < W / B; bx++) {
            double cpu = 0;
            for (int y = by * B; y < (by + 1) * B; y++)
                for (int x = bx * B; x < (bx + 1) * B; x++)
                    for (int c = 0; c < 3; c++)
                        cpu += img.rgb[3 * (y * W + x) + c];
            cpu /= B * B;
            double mean = bsum[by][bx] / nb, var = fmax(bsq[by][bx] / nb - mean * mean, 0.0);
            double se = sqrt(2.0 * var / nb) + 1e-6;
            double z = fabs(mean - cpu) / se;
            if (z > worst_z)
                worst_z = z;
            all_sum += bsum[by][bx];
            all_sq += bsq[by][bx];
        }
    double n_all = nb * (W / B) * (H / B), m_all = all_sum / n_all;
    double se_all = sqrt(2.0 * fmax(all_sq / n_all - m_all * m_all, 0.0) / n_all);
    double z_all = fabs(m_all - (mc[0] + mc[1] + mc[2])) / se_all;
    printf("%s, max depth %u: mean kernel (%.5f %.5f %.5f) cpu pt (%.5f %.5f %.5f): z %.2f (se %.2g%%); "
           "worst of %d 8x8 blocks z %.2f\n", strstr(scene, "dragon") ? "dragon" : scene, max_depth, mk[0], mk[1], mk[2], mc[0], mc[1], mc[2], z_all,
           100.0 * se_all / m_all, (W / B) * (H / B), worst_z);
    for (int c = 0; c < 3; c++) {
        CHECK(mc[c] > 0.01);
        CHECK_REL(mk[c], mc[c], tol_mean);
    }
    CHECK(z_all < 4.0);
    CHECK(worst_z < 4.5);
    il_image_free(&img);
    il_film_release(film);
    free(k);
    il_kscene_free(&ks);
    il_scene_release(s);
}

/* What the kernel does not do yet is refused, not rendered wrong. */
static void test_refused(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    uint32_t mirror, lamp;
    CHECK_OK(il_scene_add_material(s, &(il_material_desc){.name = "m", .type = IL_MATERIAL_MIRROR}, &mirror, &err), &err);
    CHECK_OK(il_scene_add_material(s, &(il_material_desc){.name = "l", .emission = {1, 1, 1}}, &lamp, &err), &err);
    float p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t ix[] = {0, 1, 2};
    CHECK_OK(il_scene_add_mesh(s, &(il_mesh_desc){.num_vertices = 3, .num_triangles = 1, .positions = p,
                                                   .indices = ix, .material = lamp}, &err), &err);
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_kscene ks;
    CHECK(il_kscene_build(s, 8, 8, 4, 0, &ks, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "'m'") != NULL);
    il_scene_release(s);
}

int main(void)
{
    compare("cornell", 1, 0.03);
    compare("cornell", 8, 0.03);
    compare(DRAGON, 8, 0.03);
    test_refused();
    return check_report();
}
