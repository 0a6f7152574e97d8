/* il_image_compare: the error metrics every validation test, benchmark and
 * `illum compare` uses.  With N = 3 * width * height channel values a_i of
 * the test image and b_i of the reference:
 *
 *     rmse          = sqrt( (1/N) sum (a_i - b_i)^2 )
 *     rel_mse       = (1/N) sum (a_i - b_i)^2 / (b_i^2 + 0.01)
 *                     (relative MSE as in Rousselle et al., "Adaptive
 *                     rendering with non-local means filtering", SIGGRAPH
 *                     Asia 2012, with epsilon 0.01)
 *     mean_lum_x    = mean over pixels of 0.2126 R + 0.7152 G + 0.0722 B
 *                     (ITU-R BT.709-6, item 3.2)
 *     max_abs_error = max |a_i - b_i|
 *
 * A non-finite value (NaN or Inf) in either image at a channel counts as an
 * infinite error there, so it cannot hide in an average: rmse, rel_mse and
 * max_abs_error become +Inf and the diff image holds +Inf at that channel.
 * The mean luminances are plain means (a NaN makes them NaN). */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "illum/illum.h"

static bool image_ok(const il_image *im)
{
    return im && im->rgb && im->width > 0 && im->height > 0;
}

il_status il_image_compare(const il_image *a, const il_image *b, il_compare_result *out,
                           il_image *diff, il_error *err)
{
    if (!image_ok(a) || !image_ok(b))
        return il_fail(err, IL_ERR_INVALID, "compare: an image is empty");
    if (a->width != b->width || a->height != b->height)
        return il_fail(err, IL_ERR_INVALID, "compare: sizes differ (%ux%u vs reference %ux%u)",
                       a->width, a->height, b->width, b->height);
    if (diff) {
        il_status st = il_image_alloc(diff, a->width, a->height, err);
        if (st != IL_OK)
            return st;
    }
    size_t npix = (size_t)a->width * a->height;
    double sum_sq = 0.0, sum_rel = 0.0, lum_a = 0.0, lum_b = 0.0, max_abs = 0.0;
    bool nonfinite = false;
    static const double lum_w[3] = {0.2126, 0.7152, 0.0722};
    for (size_t p = 0; p < npix; p++) {
        for (int k = 0; k < 3; k++) {
            double va = a->rgb[p * 3 + k], vb = b->rgb[p * 3 + k];
            lum_a += lum_w[k] * va;
            lum_b += lum_w[k] * vb;
            double d = fabs(va - vb);
            if (!isfinite(va) || !isfinite(vb)) {
                nonfinite = true;
                d = INFINITY;
            } else {
                sum_sq += d * d;
                sum_rel += d * d / (vb * vb + 0.01);
                if (d > max_abs)
                    max_abs = d;
            }
            if (diff)
                diff->rgb[p * 3 + k] = (float)d;
        }
    }
    double n = (double)npix * 3.0;
    il_compare_result r = {
        .rmse = nonfinite ? INFINITY : sqrt(sum_sq / n),
        .rel_mse = nonfinite ? INFINITY : sum_rel / n,
        .mean_lum_a = lum_a / (double)npix,
        .mean_lum_b = lum_b / (double)npix,
        .max_abs_error = nonfinite ? INFINITY : max_abs,
    };
    if (out)
        *out = r;
    return IL_OK;
}
