/* Tone mapping: HDR radiance to display values (docs/tonemapping.md).
 *
 * Order of the steps, for every operator:
 *   1. a pixel with a NaN or infinite channel is black, a negative channel is 0;
 *   2. exposure: values times 2^EV, and with auto exposure also divided by the
 *      luminance at the chosen percentile (il_luminance_percentile);
 *   3. bloom (bloom.c) on those exposed HDR values;
 *   4. the operator's curve, then the transfer function (sRGB, or a plain
 *      power for IL_TONEMAP_GAMMA), clamped to [0,1].
 * Luminance is Rec.709's Y = 0.2126 R + 0.7152 G + 0.0722 B (ITU-R BT.709-6,
 * item 3.2), the weights illum uses everywhere (il_image_compare). */
#include "image/tonemap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "image/bloom.h"
#include "image/image_io.h"
#include "image/srgb.h"

/* ------------------------------------------------------------- checking */

il_status il_tonemap_check(const il_tonemap_desc *d, il_error *err)
{
    if (!d)
        return IL_OK;
    if ((int)d->op < (int)IL_TONEMAP_LINEAR || (int)d->op > (int)IL_TONEMAP_FILMIC)
        return il_fail(err, IL_ERR_INVALID, "tonemap: unknown operator %d", (int)d->op);
    if (!isfinite(d->exposure) || fabsf(d->exposure) > 100.0f)
        return il_fail(err, IL_ERR_INVALID, "tonemap: exposure %g EV is out of range (-100 to 100)",
                       (double)d->exposure);
    if (!(d->auto_percentile >= 0.0f && d->auto_percentile <= 100.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "tonemap: auto-exposure percentile %g is out of range (0 to 100)",
                       (double)d->auto_percentile);
    if (!(d->gamma == 0.0f || (d->gamma >= 0.01f && d->gamma <= 100.0f)))
        return il_fail(err, IL_ERR_INVALID, "tonemap: gamma %g is out of range (0.01 to 100)",
                       (double)d->gamma);
    if (!(d->white >= 0.0f) || !isfinite(d->white))
        return il_fail(err, IL_ERR_INVALID, "tonemap: white point %g must be >= 0 and finite",
                       (double)d->white);
    if (!(d->bloom >= 0.0f && d->bloom <= 1.0f))
        return il_fail(err, IL_ERR_INVALID, "tonemap: bloom %g is out of range (0 to 1)",
                       (double)d->bloom);
    if (!(d->bloom_threshold >= 0.0f) || !isfinite(d->bloom_threshold))
        return il_fail(err, IL_ERR_INVALID, "tonemap: bloom threshold %g must be >= 0 and finite",
                       (double)d->bloom_threshold);
    if (!(d->bloom_radius >= 0.0f && d->bloom_radius <= 1.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "tonemap: bloom radius %g is out of range (0 to 1 of the image diagonal)",
                       (double)d->bloom_radius);
    return IL_OK;
}

/* ---------------------------------------------------------------- pixels */

static inline double luminance(const double c[3])
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

/* Step 1 and the exposure: the pixel's values, safe to map. */
static inline void load_pixel(const float *s, double scale, double c[3])
{
    if (!(isfinite(s[0]) && isfinite(s[1]) && isfinite(s[2]))) {
        c[0] = c[1] = c[2] = 0.0;
        return;
    }
    for (int k = 0; k < 3; k++)
        c[k] = s[k] > 0.0f ? s[k] * scale : 0.0;
}

/* Narkowicz 2015/2016, "ACES Filmic Tone Mapping Curve": a rational fit of
 * ACES' RRT + ODT (Rec.709 display, its 2.4 gamma removed), max error
 * 0.0138, pre-exposed so that 1 maps to about 0.8 (the original curve is
 * the fit of 0.6 x).  Tends to 2.51/2.43 > 1, hence the clamp after it. */
static inline double aces_fit(double x)
{
    if (x >= 1e8) /* the limit, without overflowing x^2 */
        return 2.51 / 2.43;
    return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
}

/* The operator's curve for one pixel: linear display values d >= 0 before
 * the transfer function (which clamps them to [0,1]). */
static inline void curve(const il_tonemap_plan *p, size_t i, double d[3])
{
    double c[3];
    load_pixel(p->src + 3 * i, p->scale, c);
    switch (p->op) {
    case IL_TONEMAP_LINEAR:
    case IL_TONEMAP_GAMMA:
        for (int k = 0; k < 3; k++)
            d[k] = c[k];
        return;
    case IL_TONEMAP_REINHARD: {
        /* Reinhard, Stark, Shirley, Ferwerda 2002, "Photographic Tone
         * Reproduction for Digital Images", eq. 4:
         *   L_d = L (1 + L / L_white^2) / (1 + L),
         * L the luminance after the exposure (which stands in for the key
         * scaling a / L_w of their eq. 2).  Colour keeps its ratios: each
         * channel times L_d / L (their operator acts on luminance). */
        double lum = luminance(c);
        double ratio = !(lum > 0.0) ? 0.0
                       : p->white > 0.0 ? (1.0 + lum / (p->white * p->white)) / (1.0 + lum)
                                        : 1.0 / (1.0 + lum);
        for (int k = 0; k < 3; k++)
            d[k] = c[k] > 0.0 ? c[k] * ratio : 0.0;
        return;
    }
    case IL_TONEMAP_FILMIC:
        for (int k = 0; k < 3; k++)
            d[k] = aces_fit(c[k]);
        return;
    }
    d[0] = d[1] = d[2] = 0.0;
}

/* The transfer function of a linear display value, clamped to [0,1]:
 * sRGB's OETF, or the plain power 1/gamma of IL_TONEMAP_GAMMA. */
static inline double transfer(const il_tonemap_plan *p, double v)
{
    if (!(v > 0.0))
        return 0.0;
    if (v >= 1.0)
        return 1.0;
    return p->op == IL_TONEMAP_GAMMA ? pow(v, p->inv_gamma) : il_linear_to_srgb(v);
}

/* The same in float precision (powf: within an ulp or two of the float of
 * transfer(), some 3 times faster), for il_tonemap's float output. */
static inline float transfer_float(const il_tonemap_plan *p, double v)
{
    if (!(v > 0.0))
        return 0.0f;
    if (v >= 1.0)
        return 1.0f;
    float f = (float)v;
    if (p->op == IL_TONEMAP_GAMMA)
        return powf(f, (float)p->inv_gamma);
    return f <= 0.0031308f ? 12.92f * f : 1.055f * powf(f, 1.0f / 2.4f) - 0.055f;
}

/* 8-bit codes round(255 transfer(v)) by table: thresholds[k] is the smallest
 * v whose code is k or more, found by bisection over the doubles, so the
 * lookup (8 comparisons) gives the same code as the formula (which is
 * monotonic) without a pow() per channel. */
static void make_thresholds(il_tonemap_plan *p)
{
    p->thresholds[0] = -INFINITY;
    for (int k = 1; k < 256; k++) {
        /* doubles in [0, 1] are ordered like their bit patterns */
        uint64_t lo = 0, hi = 0x3ff0000000000000ull; /* code(lo) < k <= code(hi) */
        while (hi - lo > 1) {
            uint64_t mid = lo + (hi - lo) / 2;
            double v;
            memcpy(&v, &mid, sizeof v);
            if (lrint(transfer(p, v) * 255.0) >= k)
                hi = mid;
            else
                lo = mid;
        }
        memcpy(&p->thresholds[k], &hi, sizeof hi);
    }
}

static inline unsigned char code_of(const il_tonemap_plan *p, double v)
{
    int c = 0;
    for (int step = 128; step > 0; step >>= 1)
        if (v >= p->thresholds[c + step])
            c += step;
    return (unsigned char)c;
}

void il_tonemap_run(const il_tonemap_plan *p, float *out_rgb, unsigned char *out_codes)
{
    const size_t n = (size_t)p->width * p->height;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double d[3];
        curve(p, i, d);
        for (int k = 0; k < 3; k++) {
            if (out_rgb)
                out_rgb[3 * i + k] = transfer_float(p, d[k]);
            if (out_codes)
                out_codes[3 * i + k] = code_of(p, d[k]);
        }
    }
}

/* ------------------------------------------------------- auto exposure */

/* Luminance of pixel i as a float key (0 for black or non-finite pixels). */
static inline float pixel_key(const float *rgb, size_t i)
{
    double c[3];
    load_pixel(rgb + 3 * i, 1.0, c);
    return (float)luminance(c);
}

static inline uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* The nearest-rank percentile (Hyndman and Fan 1996, definition 1: the
 * inverse of the empirical distribution function), found by a two-pass radix
 * select on the bits of positive floats, which sort as unsigned integers:
 * exact, O(n), and no sort. */
double il_luminance_percentile(const il_image *in, double percent)
{
    if (!in || !in->rgb || in->width == 0 || in->height == 0)
        return 0.0;
    const size_t n = (size_t)in->width * in->height;
    size_t *hist = calloc(65536, sizeof *hist);
    if (!hist)
        return 0.0;
    size_t lit = 0;
    for (size_t i = 0; i < n; i++) {
        float l = pixel_key(in->rgb, i);
        if (l > 0.0f) {
            hist[float_bits(l) >> 16]++;
            lit++;
        }
    }
    double result = 0.0;
    if (lit > 0) {
        if (!(percent > 0.0))
            percent = 1e-9;
        if (percent > 100.0)
            percent = 100.0;
        /* rank (1-based) = ceil(p n / 100); the relative 1e-12 keeps an exact
         * product such as 99% of 100 from rounding up past 99. */
        double r = ceil(percent * (double)lit / 100.0 * (1.0 - 1e-12));
        size_t rank = r < 1.0 ? 1 : r > (double)lit ? lit : (size_t)r;
        size_t below = 0;
        uint32_t hi = 0;
        while (below + hist[hi] < rank)
            below += hist[hi++];
        memset(hist, 0, 65536 * sizeof *hist);
        for (size_t i = 0; i < n; i++) {
            float l = pixel_key(in->rgb, i);
            uint32_t b = float_bits(l);
            if (l > 0.0f && b >> 16 == hi)
                hist[b & 0xffffu]++;
        }
        uint32_t lo = 0;
        while (below + hist[lo] < rank)
            below += hist[lo++];
        uint32_t bits = hi << 16 | lo;
        float v;
        memcpy(&v, &bits, sizeof v);
        result = v;
    }
    free(hist);
    return result;
}

/* ----------------------------------------------------------------- plan */

il_status il_tonemap_plan_make(const il_image *in, const il_tonemap_desc *desc,
                               il_tonemap_plan *plan, il_error *err)
{
    memset(plan, 0, sizeof *plan);
    if (!in || !in->rgb || in->width == 0 || in->height == 0)
        return il_fail(err, IL_ERR_INVALID, "tonemap: empty input image");
    il_status st = il_tonemap_check(desc, err);
    if (st != IL_OK)
        return st;
    il_tonemap_desc d = desc ? *desc : (il_tonemap_desc){0};
    plan->op = d.op;
    plan->width = in->width;
    plan->height = in->height;
    plan->src = in->rgb;
    plan->scale = exp2((double)d.exposure);
    plan->exposure_ev = d.exposure;
    if (d.auto_exposure) {
        /* The percentile of the lit pixels maps to 1: a robust maximum (the
         * true maximum is a light source or a firefly), and black background
         * does not count, so the framing does not move it
         * (docs/tonemapping.md#auto-exposure). */
        double lp = il_luminance_percentile(in, d.auto_percentile > 0.0f ? d.auto_percentile : 99.0);
        plan->auto_luminance = lp;
        if (lp > 0.0) { /* an all-black image keeps the manual exposure */
            plan->scale /= lp;
            plan->exposure_ev -= log2(lp);
        }
    }
    plan->inv_gamma = 1.0 / (d.gamma > 0.0f ? d.gamma : 2.2);
    make_thresholds(plan);

    const size_t n = (size_t)in->width * in->height;
    if (d.bloom > 0.0f) {
        plan->owned = il_malloc(n * 3 * sizeof(float), err);
        if (!plan->owned)
            return IL_ERR_MEMORY;
        for (size_t i = 0; i < n; i++) {
            double c[3];
            load_pixel(in->rgb + 3 * i, plan->scale, c);
            for (int k = 0; k < 3; k++)
                plan->owned[3 * i + k] =
                    (float)(c[k] < IL_TONEMAP_MAX_VALUE ? c[k] : IL_TONEMAP_MAX_VALUE);
        }
        double diagonal = hypot((double)in->width, (double)in->height);
        double radius = d.bloom_radius > 0.0f ? d.bloom_radius : 0.02;
        st = il_bloom_apply(plan->owned, in->width, in->height, d.bloom,
                            d.bloom_threshold > 0.0f ? d.bloom_threshold : 1.0, radius * diagonal,
                            err);
        if (st != IL_OK) {
            il_tonemap_plan_free(plan);
            return st;
        }
        plan->src = plan->owned;
        plan->scale = 1.0;
    }
    if (plan->op == IL_TONEMAP_REINHARD) {
        if (d.white > 0.0f) {
            plan->white = d.white;
        } else { /* Reinhard et al.: "by default ... the maximum luminance in the scene" */
            double max = 0.0;
            for (size_t i = 0; i < n; i++) {
                double c[3];
                load_pixel(plan->src + 3 * i, plan->scale, c);
                double l = luminance(c);
                if (l > max)
                    max = l;
            }
            plan->white = max;
        }
    }
    return IL_OK;
}

void il_tonemap_plan_free(il_tonemap_plan *plan)
{
    if (!plan)
        return;
    free(plan->owned);
    plan->owned = NULL;
    plan->src = NULL;
}

/* ------------------------------------------------------------ public */

il_status il_tonemap(const il_image *in, const il_tonemap_desc *desc, il_image *out,
                     il_error *err)
{
    if (!out)
        return il_fail(err, IL_ERR_INVALID, "il_tonemap: output image is NULL");
    if (in && (in->width > IL_IMAGE_MAX_SIDE || in->height > IL_IMAGE_MAX_SIDE))
        return il_fail(err, IL_ERR_INVALID, "il_tonemap: image size %ux%u exceeds %u per side",
                       in->width, in->height, IL_IMAGE_MAX_SIDE);
    il_tonemap_plan plan;
    il_status st = il_tonemap_plan_make(in, desc, &plan, err);
    if (st != IL_OK)
        return st;
    il_image result = {0};
    st = il_image_alloc(&result, in->width, in->height, err);
    if (st == IL_OK)
        il_tonemap_run(&plan, result.rgb, NULL);
    il_tonemap_plan_free(&plan);
    if (st != IL_OK)
        return st;
    if (out == in)
        il_image_free(out);
    *out = result;
    return IL_OK;
}
