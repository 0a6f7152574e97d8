/* The light set: the environment as N directional lights.
 *
 * The light arriving at a surface from the environment is the integral
 *     L_o(wo) = int_S2 f(wo, wi) L_env(wi) |cos theta_i| V(wi) dwi,
 * and its Monte Carlo estimate with N directions wi_k drawn with density
 * p(wi) is  1/N sum_k f L_env(wi_k) |cos| V / p(wi_k)  (Veach 1997, 2.4;
 * pbrt-v4 2.1.3).  Fixing the N directions once for the whole image turns
 * the environment into N directional lights of radiance-per-density
 * L_env(wi_k) / (p(wi_k) N): Kemmer 2005's conversion.  Agarwal et al.
 * 2003 (Structured Importance Sampling) and Debevec 2005 (median cut) split
 * the map into regions and give each light its region's energy; the Monte
 * Carlo weight keeps the estimate unbiased for every N.
 *
 * Four ways to choose wi_k from two numbers u in [0,1)^2:
 *  - random points, uniform over the sphere (p = 1/(4 pi));
 *  - Sobol points, uniform over the sphere: il_sample_uniform_sphere is
 *    area-preserving, so the (0,2)-sequence's strata become equal-area
 *    regions of the sphere (quasi-Monte Carlo, Keller 1996);
 *  - random points through il_environment_sample: importance sampling of
 *    the map's luminance (p proportional to it, so every light carries
 *    about the same power);
 *  - Sobol points through il_environment_sample: importance and
 *    stratification together.
 * The Sobol points are the Owen-scrambled, shuffled (0,2)-sequence of
 * core/sampler (Burley 2020) keyed by the render seed: any prefix of
 * 2^k points is still a (0,k,2)-net, so every batch keeps the set
 * stratified, and each seed gives an independent randomisation (an
 * unbiased estimate, Owen 1997).  The random points are PCG numbers keyed
 * by (seed, light index). */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/ibl/ibl.h"
#include "scene/lights.h"

/* The sample stream of the light set: keyed like a pixel that no film has
 * (pixel indices are below 2^32), its sample index the light's index. */
#define IL_IBL_LIGHT_KEY 0xfffffffffffff1b1ull

void il_ibl_light(const il_scene *scene, il_ibl_selection selection, uint64_t seed, uint32_t i,
                  il_vec3 *dir, il_vec3 *weight)
{
    bool sobol = selection == IL_IBL_IMPORTANCE_SOBOL || selection == IL_IBL_SOBOL;
    bool importance = selection == IL_IBL_IMPORTANCE_SOBOL || selection == IL_IBL_IMPORTANCE;
    il_sampler smp;
    il_sampler_start(&smp, sobol ? IL_SAMPLER_SOBOL : IL_SAMPLER_PCG, seed, IL_IBL_LIGHT_KEY, i);
    il_vec2 u = il_sampler_2d(&smp);
    il_vec3 L;
    float pdf;
    if (importance) {
        L = il_environment_sample(scene, u, dir, &pdf);
    } else {
        *dir = il_sample_uniform_sphere(u);
        pdf = IL_INV_4PI;
        L = il_environment_radiance(scene, *dir);
    }
    *weight = pdf > 0.0f && isfinite(pdf) ? v3_scale(L, 1.0f / pdf) : v3s(0.0f);
    if (!v3_is_finite(*weight))
        *weight = v3s(0.0f);
}

il_status il_ibl_lights_alloc(il_ibl_lights *out, uint32_t capacity, il_error *err)
{
    memset(out, 0, sizeof *out);
    out->dir = il_malloc((capacity ? capacity : 1) * sizeof(il_vec3), err);
    out->weight = il_malloc((capacity ? capacity : 1) * sizeof(il_vec3), err);
    if (!out->dir || !out->weight) {
        il_ibl_lights_free(out);
        return IL_ERR_MEMORY;
    }
    out->capacity = capacity;
    return IL_OK;
}

void il_ibl_lights_fill(const il_scene *scene, il_ibl_selection selection, uint64_t seed,
                        uint32_t first, uint32_t count, int threads, il_ibl_lights *out)
{
    if (count > out->capacity)
        count = out->capacity;
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(static) num_threads(nt)
    for (uint32_t k = 0; k < count; k++)
        il_ibl_light(scene, selection, seed, first + k, &out->dir[k], &out->weight[k]);
    out->first = first;
    out->count = count;
}

il_status il_ibl_lights_build(const il_scene *scene, il_ibl_selection selection, uint64_t seed,
                              uint32_t count, int threads, il_ibl_lights *out, il_error *err)
{
    il_status st = il_ibl_lights_alloc(out, count, err);
    if (st == IL_OK)
        il_ibl_lights_fill(scene, selection, seed, 0, count, threads, out);
    return st;
}

void il_ibl_lights_free(il_ibl_lights *l)
{
    free(l->dir);
    free(l->weight);
    l->dir = l->weight = NULL;
    l->first = l->count = l->capacity = 0;
}
