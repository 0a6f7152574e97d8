/* Hierarchical radiosity: sizes, time per phase and memory.
 *
 *   bench_hr SCENE [--bf-eps X] [--area-eps X] [--energy-eps X] [--vis-rays N]
 *            [--max-iterations N] [--threads T] [--width W] [--height H] [--spp N]
 *
 * Solves one configuration (default: the default epsilons) and renders it
 * (default 256x256, 4 spp), then prints one line: patches, elements, leaves,
 * links, iterations, visibility rays, the seconds of setup, refinement
 * (with visibility), gather + push-pull, averaging and the render, the
 * solver's pool bytes and the peak resident memory of the process.  One
 * configuration per run, so the peak belongs to it (bench/hr.sh runs the
 * matrix).  It prints figures and never judges them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "illum/illum.h"

static void usage(void)
{
    fprintf(stderr, "usage: bench_hr SCENE [--bf-eps X] [--area-eps X] [--energy-eps X] "
                    "[--vis-rays N] [--max-iterations N] [--threads T] [--width W] [--height H] "
                    "[--spp N]\n");
}

int main(int argc, char **argv)
{
    const char *scene_name = NULL;
    il_hr_desc hr = {0};
    il_render_desc rd = {.method = IL_METHOD_HR, .spp = 4, .hr = &hr};
    uint32_t w = 256, h = 256;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (a[0] != '-') {
            scene_name = a;
            continue;
        }
        if (!v) {
            usage();
            return 2;
        }
        i++;
        if (!strcmp(a, "--bf-eps"))
            hr.bf_eps = (float)atof(v);
        else if (!strcmp(a, "--area-eps"))
            hr.area_eps = (float)atof(v);
        else if (!strcmp(a, "--energy-eps"))
            hr.energy_eps = (float)atof(v);
        else if (!strcmp(a, "--vis-rays"))
            hr.vis_rays = (uint32_t)atoi(v);
        else if (!strcmp(a, "--max-iterations"))
            hr.max_iterations = (uint32_t)atoi(v);
        else if (!strcmp(a, "--threads"))
            rd.threads = atoi(v);
        else if (!strcmp(a, "--width"))
            w = (uint32_t)atoi(v);
        else if (!strcmp(a, "--height"))
            h = (uint32_t)atoi(v);
        else if (!strcmp(a, "--spp"))
            rd.spp = (uint32_t)atoi(v);
        else {
            usage();
            return 2;
        }
    }
    if (!scene_name) {
        usage();
        return 2;
    }

    il_error err = {0};
    il_scene *scene = NULL;
    il_film *film = NULL;
    if (il_scene_load(scene_name, NULL, &scene, &err) != IL_OK ||
        il_scene_commit(scene, &err) != IL_OK || il_film_create(w, h, &film, &err) != IL_OK) {
        fprintf(stderr, "bench_hr: %s\n", err.message);
        il_scene_release(scene);
        return 1;
    }
    il_render_stats st;
    if (il_render(scene, film, &rd, &st, &err) != IL_OK) {
        fprintf(stderr, "bench_hr: %s\n", err.message);
        il_film_release(film);
        il_scene_release(scene);
        return 1;
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    const il_hr_stats *r = &st.hr;
    const double solve = r->seconds_setup + r->seconds_refine + r->seconds_gather;
    printf("%-12s %7s %7s %9s %9s %10s %5s %11s %8s %8s %8s %8s %8s %8s %9s %8s\n", "scene",
           "threads", "patches", "elements", "leaves", "links", "iters", "vis_rays", "setup_s",
           "refine_s", "gather_s", "avg_s", "render_s", "solve_s", "pools_MB", "peak_MB");
    printf("%-12s %7d %7u %9llu %9llu %10llu %5u %11llu %8.4f %8.4f %8.4f %8.4f %8.4f %8.4f %9.1f "
           "%8.1f\n",
           scene_name, rd.threads, r->patches, (unsigned long long)r->elements,
           (unsigned long long)r->leaves, (unsigned long long)r->links, r->iterations,
           (unsigned long long)r->visibility_rays, r->seconds_setup, r->seconds_refine,
           r->seconds_gather, r->seconds_average, r->seconds_render, solve,
           (double)r->peak_bytes / (1 << 20), (double)ru.ru_maxrss / 1024.0);
    il_film_release(film);
    il_scene_release(scene);
    return 0;
}
