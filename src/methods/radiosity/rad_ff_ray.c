/* Ray-cast form-factor rows: F_ij is the fraction of cosine-distributed rays
 * leaving patch i whose first hit is the front of patch j (Monte Carlo
 * estimate of the area-to-area form factor; Cohen & Wallace 1993, section
 * 4.9.4; Malley's method for the cosine lobe, pbrt-v4 A.5.3).  Origins are
 * stratified over the patch's area and directions over the disc of Malley's
 * map (a jittered m x m grid each, paired through a keyed permutation so
 * position and direction strata are independent); any remaining samples are
 * plain random.  Every random number comes from pcg32 seeded by (seed, i), so
 * a row does not depend on the thread or on when it is computed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "methods/radiosity/rad_ff_internal.h"

#define IL_FF_RAY_BATCH 64

/* A keyed permutation of [0, n): an invertible hash on the enclosing power
 * of two (xor, odd multiply and xor-shift are each bijective modulo 2^b),
 * cycle-walked until it lands below n (the idea of Kensler 2013, "Correlated
 * Multi-Jittered Sampling", section 3). */
static uint32_t permute(uint32_t k, uint32_t n, uint32_t key)
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

/* A uniform point on the patch for u in [0,1)^2: a quad is two triangles
 * (v0 v1 v2) and (v0 v2 v3) chosen by area along u.x. */
static il_vec3 patch_point(const il_rad_mesh *mesh, const il_rad_patch *p, float first_share,
                           il_vec2 u)
{
    const il_vec3 *x = mesh->positions;
    il_vec3 a = x[p->v[0]], b = x[p->v[1]], c = x[p->v[2]];
    if (p->num_corners == 4) {
        if (u.x < first_share) {
            u.x = u.x / first_share;
        } else {
            u.x = (u.x - first_share) / (1.0f - first_share);
            b = c;
            c = x[p->v[3]];
        }
        u.x = il_minf(u.x, 0x1.fffffep-1f);
    }
    il_vec2 bc = il_sample_triangle(u);
    return v3_add(a, v3_add(v3_scale(v3_sub(b, a), bc.x), v3_scale(v3_sub(c, a), bc.y)));
}

void il_ff_ray_row(const il_rad_mesh *mesh, uint32_t samples, uint64_t seed, uint32_t i,
                   float *scratch, il_ff_row *out)
{
    out->count = 0;
    if (i >= mesh->num_patches || samples == 0 || !mesh->tracer)
        return;
    const il_rad_patch *p = &mesh->patches[i];
    il_frame frame = il_frame_from_normal(p->normal);
    float first_share = 1.0f;
    if (p->num_corners == 4) {
        const il_vec3 *x = mesh->positions;
        il_vec3 a = x[p->v[0]], b = x[p->v[1]], c = x[p->v[2]], d = x[p->v[3]];
        float a1 = v3_length(v3_cross(v3_sub(b, a), v3_sub(c, a)));
        float a2 = v3_length(v3_cross(v3_sub(c, a), v3_sub(d, a)));
        first_share = a1 + a2 > 0.0f ? a1 / (a1 + a2) : 0.5f;
    }
    il_pcg32 rng = il_pcg32_seed(il_hash64(seed), 0x5f3759dfull * 2u + (uint64_t)i);
    uint32_t key = il_pcg32_next(&rng);
    uint32_t m = (uint32_t)sqrt((double)samples);
    while ((uint64_t)(m + 1) * (m + 1) <= samples)
        m++;
    uint32_t strata = m * m;
    float inv_m = 1.0f / (float)m;

    il_ray rays[IL_FF_RAY_BATCH];
    il_hit hits[IL_FF_RAY_BATCH];
    for (uint32_t base = 0; base < samples; base += IL_FF_RAY_BATCH) {
        uint32_t n = samples - base < IL_FF_RAY_BATCH ? samples - base : IL_FF_RAY_BATCH;
        for (uint32_t r = 0; r < n; r++) {
            uint32_t k = base + r;
            float j0 = il_pcg32_float(&rng), j1 = il_pcg32_float(&rng);
            float j2 = il_pcg32_float(&rng), j3 = il_pcg32_float(&rng);
            il_vec2 up, ud;
            if (k < strata) {
                uint32_t d = permute(k, strata, key);
                up = v2(((float)(k % m) + j0) * inv_m, ((float)(k / m) + j1) * inv_m);
                ud = v2(((float)(d % m) + j2) * inv_m, ((float)(d / m) + j3) * inv_m);
                up.x = il_minf(up.x, 0x1.fffffep-1f);
                up.y = il_minf(up.y, 0x1.fffffep-1f);
                ud.x = il_minf(ud.x, 0x1.fffffep-1f);
                ud.y = il_minf(ud.y, 0x1.fffffep-1f);
            } else {
                up = v2(j0, j1);
                ud = v2(j2, j3);
            }
            il_vec3 x = patch_point(mesh, p, first_share, up);
            il_vec3 dir = il_frame_to_world(&frame, il_sample_cosine_hemisphere(ud));
            rays[r].org = il_offset_origin(mesh->tracer, x, p->normal, dir);
            rays[r].dir = dir;
            rays[r].tmin = 0.0f;
            rays[r].tmax = INFINITY;
        }
        il_trace_closest_n(mesh->tracer, rays, hits, n);
        for (uint32_t r = 0; r < n; r++) {
            if (hits[r].mesh == IL_HIT_NONE)
                continue;
            uint32_t j = mesh->tri_patch[hits[r].prim];
            if (j == IL_RAD_NO_PATCH || j == i)
                continue;
            /* Only the front of a patch receives. */
            if (v3_dot(rays[r].dir, mesh->patches[j].normal) >= 0.0f)
                continue;
            if (scratch[j] == 0.0f)
                out->index[out->count++] = j;
            scratch[j] += 1.0f; /* counts stay exact in float below 2^24 */
        }
    }
    il_ff_row_compact(scratch, mesh->num_patches, 1.0f / (float)samples, out);
}
