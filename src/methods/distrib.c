/* See distrib.h. */
#include "methods/distrib.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"

il_status il_distrib_check(const il_distrib *d, const il_render_desc *desc, const char *method,
                           il_error *err)
{
    if (!d)
        return IL_OK;
    if (d->size < 1 || d->rank < 0 || d->rank >= d->size)
        return il_fail(err, IL_ERR_INVALID, "%s: distributed rank %d of %d is out of range", method,
                       d->rank, d->size);
    if (d->size > 1 && !d->allgather)
        return il_fail(err, IL_ERR_INVALID, "%s: a distributed render needs an exchange (allgather)",
                       method);
    if (d->size > 1 && desc->time_limit > 0.0)
        return il_fail(err, IL_ERR_INVALID,
                       "%s: a distributed render renders a pass count, not for a time", method);
    return IL_OK;
}

il_status il_distrib_allgather(const il_distrib *d, const void *data, size_t bytes, void **out,
                               size_t *counts, il_error *err)
{
    *out = NULL;
    size_t *c = counts ? counts : calloc((size_t)d->size, sizeof *c);
    if (!c)
        return il_fail(err, IL_ERR_MEMORY, "distributed render: out of memory");
    int rc = d->allgather(d->user, data, bytes, out, c);
    if (!counts)
        free(c);
    if (rc != 0) {
        free(*out);
        *out = NULL;
        return il_fail(err, IL_ERR_RUNTIME, "distributed render: the exchange between processes failed");
    }
    return IL_OK;
}

void il_distrib_range(uint64_t n, int rank, int size, uint64_t *lo, uint64_t *hi)
{
    uint64_t q = n / (uint64_t)size, r = n % (uint64_t)size, k = (uint64_t)rank;
    *lo = k * q + (k < r ? k : r);
    *hi = *lo + q + (k < r ? 1 : 0);
}
