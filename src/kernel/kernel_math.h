/* The device-safe subset of core/vec.h that the shared kernels need: a
 * three-float vector with the layout of il_vec3 (so scene arrays can be
 * copied as they are), and its operations, all IL_DEVICE_INLINE.  The names
 * are ilk_ so that a file may include both this and core/vec.h. */
#ifndef IL_KERNEL_MATH_H
#define IL_KERNEL_MATH_H

#include "kernel/kernel_compat.h"

typedef struct ilk_vec3 { float x, y, z; } ilk_vec3;

IL_DEVICE_INLINE ilk_vec3 ilk_v3(float x, float y, float z)
{
    ilk_vec3 r;
    r.x = x; r.y = y; r.z = z;
    return r;
}
IL_DEVICE_INLINE ilk_vec3 ilk_add(ilk_vec3 a, ilk_vec3 b) { return ilk_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
IL_DEVICE_INLINE ilk_vec3 ilk_sub(ilk_vec3 a, ilk_vec3 b) { return ilk_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
IL_DEVICE_INLINE ilk_vec3 ilk_mul(ilk_vec3 a, ilk_vec3 b) { return ilk_v3(a.x * b.x, a.y * b.y, a.z * b.z); }
IL_DEVICE_INLINE ilk_vec3 ilk_scale(ilk_vec3 a, float s) { return ilk_v3(a.x * s, a.y * s, a.z * s); }
IL_DEVICE_INLINE float ilk_dot(ilk_vec3 a, ilk_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
IL_DEVICE_INLINE ilk_vec3 ilk_cross(ilk_vec3 a, ilk_vec3 b)
{
    return ilk_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* Plain comparisons, as il_minf/il_maxf in core/vec.h: with a NaN argument
 * the result is b, which the slab test below relies on. */
IL_DEVICE_INLINE float ilk_minf(float a, float b) { return a < b ? a : b; }
IL_DEVICE_INLINE float ilk_maxf(float a, float b) { return a > b ? a : b; }
IL_DEVICE_INLINE float ilk_max3(ilk_vec3 c) { return ilk_maxf(c.x, ilk_maxf(c.y, c.z)); }
/* Rec. 709 luminance, as core/vec.h's il_luminance. */
IL_DEVICE_INLINE float ilk_luminance(ilk_vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
IL_DEVICE_INLINE ilk_vec3 ilk_vmin(ilk_vec3 a, ilk_vec3 b) { return ilk_v3(ilk_minf(a.x, b.x), ilk_minf(a.y, b.y), ilk_minf(a.z, b.z)); }
IL_DEVICE_INLINE ilk_vec3 ilk_vmax(ilk_vec3 a, ilk_vec3 b) { return ilk_v3(ilk_maxf(a.x, b.x), ilk_maxf(a.y, b.y), ilk_maxf(a.z, b.z)); }
IL_DEVICE_INLINE float ilk_comp(ilk_vec3 a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }
IL_DEVICE_INLINE ilk_vec3 ilk_normalize(ilk_vec3 a)
{
    float l = sqrtf(ilk_dot(a, a));
    return l > 0.0f ? ilk_scale(a, 1.0f / l) : a;
}

#endif
