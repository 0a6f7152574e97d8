/* The shared path-tracing kernel (src/kernel/kernel_path.h, what the CUDA
 * backend runs per pixel) on the CPU: samples per second of ilk_path_sample
 * on one thread, next to il_render's path tracer on one thread, at the same
 * size, depth and sample count.  A baseline for the GPU figures
 * (docs/cuda.md).  Usage: bench_kernel [SCENE] [--width W] [--height H]
 * [--spp N] [--max-depth D]; default cornell, 128x96, 4 spp, depth 8. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "illum/illum.h"
#include "kernel/kernel_scene.h"
#include "scene/scene.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    const char *name = "cornell";
    uint32_t w = 128, h = 96, spp = 4, depth = 8;
    for (int i = 1; i < argc; i++) {
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        uint32_t *dst = !strcmp(argv[i], "--width") ? &w : !strcmp(argv[i], "--height") ? &h
                        : !strcmp(argv[i], "--spp") ? &spp : !strcmp(argv[i], "--max-depth") ? &depth : NULL;
        if (dst && v && atoi(v) > 0) {
            *dst = (uint32_t)atoi(v);
            i++;
        } else if (argv[i][0] != '-') {
            name = argv[i];
        } else {
            fprintf(stderr, "usage: bench_kernel [SCENE] [--width W] [--height H] [--spp N] [--max-depth D]\n");
            return 2;
        }
    }
    il_error err = {0};
    il_scene *s = NULL;
    if (il_scene_load(name, NULL, &s, &err) != IL_OK || il_scene_commit(s, &err) != IL_OK) {
        fprintf(stderr, "bench_kernel: %s\n", err.message);
        return 1;
    }
    il_kscene ks;
    if (il_kscene_build_pt(s, w, h, depth, 1, &ks, &err) != IL_OK) {
        fprintf(stderr, "bench_kernel: %s\n", err.message);
        il_scene_release(s);
        return 1;
    }
    double t0 = now(), sum = 0.0;
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            for (uint32_t i = 0; i < spp; i++) {
                uint32_t rays = 0;
                ilk_vec3 L = ilk_path_sample(&ks.view, x, y, i, &rays);
                sum += (double)L.x + L.y + L.z;
            }
    double t_kernel = now() - t0;
    il_kscene_free(&ks);

    il_film *film = NULL;
    il_render_desc rd = {.method = IL_METHOD_PT, .spp = spp, .max_depth = depth, .seed = 1, .threads = 1};
    double t_pt = 0.0;
    if (il_film_create(w, h, &film, &err) == IL_OK) {
        t0 = now();
        if (il_render(s, film, &rd, NULL, &err) != IL_OK)
            fprintf(stderr, "bench_kernel: %s\n", err.message);
        t_pt = now() - t0;
        il_film_release(film);
    }
    double n = (double)w * h * spp;
    printf("%s %ux%u, %u spp, max depth %u, one thread: kernel %.3g samples/s (mean %.4g), "
           "il_render pt %.3g samples/s\n", name, w, h, spp, depth, n / t_kernel, sum / n,
           t_pt > 0.0 ? n / t_pt : 0.0);
    il_scene_release(s);
    return 0;
}
