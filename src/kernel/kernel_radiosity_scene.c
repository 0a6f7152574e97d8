/* Packing and the CPU solve of the radiosity kernel; see
 * kernel_radiosity_scene.h. */
#include "kernel/kernel_radiosity_scene.h"

#include <stdlib.h>
#include <string.h>
#include "core/error.h"
#include "core/vec.h"
#include "methods/patch_mesh.h"
#include "methods/radiosity/rad_stall.h"

static ilk_vec3 to_k(il_vec3 v) { return ilk_v3(v.x, v.y, v.z); }

il_status il_krad_build(const il_patch_mesh *mesh, const il_vec3 *direct, uint32_t samples, uint64_t seed,
                        il_krad *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (samples == 0)
        return il_fail(err, IL_ERR_INVALID, "radiosity kernel: no rays per patch");
    if ((uint64_t)samples * mesh->num_patches > (uint64_t)1 << 34)
        return il_fail(err, IL_ERR_INVALID, "radiosity kernel: %u patches x %u rays is more form-factor "
                       "samples than it stores (2^34)", mesh->num_patches, samples);
    size_t np = mesh->num_patches ? mesh->num_patches : 1;
    out->patches = il_malloc(sizeof *out->patches * np, err);
    out->direct = il_malloc(sizeof *out->direct * np, err);
    if (!out->patches || !out->direct) {
        il_krad_free(out);
        return IL_ERR_MEMORY;
    }
    il_status st = il_kbvh_build_indexed(mesh->positions, mesh->tri_indices, mesh->num_tris, mesh->tri_patch,
                                         &out->bvh, err);
    if (st != IL_OK) {
        il_krad_free(out);
        return st;
    }
    double p0 = 0.0;
    for (uint32_t i = 0; i < mesh->num_patches; i++) {
        const il_patch *p = &mesh->patches[i];
        ilk_patch *q = &out->patches[i];
        memset(q, 0, sizeof *q);
        q->num_corners = p->num_corners == 4 ? 4 : 3;
        for (uint32_t c = 0; c < q->num_corners; c++)
            q->corner[c] = to_k(mesh->positions[p->v[c]]);
        q->normal = to_k(p->normal);
        q->rho = to_k(p->rho);
        q->area = p->area;
        /* As rad_ff_ray.c: the share of triangle (a b c) in the quad. */
        q->first_share = 1.0f;
        if (q->num_corners == 4) {
            il_vec3 a = mesh->positions[p->v[0]], b = mesh->positions[p->v[1]];
            il_vec3 c = mesh->positions[p->v[2]], d = mesh->positions[p->v[3]];
            float a1 = v3_length(v3_cross(v3_sub(b, a), v3_sub(c, a)));
            float a2 = v3_length(v3_cross(v3_sub(c, a), v3_sub(d, a)));
            q->first_share = a1 + a2 > 0.0f ? a1 / (a1 + a2) : 0.5f;
        }
        out->direct[i] = to_k(direct[i]);
        p0 += (double)p->area * (double)il_luminance(direct[i]);
    }
    out->initial_power = p0;
    ilk_rad_scene *v = &out->view;
    v->bvh = il_kbvh_view(&out->bvh);
    v->patches = out->patches;
    v->num_patches = mesh->num_patches;
    v->samples = samples;
    v->seed = seed;
    v->epsilon = mesh->tracer ? il_trace_epsilon(mesh->tracer) : 1e-4f;
    return IL_OK;
}

void il_krad_free(il_krad *k)
{
    il_kbvh_free(&k->bvh);
    free(k->patches);
    free(k->direct);
    memset(k, 0, sizeof *k);
}

il_status il_krad_solve(const il_krad *k, float tolerance, uint32_t max_steps, ilk_vec3 *radiance,
                        uint32_t *steps, double *fraction, bool *stalled, il_error *err)
{
    const ilk_rad_scene *sc = &k->view;
    uint32_t n = sc->num_patches, s = sc->samples;
    size_t nn = n ? n : 1;
    uint32_t *hits = il_malloc(sizeof *hits * nn * s, err);
    ilk_vec3 *delta = il_malloc(sizeof *delta * nn, err), *next = il_malloc(sizeof *next * nn, err);
    float *change = il_malloc(sizeof *change * nn, err);
    if (!hits || !delta || !next || !change) {
        free(hits);
        free(delta);
        free(next);
        free(change);
        return IL_ERR_MEMORY;
    }
    /* In the GPU's parts (ILK_RAD_ROW_PART samples each): the same rows. */
    uint32_t parts = (s + ILK_RAD_ROW_PART - 1) / ILK_RAD_ROW_PART;
#pragma omp parallel for schedule(dynamic, 16)
    for (uint64_t t = 0; t < (uint64_t)n * parts; t++) {
        uint32_t i = (uint32_t)(t / parts), first = (uint32_t)(t % parts) * ILK_RAD_ROW_PART;
        ilk_rad_row_part(sc, i, first, ILK_RAD_ROW_PART, hits + (size_t)i * s + first);
    }
    /* Sweeps in increments (kernel_radiosity.h): L = d = Ld, then d' = rho F d, L += d'. */
    for (uint32_t i = 0; i < n; i++)
        radiance[i] = delta[i] = k->direct[i];
    uint32_t step = 0;
    double frac = k->initial_power > 0.0 ? 1.0 : 0.0;
    il_rad_stall stall;
    il_rad_stall_start(&stall, 1);
    bool stuck = false;
    while (k->initial_power > 0.0 && (max_steps == 0 || step < max_steps)) {
#pragma omp parallel for schedule(static)
        for (uint32_t i = 0; i < n; i++) {
            next[i] = ilk_rad_bounce(sc, i, ilk_rad_sum(sc, hits + (size_t)i * s, 0, 1, delta));
            change[i] = ilk_rad_change(&sc->patches[i], next[i]);
        }
        double sum = 0.0;
        for (uint32_t i = 0; i < n; i++) {
            sum += change[i];
            radiance[i] = ilk_add(radiance[i], next[i]);
        }
        ilk_vec3 *t = delta;
        delta = next;
        next = t;
        frac = sum / k->initial_power;
        step++;
        if (frac < tolerance || (stuck = il_rad_stalled(&stall, step, frac)))
            break;
    }
    if (steps)
        *steps = step;
    if (fraction)
        *fraction = frac;
    if (stalled)
        *stalled = stuck;
    free(hits);
    free(delta);
    free(next);
    free(change);
    return IL_OK;
}
