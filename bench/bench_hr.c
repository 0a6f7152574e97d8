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
#include <sys/resource.h>

#include "bench_common.h"

static bool hr_option(const char *a, const char *v, void *user)
{
    il_hr_desc *hr = user;
    if (!strcmp(a, "--bf-eps"))
        hr->bf_eps = (float)atof(v);
    else if (!strcmp(a, "--area-eps"))
        hr->area_eps = (float)atof(v);
    else if (!strcmp(a, "--energy-eps"))
        hr->energy_eps = (float)atof(v);
    else if (!strcmp(a, "--vis-rays"))
        hr->vis_rays = (uint32_t)atoi(v);
    else if (!strcmp(a, "--max-iterations"))
        hr->max_iterations = (uint32_t)atoi(v);
    else
        return false;
    return true;
}

int main(int argc, char **argv)
{
    il_hr_desc hr = {0};
    bench_run b = {.prog = "bench_hr",
                   .usage = "bench_hr SCENE [--bf-eps X] [--area-eps X] [--energy-eps X] "
                            "[--vis-rays N] [--max-iterations N] [--threads T] [--width W] "
                            "[--height H] [--spp N]",
                   .width = 256,
                   .height = 256,
                   .rd = {.method = IL_METHOD_HR, .spp = 4, .hr = &hr}};
    if (!bench_parse(argc, argv, &b, hr_option, &hr))
        return 2;
    if (!bench_render(&b)) {
        bench_release(&b);
        return 1;
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    const il_hr_stats *r = &b.stats.hr;
    const double solve = r->seconds_setup + r->seconds_refine + r->seconds_gather;
    printf("%-12s %7s %7s %9s %9s %10s %5s %11s %8s %8s %8s %8s %8s %8s %9s %8s\n", "scene",
           "threads", "patches", "elements", "leaves", "links", "iters", "vis_rays", "setup_s",
           "refine_s", "gather_s", "avg_s", "render_s", "solve_s", "pools_MB", "peak_MB");
    printf("%-12s %7d %7u %9llu %9llu %10llu %5u %11llu %8.4f %8.4f %8.4f %8.4f %8.4f %8.4f %9.1f "
           "%8.1f\n",
           b.scene_name, b.rd.threads, r->patches, (unsigned long long)r->elements,
           (unsigned long long)r->leaves, (unsigned long long)r->links, r->iterations,
           (unsigned long long)r->visibility_rays, r->seconds_setup, r->seconds_refine,
           r->seconds_gather, r->seconds_average, r->seconds_render, solve,
           (double)r->peak_bytes / (1 << 20), (double)ru.ru_maxrss / 1024.0);
    bench_release(&b);
    return 0;
}
