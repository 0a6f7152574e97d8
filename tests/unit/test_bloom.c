/* Bloom (src/image/bloom.c, docs/tonemapping.md#bloom): energy preserved on
 * random images and at borders and corners, nothing changes below the
 * threshold, and the glare of one bright pixel: centred on it, symmetric,
 * decreasing outwards, of the kernel's width, of the right colour, the
 * same whatever the number of threads. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "check.h"
#include "illum/illum.h"
#include "image/bloom.h"

static uint64_t rng_state = 88172645463325252ull;
static double rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static void channel_sums(const float *rgb, size_t pixels, double sum[3])
{
    sum[0] = sum[1] = sum[2] = 0.0;
    for (size_t i = 0; i < pixels; i++)
        for (int k = 0; k < 3; k++)
            sum[k] += rgb[3 * i + k];
}

/* Random HDR images: mostly dim, some bright, a few very bright spikes. */
static void test_energy_random(void)
{
    static const int sizes[][2] = {{61, 47}, {200, 130}, {1, 50}, {50, 1}, {3, 3}, {1, 1}, {257, 64}};
    static const double sigmas[] = {0.3, 2.0, 7.0, 40.0, 500.0};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++)
        for (size_t gi = 0; gi < sizeof sigmas / sizeof sigmas[0]; gi++) {
            int w = sizes[si][0], h = sizes[si][1];
            size_t n = (size_t)w * h;
            float *img = malloc(n * 3 * sizeof(float));
            for (size_t i = 0; i < n * 3; i++) {
                double u = rnd();
                img[i] = (float)(u < 0.01 ? 1e4 * rnd() : 3.0 * u * u * u);
            }
            double before[3], after[3];
            channel_sums(img, n, before);
            il_error err = {0};
            double strength = gi % 2 ? 1.0 : 0.3;
            CHECK_OK(il_bloom_apply(img, (uint32_t)w, (uint32_t)h, strength, 1.0, sigmas[gi], &err),
                     &err);
            channel_sums(img, n, after);
            int negative = 0;
            for (size_t i = 0; i < n * 3; i++)
                negative += !(img[i] >= 0.0f);
            CHECK(negative == 0);
            for (int k = 0; k < 3; k++)
                CHECK_REL(after[k], before[k], 1e-4);
            free(img);
        }
}

/* One bright pixel in a corner, on an edge, or near one: all its light stays
 * in the image, and it spreads. */
static void test_energy_borders(void)
{
    const int w = 97, h = 64;
    const int spots[][2] = {{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}, {w / 2, 0}, {0, h / 2}, {3, 2}};
    for (size_t s = 0; s < sizeof spots / sizeof spots[0]; s++)
        for (int big = 0; big < 2; big++) {
            float *img = calloc((size_t)w * h * 3, sizeof(float));
            float *p = img + 3 * ((size_t)spots[s][1] * w + spots[s][0]);
            p[0] = 500.0f, p[1] = 200.0f, p[2] = 50.0f;
            il_error err = {0};
            CHECK_OK(il_bloom_apply(img, w, h, 1.0, 1.0, big ? 60.0 : 8.0, &err), &err);
            double sum[3];
            channel_sums(img, (size_t)w * h, sum);
            CHECK_REL(sum[0], 500.0, 1e-4);
            CHECK_REL(sum[1], 200.0, 1e-4);
            CHECK_REL(sum[2], 50.0, 1e-4);
            CHECK(p[0] < 250.0f); /* most of it left the pixel */
            free(img);
        }
}

/* Everything at or below the threshold: the image is untouched, bit for bit. */
static void test_below_threshold(void)
{
    const int w = 80, h = 50;
    size_t n = (size_t)w * h * 3;
    float *img = malloc(n * sizeof(float)), *copy = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; i++)
        img[i] = (float)(0.99 * rnd());
    img[0] = img[1] = img[2] = 2.0f; /* luminance exactly 2: at the threshold */
    memcpy(copy, img, n * sizeof(float));
    il_error err = {0};
    CHECK_OK(il_bloom_apply(img, w, h, 1.0, 2.0, 10.0, &err), &err);
    CHECK(memcmp(img, copy, n * sizeof(float)) == 0);
    /* strength 0 never changes anything either */
    img[5] = 100.0f;
    memcpy(copy, img, n * sizeof(float));
    CHECK_OK(il_bloom_apply(img, w, h, 0.0, 0.5, 10.0, &err), &err);
    CHECK(memcmp(img, copy, n * sizeof(float)) == 0);
    /* ... and one pixel above it does */
    CHECK_OK(il_bloom_apply(img, w, h, 1.0, 2.0, 10.0, &err), &err);
    CHECK(memcmp(img, copy, n * sizeof(float)) != 0);
    free(img);
    free(copy);
}

/* The glare of one pixel at (cx, cy) of a w x h black image. */
typedef struct halo {
    int w, h, cx, cy;
    float *img;
    double moved;  /* the light that left the pixel */
} halo;

static halo make_halo(int w, int h, int cx, int cy, double sigma, const float color[3])
{
    halo o = {w, h, cx, cy, calloc((size_t)w * h * 3, sizeof(float)), 0.0};
    float *p = o.img + 3 * ((size_t)cy * w + cx);
    memcpy(p, color, 3 * sizeof(float));
    double lum = 0.2126 * color[0] + 0.7152 * color[1] + 0.0722 * color[2];
    const double threshold = 1.0;
    o.moved = (lum - threshold) / lum; /* fraction of each channel, strength 1 */
    il_error err = {0};
    CHECK_OK(il_bloom_apply(o.img, w, h, 1.0, threshold, sigma, &err), &err);
    /* take back what stayed in the pixel: what is left is the glare */
    for (int k = 0; k < 3; k++)
        p[k] -= (float)(color[k] * (1.0 - o.moved));
    return o;
}

static double at(const halo *o, int x, int y, int k)
{
    return o->img[3 * ((size_t)y * o->w + x) + k];
}

static void test_single_pixel(void)
{
    const double sigma = 24.0; /* levels of sigma 3, 6, 12, 24: pyramid levels 0..3 */
    il_bloom_kernel kern;
    il_bloom_kernel_make(sigma, &kern);
    CHECK(kern.res[0] == 0 && kern.res[3] == 3);
    const float white[3] = {100.0f, 100.0f, 100.0f};

    /* (a) at a pixel on the coarsest lattice (a multiple of 2^(3-1) = 4) */
    halo o = make_halo(401, 401, 200, 200, sigma, white);
    double peak = at(&o, 200, 200, 0);
    double tiny = 1e-5 * peak; /* float rounding of the passes, run in either direction */
    int asym = 0, rising = 0;
    for (int d = 1; d < 200; d++) {
        double e = at(&o, 200 + d, 200, 0), wv = at(&o, 200 - d, 200, 0);
        double s = at(&o, 200, 200 + d, 0), nv = at(&o, 200, 200 - d, 0);
        asym += fabs(e - wv) > tiny || fabs(e - s) > tiny || fabs(e - nv) > tiny;
        if (d < 140) { /* off the axes: transposed, and turned by 90 degrees */
            asym += fabs(at(&o, 200 + d, 200 + d / 2, 0) - at(&o, 200 + d / 2, 200 + d, 0)) > tiny;
            asym += fabs(at(&o, 200 + d, 200 - d / 3, 0) - at(&o, 200 + d / 3, 200 + d, 0)) > tiny;
        }
        /* non-increasing outwards along the axes and the diagonals */
        rising += e > at(&o, 200 + d - 1, 200, 0) + tiny;
        rising += wv > at(&o, 200 - d + 1, 200, 0) + tiny;
        rising += s > at(&o, 200, 200 + d - 1, 0) + tiny;
        rising += at(&o, 200 + d, 200 + d, 0) > at(&o, 200 + d - 1, 200 + d - 1, 0) + tiny;
        rising += at(&o, 200 - d, 200 + d, 0) > at(&o, 200 - d + 1, 200 + d - 1, 0) + tiny;
    }
    CHECK(asym == 0);
    CHECK(rising == 0);
    CHECK(at(&o, 200 + 24, 200, 0) < 0.1 * peak && at(&o, 200 + 24, 200, 0) > 1e-4 * peak);

    /* centroid at the pixel, energy, and the width: the variance per axis of
     * the glare is the weighted sum of the levels' variances, and close to
     * that of the nominal Gaussians (sigma/8, /4, /2, 1 with weights 1/4) */
    double sum = 0.0, mx = 0.0, my = 0.0, vx = 0.0, vy = 0.0;
    for (int y = 0; y < o.h; y++)
        for (int x = 0; x < o.w; x++) {
            double g = at(&o, x, y, 0);
            sum += g;
            mx += g * (x - 200);
            my += g * (y - 200);
            vx += g * (x - 200) * (x - 200);
            vy += g * (y - 200) * (y - 200);
        }
    CHECK_REL(sum, 100.0 * o.moved, 1e-5);
    CHECK_NEAR(mx / sum, 0.0, 1e-3);
    CHECK_NEAR(my / sum, 0.0, 1e-3);
    double expect = 0.0, nominal = 0.0;
    for (int l = 0; l < IL_BLOOM_LEVELS; l++) {
        double s = sigma * ldexp(1.0, l - (IL_BLOOM_LEVELS - 1));
        expect += kern.weight[l] * kern.variance[l];
        nominal += 0.25 * s * s;
    }
    CHECK_REL(vx / sum, expect, 0.03); /* the lattice position: the pyramid adds a bit less */
    CHECK_REL(vy / sum, vx / sum, 1e-6);
    CHECK_REL(vx / sum, nominal, 0.05);
    free(o.img);

    /* (b) at odd positions: centroid still exact, symmetric to 0.1% of the
     * halo (the pyramid's lattice shifts a little of the shape) */
    const int pos[][2] = {{201, 200}, {203, 197}, {205, 211}};
    for (size_t q = 0; q < sizeof pos / sizeof pos[0]; q++) {
        int cx = pos[q][0], cy = pos[q][1];
        halo b = make_halo(401, 401, cx, cy, sigma, white);
        double s = 0.0, bx = 0.0, by = 0.0, worst = 0.0;
        for (int y = 0; y < b.h; y++)
            for (int x = 0; x < b.w; x++) {
                double g = at(&b, x, y, 0);
                s += g;
                bx += g * (x - cx);
                by += g * (y - cy);
            }
        CHECK_NEAR(bx / s, 0.0, 1e-3);
        CHECK_NEAR(by / s, 0.0, 1e-3);
        for (int d = 1; d <= 72; d++) {
            double e = at(&b, cx + d, cy, 0), wv = at(&b, cx - d, cy, 0);
            double rel = fabs(e - wv) / (e + wv);
            if (rel > worst)
                worst = rel;
        }
        CHECK(worst < 1e-3);
        free(b.img);
    }

    /* (c) colour: the glare has the source's hue everywhere */
    const float orange[3] = {40.0f, 20.0f, 5.0f};
    halo c = make_halo(201, 151, 100, 75, 10.0, orange);
    int off = 0;
    for (int y = 0; y < c.h; y += 3)
        for (int x = 0; x < c.w; x += 3) {
            double r = at(&c, x, y, 0), g = at(&c, x, y, 1), b = at(&c, x, y, 2);
            if (r > 1e-6 * at(&c, 100, 75, 0))
                off += fabs(g / r - 0.5) > 1e-4 || fabs(b / r - 0.125) > 1e-4;
        }
    CHECK(off == 0);
    free(c.img);
}

/* The levels of the kernel: near their nominal variance, coarser for wider
 * Gaussians, never below IL_BLOOM_MIN_SIGMA pixels of their level. */
static void test_kernel(void)
{
    static const double sigmas[] = {3.0, 10.0, 44.0, 200.0, 3000.0};
    for (size_t i = 0; i < sizeof sigmas / sizeof sigmas[0]; i++) {
        il_bloom_kernel k;
        il_bloom_kernel_make(sigmas[i], &k);
        double wsum = 0.0;
        for (int l = 0; l < IL_BLOOM_LEVELS; l++) {
            double s = sigmas[i] * ldexp(1.0, l - (IL_BLOOM_LEVELS - 1));
            if (s >= 2.0)
                CHECK_REL(k.variance[l], s * s, 0.08);
            if (l > 0)
                CHECK(k.res[l] >= k.res[l - 1] && k.variance[l] > k.variance[l - 1]);
            if (k.res[l] > 0)
                CHECK(s / ldexp(1.0, k.res[l]) >= IL_BLOOM_MIN_SIGMA);
            wsum += k.weight[l];
        }
        CHECK_NEAR(wsum, 1.0, 1e-12);
    }
    il_bloom_kernel k;
    il_bloom_kernel_make(0.0, &k);
    CHECK(k.variance[IL_BLOOM_LEVELS - 1] == 0.0);
}

/* One thread or two: the same bytes. */
static void test_threads(void)
{
#ifdef _OPENMP
    const int w = 150, h = 97;
    size_t n = (size_t)w * h * 3;
    float *a = malloc(n * sizeof(float)), *b = malloc(n * sizeof(float));
    for (size_t i = 0; i < n; i++)
        a[i] = (float)(rnd() < 0.02 ? 100.0 * rnd() : rnd());
    memcpy(b, a, n * sizeof(float));
    il_error err = {0};
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    CHECK_OK(il_bloom_apply(a, w, h, 0.5, 1.0, 30.0, &err), &err);
    omp_set_num_threads(3);
    CHECK_OK(il_bloom_apply(b, w, h, 0.5, 1.0, 30.0, &err), &err);
    omp_set_num_threads(saved);
    CHECK(memcmp(a, b, n * sizeof(float)) == 0);
    free(a);
    free(b);
#endif
}

static void test_invalid(void)
{
    float px[3] = {5, 5, 5};
    il_error err = {0};
    CHECK(il_bloom_apply(NULL, 1, 1, 0.5, 1.0, 1.0, &err) == IL_ERR_INVALID);
    CHECK(il_bloom_apply(px, 0, 1, 0.5, 1.0, 1.0, &err) == IL_ERR_INVALID);
    CHECK(il_bloom_apply(px, 1, 1, 1.5, 1.0, 1.0, &err) == IL_ERR_INVALID);
    CHECK(il_bloom_apply(px, 1, 1, 0.5, 0.0, 1.0, &err) == IL_ERR_INVALID);
    CHECK(il_bloom_apply(px, 1, 1, 0.5, 1.0, NAN, &err) == IL_ERR_INVALID);
    CHECK(il_bloom_apply(px, 1, 1, 0.5, 1.0, -1.0, &err) == IL_ERR_INVALID);
    CHECK(px[0] == 5.0f);
}

int main(void)
{
    test_energy_random();
    test_energy_borders();
    test_below_threshold();
    test_single_pixel();
    test_kernel();
    test_threads();
    test_invalid();
    return check_report();
}
