/* OFF: the header's counts checked against the file's size before assimp
 * reads it.
 *
 * assimp 5.2 reserves room for an OFF file's vertices and faces from its
 * header before it reads them: "OFF\n99999999 99999999 0" in a 30-byte
 * file made it take 2.9 GB and 15 s before failing.  In the text form
 * (Princeton Shape Benchmark's description of OFF) a vertex is at least
 * "0 0 0\n", 6 bytes, and a face at least "1 0\n", 4; a count that the
 * rest of the file cannot hold at that size is refused.  A header this
 * does not understand (a binary OFF, counts that are not numbers) is left
 * to assimp, which reports it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "scene/loader.h"

/* Past blanks, newlines and # comments. */
static const char *skip_space(const char *p, const char *end)
{
    while (p < end) {
        if (*p == '#')
            while (p < end && *p != '\n')
                p++;
        else if (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
            p++;
        else
            break;
    }
    return p;
}

/* A whole number at p (past space), advancing p; false if there is none. */
static bool read_count(const char **p, const char *end, uint64_t *v)
{
    *p = skip_space(*p, end);
    if (*p >= end || **p < '0' || **p > '9')
        return false;
    *v = 0;
    for (; *p < end && **p >= '0' && **p <= '9'; (*p)++)
        *v = *v > (UINT64_MAX - 9) / 10 ? UINT64_MAX : 10 * *v + (uint64_t)(**p - '0');
    return true;
}

il_status il_off_check(const char *path, il_error *err)
{
    char *text;
    size_t n;
    il_status s = il_load_read_file(path, &text, &n, err);
    if (s != IL_OK)
        return s;
    const char *end = text + n, *p = skip_space(text, end);
    /* The keyword: OFF, with optional prefixes (ST, C, N, 4, n) before it. */
    const char *word = p;
    while (p < end && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n')
        p++;
    size_t len = (size_t)(p - word);
    uint64_t nv, nf;
    const char *next = skip_space(p, end);
    bool binary = end - next >= 6 && !memcmp(next, "BINARY", 6);
    if (len >= 3 && !memcmp(p - 3, "OFF", 3) && !binary && read_count(&p, end, &nv) &&
        read_count(&p, end, &nf)) {
        uint64_t room = (uint64_t)(end - p);
        if (nv > room / 6 || nf > room / 4 || nv * 6 + nf * 4 > room)
            s = il_fail(err, IL_ERR_FORMAT, "%s: %llu vertices and %llu faces, more than the %llu bytes "
                        "left in the file can hold: the file is corrupt or truncated", path,
                        (unsigned long long)nv, (unsigned long long)nf, (unsigned long long)room);
    }
    free(text);
    return s;
}
