/* il_envmap_convert: resampling an environment map from one mapping to
 * another.  Each output texel is the solid-angle mean of the input's
 * bilinear lookups over the texel's footprint on the sphere, estimated by
 * S x S points spread over the texel, each weighted by the output
 * mapping's Jacobian dOmega/d(u,v) at it (envmap.c); so the mean radiance
 * over the sphere, the light the map gives, is kept.  S grows with the
 * ratio of output to input texel size (a coarse output averages many input
 * texels). */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "image/envmap.h"

#define IL_ENV_CONVERT_MAX_WIDTH 16384u

/* Radians per texel near the middle of a map: a lat-long map spans pi in
 * its height, an angular map pi in its radius (half the width), a cube
 * face pi/2 on average over its width (a third of the cross's). */
static double texel_angle(il_env_mapping m, uint32_t width, uint32_t height)
{
    const double pi = 3.14159265358979323846;
    switch (m) {
    case IL_ENV_ANGULAR: return 2.0 * pi / width;
    case IL_ENV_CROSS: return pi / 2.0 / (width / 3);
    case IL_ENV_LATLONG:
    default: return pi / height;
    }
}

/* The output size: from `width` when given, else from the texel angle. */
static il_status output_size(il_env_mapping to, uint32_t width, double angle, uint32_t *w, uint32_t *h,
                             il_error *err)
{
    const double pi = 3.14159265358979323846;
    if (width == 0) {
        switch (to) {
        case IL_ENV_ANGULAR: width = (uint32_t)fmax(1.0, round(2.0 * pi / angle)); break;
        case IL_ENV_CROSS: width = 3 * (uint32_t)fmax(1.0, round(pi / 2.0 / angle)); break;
        case IL_ENV_LATLONG:
        default: width = 2 * (uint32_t)fmax(1.0, round(pi / angle)); break;
        }
        if (width > IL_ENV_CONVERT_MAX_WIDTH)
            width = to == IL_ENV_CROSS ? IL_ENV_CONVERT_MAX_WIDTH / 3 * 3 : IL_ENV_CONVERT_MAX_WIDTH;
    }
    if (width > IL_ENV_CONVERT_MAX_WIDTH)
        return il_fail(err, IL_ERR_INVALID, "envmap convert: width %u is more than %u", width,
                       IL_ENV_CONVERT_MAX_WIDTH);
    switch (to) {
    case IL_ENV_ANGULAR:
        *w = *h = width;
        return IL_OK;
    case IL_ENV_CROSS:
        if (width % 3 != 0)
            return il_fail(err, IL_ERR_INVALID,
                           "envmap convert: a cross's width must be divisible by 3, not %u", width);
        *w = width;
        *h = width / 3 * 4;
        return IL_OK;
    case IL_ENV_LATLONG:
        if (width < 2 || width % 2 != 0)
            return il_fail(err, IL_ERR_INVALID,
                           "envmap convert: a lat-long map's width must be even (2:1), not %u", width);
        *w = width;
        *h = width / 2;
        return IL_OK;
    }
    return il_fail(err, IL_ERR_INVALID, "envmap convert: unknown target mapping %d", (int)to);
}

il_status il_envmap_convert(const il_image *src, il_env_mapping from, il_env_mapping to,
                            uint32_t width, il_image *dst, il_error *err)
{
    if (!dst)
        return il_fail(err, IL_ERR_INVALID, "envmap convert: no output image");
    dst->width = dst->height = 0;
    dst->rgb = NULL;
    il_status st = il_envmap_check(src, from, "input map", err);
    if (st != IL_OK)
        return st;
    double angle_in = texel_angle(from, src->width, src->height);
    uint32_t w, h;
    if ((st = output_size(to, width, angle_in, &w, &h, err)) != IL_OK)
        return st;
    if ((st = il_image_alloc(dst, w, h, err)) != IL_OK)
        return st;
    double ratio = texel_angle(to, w, h) / angle_in;
    int S = (int)ceil(4.0 * ratio);
    S = S < 4 ? 4 : (S > 16 ? 16 : S);

#pragma omp parallel for schedule(dynamic, 4)
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < w; x++) {
            double acc[3] = {0, 0, 0}, wsum = 0.0;
            for (int sy = 0; sy < S; sy++) {
                for (int sx = 0; sx < S; sx++) {
                    il_vec2 uv = v2(((float)x + ((float)sx + 0.5f) / S) / (float)w,
                                    ((float)y + ((float)sy + 0.5f) / S) / (float)h);
                    il_vec3 d;
                    float j = il_envmap_jacobian(to, uv);
                    if (!(j > 0.0f) || !il_envmap_uv_to_dir(to, uv, &d))
                        continue;
                    il_vec3 L = il_envmap_lookup(src, from, d);
                    acc[0] += (double)L.x * j;
                    acc[1] += (double)L.y * j;
                    acc[2] += (double)L.z * j;
                    wsum += j;
                }
            }
            float *p = dst->rgb + 3 * ((size_t)y * w + x);
            for (int c = 0; c < 3; c++)
                p[c] = wsum > 0.0 ? (float)(acc[c] / wsum) : 0.0f;
        }
    }
    return IL_OK;
}
