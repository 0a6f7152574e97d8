/* Importance sampling of environment maps (src/image/envmap_sample.c), for
 * lat-long, angular and cross maps, rotated and not, among them a map with
 * one tiny texel 10^5 times brighter than the rest and the shared Poly
 * Haven map with a sun 69,000 times its mean:
 *   - the pdf integrates to 1 over the sphere (exactly on the grid it is
 *     tabulated on, and by an equal-area quadrature in world space);
 *   - chi-square tests of sample histograms against the pdf's integrals
 *     over the bins (Pearson, tests/unit/chi2.h), on the sampling grid's
 *     cells and on a coarse world-space grid;
 *   - il_envmap_pdf(direction of a sample) equals the pdf the sample
 *     returned, and its radiance equals il_envmap_eval;
 *   - the pdf is positive wherever the map gives light (MIS and pure light
 *     sampling stay unbiased);
 *   - E[L / pdf] is 4 pi times the mean radiance (the weight the many-light
 *     method and the path tracer use). */
#include <string.h>

#include "check.h"
#include "chi2.h"
#include "core/rng.h"
#include "core/vec.h"
#include "image/envmap.h"

#define PI_D 3.14159265358979323846
/* Two chi-square tests for each of the NUM_RUNS runs below, at an overall
 * significance of 1% (Sidak). */
#define NUM_RUNS 6
static double g_alpha;

/* A smooth lat-long map with one texel of radiance 1e5 (the spot). */
static il_image spot_map(uint32_t w, uint32_t h)
{
    il_image img = {0};
    il_error err;
    CHECK_OK(il_image_alloc(&img, w, h, &err), &err);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            float *p = img.rgb + 3 * ((size_t)y * w + x);
            float s = 0.2f + 0.8f * (float)y / h + 0.3f * sinf(6.2831853f * x / w);
            p[0] = s;
            p[1] = 0.5f * s;
            p[2] = 0.25f + 0.1f * s;
        }
    float *spot = img.rgb + 3 * ((size_t)(h / 3) * w + (5 * w) / 8);
    spot[0] = spot[1] = spot[2] = 1e5f;
    return img;
}

/* The world direction of local lat-long coordinates (u, v). */
static il_vec3 grid_dir(const il_envmap *env, float u, float v)
{
    return il_envmap_to_world(env, il_envmap_latlong_dir(u, v));
}

/* The pdf on the sampling grid's cell (i, j), as a density in (u, v):
 * pdf_omega * 2 pi^2 sin(theta) at the cell's centre. */
static double cell_pdf_uv(const il_envmap *env, uint32_t i, uint32_t j)
{
    const il_envmap_dist *d = &env->dist;
    float u = (i + 0.5f) / d->width, v = (j + 0.5f) / d->height;
    return il_envmap_pdf(env, grid_dir(env, u, v)) * 2.0 * PI_D * PI_D * sin(PI_D * v);
}

static void check_integral(const il_envmap *env, const char *name, bool world)
{
    const il_envmap_dist *d = &env->dist;
    /* On the grid: the pdf is constant in (u, v) on each cell, so 2 x 2
     * midpoints per cell give its integral to float precision. */
    double sum = 0.0;
    for (uint32_t j = 0; j < 2 * d->height; j++)
        for (uint32_t i = 0; i < 2 * d->width; i++) {
            float u = (i + 0.5f) / (2 * d->width), v = (j + 0.5f) / (2 * d->height);
            sum += il_envmap_pdf(env, grid_dir(env, u, v)) * 2.0 * PI_D * PI_D * sin(PI_D * v);
        }
    sum /= 4.0 * d->width * d->height;
    printf("%s: integral of the pdf %.7f on its grid\n", name, sum);
    CHECK_NEAR(sum, 1.0, 1e-4);
    if (!world)
        return;
    /* In world space, blind to the grid: an equal-area grid in (cos, phi)
     * about +y.  Its error comes from the cells its lines cut, a fraction
     * of the mass of those cells: small for the synthetic maps' 64 x 32
     * cells, but several per cent where one small cell holds most of the
     * mass (Grace's windows, the sun), so only for the former. */
    const int nz = 1024, nphi = 2048;
    double sw = 0.0;
    for (int a = 0; a < nz; a++) {
        double z = 1.0 - (a + 0.5) * 2.0 / nz, r = sqrt(1.0 - z * z);
        for (int b = 0; b < nphi; b++) {
            double phi = (b + 0.5) * 2.0 * PI_D / nphi;
            sw += il_envmap_pdf(env, v3((float)(r * cos(phi)), (float)z, (float)(r * sin(phi))));
        }
    }
    sw *= 4.0 * PI_D / ((double)nz * nphi);
    printf("%s: integral of the pdf %.5f in world space\n", name, sw);
    CHECK_NEAR(sw, 1.0, 0.01);
}

/* Samples n directions: checks them against pdf() and eval(), fills the
 * two histograms, and returns the mean of lum(L)/pdf. */
static double draw(const il_envmap *env, uint32_t n, double *hist_grid, uint32_t g, double *hist_world,
                   int bw, int bh, const char *name)
{
    const il_envmap_dist *d = &env->dist;
    il_pcg32 rng = il_pcg32_seed(12345, 7);
    uint32_t gw = d->width / g, gh = d->height / g;
    uint32_t mismatched = 0, zero = 0, bad_radiance = 0;
    float max_texel = 0.0f;
    for (size_t k = 0; k < 3 * (size_t)env->img.width * env->img.height; k++)
        max_texel = il_maxf(max_texel, env->img.rgb[k]);
    double worst_rel = 0.0, est = 0.0;
    for (uint32_t k = 0; k < n; k++) {
        il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        il_vec3 dir;
        float pdf;
        il_vec3 L = il_envmap_sample(env, u, &dir, &pdf);
        if (!(pdf > 0.0f)) {
            zero++;
            continue;
        }
        float p2 = il_envmap_pdf(env, dir);
        double rel = fabs(p2 - pdf) / pdf;
        if (rel > 1e-3)
            mismatched++;
        else
            worst_rel = fmax(worst_rel, rel);
        /* The same lookup, up to the rounding of turning the direction
         * to the world and back, which moves it ~3e-7 rad: 1e-5 of the
         * largest texel covers that on the steepest slope (the spot's
         * 1e5 over one texel).  A cube's edge is a step (each face
         * filters on its own), where the rounding may pick the other
         * face: a few in 10^5 may differ there. */
        il_vec3 L2 = il_envmap_eval(env, dir);
        if (fabsf(L.x - L2.x) > 1e-4f * L2.x + 1e-5f * max_texel) {
            if (bad_radiance < 5)
                fprintf(stderr, "%s: sample radiance %g, eval %g\n", name, L.x, L2.x);
            bad_radiance++;
        }
        est += il_luminance(L) / pdf;
        /* Local grid bin. */
        il_vec2 uv = il_envmap_dir_to_uv(IL_ENV_LATLONG, il_envmap_to_local(env, dir));
        uint32_t i = (uint32_t)fminf(uv.x * d->width, d->width - 1) / g;
        uint32_t j = (uint32_t)fminf(uv.y * d->height, d->height - 1) / g;
        hist_grid[(size_t)j * gw + i] += 1.0;
        il_vec2 wv = il_envmap_dir_to_uv(IL_ENV_LATLONG, dir);
        int bi = (int)fminf(wv.x * bw, bw - 1), bj = (int)fminf(wv.y * bh, bh - 1);
        hist_world[bj * bw + bi] += 1.0;
    }
    (void)gh;
    printf("%s: %u samples, %u with pdf 0, %u whose pdf() differs by > 1e-3 (else at most %.2g), "
           "%u whose radiance differs from eval()\n", name, n, zero, mismatched, worst_rel, bad_radiance);
    /* A sample a hair from a cell's edge can land in the neighbour once
     * mapped to a direction and back: allow one in 10^4. */
    CHECK(mismatched <= n / 10000);
    CHECK(zero <= n / 10000);
    CHECK(bad_radiance <= n / 100000);
    return est / n;
}

/* Length of [c0, c1] inside [b0, b1], the latter taken modulo 1 when wrap. */
static double overlap(double c0, double c1, double b0, double b1, bool wrap)
{
    double s = 0.0;
    for (int k = wrap ? -2 : 0; k <= (wrap ? 2 : 0); k++)
        s += fmax(0.0, fmin(c1, b1 + k) - fmax(c0, b0 + k));
    return s;
}

static void check_sampling(const il_envmap *env, const char *name, uint32_t g, uint32_t n, bool world)
{
    const il_envmap_dist *d = &env->dist;
    check_integral(env, name, world);

    uint32_t gw = d->width / g, gh = d->height / g;
    double *obs = calloc((size_t)gw * gh, sizeof(double));
    double *expd = calloc((size_t)gw * gh, sizeof(double));
    const int bw = 16, bh = 8;
    double wobs[16 * 8] = {0}, wexp[16 * 8] = {0};
    double est = draw(env, n, obs, g, wobs, bw, bh, name);

    /* Expected counts on the grid: exact, the pdf is constant per cell. */
    for (uint32_t j = 0; j < gh * g; j++)
        for (uint32_t i = 0; i < gw * g; i++)
            expd[(size_t)(j / g) * gw + i / g] += n * cell_pdf_uv(env, i, j) / ((double)d->width * d->height);
    char label[128];
    snprintf(label, sizeof label, "%s grid chi2", name);
    double p = chi2_pvalue(obs, expd, (int)(gw * gh), label);
    printf("%s: chi-square p-value on %u x %u grid bins %.4f\n", name, gw, gh, p);
    CHECK(p > g_alpha);

    /* World bins 16 x 8 in (u, v) about +y, blind to the rotation.  The
     * rotation turns about +y, the lat-long grid's axis, so a world bin
     * is a rectangle of the grid shifted by rotation / 2 pi in u: its
     * expected count is exact from the cells' overlaps with it. */
    for (int bj = 0; bj < bh; bj++)
        for (int bi = 0; bi < bw; bi++) {
            double u0 = (double)bi / bw + env->rotation / (2.0 * PI_D), u1 = u0 + 1.0 / bw;
            double v0 = (double)bj / bh, v1 = v0 + 1.0 / bh;
            double s = 0.0;
            for (uint32_t j = 0; j < d->height; j++) {
                double ov = overlap((double)j / d->height, (j + 1.0) / d->height, v0, v1, false);
                if (ov <= 0.0)
                    continue;
                for (uint32_t i = 0; i < d->width; i++) {
                    double ou = overlap((double)i / d->width, (i + 1.0) / d->width, u0, u1, true);
                    if (ou > 0.0)
                        s += cell_pdf_uv(env, i, j) * ou * ov;
                }
            }
            wexp[bj * bw + bi] = n * s;
        }
    snprintf(label, sizeof label, "%s world chi2", name);
    double pw = chi2_pvalue(wobs, wexp, bw * bh, label);
    printf("%s: chi-square p-value on 16 x 8 world bins %.4f\n", name, pw);
    CHECK(pw > g_alpha);

    /* E[lum(L)/pdf] = int lum(L) dOmega = 4 pi lum(mean). */
    double expect = 4.0 * PI_D * il_luminance(d->mean);
    printf("%s: E[L/pdf] %.5g, 4 pi mean %.5g (%+.3f%%)\n", name, est, expect, 100.0 * (est / expect - 1.0));
    CHECK_REL(est, expect, 0.01);

    /* Positive wherever there is light, on a grid finer than the map. */
    uint32_t missed = 0;
    for (int a = 0; a < 512; a++)
        for (int b = 0; b < 1024; b++) {
            il_vec3 dir = il_envmap_latlong_dir((b + 0.37f) / 1024, (a + 0.61f) / 512);
            if (il_luminance(il_envmap_eval(env, dir)) > 0.0f && !(il_envmap_pdf(env, dir) > 0.0f))
                missed++;
        }
    CHECK(missed == 0);
    free(obs);
    free(expd);
}

static void run(const il_image *img, il_env_mapping m, float rot, const char *name, uint32_t g, uint32_t n,
                bool world)
{
    il_envmap env;
    il_error err;
    il_status st = il_envmap_init(&env, img, m, rot, 0.0f, NULL, &err);
    CHECK_OK(st, &err);
    if (st != IL_OK)
        return;
    char label[96];
    snprintf(label, sizeof label, "%s %s rot %g", name, il_envmap_mapping_name(m), rot);
    check_sampling(&env, label, g, n, world);
    il_envmap_free(&env);
}

/* The mean radiance the tables report is the solid-angle mean of the
 * lookups (checked against an independent quadrature). */
static void check_mean(const il_image *img, il_env_mapping m, const char *name)
{
    il_envmap env;
    il_error err;
    CHECK_OK(il_envmap_init(&env, img, m, 0, 0, NULL, &err), &err);
    const int nz = 1024, nphi = 2048;
    double s = 0.0;
    for (int a = 0; a < nz; a++) {
        double z = 1.0 - (a + 0.5) * 2.0 / nz, r = sqrt(1.0 - z * z);
        for (int b = 0; b < nphi; b++) {
            double phi = (b + 0.5) * 2.0 * PI_D / nphi;
            s += il_luminance(il_envmap_lookup(img, m, v3((float)(r * cos(phi)), (float)z, (float)(r * sin(phi)))));
        }
    }
    s /= (double)nz * nphi;
    printf("%s %s: mean luminance %.6g from the tables, %.6g by quadrature\n", name,
           il_envmap_mapping_name(m), il_luminance(env.dist.mean), s);
    CHECK_REL(il_luminance(env.dist.mean), s, 0.01);
    il_envmap_free(&env);
}

int main(void)
{
    il_error err;
    g_alpha = chi2_significance(0.01, 2 * NUM_RUNS);
    il_image spot = spot_map(64, 32);
    run(&spot, IL_ENV_LATLONG, 0.0f, "spot", 1, 2000000, true);
    run(&spot, IL_ENV_LATLONG, 77.0f, "spot", 1, 2000000, true);
    check_mean(&spot, IL_ENV_LATLONG, "spot");

    /* The same sky as an angular map and a cross (resampled tables). */
    il_image ang = {0}, cross = {0};
    CHECK_OK(il_envmap_convert(&spot, IL_ENV_LATLONG, IL_ENV_ANGULAR, 0, &ang, &err), &err);
    CHECK_OK(il_envmap_convert(&spot, IL_ENV_LATLONG, IL_ENV_CROSS, 0, &cross, &err), &err);
    run(&ang, IL_ENV_ANGULAR, 0.0f, "spot", 1, 2000000, true);
    run(&cross, IL_ENV_CROSS, -30.0f, "spot", 1, 2000000, true);
    check_mean(&ang, IL_ENV_ANGULAR, "spot");
    check_mean(&cross, IL_ENV_CROSS, "spot");
    il_image_free(&ang);
    il_image_free(&cross);
    il_image_free(&spot);

    /* The shared maps: Grace Cathedral and the sun. */
    char path[1024];
    il_image grace = {0}, sun = {0};
    snprintf(path, sizeof path, "%s/scenes/envmaps/probulator_grace_256x128.hdr", IL_SHARED_DIR);
    CHECK_OK(il_image_read(path, &grace, &err), &err);
    snprintf(path, sizeof path, "%s/scenes/envmaps/polyhaven_pedestrian_overpass_1k.hdr", IL_SHARED_DIR);
    CHECK_OK(il_image_read(path, &sun, &err), &err);
    if (grace.rgb) {
        run(&grace, IL_ENV_LATLONG, 30.0f, "grace", 2, 2000000, false);
        check_mean(&grace, IL_ENV_LATLONG, "grace");
    }
    if (sun.rgb) {
        run(&sun, IL_ENV_LATLONG, 0.0f, "overpass", 8, 2000000, false);
        check_mean(&sun, IL_ENV_LATLONG, "overpass");
    }
    il_image_free(&grace);
    il_image_free(&sun);
    return check_report();
}
