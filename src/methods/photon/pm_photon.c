/* The 20-byte stored photon (pm.h): float position, RGBE power, octahedral
 * direction and normal. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/photon/pm_internal.h"

/* ------------------------------------------------------------------ RGBE */

/* Ward's shared-exponent RGB ("Real Pixels", Graphics Gems II, 1991): three
 * 8-bit mantissas and an 8-bit exponent e+128, c = m * 2^(e-8).  Ward
 * truncates; here the mantissas are rounded to nearest, so decoding needs
 * no half-step offset and the error is unbiased: at most half a step, 2^-8
 * relative to the largest channel (its mantissa is 128..255). */
#define RGBE_EXP_MIN (-127)   /* stored exponent byte 1; byte 0 means black */
#define RGBE_EXP_MAX 127

static float rgbe_clean(float x) { return x > 0.0f ? x : 0.0f; } /* negative and NaN: 0 */

uint32_t il_rgbe_pack(il_vec3 c)
{
    double ch[3] = {rgbe_clean(c.x), rgbe_clean(c.y), rgbe_clean(c.z)};
    double v = fmax(ch[0], fmax(ch[1], ch[2]));
    if (!(v > 0.0))
        return 0;
    /* The largest value: mantissa 255 at the largest exponent.  Larger ones
     * (and infinity) are scaled down together, keeping the hue. */
    const double vmax = 255.0 * ldexp(1.0, RGBE_EXP_MAX - 8);
    if (v > vmax) {
        double s = isinf(v) ? 0.0 : vmax / v;
        for (int i = 0; i < 3; i++)
            ch[i] = isinf(ch[i]) ? vmax : ch[i] * s;
        v = vmax;
    }
    int e;
    frexp(v, &e);                       /* v = f * 2^e, f in [0.5, 1) */
    if (e < RGBE_EXP_MIN)
        e = RGBE_EXP_MIN;               /* tiny: smaller mantissas, then 0 */
    long m[3];
    for (;;) {
        double s = ldexp(1.0, 8 - e);
        for (int i = 0; i < 3; i++)
            m[i] = lround(ch[i] * s);
        if (m[0] < 256 && m[1] < 256 && m[2] < 256)
            break;
        e++;                            /* 255.5 rounded up to 256: 128 at e+1 */
    }
    if (m[0] == 0 && m[1] == 0 && m[2] == 0)
        return 0;
    return (uint32_t)m[0] | (uint32_t)m[1] << 8 | (uint32_t)m[2] << 16 | (uint32_t)(e + 128) << 24;
}

il_vec3 il_rgbe_unpack(uint32_t rgbe)
{
    uint32_t eb = rgbe >> 24;
    if (eb == 0)
        return v3s(0.0f);
    int e = (int)eb - 128 - 8;          /* c = m * 2^e */
    float s;
    if (e >= -126) {
        /* 2^e built from its bits: this runs for every photon of every estimate. */
        uint32_t bits = (uint32_t)(e + 127) << 23;
        memcpy(&s, &bits, sizeof s);
    } else {
        s = ldexpf(1.0f, e);
    }
    return v3((float)(rgbe & 255u) * s, (float)((rgbe >> 8) & 255u) * s,
              (float)((rgbe >> 16) & 255u) * s);
}

/* ------------------------------------------------------------ octahedral */

/* Octahedral unit vectors (Cigolle et al. 2014, "A Survey of Efficient
 * Representations for Independent Unit Vectors", JCGT 3(2), sections 3.1
 * and 3.3): project onto the octahedron |x|+|y|+|z| = 1, fold the lower
 * half over the diagonals onto the square, store each coordinate as a snorm
 * with 2^(bits-1)-1 steps per side (so 0 and +-1, hence the axes, are
 * exact).  Encoding rounds each coordinate to nearest. */

static float sign_not_zero(float x) { return x >= 0.0f ? 1.0f : -1.0f; }

static il_vec3 oct_decode(float x, float y)
{
    float z = 1.0f - fabsf(x) - fabsf(y);
    if (z < 0.0f) {
        float ox = x;
        x = (1.0f - fabsf(y)) * sign_not_zero(ox);
        y = (1.0f - fabsf(ox)) * sign_not_zero(y);
    }
    return v3_normalize(v3(x, y, z));
}

static unsigned oct_bits(unsigned bits) { return bits < 2 ? 2 : (bits > 8 ? 8 : bits); }

uint16_t il_oct_pack(il_vec3 n, unsigned bits)
{
    bits = oct_bits(bits);
    const int M = (1 << (bits - 1)) - 1;
    float l1 = fabsf(n.x) + fabsf(n.y) + fabsf(n.z);
    if (!(l1 > 0.0f) || !isfinite(l1))
        n = v3(0.0f, 0.0f, 1.0f), l1 = 1.0f;
    n = v3_scale(n, 1.0f / l1);
    float px = n.x, py = n.y;
    if (n.z < 0.0f) {
        px = (1.0f - fabsf(n.y)) * sign_not_zero(n.x);
        py = (1.0f - fabsf(n.x)) * sign_not_zero(n.y);
    }
    float fx = il_clampf(px, -1.0f, 1.0f) * (float)M, fy = il_clampf(py, -1.0f, 1.0f) * (float)M;
    /* Plain rounding: Cigolle et al.'s "precise" search of the four
     * neighbours would shave the worst error from about 0.9 to 0.63 degrees
     * (8 bits) at five decodes per photon, a fifth of the tracing time;
     * the estimates need neither (the normal test allows 26 degrees). */
    int bx = (int)lrintf(fx), by = (int)lrintf(fy);
    return (uint16_t)((unsigned)(bx + M) | (unsigned)(by + M) << bits);
}

il_vec3 il_oct_unpack(uint16_t e, unsigned bits)
{
    bits = oct_bits(bits);
    const int M = (1 << (bits - 1)) - 1;
    const unsigned mask = (1u << bits) - 1u;
    float inv = 1.0f / (float)M;
    int ux = (int)(e & mask), uy = (int)((e >> bits) & mask);
    return oct_decode((float)(ux - M) * inv, (float)(uy - M) * inv);
}

/* ---------------------------------------------------------------- photon */

il_photon il_photon_pack(il_vec3 p, il_vec3 power, il_vec3 dir, il_vec3 normal)
{
    il_photon ph;
    ph.p[0] = p.x;
    ph.p[1] = p.y;
    ph.p[2] = p.z;
    ph.power = il_rgbe_pack(power);
    ph.dir = il_oct_pack(dir, 8);
    ph.normal = (uint16_t)(il_oct_pack(normal, 7) & IL_PM_NORMAL_MASK);
    return ph;
}

il_vec3 il_photon_pos(const il_photon *ph) { return v3(ph->p[0], ph->p[1], ph->p[2]); }
il_vec3 il_photon_power(const il_photon *ph) { return il_rgbe_unpack(ph->power); }
il_vec3 il_photon_dir(const il_photon *ph) { return il_oct_unpack(ph->dir, 8); }
il_vec3 il_photon_normal(const il_photon *ph)
{
    return il_oct_unpack((uint16_t)(ph->normal & IL_PM_NORMAL_MASK), 7);
}

/* --------------------------------------------------------------- display */

void il_pm_report_photons(const il_photon_desc *d, const il_photon *photons, size_t n, int which)
{
    if (!d || !d->on_photons)
        return;
    float *xyz = malloc((n ? n : 1u) * 3 * sizeof *xyz);
    if (!xyz)
        return;
    for (size_t i = 0; i < n; i++)
        memcpy(xyz + 3 * i, photons[i].p, 3 * sizeof *xyz);
    d->on_photons(xyz, n, which, d->on_photons_user);
    free(xyz);
}
