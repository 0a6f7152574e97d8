/* il_rad_solve: picks the solver; the parallel row fetch both solvers use. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/radiosity/rad_solve.h"

il_status il_rad_rows_init(il_rad_rows *rows, const il_ff *ff, uint32_t cap, int threads,
                           il_error *err)
{
    memset(rows, 0, sizeof *rows);
    if (cap == 0)
        cap = 1;
    if (threads < 1)
        threads = 1;
    rows->cap = cap;
    rows->threads = threads;
    rows->work = il_calloc((size_t)threads, sizeof *rows->work, err);
    rows->row = il_calloc(cap, sizeof *rows->row, err);
    rows->copy = il_calloc(cap, sizeof *rows->copy, err);
    rows->copy_cap = il_calloc(cap, sizeof *rows->copy_cap, err);
    if (!rows->work || !rows->row || !rows->copy || !rows->copy_cap) {
        il_rad_rows_free(rows);
        return il_fail(err, IL_ERR_MEMORY, "radiosity: out of memory for form-factor rows");
    }
    for (int t = 0; t < threads; t++) {
        il_status st = il_ff_work_create(ff, &rows->work[t], err);
        if (st != IL_OK) {
            il_rad_rows_free(rows);
            return st;
        }
    }
    return IL_OK;
}

void il_rad_rows_free(il_rad_rows *rows)
{
    if (rows->work)
        for (int t = 0; t < rows->threads; t++)
            il_ff_work_release(rows->work[t]);
    if (rows->copy)
        for (uint32_t k = 0; k < rows->cap; k++) {
            free(rows->copy[k].index);
            free(rows->copy[k].value);
        }
    free(rows->work);
    free(rows->row);
    free(rows->copy);
    free(rows->copy_cap);
    memset(rows, 0, sizeof *rows);
}

size_t il_rad_rows_bytes(const il_rad_rows *rows)
{
    size_t b = 0;
    for (uint32_t k = 0; k < rows->cap; k++)
        b += (size_t)rows->copy_cap[k] * (sizeof(uint32_t) + sizeof(float));
    return b;
}

bool il_rad_rows_copy(il_rad_rows *rows, uint32_t k, const il_ff_row *src)
{
    il_ff_row *dst = &rows->copy[k];
    if (src->count > rows->copy_cap[k]) {
        uint32_t *idx = realloc(dst->index, (size_t)src->count * sizeof *idx);
        if (idx)
            dst->index = idx;
        float *val = realloc(dst->value, (size_t)src->count * sizeof *val);
        if (val)
            dst->value = val;
        if (!idx || !val)
            return false;
        rows->copy_cap[k] = src->count;
    }
    if (src->count) {
        memcpy(dst->index, src->index, (size_t)src->count * sizeof *dst->index);
        memcpy(dst->value, src->value, (size_t)src->count * sizeof *dst->value);
    }
    dst->count = src->count;
    return true;
}

il_status il_rad_rows_fetch(il_rad_rows *rows, const il_ff *ff, il_ff_cache *cache,
                            const uint32_t *patches, uint32_t first, uint32_t count,
                            il_radiosity_stats *stats, il_error *err)
{
    if (count > rows->cap)
        return il_fail(err, IL_ERR_INVALID, "radiosity: row block of %u exceeds %u", count,
                       rows->cap);
    if (il_distrib_on(rows->distrib))
        return il_rad_rows_fetch_split(rows, ff, cache, patches, first, count, stats, err);
    double t0 = omp_get_wtime();
    uint64_t computed = 0;
    int failed = 0;
    /* Each slot is written by one iteration only; a row's value depends on
     * (seed, patch) only, so the result is the same whatever the thread. */
#pragma omp parallel for schedule(dynamic, 1) num_threads(rows->threads) \
    reduction(+ : computed) reduction(| : failed)
    for (uint32_t k = 0; k < count; k++) {
        uint32_t i = patches ? patches[k] : first + k;
        const il_ff_row *row = il_ff_cache_get(cache, i);
        if (row) {
            rows->row[k] = row;
            continue;
        }
        il_ff_work *work = rows->work[omp_get_thread_num()];
        row = il_ff_compute_row(ff, work, i);
        computed++;
        il_ff_cache_put(cache, i, row);
        if (!il_rad_rows_copy(rows, k, row)) {
            failed |= 1;
            rows->row[k] = NULL;
            continue;
        }
        rows->row[k] = &rows->copy[k];
    }
    if (stats) {
        stats->seconds_form_factors += omp_get_wtime() - t0;
        stats->rows_computed += computed;
    }
    if (failed)
        return il_fail(err, IL_ERR_MEMORY, "radiosity: out of memory for form-factor rows");
    return IL_OK;
}

double il_rad_power(const il_patch_mesh *mesh, const il_vec3 *v)
{
    double p = 0.0;
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        p += (double)mesh->patches[i].area * (double)il_luminance(v[i]);
    return p;
}

il_status il_rad_solve(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                       const il_rad_settings *settings, il_rad_solution *sol,
                       il_radiosity_stats *stats, il_error *err)
{
    if (!mesh || !ff || !cache || !settings || !sol || sol->num_patches != mesh->num_patches)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: the solve needs a mesh, form factors, a cache and a solution");
    il_radiosity_stats local;
    memset(&local, 0, sizeof local);
    if (!stats)
        stats = &local;
    double t0 = omp_get_wtime();
    il_status st;
    switch (settings->solver) {
    case IL_SOLVER_SHOOTING:
        st = il_rad_solve_shooting(mesh, ff, cache, settings, sol, stats, err);
        break;
    case IL_SOLVER_JACOBI:
    case IL_SOLVER_GAUSS_SEIDEL:
        st = il_rad_solve_gathering(mesh, ff, cache, settings, sol, stats, err);
        break;
    default:
        return il_fail(err, IL_ERR_INVALID, "radiosity: unknown solver %d", (int)settings->solver);
    }
    /* Accumulated: il_rad_run solves twice with adaptive subdivision. */
    stats->seconds_solve += omp_get_wtime() - t0;
    stats->steps += sol->steps;
    stats->unshot_fraction = sol->unshot_fraction;
    stats->stalled = stats->stalled || sol->stalled;
    stats->cache_bytes = il_ff_cache_bytes(cache);
    return st;
}

bool il_rad_report_step(const il_patch_mesh *mesh, const il_rad_settings *settings,
                        const il_vec3 *radiance, il_vec3 ambient, float *display,
                        uint32_t steps, double unshot_fraction, double seconds)
{
    uint32_t n = mesh->num_patches;
    for (uint32_t i = 0; i < n; i++) {
        il_vec3 c = v3_add(radiance[i], v3_mul(mesh->patches[i].rho, ambient));
        display[3 * (size_t)i + 0] = c.x;
        display[3 * (size_t)i + 1] = c.y;
        display[3 * (size_t)i + 2] = c.z;
    }
    il_radiosity_progress prog = {
        .step = steps,
        .num_patches = n,
        .unshot_fraction = unshot_fraction,
        .seconds = seconds,
        .radiance = display,
    };
    if (settings->on_patches && !settings->on_patches(mesh, display, settings->on_patches_user))
        return false;
    return settings->on_step(&prog, settings->on_step_user);
}
