/* Small vector maths on il_vec3 / il_vec2, all inline.  il_vec3 doubles as
 * an RGB colour (x=r, y=g, z=b). */
#ifndef IL_CORE_VEC_H
#define IL_CORE_VEC_H

#include <math.h>
#include <stdbool.h>
#include "illum/illum.h"

#define IL_PI 3.14159265358979323846f
#define IL_INV_PI 0.31830988618379067154f
#define IL_INV_2PI 0.15915494309189533577f
#define IL_INV_4PI 0.07957747154594766788f

static inline il_vec3 v3(float x, float y, float z) { return (il_vec3){x, y, z}; }
static inline il_vec3 v3s(float s) { return (il_vec3){s, s, s}; }
static inline il_vec2 v2(float x, float y) { return (il_vec2){x, y}; }
static inline il_vec3 v3_add(il_vec3 a, il_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline il_vec3 v3_sub(il_vec3 a, il_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline il_vec3 v3_mul(il_vec3 a, il_vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline il_vec3 v3_scale(il_vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline il_vec3 v3_neg(il_vec3 a) { return v3(-a.x, -a.y, -a.z); }
/* a + b*s */
static inline il_vec3 v3_fma(il_vec3 a, il_vec3 b, float s) { return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
static inline float v3_dot(il_vec3 a, il_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline il_vec3 v3_cross(il_vec3 a, il_vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float v3_length2(il_vec3 a) { return v3_dot(a, a); }
static inline float v3_length(il_vec3 a) { return sqrtf(v3_dot(a, a)); }
static inline il_vec3 v3_normalize(il_vec3 a)
{
    float l = v3_length(a);
    return l > 0.0f ? v3_scale(a, 1.0f / l) : a;
}
/* Plain comparisons rather than fminf/fmaxf: without -ffinite-math-only gcc
 * turns those into library calls on the hot path.  Unlike fminf/fmaxf they
 * do not skip NaN arguments (the result is then b). */
static inline float il_minf(float a, float b) { return a < b ? a : b; }
static inline float il_maxf(float a, float b) { return a > b ? a : b; }
static inline il_vec3 v3_min(il_vec3 a, il_vec3 b) { return v3(il_minf(a.x, b.x), il_minf(a.y, b.y), il_minf(a.z, b.z)); }
static inline il_vec3 v3_max(il_vec3 a, il_vec3 b) { return v3(il_maxf(a.x, b.x), il_maxf(a.y, b.y), il_maxf(a.z, b.z)); }
static inline float v3_max_comp(il_vec3 a) { return il_maxf(a.x, il_maxf(a.y, a.z)); }
static inline float v3_avg(il_vec3 a) { return (a.x + a.y + a.z) * (1.0f / 3.0f); }
static inline bool v3_is_zero(il_vec3 a) { return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f; }
static inline bool v3_is_finite(il_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }
static inline float v3_get(il_vec3 a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }
/* Rec.709 / sRGB luminance of a linear RGB colour. */
static inline float il_luminance(il_vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

static inline float il_clampf(float x, float lo, float hi) { return x < lo ? lo : (x > hi ? hi : x); }
static inline float il_lerpf(float a, float b, float t) { return a + (b - a) * t; }

/* An orthonormal basis around a unit normal n (Duff et al. 2017, "Building an
 * Orthonormal Basis, Revisited", JCGT 6(1)). */
typedef struct il_frame { il_vec3 s, t, n; } il_frame;

static inline il_frame il_frame_from_normal(il_vec3 n)
{
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    il_frame f;
    f.s = v3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.t = v3(b, sign + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}
static inline il_vec3 il_frame_to_local(const il_frame *f, il_vec3 v)
{
    return v3(v3_dot(v, f->s), v3_dot(v, f->t), v3_dot(v, f->n));
}
static inline il_vec3 il_frame_to_world(const il_frame *f, il_vec3 v)
{
    return v3_add(v3_add(v3_scale(f->s, v.x), v3_scale(f->t, v.y)), v3_scale(f->n, v.z));
}

#endif
