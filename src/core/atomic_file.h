/* Files that appear whole or not at all: written under a temporary name in the
 * target's folder (so rename() is atomic) and renamed into place only when
 * everything was written.  Every output of illum goes through this. */
#ifndef IL_CORE_ATOMIC_FILE_H
#define IL_CORE_ATOMIC_FILE_H

#include <stdio.h>
#include "illum/illum.h"

typedef struct il_atomic_file {
    FILE *f;            /* write here */
    const char *path;   /* the target */
    char *tmp;          /* path + ".tmp-" + six random characters (mkstemp), or in
                           path's folder ".illum-tmp-" + six for a long name */
} il_atomic_file;

/* Creates the temporary file (mode 0644) and opens it for binary writing. */
il_status il_atomic_open(il_atomic_file *af, const char *path, il_error *err);

/* Finishes: when `status` (the outcome of writing) is IL_OK, flushes, syncs
 * and renames the file into place; otherwise, or when any of that fails,
 * removes the temporary file.  Returns the final status. */
il_status il_atomic_close(il_atomic_file *af, il_status status, il_error *err);

/* Checks, before any work is spent on its content, that `path` can be written
 * the way il_atomic_open and il_atomic_close will: not empty, not a folder,
 * and a temporary file can be created beside it (it is removed at once). */
il_status il_atomic_check(const char *path, il_error *err);

#endif
