/* Pixel jitter by filter importance sampling (pbrt-v4 8.8): samples are
 * placed with density proportional to the filter, so each carries weight 1. */
#include <math.h>

#include "methods/camera_pass.h"

/* Inverse error function: the single-precision approximation of Giles 2012
 * ("Approximating the erfinv function", GPU Computing Gems Jade, ch. 10),
 * then two Newton steps on erf(x) - y = 0 to bring it to float accuracy
 * (d/dx erf(x) = 2/sqrt(pi) exp(-x^2)). */
float il_erfinv(float y)
{
    if (!(y > -1.0f && y < 1.0f))
        return y >= 1.0f ? INFINITY : -INFINITY;
    float w = -logf((1.0f - y) * (1.0f + y)), p;
    if (w < 5.0f) {
        w -= 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = sqrtf(w) - 3.0f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    double x = (double)p * y;
    for (int i = 0; i < 2; i++)
        x -= (erf(x) - y) / (1.1283791670955126 * exp(-x * x));
    return (float)x;
}

#define IL_GAUSS_SIGMA 0.5f
#define IL_GAUSS_RADIUS 1.5f

/* Inverse CDF of the Gaussian truncated to [-r, r]:
 * x = sigma sqrt(2) erfinv(lerp(u, -erf(a), erf(a))), a = r / (sigma sqrt(2)). */
static float truncated_gaussian(float u)
{
    const float s2 = IL_GAUSS_SIGMA * 1.41421356f;
    float e = erff(IL_GAUSS_RADIUS / s2);
    float x = s2 * il_erfinv((2.0f * u - 1.0f) * e);
    return il_clampf(x, -IL_GAUSS_RADIUS, IL_GAUSS_RADIUS);
}

il_vec2 il_filter_offset(il_filter_type filter, il_vec2 u)
{
    if (filter == IL_FILTER_GAUSSIAN)
        return v2(0.5f + truncated_gaussian(u.x), 0.5f + truncated_gaussian(u.y));
    return u;
}
