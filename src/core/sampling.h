/* Warps from uniform [0,1)^2 to directions and points, their densities, and
 * tabulated 1D distributions.  References: pbrt-v4 (Pharr, Jakob, Humphreys),
 * chapter A.5 "Sampling Algorithms". */
#ifndef IL_CORE_SAMPLING_H
#define IL_CORE_SAMPLING_H

#include <stdint.h>
#include "core/vec.h"

/* Shirley-Chiu concentric map to the unit disk (pbrt-v4 A.5.1). */
il_vec2 il_sample_concentric_disk(il_vec2 u);

/* Directions in the local frame (z up). */
il_vec3 il_sample_cosine_hemisphere(il_vec2 u);   /* pdf cos(theta)/pi */
float il_cosine_hemisphere_pdf(float cos_theta);
/* il_sample_cosine_hemisphere of u[0..n-1] into out, bit for bit, eight at
 * a time in AVX2 lanes where the CPU has it. */
void il_sample_cosine_hemisphere_n(const il_vec2 *u, il_vec3 *out, uint32_t n);
il_vec3 il_sample_uniform_hemisphere(il_vec2 u);  /* pdf 1/(2 pi) */
il_vec3 il_sample_uniform_sphere(il_vec2 u);      /* pdf 1/(4 pi) */
il_vec3 il_sample_uniform_cone(il_vec2 u, float cos_max); /* pdf 1/(2 pi (1-cos_max)) */
float il_uniform_cone_pdf(float cos_max);
/* The normalised Phong lobe around +z: pdf (n+1)/(2 pi) cos^n(alpha). */
il_vec3 il_sample_phong_lobe(il_vec2 u, float exponent);
float il_phong_lobe_pdf(float cos_alpha, float exponent);

/* Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2;
 * area density 1/A (Heitz 2019 or Turk 1990 square-root map). */
il_vec2 il_sample_triangle(il_vec2 u);

/* Veach's power heuristic with beta = 2 (Veach 1997, section 9.2.4). */
static inline float il_power_heuristic(float pdf_f, float pdf_g)
{
    float f = pdf_f * pdf_f, g = pdf_g * pdf_g;
    return f + g > 0.0f ? f / (f + g) : 0.0f;
}

/* The last bin i in [0, n-1] with cdf[i] <= u, for a non-decreasing cdf
 * with cdf[0] <= u (n >= 1): a binary search without branches on the data
 * (Khuong & Morin 2017, "Array Layouts for Comparison-Based Searching",
 * branch-free search), so random u costs no mispredicted branches.  Bins of
 * zero width are never chosen: if cdf[i] == cdf[i+1] <= u, i+1 qualifies. */
static inline uint32_t il_cdf_find(const float *cdf, uint32_t n, float u)
{
    uint32_t lo = 0, len = n;
    while (len > 1) {
        uint32_t half = len / 2;
        lo = cdf[lo + half] <= u ? lo + half : lo;   /* a conditional move */
        len -= half;
    }
    return lo;
}

/* A piecewise-constant distribution over n bins of [0,1). */
typedef struct il_distrib1d {
    uint32_t n;
    float *func;      /* n non-negative weights */
    float *cdf;       /* n+1 entries, cdf[0]=0, cdf[n]=1 */
    uint32_t *guide;  /* n+1 entries: guide[k] is the bin of u = k/n (the last just
                         below 1 for k = n), so a u in [k/n, (k+1)/n) falls in one of
                         the bins guide[k] .. guide[k+1] (a guide table: Chen &
                         Asau 1974; Devroye 1986, III.2.4) */
    float integral;   /* sum(func)/n */
} il_distrib1d;

/* Builds from n weights (copied).  All-zero weights give a uniform distribution. */
il_status il_distrib1d_init(il_distrib1d *d, const float *weights, uint32_t n, il_error *err);
void il_distrib1d_free(il_distrib1d *d);
/* Picks the bin il_cdf_find gives (the last with cdf[i] <= u), found by a
 * binary search between the guide table's bounds, which mostly leaves one
 * or two bins to look at; returns it, its probability in *pmf (may be NULL)
 * and u rescaled to [0,1) within the bin in *u_remapped (may be NULL). */
uint32_t il_distrib1d_sample_discrete(const il_distrib1d *d, float u, float *pmf, float *u_remapped);
float il_distrib1d_pmf(const il_distrib1d *d, uint32_t i);

#endif
