/* Radiosity: time per phase and memory.
 *
 *   bench_radiosity SCENE [--subdiv L | --patch-size M] [--form-factors auto|hemicube|raycast]
 *                   [--hemicube-res N] [--ff-samples N] [--solver shooting|jacobi|gauss-seidel]
 *                   [--tolerance X] [--ff-cache-mb N] [--threads T] [--width W] [--height H] [--spp N]
 *
 * Solves one configuration (default: converged to 0.01, form factors auto) and
 * renders it (default 256x256, 4 spp), then prints one line: patches, steps,
 * the seconds of meshing, form factors, the whole solve (form factors
 * included), the render, and the peak resident memory of the process.  One
 * configuration per run, so the peak belongs to it (bench/radiosity.sh runs
 * the matrix).  It prints figures and never judges them. */
#include <sys/resource.h>

#include "bench_common.h"

static bool radiosity_option(const char *a, const char *v, void *user)
{
    il_radiosity_desc *rad = user;
    if (!strcmp(a, "--subdiv"))
        rad->subdivisions = (uint32_t)atoi(v);
    else if (!strcmp(a, "--patch-size"))
        rad->patch_size = (float)atof(v);
    else if (!strcmp(a, "--form-factors"))
        rad->form_factors = !strcmp(v, "raycast")    ? IL_FF_RAYCAST
                            : !strcmp(v, "hemicube") ? IL_FF_HEMICUBE
                                                     : IL_FF_AUTO;
    else if (!strcmp(a, "--hemicube-res"))
        rad->hemicube_resolution = (uint32_t)atoi(v);
    else if (!strcmp(a, "--ff-samples"))
        rad->ray_samples = (uint32_t)atoi(v);
    else if (!strcmp(a, "--solver"))
        rad->solver = !strcmp(v, "jacobi")         ? IL_SOLVER_JACOBI
                      : !strcmp(v, "gauss-seidel") ? IL_SOLVER_GAUSS_SEIDEL
                                                   : IL_SOLVER_SHOOTING;
    else if (!strcmp(a, "--tolerance"))
        rad->tolerance = (float)atof(v);
    else if (!strcmp(a, "--ff-cache-mb"))
        rad->ff_cache_mb = (uint32_t)atoi(v);
    else
        return false;
    return true;
}

int main(int argc, char **argv)
{
    il_radiosity_desc rad = {0};
    bench_run b = {.prog = "bench_radiosity",
                   .usage = "bench_radiosity SCENE [--subdiv L | --patch-size M] "
                            "[--form-factors auto|hemicube|raycast] [--hemicube-res N] [--ff-samples N] "
                            "[--solver shooting|jacobi|gauss-seidel] [--tolerance X] "
                            "[--ff-cache-mb N] [--threads T] [--width W] [--height H] [--spp N]",
                   .width = 256,
                   .height = 256,
                   .rd = {.method = IL_METHOD_RADIOSITY, .spp = 4, .radiosity = &rad}};
    if (!bench_parse(argc, argv, &b, radiosity_option, &rad))
        return 2;
    if (!bench_render(&b)) {
        bench_release(&b);
        return 1;
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    const il_radiosity_stats *r = &b.stats.radiosity;
    printf("%-12s %-8s %7s %8s %6s %7s %8s %8s %8s %8s %8s %9s %9s\n", "scene", "ff", "threads",
           "patches", "steps", "unshot", "mesh_s", "ff_s", "solve_s", "render_s", "total_s",
           "cache_MB", "peak_MB");
    printf("%-12s %-8s %7d %8u %6u %7.4f %8.3f %8.3f %8.3f %8.3f %8.3f %9.1f %9.1f\n", b.scene_name,
           r->form_factors == IL_FF_RAYCAST ? "raycast" : "hemicube", b.rd.threads, r->num_patches,
           r->steps, r->unshot_fraction, r->seconds_mesh, r->seconds_form_factors, r->seconds_solve,
           r->seconds_render, r->seconds_mesh + r->seconds_solve,
           (double)r->cache_bytes / (1 << 20), (double)ru.ru_maxrss / 1024.0);
    bench_release(&b);
    return 0;
}
