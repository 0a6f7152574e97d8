/* Radiance estimates from a photon map (Jensen 2001, 7.1-7.2).
 *
 *   L(x, wo) ~ sum_p f(x, wo, wi_p) Phi_p w(d_p) / (norm pi r^2)
 *
 * r is the distance to the k-th nearest photon (k-NN) or the fixed radius,
 * w the filter kernel and norm its integral over the unit disc divided by
 * pi, so that a uniform photon density gives the same answer with every
 * filter:
 *   cone (7.2.2):   w = 1 - d / (k r), k = 1.1; norm = 1 - 2 / (3k)
 *                   (integral of w over the disc: pi r^2 (1 - 2/(3k)))
 *   Epanechnikov:   w = 1 - d^2 / r^2;          norm = 1/2
 *                   (the 2D kernel 2/(pi r^2) (1 - d^2/r^2) integrates to 1)
 */
#include <string.h>

#include "core/error.h"
#include "methods/photon/pm_internal.h"

#define CONE_K 1.1f

void il_pm_scratch_free(il_pm_scratch *s)
{
    if (!s)
        return;
    free(s->knn);
    il_pm_buffer_free(&s->range);
    memset(s, 0, sizeof *s);
}

/* Which photons the estimate uses is chosen by q->lookup, whichever
 * structure the map holds (both answer both queries): IL_PHOTON_KDTREE the
 * q->k nearest within q->radius (k = 0: all within q->radius), IL_PHOTON_GRID
 * all within q->radius.  *found = 0 when there is nothing to estimate. */
static il_status gather(const il_pm_map *map, const il_pm_lookup *q, il_vec3 p,
                        il_pm_scratch *scratch, const il_pm_neighbour **nb, uint32_t *found,
                        float *r2, il_error *err)
{
    *found = 0;
    if (!map || map->count == 0 || !(q->radius > 0.0f))
        return IL_OK;
    float max_d2 = q->radius * q->radius;
    /* Far from every photon of the map (a caustic map lit in one corner):
     * nothing to search for. */
    const float pq[3] = {p.x, p.y, p.z};
    float out_d2 = 0.0f;
    for (int c = 0; c < 3; c++) {
        float e = il_maxf(map->lo[c] - pq[c], pq[c] - map->hi[c]);
        out_d2 += e > 0.0f ? e * e : 0.0f;
    }
    if (out_d2 > max_d2)
        return IL_OK;
    if (q->lookup == IL_PHOTON_KDTREE && q->k > 0) {
        if (scratch->knn_cap < q->k) {
            il_pm_neighbour *items = realloc(scratch->knn, (size_t)q->k * sizeof *items);
            if (!items)
                return il_fail(err, IL_ERR_MEMORY, "photon map: out of memory for %u neighbours", q->k);
            scratch->knn = items;
            scratch->knn_cap = q->k;
        }
        *found = il_pm_knn(map, p, q->k, max_d2, scratch->knn, r2);
        *nb = scratch->knn;
    } else {
        scratch->range.count = 0;
        il_status st = il_pm_range(map, p, max_d2, &scratch->range, err);
        if (st != IL_OK)
            return st;
        *found = scratch->range.count;
        *nb = scratch->range.items;
        *r2 = max_d2;
    }
    if (!(*r2 > 0.0f))
        *found = 0;
    return IL_OK;
}

/* The filter's weight of a photon at squared distance d2 and the factor
 * 1 / (norm pi r^2) (the header's kernels). */
typedef struct pm_filter {
    bool cone;
    float r, inv_r2, inv_kr, scale;
} pm_filter;

static pm_filter filter_for(il_photon_filter filter, float r2, float power_scale)
{
    pm_filter f;
    f.cone = filter == IL_PHOTON_CONE;
    f.r = sqrtf(r2);
    f.inv_r2 = 1.0f / r2;
    f.inv_kr = f.cone ? 1.0f / (CONE_K * sqrtf(r2)) : 0.0f;
    float norm = f.cone ? 1.0f - 2.0f / (3.0f * CONE_K) : 0.5f;
    f.scale = power_scale / (norm * IL_PI * r2);
    return f;
}

static inline float filter_weight(const pm_filter *f, float d2)
{
    return f->cone ? 1.0f - sqrtf(d2) * f->inv_kr : 1.0f - d2 * f->inv_r2;
}

/* gather, then the filter for the radius the photons were found in. */
static il_status gather_filtered(const il_pm_map *map, const il_pm_lookup *q, il_vec3 p,
                                 il_pm_scratch *scratch, const il_pm_neighbour **nb,
                                 uint32_t *found, pm_filter *flt, il_error *err)
{
    float r2 = 0.0f;
    il_status st = gather(map, q, p, scratch, nb, found, &r2, err);
    if (st == IL_OK && *found > 0)
        *flt = filter_for(q->filter, r2, map->power_scale);
    return st;
}

/* The seed's fix for light leaking round corners and through thin walls,
 * only photons that landed on a surface facing the same way, and the disc
 * that leaves out those on a parallel surface just behind the query's
 * (il_pm_on_surface). */
static inline bool on_surface(const il_photon *ph, il_vec3 n, il_vec3 x, const pm_filter *flt)
{
    return il_pm_on_surface(ph, n, x, flt->r);
}

/* The grazing limit of scene/bsdf.c (IL_BSDF_EPS there). */
#define LAMBERT_EPS 1e-7f

/* A Lambertian BSDF is rho/pi for every wi it does not reject, so the sum
 * over photons is rho/pi times the sum of the accepted powers: one product
 * instead of an il_bsdf_eval per photon.  The rejection is il_bsdf_eval's,
 * term for term (scene/bsdf.c): wo and wi on the same side of the
 * geometric normal, neither grazing in the shading frame flipped to wo's
 * side.  So the answer equals the general loop's up to float rounding. */
static il_vec3 lambert_sum(const il_pm_map *map, const il_bsdf *bsdf, il_vec3 p, il_vec3 n,
                           il_vec3 wo, const il_pm_neighbour *nb, uint32_t found,
                           const pm_filter *flt)
{
    float zo = v3_dot(wo, bsdf->frame.n);
    float side = zo < 0.0f ? -1.0f : 1.0f;
    if (!(side * zo > LAMBERT_EPS))
        return v3s(0.0f);
    float go = v3_dot(wo, bsdf->ng);
    il_vec3 sum = v3s(0.0f);
    for (uint32_t i = 0; i < found; i++) {
        const il_photon *ph = &map->photons[nb[i].index];
        if (!on_surface(ph, n, p, flt))
            continue;
        il_vec3 wi = il_photon_dir(ph);
        if (!(go * v3_dot(wi, bsdf->ng) > 0.0f) || !(side * v3_dot(wi, bsdf->frame.n) > LAMBERT_EPS))
            continue;
        sum = v3_fma(sum, il_photon_power(ph), filter_weight(flt, nb[i].d2));
    }
    return v3_mul(v3_scale(bsdf->diffuse, IL_INV_PI), sum);
}

il_status il_pm_estimate(const il_pm_map *map, const il_pm_lookup *q, const il_bsdf *bsdf,
                         il_vec3 p, il_vec3 n, il_vec3 wo, il_pm_scratch *scratch, il_vec3 *out,
                         il_error *err)
{
    *out = v3s(0.0f);
    const il_pm_neighbour *nb = NULL;
    uint32_t found;
    pm_filter flt;
    il_status st = gather_filtered(map, q, p, scratch, &nb, &found, &flt, err);
    if (st != IL_OK || found == 0)
        return st;
    if (bsdf->type == IL_MATERIAL_DIFFUSE) {
        *out = v3_scale(lambert_sum(map, bsdf, p, n, wo, nb, found, &flt), flt.scale);
        return IL_OK;
    }
    il_vec3 sum = v3s(0.0f);
    for (uint32_t i = 0; i < found; i++) {
        const il_photon *ph = &map->photons[nb[i].index];
        if (!on_surface(ph, n, p, &flt))
            continue;
        il_vec3 f = il_bsdf_eval(bsdf, wo, il_photon_dir(ph), NULL);
        if (v3_is_zero(f))
            continue;
        sum = v3_fma(sum, v3_mul(f, il_photon_power(ph)), filter_weight(&flt, nb[i].d2));
    }
    *out = v3_scale(sum, flt.scale);
    return IL_OK;
}

il_status il_pm_irradiance_estimate(const il_pm_map *map, const il_pm_lookup *q, il_vec3 p,
                                    il_vec3 n, il_pm_scratch *scratch, il_vec3 *out, il_error *err)
{
    *out = v3s(0.0f);
    const il_pm_neighbour *nb = NULL;
    uint32_t found;
    pm_filter flt;
    il_status st = gather_filtered(map, q, p, scratch, &nb, &found, &flt, err);
    if (st != IL_OK || found == 0)
        return st;
    il_vec3 sum = v3s(0.0f);
    for (uint32_t i = 0; i < found; i++) {
        const il_photon *ph = &map->photons[nb[i].index];
        if (!on_surface(ph, n, p, &flt) || !(v3_dot(il_photon_dir(ph), n) > 0.0f))
            continue;
        sum = v3_fma(sum, il_photon_power(ph), filter_weight(&flt, nb[i].d2));
    }
    *out = v3_scale(sum, flt.scale);
    return IL_OK;
}

il_status il_pm_estimate_global(const il_pm_map *map, const il_pm_lookup *q, const il_bsdf *bsdf,
                                il_vec3 p, il_vec3 n, il_vec3 wo, il_pm_scratch *scratch,
                                il_vec3 *out, il_error *err)
{
    if (!map || !map->irr || bsdf->type != IL_MATERIAL_DIFFUSE)
        return il_pm_estimate(map, q, bsdf, p, n, wo, scratch, out, err);
    *out = v3s(0.0f);
    /* il_bsdf_eval's rejection of a grazing or back-facing wo, as above. */
    float zo = fabsf(v3_dot(wo, bsdf->frame.n));
    if (!(zo > LAMBERT_EPS) || v3_dot(wo, bsdf->ng) == 0.0f)
        return IL_OK;
    il_vec3 E;
    if (il_pm_irradiance_lookup(map, p, n, q->radius * q->radius, &E))
        *out = v3_mul(v3_scale(bsdf->diffuse, IL_INV_PI), E);
    return IL_OK;
}
