/* Gathering: iterative solution of the radiosity system in radiance,
 *     L_i = Ld_i + rho_i sum_j F_ij L_j
 * (Cohen & Wallace 1993, section 5.3: Jacobi and Gauss-Seidel iteration).
 *
 * Jacobi: every patch gathers from the previous sweep's values; the patches
 * of a block are updated in parallel.  It runs in increments, on the change
 * d = L - L_prev: d' = rho F d, L += d', from L = d = Ld (the same
 * iteration, kernel/kernel_radiosity.h).  Gauss-Seidel: patches are updated in
 * place in patch order, each seeing the values already updated in this
 * sweep (sequential; the rows are still computed in parallel ahead of use, a
 * block at a time).
 *
 * Convergence: the power the sweep changed, sum_i A_i lum(|L_new - L_old|),
 * over the initial power sum_i A_i lum(Ld_i), below the tolerance.  Sums are
 * formed in patch order, so the result does not depend on the thread count.
 * After the solve sol->unshot holds the last sweep's change (what a further
 * sweep would still roughly add), for display and diagnostics.
 *
 * Both solvers work on radiances in double and write the float solution
 * after each sweep.  Near an albedo of 1 a sweep changes L by far less than
 * float's resolution (at rho = 0.9998 and L near 25,000, whose ulp is
 * 0.002): in floats the change, a difference of nearly equal values, stuck
 * at a few ulps, L could not take changes below half an ulp, and the solve
 * stopped as stalled (rad_stall.h) short of its tolerance. */
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

/* out = rho_i sum_j F_ij X_j, X three doubles per patch. */
static void reflected(const il_patch_mesh *mesh, const il_ff_row *row, uint32_t i, const double *X,
                      double out[3])
{
    double r = 0.0, g = 0.0, b = 0.0;
    for (uint32_t k = 0; k < row->count; k++) {
        uint32_t j = row->index[k];
        if (j == i)
            continue;
        double f = row->value[k];
        r += f * X[3 * (size_t)j];
        g += f * X[3 * (size_t)j + 1];
        b += f * X[3 * (size_t)j + 2];
    }
    il_vec3 rho = mesh->patches[i].rho;
    out[0] = rho.x * r;
    out[1] = rho.y * g;
    out[2] = rho.z * b;
}

/* The power a change d carries at patch i: A_i lum(|d|). */
static double change_power(const il_patch_mesh *mesh, uint32_t i, const double *d)
{
    return (double)mesh->patches[i].area * (0.2126 * fabs(d[0]) + 0.7152 * fabs(d[1]) + 0.0722 * fabs(d[2]));
}

static il_vec3 to_float(const double *d) { return v3((float)d[0], (float)d[1], (float)d[2]); }

il_status il_rad_solve_gathering(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                                 const il_rad_settings *settings, il_rad_solution *sol,
                                 il_radiosity_stats *stats, il_error *err)
{
    uint32_t n = mesh->num_patches;
    bool jacobi = settings->solver == IL_SOLVER_JACOBI;
    double t0 = omp_get_wtime();
    for (uint32_t i = 0; i < n; i++) {
        sol->radiance[i] = sol->direct[i];
        sol->unshot[i] = v3s(0.0f);
    }
    sol->steps = 0;
    sol->ambient = v3s(0.0f);
    double p0 = il_rad_power(mesh, sol->direct);

    size_t nn = n ? n : 1u;
    /* In double, three per patch: the radiance being solved; Jacobi's last
     * and next increments. */
    size_t vec_bytes = nn * 3 * sizeof(double);
    double *lw = il_malloc(vec_bytes, err);
    double *dw = jacobi ? il_malloc(vec_bytes, err) : NULL, *nw = jacobi ? il_malloc(vec_bytes, err) : NULL;
    double *change = il_malloc(nn * sizeof *change, err);
    float *display = settings->on_step ? il_malloc(nn * 3 * sizeof *display, err) : NULL;
    if (!lw || (jacobi && (!dw || !nw)) || !change || (settings->on_step && !display)) {
        free(lw);
        free(dw);
        free(nw);
        free(change);
        free(display);
        return IL_ERR_MEMORY;
    }
    /* L = Ld, and Jacobi's increments start from d = Ld. */
    for (uint32_t i = 0; i < n; i++) {
        il_vec3 ld = sol->direct[i];
        double v[3] = {ld.x, ld.y, ld.z};
        memcpy(lw + 3 * (size_t)i, v, sizeof v);
        if (jacobi)
            memcpy(dw + 3 * (size_t)i, v, sizeof v);
    }
    /* Split across processes every process must fetch the same blocks,
     * whatever its thread count: the largest block then. */
    uint32_t bs = block_size(il_distrib_on(settings->distrib) ? 32 : settings->threads, n);
    il_rad_rows rows;
    il_status st = il_rad_rows_init(&rows, ff, bs, settings->threads, err);
    if (st != IL_OK) {
        free(lw);
        free(dw);
        free(nw);
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
        for (uint32_t first = 0; first < n && st == IL_OK; first += bs) {
            uint32_t count = n - first < bs ? n - first : bs;
            st = il_rad_rows_fetch(&rows, ff, cache, NULL, first, count, stats, err);
            if (st != IL_OK)
                break;
            if (jacobi) {
#pragma omp parallel for schedule(static) num_threads(settings->threads)
                for (uint32_t k = 0; k < count; k++)
                    reflected(mesh, rows.row[k], first + k, dw, nw + 3 * (size_t)(first + k));
            } else {
                for (uint32_t k = 0; k < count; k++) {
                    uint32_t i = first + k;
                    double o[3], *l = lw + 3 * (size_t)i;
                    reflected(mesh, rows.row[k], i, lw, o);
                    il_vec3 ld = sol->direct[i];
                    double d[3] = {ld.x + o[0] - l[0], ld.y + o[1] - l[1], ld.z + o[2] - l[2]};
                    for (int c = 0; c < 3; c++)
                        l[c] += d[c];
                    sol->unshot[i] = to_float(d);
                    change[i] = change_power(mesh, i, d);
                }
            }
        }
        if (st != IL_OK)
            break;
        if (jacobi) {
            for (uint32_t i = 0; i < n; i++) {
                const double *d = nw + 3 * (size_t)i;
                for (int c = 0; c < 3; c++)
                    lw[3 * (size_t)i + c] += d[c];
                sol->unshot[i] = to_float(d);
                change[i] = change_power(mesh, i, d);
            }
            double *t = dw;
            dw = nw;
            nw = t;
        }
        il_vec3 *L = sol->radiance;
        for (uint32_t i = 0; i < n; i++)
            L[i] = to_float(lw + 3 * (size_t)i);
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
    size_t working = il_rad_rows_bytes(&rows) + nn * sizeof *change + (jacobi ? 3 : 1) * vec_bytes +
                     (display ? nn * 3 * sizeof *display : 0);
    if (working > stats->peak_bytes)
        stats->peak_bytes = working;
    il_rad_rows_free(&rows);
    free(lw);
    free(dw);
    free(nw);
    free(change);
    free(display);
    return st;
}
