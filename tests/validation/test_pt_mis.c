/* Light sampling alone, BSDF sampling alone and their MIS combination are
 * three unbiased estimators of the same image (Veach 1997, chapter 9), so
 * their expectations must agree everywhere.  The scene has what makes them
 * differ in variance: a small area light above a glossy Phong floor
 * (exponent 20), a diffuse wall, and a dim uniform sky.
 *
 * The tolerance comes from the data: each strategy renders K images with
 * independent seeds (independent Owen scramblings, so the K images are
 * i.i.d. randomised-QMC estimates); over the K values of a region's mean we
 * take the sample standard deviation, and two strategies agree when their
 * means differ by less than 5 combined standard errors.  With K = 16 the
 * t-distribution with 15 degrees of freedom puts 5 standard errors at a
 * two-sided p of about 2e-4 per comparison. */
#include "pt_scenes.h"

enum { W = 32, H = 32, K = 16, SPP = 64, RX = 4, RY = 4, NREG = RX * RY + 1 };

static il_scene *glossy_scene(void)
{
    il_scene *s = new_scene();
    uint32_t phong = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG, .diffuse = v3(0.2f, 0.25f, 0.3f),
                                                         .specular = v3s(0.6f), .exponent = 20.0f});
    uint32_t wall = add_material(s, (il_material_desc){.diffuse = v3(0.7f, 0.5f, 0.3f)});
    uint32_t light = add_material(s, (il_material_desc){.emission = v3(8.0f, 7.0f, 6.0f)});
    add_floor(s, 0.0f, 2.0f, phong);
    add_quad(s, v3(0, 1, -2), v3(2, 0, 0), v3(0, 1, 0), wall);          /* faces +z */
    add_quad(s, v3(0, 1.5f, 0), v3(0.25f, 0, 0), v3(0, 0, 0.25f), light); /* faces down */
    il_environment_desc env = {.radiance = v3(0.05f, 0.1f, 0.2f)};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    set_camera(s, v3(0, 1, 3), v3(0, 0.3f, 0), v3(0, 1, 0), 60.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

/* Region means of the channel average: RX x RY blocks, then the whole image. */
static void regions(const il_image *img, double out[NREG])
{
    for (int r = 0; r < RX * RY; r++) {
        uint32_t x0 = (uint32_t)(r % RX) * (W / RX), y0 = (uint32_t)(r / RX) * (H / RY);
        out[r] = 0.0;
        for (int c = 0; c < 3; c++)
            out[r] += region_mean(img, x0, y0, x0 + W / RX, y0 + H / RY, c) / 3.0;
    }
    out[RX * RY] = 0.0;
    for (int c = 0; c < 3; c++)
        out[RX * RY] += image_mean(img, c) / 3.0;
}

int main(void)
{
    il_scene *s = glossy_scene();
    const il_pt_strategy strategies[3] = {IL_PT_MIS, IL_PT_NEE_ONLY, IL_PT_BSDF_ONLY};
    static double v[3][K][NREG];
    for (int st = 0; st < 3; st++)
        for (int k = 0; k < K; k++) {
            il_render_desc rd = {.spp = SPP, .max_depth = 5, .seed = 1000u + (uint64_t)k};
            il_render_stats stats;
            il_image img = render_image(s, W, H, &rd, strategies[st], &stats);
            CHECK(img.rgb && image_finite(&img) && stats.nonfinite_samples == 0);
            if (img.rgb)
                regions(&img, v[st][k]);
            il_image_free(&img);
        }

    double mean[3][NREG], se[3][NREG];
    for (int st = 0; st < 3; st++)
        for (int r = 0; r < NREG; r++) {
            double m = 0.0, q = 0.0;
            for (int k = 0; k < K; k++)
                m += v[st][k][r];
            m /= K;
            for (int k = 0; k < K; k++)
                q += (v[st][k][r] - m) * (v[st][k][r] - m);
            mean[st][r] = m;
            se[st][r] = sqrt(q / (K - 1) / K);
        }

    printf("whole image: MIS %.5f +- %.5f, NEE %.5f +- %.5f, BSDF %.5f +- %.5f\n", mean[0][NREG - 1],
           se[0][NREG - 1], mean[1][NREG - 1], se[1][NREG - 1], mean[2][NREG - 1], se[2][NREG - 1]);
    int worst_pair = 0, worst_r = 0;
    double worst = 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++)
            for (int r = 0; r < NREG; r++) {
                double tol = 5.0 * sqrt(se[a][r] * se[a][r] + se[b][r] * se[b][r]) + 1e-6 * fabs(mean[a][r]);
                double z = fabs(mean[a][r] - mean[b][r]) / tol;
                if (z > worst) {
                    worst = z;
                    worst_pair = a * 3 + b;
                    worst_r = r;
                }
                CHECK_NEAR(mean[a][r], mean[b][r], tol);
            }
    printf("largest difference: %.2f of the tolerance (strategies %d/%d, region %d)\n", worst,
           worst_pair / 3, worst_pair % 3, worst_r);

    /* The test has teeth: on the whole image the tolerance is below 2% of
     * the mean, so a bias of that size in any strategy would fail it. */
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++) {
            double tol = 5.0 * sqrt(se[a][NREG - 1] * se[a][NREG - 1] + se[b][NREG - 1] * se[b][NREG - 1]);
            CHECK(tol < 0.02 * mean[0][NREG - 1]);
        }
    /* And MIS is never much noisier than the better of the two (Veach's
     * bound); on the whole image it is the least noisy here. */
    CHECK(se[0][NREG - 1] <= 1.5 * fmin(se[1][NREG - 1], se[2][NREG - 1]));

    il_scene_release(s);
    return check_report();
}
