/* Checkpoint files (mpi_checkpoint.h).  Layout, host byte order:
 *   "ILLUMCKP", u32 version, u32 0x01020304 (byte order), u32 width,
 *   u32 height, u32 tiles, u32 0, u64 fingerprint,
 *   tiles bytes (done), width*height*4 doubles (film),
 *   u64 FNV-1a of everything before it (a torn or changed file is refused).
 * Written through il_atomic_file (temporary name, fsync, rename), then the
 * folder is synced so that the rename itself is on disk. */
#include "cli/mpi/mpi_checkpoint.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "core/atomic_file.h"
#include "core/error.h"

#define MAGIC "ILLUMCKP"
#define VERSION 1u
#define BYTE_ORDER_MARK 0x01020304u
#define HEADER_BYTES (8 + 6 * 4 + 8)

uint64_t cli_fnv1a(uint64_t h, const void *data, size_t bytes)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < bytes; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

bool cli_fnv1a_file(uint64_t *h, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    unsigned char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0)
        *h = cli_fnv1a(*h, buf, n);
    bool ok = !ferror(f);
    fclose(f);
    return ok;
}

static size_t film_bytes(const cli_checkpoint *ck)
{
    return (size_t)ck->width * ck->height * 4 * sizeof(double);
}

static void put_u32(unsigned char **p, uint32_t v)
{
    memcpy(*p, &v, 4);
    *p += 4;
}

/* The folder of path, so that the rename itself is on disk. */
static void sync_folder(const char *path)
{
    char dir[4096];
    cli_folder_of(path, dir, sizeof dir);
    int fd = open(dir, O_RDONLY);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
}

il_status cli_checkpoint_write(const char *path, const cli_checkpoint *ck, il_error *err)
{
    unsigned char head[HEADER_BYTES], *p = head;
    memcpy(p, MAGIC, 8);
    p += 8;
    put_u32(&p, VERSION);
    put_u32(&p, BYTE_ORDER_MARK);
    put_u32(&p, ck->width);
    put_u32(&p, ck->height);
    put_u32(&p, ck->tiles);
    put_u32(&p, 0);
    memcpy(p, &ck->fingerprint, 8);
    uint64_t sum = cli_fnv1a(CLI_FNV_OFFSET, head, sizeof head);
    sum = cli_fnv1a(sum, ck->done, ck->tiles);
    sum = cli_fnv1a(sum, ck->film, film_bytes(ck));

    il_atomic_file af;
    il_status st = il_atomic_open(&af, path, err);
    if (st != IL_OK)
        return st;
    bool ok = fwrite(head, sizeof head, 1, af.f) == 1 &&
              (ck->tiles == 0 || fwrite(ck->done, ck->tiles, 1, af.f) == 1) &&
              fwrite(ck->film, film_bytes(ck), 1, af.f) == 1 && fwrite(&sum, sizeof sum, 1, af.f) == 1;
    if (!ok)
        st = il_fail(err, IL_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    st = il_atomic_close(&af, st, err);
    if (st == IL_OK)
        sync_folder(path);
    return st;
}

il_status cli_checkpoint_read(const char *path, cli_checkpoint *ck, bool *found, il_error *err)
{
    *found = false;
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (errno == ENOENT)
            return IL_OK;
        return il_fail(err, IL_ERR_IO, "checkpoint %s: cannot open: %s", path, strerror(errno));
    }
    *found = true;
    size_t want = HEADER_BYTES + ck->tiles + film_bytes(ck) + 8;
    unsigned char *buf = malloc(want + 1);
    if (!buf) {
        fclose(f);
        return il_fail(err, IL_ERR_MEMORY, "checkpoint %s: out of memory", path);
    }
    size_t got = fread(buf, 1, want + 1, f);
    fclose(f);
    il_status st = IL_OK;
    uint32_t head[6];
    uint64_t fingerprint, sum;
    if (got < HEADER_BYTES || memcmp(buf, MAGIC, 8) != 0) {
        st = il_fail(err, IL_ERR_INVALID, "checkpoint %s: not an illum checkpoint file", path);
        goto done;
    }
    memcpy(head, buf + 8, sizeof head);
    memcpy(&fingerprint, buf + 8 + sizeof head, 8);
    if (head[0] != VERSION || head[1] != BYTE_ORDER_MARK) {
        st = il_fail(err, IL_ERR_INVALID,
                     "checkpoint %s: written by another version of illum or another kind of "
                     "machine; delete it to render from the start",
                     path);
        goto done;
    }
    if (fingerprint != ck->fingerprint || head[2] != ck->width || head[3] != ck->height ||
        head[4] != ck->tiles) {
        st = il_fail(err, IL_ERR_INVALID,
                     "checkpoint %s: written by another render (the scene, a file it names or "
                     "an option that changes pixels differs); delete it to render from the "
                     "start, or name another file with --checkpoint",
                     path);
        goto done;
    }
    memcpy(&sum, buf + want - 8, 8);
    if (got != want || cli_fnv1a(CLI_FNV_OFFSET, buf, want - 8) != sum) {
        st = il_fail(err, IL_ERR_INVALID,
                     "checkpoint %s: damaged (cut short or changed); delete it to render from "
                     "the start",
                     path);
        goto done;
    }
    memcpy(ck->done, buf + HEADER_BYTES, ck->tiles);
    memcpy(ck->film, buf + HEADER_BYTES + ck->tiles, film_bytes(ck));
    /* The checksum finds damage, not a file made to pass it: what a render
     * could not have written is refused too (done 0 or 1; sums finite, the
     * weights not negative). */
    for (uint32_t t = 0; t < ck->tiles && st == IL_OK; t++)
        if (ck->done[t] > 1)
            st = il_fail(err, IL_ERR_INVALID, "checkpoint %s: tile %u is marked %u (0 or 1 expected); "
                         "delete it to render from the start", path, t, ck->done[t]);
    for (size_t k = 0; k < (size_t)ck->width * ck->height * 4 && st == IL_OK; k++)
        if (!isfinite(ck->film[k]) || (k % 4 == 3 && ck->film[k] < 0.0))
            st = il_fail(err, IL_ERR_INVALID, "checkpoint %s: pixel %zu holds %g, which no render "
                         "writes; delete it to render from the start", path, k / 4, ck->film[k]);
done:
    free(buf);
    return st;
}

/* The checkpoint's fingerprint: the command line without the options that
 * do not change the film (outputs, checkpointing, reporting, threads: the
 * film is the same for every thread count), the contents of every argument
 * that names a file (the scene, a camera file, an environment map), and
 * il_render's options as the scene's render block completed them. */
uint64_t cli_checkpoint_fingerprint(int argc, char **argv, const il_render_desc *desc, uint32_t width,
                                    uint32_t height)
{
    static const char *const with_value[] = {"-o", "--output", "--write-every", "--checkpoint",
                                             "--checkpoint-every", "--stats", "--threads",
                                             "--exposure"};
    static const char *const flags[] = {"-q", "--quiet", "--exr-float"};
    uint64_t fp = CLI_FNV_OFFSET;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool skip = false;
        for (size_t k = 0; k < sizeof with_value / sizeof *with_value; k++)
            if (!strcmp(a, with_value[k])) {
                skip = true;
                i++;
            }
        for (size_t k = 0; k < sizeof flags / sizeof *flags; k++)
            skip = skip || !strcmp(a, flags[k]);
        if (skip)
            continue;
        fp = cli_fnv1a(fp, a, strlen(a) + 1);
        struct stat sb;
        if (stat(a, &sb) == 0 && S_ISREG(sb.st_mode) && !cli_fnv1a_file(&fp, a))
            fp = cli_fnv1a(fp, "unreadable", 10);
    }
    uint32_t v[7] = {width, height, desc->spp ? desc->spp : 16u, desc->max_depth ? desc->max_depth : 8u,
                     (uint32_t)desc->method, (uint32_t)desc->sampler, (uint32_t)desc->filter};
    fp = cli_fnv1a(fp, v, sizeof v);
    return cli_fnv1a(fp, &desc->seed, sizeof desc->seed);
}
