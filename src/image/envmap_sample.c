/* Importance sampling of an environment map: a piecewise-constant 2D
 * density over a lat-long grid of cells, sampled as the marginal over the
 * rows and then the conditional within the chosen row, each by binary
 * search of its CDF (pbrt-v3 13.6.7 "2D Sampling with Multidimensional
 * Transformations" and 14.2.4 "Infinite Area Lights"; pbrt-v4 A.5.2 and
 * 12.5.2).
 *
 * The grid.  A lat-long map uses its own texels as the cells.  Angular maps
 * and crosses are tabulated on a lat-long grid of about their resolution
 * (2H x H cells, H = the angular map's radius in texels, or twice the
 * cross's face size): the density then lives on the grid, so the pdf below
 * is exact for what is sampled whatever the mapping (only its resemblance
 * to the radiance depends on the tabulation).
 *
 * The weights.  A cell's weight is its mean luminance times sin(theta) at
 * its centre, since a cell of the (u, v) square covers a solid angle
 * proportional to sin(theta):
 *   - lat-long: the exact mean of the bilinear lookup over the texel, which
 *     is the separable filter [1/8, 3/4, 1/8] over the texel and its
 *     neighbours (integrating the tent of each neighbour over the cell);
 *     so a cell that can return any light has a positive weight;
 *   - angular, cross: the mean of 2 x 2 lookups spread over the cell, plus
 *     a floor of 1e-3 of the map's mean: light that falls between the
 *     lookups is still sampled (with low probability), so light sampling
 *     alone (photon mapping's direct light, the ibl method) stays unbiased.
 *
 * The mean radiance (the environment's power for light selection) is the
 * solid-angle mean of the cells for a lat-long map, of the texels for the
 * others (texel_mean).
 *
 * The density in solid angle.  (u, v) in the unit square maps to
 * theta = pi v, phi = 2 pi u, dOmega = 2 pi^2 sin(theta) du dv, so
 *   pdf_omega = pdf_uv(u, v) / (2 pi^2 sin theta)   (pbrt-v3 14.2.4,
 * pbrt-v4 12.5.2), with pdf_uv = pmf(row) H * pmf(column | row) W. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "image/envmap.h"

#define IL_ENV_SUPERSAMPLE 2
#define IL_ENV_FLOOR 1e-3
#define IL_ENV_GRID_MIN 8u
#define IL_ENV_GRID_MAX 2048u

void il_envmap_dist_free(il_envmap_dist *d)
{
    if (!d)
        return;
    if (d->rows) {
        for (uint32_t j = 0; j < d->height; j++)
            il_distrib1d_free(&d->rows[j]);
        free(d->rows);
    }
    il_distrib1d_free(&d->marginal);
    memset(d, 0, sizeof *d);
}

/* Solid angle of a row of the grid: the band between theta_j and theta_j+1. */
static double row_solid_angle(uint32_t j, uint32_t h)
{
    const double pi = 3.14159265358979323846;
    return 2.0 * pi * (cos(pi * j / h) - cos(pi * (j + 1.0) / h));
}

/* Lat-long map: weights from the cell means of the bilinear lookup.  The
 * lookup wraps in u and clamps at the poles (envmap.c), and so does the
 * filter. */
static void weights_latlong(const il_image *img, float *w, double *row_rgb)
{
    const uint32_t W = img->width, H = img->height;
    static const float k[3] = {0.125f, 0.75f, 0.125f};
#pragma omp parallel for schedule(static)
    for (uint32_t j = 0; j < H; j++) {
        double acc[3] = {0, 0, 0};
        uint32_t ys[3] = {j == 0 ? 0 : j - 1, j, j + 1 == H ? H - 1 : j + 1};
        float st = sinf(IL_PI * ((float)j + 0.5f) / (float)H);
        double band = row_solid_angle(j, H) / W;
        for (uint32_t i = 0; i < W; i++) {
            uint32_t xs[3] = {i == 0 ? W - 1 : i - 1, i, i + 1 == W ? 0 : i + 1};
            float c[3] = {0, 0, 0};
            for (int dy = 0; dy < 3; dy++)
                for (int dx = 0; dx < 3; dx++) {
                    const float *p = img->rgb + 3 * ((size_t)ys[dy] * W + xs[dx]);
                    float kk = k[dy] * k[dx];
                    c[0] += kk * p[0];
                    c[1] += kk * p[1];
                    c[2] += kk * p[2];
                }
            w[(size_t)j * W + i] = il_luminance(v3(c[0], c[1], c[2])) * st;
            for (int ch = 0; ch < 3; ch++)
                acc[ch] += c[ch] * band;
        }
        for (int ch = 0; ch < 3; ch++)
            row_rgb[3 * j + ch] = acc[ch];
    }
}

/* Angular map or cross: weights from S x S lookups per cell of a W x H
 * lat-long grid (solid-angle weighted within the cell), plus the floor. */
static void weights_resampled(const il_image *img, il_env_mapping m, uint32_t W, uint32_t H, float *w,
                              double *row_rgb)
{
    const int S = IL_ENV_SUPERSAMPLE;
#pragma omp parallel for schedule(dynamic, 4)
    for (uint32_t j = 0; j < H; j++) {
        double acc[3] = {0, 0, 0};
        float st_c = sinf(IL_PI * ((float)j + 0.5f) / (float)H);
        double band = row_solid_angle(j, H) / W;
        for (uint32_t i = 0; i < W; i++) {
            double c[3] = {0, 0, 0}, sw = 0.0;
            for (int sy = 0; sy < S; sy++) {
                float v = ((float)j + ((float)sy + 0.5f) / S) / (float)H;
                float st = sinf(IL_PI * v);
                for (int sx = 0; sx < S; sx++) {
                    float u = ((float)i + ((float)sx + 0.5f) / S) / (float)W;
                    il_vec3 L = il_envmap_lookup(img, m, il_envmap_latlong_dir(u, v));
                    c[0] += (double)L.x * st;
                    c[1] += (double)L.y * st;
                    c[2] += (double)L.z * st;
                    sw += st;
                }
            }
            for (int ch = 0; ch < 3; ch++)
                c[ch] = sw > 0.0 ? c[ch] / sw : 0.0;
            float lum = il_luminance(v3((float)c[0], (float)c[1], (float)c[2]));
            w[(size_t)j * W + i] = lum * st_c;
            for (int ch = 0; ch < 3; ch++)
                acc[ch] += c[ch] * band;
        }
        for (int ch = 0; ch < 3; ch++)
            row_rgb[3 * j + ch] = acc[ch];
    }
    /* Summed in a fixed order: the same tables whatever the thread count. */
    double wsum = 0.0, ssum = 0.0;
    for (uint32_t j = 0; j < H; j++) {
        float st_c = sinf(IL_PI * ((float)j + 0.5f) / (float)H);
        for (uint32_t i = 0; i < W; i++)
            wsum += w[(size_t)j * W + i];
        ssum += (double)st_c * W;
    }
    /* The floor: a fraction of the mean luminance, times sin(theta) so that
     * it is uniform over the sphere. */
    double floor_lum = ssum > 0.0 ? IL_ENV_FLOOR * wsum / ssum : 0.0;
    for (uint32_t j = 0; j < H; j++) {
        float st_c = sinf(IL_PI * ((float)j + 0.5f) / (float)H);
        for (uint32_t i = 0; i < W; i++)
            w[(size_t)j * W + i] += (float)(floor_lum * st_c);
    }
}

/* Angular map or cross: the mean radiance of the texels, each times its
 * solid angle (the Jacobian integrated over the texel by 4 x 4 midpoints;
 * for the angular map only its part inside the disk).  Exact for texels
 * taken as constant, and more accurate than the grid's supersampled means
 * when a few texels hold most of the light. */
static void texel_mean(const il_image *img, il_env_mapping m, double mean[3])
{
    const uint32_t W = img->width, H = img->height;
    const int q = 4;
    double *row = calloc((size_t)H * 3, sizeof(double));
    if (!row)
        return;   /* keeps the grid's estimate */
#pragma omp parallel for schedule(static)
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double omega = 0.0;
            for (int b = 0; b < q; b++)
                for (int a = 0; a < q; a++)
                    omega += il_envmap_jacobian(m, v2(((float)x + (a + 0.5f) / q) / (float)W,
                                                      ((float)y + (b + 0.5f) / q) / (float)H));
            omega /= (double)q * q * W * H;
            const float *p = img->rgb + 3 * ((size_t)y * W + x);
            for (int c = 0; c < 3; c++)
                row[3 * y + c] += p[c] * omega;
        }
    for (int c = 0; c < 3; c++)
        mean[c] = 0.0;
    for (uint32_t y = 0; y < H; y++)
        for (int c = 0; c < 3; c++)
            mean[c] += row[3 * y + c];
    free(row);
}

static uint32_t clamp_u32(uint32_t x, uint32_t lo, uint32_t hi) { return x < lo ? lo : (x > hi ? hi : x); }

il_status il_envmap_dist_build(il_envmap *env, il_error *err)
{
    il_envmap_dist *d = &env->dist;
    memset(d, 0, sizeof *d);
    const il_image *img = &env->img;
    uint32_t W, H;
    if (env->mapping == IL_ENV_LATLONG) {
        W = img->width;
        H = img->height;
    } else {
        /* About the map's resolution: the angular map's radius spans pi
         * (w/2 texels), a cube face pi/2 (w/3 texels). */
        uint32_t h = env->mapping == IL_ENV_ANGULAR ? img->width / 2 : 2 * (img->width / 3);
        H = clamp_u32(h, IL_ENV_GRID_MIN, IL_ENV_GRID_MAX);
        W = 2 * H;
    }
    float *w = il_malloc((size_t)W * H * sizeof(float), err);
    float *row_sum = il_malloc((size_t)H * sizeof(float), err);
    double *row_rgb = il_malloc((size_t)H * 3 * sizeof(double), err);
    d->rows = il_calloc(H, sizeof(il_distrib1d), err);
    if (!w || !row_sum || !row_rgb || !d->rows) {
        free(w);
        free(row_sum);
        free(row_rgb);
        free(d->rows);
        d->rows = NULL;
        return IL_ERR_MEMORY;
    }
    d->width = W;
    d->height = H;
    if (env->mapping == IL_ENV_LATLONG)
        weights_latlong(img, w, row_rgb);
    else
        weights_resampled(img, env->mapping, W, H, w, row_rgb);
    double mean[3] = {0, 0, 0};
    for (uint32_t j = 0; j < H; j++)
        for (int ch = 0; ch < 3; ch++)
            mean[ch] += row_rgb[3 * j + ch];
    free(row_rgb);
    if (env->mapping != IL_ENV_LATLONG)
        texel_mean(img, env->mapping, mean);
    d->mean = v3((float)(mean[0] / (4.0 * IL_PI)), (float)(mean[1] / (4.0 * IL_PI)),
                 (float)(mean[2] / (4.0 * IL_PI)));

    il_status st = IL_OK;
    for (uint32_t j = 0; j < H && st == IL_OK; j++) {
        const float *row = w + (size_t)j * W;
        double s = 0.0;
        for (uint32_t i = 0; i < W; i++)
            s += row[i];
        row_sum[j] = (float)s;
        st = il_distrib1d_init(&d->rows[j], row, W, err);
    }
    if (st == IL_OK)
        st = il_distrib1d_init(&d->marginal, row_sum, H, err);
    free(w);
    free(row_sum);
    if (st != IL_OK)
        il_envmap_dist_free(d);
    return st;
}

il_vec3 il_envmap_sample(const il_envmap *env, il_vec2 u, il_vec3 *dir, float *pdf)
{
    const il_envmap_dist *d = &env->dist;
    float pm, pc, um, uc;
    uint32_t j = il_distrib1d_sample_discrete(&d->marginal, u.y, &pm, &um);
    uint32_t i = il_distrib1d_sample_discrete(&d->rows[j], u.x, &pc, &uc);
    float fu = ((float)i + uc) / (float)d->width, fv = ((float)j + um) / (float)d->height;
    float st = sinf(IL_PI * fv);
    il_vec3 local = il_envmap_latlong_dir(fu, fv);
    *dir = il_envmap_to_world(env, local);
    float p = pm * pc * (float)d->width * (float)d->height / (2.0f * IL_PI * IL_PI * st);
    if (!(st > 0.0f) || !(p > 0.0f) || !isfinite(p)) {
        *pdf = 0.0f;
        return v3s(0.0f);
    }
    *pdf = p;
    /* A lat-long image is looked up at the point drawn (the direction's
     * own texel coordinates, up to rounding: no atan2f back). */
    if (env->mapping == IL_ENV_LATLONG)
        return il_envmap_lookup_latlong_uv(&env->img, v2(fu, fv));
    return il_envmap_lookup(&env->img, env->mapping, local);
}

/* The density at lat-long point uv of a direction whose sin(theta) is st
 * (> 0). */
static float pdf_at_uv(const il_envmap_dist *d, il_vec2 uv, float st)
{
    uint32_t i = (uint32_t)il_minf(uv.x * (float)d->width, (float)(d->width - 1));
    uint32_t j = (uint32_t)il_minf(uv.y * (float)d->height, (float)(d->height - 1));
    float pm = il_distrib1d_pmf(&d->marginal, j), pc = il_distrib1d_pmf(&d->rows[j], i);
    return pm * pc * (float)d->width * (float)d->height / (2.0f * IL_PI * IL_PI * st);
}

float il_envmap_pdf(const il_envmap *env, il_vec3 dir)
{
    il_vec3 local = il_envmap_to_local(env, dir);
    float st = sqrtf(local.x * local.x + local.z * local.z) / v3_length(dir);
    if (!(st > 0.0f))
        return 0.0f;
    return pdf_at_uv(&env->dist, il_envmap_dir_to_uv(IL_ENV_LATLONG, local), st);
}

il_vec3 il_envmap_eval_pdf(const il_envmap *env, il_vec3 dir, float *pdf)
{
    if (env->mapping != IL_ENV_LATLONG) {
        *pdf = il_envmap_pdf(env, dir);
        return il_envmap_eval(env, dir);
    }
    /* il_envmap_eval's and il_envmap_pdf's steps, sharing uv. */
    il_vec3 local = il_envmap_to_local(env, dir);
    float st = sqrtf(local.x * local.x + local.z * local.z) / v3_length(dir);
    bool lookup = v3_is_finite(local) && !v3_is_zero(local);
    if (!lookup && !(st > 0.0f)) {
        *pdf = 0.0f;
        return v3s(0.0f);
    }
    il_vec2 uv = il_envmap_dir_to_uv(IL_ENV_LATLONG, local);
    *pdf = st > 0.0f ? pdf_at_uv(&env->dist, uv, st) : 0.0f;
    return lookup ? il_envmap_lookup_latlong_uv(&env->img, uv) : v3s(0.0f);
}
