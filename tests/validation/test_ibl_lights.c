/* The light sets' weights: with light i of direction wi_i and weight
 * w_i = L(wi_i) / pdf(wi_i), every selection's mean 1/N sum_i w_i g(wi_i)
 * is a Monte Carlo estimate of int_S2 L(w) g(w) dw (ibl_lights.c).  Checked
 * for g = 1 (the environment's total), g = max(0, w.y) (irradiance on a
 * floor) and g = max(0, w.x) (on a wall facing +x) against a brute-force
 * integral over a fine lat-long grid, for all four selections under Grace
 * Cathedral (2^20 importance-sampled lights, 2^22 uniform ones), within
 * five standard errors of the sample (the Sobol sets' errors are far
 * smaller).  Importance sampling must cut the spread of the
 * weights' luminance (the variance of a light's contribution) several
 * times below uniform sampling, and under a constant sky every uniform
 * light carries exactly 4 pi L. */
#include "test_ibl_common.h"
#include "scene/lights.h"

/* Lights per set: uniform sets need more (their weights spread widely). */
#define N_IMPORTANCE (1u << 20)
#define N_UNIFORM (1u << 22)

/* int L(w) g_k(w) dw by the midpoint rule over a 2048 x 1024 lat-long grid
 * (8 times finer than the map), dw = 2 pi^2 sin(theta) du dv. */
static void reference(const il_scene *s, double out[3][3])
{
    const int nu = 2048, nv = 1024;
    memset(out, 0, 9 * sizeof(double));
    for (int j = 0; j < nv; j++) {
        double v = (j + 0.5) / nv, theta = PI_D * v;
        double dw = 2.0 * PI_D * PI_D * sin(theta) / ((double)nu * nv);
        for (int i = 0; i < nu; i++) {
            double u = (i + 0.5) / nu, phi = 2.0 * PI_D * (u - 0.5);
            il_vec3 d = v3((float)(sin(theta) * sin(phi)), (float)cos(theta), (float)(-sin(theta) * cos(phi)));
            il_vec3 L = il_environment_radiance(s, d);
            double g[3] = {1.0, d.y > 0.0f ? d.y : 0.0, d.x > 0.0f ? d.x : 0.0};
            for (int k = 0; k < 3; k++)
                for (int c = 0; c < 3; c++)
                    out[k][c] += v3_get(L, c) * g[k] * dw;
        }
    }
}

/* Returns the relative spread (std / mean) of the weights' luminance. */
static double check_set(const char *name, const il_scene *s, il_ibl_selection sel, double ref[3][3])
{
    il_ibl_lights ls = {0};
    uint32_t n_lights = sel == IL_IBL_SOBOL || sel == IL_IBL_RANDOM ? N_UNIFORM : N_IMPORTANCE;
    CHECK_OK(il_ibl_lights_build(s, sel, 5, n_lights, 1, &ls, &g_err), &g_err);
    if (ls.count != n_lights)
        return 0.0;
    double sum[3][3] = {{0}}, sum2[3][3] = {{0}}, lum = 0.0, lum2 = 0.0;
    bool finite = true;
    for (uint32_t i = 0; i < ls.count; i++) {
        il_vec3 d = ls.dir[i], w = ls.weight[i];
        finite &= v3_is_finite(w) && w.x >= 0.0f && w.y >= 0.0f && w.z >= 0.0f &&
                  fabsf(v3_length(d) - 1.0f) < 1e-4f;
        double g[3] = {1.0, d.y > 0.0f ? d.y : 0.0, d.x > 0.0f ? d.x : 0.0};
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 3; c++) {
                double x = v3_get(w, c) * g[k];
                sum[k][c] += x;
                sum2[k][c] += x * x;
            }
        double l = il_luminance(w);
        lum += l;
        lum2 += l * l;
    }
    CHECK(finite);
    const char *what[3] = {"total", "floor", "wall"};
    double n = ls.count;
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < 3; c++) {
            double mean = sum[k][c] / n;
            double se = sqrt(fmax(sum2[k][c] / n - mean * mean, 0.0) / n);
            double err = fabs(mean - ref[k][c]);
            if (c == 1)
                printf("%-17s %-5s %.5f reference %.5f (%+.3f%%, %.1f standard errors)\n", name, what[k],
                       mean, ref[k][c], 100.0 * (mean / ref[k][c] - 1.0), se > 0.0 ? err / se : 0.0);
            /* 0.2% for the reference grid's own error. */
            CHECK(err <= 5.0 * se + 0.002 * ref[k][c]);
        }
    double m = lum / n;
    double spread = sqrt(fmax(lum2 / n - m * m, 0.0)) / m;
    printf("%-17s spread of the weights' luminance %.3f\n", name, spread);
    il_ibl_lights_free(&ls);
    return spread;
}

static void test_map(void)
{
    il_scene *s = new_scene();
    add_floor(s, 0.0f, 1.0f, 0);
    if (!set_map(s, "probulator_grace_256x128.hdr")) {
        il_scene_release(s);
        return;
    }
    commit(s);
    double ref[3][3];
    reference(s, ref);
    double spread_is = check_set("importance-sobol", s, IL_IBL_IMPORTANCE_SOBOL, ref);
    double spread_i = check_set("importance", s, IL_IBL_IMPORTANCE, ref);
    double spread_s = check_set("sobol", s, IL_IBL_SOBOL, ref);
    double spread_r = check_set("random", s, IL_IBL_RANDOM, ref);
    /* Importance sampling of a map with bright windows: each light carries
     * nearly the same power; uniform lights differ by orders of magnitude. */
    CHECK(spread_i < 0.25 * spread_r && spread_is < 0.25 * spread_s);

    /* Light i does not depend on how many lights are drawn, and the seed
     * picks an independent randomisation. */
    il_vec3 d0, w0, d1, w1, d2, w2;
    il_ibl_lights ls = {0};
    CHECK_OK(il_ibl_lights_build(s, IL_IBL_IMPORTANCE_SOBOL, 9, 100, 2, &ls, &g_err), &g_err);
    il_ibl_light(s, IL_IBL_IMPORTANCE_SOBOL, 9, 77, &d0, &w0);
    il_ibl_light(s, IL_IBL_IMPORTANCE_SOBOL, 10, 77, &d1, &w1);
    il_ibl_light(s, IL_IBL_RANDOM, 9, 77, &d2, &w2);
    CHECK(ls.count == 100 && !memcmp(&ls.dir[77], &d0, sizeof d0) && !memcmp(&ls.weight[77], &w0, sizeof w0));
    CHECK(memcmp(&d0, &d1, sizeof d0) != 0 && memcmp(&d0, &d2, sizeof d0) != 0);
    il_ibl_lights_free(&ls);
    il_scene_release(s);
}

static void test_constant(void)
{
    const il_vec3 L = {0.5f, 1.0f, 2.0f};
    il_scene *s = new_scene();
    add_floor(s, 0.0f, 1.0f, 0);
    set_sky(s, L);
    commit(s);
    static const il_ibl_selection sels[] = {IL_IBL_IMPORTANCE_SOBOL, IL_IBL_IMPORTANCE, IL_IBL_SOBOL,
                                            IL_IBL_RANDOM};
    for (int k = 0; k < 4; k++) {
        il_ibl_lights ls = {0};
        CHECK_OK(il_ibl_lights_build(s, sels[k], 1, 1000, 0, &ls, &g_err), &g_err);
        bool exact = ls.count == 1000;
        for (uint32_t i = 0; i < ls.count; i++)
            exact &= fabsf(ls.weight[i].y - 4.0f * IL_PI * L.y) <= 1e-5f * 4.0f * IL_PI * L.y &&
                     fabsf(ls.weight[i].z - 4.0f * IL_PI * L.z) <= 1e-5f * 4.0f * IL_PI * L.z;
        CHECK(exact);
        il_ibl_lights_free(&ls);
    }
    il_scene_release(s);
}

int main(void)
{
    test_constant();
    test_map();
    return check_report();
}
