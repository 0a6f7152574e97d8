/* Tone mapping internals (docs/tonemapping.md), shared by il_tonemap
 * (tonemap.c), the PNG writer (png.c) and `illum tonemap`.
 *
 * A plan holds everything decided from the whole image (the exposure with
 * its automatic part, the bloomed copy, Reinhard's white point); mapping a
 * pixel is then independent of every other pixel. */
#ifndef IL_IMAGE_TONEMAP_H
#define IL_IMAGE_TONEMAP_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "illum/illum.h"

/* Values after the exposure are kept at or below this when bloom copies the
 * image into floats (it keeps the glare sums finite); it is far above
 * anything a display value depends on. */
#define IL_TONEMAP_MAX_VALUE 1e30

typedef struct il_tonemap_plan {
    il_tonemap_op op;
    uint32_t width, height;
    const float *src;        /* the HDR values to map: the input, or `owned` */
    float *owned;            /* the exposed and bloomed copy (bloom only) */
    double scale;            /* multiplies src while mapping (1 with `owned`) */
    double inv_gamma;        /* IL_TONEMAP_GAMMA: 1 / gamma */
    double white;            /* IL_TONEMAP_REINHARD: L_white after the exposure */
    double exposure_ev;      /* the exposure in all, EV: manual + automatic */
    double auto_luminance;   /* auto exposure: the percentile's luminance (0: none,
                                or every pixel is black) */
    double thresholds[256];  /* 8-bit codes: the smallest linear display value
                                of code k (k >= 1) */
} il_tonemap_plan;

/* Checks a desc's fields (NULL is valid: linear, EV 0).  IL_ERR_INVALID
 * names the field at fault. */
il_status il_tonemap_check(const il_tonemap_desc *desc, il_error *err);

/* Builds the plan for `in` (bloom runs here).  Free with il_tonemap_plan_free. */
il_status il_tonemap_plan_make(const il_image *in, const il_tonemap_desc *desc,
                               il_tonemap_plan *plan, il_error *err);
void il_tonemap_plan_free(il_tonemap_plan *plan);

/* Maps every pixel: display values in [0,1] into out_rgb (3 floats per
 * pixel), or 8-bit codes round(255 v) into out_codes; one may be NULL. */
void il_tonemap_run(const il_tonemap_plan *plan, float *out_rgb, unsigned char *out_codes);

/* The nearest-rank percentile (0 < percent <= 100) of the Rec.709 luminance
 * over the pixels whose luminance is above 0: the smallest L such that at
 * least percent % of those pixels have luminance <= L.  Pixels with a NaN or
 * infinite channel count as black; negative channels as 0.  Returns 0 when
 * every pixel is black. */
double il_luminance_percentile(const il_image *in, double percent);

/* png.c: writes a PNG of `image` mapped through `desc` (validated). */
il_status il_png_write_tonemapped(const il_image *image, FILE *f, const char *path,
                                  const il_tonemap_desc *desc, il_error *err);

#endif
