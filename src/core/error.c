#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *il_status_name(il_status status)
{
    switch (status) {
    case IL_OK: return "ok";
    case IL_ERR_IO: return "i/o error";
    case IL_ERR_FORMAT: return "format error";
    case IL_ERR_INVALID: return "invalid input";
    case IL_ERR_MEMORY: return "out of memory";
    case IL_ERR_RUNTIME: return "runtime failure";
    }
    return "unknown status";
}

il_status il_fail(il_error *err, il_status status, const char *fmt, ...)
{
    if (err) {
        err->status = status;
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return status;
}

void il_error_clear(il_error *err)
{
    if (err) {
        err->status = IL_OK;
        err->message[0] = '\0';
    }
}

void *il_malloc(size_t size, il_error *err)
{
    void *p = malloc(size ? size : 1);
    if (!p)
        il_fail(err, IL_ERR_MEMORY, "out of memory allocating %zu bytes", size);
    return p;
}

void *il_calloc(size_t count, size_t size, il_error *err)
{
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p)
        il_fail(err, IL_ERR_MEMORY, "out of memory allocating %zu x %zu bytes", count, size);
    return p;
}
