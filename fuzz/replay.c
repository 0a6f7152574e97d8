/* Replays a fuzz corpus through the .hdr fuzz target without libFuzzer: the
 * ctest unit/test_hdr_corpus (fuzz/README.md).  Usage: replay DIR...
 *
 * Every file goes through LLVMFuzzerTestOneInput (which aborts when the
 * reader breaks its contract).  The file name then says what must happen:
 *   ok-*           reads without error;
 *   ok-pattern-*   ... and decodes to exactly the same image as every other
 *                  ok-pattern-* file (one pattern in every orientation and
 *                  encoding: fuzz/make_corpus.py);
 *   bad-*          fails with IL_ERR_FORMAT and a message naming the file;
 *   anything else  (inputs the fuzzer found) only must not crash. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static unsigned char *load(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0;
    unsigned char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n, f)) > 0;) {
        n += got;
        if (n == cap) {
            unsigned char *bigger = realloc(buf, cap *= 2);
            if (!bigger)
                free(buf);
            buf = bigger;
        }
    }
    fclose(f);
    *size = n;
    return buf;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(int argc, char **argv)
{
    int files = 0, failures = 0, patterns = 0;
    il_image pattern = {0};
    char first[2048] = "";
    for (int d = 1; d < argc; d++) {
        DIR *dir = opendir(argv[d]);
        if (!dir) {
            fprintf(stderr, "replay: cannot open directory %s\n", argv[d]);
            return 1;
        }
        char **names = NULL;
        size_t count = 0;
        for (struct dirent *e; (e = readdir(dir));) {
            if (e->d_name[0] == '.')
                continue;
            char **more = realloc(names, (count + 1) * sizeof *names);
            if (!more)
                return 1;
            names = more;
            names[count++] = strdup(e->d_name);
        }
        closedir(dir);
        qsort(names, count, sizeof *names, compare_names);
        for (size_t i = 0; i < count; i++) {
            char path[2048];
            snprintf(path, sizeof path, "%s/%s", argv[d], names[i]);
            size_t size = 0;
            unsigned char *data = load(path, &size);
            if (!data) {
                fprintf(stderr, "replay: cannot read %s\n", path);
                failures++;
                continue;
            }
            LLVMFuzzerTestOneInput(data, size); /* aborts on a broken contract */
            files++;
            il_image im = {0};
            il_error err = {0};
            il_status st = il_hdr_read(data, size, path, &im, &err);
            const char *name = names[i];
            if (strncmp(name, "ok-", 3) == 0 && st != IL_OK) {
                fprintf(stderr, "FAIL %s: should read, got: %s\n", path, err.message);
                failures++;
            } else if (strncmp(name, "bad-", 4) == 0 &&
                       (st != IL_ERR_FORMAT || !strstr(err.message, path))) {
                fprintf(stderr, "FAIL %s: should be a format error naming it (status %d)\n",
                        path, (int)st);
                failures++;
            } else if (st == IL_OK && strncmp(name, "ok-pattern-", 11) == 0) {
                patterns++;
                if (!pattern.rgb) {
                    pattern = im;
                    im = (il_image){0};
                    snprintf(first, sizeof first, "%s", path);
                } else if (im.width != pattern.width || im.height != pattern.height ||
                           memcmp(im.rgb, pattern.rgb,
                                  (size_t)im.width * im.height * 3 * sizeof(float)) != 0) {
                    fprintf(stderr, "FAIL %s: decodes differently from %s\n", path, first);
                    failures++;
                }
            }
            if (st != IL_OK)
                printf("%-40s %s\n", name, err.message);
            else
                printf("%-40s ok %ux%u\n", name, im.width ? im.width : pattern.width,
                       im.height ? im.height : pattern.height);
            il_image_free(&im);
            free(data);
            free(names[i]);
        }
        free(names);
    }
    il_image_free(&pattern);
    printf("%d files (%d pattern files agree), %d failed\n", files, patterns, failures);
    return failures || files == 0 ? 1 : 0;
}
