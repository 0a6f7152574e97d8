/* Environment maps: mappings, lookups, validation; see envmap.h for the
 * conventions and docs/environment.md for the drawings.  The angular map is
 * Debevec's (Debevec 1998, "Rendering Synthetic Objects into Real Scenes",
 * and his Light Probe Image Gallery); the lat-long and cube mappings are
 * those of pbrt-v3 14.2.4 and Greene 1986 ("Environment Mapping and Other
 * Applications of World Projections"). */
#include "image/envmap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

const char *il_envmap_mapping_name(il_env_mapping m)
{
    switch (m) {
    case IL_ENV_LATLONG: return "latlong";
    case IL_ENV_ANGULAR: return "angular";
    case IL_ENV_CROSS: return "cross";
    }
    return "unknown";
}

bool il_envmap_mapping_from_name(const char *name, il_env_mapping *out)
{
    if (!strcmp(name, "latlong"))
        *out = IL_ENV_LATLONG;
    else if (!strcmp(name, "angular"))
        *out = IL_ENV_ANGULAR;
    else if (!strcmp(name, "cross"))
        *out = IL_ENV_CROSS;
    else
        return false;
    return true;
}

il_env_mapping il_envmap_mapping_for_size(uint32_t width, uint32_t height)
{
    if (width == height)
        return IL_ENV_ANGULAR;
    if ((uint64_t)width * 4 == (uint64_t)height * 3)
        return IL_ENV_CROSS;
    return IL_ENV_LATLONG;
}

il_status il_envmap_check(const il_image *img, il_env_mapping m, const char *what, il_error *err)
{
    if (!what)
        what = "environment map";
    if (!img || !img->rgb || img->width == 0 || img->height == 0)
        return il_fail(err, IL_ERR_INVALID, "%s: the image is empty", what);
    uint32_t w = img->width, h = img->height;
    switch (m) {
    case IL_ENV_LATLONG:
        break;
    case IL_ENV_ANGULAR:
        if (w != h)
            return il_fail(err, IL_ERR_INVALID,
                           "%s: an angular map (light probe) must be square, this one is %ux%u", what,
                           w, h);
        break;
    case IL_ENV_CROSS:
        if (w % 3 != 0 || (uint64_t)w * 4 != (uint64_t)h * 3)
            return il_fail(err, IL_ERR_INVALID,
                           "%s: a vertical cross must be 3 faces wide and 4 tall (3:4, width "
                           "divisible by 3), this one is %ux%u",
                           what, w, h);
        break;
    default:
        return il_fail(err, IL_ERR_INVALID, "%s: unknown mapping %d", what, (int)m);
    }
    size_t n = (size_t)w * h * 3;
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(img->rgb[k])) {
            size_t px = k / 3;
            return il_fail(err, IL_ERR_INVALID, "%s: texel (%zu, %zu) is %s (NaN or infinite)",
                           what, px % w, px / w, isnan(img->rgb[k]) ? "NaN" : "infinite");
        }
        /* Beyond this the sampling tables' sums would overflow a float. */
        if (fabsf(img->rgb[k]) > IL_ENVMAP_MAX_RADIANCE) {
            size_t px = k / 3;
            return il_fail(err, IL_ERR_INVALID, "%s: texel (%zu, %zu) is %g, more than the %g a map "
                           "may hold", what, px % w, px / w, (double)img->rgb[k],
                           (double)IL_ENVMAP_MAX_RADIANCE);
        }
    }
    return IL_OK;
}

/* ------------------------------------------------------------- the cross */

/* The six cells of the vertical cross: column and row of the cell, and the
 * face's centre, right and up directions (envmap.h). */
typedef struct cross_face {
    int col, row;
    il_vec3 c, r, t;
} cross_face;

static const cross_face cross_faces[6] = {
    {1, 1, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}},  /* -z, the front */
    {2, 1, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}},   /* +x */
    {0, 1, {-1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, /* -x */
    {1, 0, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}},   /* +y */
    {1, 2, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}}, /* -y */
    {1, 3, {0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  /* +z, upside down */
};

/* The face a direction falls on (its largest component) and the
 * coordinates (a, b) in [-1,1]^2 on it. */
static int cross_face_of(il_vec3 d, float *a, float *b)
{
    float ax = fabsf(d.x), ay = fabsf(d.y), az = fabsf(d.z);
    int f;
    if (ax >= ay && ax >= az)
        f = d.x > 0.0f ? 1 : 2;
    else if (ay >= az)
        f = d.y > 0.0f ? 3 : 4;
    else
        f = d.z < 0.0f ? 0 : 5;
    const cross_face *cf = &cross_faces[f];
    float dc = v3_dot(d, cf->c);
    if (!(dc > 0.0f)) {
        *a = *b = 0.0f;
        return f;
    }
    *a = il_clampf(v3_dot(d, cf->r) / dc, -1.0f, 1.0f);
    *b = il_clampf(v3_dot(d, cf->t) / dc, -1.0f, 1.0f);
    return f;
}

static int cross_face_at(int col, int row)
{
    for (int f = 0; f < 6; f++)
        if (cross_faces[f].col == col && cross_faces[f].row == row)
            return f;
    return -1;
}

/* ------------------------------------------------------------- mappings */

il_vec2 il_envmap_dir_to_uv(il_env_mapping m, il_vec3 d)
{
    switch (m) {
    case IL_ENV_ANGULAR: {
        /* Debevec: r = acos(Dz) / (pi sqrt(Dx^2 + Dy^2)); atan2 keeps the
         * angle accurate near +z where acos loses it. */
        float s = sqrtf(d.x * d.x + d.y * d.y);
        float a, b;
        if (s > 0.0f) {
            float r = atan2f(s, d.z) * IL_INV_PI / s;
            a = d.x * r;
            b = d.y * r;
        } else {
            a = 0.0f;
            b = d.z >= 0.0f ? 0.0f : 1.0f;   /* -z is the whole rim: take its top */
        }
        return v2(0.5f * (a + 1.0f), 0.5f * (1.0f - b));
    }
    case IL_ENV_CROSS: {
        float a, b;
        const cross_face *cf = &cross_faces[cross_face_of(d, &a, &b)];
        return v2(((float)cf->col + 0.5f * (a + 1.0f)) * (1.0f / 3.0f),
                  ((float)cf->row + 0.5f * (1.0f - b)) * 0.25f);
    }
    case IL_ENV_LATLONG:
    default: {
        float theta = atan2f(sqrtf(d.x * d.x + d.z * d.z), d.y);
        float phi = atan2f(d.x, -d.z);
        return v2(il_clampf(0.5f + phi * IL_INV_2PI, 0.0f, 1.0f),
                  il_clampf(theta * IL_INV_PI, 0.0f, 1.0f));
    }
    }
}

bool il_envmap_uv_to_dir(il_env_mapping m, il_vec2 uv, il_vec3 *dir)
{
    if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f))
        return false;
    switch (m) {
    case IL_ENV_ANGULAR: {
        float a = 2.0f * uv.x - 1.0f, b = 1.0f - 2.0f * uv.y;
        float r = sqrtf(a * a + b * b);
        if (r > 1.0f)
            return false;
        float theta = IL_PI * r, st = sinf(theta);
        float ca = r > 0.0f ? a / r : 1.0f, sa = r > 0.0f ? b / r : 0.0f;
        *dir = v3(st * ca, st * sa, cosf(theta));
        return true;
    }
    case IL_ENV_CROSS: {
        float x = 3.0f * uv.x, y = 4.0f * uv.y;
        int col = (int)il_minf(floorf(x), 2.0f), row = (int)il_minf(floorf(y), 3.0f);
        int f = cross_face_at(col, row);
        if (f < 0)
            return false;
        const cross_face *cf = &cross_faces[f];
        float a = 2.0f * (x - (float)col) - 1.0f, b = 1.0f - 2.0f * (y - (float)row);
        *dir = v3_normalize(v3_add(cf->c, v3_add(v3_scale(cf->r, a), v3_scale(cf->t, b))));
        return true;
    }
    case IL_ENV_LATLONG:
    default:
        *dir = il_envmap_latlong_dir(uv.x, uv.y);
        return true;
    }
}

float il_envmap_jacobian(il_env_mapping m, il_vec2 uv)
{
    if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f))
        return 0.0f;
    switch (m) {
    case IL_ENV_ANGULAR: {
        /* (a, b) = 2 (u, v) - 1 covers 4 units of area; in polar form
         * da db = r dr dpsi and dOmega = sin(pi r) pi dr dpsi. */
        float a = 2.0f * uv.x - 1.0f, b = 1.0f - 2.0f * uv.y;
        float r = sqrtf(a * a + b * b);
        if (r > 1.0f)
            return 0.0f;
        return r > 1e-6f ? 4.0f * IL_PI * sinf(IL_PI * r) / r : 4.0f * IL_PI * IL_PI;
    }
    case IL_ENV_CROSS: {
        /* dOmega = da db / (1 + a^2 + b^2)^(3/2) on a face; a face's cell
         * is a sixth of the width and a quarter of the height, so
         * da db = 48 du dv. */
        float x = 3.0f * uv.x, y = 4.0f * uv.y;
        int col = (int)il_minf(floorf(x), 2.0f), row = (int)il_minf(floorf(y), 3.0f);
        if (cross_face_at(col, row) < 0)
            return 0.0f;
        float a = 2.0f * (x - (float)col) - 1.0f, b = 1.0f - 2.0f * (y - (float)row);
        float q = 1.0f + a * a + b * b;
        return 48.0f / (q * sqrtf(q));
    }
    case IL_ENV_LATLONG:
    default:
        return 2.0f * IL_PI * IL_PI * sinf(IL_PI * uv.y);
    }
}

/* ------------------------------------------------------------- lookups */

static inline il_vec3 texel(const il_image *img, uint32_t x, uint32_t y)
{
    const float *p = img->rgb + 3 * ((size_t)y * img->width + x);
    return v3(p[0], p[1], p[2]);
}

static inline il_vec3 bilerp(const il_image *img, uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1,
                             float tx, float ty)
{
    il_vec3 top = v3_add(v3_scale(texel(img, x0, y0), 1.0f - tx), v3_scale(texel(img, x1, y0), tx));
    il_vec3 bot = v3_add(v3_scale(texel(img, x0, y1), 1.0f - tx), v3_scale(texel(img, x1, y1), tx));
    return v3_add(v3_scale(top, 1.0f - ty), v3_scale(bot, ty));
}

/* Whether texel (x, y) of a w x w angular map overlaps the unit disk: the
 * point of the texel's square nearest the centre is inside it. */
static inline bool angular_texel_in_disk(uint32_t x, uint32_t y, uint32_t w)
{
    float s = 2.0f / (float)w;   /* texel size in (a, b) */
    float a0 = -1.0f + s * (float)x, b0 = -1.0f + s * (float)y;
    float a = il_clampf(0.0f, a0, a0 + s), b = il_clampf(0.0f, b0, b0 + s);
    return a * a + b * b < 1.0f;
}

/* The angular map's bilinear lookup leaves out texels wholly outside the
 * disk (the black border of a light probe) and renormalises the weights of
 * the others, so that the rim (directions near -z) is not darkened. */
static il_vec3 angular_bilerp(const il_image *img, uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1,
                              float tx, float ty)
{
    const uint32_t xs[2] = {x0, x1}, ys[2] = {y0, y1};
    const float wx[2] = {1.0f - tx, tx}, wy[2] = {1.0f - ty, ty};
    il_vec3 acc = v3s(0.0f);
    float wsum = 0.0f;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            float wgt = wx[i] * wy[j];
            if (wgt > 0.0f && angular_texel_in_disk(xs[i], ys[j], img->width)) {
                acc = v3_fma(acc, texel(img, xs[i], ys[j]), wgt);
                wsum += wgt;
            }
        }
    if (wsum > 0.0f)
        return v3_scale(acc, 1.0f / wsum);
    /* Only on a map of a texel or two: the nearest texel. */
    return texel(img, tx < 0.5f ? x0 : x1, ty < 0.5f ? y0 : y1);
}

/* Bilinear weights along one axis of n texels starting at `base`, for the
 * continuous texel coordinate p (texel centres at k + 1/2), clamped. */
static inline void axis_clamp(float p, uint32_t n, uint32_t base, uint32_t *i0, uint32_t *i1, float *t)
{
    float x = p - 0.5f;
    float fx = floorf(x);
    *t = x - fx;
    long k = (long)fx;
    long k0 = k < 0 ? 0 : (k >= (long)n ? (long)n - 1 : k);
    long k1 = k + 1 < 0 ? 0 : (k + 1 >= (long)n ? (long)n - 1 : k + 1);
    *i0 = base + (uint32_t)k0;
    *i1 = base + (uint32_t)k1;
}

il_vec3 il_envmap_lookup(const il_image *img, il_env_mapping m, il_vec3 dir)
{
    if (!v3_is_finite(dir) || v3_is_zero(dir))
        return v3s(0.0f);
    uint32_t w = img->width, h = img->height;
    uint32_t x0, x1, y0, y1;
    float tx, ty;
    switch (m) {
    case IL_ENV_CROSS: {
        float a, b;
        const cross_face *cf = &cross_faces[cross_face_of(dir, &a, &b)];
        uint32_t f = w / 3;
        axis_clamp(0.5f * (a + 1.0f) * (float)f, f, (uint32_t)cf->col * f, &x0, &x1, &tx);
        axis_clamp(0.5f * (1.0f - b) * (float)f, f, (uint32_t)cf->row * f, &y0, &y1, &ty);
        break;
    }
    case IL_ENV_ANGULAR: {
        il_vec2 uv = il_envmap_dir_to_uv(m, dir);
        axis_clamp(uv.x * (float)w, w, 0, &x0, &x1, &tx);
        axis_clamp(uv.y * (float)h, h, 0, &y0, &y1, &ty);
        return angular_bilerp(img, x0, x1, y0, y1, tx, ty);
    }
    case IL_ENV_LATLONG:
    default:
        return il_envmap_lookup_latlong_uv(img, il_envmap_dir_to_uv(m, dir));
    }
    return bilerp(img, x0, x1, y0, y1, tx, ty);
}

il_vec3 il_envmap_lookup_latlong_uv(const il_image *img, il_vec2 uv)
{
    uint32_t w = img->width, h = img->height;
    uint32_t x0, x1, y0, y1;
    float tx, ty;
    /* Wraps around in u: the left and right edges meet at +z. */
    float x = uv.x * (float)w - 0.5f;
    float fx = floorf(x);
    tx = x - fx;
    long k = (long)fx % (long)w;
    if (k < 0)
        k += w;
    x0 = (uint32_t)k;
    x1 = x0 + 1 == w ? 0 : x0 + 1;
    axis_clamp(uv.y * (float)h, h, 0, &y0, &y1, &ty);
    return bilerp(img, x0, x1, y0, y1, tx, ty);
}

/* ------------------------------------------------------------- the map */

il_status il_envmap_init(il_envmap *env, const il_image *img, il_env_mapping m, float rotation_deg,
                         float intensity, uint64_t *clamped, il_error *err)
{
    memset(env, 0, sizeof *env);
    if (clamped)
        *clamped = 0;
    il_status st = il_envmap_check(img, m, "environment map", err);
    if (st != IL_OK)
        return st;
    if (intensity == 0.0f)
        intensity = 1.0f;
    if (!(intensity > 0.0f) || !isfinite(intensity))
        return il_fail(err, IL_ERR_INVALID, "environment: intensity must be finite and > 0, not %g",
                       (double)intensity);
    if (!isfinite(rotation_deg))
        return il_fail(err, IL_ERR_INVALID, "environment: rotation must be a finite angle");
    if ((st = il_image_alloc(&env->img, img->width, img->height, err)) != IL_OK)
        return st;
    size_t n = (size_t)img->width * img->height * 3;
    uint64_t neg = 0;
    for (size_t k = 0; k < n; k++) {
        float v = img->rgb[k];
        if (v < 0.0f) {
            v = 0.0f;
            neg++;
        }
        v *= intensity;
        if (!(v <= IL_ENVMAP_MAX_RADIANCE)) {
            il_envmap_free(env);
            return il_fail(err, IL_ERR_INVALID,
                           "environment: texel value %g times intensity %g overflows",
                           (double)img->rgb[k], (double)intensity);
        }
        env->img.rgb[k] = v;
    }
    if (clamped)
        *clamped = neg;
    env->mapping = m;
    /* Reduced to (-360, 360) first so that large angles keep their precision. */
    double rad = fmod((double)rotation_deg, 360.0) * (3.14159265358979323846 / 180.0);
    env->rotation = (float)rad;
    env->cos_rot = (float)cos(rad);
    env->sin_rot = (float)sin(rad);
    if ((st = il_envmap_dist_build(env, err)) != IL_OK) {
        il_envmap_free(env);
        return st;
    }
    return IL_OK;
}

void il_envmap_free(il_envmap *env)
{
    if (!env)
        return;
    il_image_free(&env->img);
    il_envmap_dist_free(&env->dist);
    memset(env, 0, sizeof *env);
}
