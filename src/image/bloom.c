/* Energy-preserving bloom: see bloom.h for the model and its sources.
 *
 * Layout of the work: the bright part of the image goes into a layer at
 * full resolution; level k is level k-1 taken down the pyramid to res[k] and
 * blurred further there (horizontal passes on blocks of rows, vertical
 * passes on column strips: blocks small enough to stay in cache, laid out so
 * that the running sums of many lines run side by side in the vector
 * units).  The levels are then summed from the coarsest up (weighted, each
 * sum taken one pyramid step up before the next level is added) onto the
 * image the bright part was taken from.  Rows, blocks and strips are
 * independent, so the number of threads never changes the result. */
#include "image/bloom.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"

/* Floats per block row of the box passes: the lanes of the running sums. */
#define STRIP 64
/* Image rows per block of the horizontal passes. */
#define ROWS (STRIP / 3)

/* ----------------------------------------------------------- the kernel */

/* Variance of an extended box (Gwosdek et al. 2011): 2r+1 ones and alpha
 * at -(r+1) and r+1; the second moment of the weights over their sum,
 * (sum_{|d|<=r} d^2 + 2 alpha (r+1)^2) / (2r + 1 + 2 alpha). */
static double ext_box_variance(int r, double alpha)
{
    double rr = r;
    return (rr * (rr + 1.0) * (2.0 * rr + 1.0) / 3.0 + 2.0 * alpha * (rr + 1.0) * (rr + 1.0)) /
           (2.0 * rr + 1.0 + 2.0 * alpha);
}

/* The extended box of variance t: the largest plain box below it, and the
 * end weight that makes up the rest (the variance above solved for alpha). */
static void ext_box(double t, int *radius, double *alpha)
{
    if (!(t > 0.0)) {
        *radius = 0;
        *alpha = 0.0;
        return;
    }
    int r = (int)floor((sqrt(1.0 + 12.0 * t) - 1.0) / 2.0);
    while ((r + 1.0) * (r + 2.0) / 3.0 <= t) /* plain box of radius r: r(r+1)/3 */
        r++;
    while (r > 0 && r * (r + 1.0) / 3.0 > t)
        r--;
    double a = (t * (2.0 * r + 1.0) - r * (r + 1.0) * (2.0 * r + 1.0) / 3.0) /
               (2.0 * (r + 1.0) * (r + 1.0) - 2.0 * t);
    *radius = r;
    *alpha = a < 0.0 ? 0.0 : a > 1.0 ? 1.0 : a;
}

void il_bloom_kernel_make(double sigma, il_bloom_kernel *k)
{
    memset(k, 0, sizeof *k);
    if (!(sigma > 0.0))
        sigma = 0.0;
    if (sigma > 1e6) /* wider than any image (65536 per side) already */
        sigma = 1e6;
    double blur = 0.0; /* variance of the box passes so far, image pixels^2 */
    int j = 0;
    for (int l = 0; l < IL_BLOOM_LEVELS; l++) {
        double s = sigma * ldexp(1.0, l - (IL_BLOOM_LEVELS - 1));
        while (j < 20 && s >= IL_BLOOM_MIN_SIGMA * ldexp(1.0, j + 1))
            j++;
        k->res[l] = j;
        /* Pyramid step i (down, and up again) adds 1 + 1 pixel^2 of level i. */
        double steps = 2.0 * (ldexp(1.0, 2 * j) - 1.0) / 3.0;
        double scale = ldexp(1.0, 2 * j); /* pixels^2 of level j in image pixels^2 */
        double inc = (s * s - steps - blur) / scale;
        ext_box(inc > 0.0 ? inc / IL_BLOOM_PASSES : 0.0, &k->box_radius[l], &k->box_alpha[l]);
        blur += IL_BLOOM_PASSES * ext_box_variance(k->box_radius[l], k->box_alpha[l]) * scale;
        k->variance[l] = blur + steps;
        k->weight[l] = 1.0 / IL_BLOOM_LEVELS;
    }
}

/* ------------------------------------------------------------ the work */

typedef struct plane {
    float *rgb;
    int w, h;
} plane;

typedef struct bloom_work {
    int nthreads;
    float *tmp;               /* per thread: 2 buffers of tmp_size floats */
    size_t tmp_size;
    double *acc;              /* per thread: STRIP running sums */
    double *inv_x, *inv_y;    /* 1 / N of the level's boxes along x and y */
} bloom_work;

static int thread_id(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

/* 1 / N(j): N(j) is the weight source j's box puts inside a line of n
 * (2r+1+2 alpha away from the ends).  Dividing the source by it before the
 * box sum makes the pass spread every source with weights that sum to 1. */
static void inverse_counts(int n, int r, double alpha, double *inv)
{
    for (int j = 0; j < n; j++) {
        long lo = (long)j - r < 0 ? 0 : (long)j - r;
        long hi = (long)j + r > n - 1 ? n - 1 : (long)j + r;
        double w = (double)(hi - lo + 1);
        if ((long)j - r - 1 >= 0)
            w += alpha;
        if ((long)j + r + 1 <= n - 1)
            w += alpha;
        inv[j] = 1.0 / w;
    }
}

/* One normalised extended-box pass along a line of n samples, for s lines
 * at once: `in` and `out` hold n rows of s floats (row j: sample j of every
 * line), acc holds s running sums (double: a float sum would keep an error
 * of 2^-24 of a bright pixel for the rest of the line).  With y = in / N:
 *   out[i] = sum over |i-j| <= r of y[j] + alpha (y[i-r-1] + y[i+r+1]).
 * Rows outside the line enter with weight 0. */
static void box_lines(const float *restrict in, float *restrict out, int n, int s, int r,
                      double alpha, const double *restrict inv, double *restrict acc)
{
    for (int x = 0; x < s; x++)
        acc[x] = 0.0;
    int first = r < n - 1 ? r : n - 1;
    for (int j = 0; j <= first; j++) {
        const float *restrict row = in + (size_t)j * s;
        double w = inv[j];
        for (int x = 0; x < s; x++)
            acc[x] += row[x] * w;
    }
    for (int i = 0; i < n; i++) {
        long lo = (long)i - r - 1, hi = (long)i + r + 1, sub = (long)i - r;
        const float *restrict rlo = lo >= 0 ? in + (size_t)lo * s : in;
        const float *restrict rhi = hi < n ? in + (size_t)hi * s : in;
        const float *restrict rsub = sub >= 0 ? in + (size_t)sub * s : in;
        double wlo = lo >= 0 ? alpha * inv[lo] : 0.0;
        double add = hi < n ? inv[hi] : 0.0, whi = alpha * add;
        double wsub = sub >= 0 ? inv[sub] : 0.0;
        float *restrict o = out + (size_t)i * s;
        for (int x = 0; x < s; x++) {
            double v = acc[x] + rlo[x] * wlo + rhi[x] * whi;
            o[x] = v > 0.0 ? (float)v : 0.0f;
            acc[x] += rhi[x] * add - rsub[x] * wsub;
        }
    }
}

/* Runs the level's passes on t0 (n rows of s floats); returns the buffer
 * (t0 or t1) that holds the result. */
static float *box_cascade(float *t0, float *t1, int n, int s, int radius, double alpha,
                          const double *inv, double *acc)
{
    if (radius == 0 && alpha == 0.0) /* the identity */
        return t0;
    float *cur = t0;
    for (int p = 0; p < IL_BLOOM_PASSES; p++) {
        float *dst = cur == t0 ? t1 : t0;
        box_lines(cur, dst, n, s, radius, alpha, inv, acc);
        cur = dst;
    }
    return cur;
}

/* The horizontal passes, ROWS image rows at a time, gathered so that sample
 * x of those rows is one row of 3 * ROWS floats. */
static void blur_rows(bloom_work *b, plane *p, int radius, double alpha)
{
    const int w = p->w, h = p->h;
    const int blocks = (h + ROWS - 1) / ROWS;
#pragma omp parallel for schedule(static) num_threads(b->nthreads)
    for (int bi = 0; bi < blocks; bi++) {
        int y0 = bi * ROWS, rows = h - y0 < ROWS ? h - y0 : ROWS, s = 3 * rows;
        int t = thread_id();
        float *t0 = b->tmp + (size_t)t * 2 * b->tmp_size, *t1 = t0 + b->tmp_size;
        for (int k = 0; k < rows; k++) {
            const float *src = p->rgb + (size_t)(y0 + k) * w * 3;
            for (int x = 0; x < w; x++) {
                float *d = t0 + (size_t)x * s + 3 * k;
                d[0] = src[3 * x];
                d[1] = src[3 * x + 1];
                d[2] = src[3 * x + 2];
            }
        }
        float *cur =
            box_cascade(t0, t1, w, s, radius, alpha, b->inv_x, b->acc + (size_t)t * STRIP);
        for (int k = 0; k < rows; k++) {
            float *dst = p->rgb + (size_t)(y0 + k) * w * 3;
            for (int x = 0; x < w; x++) {
                const float *c = cur + (size_t)x * s + 3 * k;
                dst[3 * x] = c[0];
                dst[3 * x + 1] = c[1];
                dst[3 * x + 2] = c[2];
            }
        }
    }
}

/* The vertical passes on strips of STRIP floats of every row. */
static void blur_columns(bloom_work *b, plane *p, int radius, double alpha)
{
    const int h = p->h;
    const size_t pitch = (size_t)p->w * 3;
    const int strips = (int)((pitch + STRIP - 1) / STRIP);
#pragma omp parallel for schedule(static) num_threads(b->nthreads)
    for (int si = 0; si < strips; si++) {
        size_t x0 = (size_t)si * STRIP;
        int s = (int)(pitch - x0 < STRIP ? pitch - x0 : STRIP);
        int t = thread_id();
        float *t0 = b->tmp + (size_t)t * 2 * b->tmp_size, *t1 = t0 + b->tmp_size;
        for (int y = 0; y < h; y++)
            memcpy(t0 + (size_t)y * s, p->rgb + y * pitch + x0, sizeof(float) * (size_t)s);
        float *cur =
            box_cascade(t0, t1, h, s, radius, alpha, b->inv_y, b->acc + (size_t)t * STRIP);
        for (int y = 0; y < h; y++)
            memcpy(p->rgb + y * pitch + x0, cur + (size_t)y * s, sizeof(float) * (size_t)s);
    }
}

static void blur(bloom_work *b, plane *p, int radius, double alpha)
{
    if (radius == 0 && alpha == 0.0)
        return;
    inverse_counts(p->w, radius, alpha, b->inv_x);
    inverse_counts(p->h, radius, alpha, b->inv_y);
    blur_rows(b, p, radius, alpha);
    blur_columns(b, p, radius, alpha);
}

/* ------------------------------------------------------------ pyramid */

/* Size of the next coarser level: nodes at fine positions 0, 2, ..., so
 * that every fine pixel has a node at it or on both sides. */
static int coarse_size(int n)
{
    return n / 2 + 1;
}

/* A plane of w x h pixels, zeroed when `zero`. */
static il_status plane_alloc(plane *p, int w, int h, bool zero, il_error *err)
{
    p->w = w;
    p->h = h;
    size_t n = (size_t)w * h * 3;
    p->rgb = zero ? il_calloc(n, sizeof(float), err) : il_malloc(n * sizeof(float), err);
    return p->rgb ? IL_OK : IL_ERR_MEMORY;
}

/* One axis of a pyramid step as a gather: output pixel o takes
 * sum over q < count of w[q] * input pixel (first + q). */
typedef struct taps {
    int first, count;
    float w[5];
} taps;

/* Cubic B-spline subdivision (Lane and Riesenfeld 1980): coarse pixel c
 * sits on fine pixel 2c and spreads over fine 2c-2 .. 2c+2 with
 * (1, 4, 6, 4, 1)/16. */
static const double spline[5] = {1.0 / 16, 4.0 / 16, 6.0 / 16, 4.0 / 16, 1.0 / 16};

/* Weight with which fine pixel f (of n) sends its light to coarse pixel c
 * (of m): the subdivision transposed, doubled (1 per fine pixel), divided by
 * its sum over the coarse pixels inside. */
static double down_weight(int f, int c, int n, int m)
{
    (void)n;
    double total = 0.0, mine = 0.0;
    for (int cc = (f - 2 + 1) / 2 - 1; cc <= (f + 2) / 2 + 1; cc++) {
        int d = f - 2 * cc;
        if (d < -2 || d > 2 || cc < 0 || cc >= m)
            continue;
        total += spline[d + 2];
        if (cc == c)
            mine = spline[d + 2];
    }
    return total > 0.0 ? mine / total : 0.0;
}

/* Weight with which coarse pixel c (of m) sends its light to fine pixel f
 * (of n): the subdivision, divided by its sum over the fine pixels inside. */
static double up_weight(int c, int f, int n)
{
    double total = 0.0;
    for (int d = -2; d <= 2; d++)
        if (2 * c + d >= 0 && 2 * c + d < n)
            total += spline[d + 2];
    int d = f - 2 * c;
    return d >= -2 && d <= 2 && total > 0.0 ? spline[d + 2] / total : 0.0;
}

/* Gather taps down (fine n -> coarse m, out has m) or up (coarse m -> fine
 * n, out has n). */
static void make_taps(bool down, int n, int m, taps *out)
{
    int outputs = down ? m : n;
    for (int o = 0; o < outputs; o++) {
        taps *t = &out[o];
        int lo = down ? 2 * o - 2 : (o - 2 + 1) / 2, hi = down ? 2 * o + 2 : (o + 2) / 2;
        if (!down && o - 2 < 0)
            lo = 0;
        int limit = down ? n : m;
        if (lo < 0)
            lo = 0;
        if (hi > limit - 1)
            hi = limit - 1;
        t->first = lo;
        t->count = 0;
        for (int i = lo; i <= hi && t->count < 5; i++)
            t->w[t->count++] = (float)(down ? down_weight(i, o, n, m) : up_weight(i, o, n));
    }
}

/* tmp = the gather of `in` along x through tx (tmp: out_w x in->h). */
static void resample_x(const plane *in, plane *tmp, const taps *tx, int nthreads)
{
    const int iw = in->w, ow = tmp->w, h = in->h;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int y = 0; y < h; y++) {
        const float *row = in->rgb + (size_t)y * iw * 3;
        float *o = tmp->rgb + (size_t)y * ow * 3;
        for (int ox = 0; ox < ow; ox++) {
            const taps *t = &tx[ox];
            const float *px = row + 3 * (size_t)t->first;
            float r = 0.0f, g = 0.0f, bl = 0.0f;
            for (int q = 0; q < t->count; q++) {
                r += t->w[q] * px[3 * q];
                g += t->w[q] * px[3 * q + 1];
                bl += t->w[q] * px[3 * q + 2];
            }
            o[3 * ox] = r;
            o[3 * ox + 1] = g;
            o[3 * ox + 2] = bl;
        }
    }
}

/* out (= or +=) the gather of tmp along y through ty: whole rows at once. */
static void resample_y(const plane *tmp, plane *out, const taps *ty, bool add, int nthreads)
{
    const size_t pitch = (size_t)out->w * 3;
    const int oh = out->h;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (int oy = 0; oy < oh; oy++) {
        float *restrict o = out->rgb + (size_t)oy * pitch;
        if (!add)
            for (size_t x = 0; x < pitch; x++)
                o[x] = 0.0f;
        const taps *t = &ty[oy];
        for (int q = 0; q < t->count; q++) {
            const float *restrict row = tmp->rgb + (size_t)(t->first + q) * pitch;
            float wq = t->w[q];
            for (size_t x = 0; x < pitch; x++)
                o[x] += wq * row[x];
        }
    }
}

/* out (= or +=) the separable gather of `in` through tx, ty. */
static il_status resample(const plane *in, plane *out, const taps *tx, const taps *ty, bool add,
                          int nthreads, il_error *err)
{
    plane tmp = {il_malloc((size_t)out->w * in->h * 3 * sizeof(float), err), out->w, in->h};
    if (!tmp.rgb)
        return IL_ERR_MEMORY;
    resample_x(in, &tmp, tx, nthreads);
    resample_y(&tmp, out, ty, add, nthreads);
    free(tmp.rgb);
    return IL_OK;
}

/* coarse = down(fine); the taps buffer holds coarse->w + coarse->h taps. */
static il_status down(const plane *fine, plane *coarse, taps *buf, int nthreads, il_error *err)
{
    make_taps(true, fine->w, coarse->w, buf);
    make_taps(true, fine->h, coarse->h, buf + coarse->w);
    return resample(fine, coarse, buf, buf + coarse->w, false, nthreads, err);
}

/* fine += up(coarse); the taps buffer holds fine->w + fine->h taps. */
static il_status up_add(const plane *coarse, plane *fine, taps *buf, int nthreads, il_error *err)
{
    make_taps(false, fine->w, coarse->w, buf);
    make_taps(false, fine->h, coarse->h, buf + fine->w);
    return resample(coarse, fine, buf, buf + fine->w, true, nthreads, err);
}

/* dst += weight * src (same size). */
static void add_scaled(plane *dst, const plane *src, float weight, int nthreads)
{
    const size_t n = (size_t)dst->w * dst->h * 3;
#pragma omp parallel for schedule(static) num_threads(nthreads)
    for (size_t i = 0; i < n; i++)
        dst->rgb[i] += weight * src->rgb[i];
}

/* ----------------------------------------------------------------- apply */

/* Moves strength * (L - T) / L of every pixel whose Rec.709 luminance L
 * (ITU-R BT.709-6, item 3.2) is above T into the layer (the hue is kept: all
 * three channels by the same factor).  Returns whether any pixel was. */
static bool extract_bright(float *img, float *layer, size_t n, double strength,
                           double threshold, int nthreads)
{
    int any = 0;
    const float t = (float)threshold, k = (float)strength;
#pragma omp parallel for schedule(static) num_threads(nthreads) reduction(| : any)
    for (size_t i = 0; i < n; i++) {
        float *c = img + 3 * i, *l = layer + 3 * i;
        float lum = 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
        float f = lum > t ? k * (lum - t) / lum : 0.0f; /* 0: c - 0 leaves c as it was */
        for (int q = 0; q < 3; q++) {
            l[q] = c[q] * f;
            c[q] -= l[q];
        }
        any |= f > 0.0f;
    }
    return any != 0;
}

il_status il_bloom_apply(float *rgb, uint32_t width, uint32_t height, double strength,
                         double threshold, double sigma, il_error *err)
{
    if (!rgb || width == 0 || height == 0)
        return il_fail(err, IL_ERR_INVALID, "bloom: empty image");
    if (!(strength >= 0.0 && strength <= 1.0) || !(threshold > 0.0) || !isfinite(threshold) ||
        !(sigma >= 0.0) || !isfinite(sigma))
        return il_fail(err, IL_ERR_INVALID,
                       "bloom: strength %g (0..1), threshold %g (> 0) or radius %g (>= 0) out of range",
                       strength, threshold, sigma);
    if (strength == 0.0)
        return IL_OK;

    bloom_work b = {.nthreads = 1};
#ifdef _OPENMP
    b.nthreads = omp_get_max_threads();
    if (b.nthreads < 1)
        b.nthreads = 1;
#endif
    il_bloom_kernel k;
    il_bloom_kernel_make(sigma, &k);
    const int w = (int)width, h = (int)height;
    const size_t n = (size_t)width * height;

    /* Planes: levels[l] is level l's blurred light at res k.res[l]; the
     * pyramid steps in between are freed as soon as they are used. */
    plane levels[IL_BLOOM_LEVELS] = {{0}};
    plane image = {rgb, w, h};
    plane acc = {0};
    il_status st = IL_OK;
    b.tmp_size = (size_t)(w > h ? w : h) * STRIP;
    b.tmp = il_malloc((size_t)b.nthreads * 2 * b.tmp_size * sizeof(float), err);
    b.acc = il_malloc((size_t)b.nthreads * STRIP * sizeof(double), err);
    double *inv = il_malloc(((size_t)width + height) * sizeof(double), err);
    taps *tp = il_malloc(sizeof(taps) * ((size_t)width + height), err);
    if (!b.tmp || !b.acc || !inv || !tp || plane_alloc(&levels[0], w, h, false, err) != IL_OK) {
        st = IL_ERR_MEMORY;
        goto done;
    }
    b.inv_x = inv;
    b.inv_y = inv + width;
    if (!extract_bright(rgb, levels[0].rgb, n, strength, threshold, b.nthreads))
        goto done; /* nothing above the threshold: the image is untouched */

    /* Down the pyramid: level l starts as level l-1 (level 0 as the bright
     * layer), brought down to res[l], and is blurred further there. */
    for (int l = 0; l < IL_BLOOM_LEVELS; l++) {
        int res = l == 0 ? 0 : k.res[l - 1];
        if (l > 0 && res == k.res[l]) {
            const plane *prev = &levels[l - 1];
            if ((st = plane_alloc(&levels[l], prev->w, prev->h, false, err)) != IL_OK)
                goto done;
            memcpy(levels[l].rgb, prev->rgb, sizeof(float) * 3 * (size_t)prev->w * prev->h);
        }
        const plane *src = l == 0 ? &levels[0] : &levels[l - 1];
        for (; res < k.res[l]; res++) {
            plane coarse;
            st = plane_alloc(&coarse, coarse_size(src->w), coarse_size(src->h), false, err);
            if (st != IL_OK)
                goto done;
            st = down(src, &coarse, tp, b.nthreads, err);
            if (src == &levels[l]) /* this level's own previous step */
                free(levels[l].rgb);
            levels[l] = coarse;
            if (st != IL_OK)
                goto done;
            src = &levels[l];
        }
        blur(&b, &levels[l], k.box_radius[l], k.box_alpha[l]);
    }

    /* Up: acc = w_L levels[L]; then, step by step up to the next level's
     * resolution, adding each level; at last onto the image itself. */
    for (int l = IL_BLOOM_LEVELS; l >= 0; l--) {
        int target = l > 0 ? k.res[l - 1] : 0; /* resolution of what comes next */
        if (l == IL_BLOOM_LEVELS) {
            acc = levels[l - 1];
            levels[l - 1].rgb = NULL;
            float wl = (float)k.weight[l - 1];
            for (size_t i = 0; i < (size_t)acc.w * acc.h * 3; i++)
                acc.rgb[i] *= wl;
            continue;
        }
        for (int res = k.res[l]; res > target; res--) {
            /* the size at res - 1: from the image down */
            int fw = w, fh = h;
            for (int q = 0; q < res - 1; q++) {
                fw = coarse_size(fw);
                fh = coarse_size(fh);
            }
            plane fine = image;
            if (res - 1 > 0 && (st = plane_alloc(&fine, fw, fh, true, err)) != IL_OK)
                goto done;
            st = up_add(&acc, &fine, tp, b.nthreads, err);
            free(acc.rgb);
            acc = res - 1 > 0 ? fine : (plane){0};
            if (st != IL_OK)
                goto done;
        }
        if (l > 0) { /* add level l-1 */
            if (acc.rgb)
                add_scaled(&acc, &levels[l - 1], (float)k.weight[l - 1], b.nthreads);
            else /* at the image's resolution: acc is the image itself */
                add_scaled(&image, &levels[l - 1], (float)k.weight[l - 1], b.nthreads);
        }
    }
    if (acc.rgb) /* every level at the image's resolution: acc is a sum beside it */
        add_scaled(&image, &acc, 1.0f, b.nthreads);
done:
    for (int l = 0; l < IL_BLOOM_LEVELS; l++)
        free(levels[l].rgb);
    free(acc.rgb);
    free(tp);
    free(inv);
    free(b.acc);
    free(b.tmp);
    return st;
}
