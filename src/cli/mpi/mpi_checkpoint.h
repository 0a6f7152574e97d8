/* Checkpoints of a distributed path-traced render (docs/distributed.md,
 * "Checkpoints"): which 16x16 tiles of the film are finished and the film's
 * sums, so that a run that failed can be run again and render only the rest.
 * Rank 0 alone reads and writes them.  No MPI here. */
#ifndef IL_CLI_MPI_CHECKPOINT_H
#define IL_CLI_MPI_CHECKPOINT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "illum/illum.h"

#define CLI_FNV_OFFSET 0xcbf29ce484222325ull

/* FNV-1a, 64 bits (Fowler, Noll, Vo): h = (h ^ byte) * 0x100000001b3 per byte. */
uint64_t cli_fnv1a(uint64_t h, const void *data, size_t bytes);
/* Adds the contents of the file at path to h; false when it cannot be read. */
bool cli_fnv1a_file(uint64_t *h, const char *path);

/* The fingerprint of a render: the command line (argv[1..argc-1]) without
 * the options that do not change the film, the contents of every argument
 * that names a file, and il_render's options (docs/distributed.md). */
uint64_t cli_checkpoint_fingerprint(int argc, char **argv, const il_render_desc *desc, uint32_t width,
                                    uint32_t height);

typedef struct cli_checkpoint {
    uint64_t fingerprint;     /* the scene and every option that changes pixels */
    uint32_t width, height;   /* the film */
    uint32_t tiles;           /* entries of done */
    unsigned char *done;      /* per tile (row by row): 1 when its pixels are in film */
    double *film;             /* il_film_data: width * height * 4 doubles */
} cli_checkpoint;

/* Writes the checkpoint to `path` atomically: a temporary file beside it,
 * fsync, rename, fsync of the folder.  A reader sees the old checkpoint or
 * the new one, never a part. */
il_status cli_checkpoint_write(const char *path, const cli_checkpoint *ck, il_error *err);

/* Reads `path` into ck->done and ck->film (allocated by the caller, sized by
 * ck's width, height and tiles).  *found is false (and IL_OK) when there is
 * no such file.  A file that is not a checkpoint, is damaged, or was written
 * by another render (fingerprint or size differ) is IL_ERR_INVALID with a
 * message saying so; ck is then unchanged. */
il_status cli_checkpoint_read(const char *path, cli_checkpoint *ck, bool *found, il_error *err);

#endif
