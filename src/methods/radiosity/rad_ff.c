/* The form-factor front end: holds the mesh and settings (and the hemicube's
 * delta form factors) and computes rows with the chosen back-end into
 * per-thread work buffers. */
#include <stdlib.h>

#include "core/error.h"
#include "methods/radiosity/rad_ff_internal.h"

#define IL_FF_DEFAULT_HEMICUBE 256u
#define IL_FF_DEFAULT_RAYS 4096u

struct il_ff {
    const il_patch_mesh *mesh;
    il_rad_settings settings;
    il_hemicube *hemicube;      /* IL_FF_HEMICUBE only */
};

struct il_ff_work {
    const il_ff *ff;
    il_hemicube_buffers *hemicube;
    float *scratch;             /* ray-cast tallies, num_patches, kept zeroed */
    il_vec2 *ray_order;         /* ray-cast samples in tracing order, 2 * ray_samples */
    il_ff_row row;              /* index/value with room for num_patches */
};

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

void il_ff_row_compact(float *scratch, uint32_t num_patches, float scale, il_ff_row *row)
{
    uint32_t count = row->count;
    if (count > num_patches / 16u) {
        /* Many entries: one sweep over scratch is cheaper than a sort. */
        uint32_t c = 0;
        for (uint32_t j = 0; j < num_patches; j++) {
            if (scratch[j] != 0.0f) {
                row->index[c] = j;
                row->value[c] = scratch[j] * scale;
                scratch[j] = 0.0f;
                c++;
            }
        }
        row->count = c;
        return;
    }
    qsort(row->index, count, sizeof *row->index, cmp_u32);
    for (uint32_t k = 0; k < count; k++) {
        uint32_t j = row->index[k];
        row->value[k] = scratch[j] * scale;
        scratch[j] = 0.0f;
    }
}

/* IL_FF_AUTO.  A hemicube of resolution N has 3N^2 pixels (the top face N^2,
 * the four half sides 2N^2); with fewer than about 4 of them a patch, small
 * and distant patches fall between pixel centres and the rows alias, and a
 * row's cost, which grows with the patches projected, passes the ray-cast
 * row's (4096 rays whatever the count).  Measured (docs/radiosity.md, "When
 * to use which"): on the Cornell box the hemicube is the more accurate at
 * equal time from 6,170 patches up to about 43,000, where the two are even
 * (hemicube 195 s, ray-cast 45 s); on the atrium's 150,848 patches ray-cast
 * takes 74 s against 280 s and is the closer of the two to a 32,768-ray
 * reference. */
il_form_factor_method il_ff_auto_method(il_form_factor_method method, uint32_t num_patches,
                                        uint32_t hemicube_resolution)
{
    if (method != IL_FF_AUTO)
        return method;
    uint64_t n = hemicube_resolution ? hemicube_resolution : IL_FF_DEFAULT_HEMICUBE;
    return (uint64_t)num_patches * 4u <= 3u * n * n ? IL_FF_HEMICUBE : IL_FF_RAYCAST;
}

il_form_factor_method il_ff_method(const il_ff *ff) { return ff->settings.form_factors; }

il_status il_ff_create(const il_patch_mesh *mesh, const il_rad_settings *settings, il_ff **out,
                       il_error *err)
{
    *out = NULL;
    if (!mesh || !settings)
        return il_fail(err, IL_ERR_INVALID, "form factors: no mesh or settings");
    if ((unsigned)settings->form_factors > IL_FF_RAYCAST)
        return il_fail(err, IL_ERR_INVALID, "form factors: unknown method %d",
                       (int)settings->form_factors);
    il_form_factor_method method =
        il_ff_auto_method(settings->form_factors, mesh->num_patches, settings->hemicube_resolution);
    if (method == IL_FF_RAYCAST && !mesh->tracer)
        return il_fail(err, IL_ERR_INVALID, "form factors: the mesh has no tracer");
    il_ff *ff = il_calloc(1, sizeof *ff, err);
    if (!ff)
        return IL_ERR_MEMORY;
    ff->mesh = mesh;
    ff->settings = *settings;
    ff->settings.form_factors = method;
    if (ff->settings.hemicube_resolution == 0)
        ff->settings.hemicube_resolution = IL_FF_DEFAULT_HEMICUBE;
    if (ff->settings.ray_samples == 0)
        ff->settings.ray_samples = IL_FF_DEFAULT_RAYS;
    if (method == IL_FF_HEMICUBE) {
        il_status st = il_hemicube_create(mesh, ff->settings.hemicube_resolution, &ff->hemicube, err);
        if (st != IL_OK) {
            free(ff);
            return st;
        }
    }
    *out = ff;
    return IL_OK;
}

void il_ff_release(il_ff *ff)
{
    if (!ff)
        return;
    il_hemicube_release(ff->hemicube);
    free(ff);
}

il_status il_ff_work_create(const il_ff *ff, il_ff_work **out, il_error *err)
{
    *out = NULL;
    il_ff_work *w = il_calloc(1, sizeof *w, err);
    if (!w)
        return IL_ERR_MEMORY;
    w->ff = ff;
    size_t n = ff->mesh->num_patches ? ff->mesh->num_patches : 1;
    w->row.index = il_malloc(n * sizeof *w->row.index, err);
    w->row.value = w->row.index ? il_malloc(n * sizeof *w->row.value, err) : NULL;
    if (!w->row.value) {
        il_ff_work_release(w);
        return IL_ERR_MEMORY;
    }
    if (ff->hemicube) {
        il_status st = il_hemicube_buffers_create(ff->hemicube, &w->hemicube, err);
        if (st != IL_OK) {
            il_ff_work_release(w);
            return st;
        }
    } else {
        w->scratch = il_calloc(n, sizeof *w->scratch, err);
        w->ray_order = w->scratch ? il_malloc(2 * (size_t)ff->settings.ray_samples * sizeof *w->ray_order, err)
                                  : NULL;
        if (!w->ray_order) {
            il_ff_work_release(w);
            return IL_ERR_MEMORY;
        }
    }
    *out = w;
    return IL_OK;
}

void il_ff_work_release(il_ff_work *work)
{
    if (!work)
        return;
    il_hemicube_buffers_release(work->hemicube);
    free(work->scratch);
    free(work->ray_order);
    free(work->row.index);
    free(work->row.value);
    free(work);
}

const il_ff_row *il_ff_compute_row(const il_ff *ff, il_ff_work *work, uint32_t i)
{
    work->row.count = 0;
    if (i >= ff->mesh->num_patches)
        return &work->row;
    if (ff->hemicube)
        il_hemicube_row(ff->hemicube, work->hemicube, i, &work->row);
    else
        il_ff_ray_row_ordered(ff->mesh, ff->settings.ray_samples, ff->settings.seed, i,
                              work->scratch, work->ray_order, &work->row);
    return &work->row;
}
