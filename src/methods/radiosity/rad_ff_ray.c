/* Ray-cast form-factor rows: F_ij is the fraction of cosine-distributed rays
 * leaving patch i whose first hit is the front of patch j (Monte Carlo
 * estimate of the area-to-area form factor; Cohen & Wallace 1993, section
 * 4.9.4; Malley's method for the cosine lobe, pbrt-v4 A.5.3).  Origins are
 * stratified over the patch's area and directions over the disc of Malley's
 * map (a jittered m x m grid each, paired through a keyed permutation so
 * position and direction strata are independent); any remaining samples are
 * plain random.  Every random number comes from pcg32 seeded by (seed, i), so
 * a row does not depend on the thread or on when it is computed.
 *
 * Speed: the rays go in direction-stratum order (neighbouring rays leave a
 * small patch in neighbouring directions, so Embree's traversal stays in
 * cache: the stratified samples are drawn first, in the usual order, into
 * the slots of their direction strata), through the stream call in batches
 * of 256; the disc map uses short polynomials instead of sinf/cosf; the
 * hit patches' normals are prefetched.  The order changes no result: the
 * rays are the same and the counts are exact. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "kernel/kernel_radiosity.h"
#include "methods/radiosity/rad_ff_internal.h"

#define IL_FF_RAY_BATCH 256

/* The rays of a row are the GPU kernel's (kernel/kernel_radiosity.h, one
 * source for both): ilk_permute, a keyed permutation of [0, n) (Kensler
 * 2013, "Correlated Multi-Jittered Sampling", section 3), and Malley's
 * cosine directions on the concentric disc. */
static inline il_vec3 cosine_direction(il_vec2 u)
{
    ilk_vec3 d = ilk_concentric_cosine(u.x, u.y);
    return v3(d.x, d.y, d.z);
}

/* A uniform point on the patch for u in [0,1)^2: a quad is two triangles
 * (a b c) and (a c d) chosen by area along u.x; inside a triangle
 * il_sample_triangle (Heitz 2019) maps the square onto it. */
static inline il_vec3 patch_point(const il_vec3 *corner, uint32_t num_corners, float first_share,
                                  il_vec2 u)
{
    il_vec3 a = corner[0], b = corner[1], c = corner[2];
    if (num_corners == 4) {
        if (u.x < first_share) {
            u.x = u.x / first_share;
        } else {
            u.x = (u.x - first_share) / (1.0f - first_share);
            b = c;
            c = corner[3];
        }
        u.x = il_minf(u.x, 0x1.fffffep-1f);
    }
    il_vec2 bary = il_sample_triangle(u);
    return v3_add(a, v3_add(v3_scale(v3_sub(b, a), bary.x), v3_scale(v3_sub(c, a), bary.y)));
}

/* The ray of sample (up, ud): a point on the patch lifted off it along the
 * normal as il_offset_origin does (every ray leaves on the front side),
 * and a cosine-distributed direction. */
typedef struct ray_setup {
    il_frame frame;
    il_vec3 corner[4];
    uint32_t num_corners;
    float first_share, eps;
} ray_setup;

static inline il_ray make_ray(const ray_setup *rs, il_vec2 up, il_vec2 ud)
{
    il_vec3 x = patch_point(rs->corner, rs->num_corners, rs->first_share, up);
    float mag = il_maxf(fabsf(x.x), il_maxf(fabsf(x.y), fabsf(x.z)));
    il_ray ray;
    ray.org = v3_fma(x, rs->frame.n, rs->eps + mag * 4.0f * FLT_EPSILON);
    ray.dir = il_frame_to_world(&rs->frame, cosine_direction(ud));
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    return ray;
}

/* Traces n rays and counts the first hits on the front of patches other
 * than i.  The patch of each hit first, prefetching its normal (the
 * patches are large and hit in no order), then the front test. */
static void trace_batch(const il_patch_mesh *mesh, uint32_t i, const il_ray *rays, il_hit *hits,
                        uint32_t n, float *scratch, il_ff_row *out)
{
    il_trace_closest_n(mesh->tracer, rays, hits, n);
    uint32_t hit_patch[IL_FF_RAY_BATCH];
    for (uint32_t r = 0; r < n; r++) {
        uint32_t j = hits[r].mesh == IL_HIT_NONE ? IL_NO_PATCH : mesh->tri_patch[hits[r].prim];
        hit_patch[r] = j == i ? IL_NO_PATCH : j;
        if (hit_patch[r] != IL_NO_PATCH)
            __builtin_prefetch(&mesh->patches[j].normal);
    }
    for (uint32_t r = 0; r < n; r++) {
        uint32_t j = hit_patch[r];
        /* Only the front of a patch receives. */
        if (j == IL_NO_PATCH || v3_dot(rays[r].dir, mesh->patches[j].normal) >= 0.0f)
            continue;
        if (scratch[j] == 0.0f)
            out->index[out->count++] = j;
        scratch[j] += 1.0f; /* counts stay exact in float below 2^24 */
    }
}

void il_ff_ray_row_ordered(const il_patch_mesh *mesh, uint32_t samples, uint64_t seed, uint32_t i,
                           float *scratch, il_vec2 *order, il_ff_row *out)
{
    out->count = 0;
    if (i >= mesh->num_patches || samples == 0 || !mesh->tracer)
        return;
    const il_patch *p = &mesh->patches[i];
    ray_setup rs;
    rs.frame = il_frame_from_normal(p->normal);
    rs.num_corners = p->num_corners == 4 ? 4 : 3;
    for (uint32_t k = 0; k < rs.num_corners; k++)
        rs.corner[k] = mesh->positions[p->v[k]];
    rs.first_share = 1.0f;
    if (rs.num_corners == 4) {
        il_vec3 a = rs.corner[0], b = rs.corner[1], c = rs.corner[2], d = rs.corner[3];
        float a1 = v3_length(v3_cross(v3_sub(b, a), v3_sub(c, a)));
        float a2 = v3_length(v3_cross(v3_sub(c, a), v3_sub(d, a)));
        rs.first_share = a1 + a2 > 0.0f ? a1 / (a1 + a2) : 0.5f;
    }
    rs.eps = il_trace_epsilon(mesh->tracer);
    il_pcg32 rng = il_pcg32_seed(il_hash64(seed), 0x5f3759dfull * 2u + (uint64_t)i);
    uint32_t key = il_pcg32_next(&rng);
    uint32_t m = (uint32_t)sqrt((double)samples);
    while ((uint64_t)(m + 1) * (m + 1) <= samples)
        m++;
    uint32_t strata = m * m;
    float inv_m = 1.0f / (float)m;

    /* With `order`, the stratified samples are first drawn (in sample order,
     * so the random numbers are the same) into the slot of their direction
     * stratum, and traced in that order. */
    if (order) {
        for (uint32_t k = 0; k < strata; k++) {
            float j0 = il_pcg32_float(&rng), j1 = il_pcg32_float(&rng);
            float j2 = il_pcg32_float(&rng), j3 = il_pcg32_float(&rng);
            uint32_t d = ilk_permute(k, strata, key);
            il_vec2 up = v2(((float)(k % m) + j0) * inv_m, ((float)(k / m) + j1) * inv_m);
            il_vec2 ud = v2(((float)(d % m) + j2) * inv_m, ((float)(d / m) + j3) * inv_m);
            order[2 * d] = v2(il_minf(up.x, 0x1.fffffep-1f), il_minf(up.y, 0x1.fffffep-1f));
            order[2 * d + 1] = v2(il_minf(ud.x, 0x1.fffffep-1f), il_minf(ud.y, 0x1.fffffep-1f));
        }
    }
    il_ray rays[IL_FF_RAY_BATCH];
    il_hit hits[IL_FF_RAY_BATCH];
    for (uint32_t base = 0; base < samples; base += IL_FF_RAY_BATCH) {
        uint32_t n = samples - base < IL_FF_RAY_BATCH ? samples - base : IL_FF_RAY_BATCH;
        for (uint32_t r = 0; r < n; r++) {
            uint32_t k = base + r;
            il_vec2 up, ud;
            if (k < strata && order) {
                up = order[2 * k];
                ud = order[2 * k + 1];
            } else {
                float j0 = il_pcg32_float(&rng), j1 = il_pcg32_float(&rng);
                float j2 = il_pcg32_float(&rng), j3 = il_pcg32_float(&rng);
                if (k < strata) {
                    uint32_t d = ilk_permute(k, strata, key);
                    up = v2(((float)(k % m) + j0) * inv_m, ((float)(k / m) + j1) * inv_m);
                    ud = v2(((float)(d % m) + j2) * inv_m, ((float)(d / m) + j3) * inv_m);
                    up = v2(il_minf(up.x, 0x1.fffffep-1f), il_minf(up.y, 0x1.fffffep-1f));
                    ud = v2(il_minf(ud.x, 0x1.fffffep-1f), il_minf(ud.y, 0x1.fffffep-1f));
                } else {
                    up = v2(j0, j1);
                    ud = v2(j2, j3);
                }
            }
            rays[r] = make_ray(&rs, up, ud);
        }
        trace_batch(mesh, i, rays, hits, n, scratch, out);
    }
    il_ff_row_compact(scratch, mesh->num_patches, 1.0f / (float)samples, out);
}

void il_ff_ray_row(const il_patch_mesh *mesh, uint32_t samples, uint64_t seed, uint32_t i,
                   float *scratch, il_ff_row *out)
{
    /* The same row with or without the buffer (only the tracing order
     * differs); without one when it cannot be had. */
    il_vec2 *order = malloc(2 * (size_t)(samples ? samples : 1) * sizeof *order);
    il_ff_ray_row_ordered(mesh, samples, seed, i, scratch, order, out);
    free(order);
}
