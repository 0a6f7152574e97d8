/* The library side of one render split across processes (il_distrib in
 * illum.h, docs/distributed.md): checks and the one exchange the methods
 * use.  The caller (src/cli/mpi/) implements the exchange with MPI; the
 * library never sees MPI. */
#ifndef IL_METHODS_DISTRIB_H
#define IL_METHODS_DISTRIB_H

#include <stdbool.h>
#include <stddef.h>
#include "illum/illum.h"

/* True when the render is split across more than one process. */
static inline bool il_distrib_on(const il_distrib *d) { return d && d->size > 1; }

/* IL_ERR_INVALID when d is set but malformed (rank out of range, no
 * exchange) or the options cannot run split (a time limit). */
il_status il_distrib_check(const il_distrib *d, const il_render_desc *desc, const char *method,
                           il_error *err);

/* d->allgather with the library's error reporting: every process's bytes
 * concatenated in rank order into *out (free() it; NULL when empty);
 * counts (d->size entries, may be NULL) gets each process's bytes. */
il_status il_distrib_allgather(const il_distrib *d, const void *data, size_t bytes, void **out,
                               size_t *counts, il_error *err);

/* The part [lo, hi) of n items that process `rank` of `size` takes:
 * contiguous, in rank order, sizes differing by at most one. */
void il_distrib_range(uint64_t n, int rank, int size, uint64_t *lo, uint64_t *hi);

#endif
