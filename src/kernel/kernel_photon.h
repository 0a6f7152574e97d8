/* One photon path, shared by the CPU (gcc) and the GPU (src/cuda/
 * photon_kernel.cu, one thread per photon): emission from the emissive
 * triangles of kernel/kernel_scene.h (chosen by power, a uniform point,
 * a cosine-distributed direction), diffuse bounces with Russian roulette,
 * and a record at every diffuse hit (Jensen 2001, chapter 5: the global
 * map; the first hits, direct light, are recorded but left out of the
 * grid, kernel_grid.h, since the gather takes direct light by a shadow ray).
 *
 * Every photon owns max_depth consecutive record slots (photon i writes
 * slots[i * max_depth ..]); the unused ones are marked empty.  No atomics:
 * the output depends only on (seed, i), identical on both targets up to
 * float rounding, and the grid's sort (kernel/kernel_grid.h) drops the empty
 * slots at the end. */
#ifndef IL_KERNEL_PHOTON_H
#define IL_KERNEL_PHOTON_H

#include "kernel/kernel_path.h"

#define ILK_PHOTON_EMPTY UINT32_MAX

/* 40 bytes: where it landed, its power (W), the geometric normal turned to
 * the side it arrived from, and how many bounces it took (ILK_PHOTON_EMPTY:
 * an unused slot). */
typedef struct ilk_photon {
    ilk_vec3 p;
    uint32_t bounces;
    ilk_vec3 power;
    ilk_vec3 n;
} ilk_photon;


IL_DEVICE_INLINE ilk_rng ilk_photon_rng(uint64_t seed, uint32_t index)
{
    /* A stream of its own, apart from the camera streams (pixel < 2^40). */
    return ilk_rng_for(seed ^ 0x70686f746f6e0000ULL, (1ULL << 40) + index, 0);
}

/* Traces photon `index` of `num_emitted` and fills its max_depth slots. */
IL_DEVICE_INLINE void ilk_photon_trace(const ilk_scene *sc, uint32_t index, uint32_t num_emitted, ilk_photon *slots)
{
    uint32_t max_store = sc->max_depth, stored = 0;
    for (uint32_t k = 0; k < max_store; k++)
        slots[k].bounces = ILK_PHOTON_EMPTY;
    if (sc->num_lights == 0 || num_emitted == 0)
        return;
    ilk_rng rng = ilk_photon_rng(sc->seed, index);
    float u = ilk_rng_float(&rng), u1 = ilk_rng_float(&rng), u2 = ilk_rng_float(&rng);
    uint32_t li = ilk_pick_light(sc->light_cdf, sc->num_lights, u);
    float pmf = sc->light_cdf[li + 1] - sc->light_cdf[li];
    const ilk_tri *lt = &sc->bvh.tris[sc->lights[li]];
    const ilk_material *lm = &sc->materials[lt->pad];
    ilk_vec3 c = ilk_cross(lt->e1, lt->e2);
    float area2 = sqrtf(ilk_dot(c, c));
    if (!(pmf > 0.0f) || !(area2 > 0.0f))
        return;
    float su = sqrtf(u1), b1 = u2 * su, b0 = 1.0f - su;
    ilk_vec3 q = ilk_add(lt->v0, ilk_add(ilk_scale(lt->e1, 1.0f - b0 - b1), ilk_scale(lt->e2, b1)));
    ilk_vec3 nl = ilk_scale(c, 1.0f / area2);
    float sides = 1.0f;
    if (lm->two_sided) {
        sides = 2.0f;
        if (ilk_rng_float(&rng) < 0.5f)
            nl = ilk_scale(nl, -1.0f);
    }
    /* Light power Phi = pi A Le per face (Lambertian emitter); the photon
     * carries Phi / (pmf N), pmf the chance of this light. */
    ilk_vec3 power = ilk_scale(lm->emission, ILK_PI * 0.5f * area2 * sides / (pmf * (float)num_emitted));
    float e1 = ilk_rng_float(&rng), e2 = ilk_rng_float(&rng);
    ilk_ray ray;
    ray.dir = ilk_cosine_dir(nl, e1, e2);
    ray.org = ilk_add(q, ilk_scale(nl, sc->epsilon));
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    for (uint32_t bounce = 0; stored < max_store; bounce++) {
        ilk_hit h;
        if (!ilk_bvh_closest(&sc->bvh, &ray, &h))
            return;
        const ilk_tri *tr = &sc->bvh.tris[h.tri];
        const ilk_material *m = &sc->materials[tr->pad];
        ilk_vec3 ng = ilk_normalize(ilk_cross(tr->e1, tr->e2));
        ilk_vec3 n = ilk_dot(ng, ray.dir) < 0.0f ? ng : ilk_scale(ng, -1.0f);
        ilk_vec3 p = ilk_add(ray.org, ilk_scale(ray.dir, h.t));
        ilk_photon *rec = &slots[stored++];
        rec->p = p;
        rec->power = power;
        rec->n = n;
        rec->bounces = bounce;
        /* Russian roulette on the albedo (Jensen 2001, 2.4.1): survive with
         * q = max(rho), carry rho / q, so the power stays about constant. */
        float survive = ilk_minf(1.0f, ilk_max3(m->diffuse));
        if (!(survive > 0.0f) || ilk_rng_float(&rng) >= survive)
            return;
        power = ilk_scale(ilk_mul(power, m->diffuse), 1.0f / survive);
        float d1 = ilk_rng_float(&rng), d2 = ilk_rng_float(&rng);
        ray.dir = ilk_cosine_dir(n, d1, d2);
        ray.org = ilk_add(p, ilk_scale(n, sc->epsilon));
        ray.tmin = 0.0f;
        ray.tmax = INFINITY;
    }
}

#endif
