/* What the method benchmarks (bench_radiosity, bench_hr, bench_photon)
 * share: the scene argument and the render options every one takes
 * (--threads, --width, --height, --spp), and loading, committing and
 * rendering with one error line. */
#ifndef IL_BENCH_COMMON_H
#define IL_BENCH_COMMON_H

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "illum/illum.h"

typedef struct bench_run {
    const char *prog;          /* for messages */
    const char *usage;         /* printed on a bad command line */
    const char *scene_name;
    uint32_t width, height;
    il_render_desc rd;
    il_scene *scene;
    il_film *film;
    il_render_stats stats;
} bench_run;

/* A method's own option: false when `name` is not one of them. */
typedef bool (*bench_option_fn)(const char *name, const char *value, void *user);

/* Reads argv into b (and the method's options through fn); false after
 * printing the usage when the command line is wrong. */
static inline bool bench_parse(int argc, char **argv, bench_run *b, bench_option_fn fn, void *user)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (a[0] != '-') {
            b->scene_name = a;
            continue;
        }
        i++;
        bool ok = true;
        if (!v)
            ok = false;
        else if (!strcmp(a, "--threads"))
            b->rd.threads = atoi(v);
        else if (!strcmp(a, "--width"))
            b->width = (uint32_t)atoi(v);
        else if (!strcmp(a, "--height"))
            b->height = (uint32_t)atoi(v);
        else if (!strcmp(a, "--spp"))
            b->rd.spp = (uint32_t)atoi(v);
        else
            ok = fn(a, v, user);
        if (!ok) {
            fprintf(stderr, "usage: %s\n", b->usage);
            return false;
        }
    }
    if (!b->scene_name)
        fprintf(stderr, "usage: %s\n", b->usage);
    return b->scene_name != NULL;
}

/* Loads and commits the scene, makes the film and renders with b->rd;
 * false after printing "PROG: message". */
static inline bool bench_render(bench_run *b)
{
    il_error err = {0};
    if (il_scene_load(b->scene_name, NULL, &b->scene, &err) != IL_OK ||
        il_scene_commit(b->scene, &err) != IL_OK ||
        il_film_create(b->width, b->height, &b->film, &err) != IL_OK ||
        il_render(b->scene, b->film, &b->rd, &b->stats, &err) != IL_OK) {
        fprintf(stderr, "%s: %s\n", b->prog, err.message);
        return false;
    }
    return true;
}

static inline void bench_release(bench_run *b)
{
    il_film_release(b->film);
    il_scene_release(b->scene);
}

#endif
