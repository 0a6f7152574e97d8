/* The sRGB transfer functions of IEC 61966-2-1:1999 (section 5.2 and 5.3),
 * in double precision.  Used by the PNG/JPEG codec and by tone mapping. */
#ifndef IL_IMAGE_SRGB_H
#define IL_IMAGE_SRGB_H

#include <math.h>

/* Electro-optical transfer: encoded value c in [0,1] -> linear value. */
static inline double il_srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* Inverse: linear value v in [0,1] -> encoded value. */
static inline double il_linear_to_srgb(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* Linear value -> 8-bit sRGB code: clamped to [0,1] (NaN counts as 0),
 * encoded, rounded to the nearest code.  Callers map a non-finite *pixel*
 * to 0 before scaling it by the exposure. */
static inline unsigned char il_linear_to_srgb8(double v)
{
    if (!(v > 0.0)) /* also NaN */
        return 0;
    if (v >= 1.0)
        return 255;
    return (unsigned char)lrint(il_linear_to_srgb(v) * 255.0);
}

#endif
