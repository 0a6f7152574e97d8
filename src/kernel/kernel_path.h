/* One path-traced camera sample, shared by the CPU (gcc) and the GPU
 * megakernel (src/cuda/pt_kernel.cu): pinhole camera as scene/camera.c,
 * diffuse surfaces and front-face area emitters, next-event estimation on the
 * emissive triangles (chosen by power) at every vertex, cosine-weighted
 * bounces.  Emission is counted on camera rays only, so every path length is
 * estimated once, by NEE (pbrt-v4 section 13.4 without MIS: unbiased, and the
 * same expectation as the CPU path tracer's NEE + MIS).  Random numbers: the
 * CPU's Owen-scrambled Sobol sampler (kernel/kernel_sobol.h, the same
 * numbers as core/sampler.c for a (seed, pixel, sample, dimension)), the
 * camera jitter in dimensions 0-1 and three pairs per vertex (light choice,
 * point on the light, bounce), so the result does not depend on how pixels
 * are split among threads or GPU blocks.  The CPU path tracer spends its
 * dimensions differently (MIS, its own BSDF sampling), so images agree in
 * expectation, not bit for bit.  The PCG32 stream below (ilk_rng) is for
 * the photon kernels. */
#ifndef IL_KERNEL_PATH_H
#define IL_KERNEL_PATH_H

#include "kernel/kernel_bvh.h"
#include "kernel/kernel_sobol.h"

#define ILK_PI 3.14159265358979323846f

typedef struct ilk_material {
    ilk_vec3 diffuse;      /* albedo */
    uint32_t two_sided;    /* emits from both faces */
    ilk_vec3 emission;     /* radiance */
    uint32_t pad;
} ilk_material;

typedef struct ilk_camera {
    ilk_vec3 position, forward, right, up;
    float tan_half_x, tan_half_y, inv_width, inv_height;
} ilk_camera;

/* Everything a path needs, as flat arrays (host or device pointers).  The
 * material of tris[i] is materials[tris[i].pad] (bvh_build.c stores it). */
typedef struct ilk_scene {
    ilk_bvh bvh;
    const ilk_material *materials;
    const uint32_t *lights;        /* emissive triangles (indices into tris) */
    const float *light_cdf;        /* num_lights + 1 entries, by power */
    uint32_t num_lights;
    float epsilon;                 /* ray offset, as il_trace_epsilon */
    ilk_camera camera;
    uint32_t width, height, max_depth;
    uint64_t seed;
} ilk_scene;

/* PCG32 (O'Neill 2014, pcg-random.org, "XSH RR"), as core/rng.h. */
typedef struct ilk_rng { uint64_t state, inc; } ilk_rng;

IL_DEVICE_INLINE uint32_t ilk_rng_next(ilk_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xs = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xs >> rot) | (xs << ((32u - rot) & 31u));
}
/* [0, 1): the top 24 bits. */
IL_DEVICE_INLINE float ilk_rng_float(ilk_rng *r) { return (float)(ilk_rng_next(r) >> 8) * (1.0f / 16777216.0f); }

/* SplitMix64 finaliser (Steele et al. 2014) to key streams. */
IL_DEVICE_INLINE uint64_t ilk_hash64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

IL_DEVICE_INLINE ilk_rng ilk_rng_for(uint64_t seed, uint64_t pixel, uint32_t sample)
{
    ilk_rng r;
    r.state = 0;
    r.inc = (ilk_hash64(seed ^ (pixel << 20) ^ sample) << 1u) | 1u;
    ilk_rng_next(&r);
    r.state += ilk_hash64(pixel * 0x100000001b3ULL + sample + (seed << 40));
    ilk_rng_next(&r);
    return r;
}

/* Cosine-weighted direction around the unit normal n (Malley's method,
 * pbrt-v4 section A.5.3) in the basis of Duff et al. 2017 (JCGT 6(1)). */
IL_DEVICE_INLINE ilk_vec3 ilk_cosine_dir(ilk_vec3 n, float u1, float u2)
{
    float r = sqrtf(u1), phi = 2.0f * ILK_PI * u2;
    float x = r * cosf(phi), y = r * sinf(phi), z = sqrtf(ilk_maxf(0.0f, 1.0f - u1));
    float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    ilk_vec3 s = ilk_v3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    ilk_vec3 t = ilk_v3(b, sign + n.y * n.y * a, -n.y);
    return ilk_add(ilk_add(ilk_scale(s, x), ilk_scale(t, y)), ilk_scale(n, z));
}

/* The light with cdf[i] <= u < cdf[i+1] (binary search). */
IL_DEVICE_INLINE uint32_t ilk_pick_light(const float *cdf, uint32_t n, float u)
{
    uint32_t lo = 0, hi = n;
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Direct light at p (unit normal n facing the incoming side, albedo rho):
 * one emissive triangle by power (u), one uniform point on it (u1, u2;
 * pbrt-v4 section 6.5), the area-measure estimator
 * Le f cos cos' / (d^2 p_light p_area). */
IL_DEVICE_INLINE ilk_vec3 ilk_direct(const ilk_scene *sc, ilk_vec3 p, ilk_vec3 n, ilk_vec3 rho, float u, float u1,
                                     float u2)
{
    ilk_vec3 zero = ilk_v3(0, 0, 0);
    if (sc->num_lights == 0)
        return zero;
    uint32_t li = ilk_pick_light(sc->light_cdf, sc->num_lights, u);
    float pmf = sc->light_cdf[li + 1] - sc->light_cdf[li];
    if (!(pmf > 0.0f))
        return zero;
    const ilk_tri *lt = &sc->bvh.tris[sc->lights[li]];
    const ilk_material *lm = &sc->materials[lt->pad];
    float su = sqrtf(u1), b1 = u2 * su, b0 = 1.0f - su;
    ilk_vec3 q = ilk_add(lt->v0, ilk_add(ilk_scale(lt->e1, 1.0f - b0 - b1), ilk_scale(lt->e2, b1)));
    ilk_vec3 c = ilk_cross(lt->e1, lt->e2);
    float area2 = sqrtf(ilk_dot(c, c));
    if (!(area2 > 0.0f))
        return zero;
    ilk_vec3 nl = ilk_scale(c, 1.0f / area2);
    ilk_vec3 d = ilk_sub(q, p);
    float dist2 = ilk_dot(d, d);
    if (!(dist2 > 0.0f))
        return zero;
    float dist = sqrtf(dist2);
    ilk_vec3 w = ilk_scale(d, 1.0f / dist);
    float cos_p = ilk_dot(n, w), cos_l = -ilk_dot(nl, w);
    if (lm->two_sided)
        cos_l = cos_l < 0.0f ? -cos_l : cos_l;
    if (!(cos_p > 0.0f) || !(cos_l > 0.0f))
        return zero;
    ilk_ray shadow;
    shadow.org = ilk_add(p, ilk_scale(n, sc->epsilon));
    shadow.dir = ilk_sub(q, shadow.org);
    shadow.tmin = 0.0f;
    shadow.tmax = 1.0f - 1e-4f;
    if (ilk_bvh_occluded(&sc->bvh, &shadow))
        return zero;
    float g = cos_p * cos_l / dist2 * (0.5f * area2) / pmf * (1.0f / ILK_PI);
    return ilk_scale(ilk_mul(lm->emission, rho), g);
}

/* The pinhole camera ray through film position (x + u, y + v), as
 * scene/camera.c (pixel (0, 0) at the top left). */
IL_DEVICE_INLINE ilk_ray ilk_camera_ray(const ilk_camera *cam, uint32_t x, uint32_t y, float u, float v)
{
    float fx = (float)x + u, fy = (float)y + v;
    float sx = (2.0f * fx * cam->inv_width - 1.0f) * cam->tan_half_x;
    float sy = (1.0f - 2.0f * fy * cam->inv_height) * cam->tan_half_y;
    ilk_ray ray;
    ray.org = cam->position;
    ray.dir = ilk_normalize(ilk_add(cam->forward, ilk_add(ilk_scale(cam->right, sx), ilk_scale(cam->up, sy))));
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    return ray;
}

/* The radiance of one camera sample through pixel (x, y). */
IL_DEVICE_INLINE ilk_vec3 ilk_path_sample(const ilk_scene *sc, uint32_t x, uint32_t y, uint32_t sample)
{
    ilk_sobol smp = ilk_sobol_start(sc->seed, (uint64_t)y * sc->width + x, sample);
    float u, v;
    ilk_sobol_2d(&smp, &u, &v);
    ilk_ray ray = ilk_camera_ray(&sc->camera, x, y, u, v);
    ilk_vec3 L = ilk_v3(0, 0, 0), beta = ilk_v3(1, 1, 1);
    for (uint32_t depth = 0;; depth++) {
        ilk_hit h;
        if (!ilk_bvh_closest(&sc->bvh, &ray, &h))
            break;
        const ilk_tri *tr = &sc->bvh.tris[h.tri];
        const ilk_material *m = &sc->materials[tr->pad];
        ilk_vec3 ng = ilk_normalize(ilk_cross(tr->e1, tr->e2));
        float side = ilk_dot(ng, ray.dir);
        if (depth == 0 && (side < 0.0f || m->two_sided))
            L = ilk_add(L, ilk_mul(beta, m->emission));
        if (depth >= sc->max_depth)
            break;
        ilk_vec3 n = side < 0.0f ? ng : ilk_scale(ng, -1.0f);
        ilk_vec3 p = ilk_add(ray.org, ilk_scale(ray.dir, h.t));
        float ul, unused, u1, u2;
        ilk_sobol_2d(&smp, &ul, &unused);
        ilk_sobol_2d(&smp, &u1, &u2);
        L = ilk_add(L, ilk_mul(beta, ilk_direct(sc, p, n, m->diffuse, ul, u1, u2)));
        if (depth + 1 >= sc->max_depth)
            break;
        /* Lambertian: f cos / pdf = rho. */
        beta = ilk_mul(beta, m->diffuse);
        if (beta.x <= 0.0f && beta.y <= 0.0f && beta.z <= 0.0f)
            break;
        ilk_sobol_2d(&smp, &u1, &u2);
        ray.dir = ilk_cosine_dir(n, u1, u2);
        ray.org = ilk_add(p, ilk_scale(n, sc->epsilon));
        ray.tmin = 0.0f;
        ray.tmax = INFINITY;
    }
    return L;
}

#endif
