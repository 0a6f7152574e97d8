#include "core/atomic_file.h"

#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

/* The temporary name is the output's path, ".tmp-" and the six characters
 * that mkstemp(3) requires to be 'X' and replaces with a unique suffix.
 * Where that name is too long for the file system (an output name of
 * 245 or more characters) it is ".illum-tmp-" and the six in the output's
 * folder. */
#define IL_TMP_PREFIX ".tmp-"
#define IL_TMP_SHORT ".illum-tmp-"
#define IL_MKSTEMP_CHARS 6

/* Fills tmp (room for strlen(path) + strlen(IL_TMP_SHORT) + 8) with the
 * temporary name's template: path + IL_TMP_PREFIX, or with `in_folder`,
 * path's folder + IL_TMP_SHORT; then the six 'X'. */
static void tmp_template(char *tmp, const char *path, bool in_folder)
{
    size_t len = strlen(path);
    const char *suffix = IL_TMP_PREFIX;
    if (in_folder) {
        const char *slash = strrchr(path, '/');
        len = slash ? (size_t)(slash - path) + 1 : 0;
        suffix = IL_TMP_SHORT;
    }
    memcpy(tmp, path, len);
    memcpy(tmp + len, suffix, strlen(suffix));
    len += strlen(suffix);
    memset(tmp + len, 'X', IL_MKSTEMP_CHARS);
    tmp[len + IL_MKSTEMP_CHARS] = '\0';
}

il_status il_atomic_open(il_atomic_file *af, const char *path, il_error *err)
{
    af->f = NULL;
    af->path = path;
    af->tmp = il_malloc(strlen(path) + sizeof IL_TMP_SHORT + IL_MKSTEMP_CHARS + 1, err);
    if (!af->tmp)
        return IL_ERR_MEMORY;
    tmp_template(af->tmp, path, false);
    int fd = mkstemp(af->tmp);
    if (fd < 0 && errno == ENAMETOOLONG) {
        tmp_template(af->tmp, path, true);
        fd = mkstemp(af->tmp);
    }
    if (fd < 0) {
        il_status st = il_fail(err, IL_ERR_IO, "%s: cannot create file: %s", path, strerror(errno));
        free(af->tmp);
        af->tmp = NULL;
        return st;
    }
    /* mkstemp creates the file 0600; outputs are ordinary files. */
    (void)fchmod(fd, 0644);
    af->f = fdopen(fd, "wb");
    if (!af->f) {
        il_status st = il_fail(err, IL_ERR_IO, "%s: cannot open for writing: %s", path,
                               strerror(errno));
        close(fd);
        unlink(af->tmp);
        free(af->tmp);
        af->tmp = NULL;
        return st;
    }
    return IL_OK;
}

il_status il_atomic_close(il_atomic_file *af, il_status st, il_error *err)
{
    if (st == IL_OK && (fflush(af->f) != 0 || ferror(af->f) || fsync(fileno(af->f)) != 0))
        st = il_fail(err, IL_ERR_IO, "%s: cannot write: %s", af->path, strerror(errno));
    if (fclose(af->f) != 0 && st == IL_OK)
        st = il_fail(err, IL_ERR_IO, "%s: cannot write: %s", af->path, strerror(errno));
    if (st == IL_OK && rename(af->tmp, af->path) != 0)
        st = il_fail(err, IL_ERR_IO, "%s: cannot rename the temporary file into place: %s",
                     af->path, strerror(errno));
    if (st != IL_OK)
        unlink(af->tmp);
    free(af->tmp);
    af->tmp = NULL;
    af->f = NULL;
    return st;
}

il_status il_atomic_check(const char *path, il_error *err)
{
    if (!path[0])
        return il_fail(err, IL_ERR_IO, "an output file name is empty");
    /* The rename at the end would fail, after all the work. */
    const char *slash = strrchr(path, '/');
    size_t name = strlen(slash ? slash + 1 : path);
    if (name > NAME_MAX)
        return il_fail(err, IL_ERR_IO, "%s: the file name is too long (%zu characters; at most %d)", path,
                       name, NAME_MAX);
    struct stat sb;
    bool exists = stat(path, &sb) == 0;
    if (exists && S_ISDIR(sb.st_mode))
        return il_fail(err, IL_ERR_IO, "%s: is a folder, not a file", path);
    /* The output replaces the file by renaming over it, which would replace
     * a device such as /dev/null, or a pipe, by a plain file. */
    if (exists && !S_ISREG(sb.st_mode))
        return il_fail(err, IL_ERR_IO, "%s: is a device or a pipe, not a file (outputs are written as "
                       "files)", path);
    il_atomic_file af;
    il_status st = il_atomic_open(&af, path, err);
    if (st != IL_OK)
        return st;
    il_error ignored = {0};
    il_atomic_close(&af, IL_ERR_IO, &ignored); /* removes the temporary file */
    return IL_OK;
}
