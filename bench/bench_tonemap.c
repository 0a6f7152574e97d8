/* Tone mapping and bloom speed (issue 6): bloom, il_tonemap per operator
 * (with auto exposure, with and without bloom) and a PNG write through the
 * operator, on random HDR images of 512x512 and 1920x1080 (values u^3 * 8,
 * u uniform: about 40% of the pixels above luminance 1).  Prints the best
 * wall and CPU time of REPS runs.
 *
 * Usage: bench_tonemap [REPS] [OUT_DIR]   (defaults 7 and /tmp) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "illum/illum.h"
#include "image/bloom.h"

static double clock_seconds(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct timing {
    double wall, cpu;
} timing;

static void timing_start(timing *t)
{
    t->wall = clock_seconds(CLOCK_MONOTONIC);
    t->cpu = clock_seconds(CLOCK_PROCESS_CPUTIME_ID);
}

/* Keeps the best (smallest) of the runs in *best. */
static void timing_stop(const timing *t, timing *best)
{
    double wall = clock_seconds(CLOCK_MONOTONIC) - t->wall;
    double cpu = clock_seconds(CLOCK_PROCESS_CPUTIME_ID) - t->cpu;
    if (wall < best->wall)
        best->wall = wall;
    if (cpu < best->cpu)
        best->cpu = cpu;
}

static void report(const char *label, const timing *best)
{
    printf("  %-46s wall %8.1f ms  cpu %8.1f ms\n", label, best->wall * 1e3, best->cpu * 1e3);
}

static void time_tonemap(const il_image *img, const il_tonemap_desc *d, int reps, const char *label)
{
    timing best = {1e9, 1e9}, t;
    for (int r = 0; r < reps; r++) {
        il_error err = {0};
        il_image out = {0};
        timing_start(&t);
        if (il_tonemap(img, d, &out, &err) != IL_OK)
            fprintf(stderr, "bench_tonemap: %s\n", err.message);
        timing_stop(&t, &best);
        il_image_free(&out);
    }
    report(label, &best);
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 7;
    const char *dir = argc > 2 ? argv[2] : "/tmp";
    if (reps < 1)
        reps = 1;
    static const uint32_t sizes[2][2] = {{512, 512}, {1920, 1080}};
    static const char *const op_names[] = {"linear", "gamma", "reinhard", "filmic"};
    char png[1024];
    snprintf(png, sizeof png, "%s/bench_tonemap.png", dir);

    for (int s = 0; s < 2; s++) {
        uint32_t w = sizes[s][0], h = sizes[s][1];
        size_t n = (size_t)w * h * 3;
        il_error err = {0};
        il_image img = {0};
        if (il_image_alloc(&img, w, h, &err) != IL_OK) {
            fprintf(stderr, "bench_tonemap: %s\n", err.message);
            return 1;
        }
        srand(1);
        for (size_t i = 0; i < n; i++) {
            double u = rand() / (double)RAND_MAX;
            img.rgb[i] = (float)(u * u * u * 8.0);
        }
        float radius_px = 0.02f * hypotf((float)w, (float)h);
        printf("%ux%u (bloom radius 0.02 of the diagonal = %.1f px):\n", w, h, radius_px);

        float *copy = malloc(n * sizeof *copy);
        if (!copy)
            return 1;
        timing best = {1e9, 1e9}, t;
        for (int r = 0; r < reps; r++) {
            memcpy(copy, img.rgb, n * sizeof *copy);
            timing_start(&t);
            il_bloom_apply(copy, w, h, 0.2f, 1.0f, radius_px, &err);
            timing_stop(&t, &best);
        }
        report("bloom (strength 0.2, threshold 1)", &best);
        free(copy);

        for (int op = 0; op < 4; op++) {
            char label[96];
            il_tonemap_desc d = {.op = (il_tonemap_op)op, .auto_exposure = true};
            snprintf(label, sizeof label, "il_tonemap %s, auto exposure", op_names[op]);
            time_tonemap(&img, &d, reps, label);
            d.bloom = 0.2f;
            snprintf(label, sizeof label, "il_tonemap %s, auto exposure + bloom", op_names[op]);
            time_tonemap(&img, &d, reps, label);
        }

        il_tonemap_desc filmic = {.op = IL_TONEMAP_FILMIC, .auto_exposure = true, .bloom = 0.2f};
        il_write_desc with_op = {.tonemap = &filmic}, plain = {0};
        const il_write_desc *writes[2] = {&with_op, &plain};
        const char *labels[2] = {"PNG write, filmic + auto exposure + bloom",
                                 "PNG write, no operator (plain sRGB)"};
        for (int k = 0; k < 2; k++) {
            timing b = {1e9, 1e9};
            for (int r = 0; r < reps; r++) {
                timing_start(&t);
                if (il_image_write(&img, png, writes[k], &err) != IL_OK)
                    fprintf(stderr, "bench_tonemap: %s\n", err.message);
                timing_stop(&t, &b);
            }
            report(labels[k], &b);
        }
        remove(png);
        il_image_free(&img);
    }
    return 0;
}
