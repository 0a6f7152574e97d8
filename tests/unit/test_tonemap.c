/* Tone mapping (docs/tonemapping.md): every operator against values worked
 * out by hand from its formula, monotonicity, the PNG bytes of the old
 * linear path, Reinhard's white point, the ACES fit at known points, auto
 * exposure at its percentile, and NaN/Inf/huge/negative input. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"
#include "image/srgb.h"
#include "image/tonemap.h"

/* A 1 x n image of grey pixels. */
static il_image greys(const double *v, uint32_t n)
{
    il_image img = {0};
    il_error err = {0};
    il_image_alloc(&img, n, 1, &err);
    for (uint32_t i = 0; i < n; i++)
        img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = (float)v[i];
    return img;
}

/* The display value (channel 0) of grey v under desc. */
static double map1(double v, const il_tonemap_desc *desc)
{
    il_image in = greys(&v, 1), out = {0};
    il_error err = {0};
    double r = -1.0;
    if (il_tonemap(&in, desc, &out, &err) == IL_OK)
        r = out.rgb[0];
    else
        fprintf(stderr, "il_tonemap: %s\n", err.message);
    il_image_free(&in);
    il_image_free(&out);
    return r;
}

/* sRGB decoding by hand (IEC 61966-2-1), to read display values back. */
static double srgb_decode(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* Expected values below: worked out from each formula with a calculator. */
static void test_linear_and_gamma(void)
{
    il_tonemap_desc lin = {.op = IL_TONEMAP_LINEAR};
    /* sRGB(0.5) = 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357 */
    CHECK_NEAR(map1(0.5, &lin), 0.7353570, 1e-6);
    CHECK_NEAR(map1(0.5, NULL), 0.7353570, 1e-6);   /* NULL: linear, EV 0 */
    CHECK_NEAR(map1(0.002, &lin), 0.02584, 1e-6);   /* the linear toe: 12.92 v */
    CHECK(map1(2.0, &lin) == 1.0);                  /* clamped */
    CHECK(map1(-1.0, &lin) == 0.0);
    lin.exposure = 1.0f;                            /* 0.25 * 2^1 = 0.5 */
    CHECK_NEAR(map1(0.25, &lin), 0.7353570, 1e-6);
    lin.exposure = -2.0f;                           /* 2 * 2^-2 = 0.5 */
    CHECK_NEAR(map1(2.0, &lin), 0.7353570, 1e-6);

    il_tonemap_desc gam = {.op = IL_TONEMAP_GAMMA}; /* gamma 0 means 2.2 */
    CHECK_NEAR(map1(0.5, &gam), 0.7297401, 1e-6);   /* 0.5^(1/2.2) */
    gam.gamma = 1.8f;
    CHECK_NEAR(map1(0.5, &gam), 0.6803950, 1e-6);   /* 0.5^(1/1.8) */
    gam.gamma = 1.0f;
    CHECK_NEAR(map1(0.3, &gam), 0.3, 1e-6);         /* the identity */
    CHECK(map1(5.0, &gam) == 1.0);
    CHECK(map1(0.002, &gam) != map1(0.002, &lin));  /* no linear toe */
}

static void test_reinhard(void)
{
    il_tonemap_desc r = {.op = IL_TONEMAP_REINHARD, .white = 4.0f};
    /* L = 1, L_white = 4: L_d = 1 (1 + 1/16) / 2 = 0.53125 -> sRGB 0.755576 */
    CHECK_NEAR(map1(1.0, &r), 0.7555759, 1e-6);
    /* The white point maps to 1 exactly; above it, clamped white. */
    CHECK_NEAR(map1(4.0, &r), 1.0, 1e-6);
    CHECK(map1(9.0, &r) == 1.0);
    /* Small values map to about L: L_d = L (1 + L/16) / (1 + L) = 0.000999 for L = 1e-3. */
    double small = srgb_decode(map1(1e-3, &r));
    CHECK_REL(small, 1e-3 * (1.0 + 1e-3 / 16.0) / (1.0 + 1e-3), 1e-4);
    CHECK_REL(small, 1e-3, 2e-3);

    /* White 0: the image's largest luminance (7) maps to 1. */
    double v[3] = {0.1, 1.0, 7.0};
    il_image in = greys(v, 3), out = {0};
    il_error err = {0};
    il_tonemap_desc r0 = {.op = IL_TONEMAP_REINHARD};
    CHECK_OK(il_tonemap(&in, &r0, &out, &err), &err);
    if (out.rgb) {
        CHECK_NEAR(out.rgb[6], 1.0, 1e-6);
        /* L = 1, L_white = 7: (1 + 1/49)/2 = 0.510204 -> sRGB 0.742038 */
        CHECK_NEAR(out.rgb[3], 0.7420381, 1e-6);
    }
    il_image_free(&out);
    /* ... after the exposure: EV 1 makes the largest 14, still mapped to 1,
     * and 1 becomes 2: 2 (1 + 2/196) / 3 = 0.673469. */
    r0.exposure = 1.0f;
    CHECK_OK(il_tonemap(&in, &r0, &out, &err), &err);
    if (out.rgb) {
        CHECK_NEAR(out.rgb[6], 1.0, 1e-6);
        CHECK_NEAR(srgb_decode(out.rgb[3]), 2.0 * (1.0 + 2.0 / 196.0) / 3.0, 1e-5);
    }
    il_image_free(&out);
    il_image_free(&in);

    /* Colour keeps its ratios (the operator scales luminance): (0.4, 0.2, 0.1)
     * with a large white point. */
    il_image c = {0};
    il_image_alloc(&c, 1, 1, &err);
    c.rgb[0] = 0.4f, c.rgb[1] = 0.2f, c.rgb[2] = 0.1f;
    il_tonemap_desc rw = {.op = IL_TONEMAP_REINHARD, .white = 1000.0f};
    CHECK_OK(il_tonemap(&c, &rw, &out, &err), &err);
    if (out.rgb) {
        double a = srgb_decode(out.rgb[0]), b = srgb_decode(out.rgb[1]),
               d = srgb_decode(out.rgb[2]);
        CHECK_REL(a / b, 2.0, 1e-4);
        CHECK_REL(b / d, 2.0, 1e-4);
        double lum = 0.2126 * 0.4 + 0.7152 * 0.2 + 0.0722 * 0.1;
        CHECK_REL(a, 0.4 * (1.0 + lum / 1e6) / (1.0 + lum), 1e-4);
    }
    il_image_free(&out);
    il_image_free(&c);
}

static void test_filmic(void)
{
    il_tonemap_desc f = {.op = IL_TONEMAP_FILMIC};
    /* x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14):
     * x = 1: 2.54 / 3.16 = 0.803797 -> sRGB 0.908230
     * x = 0.18: 0.0867240 / 0.3249320 = 0.266899 -> sRGB 0.553458
     * x = 4: 40.28 / 41.38 = 0.973417 -> sRGB 0.988223 */
    CHECK_NEAR(srgb_decode(map1(1.0, &f)), 0.8037975, 1e-5);
    CHECK_NEAR(map1(1.0, &f), 0.9082305, 1e-5);
    CHECK_NEAR(srgb_decode(map1(0.18, &f)), 0.2668989, 1e-5);
    CHECK_NEAR(map1(0.18, &f), 0.5534576, 1e-5);
    CHECK_NEAR(map1(4.0, &f), 0.9882227, 1e-5);
    CHECK(map1(0.0, &f) == 0.0);
    CHECK(map1(1e6, &f) == 1.0); /* the curve tends to 2.51/2.43 > 1: clamped */
    CHECK(map1(1e30, &f) == 1.0);
}

/* Every operator is non-decreasing in the input and stays in [0, 1]. */
static void test_monotonic(void)
{
    enum { N = 400 };
    double v[N];
    for (int i = 0; i < N; i++)
        v[i] = i == 0 ? 0.0 : 1e-5 * pow(10.0, 10.0 * i / N); /* 1e-5 .. 1e5 */
    il_image in = greys(v, N);
    for (int op = IL_TONEMAP_LINEAR; op <= IL_TONEMAP_FILMIC; op++) {
        for (int expo = 0; expo < 2; expo++) {
            il_tonemap_desc d = {.op = (il_tonemap_op)op, .exposure = expo ? -3.0f : 0.0f,
                                 .white = op == IL_TONEMAP_REINHARD ? 50.0f : 0.0f};
            il_image out = {0};
            il_error err = {0};
            CHECK_OK(il_tonemap(&in, &d, &out, &err), &err);
            if (!out.rgb)
                continue;
            int bad = 0, rising = 0;
            for (int i = 0; i < N; i++) {
                float y = out.rgb[3 * i];
                bad += !(y >= 0.0f && y <= 1.0f);
                if (i > 0) {
                    bad += y < out.rgb[3 * (i - 1)];
                    rising += y > out.rgb[3 * (i - 1)];
                }
            }
            CHECK(bad == 0);
            CHECK(rising > N / 4);
            CHECK(out.rgb[0] == 0.0f && out.rgb[3 * (N - 1)] == 1.0f);
            il_image_free(&out);
        }
    }
    il_image_free(&in);
}

/* The PNG writer: a NULL tonemap desc keeps the old transfer bit for bit
 * (value * 2^exposure, non-finite channels 0, clamp, sRGB, round), and the
 * linear operator gives the same bytes. */
static unsigned char old_code(float v, double exposure)
{
    if (!isfinite(v))
        return 0;
    double x = v * (exposure != 0.0 ? exp2(exposure) : 1.0);
    if (!(x > 0.0))
        return 0;
    if (x >= 1.0)
        return 255;
    double s = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
    return (unsigned char)lrint(s * 255.0);
}

static bool read_file(const char *path, unsigned char **data, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    *data = malloc(n > 0 ? (size_t)n : 1);
    *size = *data ? fread(*data, 1, (size_t)n, f) : 0;
    fclose(f);
    return *data && *size == (size_t)n;
}

static bool same_file(const char *a, const char *b)
{
    unsigned char *da = NULL, *db = NULL;
    size_t na = 0, nb = 0;
    bool same = read_file(a, &da, &na) && read_file(b, &db, &nb) && na == nb &&
                memcmp(da, db, na) == 0;
    free(da);
    free(db);
    return same;
}

/* The codes of a PNG, recovered from il_image_read's decoded values. */
static int codes_match(const char *path, const il_image *src, double exposure)
{
    float lut[256];
    for (int k = 0; k < 256; k++)
        lut[k] = (float)il_srgb_to_linear(k / 255.0);
    il_image back = {0};
    il_error err = {0};
    if (il_image_read(path, &back, &err) != IL_OK)
        return -1;
    int wrong = 0;
    size_t n = (size_t)src->width * src->height * 3;
    for (size_t i = 0; i < n; i++) {
        int code = -1;
        for (int k = 0; k < 256 && code < 0; k++)
            if (back.rgb[i] == lut[k])
                code = k;
        wrong += code != old_code(src->rgb[i], exposure);
    }
    il_image_free(&back);
    return wrong;
}

static void test_png_bytes(void)
{
    const char *dir = check_tmp_dir();
    char p_null[512], p_lin[512], p_exp[512], p_linexp[512];
    snprintf(p_null, sizeof p_null, "%s/tm_null.png", dir);
    snprintf(p_lin, sizeof p_lin, "%s/tm_linear.png", dir);
    snprintf(p_exp, sizeof p_exp, "%s/tm_null_exp.png", dir);
    snprintf(p_linexp, sizeof p_linexp, "%s/tm_linear_exp.png", dir);

    /* Random values over the whole code range, the neighbours of every code
     * boundary, negatives and values above 1. */
    const uint32_t w = 256, h = 64;
    il_image img = {0};
    il_error err = {0};
    il_image_alloc(&img, w, h, &err);
    uint64_t s = 12345;
    for (size_t i = 0; i < (size_t)w * h * 3; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double u = (double)(s >> 11) / 9007199254740992.0;
        img.rgb[i] = (float)(u * u * 1.2 - 0.05);
    }
    for (int k = 0; k < 255; k++) { /* the value between codes k and k+1, +-2 ulps */
        float b = (float)srgb_decode((k + 0.5) / 255.0);
        float *p = img.rgb + 5 * k;
        p[0] = nextafterf(nextafterf(b, 0.0f), 0.0f);
        p[1] = nextafterf(b, 0.0f);
        p[2] = b;
        p[3] = nextafterf(b, 2.0f);
        p[4] = nextafterf(nextafterf(b, 2.0f), 2.0f);
    }
    CHECK_OK(il_image_write(&img, p_null, NULL, &err), &err);
    CHECK(codes_match(p_null, &img, 0.0) == 0);
    il_tonemap_desc lin = {.op = IL_TONEMAP_LINEAR};
    il_write_desc wd = {.tonemap = &lin};
    CHECK_OK(il_image_write(&img, p_lin, &wd, &err), &err);
    CHECK(same_file(p_null, p_lin));

    /* With an exposure: write.exposure (NULL tonemap) and the linear
     * operator's exposure agree, and write.exposure is ignored with a desc. */
    il_write_desc we = {.exposure = 1.5f};
    CHECK_OK(il_image_write(&img, p_exp, &we, &err), &err);
    CHECK(codes_match(p_exp, &img, 1.5) == 0);
    lin.exposure = 1.5f;
    il_write_desc wle = {.exposure = 7.0f, .tonemap = &lin};
    CHECK_OK(il_image_write(&img, p_linexp, &wle, &err), &err);
    CHECK(same_file(p_exp, p_linexp));
    CHECK(!same_file(p_null, p_exp));

    /* Each operator's codes are round(255 v) of il_tonemap's float values. */
    for (int op = IL_TONEMAP_LINEAR; op <= IL_TONEMAP_FILMIC; op++) {
        il_tonemap_desc d = {.op = (il_tonemap_op)op, .exposure = 0.5f};
        il_write_desc wop = {.tonemap = &d};
        CHECK_OK(il_image_write(&img, p_lin, &wop, &err), &err);
        il_image disp = {0}, back = {0};
        CHECK_OK(il_tonemap(&img, &d, &disp, &err), &err);
        CHECK_OK(il_image_read(p_lin, &back, &err), &err);
        int off = 0;
        for (size_t i = 0; back.rgb && disp.rgb && i < (size_t)w * h * 3; i++) {
            double code = il_linear_to_srgb(back.rgb[i]) * 255.0;
            off += fabs(code - disp.rgb[i] * 255.0) > 0.5 + 1e-3;
        }
        CHECK(back.rgb && off == 0);
        il_image_free(&disp);
        il_image_free(&back);
    }
    il_image_free(&img);
}

/* The old path zeroes a non-finite channel; the operators blacken the pixel. */
static void test_png_nonfinite(void)
{
    const char *dir = check_tmp_dir();
    char a[512], b[512];
    snprintf(a, sizeof a, "%s/tm_nan_old.png", dir);
    snprintf(b, sizeof b, "%s/tm_nan_op.png", dir);
    il_image img = {0};
    il_error err = {0};
    il_image_alloc(&img, 2, 1, &err);
    img.rgb[0] = NAN, img.rgb[1] = 0.5f, img.rgb[2] = 0.5f;
    img.rgb[3] = 0.5f, img.rgb[4] = 0.5f, img.rgb[5] = 0.5f;
    il_tonemap_desc lin = {0};
    il_write_desc wd = {.tonemap = &lin};
    CHECK_OK(il_image_write(&img, a, NULL, &err), &err);
    CHECK_OK(il_image_write(&img, b, &wd, &err), &err);
    il_image ra = {0}, rb = {0};
    CHECK_OK(il_image_read(a, &ra, &err), &err);
    CHECK_OK(il_image_read(b, &rb, &err), &err);
    if (ra.rgb && rb.rgb) {
        CHECK(ra.rgb[0] == 0.0f && ra.rgb[1] > 0.2f); /* old: that channel only */
        CHECK(rb.rgb[0] == 0.0f && rb.rgb[1] == 0.0f && rb.rgb[2] == 0.0f);
        CHECK(rb.rgb[3] == ra.rgb[3]);
    }
    il_image_free(&ra);
    il_image_free(&rb);
    il_image_free(&img);
}

/* Auto exposure: the luminance at the percentile maps to 1; black pixels do
 * not count. */
static void test_auto_exposure(void)
{
    /* 100 greys of luminance 1..100 and 50 black pixels. */
    double v[150];
    for (int i = 0; i < 150; i++)
        v[i] = i < 100 ? i + 1 : 0.0;
    il_image in = greys(v, 150), out = {0};
    il_error err = {0};
    /* nearest rank: ceil(0.99 * 100) = 99th value; with the blacks it would be
     * ceil(0.99 * 150) = 149th, i.e. 99 as well, so also check 50%: 50 vs 25. */
    CHECK_NEAR(il_luminance_percentile(&in, 99.0), 99.0, 1e-4);
    CHECK_NEAR(il_luminance_percentile(&in, 50.0), 50.0, 1e-4);
    CHECK_NEAR(il_luminance_percentile(&in, 100.0), 100.0, 1e-4);
    CHECK_NEAR(il_luminance_percentile(&in, 0.5), 1.0, 1e-4);
    CHECK_NEAR(il_luminance_percentile(&in, 1.5), 2.0, 1e-4);

    il_tonemap_desc d = {.op = IL_TONEMAP_GAMMA, .gamma = 1.0f, .auto_exposure = true};
    CHECK_OK(il_tonemap(&in, &d, &out, &err), &err); /* default 99 */
    if (out.rgb) {
        CHECK_NEAR(out.rgb[3 * 98], 1.0, 1e-6);             /* luminance 99 */
        CHECK_NEAR(out.rgb[3 * 97], 98.0 / 99.0, 1e-6);
        CHECK_NEAR(out.rgb[3 * 49], 50.0 / 99.0, 1e-6);
        CHECK(out.rgb[3 * 120] == 0.0f);
    }
    il_image_free(&out);
    d.auto_percentile = 50.0f;
    d.exposure = -1.0f; /* adds: 50 maps to 1/2 */
    CHECK_OK(il_tonemap(&in, &d, &out, &err), &err);
    if (out.rgb) {
        CHECK_NEAR(out.rgb[3 * 49], 0.5, 1e-6);
        CHECK_NEAR(out.rgb[3 * 24], 0.25, 1e-6);
    }
    il_image_free(&out);
    il_image_free(&in);

    /* A colour image: the percentile is of luminance. */
    il_image c = {0};
    il_image_alloc(&c, 3, 1, &err);
    float px[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}; /* luminances 0.2126, 0.7152, 0.0722 */
    memcpy(c.rgb, px, sizeof px);
    CHECK_NEAR(il_luminance_percentile(&c, 50.0), 0.2126, 1e-6);
    CHECK_NEAR(il_luminance_percentile(&c, 100.0), 0.7152, 1e-6);
    il_image_free(&c);

    /* All black: no exposure change, black out, no failure. */
    double z[4] = {0, 0, 0, 0};
    il_image black = greys(z, 4);
    CHECK(il_luminance_percentile(&black, 99.0) == 0.0);
    il_tonemap_desc a = {.auto_exposure = true};
    CHECK_OK(il_tonemap(&black, &a, &out, &err), &err);
    CHECK(out.rgb && out.rgb[0] == 0.0f);
    il_image_free(&out);
    il_image_free(&black);
}

/* NaN, Inf, huge and negative values: black (or clamped), never NaN out. */
static void test_nonfinite(void)
{
    const float vals[] = {NAN, INFINITY, -INFINITY, 3e38f, -5.0f, 1e-40f, 0.5f, 20.0f};
    const int nv = (int)(sizeof vals / sizeof vals[0]);
    il_image img = {0};
    il_error err = {0};
    il_image_alloc(&img, (uint32_t)(nv * nv), 3, &err);
    for (uint32_t y = 0; y < 3; y++)
        for (int i = 0; i < nv * nv; i++) {
            float *p = img.rgb + 3 * ((size_t)y * nv * nv + i);
            p[0] = vals[i % nv];
            p[1] = vals[(i / nv) % nv];
            p[2] = vals[(i + y) % nv];
        }
    for (int op = IL_TONEMAP_LINEAR; op <= IL_TONEMAP_FILMIC; op++)
        for (int variant = 0; variant < 4; variant++) {
            il_tonemap_desc d = {.op = (il_tonemap_op)op,
                                 .auto_exposure = variant & 1,
                                 .bloom = variant & 2 ? 0.5f : 0.0f,
                                 .exposure = variant == 3 ? 40.0f : 0.0f};
            il_image out = {0};
            CHECK_OK(il_tonemap(&img, &d, &out, &err), &err);
            if (!out.rgb)
                continue;
            int bad = 0;
            for (size_t i = 0; i < (size_t)img.width * img.height * 3; i++)
                bad += !(out.rgb[i] >= 0.0f && out.rgb[i] <= 1.0f);
            CHECK(bad == 0);
            /* pixel 0 is (NaN, NaN, NaN) and pixel 1 (Inf, NaN, ...): black
             * (without bloom: with it, glare from the neighbours lands there) */
            if (d.bloom == 0.0f)
                CHECK(out.rgb[0] == 0.0f && out.rgb[3] == 0.0f && out.rgb[4] == 0.0f);
            il_image_free(&out);
        }
    il_image_free(&img);
}

/* Bad settings are IL_ERR_INVALID, and a PNG write with them leaves no file. */
static void test_invalid(void)
{
    double v = 1.0;
    il_image in = greys(&v, 1), out = {0};
    il_error err = {0};
    il_tonemap_desc bad[] = {
        {.op = (il_tonemap_op)7},
        {.exposure = NAN},
        {.exposure = 200.0f},
        {.auto_exposure = true, .auto_percentile = 101.0f},
        {.auto_percentile = -1.0f},
        {.op = IL_TONEMAP_GAMMA, .gamma = -2.0f},
        {.white = -1.0f},
        {.white = INFINITY},
        {.bloom = 1.5f},
        {.bloom = -0.1f},
        {.bloom = 0.5f, .bloom_threshold = -1.0f},
        {.bloom = 0.5f, .bloom_radius = 2.0f},
        {.bloom = NAN},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        CHECK(il_tonemap(&in, &bad[i], &out, &err) == IL_ERR_INVALID);
        CHECK(out.rgb == NULL);
    }
    CHECK(il_tonemap(NULL, NULL, &out, &err) == IL_ERR_INVALID);
    CHECK(il_tonemap(&in, NULL, NULL, &err) == IL_ERR_INVALID);
    il_image empty = {0};
    CHECK(il_tonemap(&empty, NULL, &out, &err) == IL_ERR_INVALID);

    char path[512];
    snprintf(path, sizeof path, "%s/tm_bad.png", check_tmp_dir());
    remove(path);
    il_write_desc wd = {.tonemap = &bad[8]};
    CHECK(il_image_write(&in, path, &wd, &err) == IL_ERR_INVALID);
    FILE *f = fopen(path, "rb");
    CHECK(f == NULL);
    if (f)
        fclose(f);
    /* EXR/HDR/PFM ignore the tone mapping (radiance out). */
    char pfm[512];
    snprintf(pfm, sizeof pfm, "%s/tm_radiance.pfm", check_tmp_dir());
    il_tonemap_desc filmic = {.op = IL_TONEMAP_FILMIC, .exposure = 3.0f};
    il_write_desc wf = {.tonemap = &filmic};
    CHECK_OK(il_image_write(&in, pfm, &wf, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(pfm, &back, &err), &err);
    CHECK(back.rgb && back.rgb[0] == 1.0f);
    il_image_free(&back);
    il_image_free(&in);
}

/* out may be the input itself. */
static void test_in_place(void)
{
    double v[2] = {0.5, 4.0};
    il_image img = greys(v, 2);
    il_error err = {0};
    il_tonemap_desc d = {.op = IL_TONEMAP_LINEAR};
    CHECK_OK(il_tonemap(&img, &d, &img, &err), &err);
    CHECK(img.rgb && img.width == 2);
    if (img.rgb) {
        CHECK_NEAR(img.rgb[0], 0.7353570, 1e-6);
        CHECK(img.rgb[3] == 1.0f);
    }
    il_image_free(&img);
}

/* Bloom through il_tonemap keeps the light: with the gamma-1 operator and
 * everything well below 1 after the glare, display values are the bloomed
 * radiance, whose sum is the input's. */
static void test_bloom_through_tonemap(void)
{
    il_image img = {0};
    il_error err = {0};
    il_image_alloc(&img, 64, 48, &err);
    for (size_t i = 0; i < 64 * 48 * 3; i++)
        img.rgb[i] = 0.01f;
    float *p = img.rgb + 3 * (20 * 64 + 30);
    p[0] = p[1] = p[2] = 0.5f; /* luminance 0.5: above a threshold of 0.1 */
    il_tonemap_desc d = {.op = IL_TONEMAP_GAMMA, .gamma = 1.0f, .bloom = 0.8f,
                         .bloom_threshold = 0.1f, .bloom_radius = 0.05f};
    il_image out = {0};
    CHECK_OK(il_tonemap(&img, &d, &out, &err), &err);
    if (out.rgb) {
        double sum_in = 0.0, sum_out = 0.0;
        for (size_t i = 0; i < 64 * 48 * 3; i++) {
            sum_in += img.rgb[i];
            sum_out += out.rgb[i];
        }
        CHECK_REL(sum_out, sum_in, 1e-5);
        /* 0.8 * (0.5 - 0.1)/0.5 = 64% of the pixel left it (some comes back). */
        CHECK(out.rgb[3 * (20 * 64 + 30)] < 0.3f);
        CHECK(out.rgb[3 * (20 * 64 + 33)] > 0.0101f); /* glare 3 pixels away */
    }
    il_image_free(&out);
    il_image_free(&img);
}

int main(void)
{
    test_linear_and_gamma();
    test_reinhard();
    test_filmic();
    test_monotonic();
    test_png_bytes();
    test_png_nonfinite();
    test_auto_exposure();
    test_nonfinite();
    test_invalid();
    test_in_place();
    test_bloom_through_tonemap();
    return check_report();
}
