/* Radiance .hdr (RGBE) reader and writer: src/image/rgbe.c, rgbe_read.c.
 *
 * Files are encoded by hand here, independently of src/image: one pattern in
 * all eight orientations and all three scanline encodings (flat, old-style
 * runs, new-style per-channel runs), XYZE, EXPOSURE / COLORCORR / PIXASPECT,
 * corrupt headers and streams, every truncation of small files.  The real
 * maps in shared/scenes/envmaps are compared with stb_image's decoder.
 * Expected values use the standard decoding (m + 0.5) 2^(e - 136)
 * (Radiance's colr_color), computed here with ldexp. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb/stb_image.h>

#include "check.h"
#include "core/color.h"
#include "image/image_io.h"

/* ------------------------------------------------------------ helpers */

typedef struct buf {
    unsigned char *d;
    size_t n, cap;
} buf;

static void put(buf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->d = realloc(b->d, b->cap);
        if (!b->d)
            abort();
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static void put_str(buf *b, const char *s) { put(b, s, strlen(s)); }

static void put4(buf *b, int r, int g, int bl, int e)
{
    unsigned char px[4] = {(unsigned char)r, (unsigned char)g, (unsigned char)bl,
                           (unsigned char)e};
    put(b, px, 4);
}

/* The standard decoding of channel k, computed independently. */
static double ref_value(const unsigned char *px, int k)
{
    return px[3] ? ldexp(px[k] + 0.5, px[3] - 136) : 0.0;
}

static il_status read_buf(const buf *b, const char *name, il_image *im, il_hdr_info *info,
                          il_error *err)
{
    return il_hdr_read_info(b->d, b->n, name, im, info, err);
}

/* Reads and expects IL_ERR_FORMAT naming the file, with nothing allocated. */
static void expect_bad(const char *name, const void *data, size_t n)
{
    il_image im = {0};
    il_error err = {0};
    il_status st = il_hdr_read(data, n, name, &im, &err);
    CHECK(st == IL_ERR_FORMAT);
    CHECK(strstr(err.message, name) != NULL);
    CHECK(im.rgb == NULL && im.width == 0 && im.height == 0);
    if (st != IL_ERR_FORMAT)
        fprintf(stderr, "  %s: status %d (%s)\n", name, (int)st, err.message);
}

static void expect_bad_str(const char *name, const char *text) { expect_bad(name, text, strlen(text)); }

static double max3(const float *v) { return fmax(v[0], fmax(v[1], v[2])); }

/* ----------------------------------------------------- pixel encoding */

/* Every normalised RGBE pixel (largest mantissa >= 128) decodes to the
 * standard value and encodes back to the same bytes. */
static void test_pixel_codec(void)
{
    int wrong_decode = 0, wrong_encode = 0;
    uint32_t seed = 12345;
    for (int e = 24; e < 256; e++) {
        for (int m = 128; m < 256; m++) {
            seed = seed * 1664525u + 1013904223u;
            int k = (int)(seed >> 30) % 3;
            unsigned char px[4];
            for (int c = 0; c < 3; c++)
                px[c] = (unsigned char)((seed >> (8 * c)) % (unsigned)(m + 1));
            px[k] = (unsigned char)m;
            px[3] = (unsigned char)e;
            float rgb[3];
            il_rgbe_decode(px, rgb);
            for (int c = 0; c < 3; c++)
                wrong_decode += rgb[c] != ref_value(px, c);
            unsigned char back[4];
            il_rgbe_encode(rgb, back);
            wrong_encode += memcmp(back, px, 4) != 0;
        }
    }
    CHECK(wrong_decode == 0);
    CHECK(wrong_encode == 0);

    /* Zero exponent: black, whatever the mantissas. */
    float rgb[3];
    il_rgbe_decode((const unsigned char[4]){200, 100, 50, 0}, rgb);
    CHECK(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0);
    /* 1 is 128.5/128: the offset is half a mantissa step. */
    il_rgbe_decode((const unsigned char[4]){128, 0, 255, 129}, rgb);
    CHECK(rgb[0] == 128.5f / 128 && rgb[1] == 0.5f / 128 && rgb[2] == 255.5f / 128);

    unsigned char px[4];
    il_rgbe_encode((const float[3]){1.0f, 0.5f, 0.25f}, px);
    CHECK(px[0] == 128 && px[1] == 64 && px[2] == 32 && px[3] == 129);
    il_rgbe_encode((const float[3]){0.0f, 0.0f, 0.0f}, px);
    CHECK(px[0] == 0 && px[1] == 0 && px[2] == 0 && px[3] == 0);
    il_rgbe_encode((const float[3]){1e-33f, 1e-33f, 0.0f}, px); /* below 1e-32: black */
    CHECK(px[3] == 0);
    il_rgbe_encode((const float[3]){1e-31f, 0.0f, 0.0f}, px);
    CHECK(px[3] != 0 && px[0] >= 128);
    il_rgbe_encode((const float[3]){NAN, -3.0f, 2.0f}, px); /* NaN, negative -> 0 */
    CHECK(px[0] == 0 && px[1] == 0 && px[2] == 128 && px[3] == 130);
    il_rgbe_encode((const float[3]){INFINITY, 1.0f, 0.0f}, px); /* clamped to the largest */
    CHECK(px[0] == 255 && px[3] == 255);
    il_rgbe_encode((const float[3]){3e38f, 3e38f, 3e38f}, px);
    CHECK(px[0] == 255 && px[1] == 255 && px[2] == 255 && px[3] == 255);
}

/* Encode + decode of random pixels over 60 orders of magnitude: every
 * channel within 2^-8 of the pixel's largest channel.  Derivation: with the
 * largest channel v = f 2^e, f in [0.5, 1), the mantissa step is 2^(e-8);
 * truncation then decoding at the step's middle errs by at most half a step,
 * 2^(e-9) = 2^-8 2^(e-1) <= 2^-8 v.  The bound is tight: the worst error seen
 * comes close to it. */
static void test_round_trip_bound(void)
{
    uint64_t s = 0x9e3779b97f4a7c15ull;
    int bad = 0;
    double worst = 0.0;
    for (int i = 0; i < 1000000; i++) {
        float v[3];
        for (int k = 0; k < 3; k++) {
            s ^= s << 13, s ^= s >> 7, s ^= s << 17;
            double u = (double)(s >> 11) / 9007199254740992.0;
            v[k] = (s & 15) == 0 ? 0.0f : (float)exp(-69.0 + 138.0 * u); /* 1e-30 .. 1e30 */
        }
        unsigned char px[4];
        float back[3];
        il_rgbe_encode(v, px);
        il_rgbe_decode(px, back);
        double m = max3(v);
        for (int k = 0; k < 3; k++) {
            double e = fabs((double)back[k] - v[k]);
            bad += !(e <= ldexp(m, -8));
            if (m > 0 && e / m > worst)
                worst = e / m;
        }
    }
    CHECK(bad == 0);
    CHECK(worst > 0.95 * ldexp(1.0, -8) && worst <= ldexp(1.0, -8));
}

/* -------------------------------------------------------- the writer */

static il_status write_mem(const il_image *im, buf *out, il_error *err)
{
    char *data = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&data, &len);
    if (!f)
        return IL_ERR_IO;
    il_status st = il_hdr_write(im, f, "mem.hdr", err);
    fclose(f);
    out->d = (unsigned char *)data;
    out->n = out->cap = len;
    return st;
}

/* Random images with constant stretches (runs longer than 127 and literal
 * stretches longer than 128), written and read back at widths around the RLE
 * limits: header, scanline kind and values within the bound above. */
static void test_writer(void)
{
    const uint32_t widths[] = {1, 7, 8, 9, 127, 128, 129, 300, 1000, 32767, 32768, 40000};
    uint32_t seed = 7;
    for (size_t t = 0; t < sizeof widths / sizeof widths[0]; t++) {
        uint32_t w = widths[t], h = w > 1000 ? 1 : 3;
        il_image im = {0};
        il_error err = {0};
        CHECK_OK(il_image_alloc(&im, w, h, &err), &err);
        if (!im.rgb)
            continue;
        for (size_t i = 0; i < (size_t)w * h; i++) {
            seed = seed * 1664525u + 1013904223u;
            size_t x = i % w;
            bool constant = (x / 200) % 2 == 1; /* 200-pixel stretches */
            for (int k = 0; k < 3; k++)
                im.rgb[i * 3 + k] = constant ? 0.75f * (float)(k + 1)
                                             : (float)ldexp((seed >> (8 * k) & 255) + 1.0,
                                                            (int)(seed >> 28) - 8);
        }
        buf b = {0};
        CHECK_OK(write_mem(&im, &b, &err), &err);
        char head[200];
        snprintf(head, sizeof head,
                 "#?RADIANCE\n# written by illum\nFORMAT=32-bit_rle_rgbe\n\n-Y %u +X %u\n", h,
                 w);
        size_t hl = strlen(head);
        CHECK(b.n > hl && memcmp(b.d, head, hl) == 0);
        bool rle = w >= 8 && w <= 32767;
        if (rle && b.n >= hl + 4)
            CHECK(b.d[hl] == 2 && b.d[hl + 1] == 2 && (b.d[hl + 2] << 8 | b.d[hl + 3]) == (int)w);
        if (!rle)
            CHECK(b.n == hl + (size_t)w * h * 4);
        il_image back = {0};
        il_hdr_info info;
        CHECK_OK(read_buf(&b, "mem.hdr", &back, &info, &err), &err);
        if (back.rgb) {
            CHECK(back.width == w && back.height == h);
            CHECK(info.rle_scanlines == (rle ? h : 0) && info.flat_scanlines == (rle ? 0 : h));
            CHECK(info.old_runs == 0 && !info.xyze && strcmp(info.orientation, "-Y+X") == 0);
            int bad = 0;
            for (size_t i = 0; i < (size_t)w * h; i++) {
                double m = max3(im.rgb + 3 * i);
                for (int k = 0; k < 3; k++)
                    bad += !(fabs(back.rgb[3 * i + k] - im.rgb[3 * i + k]) <= ldexp(m, -8));
            }
            CHECK(bad == 0);
            if (bad)
                fprintf(stderr, "  width %u: %d channels off\n", w, bad);
        }
        il_image_free(&back);
        il_image_free(&im);
        free(b.d);
    }
}

/* ------------------------------------------------ hand-made encodings */

#define PW 10
#define PH 9

/* The test pattern: RGBE bytes of pixel (x, y), y from the top.  Every
 * pixel differs from every other except two constant stretches, one along
 * row 3 and one down column 9, so that old-style runs occur whichever way
 * the scanlines go; blue is constant (a run in every new-style scanline).
 * Mantissas are >= 128: never a run marker, never an RLE start. */
static void pattern_px(int x, int y, unsigned char px[4])
{
    px[0] = (unsigned char)(128 + 12 * x);
    px[1] = (unsigned char)(128 + 13 * y);
    px[2] = 150;
    px[3] = (unsigned char)(126 + (x + 2 * y) % 5);
    if (y == 3 && x >= 2 && x <= 7)
        px[0] = 129, px[1] = 131, px[3] = 128;
    if (x == 9 && y >= 1 && y <= 7)
        px[0] = 250, px[1] = 140, px[3] = 131;
}

typedef struct orient {
    const char *fmt; /* resolution line, with the sizes as %d in file order */
    const char *name;
    bool x_first, x_decreasing, y_increasing;
} orient;

static const orient orients[8] = {
    {"-Y %d +X %d", "-Y+X", false, false, false}, {"-Y %d -X %d", "-Y-X", false, true, false},
    {"+Y %d +X %d", "+Y+X", false, false, true},  {"+Y %d -X %d", "+Y-X", false, true, true},
    {"+X %d +Y %d", "+X+Y", true, false, true},   {"+X %d -Y %d", "+X-Y", true, false, false},
    {"-X %d +Y %d", "-X+Y", true, true, true},    {"-X %d -Y %d", "-X-Y", true, true, false},
};

/* The pattern's pixel at file position (scanline i, pixel j), following the
 * Radiance notes: the first axis named varies slowest; +X is left to right,
 * +Y bottom to top. */
static void file_px(const orient *o, int i, int j, unsigned char px[4])
{
    int a = i, b = j; /* a: index along the first axis, b: along the second */
    int x, y_up;
    if (o->x_first) {
        x = o->x_decreasing ? PW - 1 - a : a;
        y_up = o->y_increasing ? b : PH - 1 - b;
    } else {
        y_up = o->y_increasing ? a : PH - 1 - a;
        x = o->x_decreasing ? PW - 1 - b : b;
    }
    pattern_px(x, PH - 1 - y_up, px);
}

enum { ENC_FLAT, ENC_OLD, ENC_RLE };

/* Old-style runs: after a pixel, n repeats as (1,1,1,n & 255),
 * (1,1,1,(n >> 8) & 255), ... (low byte first, each marker's count shifted 8
 * bits more). */
static void put_old_run(buf *b, size_t n)
{
    while (n > 0) {
        put4(b, 1, 1, 1, (int)(n & 255));
        n >>= 8;
    }
}

/* New-style RLE of one scanline of n pixels: runs of 3+ equal bytes as
 * (128 + len, byte), len <= 127; other bytes literally, (len, bytes),
 * len <= 128. */
static void put_rle_line(buf *b, const unsigned char *line, size_t n)
{
    put4(b, 2, 2, (int)(n >> 8), (int)(n & 255));
    for (int k = 0; k < 4; k++) {
        size_t i = 0;
        while (i < n) {
            size_t r = 1;
            while (i + r < n && r < 127 && line[(i + r) * 4 + k] == line[i * 4 + k])
                r++;
            if (r >= 3) {
                unsigned char code[2] = {(unsigned char)(128 + r), line[i * 4 + k]};
                put(b, code, 2);
                i += r;
                continue;
            }
            size_t j = i;
            while (j < n && j - i < 128 &&
                   !(j + 2 < n && line[j * 4 + k] == line[(j + 1) * 4 + k] &&
                     line[j * 4 + k] == line[(j + 2) * 4 + k]))
                j++;
            unsigned char len = (unsigned char)(j - i);
            put(b, &len, 1);
            for (; i < j; i++)
                put(b, &line[i * 4 + k], 1);
        }
    }
}

static void put_line(buf *b, const unsigned char *line, size_t n, int enc)
{
    if (enc == ENC_RLE) {
        put_rle_line(b, line, n);
    } else if (enc == ENC_FLAT) {
        put(b, line, n * 4);
    } else {
        size_t i = 0;
        while (i < n) {
            put(b, line + i * 4, 4);
            size_t j = i + 1;
            while (j < n && memcmp(line + j * 4, line + i * 4, 4) == 0)
                j++;
            put_old_run(b, j - i - 1);
            i = j;
        }
    }
}

static buf pattern_file(const orient *o, int enc)
{
    buf b = {0};
    char res[64];
    if (o->x_first)
        snprintf(res, sizeof res, o->fmt, PW, PH);
    else
        snprintf(res, sizeof res, o->fmt, PH, PW);
    put_str(&b, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n");
    put_str(&b, res);
    put_str(&b, "\n");
    int nslow = o->x_first ? PW : PH, nfast = o->x_first ? PH : PW;
    unsigned char line[4 * PW * PH];
    for (int i = 0; i < nslow; i++) {
        for (int j = 0; j < nfast; j++)
            file_px(o, i, j, line + 4 * j);
        put_line(&b, line, (size_t)nfast, enc);
    }
    return b;
}

/* Checks a decoded image against the pattern, exactly. */
static int pattern_mismatches(const il_image *im)
{
    if (!im->rgb || im->width != PW || im->height != PH)
        return -1;
    int bad = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            unsigned char px[4];
            pattern_px(x, y, px);
            for (int k = 0; k < 3; k++)
                bad += im->rgb[(y * PW + x) * 3 + k] != (float)ref_value(px, k);
        }
    return bad;
}

/* Every orientation in every encoding decodes to the pattern, top row
 * first; the info says which scanline kinds were met. */
static void test_orientations(void)
{
    const char *encs[] = {"flat", "old RLE", "new RLE"};
    for (int o = 0; o < 8; o++)
        for (int enc = 0; enc < 3; enc++) {
            buf b = pattern_file(&orients[o], enc);
            il_image im = {0};
            il_hdr_info info;
            il_error err = {0};
            CHECK_OK(read_buf(&b, "pattern.hdr", &im, &info, &err), &err);
            int bad = pattern_mismatches(&im);
            CHECK(bad == 0);
            if (bad)
                fprintf(stderr, "  %s %s: %d mismatches\n", orients[o].name, encs[enc], bad);
            if (im.rgb) {
                int nslow = orients[o].x_first ? PW : PH;
                CHECK(strcmp(info.orientation, orients[o].name) == 0);
                CHECK(info.rle_scanlines == (enc == ENC_RLE ? (uint32_t)nslow : 0));
                CHECK(info.flat_scanlines == (enc == ENC_RLE ? 0 : (uint32_t)nslow));
                CHECK(enc == ENC_OLD ? info.old_runs > 0 : info.old_runs == 0);
            }
            il_image_free(&im);
            free(b.d);
        }
}

/* Old-style runs: counts above 255 through chained markers, a zero-count
 * marker that only shifts, a run at the start of a scanline (repeating the
 * previous scanline's last pixel), and the corrupt cases. */
static void test_old_runs(void)
{
    buf b = {0};
    put_str(&b, "#?RADIANCE\n\n-Y 2 +X 300\n");
    put4(&b, 130, 131, 132, 129);
    put_old_run(&b, 299); /* (1,1,1,43) (1,1,1,1): 43 + 256 */
    put4(&b, 1, 1, 1, 43); /* row 2 starts with a run of row 1's last pixel */
    put4(&b, 200, 150, 140, 128);
    put4(&b, 1, 1, 1, 0); /* count 0, shift 8 for the next marker */
    put4(&b, 1, 1, 1, 1); /* 1 << 8 = 256 */
    il_image im = {0};
    il_hdr_info info;
    il_error err = {0};
    CHECK_OK(read_buf(&b, "old.hdr", &im, &info, &err), &err);
    if (im.rgb) {
        int bad = 0;
        for (int i = 0; i < 600; i++) {
            bool second = i >= 300 + 43;
            float expect[3] = {second ? 200.5f / 256 : 130.5f / 128,
                               second ? 150.5f / 256 : 131.5f / 128,
                               second ? 140.5f / 256 : 132.5f / 128};
            for (int k = 0; k < 3; k++)
                bad += im.rgb[3 * i + k] != expect[k];
        }
        CHECK(bad == 0);
        CHECK(info.old_runs == 5 && info.flat_scanlines == 2);
    }
    il_image_free(&im);
    free(b.d);

    const char *head = "#?RADIANCE\n\n-Y 1 +X 300\n";
    b = (buf){0};
    put_str(&b, head);
    put4(&b, 1, 1, 1, 5); /* a run before any pixel */
    put4(&b, 130, 131, 132, 129);
    expect_bad("first-run.hdr", b.d, b.n);
    b.n = strlen(head);
    put4(&b, 130, 131, 132, 129);
    put_old_run(&b, 300); /* one too many */
    expect_bad("old-overrun.hdr", b.d, b.n);
    b.n = strlen(head);
    put4(&b, 130, 131, 132, 129);
    for (int i = 0; i < 3; i++)
        put4(&b, 1, 1, 1, 0);
    put4(&b, 1, 1, 1, 1); /* 1 << 24 */
    expect_bad("old-shift.hdr", b.d, b.n);
    free(b.d);
}

/* Each scanline is classified on its own: new-style RLE in one, flat in the
 * next even when it starts with byte 2 (then 2, 2 needs hi < 128); widths
 * below 8 are never RLE. */
static void test_mixed_scanlines(void)
{
    unsigned char row[4 * PW];
    for (int x = 0; x < PW; x++)
        pattern_px(x, 0, row + 4 * x);
    buf b = {0};
    put_str(&b, "#?RADIANCE\n\n-Y 3 +X 10\n");
    put_rle_line(&b, row, PW);
    unsigned char first2[4] = {2, 200, 5, 128}, first3[4] = {2, 2, 133, 128};
    put(&b, first2, 4);
    put(&b, row + 4, 4 * (PW - 1));
    put(&b, first3, 4);
    put(&b, row + 4, 4 * (PW - 1));
    il_image im = {0};
    il_hdr_info info;
    il_error err = {0};
    CHECK_OK(read_buf(&b, "mixed.hdr", &im, &info, &err), &err);
    if (im.rgb) {
        CHECK(info.rle_scanlines == 1 && info.flat_scanlines == 2);
        CHECK(im.rgb[3 * PW * 1 + 1] == 200.5f / 256 && im.rgb[3 * PW * 2 + 2] == 133.5f / 256);
        int bad = 0;
        for (int y = 0; y < 3; y++)
            for (int x = y ? 1 : 0; x < PW; x++)
                for (int k = 0; k < 3; k++)
                    bad += im.rgb[(y * PW + x) * 3 + k] != (float)ref_value(row + 4 * x, k);
        CHECK(bad == 0);
    }
    il_image_free(&im);
    free(b.d);

    /* Width 7: 2,2,0,7 is a pixel, not an RLE marker. */
    b = (buf){0};
    put_str(&b, "#?RADIANCE\n\n-Y 1 +X 7\n");
    put4(&b, 2, 2, 0, 7);
    for (int i = 1; i < 7; i++)
        put4(&b, 140, 150, 160, 130);
    CHECK_OK(read_buf(&b, "narrow.hdr", &im, &info, &err), &err);
    if (im.rgb)
        CHECK(im.rgb[0] == 2.5f * ldexpf(1, 7 - 136) && info.flat_scanlines == 1);
    il_image_free(&im);
    free(b.d);

    /* Corrupt new-style scanlines. */
    const char *head = "#?RADIANCE\n\n-Y 1 +X 10\n";
    b = (buf){0};
    put_str(&b, head);
    put4(&b, 2, 2, 0, 11);
    for (int i = 0; i < 20; i++)
        put4(&b, 0x82, 9, 0x82, 9);
    expect_bad("rle-length.hdr", b.d, b.n);
    b.n = strlen(head);
    put4(&b, 2, 2, 0, 10);
    unsigned char run[2] = {128 + 11, 5};
    put(&b, run, 2);
    for (int i = 0; i < 20; i++)
        put4(&b, 0x82, 9, 0x82, 9);
    expect_bad("rle-run-overrun.hdr", b.d, b.n);
    b.n = strlen(head);
    put4(&b, 2, 2, 0, 10);
    unsigned char lit = 11;
    put(&b, &lit, 1);
    for (int i = 0; i < 20; i++)
        put4(&b, 0x82, 9, 0x82, 9);
    expect_bad("rle-literal-overrun.hdr", b.d, b.n);
    free(b.d);
}

/* --------------------------------------------------------------- XYZE */

/* XYZ -> linear Rec.709, D65 white: IEC 61966-2-1:1999 eq. (7), typed in
 * here again as the independent reference. */
static void ref_xyz_to_rgb(const double xyz[3], double rgb[3])
{
    static const double m[3][3] = {
        {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
    for (int r = 0; r < 3; r++)
        rgb[r] = m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2];
}

static void test_xyze(void)
{
    /* The matrix the reader uses (core/color.c), against known values: D65
     * white (x, y) = (0.3127, 0.3290) with Y = 1 and the Rec.709 primaries
     * (ITU-R BT.709-6 table: XYZ of R, G, B at unit RGB). */
    const double known[4][6] = {
        {0.9505, 1.0, 1.0890, 1, 1, 1},       {0.4124, 0.2126, 0.0193, 1, 0, 0},
        {0.3576, 0.7152, 0.1192, 0, 1, 0},    {0.1805, 0.0722, 0.9505, 0, 0, 1},
    };
    for (int i = 0; i < 4; i++) {
        il_vec3 c = il_xyz_to_rec709(
            (il_vec3){(float)known[i][0], (float)known[i][1], (float)known[i][2]});
        CHECK_NEAR(c.x, known[i][3], 1e-3);
        CHECK_NEAR(c.y, known[i][4], 1e-3);
        CHECK_NEAR(c.z, known[i][5], 1e-3);
    }

    /* An XYZE file: D65 white, the red primary, pure Y (out of gamut: R and
     * B negative, clipped to 0), and black. */
    const float xyz[4][3] = {{0.9505f, 1.0f, 1.089f}, {0.4124f, 0.2126f, 0.0193f},
                             {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    unsigned char px[4][4];
    buf b = {0};
    put_str(&b, "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 4\n");
    for (int i = 0; i < 4; i++) {
        il_rgbe_encode(xyz[i], px[i]);
        put(&b, px[i], 4);
    }
    il_image im = {0};
    il_hdr_info info;
    il_error err = {0};
    CHECK_OK(read_buf(&b, "xyze.hdr", &im, &info, &err), &err);
    if (im.rgb) {
        CHECK(info.xyze);
        /* Exactly the matrix applied to the decoded XYZ. */
        for (int i = 0; i < 4; i++) {
            double q[3] = {ref_value(px[i], 0), ref_value(px[i], 1), ref_value(px[i], 2)};
            double rgb[3];
            ref_xyz_to_rgb(q, rgb);
            for (int k = 0; k < 3; k++)
                CHECK_NEAR(im.rgb[3 * i + k], fmax(rgb[k], 0.0), 1e-6 * (1 + fabs(rgb[k])));
        }
        /* And near the exact answers: RGBE keeps XYZ to 2^-8 of the largest
         * component; the matrix rows sum to at most 5.3 in magnitude. */
        double tol = 5.3 * ldexp(1.089, -8);
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(im.rgb[k], 1.0, tol);
        CHECK_NEAR(im.rgb[3], 1.0, tol);
        CHECK_NEAR(im.rgb[4], 0.0, tol);
        CHECK_NEAR(im.rgb[5], 0.0, tol);
        CHECK(im.rgb[6] == 0.0f && im.rgb[8] == 0.0f);
        CHECK_NEAR(im.rgb[7], 1.8758, 2 * ldexp(1.8758, -8));
        CHECK(im.rgb[9] == 0 && im.rgb[10] == 0 && im.rgb[11] == 0);
    }
    il_image_free(&im);
    free(b.d);
}

/* ---------------------------------------------- EXPOSURE, COLORCORR */

/* Pixels are divided by the product of all EXPOSURE lines and, per channel,
 * by the product of all COLORCORR lines; PIXASPECT multiplies up and is only
 * reported.  Powers of two keep the expected values exact. */
static void test_exposure_colorcorr(void)
{
    const unsigned char px[2][4] = {{128, 64, 200, 130}, {255, 255, 255, 140}};
    const char *headers[] = {
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n",
        "#?RADIANCE\nEXPOSURE=2\n# a comment\nEXPOSURE= 4.0\n COLORCORR=1 2 4\n"
        "SOFTWARE=some program 1.0\nCOLORCORR=2\t1 0.5e0\nPIXASPECT=0.5\nPIXASPECT=3\n"
        "VIEW= -vtv -vp 0 0 0\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n",
        "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 2\n",
        "#?RADIANCE\nFORMAT=32-bit_rle_xyze\nEXPOSURE=0.25\nCOLORCORR=1 0.5 2\n\n-Y 1 +X 2\n",
    };
    il_image im[4] = {{0}};
    il_hdr_info info[4];
    for (int h = 0; h < 4; h++) {
        buf b = {0};
        put_str(&b, headers[h]);
        put(&b, px, sizeof px);
        il_error err = {0};
        CHECK_OK(read_buf(&b, "exposure.hdr", &im[h], &info[h], &err), &err);
        free(b.d);
    }
    if (im[0].rgb && im[1].rgb) {
        CHECK(info[1].exposure == 8.0);
        CHECK(info[1].colorcorr[0] == 2.0 && info[1].colorcorr[1] == 2.0 &&
              info[1].colorcorr[2] == 2.0);
        CHECK(info[1].pixaspect == 1.5 && info[0].pixaspect == 1.0);
        for (int i = 0; i < 6; i++)
            CHECK(im[1].rgb[i] == im[0].rgb[i] / 16.0f);
    }
    if (im[2].rgb && im[3].rgb) {
        /* XYZE: COLORCORR divides X, Y, Z before the conversion. */
        double q[3] = {ref_value(px[0], 0) / 0.25, ref_value(px[0], 1) / 0.125,
                       ref_value(px[0], 2) / 0.5};
        double rgb[3];
        ref_xyz_to_rgb(q, rgb);
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(im[3].rgb[k], fmax(rgb[k], 0.0), 1e-6 * (1 + fabs(rgb[k])));
        CHECK(fabs(im[3].rgb[0] - im[2].rgb[0] * 4) > 0.01); /* not one common factor */
    }
    for (int h = 0; h < 4; h++)
        il_image_free(&im[h]);

    /* Values beyond float after the division are clamped, not Inf. */
    buf b = {0};
    put_str(&b, "#?RADIANCE\nEXPOSURE=1e-20\n\n-Y 1 +X 1\n");
    put4(&b, 255, 255, 255, 255);
    il_image big = {0};
    il_error err = {0};
    CHECK_OK(read_buf(&b, "clamp.hdr", &big, NULL, &err), &err);
    if (big.rgb)
        CHECK(isfinite(big.rgb[0]) && big.rgb[0] > 1e38f);
    il_image_free(&big);
    free(b.d);

    const char *bad[] = {
        "EXPOSURE=0\n",   "EXPOSURE=-1\n",        "EXPOSURE=nan\n",      "EXPOSURE=inf\n",
        "EXPOSURE=abc\n", "EXPOSURE=1 2\n",       "EXPOSURE=\n",         "COLORCORR=1 1\n",
        "COLORCORR=1 1 1 1\n", "COLORCORR=1 0 1\n", "PIXASPECT=-2\n",
        "EXPOSURE=1e20\nEXPOSURE=1e20\n", /* product beyond 1e30 */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        b = (buf){0};
        put_str(&b, "#?RADIANCE\n");
        put_str(&b, bad[i]);
        put_str(&b, "\n-Y 1 +X 2\n");
        put(&b, px, sizeof px);
        expect_bad("header-value.hdr", b.d, b.n);
        free(b.d);
    }
}

/* ---------------------------------------------------- headers, sizes */

static void test_headers(void)
{
    const unsigned char px[4] = {128, 128, 128, 129};
    /* Accepted variants: another magic, CRLF lines, no FORMAT line, blanks
     * around the resolution fields. */
    const char *good[] = {
        "#?RGBE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n",
        "#?RADIANCE\r\nFORMAT=32-bit_rle_rgbe\r\n\r\n-Y 1 +X 1\r\n",
        "#?SOMEPROGRAM\n\n-Y 1 +X 1\n",
        "#?RADIANCE\nFORMAT= 32-bit_rle_rgbe \n\n-Y\t1   +X 01 \n",
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        buf b = {0};
        put_str(&b, good[i]);
        put(&b, px, 4);
        put_str(&b, "trailing bytes are ignored");
        il_image im = {0};
        il_error err = {0};
        CHECK_OK(read_buf(&b, "good.hdr", &im, NULL, &err), &err);
        CHECK(im.rgb && im.width == 1 && im.height == 1 && im.rgb[0] == 128.5f / 128);
        il_image_free(&im);
        free(b.d);
    }
    /* Refused headers and resolution lines (pixels follow each). */
    const char *bad[] = {
        "RADIANCE\n\n-Y 1 +X 1\n",                         /* no magic */
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n-Y 1 +X 1\n", /* no empty line */
        "#?RADIANCE\nFORMAT=32-bit_rle_rgba\n\n-Y 1 +X 1\n",
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n",
        "#?RADIANCE\n\n-Y 1 +Y 1\n",      "#?RADIANCE\n\n-X 1 +X 1\n",
        "#?RADIANCE\n\n-Y 1\n",           "#?RADIANCE\n\n-Y 1 +X\n",
        "#?RADIANCE\n\nY 1 X 1\n",        "#?RADIANCE\n\n-Y1 +X 1\n",
        "#?RADIANCE\n\n-Y 1 +X 1 junk\n", "#?RADIANCE\n\n-Y -1 +X 1\n",
        "#?RADIANCE\n\n-Z 1 +X 1\n",      "#?RADIANCE\n\n-Y 0 +X 1\n",
        "#?RADIANCE\n\n-Y 1 +X 65537\n",  "#?RADIANCE\n\n-Y 1 +X 4294967297\n",
        "#?RADIANCE\n\n-Y 1 +X 99999999999999999999999999\n",
        "#?RADIANCE\n\n\n-Y 1 +X 1\n", /* an empty resolution line */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        buf b = {0};
        put_str(&b, bad[i]);
        put(&b, px, 4);
        expect_bad("bad-header.hdr", b.d, b.n);
        free(b.d);
    }
    expect_bad("empty.hdr", "", 0);
    expect_bad("no-newline.hdr", "#?RADIANCE", 10);
    expect_bad_str("no-resolution.hdr", "#?RADIANCE\n\n");
    expect_bad_str("cut-resolution.hdr", "#?RADIANCE\n\n-Y 1 +X 1");
    /* A size that a short file cannot hold is refused before allocating. */
    expect_bad_str("short.hdr", "#?RADIANCE\n\n-Y 65536 +X 65536\n\x02\x02\x01\x00");
}

/* Every truncation of small files (each encoding, XYZE with header
 * variables) is a format error naming the file; flipping any byte reads or
 * fails cleanly. */
static void test_truncations(void)
{
    buf files[4];
    for (int enc = 0; enc < 3; enc++)
        files[enc] = pattern_file(&orients[enc == 1 ? 4 : 0], enc);
    buf x = {0};
    put_str(&x, "#?RADIANCE\nFORMAT=32-bit_rle_xyze\nEXPOSURE=2\nCOLORCORR=1 1 1\n\n+X 2 -Y 2\n");
    for (int i = 0; i < 4; i++)
        put4(&x, 140 + i, 150, 160, 130);
    files[3] = x;
    int wrong = 0, flips_ok = 0, flips_bad = 0, flips_wrong = 0;
    for (int f = 0; f < 4; f++) {
        for (size_t len = 0; len < files[f].n; len++) {
            /* An exact-size copy, so that ASan builds see any overread. */
            unsigned char *cut = malloc(len ? len : 1);
            memcpy(cut, files[f].d, len);
            il_image im = {0};
            il_error err = {0};
            il_status st = il_hdr_read(cut, len, "cut.hdr", &im, &err);
            free(cut);
            if (st != IL_ERR_FORMAT || im.rgb || !strstr(err.message, "cut.hdr")) {
                if (wrong++ < 5)
                    fprintf(stderr, "  file %d cut to %zu: status %d (%s)\n", f, len, (int)st,
                            err.message);
            }
            il_image_free(&im);
        }
        unsigned char *copy = malloc(files[f].n);
        for (size_t i = 0; i < files[f].n; i++) {
            memcpy(copy, files[f].d, files[f].n);
            copy[i] ^= 0xff;
            il_image im = {0};
            il_error err = {0};
            il_status st = il_hdr_read(copy, files[f].n, "flip.hdr", &im, &err);
            if (st == IL_OK) {
                flips_ok++;
                for (size_t k = 0; k < (size_t)im.width * im.height * 3; k++)
                    flips_wrong += !(im.rgb[k] >= 0.0f && isfinite(im.rgb[k]));
            } else if (st == IL_ERR_FORMAT && !im.rgb && strstr(err.message, "flip.hdr")) {
                flips_bad++;
            } else {
                flips_wrong++;
            }
            il_image_free(&im);
        }
        free(copy);
        free(files[f].d);
    }
    CHECK(wrong == 0);
    CHECK(flips_wrong == 0);
    CHECK(flips_ok > 0 && flips_bad > 0);
}

/* ---------------------------------------------------------- real maps */

/* The shared environment maps: their sizes, and every pixel against stb_image
 * (an independent decoder).  stb decodes m 2^(e-136), without the half-step
 * offset, so per pixel ours minus stb's must be one and the same value
 * 2^(e-137) in all three channels (0 for black pixels), exactly.  The maps
 * then survive our writer: decode -> encode -> decode is exact for
 * normalised pixels and within 2^-8 of the largest channel otherwise. */
static void test_real_maps(void)
{
    static const struct {
        const char *name;
        uint32_t w, h;
        double mean_lum; /* from shared/scenes/envmaps/SOURCE.md */
    } maps[] = {
        {"probulator_ennis_256x128.hdr", 256, 128, 0.840},
        {"probulator_grace_256x128.hdr", 256, 128, 0.422},
        {"probulator_pisa_256x128.hdr", 256, 128, 0.159},
        {"probulator_uffizi_256x128.hdr", 256, 128, 1.78},
        {"probulator_wells_256x128.hdr", 256, 128, 0.184},
        {"polyhaven_venice_sunset_1k.hdr", 1024, 512, 0.425},
        {"polyhaven_pedestrian_overpass_1k.hdr", 1024, 512, 0.508},
    };
    for (size_t m = 0; m < sizeof maps / sizeof maps[0]; m++) {
        char path[1200];
        snprintf(path, sizeof path, "%s/scenes/envmaps/%s", IL_SHARED_DIR, maps[m].name);
        il_image im = {0};
        il_error err = {0};
        CHECK_OK(il_image_read(path, &im, &err), &err);
        if (!im.rgb)
            continue;
        CHECK(im.width == maps[m].w && im.height == maps[m].h);
        int sw = 0, sh = 0, sc = 0;
        float *ref = stbi_loadf(path, &sw, &sh, &sc, 3);
        CHECK(ref != NULL && (uint32_t)sw == im.width && (uint32_t)sh == im.height);
        if (ref && (uint32_t)sw == im.width && (uint32_t)sh == im.height) {
            size_t n = (size_t)sw * sh, bad = 0;
            double lum = 0.0;
            for (size_t i = 0; i < n; i++) {
                const float *a = im.rgb + 3 * i, *r = ref + 3 * i;
                float d = a[0] - r[0];
                int e2;
                bool ok = d == a[1] - r[1] && d == a[2] - r[2];
                if (d != 0.0f)
                    ok = ok && frexpf(d, &e2) == 0.5f && 512.0f * d > max3(r);
                else
                    ok = ok && a[0] == 0 && a[1] == 0 && a[2] == 0;
                bad += !ok;
                lum += 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2];
            }
            CHECK(bad == 0);
            if (bad)
                fprintf(stderr, "  %s: %zu pixels differ from stb_image\n", maps[m].name, bad);
            CHECK_REL(lum / n, maps[m].mean_lum, 0.02);
        }
        stbi_image_free(ref);

        buf b = {0};
        CHECK_OK(write_mem(&im, &b, &err), &err);
        il_image back = {0};
        CHECK_OK(read_buf(&b, "rewritten.hdr", &back, NULL, &err), &err);
        if (back.rgb) {
            size_t n = (size_t)im.width * im.height, bad = 0, exact = 0;
            for (size_t i = 0; i < n; i++) {
                double mx = max3(im.rgb + 3 * i);
                bool same = true;
                for (int k = 0; k < 3; k++) {
                    bad += !(fabs(back.rgb[3 * i + k] - im.rgb[3 * i + k]) <= ldexp(mx, -8));
                    same = same && back.rgb[3 * i + k] == im.rgb[3 * i + k];
                }
                exact += same;
            }
            CHECK(bad == 0);
            CHECK(exact > n * 99 / 100);
        }
        il_image_free(&back);
        free(b.d);
        il_image_free(&im);
    }
}

int main(void)
{
    test_pixel_codec();
    test_round_trip_bound();
    test_writer();
    test_orientations();
    test_old_runs();
    test_mixed_scanlines();
    test_xyze();
    test_exposure_colorcorr();
    test_headers();
    test_truncations();
    test_real_maps();
    return check_report();
}
