/* Image files: round trips of every writer through the readers (EXR float
 * bit-exact, EXR half within half precision, HDR within RGBE precision, PFM
 * bit-exact, PNG exact on sRGB code values), files from other writers (stb's
 * PNG/JPEG, tiled / grey / uint EXR through the OpenEXR C API), and bad input:
 * truncated and corrupted files of every format, missing files, unknown
 * extensions, and writes that fail without leaving any file behind. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include <OpenEXR/openexr.h>
#include <stb/stb_image_write.h>

#include "check.h"
#include "illum/illum.h"

static char dir[768];

static const char *tmp_path(char *buf, const char *name)
{
    snprintf(buf, 1100, "%s/%s", dir, name);
    return buf;
}

static bool file_exists(const char *path)
{
    return access(path, F_OK) == 0;
}

/* Number of files in our scratch directory whose name contains `part`. */
static int count_files(const char *part)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        n += strstr(e->d_name, part) != NULL;
    closedir(d);
    return n;
}

static unsigned char *load(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *data = malloc(n > 0 ? (size_t)n : 1);
    *size = fread(data, 1, (size_t)n, f);
    fclose(f);
    return data;
}

static void save(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return;
    fwrite(data, 1, size, f);
    fclose(f);
}

static il_image alloc_image(uint32_t w, uint32_t h)
{
    il_image im = {0};
    il_error err = {0};
    CHECK_OK(il_image_alloc(&im, w, h, &err), &err);
    return im;
}

/* Values spanning 1e-3 .. 1e4 (and some zeros), different per channel. */
static il_image hdr_pattern(uint32_t w, uint32_t h)
{
    il_image im = alloc_image(w, h);
    size_t n = (size_t)w * h * 3;
    for (size_t i = 0; i < n; i++) {
        double t = (double)((i * 7919) % n) / (double)(n - 1); /* scrambled 0..1 */
        im.rgb[i] = (float)pow(10.0, -3.0 + 7.0 * t);
        if (i % 17 == 5)
            im.rgb[i] = 0.0f;
    }
    return im;
}

static double max3(const float *p)
{
    return fmax(p[0], fmax(p[1], p[2]));
}

static bool same_bits(const il_image *a, const il_image *b)
{
    return a->width == b->width && a->height == b->height &&
           memcmp(a->rgb, b->rgb, (size_t)a->width * a->height * 3 * sizeof(float)) == 0;
}

/* ------------------------------------------------------------ round trips */

static void test_exr_float_exact(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = hdr_pattern(37, 21); /* 21 rows: the last ZIP chunk is short */
    im.rgb[0] = -2.5f;                 /* negatives and tiny values survive too */
    im.rgb[1] = 1e-30f;
    im.rgb[2] = 3.0e38f;
    il_write_desc wd = {.exr_precision = IL_EXR_FLOAT};
    CHECK_OK(il_image_write(&im, tmp_path(p, "float.exr"), &wd, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    CHECK(same_bits(&im, &back));
    il_image_free(&back);
    il_image_free(&im);
}

/* A ZIP chunk whose compressed size equals its raw size must be stored raw
 * (readers take it as raw): the OpenEXR Core library kept the zlib bytes
 * there until 2026 (openexr issue #2306) and the chunk read back as
 * garbage; src/image/exr.c stores it raw.  One 32x16 chunk is 6144 raw
 * bytes in float, 3072 in half; m of its pixels hold random values that
 * the precision stores exactly (28-bit float patterns, or any finite
 * normal half) and the rest 1.0, so the compressed size climbs 6-12 bytes
 * per m through the raw size near m = 500.  With the library's compressor
 * alone, 3 of the 480 float images and 6 of the 1920 half ones came back
 * wrong (Debian 12's OpenEXR 3.1.5 and zlib, 2026-11-28). */
static float random_value(uint32_t r, il_exr_precision precision)
{
    if (precision == IL_EXR_FLOAT) {
        uint32_t bits = 0x30000000u | (r >> 4); /* exponent 96..127: finite */
        float v;
        memcpy(&v, &bits, sizeof v);
        return v;
    }
    r ^= r >> 16;                              /* the LCG's low bits repeat: mix */
    r *= 0x7feb352du;
    r ^= r >> 15;
    r *= 0x846ca68bu;
    r ^= r >> 16;
    int e = 1 + (int)((r >> 10) % 30u);        /* half exponent 1..30: normal */
    float v = ldexpf(1.0f + (float)(r & 1023u) / 1024.0f, e - 15);
    return (r >> 31) ? -v : v;
}

static void test_exr_incompressible_chunks(void)
{
    char p[1100];
    il_error err = {0};
    for (int prec = 0; prec < 2; prec++) {
        il_exr_precision precision = prec ? IL_EXR_HALF : IL_EXR_FLOAT;
        uint32_t state = 12345u, wrong = 0;
        uint32_t seeds = prec ? 64u : 16u;
        for (uint32_t seed = 0; seed < seeds; seed++) {
            /* the crossing: near m = 505 in float, 500 in half (of 512) */
            for (uint32_t m = prec ? 483u : 490u, end = m + 30u; m < end; m++) {
                il_image im = {0};
                CHECK_OK(il_image_alloc(&im, 32, 16, &err), &err);
                for (uint32_t i = 0; i < 32u * 16u * 3u; i++) {
                    im.rgb[i] = 1.0f;
                    if (i / 3u < m) {
                        state = state * 1664525u + 1013904223u + seed;
                        im.rgb[i] = random_value(state, precision);
                    }
                }
                il_write_desc wd = {.exr_precision = precision};
                CHECK_OK(il_image_write(&im, tmp_path(p, "incompressible.exr"), &wd, &err), &err);
                il_image back = {0};
                CHECK_OK(il_image_read(p, &back, &err), &err);
                wrong += !same_bits(&im, &back);
                il_image_free(&back);
                il_image_free(&im);
            }
        }
        CHECK(wrong == 0);
        if (wrong > 0)
            fprintf(stderr, "%u of %u %s EXR chunks near their raw size read back wrong\n", wrong,
                    30u * seeds, prec ? "half" : "float");
    }
}

static void test_exr_half(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = hdr_pattern(40, 33);
    /* Default precision is half. */
    CHECK_OK(il_image_write(&im, tmp_path(p, "half.EXR"), NULL, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    CHECK(back.width == 40 && back.height == 33);
    if (back.rgb) {
        /* Round to nearest half: relative error <= 2^-11 for normal halves
         * (>= 2^-14 ~ 6.1e-5; all values here are 0 or >= 1e-3). */
        int bad = 0;
        for (size_t i = 0; i < 40 * 33 * 3; i++)
            bad += !(fabs(back.rgb[i] - im.rgb[i]) <= ldexp(1.0, -11) * fabs(im.rgb[i]));
        CHECK(bad == 0);
        CHECK(back.rgb[5] == 0.0f); /* zeros stay zero (index 5: i % 17 == 5) */
    }
    il_image_free(&back);
    il_image_free(&im);
}

/* A half holds up to 65504: brighter values (the sun seen by the camera)
 * are written as +-65504, not as infinity; the image itself is untouched,
 * and a float EXR keeps them. */
static void test_exr_half_clamp(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = {.width = 2, .height = 1, .rgb = (float[6]){1.5e9f, 65504.0f, 70000.0f, -1e6f, 2.0f, 0.25f}};
    const float want[6] = {65504.0f, 65504.0f, 65504.0f, -65504.0f, 2.0f, 0.25f};
    CHECK_OK(il_image_write(&im, tmp_path(p, "bright.exr"), NULL, &err), &err);
    CHECK(im.rgb[0] == 1.5e9f && im.rgb[3] == -1e6f);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    for (int i = 0; back.rgb && i < 6; i++)
        CHECK(back.rgb[i] == want[i]);
    il_image_free(&back);
    il_write_desc wf = {.exr_precision = IL_EXR_FLOAT};
    CHECK_OK(il_image_write(&im, tmp_path(p, "bright_float.exr"), &wf, &err), &err);
    CHECK_OK(il_image_read(p, &back, &err), &err);
    for (int i = 0; back.rgb && i < 6; i++)
        CHECK(back.rgb[i] == im.rgb[i]);
    il_image_free(&back);
}

static void test_hdr_rgbe(void)
{
    il_error err = {0};
    /* Width 45 uses RLE scanlines, width 5 flat ones. */
    const uint32_t widths[] = {45, 5};
    for (int t = 0; t < 2; t++) {
        char p[1100];
        il_image im = hdr_pattern(widths[t], 9);
        /* A constant stretch exercises runs; a black pixel exercises 0. */
        for (uint32_t x = 0; x < widths[t]; x++) {
            float *px = im.rgb + (2 * widths[t] + x) * 3;
            px[0] = 0.25f, px[1] = 1000.0f, px[2] = 0.001f;
        }
        im.rgb[3] = im.rgb[4] = im.rgb[5] = 0.0f;
        CHECK_OK(il_image_write(&im, tmp_path(p, t ? "flat.hdr" : "rle.hdr"), NULL, &err), &err);
        il_image back = {0};
        CHECK_OK(il_image_read(p, &back, &err), &err);
        CHECK(back.width == im.width && back.height == im.height);
        if (!back.rgb)
            continue;
        /* RGBE shares one exponent; rounding the mantissa to nearest keeps
         * every channel within 2^-8 of the pixel's largest component. */
        int bad = 0;
        double worst = 0;
        for (size_t i = 0; i < (size_t)im.width * im.height; i++) {
            double m = max3(im.rgb + i * 3);
            for (int k = 0; k < 3; k++) {
                double e = fabs(back.rgb[i * 3 + k] - im.rgb[i * 3 + k]);
                bad += !(e <= ldexp(1.0, -8) * m * (1 + 1e-6));
                if (m > 0 && e / m > worst)
                    worst = e / m;
            }
        }
        CHECK(bad == 0);
        CHECK(worst > ldexp(1.0, -10)); /* the bound is not vacuous: we are lossy */
        CHECK(back.rgb[3] == 0 && back.rgb[4] == 0 && back.rgb[5] == 0);
        /* The constant row: 1000 is the max, 0.25 is a few mantissa units. */
        CHECK_REL(back.rgb[(2 * widths[t] + 3) * 3 + 1], 1000.0, ldexp(1.0, -8));
        il_image_free(&back);
        il_image_free(&im);
    }
}

static void test_hdr_special_values(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = alloc_image(8, 1);
    const float v[24] = {NAN, 1, 1, -5, 2, 2, INFINITY, 0, 0, 1e-40f, 0, 0,
                         1, 1, 1, 255.9f, 0, 0, 0.5f, 0.5f, 0.5f, 0, 0, 0};
    memcpy(im.rgb, v, sizeof v);
    CHECK_OK(il_image_write(&im, tmp_path(p, "special.hdr"), NULL, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    if (back.rgb) {
        /* Decoded as (m + 0.5) 2^(e-136): a zero mantissa is half a step,
         * 1 is 128.5/128 (docs/images.md, Radiance .hdr). */
        CHECK(back.rgb[0] == 0.5f / 128 && back.rgb[1] == 128.5f / 128); /* NaN -> m = 0 */
        CHECK(back.rgb[3] == 0.5f / 64 && back.rgb[4] == 128.5f / 64);   /* negative -> m = 0 */
        CHECK(back.rgb[6] > 1e37f && isfinite(back.rgb[6]));             /* Inf -> largest */
        CHECK(back.rgb[12] == 128.5f / 128 && back.rgb[13] == 128.5f / 128);
        CHECK_REL(back.rgb[15], 255.9, ldexp(1.0, -8));                  /* m = 255 */
        CHECK(back.rgb[18] == 128.5f / 256);
    }
    il_image_free(&back);
    il_image_free(&im);
}

static void test_pfm_exact(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = hdr_pattern(13, 7);
    im.rgb[0] = NAN;
    im.rgb[1] = -INFINITY;
    im.rgb[2] = 1e-42f; /* subnormal */
    im.rgb[3] = -0.0f;
    CHECK_OK(il_image_write(&im, tmp_path(p, "exact.pfm"), NULL, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    CHECK(same_bits(&im, &back));
    il_image_free(&back);

    /* Rows are stored bottom to top: the first pixel in the file is the
     * bottom-left one. */
    size_t size = 0;
    unsigned char *data = load(p, &size);
    if (data) {
        const char *hdr = "PF\n13 7\n-1.0\n";
        CHECK(size == strlen(hdr) + 13 * 7 * 12 && memcmp(data, hdr, strlen(hdr)) == 0);
        float first;
        memcpy(&first, data + strlen(hdr), 4); /* little-endian host */
        CHECK(memcmp(&first, &im.rgb[6 * 13 * 3], 4) == 0);
    }
    free(data);
    il_image_free(&im);
}

static void test_pfm_variants(void)
{
    char p[1100];
    il_error err = {0};
    /* Grey, big-endian (positive scale), scale 2: values are multiplied. */
    unsigned char buf[64];
    const char *hdr = "Pf\n2 2\n2.0\n";
    size_t n = strlen(hdr);
    memcpy(buf, hdr, n);
    const float vals[4] = {1.0f, 2.0f, 3.0f, 4.0f}; /* bottom row first */
    for (int i = 0; i < 4; i++) {
        uint32_t u;
        memcpy(&u, &vals[i], 4);
        buf[n++] = (unsigned char)(u >> 24);
        buf[n++] = (unsigned char)(u >> 16);
        buf[n++] = (unsigned char)(u >> 8);
        buf[n++] = (unsigned char)u;
    }
    save(tmp_path(p, "grey_be.pfm"), buf, n);
    il_image im = {0};
    CHECK_OK(il_image_read(p, &im, &err), &err);
    CHECK(im.width == 2 && im.height == 2);
    if (im.rgb) {
        /* top row = file row 1 = (3, 4), bottom = (1, 2); grey replicated; x2 */
        const float want[4] = {6, 8, 2, 4};
        int bad = 0;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                bad += im.rgb[i * 3 + k] != want[i];
        CHECK(bad == 0);
    }
    il_image_free(&im);
}

/* The sRGB EOTF, written out independently of the library. */
static double srgb_eotf(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* A PNG whose IDAT byte is flipped: stb_image decodes it as other pixels,
 * the chunk's CRC finds it (png_check_structure). */
static void test_png_crc(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = alloc_image(8, 8);
    for (int i = 0; i < 8 * 8 * 3; i++)
        im.rgb[i] = (float)(i % 7) / 7.0f;
    CHECK_OK(il_image_write(&im, tmp_path(p, "crc.png"), NULL, &err), &err);
    il_image_free(&im);
    unsigned char buf[4096];
    FILE *f = fopen(p, "rb");
    size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f)
        fclose(f);
    unsigned char *idat = NULL;
    for (size_t k = 0; k + 4 <= n && !idat; k++)
        if (!memcmp(buf + k, "IDAT", 4))
            idat = buf + k;
    CHECK(idat != NULL);
    if (!idat)
        return;
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);   /* as written: fine */
    il_image_free(&back);
    idat[4 + 3] ^= 0x10;   /* a byte of the compressed data */
    save(tmp_path(p, "crc-flipped.png"), buf, n);
    CHECK(il_image_read(p, &back, &err) == IL_ERR_FORMAT);
    CHECK(strstr(err.message, "crc-flipped.png: PNG chunk 'IDAT' is corrupt (its CRC does not match)"));
    il_image_free(&back);
}

/* A well-formed PNG of 0 x 5 pixels (IHDR with a valid CRC): the image's
 * zero size is named, not stb_image's "unknown image type". */
static void test_png_zero_size(void)
{
    static const unsigned char ihdr[17] = {'I', 'H', 'D', 'R', 0, 0, 0, 0, 0, 0, 0, 5, 8, 2, 0, 0, 0};
    unsigned char buf[64] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13};
    size_t n = 12;
    memcpy(buf + n, ihdr, sizeof ihdr);
    n += sizeof ihdr;
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t k = 0; k < sizeof ihdr; k++) {
        crc ^= ihdr[k];
        for (int b = 0; b < 8; b++)
            crc = crc & 1u ? 0xEDB88320u ^ (crc >> 1) : crc >> 1;
    }
    crc ^= 0xFFFFFFFFu;
    for (int b = 3; b >= 0; b--)
        buf[n++] = (unsigned char)(crc >> (8 * b));
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    memcpy(buf + n, iend, sizeof iend);
    n += sizeof iend;
    char p[1100];
    save(tmp_path(p, "zero.png"), buf, n);
    il_image back = {0};
    il_error err = {0};
    CHECK(il_image_read(p, &back, &err) == IL_ERR_FORMAT);
    CHECK(strstr(err.message, "zero.png: image has zero size (0x5)"));
    il_image_free(&back);
}

static void test_png(void)
{
    char p[1100];
    il_error err = {0};
    /* Every 8-bit code value, decoded to linear, must come back bit-exact. */
    il_image im = alloc_image(16, 16);
    for (int i = 0; i < 256; i++) {
        im.rgb[i * 3 + 0] = (float)srgb_eotf(i / 255.0);
        im.rgb[i * 3 + 1] = (float)srgb_eotf((255 - i) / 255.0);
        im.rgb[i * 3 + 2] = (float)srgb_eotf(((i * 7) % 256) / 255.0);
    }
    CHECK_OK(il_image_write(&im, tmp_path(p, "codes.png"), NULL, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    CHECK(same_bits(&im, &back));
    il_image_free(&back);

    /* Exposure +1 doubles; clamping; NaN, Inf and negatives give 0. */
    il_image q = alloc_image(6, 1);
    const float v[18] = {(float)srgb_eotf(100 / 255.0) / 2, 0.5f, 0, 7.0f, 0.5f, 0,
                         NAN,   INFINITY, -INFINITY, -1, 0.2f, 0.2f,
                         0,     0,        0,         1e30f, 1e30f, 1e30f};
    memcpy(q.rgb, v, sizeof v);
    il_write_desc wd = {.exposure = 1.0f};
    CHECK_OK(il_image_write(&q, tmp_path(p, "exposure.png"), &wd, &err), &err);
    CHECK_OK(il_image_read(p, &back, &err), &err);
    if (back.rgb) {
        CHECK_REL(back.rgb[0], srgb_eotf(100 / 255.0), 1e-6); /* 2 * half of code 100 */
        CHECK(back.rgb[1] == 1.0f && back.rgb[3] == 1.0f);     /* 2*0.5 and 14 clamp to 1 */
        CHECK(back.rgb[6] == 0 && back.rgb[7] == 0 && back.rgb[8] == 0 && back.rgb[9] == 0);
        CHECK_REL(back.rgb[10], srgb_eotf(round(255 * (1.055 * pow(0.4, 1 / 2.4) - 0.055)) / 255),
                  1e-6);
        CHECK(back.rgb[15] == 1.0f);
    }
    il_image_free(&back);
    il_image_free(&q);
    il_image_free(&im);
}

static void test_png_grey_alpha_and_jpeg(void)
{
    char p[1100];
    il_error err = {0};
    /* Grey + alpha PNG from another writer: grey replicated, alpha dropped. */
    unsigned char ga[4 * 2 * 2];
    for (int i = 0; i < 4; i++) {
        ga[i * 2] = (unsigned char)(i * 60);
        ga[i * 2 + 1] = (unsigned char)(i * 10);
    }
    CHECK(stbi_write_png(tmp_path(p, "ga.png"), 2, 2, 2, ga, 4) != 0);
    il_image im = {0};
    CHECK_OK(il_image_read(p, &im, &err), &err);
    CHECK(im.width == 2 && im.height == 2);
    if (im.rgb) {
        int bad = 0;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                bad += im.rgb[i * 3 + k] != (float)srgb_eotf(i * 60 / 255.0);
        CHECK(bad == 0);
    }
    il_image_free(&im);

    /* RGBA */
    unsigned char rgba[4] = {255, 128, 0, 7};
    CHECK(stbi_write_png(tmp_path(p, "rgba.png"), 1, 1, 4, rgba, 4) != 0);
    CHECK_OK(il_image_read(p, &im, &err), &err);
    if (im.rgb) {
        CHECK(im.rgb[0] == 1.0f && im.rgb[2] == 0.0f);
        CHECK(im.rgb[1] == (float)srgb_eotf(128 / 255.0));
    }
    il_image_free(&im);

    /* JPEG of a flat colour: lossy, but a flat block decodes within a code. */
    unsigned char flat[16 * 16 * 3];
    for (int i = 0; i < 16 * 16; i++)
        flat[i * 3] = 200, flat[i * 3 + 1] = 100, flat[i * 3 + 2] = 50;
    CHECK(stbi_write_jpg(tmp_path(p, "flat.jpg"), 16, 16, 3, flat, 100) != 0);
    CHECK_OK(il_image_read(p, &im, &err), &err);
    CHECK(im.width == 16 && im.height == 16);
    if (im.rgb) {
        CHECK_NEAR(im.rgb[0], srgb_eotf(200 / 255.0), srgb_eotf(202 / 255.0) - srgb_eotf(200 / 255.0));
        CHECK_NEAR(im.rgb[1], srgb_eotf(100 / 255.0), srgb_eotf(102 / 255.0) - srgb_eotf(100 / 255.0));
        CHECK_NEAR(im.rgb[2], srgb_eotf(50 / 255.0), srgb_eotf(52 / 255.0) - srgb_eotf(50 / 255.0));
    }
    il_image_free(&im);
}

/* ------------------------------------------- EXR files from another writer */

/* Writes an EXR with the given channels through the OpenEXR C API: scanline
 * or 8x8 tiles, every channel of type `type`, value of channel c at (x, y) =
 * (x + 2y + c) / 8 (integer x + 2y + c for UINT); data window origin
 * (ox, oy). */
static bool write_test_exr(const char *path, int w, int h, int ox, int oy, bool tiled,
                           const char **names, int nch, exr_pixel_type_t type)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctxt = NULL;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctxt, "test", tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
    exr_attr_box2i_t dw;
    dw.min.x = ox;
    dw.min.y = oy;
    dw.max.x = ox + w - 1;
    dw.max.y = oy + h - 1;
    exr_attr_v2f_t center;
    center.x = center.y = 0.0f;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr(ctxt, part, &dw, &dw, 1.0f, &center, 1.0f,
                                          EXR_LINEORDER_INCREASING_Y, EXR_COMPRESSION_ZIPS);
    if (rv == EXR_ERR_SUCCESS && tiled)
        rv = exr_set_tile_descriptor(ctxt, part, 8, 8, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    for (int c = 0; c < nch && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(ctxt, part, names[c], type, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_set_version(ctxt, part, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);

    /* Planar source: one w*h plane per channel, floats or uint32. */
    uint32_t *planes = malloc((size_t)w * h * nch * 4);
    for (int c = 0; c < nch; c++)
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                uint32_t *dst = planes + ((size_t)c * h + y) * w + x;
                if (type == EXR_PIXEL_UINT) {
                    *dst = (uint32_t)(x + 2 * y + c);
                } else {
                    float f = (float)(x + 2 * y + c) / 8.0f;
                    memcpy(dst, &f, 4);
                }
            }
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool inited = false;
    int32_t lines = 1;
    if (rv == EXR_ERR_SUCCESS && !tiled)
        rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    int nx = tiled ? (w + 7) / 8 : 1, ny = tiled ? (h + 7) / 8 : (h + lines - 1) / lines;
    for (int ty = 0; ty < ny && rv == EXR_ERR_SUCCESS; ty++)
        for (int tx = 0; tx < nx && rv == EXR_ERR_SUCCESS; tx++) {
            exr_chunk_info_t ci;
            rv = tiled ? exr_write_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &ci)
                       : exr_write_scanline_chunk_info(ctxt, part, oy + ty * lines, &ci);
            if (rv != EXR_ERR_SUCCESS)
                break;
            rv = inited ? exr_encoding_update(ctxt, part, &ci, &enc)
                        : exr_encoding_initialize(ctxt, part, &ci, &enc);
            inited = true;
            int x0 = tiled ? tx * 8 : 0, y0 = tiled ? ty * 8 : ci.start_y - oy;
            for (int i = 0; i < enc.channel_count && rv == EXR_ERR_SUCCESS; i++) {
                int c = 0;
                while (c < nch && strcmp(names[c], enc.channels[i].channel_name) != 0)
                    c++;
                enc.channels[i].encode_from_ptr =
                    (const uint8_t *)(planes + ((size_t)c * h + y0) * w + x0);
                enc.channels[i].user_pixel_stride = 4;
                enc.channels[i].user_line_stride = w * 4;
                enc.channels[i].user_data_type = (uint16_t)(type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT
                                                                                   : EXR_PIXEL_FLOAT);
                enc.channels[i].user_bytes_per_element = 4;
            }
            if (rv == EXR_ERR_SUCCESS)
                rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
            if (rv == EXR_ERR_SUCCESS)
                rv = exr_encoding_run(ctxt, part, &enc);
        }
    if (inited)
        exr_encoding_destroy(ctxt, &enc);
    free(planes);
    exr_result_t frv = exr_finish(&ctxt);
    return rv == EXR_ERR_SUCCESS && frv == EXR_ERR_SUCCESS;
}

static void check_exr_values(const char *path, int w, int h, bool grey, double unit)
{
    il_error err = {0};
    il_image im = {0};
    CHECK_OK(il_image_read(path, &im, &err), &err);
    CHECK(im.width == (uint32_t)w && im.height == (uint32_t)h);
    if (!im.rgb)
        return;
    int bad = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 3; k++) {
                double want = (x + 2 * y + (grey ? 0 : k)) * unit;
                bad += im.rgb[((size_t)y * w + x) * 3 + k] != (float)want;
            }
    CHECK(bad == 0);
    il_image_free(&im);
}

static void test_exr_foreign(void)
{
    char p[1100];
    il_error err = {0};
    /* Tiled half RGBA with partial edge tiles and an offset data window; the
     * alpha channel is ignored. */
    const char *rgba[4] = {"R", "G", "B", "A"};
    CHECK(write_test_exr(tmp_path(p, "tiled.exr"), 19, 11, -3, 5, true, rgba, 4, EXR_PIXEL_HALF));
    check_exr_values(p, 19, 11, false, 1.0 / 8);
    /* Scanline, uint channels, offset data window. */
    CHECK(write_test_exr(tmp_path(p, "uint.exr"), 7, 5, 2, -4, false, rgba, 3, EXR_PIXEL_UINT));
    check_exr_values(p, 7, 5, false, 1.0);
    /* Luminance only: Y replicated into R, G, B. */
    const char *y[1] = {"Y"};
    CHECK(write_test_exr(tmp_path(p, "grey.exr"), 9, 4, 0, 0, false, y, 1, EXR_PIXEL_FLOAT));
    check_exr_values(p, 9, 4, true, 1.0 / 8);
    /* Neither RGB nor Y: an error naming the file. */
    const char *z[1] = {"Z"};
    CHECK(write_test_exr(tmp_path(p, "depth.exr"), 4, 4, 0, 0, false, z, 1, EXR_PIXEL_FLOAT));
    il_image im = {0};
    CHECK(il_image_read(p, &im, &err) == IL_ERR_FORMAT);
    CHECK(strstr(err.message, "depth.exr") != NULL);
    CHECK(im.rgb == NULL);
}

/* --------------------------------------------------------------- bad input */

/* Cuts the file down with truncate(), one length at a time from size-1 to 0
 * (every length for small files, a stride for bigger ones): each read must be
 * IL_ERR_FORMAT naming the file, and leave the output image empty. */
static void check_truncations(const char *name, const unsigned char *data, size_t size)
{
    char p[1100];
    tmp_path(p, name);
    save(p, data, size);
    int wrong = 0, unnamed = 0, tried = 0;
    size_t step = size <= 4096 ? 1 : size / 1500;
    for (size_t len = size; len-- > 0;) {
        if (len > 256 && (size - len) % step != 0)
            continue;
        if (truncate(p, (off_t)len) != 0)
            break;
        il_error err = {0};
        il_image im = {0};
        il_status st = il_image_read(p, &im, &err);
        tried++;
        if (st != IL_ERR_FORMAT || im.rgb != NULL) {
            if (wrong < 5)
                fprintf(stderr, "  %s cut to %zu of %zu bytes: status %d (%s)\n", name, len, size,
                        (int)st, err.message);
            wrong++;
        }
        if (!strstr(err.message, name))
            unnamed++;
        il_image_free(&im);
    }
    CHECK(tried > 0);
    CHECK(wrong == 0);
    CHECK(unnamed == 0);
    /* And the complete file still reads. */
    save(p, data, size);
    il_error err = {0};
    il_image im = {0};
    CHECK_OK(il_image_read(p, &im, &err), &err);
    il_image_free(&im);
}

/* Flips every byte of the first `span` bytes, one at a time: the read may
 * succeed (a flipped pixel value) or fail with IL_ERR_FORMAT, but never crash,
 * hang or report anything else.  Flipping the magic must fail. */
static void check_flips(const char *name, const unsigned char *data, size_t size, size_t span)
{
    char p[1100];
    tmp_path(p, name);
    unsigned char *copy = malloc(size);
    int wrong = 0;
    if (span > size)
        span = size;
    for (size_t i = 0; i < span; i++) {
        memcpy(copy, data, size);
        copy[i] ^= 0xff;
        save(p, copy, size);
        il_error err = {0};
        il_image im = {0};
        il_status st = il_image_read(p, &im, &err);
        bool ok = st == IL_ERR_FORMAT ? im.rgb == NULL && strstr(err.message, name) != NULL
                                      : st == IL_OK && im.rgb != NULL && im.width > 0;
        if (i < 2 && st != IL_ERR_FORMAT)
            ok = false;
        if (!ok) {
            if (wrong < 5)
                fprintf(stderr, "  %s with byte %zu flipped: status %d (%s)\n", name, i, (int)st,
                        err.message);
            wrong++;
        }
        il_image_free(&im);
    }
    CHECK(wrong == 0);
    free(copy);
}

static void test_corrupt_files(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = hdr_pattern(20, 19);
    for (size_t i = 0; i < 20 * 3; i++) /* a constant row for HDR runs */
        im.rgb[20 * 3 * 4 + i] = 0.5f;
    il_write_desc wf = {.exr_precision = IL_EXR_FLOAT};
    struct {
        const char *good, *bad;
        const il_write_desc *desc;
    } files[] = {
        {"good_half.exr", "bad_half.exr", NULL}, {"good_float.exr", "bad_float.exr", &wf},
        {"good.hdr", "bad.hdr", NULL},           {"good.pfm", "bad.pfm", NULL},
        {"good.png", "bad.png", NULL},
    };
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        CHECK_OK(il_image_write(&im, tmp_path(p, files[f].good), files[f].desc, &err), &err);
        size_t size = 0;
        unsigned char *data = load(p, &size);
        CHECK(data != NULL && size > 100);
        if (!data)
            continue;
        check_truncations(files[f].bad, data, size);
        check_flips(files[f].bad, data, size, 600);
        free(data);
    }
    /* JPEG and a flat (uncompressed) HDR, from their own writers. */
    unsigned char px[20 * 19 * 3];
    for (size_t i = 0; i < sizeof px; i++)
        px[i] = (unsigned char)(i * 37);
    CHECK(stbi_write_jpg(tmp_path(p, "good.jpg"), 20, 19, 3, px, 90) != 0);
    size_t size = 0;
    unsigned char *data = load(p, &size);
    if (data) {
        check_truncations("bad.jpg", data, size);
        check_flips("bad.jpg", data, size, 700);
    }
    free(data);
    il_image narrow = hdr_pattern(3, 40);
    CHECK_OK(il_image_write(&narrow, tmp_path(p, "good_flat.hdr"), NULL, &err), &err);
    data = load(p, &size);
    if (data)
        check_truncations("bad_flat.hdr", data, size);
    free(data);
    il_image_free(&narrow);
    il_image_free(&im);
}

static void expect_format_error(const char *name, const char *content, size_t len)
{
    char p[1100];
    save(tmp_path(p, name), content, len);
    il_error err = {0};
    il_image im = {0};
    CHECK(il_image_read(p, &im, &err) == IL_ERR_FORMAT);
    CHECK(strstr(err.message, name) != NULL);
    CHECK(im.rgb == NULL);
}

static void test_bad_headers(void)
{
    /* Absurd and overflowing sizes are rejected before any allocation. */
    expect_format_error("huge.pfm", "PF\n70000 1\n-1.0\n", 17);
    expect_format_error("overflow.pfm", "PF\n4294967297 4294967297\n-1.0\n", 30);
    expect_format_error("zero.pfm", "PF\n0 5\n-1.0\n", 12);
    expect_format_error("negative.pfm", "PF\n-3 5\n-1.0\n", 13);
    expect_format_error("noscale.pfm", "PF\n3 5\n0\n", 10);
    const char *hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 100000\n";
    expect_format_error("huge.hdr", hdr, strlen(hdr));
    hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 1 +Y 2\n\0\0\0\0\0\0\0\0";
    expect_format_error("same-axis.hdr", hdr, strlen(hdr) + 8);
    hdr = "#?RADIANCE\nFORMAT=32-bit_xyze\n\n-Y 1 +X 1\n\0\0\0\0";
    expect_format_error("xyze.hdr", hdr, strlen(hdr) + 4);
    /* Unknown content, with a known and an unknown extension; empty file. */
    expect_format_error("text.png", "hello, world\n", 13);
    expect_format_error("text.xyz", "hello, world\n", 13);
    expect_format_error("empty.exr", "", 0);
}

static void test_missing_and_dispatch(void)
{
    char p[1100], q[1100];
    il_error err = {0};
    il_image im = {0};
    CHECK(il_image_read(tmp_path(p, "does-not-exist.exr"), &im, &err) == IL_ERR_IO);
    CHECK(strstr(err.message, "does-not-exist.exr") != NULL);
    CHECK(im.rgb == NULL);
    CHECK(il_image_read(dir, &im, &err) == IL_ERR_IO); /* a directory */

    /* The format comes from the magic bytes, not the name. */
    il_image a = hdr_pattern(4, 3);
    CHECK_OK(il_image_write(&a, tmp_path(p, "really_pfm.pfm"), NULL, &err), &err);
    CHECK(rename(p, tmp_path(q, "misnamed.png")) == 0);
    CHECK_OK(il_image_read(q, &im, &err), &err);
    CHECK(same_bits(&a, &im));
    il_image_free(&im);
    il_image_free(&a);
}

static void test_write_errors(void)
{
    char p[1100];
    il_error err = {0};
    il_image im = hdr_pattern(8, 8);
    int before = count_files(".tmp-");

    /* Unknown extension: invalid, names the path, creates nothing. */
    CHECK(il_image_write(&im, tmp_path(p, "out.bmp"), NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "out.bmp") != NULL);
    CHECK(!file_exists(p));
    CHECK(il_image_write(&im, tmp_path(p, "noext"), NULL, &err) == IL_ERR_INVALID);
    CHECK(il_image_write(&im, tmp_path(p, "out.jpg"), NULL, &err) == IL_ERR_INVALID);

    /* NULL and empty images. */
    il_image empty = {0};
    CHECK(il_image_write(NULL, tmp_path(p, "null.exr"), NULL, &err) == IL_ERR_INVALID);
    CHECK(il_image_write(&empty, p, NULL, &err) == IL_ERR_INVALID);
    il_image nopix = {.width = 4, .height = 4, .rgb = NULL};
    CHECK(il_image_write(&nopix, p, NULL, &err) == IL_ERR_INVALID);
    CHECK(!file_exists(p));

    /* A missing directory: an i/o error, and nothing is created. */
    const char *exts[] = {"exr", "hdr", "pfm", "png"};
    for (int i = 0; i < 4; i++) {
        char name[64];
        snprintf(name, sizeof name, "no-such-dir/out.%s", exts[i]);
        CHECK(il_image_write(&im, tmp_path(p, name), NULL, &err) == IL_ERR_IO);
        CHECK(strstr(err.message, name) != NULL);
        CHECK(!file_exists(tmp_path(p, "no-such-dir")));
    }

    /* The target is a directory: everything is written, the rename fails, and
     * the temporary file is removed. */
    for (int i = 0; i < 4; i++) {
        char name[64];
        snprintf(name, sizeof name, "a-directory.%s", exts[i]);
        tmp_path(p, name);
        mkdir(p, 0755);
        CHECK(il_image_write(&im, p, NULL, &err) == IL_ERR_IO);
        CHECK(strstr(err.message, name) != NULL);
        rmdir(p);
        CHECK(!file_exists(p));
    }
    CHECK(count_files(".tmp-") == before);

    /* Overwriting replaces the old file completely. */
    CHECK_OK(il_image_write(&im, tmp_path(p, "twice.pfm"), NULL, &err), &err);
    il_image small = hdr_pattern(2, 1);
    CHECK_OK(il_image_write(&small, p, NULL, &err), &err);
    il_image back = {0};
    CHECK_OK(il_image_read(p, &back, &err), &err);
    CHECK(same_bits(&small, &back));
    il_image_free(&back);
    il_image_free(&small);
    CHECK(count_files(".tmp-") == 0);
    il_image_free(&im);
}

static void test_alloc(void)
{
    il_error err = {0};
    il_image im = {0};
    CHECK(il_image_alloc(&im, 0, 5, &err) == IL_ERR_INVALID && im.rgb == NULL);
    CHECK(il_image_alloc(&im, 70000, 5, &err) == IL_ERR_INVALID && im.rgb == NULL);
    CHECK_OK(il_image_alloc(&im, 3, 2, &err), &err);
    CHECK(im.width == 3 && im.height == 2 && im.rgb && im.rgb[17] == 0.0f);
    il_image_free(&im);
    CHECK(im.rgb == NULL && im.width == 0);
    il_image_free(&im); /* twice is harmless */
    il_image_free(NULL);
}

/* Empties our scratch directory of what earlier runs left. */
static void clean_dir(void)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    char p[1100];
    while ((e = readdir(d)) != NULL)
        if (e->d_name[0] != '.') {
            tmp_path(p, e->d_name);
            if (unlink(p) != 0)
                rmdir(p);
        }
    closedir(d);
}

int main(void)
{
    snprintf(dir, sizeof dir, "%s/image_io", check_tmp_dir());
    mkdir(dir, 0755);
    clean_dir();
    test_alloc();
    test_exr_float_exact();
    test_exr_incompressible_chunks();
    test_exr_half();
    test_exr_half_clamp();
    test_hdr_rgbe();
    test_hdr_special_values();
    test_pfm_exact();
    test_pfm_variants();
    test_png();
    test_png_crc();
    test_png_grey_alpha_and_jpeg();
    test_exr_foreign();
    test_corrupt_files();
    test_png_zero_size();
    test_bad_headers();
    test_missing_and_dispatch();
    test_write_errors();
    return check_report();
}
