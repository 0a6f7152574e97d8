/* Internals of the solvers (rad_solve*.c): blocks of form-factor rows fetched
 * in parallel, from the row cache or computed (one il_ff_work per thread). */
#ifndef IL_METHODS_RADIOSITY_RAD_SOLVE_H
#define IL_METHODS_RADIOSITY_RAD_SOLVE_H

#include "methods/radiosity/rad.h"
#include "methods/radiosity/rad_stall.h"

typedef struct il_rad_rows {
    uint32_t cap;              /* most rows per block */
    int threads;
    il_ff_work **work;         /* one per thread */
    const il_ff_row **row;     /* per slot: the fetched row */
    il_ff_row *copy;           /* per slot: a copy of a computed row (the cache
                                  may not keep it, and `work` is reused) */
    uint32_t *copy_cap;
    const il_distrib *distrib; /* on: rows computed split across processes */
} il_rad_rows;

il_status il_rad_rows_init(il_rad_rows *rows, const il_ff *ff, uint32_t cap, int threads,
                           il_error *err);
void il_rad_rows_free(il_rad_rows *rows);
/* Fetches the rows of `count` (<= cap) patches into rows->row[0..count):
 * patches[k], or first + k when patches is NULL.  Rows not in the cache are
 * computed in parallel and offered to it.  Adds the wall time to
 * stats->seconds_form_factors and the computed rows to stats->rows_computed. */
il_status il_rad_rows_fetch(il_rad_rows *rows, const il_ff *ff, il_ff_cache *cache,
                            const uint32_t *patches, uint32_t first, uint32_t count,
                            il_radiosity_stats *stats, il_error *err);
/* il_rad_rows_fetch split across the processes of rows->distrib
 * (rad_solve_distrib.c): the same rows, bit for bit, on every process. */
il_status il_rad_rows_fetch_split(il_rad_rows *rows, const il_ff *ff, il_ff_cache *cache,
                                  const uint32_t *patches, uint32_t first, uint32_t count,
                                  il_radiosity_stats *stats, il_error *err);
/* Copies src into slot k of rows->copy, growing it; false without memory. */
bool il_rad_rows_copy(il_rad_rows *rows, uint32_t k, const il_ff_row *src);
/* Bytes held by the row copies. */
size_t il_rad_rows_bytes(const il_rad_rows *rows);

/* Sum_i A_i lum(v_i): the luminance power of a per-patch radiance array
 * (up to the factor pi), summed in patch order. */
double il_rad_power(const il_patch_mesh *mesh, const il_vec3 *v);

/* Calls settings->on_step after a shot batch or sweep: display (3 floats per
 * patch) is filled with radiance + rho * ambient.  Returns the callback's
 * answer (false: stop). */
bool il_rad_report_step(const il_patch_mesh *mesh, const il_rad_settings *settings,
                        const il_vec3 *radiance, il_vec3 ambient, float *display,
                        uint32_t steps, double unshot_fraction, double seconds);

#endif
