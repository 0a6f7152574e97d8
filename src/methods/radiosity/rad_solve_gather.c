/* Gathering: iterative solution of the radiosity system in radiance,
 *     L_i = Ld_i + rho_i sum_j F_ij L_j
 * (Cohen & Wallace 1993, section 5.3: Jacobi and Gauss-Seidel iteration).
 *
 * Jacobi: every patch gathers from the previous sweep's values; the patches
 * of a block are updated in parallel.  It runs in increments, on the change
 * d = L - L_prev: d' = rho F d, L += d', from L = d = Ld (the same
 * iteration; kernel/kernel_radiosity.h explains why: the measure is then
 * |d'| itself, not a difference of nearly equal floats, so it keeps falling
 * near an albedo of 1, where it otherwise sticks at a few ulps of L and the
 * solve stops as stalled).  Gauss-Seidel: patches are updated in
 * place in patch order, each seeing the values already updated in this
 * sweep (sequential; the rows are still computed in parallel ahead of use, a
 * block at a time).
 *
 * Convergence: the power the sweep changed, sum_i A_i lum(|L_new - L_old|),
 * over the initial power sum_i A_i lum(Ld_i), below the tolerance.  Sums are
 * formed in patch order, so the result does not depend on the thread count.
 * After the solve sol->unshot holds the last sweep's change (what a further
 * sweep would still roughly add), for display and diagnostics. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/radiosity/rad_solve.h"

/* Rows per block: enough to keep every thread busy, few enough that copies
 * of computed rows stay small. */
static uint32_t block_size(int threads, uint32_t n)
{
    uint32_t b = (uint32_t)threads * 8u;
    b = b < 16u ? 16u : (b > 256u ? 256u : b);
    return n < b ? (n ? n : 1u) : b;
}

/* rho_i sum_j F_ij L_j, in double. */
static void reflected(const il_patch_mesh *mesh, const il_ff_row *row, uint32_t i, const il_vec3 *L,
                      double out[3])
{
    double r = 0.0, g = 0.0, b = 0.0;
    for (uint32_t k = 0; k < row->count; k++) {
        uint32_t j = row->index[k];
        if (j == i)
            continue;
        double f = row->value[k];
        r += f * L[j].x;
        g += f * L[j].y;
        b += f * L[j].z;
    }
    il_vec3 rho = mesh->patches[i].rho;
    out[0] = rho.x * r;
    out[1] = rho.y * g;
    out[2] = rho.z * b;
}

static il_vec3 v3_abs(il_vec3 a) { return v3(fabsf(a.x), fabsf(a.y), fabsf(a.z)); }

il_status il_rad_solve_gathering(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                                 const il_rad_settings *settings, il_rad_solution *sol,
                                 il_radiosity_stats *stats, il_error *err)
{
    uint32_t n = mesh->num_patches;
    bool jacobi = settings->solver == IL_SOLVER_JACOBI;
    double t0 = omp_get_wtime();
    /* Jacobi's increments start from d = Ld. */
    for (uint32_t i = 0; i < n; i++) {
        sol->radiance[i] = sol->direct[i];
        sol->unshot[i] = jacobi ? sol->direct[i] : v3s(0.0f);
    }
    sol->steps = 0;
    sol->ambient = v3s(0.0f);
    double p0 = il_rad_power(mesh, sol->direct);

    size_t nn = n ? n : 1u;
    /* Jacobi writes the new sweep beside the old one; both keep the change. */
    il_vec3 *next = jacobi ? il_malloc(nn * sizeof *next, err) : NULL;
    double *change = il_malloc(nn * sizeof *change, err);
    float *display = settings->on_step ? il_malloc(nn * 3 * sizeof *display, err) : NULL;
    if ((jacobi && !next) || !change || (settings->on_step && !display)) {
        free(next);
        free(change);
        free(display);
        return IL_ERR_MEMORY;
    }
    /* Split across processes every process must fetch the same blocks,
     * whatever its thread count: the largest block then. */
    uint32_t bs = block_size(il_distrib_on(settings->distrib) ? 32 : settings->threads, n);
    il_rad_rows rows;
    il_status st = il_rad_rows_init(&rows, ff, bs, settings->threads, err);
    if (st != IL_OK) {
        free(next);
        free(change);
        free(display);
        return st;
    }
    rows.distrib = settings->distrib;

    uint32_t steps = 0;
    double frac = p0 > 0.0 ? 1.0 : 0.0;
    il_rad_stall stall;
    il_rad_stall_start(&stall, 1);
    sol->stalled = false;
    while (p0 > 0.0 && (settings->max_steps == 0 || steps < settings->max_steps)) {
        il_vec3 *L = sol->radiance;
        for (uint32_t first = 0; first < n && st == IL_OK; first += bs) {
            uint32_t count = n - first < bs ? n - first : bs;
            st = il_rad_rows_fetch(&rows, ff, cache, NULL, first, count, stats, err);
            if (st != IL_OK)
                break;
            if (jacobi) {
#pragma omp parallel for schedule(static) num_threads(settings->threads)
                for (uint32_t k = 0; k < count; k++) {
                    uint32_t i = first + k;
                    double o[3];
                    reflected(mesh, rows.row[k], i, sol->unshot, o);
                    next[i] = v3((float)o[0], (float)o[1], (float)o[2]);
                }
            } else {
                for (uint32_t k = 0; k < count; k++) {
                    uint32_t i = first + k;
                    /* The change Ld + rho F L - L in double, not as a
                     * difference of two nearly equal floats (see Jacobi). */
                    double o[3];
                    reflected(mesh, rows.row[k], i, L, o);
                    il_vec3 ld = sol->direct[i], l = L[i];
                    double d[3] = {ld.x + o[0] - l.x, ld.y + o[1] - l.y, ld.z + o[2] - l.z};
                    sol->unshot[i] = v3((float)d[0], (float)d[1], (float)d[2]);
                    change[i] = (double)mesh->patches[i].area * il_luminance(v3_abs(sol->unshot[i]));
                    L[i] = v3((float)(l.x + d[0]), (float)(l.y + d[1]), (float)(l.z + d[2]));
                }
            }
        }
        if (st != IL_OK)
            break;
        if (jacobi)
            for (uint32_t i = 0; i < n; i++) {
                sol->unshot[i] = next[i];
                change[i] = (double)mesh->patches[i].area * il_luminance(v3_abs(next[i]));
                L[i] = v3_add(L[i], next[i]);
            }
        double sum = 0.0;
        for (uint32_t i = 0; i < n; i++)
            sum += change[i];
        frac = sum / p0;
        steps++;
        if (settings->on_step && !il_rad_report_step(mesh, settings, L, v3s(0.0f), display,
                                                     steps, frac, omp_get_wtime() - t0))
            break;
        if (frac < settings->tolerance)
            break;
        if ((sol->stalled = il_rad_stalled(&stall, steps, frac)))
            break;
    }
    sol->steps = steps;
    sol->unshot_fraction = frac;
    size_t working = il_rad_rows_bytes(&rows) + nn * sizeof *change +
                     (next ? nn * sizeof *next : 0) + (display ? nn * 3 * sizeof *display : 0);
    if (working > stats->peak_bytes)
        stats->peak_bytes = working;
    il_rad_rows_free(&rows);
    free(next);
    free(change);
    free(display);
    return st;
}
