/* Sampling warps and 1D distributions; see sampling.h.  Formulas follow
 * pbrt-v4 (Pharr, Jakob, Humphreys 2023), appendix A.5 "Sampling Algorithms",
 * unless another source is named next to the code. */
#include "core/sampling.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define IL_SAMPLING_AVX2 1
#endif

/* The largest float below 1: keeps remapped samples inside [0, 1). */
#define IL_ONE_MINUS_EPSILON 0x1.fffffep-1f

/* cos and sin of (pi/4) t for t in [-1, 1], without a libm call: Taylor
 * polynomials of cos and sin at 0 to degree 8 and 9 (Abramowitz & Stegun
 * 4.3.65-66), evaluated in Horner form.  On |x| <= pi/4 the first omitted
 * terms, x^10/10! and x^11/11!, are below 2.5e-8 and 1.8e-9: under half
 * an ulp of 1, so the results are as accurate as cosf and sinf. */
static inline il_vec2 cos_sin_quarter_pi(float t)
{
    float x = 0.25f * IL_PI * t, x2 = x * x;
    float c = 1.0f + x2 * (-1.0f / 2.0f + x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f))));
    float s = x * (1.0f + x2 * (-1.0f / 6.0f + x2 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f + x2 * (1.0f / 362880.0f)))));
    return v2(c, s);
}

/* Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square";
 * pbrt-v4 A.5.1 SampleUniformDiskConcentric.  theta is (pi/4) t with
 * |t| <= 1 in the first case and pi/2 - (pi/4) t in the second, where
 * (cos, sin) of pi/2 - a is (sin a, cos a). */
il_vec2 il_sample_concentric_disk(il_vec2 u)
{
    float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
    if (ox == 0.0f && oy == 0.0f)
        return v2(0.0f, 0.0f);
    if (fabsf(ox) > fabsf(oy)) {
        il_vec2 cs = cos_sin_quarter_pi(oy / ox);
        return v2(ox * cs.x, ox * cs.y);
    }
    il_vec2 cs = cos_sin_quarter_pi(ox / oy);
    return v2(oy * cs.y, oy * cs.x);
}

/* Malley's method: project disk samples up to the hemisphere (pbrt-v4 A.5.3). */
il_vec3 il_sample_cosine_hemisphere(il_vec2 u)
{
    il_vec2 d = il_sample_concentric_disk(u);
    float z = sqrtf(il_maxf(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return v3(d.x, d.y, z);
}

/* ---- il_sample_cosine_hemisphere on eight samples at a time ----
 *
 * The same operations in the same order as the scalar code above (the
 * concentric map's two cases both computed and blended), each one correctly
 * rounded in AVX lanes as in scalar SSE, so the results are the same bit
 * for bit.  Compiled for AVX2 by a target attribute (no -march; no FMA, which
 * would round differently) and used only when the CPU has AVX2. */
#ifdef IL_SAMPLING_AVX2
#define IL_AVX2 __attribute__((target("avx2")))

IL_AVX2 static void cosine_hemisphere8(const float *ux, const float *uy, float *x, float *y, float *z)
{
    const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f), zero = _mm256_setzero_ps();
    const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    __m256 ox = _mm256_sub_ps(_mm256_mul_ps(two, _mm256_loadu_ps(ux)), one);
    __m256 oy = _mm256_sub_ps(_mm256_mul_ps(two, _mm256_loadu_ps(uy)), one);
    /* |ox| > |oy|: t = oy / ox, else t = ox / oy; r the divisor. */
    __m256 first = _mm256_cmp_ps(_mm256_and_ps(ox, abs_mask), _mm256_and_ps(oy, abs_mask), _CMP_GT_OQ);
    __m256 r = _mm256_blendv_ps(oy, ox, first);
    __m256 t = _mm256_div_ps(_mm256_blendv_ps(ox, oy, first), r);
    /* cos_sin_quarter_pi(t) */
    __m256 a = _mm256_mul_ps(_mm256_set1_ps(0.25f * IL_PI), t), a2 = _mm256_mul_ps(a, a);
    __m256 c = _mm256_add_ps(_mm256_set1_ps(-1.0f / 720.0f), _mm256_mul_ps(a2, _mm256_set1_ps(1.0f / 40320.0f)));
    c = _mm256_add_ps(_mm256_set1_ps(1.0f / 24.0f), _mm256_mul_ps(a2, c));
    c = _mm256_add_ps(_mm256_set1_ps(-1.0f / 2.0f), _mm256_mul_ps(a2, c));
    c = _mm256_add_ps(one, _mm256_mul_ps(a2, c));
    __m256 sn = _mm256_add_ps(_mm256_set1_ps(-1.0f / 5040.0f), _mm256_mul_ps(a2, _mm256_set1_ps(1.0f / 362880.0f)));
    sn = _mm256_add_ps(_mm256_set1_ps(1.0f / 120.0f), _mm256_mul_ps(a2, sn));
    sn = _mm256_add_ps(_mm256_set1_ps(-1.0f / 6.0f), _mm256_mul_ps(a2, sn));
    sn = _mm256_mul_ps(a, _mm256_add_ps(one, _mm256_mul_ps(a2, sn)));
    /* First case (ox c, ox s), second (oy s, oy c); (0, 0) at the centre. */
    __m256 dx = _mm256_mul_ps(r, _mm256_blendv_ps(sn, c, first));
    __m256 dy = _mm256_mul_ps(r, _mm256_blendv_ps(c, sn, first));
    __m256 centre = _mm256_and_ps(_mm256_cmp_ps(ox, zero, _CMP_EQ_OQ), _mm256_cmp_ps(oy, zero, _CMP_EQ_OQ));
    dx = _mm256_blendv_ps(dx, zero, centre);
    dy = _mm256_blendv_ps(dy, zero, centre);
    __m256 h = _mm256_sub_ps(_mm256_sub_ps(one, _mm256_mul_ps(dx, dx)), _mm256_mul_ps(dy, dy));
    _mm256_storeu_ps(x, dx);
    _mm256_storeu_ps(y, dy);
    _mm256_storeu_ps(z, _mm256_sqrt_ps(_mm256_max_ps(zero, h)));
}

IL_AVX2 static void cosine_hemisphere_avx2(const il_vec2 *u, il_vec3 *out, uint32_t n)
{
    float ux[8], uy[8], x[8], y[8], z[8];
    for (uint32_t k = 0; k < n; k += 8) {
        uint32_t m = n - k < 8 ? n - k : 8;
        for (uint32_t l = 0; l < 8; l++) {
            /* Lanes past the end repeat the last sample, their results unused. */
            il_vec2 v = u[k + (l < m ? l : m - 1)];
            ux[l] = v.x;
            uy[l] = v.y;
        }
        cosine_hemisphere8(ux, uy, x, y, z);
        for (uint32_t l = 0; l < m; l++)
            out[k + l] = v3(x[l], y[l], z[l]);
    }
}
#endif

void il_sample_cosine_hemisphere_n(const il_vec2 *u, il_vec3 *out, uint32_t n)
{
#ifdef IL_SAMPLING_AVX2
    if (__builtin_cpu_supports("avx2")) {
        cosine_hemisphere_avx2(u, out, n);
        return;
    }
#endif
    for (uint32_t k = 0; k < n; k++)
        out[k] = il_sample_cosine_hemisphere(u[k]);
}

float il_cosine_hemisphere_pdf(float cos_theta)
{
    return cos_theta > 0.0f ? cos_theta * IL_INV_PI : 0.0f;
}

/* pbrt-v4 A.5.2 SampleUniformHemisphere: z uniform in [0,1], phi uniform. */
il_vec3 il_sample_uniform_hemisphere(il_vec2 u)
{
    float z = u.x;
    float r = sqrtf(il_maxf(0.0f, 1.0f - z * z));
    float phi = 2.0f * IL_PI * u.y;
    return v3(r * cosf(phi), r * sinf(phi), z);
}

/* pbrt-v4 A.5.2 SampleUniformSphere: z uniform in [-1,1]. */
il_vec3 il_sample_uniform_sphere(il_vec2 u)
{
    float z = 1.0f - 2.0f * u.x;
    float r = sqrtf(il_maxf(0.0f, 1.0f - z * z));
    float phi = 2.0f * IL_PI * u.y;
    return v3(r * cosf(phi), r * sinf(phi), z);
}

/* pbrt-v4 A.5.4 SampleUniformCone: cos(theta) uniform in [cos_max, 1]. */
il_vec3 il_sample_uniform_cone(il_vec2 u, float cos_max)
{
    /* 1 - cos drawn directly and sin^2 = (1 - cos)(1 + cos): 1 - c^2 would
     * cancel for a narrow cone (the sun's 1 - cos is 1e-5). */
    float omc = u.x * (1.0f - cos_max);
    float c = 1.0f - omc;
    float s = sqrtf(il_maxf(0.0f, omc * (2.0f - omc)));
    float phi = 2.0f * IL_PI * u.y;
    return v3(s * cosf(phi), s * sinf(phi), c);
}

float il_uniform_cone_pdf(float cos_max)
{
    float solid_angle = 2.0f * IL_PI * (1.0f - cos_max);
    return solid_angle > 0.0f ? 1.0f / solid_angle : 0.0f;
}

/* Inverting the CDF of p(alpha) = (n+1)/(2 pi) cos^n(alpha) over the
 * hemisphere gives cos(alpha) = u^(1/(n+1)) (Lafortune & Willems 1994,
 * "Using the modified Phong reflectance model for physically based
 * rendering", section 4). */
il_vec3 il_sample_phong_lobe(il_vec2 u, float exponent)
{
    float c = powf(u.x, 1.0f / (exponent + 1.0f));
    float s = sqrtf(il_maxf(0.0f, 1.0f - c * c));
    float phi = 2.0f * IL_PI * u.y;
    return v3(s * cosf(phi), s * sinf(phi), c);
}

float il_phong_lobe_pdf(float cos_alpha, float exponent)
{
    if (cos_alpha <= 0.0f)
        return 0.0f;
    return (exponent + 1.0f) * IL_INV_2PI * powf(cos_alpha, exponent);
}

/* a where mask is all ones, b where it is zero, by the bits (no branch). */
static inline float select_bits(uint32_t mask, float a, float b)
{
    uint32_t ia, ib;
    memcpy(&ia, &a, sizeof ia);
    memcpy(&ib, &b, sizeof ib);
    ia = (ia & mask) | (ib & ~mask);
    memcpy(&a, &ia, sizeof a);
    return a;
}

/* Heitz 2019, "A Low-Distortion Map Between Triangle and Square" (as in
 * pbrt-v4 A.5.5 SampleUniformTriangle): fold the square onto the triangle
 * along the diagonal, keeping neighbourhoods intact. */
il_vec2 il_sample_triangle(il_vec2 u)
{
    /* Both halves computed and one selected: u.x < u.y is a coin toss for
     * random u, which a branch would mispredict half the time. */
    float hx = 0.5f * u.x, hy = 0.5f * u.y;
    uint32_t upper = 0u - (uint32_t)(u.x < u.y);
    return v2(select_bits(upper, hx, u.x - hy), select_bits(upper, u.y - hx, hy));
}

/* ------------------------------------------------------------ distrib1d */

il_status il_distrib1d_init(il_distrib1d *d, const float *weights, uint32_t n, il_error *err)
{
    memset(d, 0, sizeof *d);
    if (n == 0)
        return il_fail(err, IL_ERR_INVALID, "distribution: no bins (n == 0)");
    if (!weights)
        return il_fail(err, IL_ERR_INVALID, "distribution: no weights given");
    for (uint32_t i = 0; i < n; i++) {
        if (!(weights[i] >= 0.0f) || !isfinite(weights[i]))
            return il_fail(err, IL_ERR_INVALID,
                           "distribution: weight %u is %g (must be finite and >= 0)", i,
                           (double)weights[i]);
    }
    d->func = il_malloc(sizeof(float) * n, err);
    d->cdf = il_malloc(sizeof(float) * ((size_t)n + 1), err);
    if (!d->func || !d->cdf) {
        il_distrib1d_free(d);
        return err ? err->status : IL_ERR_MEMORY;
    }
    memcpy(d->func, weights, sizeof(float) * n);
    d->n = n;

    /* Running sums in double so long tables keep their precision. */
    double sum = 0.0;
    for (uint32_t i = 0; i < n; i++)
        sum += weights[i];
    d->cdf[0] = 0.0f;
    if (sum > 0.0) {
        double acc = 0.0;
        for (uint32_t i = 0; i < n; i++) {
            acc += weights[i];
            d->cdf[i + 1] = (float)(acc / sum);
        }
    } else {
        /* All weights zero: fall back to a uniform distribution. */
        for (uint32_t i = 0; i < n; i++)
            d->cdf[i + 1] = (float)((double)(i + 1) / n);
    }
    d->cdf[n] = 1.0f;
    d->integral = (float)(sum / n);
    d->guide = il_malloc(sizeof(uint32_t) * ((size_t)n + 1), err);
    if (!d->guide) {
        il_distrib1d_free(d);
        return err ? err->status : IL_ERR_MEMORY;
    }
    for (uint32_t k = 0; k <= n; k++) {
        float u = (float)((double)k / n);
        d->guide[k] = il_cdf_find(d->cdf, n, u < IL_ONE_MINUS_EPSILON ? u : IL_ONE_MINUS_EPSILON);
    }
    return IL_OK;
}

void il_distrib1d_free(il_distrib1d *d)
{
    if (!d)
        return;
    free(d->func);
    free(d->cdf);
    free(d->guide);
    memset(d, 0, sizeof *d);
}

float il_distrib1d_pmf(const il_distrib1d *d, uint32_t i)
{
    if (i >= d->n)
        return 0.0f;
    if (d->integral > 0.0f)
        return d->func[i] / (d->integral * (float)d->n);
    return 1.0f / (float)d->n;
}

/* Finds the last bin i with cdf[i] <= u.  Because u < 1 = cdf[n], the chosen
 * bin always satisfies cdf[i] <= u < cdf[i+1]: bins of zero width (zero weight)
 * can never be chosen.  u outside [0, 1) is clamped into it. */
uint32_t il_distrib1d_sample_discrete(const il_distrib1d *d, float u, float *pmf, float *u_remapped)
{
    if (!(u >= 0.0f))
        u = 0.0f;
    if (u > IL_ONE_MINUS_EPSILON)
        u = IL_ONE_MINUS_EPSILON;
    /* The bins of u's guide cell, widened in the rare case that rounding
     * in k/n put u outside them, so that cdf[lo] <= u < cdf[hi + 1]: then
     * the last bin with cdf[i] <= u lies in lo..hi, the one il_cdf_find
     * over all bins gives. */
    uint32_t k = (uint32_t)(u * (float)d->n);
    k = k < d->n ? k : d->n - 1;
    uint32_t lo = d->guide[k], hi = d->guide[k + 1];
    while (lo > 0 && d->cdf[lo] > u)
        lo--;
    while (hi + 1 < d->n && d->cdf[hi + 1] <= u)
        hi++;
    uint32_t i = lo + il_cdf_find(d->cdf + lo, hi - lo + 1, u);
    if (pmf)
        *pmf = il_distrib1d_pmf(d, i);
    if (u_remapped) {
        float width = d->cdf[i + 1] - d->cdf[i];
        float r = width > 0.0f ? (u - d->cdf[i]) / width : 0.0f;
        *u_remapped = il_clampf(r, 0.0f, IL_ONE_MINUS_EPSILON);
    }
    return i;
}
