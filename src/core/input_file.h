/* What an input may be: the readers of whole files (image/image.c,
 * scene/load.c) read only files and pipes; a device such as /dev/zero
 * never ends. */
#ifndef IL_CORE_INPUT_FILE_H
#define IL_CORE_INPUT_FILE_H

#include <stdbool.h>
#include <stdio.h>
#include <sys/stat.h>

/* Whether f, just opened for reading, is a file or a pipe. */
static inline bool il_input_is_file(FILE *f)
{
    struct stat st;
    return fstat(fileno(f), &st) == 0 && (S_ISREG(st.st_mode) || S_ISFIFO(st.st_mode));
}

#endif
