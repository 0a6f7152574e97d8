/* False-colour pictures of lux values with a labelled legend (cli.h), for
 * `illum illuminance --view`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "image/srgb.h"

/* The palette from 0 to the top of the scale, display (sRGB) colours: dark
 * blue, blue, cyan, green, yellow, orange, red, as lighting tools draw lux. */
static const float palette[][3] = {
    {0.05f, 0.05f, 0.35f}, {0.10f, 0.30f, 0.90f}, {0.00f, 0.75f, 0.85f}, {0.20f, 0.80f, 0.20f},
    {0.95f, 0.90f, 0.10f}, {0.95f, 0.45f, 0.05f}, {0.80f, 0.05f, 0.05f},
};
#define PALETTE_N (sizeof palette / sizeof palette[0])
static const float no_surface[3] = {0.15f, 0.15f, 0.15f};
static const float background[3] = {1.0f, 1.0f, 1.0f};
static const float ink[3] = {0.0f, 0.0f, 0.0f};

/* 5x7 glyphs, one byte a row, the high bit of the five on the left. */
static const char glyph_chars[] = "0123456789.lx";
static const unsigned char glyphs[][7] = {
    {14, 17, 19, 21, 25, 17, 14}, {4, 12, 4, 4, 4, 4, 14},     {14, 17, 1, 2, 4, 8, 31},
    {31, 2, 4, 2, 1, 17, 14},     {2, 6, 10, 18, 31, 2, 2},    {31, 16, 30, 1, 1, 17, 14},
    {6, 8, 16, 30, 17, 17, 14},   {31, 1, 2, 4, 8, 8, 8},      {14, 17, 17, 14, 17, 17, 14},
    {14, 17, 17, 15, 1, 2, 12},   {0, 0, 0, 0, 0, 12, 12},     {12, 4, 4, 4, 4, 4, 14},
    {0, 0, 17, 10, 4, 10, 17},
};

static void put(il_image *img, int x, int y, const float c[3])
{
    if (x < 0 || y < 0 || x >= (int)img->width || y >= (int)img->height)
        return;
    float *p = img->rgb + 3 * ((size_t)y * img->width + x);
    for (int k = 0; k < 3; k++)
        p[k] = (float)il_srgb_to_linear(c[k]); /* the PNG writer encodes it back */
}

/* Draws text with its top-left corner at (x, y), glyphs scaled by s. */
static void draw_text(il_image *img, int x, int y, int s, const char *text)
{
    for (; *text; text++, x += 6 * s) {
        const char *at = strchr(glyph_chars, *text);
        if (!at || !*text)
            continue;
        const unsigned char *g = glyphs[at - glyph_chars];
        for (int row = 0; row < 7 * s; row++)
            for (int col = 0; col < 5 * s; col++)
                if (g[row / s] & (16 >> (col / s)))
                    put(img, x + col, y + row, ink);
    }
}

static void colour_of(double t, float out[3])
{
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    double f = t * (PALETTE_N - 1);
    size_t i = (size_t)f;
    if (i >= PALETTE_N - 1)
        i = PALETTE_N - 2;
    float w = (float)(f - (double)i);
    for (int k = 0; k < 3; k++)
        out[k] = palette[i][k] * (1.0f - w) + palette[i + 1][k] * w;
}

static int compare_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

double cli_seen_quantile(const float *v, const bool *seen, size_t n, double q)
{
    float *sorted = malloc((n ? n : 1) * sizeof *sorted);
    size_t m = 0;
    for (size_t i = 0; sorted && i < n; i++)
        if (seen[i] && isfinite(v[i]))
            sorted[m++] = v[i];
    double x = 0.0;
    if (m > 0) {
        qsort(sorted, m, sizeof *sorted, compare_float);
        x = sorted[(size_t)(q * (double)(m - 1) + 0.5)];
    }
    free(sorted);
    return x;
}

double cli_falsecolor_scale(const float *lux, const bool *seen, size_t n)
{
    double top = cli_seen_quantile(lux, seen, n, 0.99);
    if (!(top > 0.0))
        return 1.0;
    /* The next of 1, 2, 2.5 and 5 times a power of ten at or above top. */
    double p = pow(10.0, floor(log10(top)));
    const double steps[] = {1.0, 2.0, 2.5, 5.0, 10.0};
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++)
        if (steps[k] * p >= top * (1.0 - 1e-9))
            return steps[k] * p;
    return 10.0 * p;
}

bool cli_falsecolor(const float *lux, const bool *seen, uint32_t w, uint32_t h, double scale_max,
                    il_image *out)
{
    int s = h >= 200 ? 2 : 1;                 /* glyph scale */
    int label_w = 7 * 6 * s;                  /* up to seven characters */
    int bar_w = 8 * s, pad = 4 * s;
    uint32_t legend = (uint32_t)(pad + bar_w + pad + label_w + pad);
    out->width = w + legend;
    out->height = h;
    out->rgb = malloc((size_t)out->width * h * 3 * sizeof *out->rgb);
    if (!out->rgb)
        return false;
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < out->width; x++) {
            size_t i = (size_t)y * w + x;
            float c[3];
            if (x >= w)
                memcpy(c, background, sizeof c);
            else if (!seen[i])
                memcpy(c, no_surface, sizeof c);
            else
                colour_of(lux[i] / scale_max, c);
            put(out, (int)x, (int)y, c);
        }
    /* The bar from 0 (bottom) to scale_max (top), with "lx" above it and
     * six labelled ticks. */
    int top = 7 * s + 2 * pad, bottom = (int)h - 4 * s - pad;
    if (bottom - top < 10 * 7 * s / 2) {     /* too short for labels: the bar alone */
        top = pad;
        bottom = (int)h - pad;
    }
    int x0 = (int)w + pad;
    for (int y = top; y <= bottom; y++) {
        float c[3];
        colour_of(bottom > top ? (double)(bottom - y) / (bottom - top) : 0.0, c);
        for (int x = x0; x < x0 + bar_w; x++)
            put(out, x, y, c);
    }
    if (top > pad) {
        draw_text(out, x0, pad, s, "lx");
        for (int k = 0; k <= 5; k++) {
            double v = scale_max * k / 5.0;
            char text[32];
            snprintf(text, sizeof text, v >= 1.0 || v == 0.0 ? "%.0f" : "%.3g", v);
            int y = bottom - (int)lrint((double)(bottom - top) * k / 5.0);
            for (int x = x0 + bar_w; x < x0 + bar_w + pad / 2 + s; x++)
                put(out, x, y, ink);
            draw_text(out, x0 + bar_w + pad, y - 7 * s / 2, s, text);
        }
    }
    return true;
}
