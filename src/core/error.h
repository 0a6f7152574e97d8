/* Filling an il_error: every fallible function reports through these. */
#ifndef IL_CORE_ERROR_H
#define IL_CORE_ERROR_H

#include "illum/illum.h"

/* Sets err (when not NULL) to status and a printf-formatted message; returns
 * status so callers can write `return il_fail(err, IL_ERR_IO, "...")`. */
il_status il_fail(il_error *err, il_status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Resets err to IL_OK with an empty message. */
void il_error_clear(il_error *err);

/* malloc/calloc/realloc that report IL_ERR_MEMORY through err on failure. */
void *il_malloc(size_t size, il_error *err);
void *il_calloc(size_t count, size_t size, il_error *err);

#endif
