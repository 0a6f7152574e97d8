/* Radiosity by gathering, shared by the CPU (gcc) and the GPU (src/cuda/
 * radiosity_kernel.cu, one thread per patch): ray-cast form factors and the
 * Jacobi sweep of the radiosity system in radiance
 *
 *     L_i = Ld_i + rho_i sum_j F_ij L_j      (Cohen & Wallace 1993, 5.3)
 *
 * Form factors: F_ij is the fraction of `samples` cosine-distributed rays
 * from patch i whose first hit is the front of patch j (Cohen & Wallace
 * 1993, 4.9.4).  The rays are those of the CPU solver's ray-cast rows
 * (methods/radiosity/rad_ff_ray.c: the same pcg32 stream per (seed, i), the
 * same stratification of origins and directions, keyed permutation, disc
 * map and ray offset), so a row here equals the CPU's row up to the two
 * ray casters' rounding.  A row is kept as the list of the patches its rays
 * hit (ILK_NO_PATCH for a miss), samples entries per patch: the sweep sums
 * L over that list, which is sum_j (count_j / samples) L_j without a sort
 * or a sparse format, and the GPU needs no atomics. */
#ifndef IL_KERNEL_RADIOSITY_H
#define IL_KERNEL_RADIOSITY_H

#include <float.h>
#include "kernel/kernel_path.h"

#define ILK_NO_PATCH UINT32_MAX

/* Samples of a row per GPU thread (and per CPU task). */
#define ILK_RAD_ROW_PART 64u

/* A patch: a planar triangle or convex quad, counter-clockwise seen from
 * the front (methods/patch_mesh.h). */
typedef struct ilk_patch {
    ilk_vec3 corner[4];
    uint32_t num_corners;      /* 3 or 4 */
    ilk_vec3 normal;           /* unit, the front */
    float first_share;         /* quads: the area share of triangle (a b c) */
    ilk_vec3 rho;              /* diffuse reflectance */
    float area;
} ilk_patch;

/* The BVH's triangles carry their patch in tris[k].pad (ILK_NO_PATCH for
 * the triangles of mirrors and glass, which block rays but receive none). */
typedef struct ilk_rad_scene {
    ilk_bvh bvh;
    const ilk_patch *patches;
    uint32_t num_patches;
    uint32_t samples;          /* rays per patch */
    uint64_t seed;
    float epsilon;             /* the ray offset, as il_trace_epsilon */
} ilk_rad_scene;

/* core/rng.h's il_pcg32, device-safe (ilk_mix64, kernel_sobol.h, is its
 * il_hash64). */
IL_DEVICE_INLINE ilk_rng ilk_pcg32_seed(uint64_t seed, uint64_t stream)
{
    ilk_rng r;
    r.state = 0u;
    r.inc = (stream << 1u) | 1u;
    ilk_rng_next(&r);
    r.state += seed;
    ilk_rng_next(&r);
    return r;
}

/* Skips delta draws of the generator in O(log delta) (Brown 1994, "Random
 * Number Generation with Arbitrary Strides"; pcg-c's pcg_advance_lcg_64):
 * the LCG step x -> a x + c composed delta times by repeated squaring. */
IL_DEVICE_INLINE void ilk_rng_advance(ilk_rng *r, uint64_t delta)
{
    uint64_t cur_mult = 6364136223846793005ULL, cur_plus = r->inc, acc_mult = 1u, acc_plus = 0u;
    while (delta > 0) {
        if (delta & 1u) {
            acc_mult *= cur_mult;
            acc_plus = acc_plus * cur_mult + cur_plus;
        }
        cur_plus = (cur_mult + 1u) * cur_plus;
        cur_mult *= cur_mult;
        delta /= 2u;
    }
    r->state = acc_mult * r->state + acc_plus;
}

/* A keyed permutation of [0, n) (an invertible
 * hash on the enclosing power of two, cycle-walked; Kensler 2013). */
IL_DEVICE_INLINE uint32_t ilk_permute(uint32_t k, uint32_t n, uint32_t key)
{
    uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    do {
        k ^= key;
        k = (k * 0x9e3779b1u) & mask;
        k ^= (k & mask) >> 3;
        k = (k * 0x85ebca6bu + (key | 1u)) & mask;
        k ^= (k & mask) >> 7;
        k = (k * 0xc2b2ae35u) & mask;
    } while (k >= n);
    return k;
}

/* sin and cos on [-pi/4, pi/4] by Taylor polynomials (the first omitted
 * terms are below 1e-9, under float rounding): no sinf/cosf in the disc map. */
IL_DEVICE_INLINE void ilk_sincos_quarter(float x, float *sn, float *cs)
{
    float x2 = x * x;
    *sn = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    *cs = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800)))));
}

/* Malley's method on Shirley and Chiu's concentric disc (pbrt-v4 A.5.1):
 * a cosine-distributed direction, z up. */
IL_DEVICE_INLINE ilk_vec3 ilk_concentric_cosine(float ux, float uy)
{
    float ox = 2.0f * ux - 1.0f, oy = 2.0f * uy - 1.0f;
    if (ox == 0.0f && oy == 0.0f)
        return ilk_v3(0.0f, 0.0f, 1.0f);
    float r, sn, cs, dx, dy;
    if (fabsf(ox) > fabsf(oy)) {
        r = ox;
        ilk_sincos_quarter(0.25f * ILK_PI * (oy / ox), &sn, &cs);
        dx = r * cs, dy = r * sn;
    } else {
        r = oy;
        ilk_sincos_quarter(0.25f * ILK_PI * (ox / oy), &sn, &cs);
        dx = r * sn, dy = r * cs;
    }
    return ilk_v3(dx, dy, sqrtf(ilk_maxf(0.0f, 1.0f - dx * dx - dy * dy)));
}

/* A uniform point on the patch: a quad is (a b c) and (a c d) by area; in
 * a triangle, Heitz 2019's square-to-triangle map (core/sampling.c). */
IL_DEVICE_INLINE ilk_vec3 ilk_patch_point(const ilk_patch *p, float ux, float uy)
{
    ilk_vec3 a = p->corner[0], b = p->corner[1], c = p->corner[2];
    if (p->num_corners == 4) {
        if (ux < p->first_share) {
            ux = ux / p->first_share;
        } else {
            ux = (ux - p->first_share) / (1.0f - p->first_share);
            b = c;
            c = p->corner[3];
        }
        ux = ilk_minf(ux, 0x1.fffffep-1f);
    }
    float hx = 0.5f * ux, hy = 0.5f * uy, bx, by;
    if (ux < uy) {
        bx = hx;
        by = uy - hx;
    } else {
        bx = ux - hy;
        by = hy;
    }
    return ilk_add(a, ilk_add(ilk_scale(ilk_sub(b, a), bx), ilk_scale(ilk_sub(c, a), by)));
}

/* The ray of sample (up, ud) from patch p: lifted off the front as
 * il_offset_origin does, a cosine direction in the frame of Duff et al.
 * 2017 (core/vec.h's il_frame_from_normal). */
IL_DEVICE_INLINE ilk_ray ilk_patch_ray(const ilk_patch *p, float eps, float upx, float upy, float udx, float udy)
{
    ilk_vec3 x = ilk_patch_point(p, upx, upy);
    float mag = ilk_maxf(fabsf(x.x), ilk_maxf(fabsf(x.y), fabsf(x.z)));
    ilk_vec3 n = p->normal;
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    ilk_vec3 s = ilk_v3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    ilk_vec3 t = ilk_v3(b, sign + n.y * n.y * a, -n.y);
    ilk_vec3 d = ilk_concentric_cosine(udx, udy);
    ilk_ray ray;
    float off = eps + mag * 4.0f * FLT_EPSILON;
    ray.org = ilk_v3(x.x + n.x * off, x.y + n.y * off, x.z + n.z * off);
    ray.dir = ilk_add(ilk_add(ilk_scale(s, d.x), ilk_scale(t, d.y)), ilk_scale(n, d.z));
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    return ray;
}

/* The patch that ray r from patch i sees first, front side only. */
IL_DEVICE_INLINE uint32_t ilk_rad_first_patch(const ilk_rad_scene *sc, uint32_t i, const ilk_ray *r)
{
    ilk_hit h;
    if (!ilk_bvh_closest(&sc->bvh, r, &h))
        return ILK_NO_PATCH;
    uint32_t j = sc->bvh.tris[h.tri].pad;
    if (j == ILK_NO_PATCH || j == i || ilk_dot(r->dir, sc->patches[j].normal) >= 0.0f)
        return ILK_NO_PATCH;
    return j;
}

/* Samples first .. first + count - 1 of row i into hits[0 .. count): the
 * patch each ray sees (ILK_NO_PATCH: none).  The random numbers in
 * rad_ff_ray.c's order (the key, then four per sample), the generator
 * advanced past the earlier samples, so a row can be split among GPU
 * threads and still be the CPU's row. */
IL_DEVICE_INLINE void ilk_rad_row_part(const ilk_rad_scene *sc, uint32_t i, uint32_t first, uint32_t count,
                                       uint32_t *hits)
{
    uint32_t samples = sc->samples;
    const ilk_patch *p = &sc->patches[i];
    ilk_rng rng = ilk_pcg32_seed(ilk_mix64(sc->seed), 0x5f3759dfULL * 2u + (uint64_t)i);
    uint32_t key = ilk_rng_next(&rng);
    ilk_rng_advance(&rng, 4u * (uint64_t)first);
    uint32_t m = (uint32_t)sqrt((double)samples);
    while ((uint64_t)(m + 1) * (m + 1) <= samples)
        m++;
    uint32_t strata = m * m;
    float inv_m = 1.0f / (float)m;
    for (uint32_t k = first; k < first + count && k < samples; k++) {
        float j0 = ilk_rng_float(&rng), j1 = ilk_rng_float(&rng);
        float j2 = ilk_rng_float(&rng), j3 = ilk_rng_float(&rng);
        float upx = j0, upy = j1, udx = j2, udy = j3;
        if (k < strata) {
            uint32_t d = ilk_permute(k, strata, key);
            upx = ilk_minf(((float)(k % m) + j0) * inv_m, 0x1.fffffep-1f);
            upy = ilk_minf(((float)(k / m) + j1) * inv_m, 0x1.fffffep-1f);
            udx = ilk_minf(((float)(d % m) + j2) * inv_m, 0x1.fffffep-1f);
            udy = ilk_minf(((float)(d / m) + j3) * inv_m, 0x1.fffffep-1f);
        }
        ilk_ray r = ilk_patch_ray(p, sc->epsilon, upx, upy, udx, udy);
        hits[k - first] = ilk_rad_first_patch(sc, i, &r);
    }
}

/* The whole row i into hits[0 .. samples). */
IL_DEVICE_INLINE void ilk_rad_row(const ilk_rad_scene *sc, uint32_t i, uint32_t *hits)
{
    ilk_rad_row_part(sc, i, 0, sc->samples, hits);
}

/* The sum of L over hits[k] for k = first, first + stride, ... < samples
 * (the CPU: one call with stride 1; the GPU: one call per lane of a warp,
 * the lanes' sums then added). */
IL_DEVICE_INLINE ilk_vec3 ilk_rad_sum(const ilk_rad_scene *sc, const uint32_t *hits, uint32_t first,
                                      uint32_t stride, const ilk_vec3 *L)
{
    float r = 0.0f, g = 0.0f, b = 0.0f;
    for (uint32_t k = first; k < sc->samples; k += stride) {
        uint32_t j = hits[k];
        if (j == ILK_NO_PATCH)
            continue;
        r += L[j].x;
        g += L[j].y;
        b += L[j].z;
    }
    return ilk_v3(r, g, b);
}

/* Jacobi sweeps in increments.  The sweep L' = Ld + rho F L (F the row's
 * hits over samples) is run on the change d = L - L_prev instead of on L:
 * d' = rho F d, L' = L + d', starting from L = d = Ld.  It is the same
 * iteration, but the sum runs over the small changes rather than over
 * radiances of nearly equal size, and the convergence measure is |d'|
 * itself rather than the difference of two nearly equal floats: near an
 * albedo of 1 (L near 1000 changing by 0.01 a sweep at albedo 0.999), the
 * sweeps on L in float measured their change with 10% noise and stopped
 * short (methods/radiosity/rad_stall.h).  It is Jacobi iteration (Cohen &
 * Wallace 1993, section 5.3) written for its successive differences. */

/* The change of patch i from the sum over its row's hits of the previous
 * sweep's changes: rho_i sum / samples. */
IL_DEVICE_INLINE ilk_vec3 ilk_rad_bounce(const ilk_rad_scene *sc, uint32_t i, ilk_vec3 sum)
{
    float inv = 1.0f / (float)sc->samples;
    ilk_vec3 rho = sc->patches[i].rho;
    return ilk_v3(rho.x * (sum.x * inv), rho.y * (sum.y * inv), rho.z * (sum.z * inv));
}

/* The power a change d carries at patch i: A_i lum(|d|), the solver's
 * convergence measure (methods/radiosity/rad_solve_gather.c). */
IL_DEVICE_INLINE float ilk_rad_change(const ilk_patch *p, ilk_vec3 d)
{
    return p->area * (0.2126f * fabsf(d.x) + 0.7152f * fabsf(d.y) + 0.0722f * fabsf(d.z));
}

#endif
