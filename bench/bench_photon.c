/* Photon mapping: photons per second, map build time, memory per photon
 * and the time of a frame.
 *
 *   bench_photon SCENE [--photons N] [--lookup kdtree|grid] [--k N] [--radius X]
 *                [--final-gather N] [--threads T] [--width W] [--height H] [--spp N]
 *
 * Renders one configuration with --method photon (default 1,000,000
 * photons, 512x512, 1 spp, the global map read directly) and prints one
 * line: photons emitted and stored, the tracing time and rate, the time to
 * build both maps, the bytes per stored photon and of the maps, and the
 * camera pass (the frame: direct light, caustics, indirect from the maps).
 * It prints figures and never judges them (bench/photon.sh runs the
 * matrix of issue 5). */
#include "bench_common.h"

static bool photon_option(const char *a, const char *v, void *user)
{
    il_photon_desc *pd = user;
    if (!strcmp(a, "--photons"))
        pd->photons = strtoull(v, NULL, 10);
    else if (!strcmp(a, "--lookup"))
        pd->lookup = !strcmp(v, "grid") ? IL_PHOTON_GRID : IL_PHOTON_KDTREE;
    else if (!strcmp(a, "--k"))
        pd->k = (uint32_t)atoi(v);
    else if (!strcmp(a, "--radius"))
        pd->max_radius = (float)atof(v);
    else if (!strcmp(a, "--final-gather"))
        pd->final_gather = (uint32_t)atoi(v);
    else
        return false;
    return true;
}

int main(int argc, char **argv)
{
    il_photon_desc pd = {0};
    bench_run b = {.prog = "bench_photon",
                   .usage = "bench_photon SCENE [--photons N] [--lookup kdtree|grid] [--k N] "
                            "[--radius X] [--final-gather N] [--threads T] [--width W] "
                            "[--height H] [--spp N]",
                   .width = 512,
                   .height = 512,
                   .rd = {.method = IL_METHOD_PHOTON, .spp = 1, .photon = &pd}};
    if (!bench_parse(argc, argv, &b, photon_option, &pd))
        return 2;
    if (!bench_render(&b)) {
        bench_release(&b);
        return 1;
    }
    const il_photon_stats *p = &b.stats.photon;
    const char *base = strrchr(b.scene_name, '/');
    base = base ? base + 1 : b.scene_name;
    printf("%-20s %7s %9s %9s %9s %8s %9s %8s %5s %8s %8s\n", "scene", "threads", "emitted",
           "global", "caustic", "trace_s", "Mphot/s", "build_s", "B/ph", "maps_MB", "frame_s");
    printf("%-20.20s %7d %9llu %9llu %9llu %8.3f %9.3f %8.3f %5u %8.1f %8.3f\n", base, b.rd.threads,
           (unsigned long long)p->emitted, (unsigned long long)p->stored_global,
           (unsigned long long)p->stored_caustic, p->seconds_trace,
           p->seconds_trace > 0.0 ? (double)p->emitted / p->seconds_trace * 1e-6 : 0.0,
           p->seconds_build, p->bytes_per_photon, (double)p->map_bytes / (1 << 20),
           p->seconds_render);
    bench_release(&b);
    return 0;
}
