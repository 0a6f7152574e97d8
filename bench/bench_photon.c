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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "illum/illum.h"

static void usage(void)
{
    fprintf(stderr, "usage: bench_photon SCENE [--photons N] [--lookup kdtree|grid] [--k N] "
                    "[--radius X] [--final-gather N] [--threads T] [--width W] [--height H] "
                    "[--spp N]\n");
}

int main(int argc, char **argv)
{
    const char *scene_name = NULL;
    il_photon_desc pd = {0};
    il_render_desc rd = {.method = IL_METHOD_PHOTON, .spp = 1, .photon = &pd};
    uint32_t w = 512, h = 512;
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
        if (!strcmp(a, "--photons"))
            pd.photons = strtoull(v, NULL, 10);
        else if (!strcmp(a, "--lookup"))
            pd.lookup = !strcmp(v, "grid") ? IL_PHOTON_GRID : IL_PHOTON_KDTREE;
        else if (!strcmp(a, "--k"))
            pd.k = (uint32_t)atoi(v);
        else if (!strcmp(a, "--radius"))
            pd.max_radius = (float)atof(v);
        else if (!strcmp(a, "--final-gather"))
            pd.final_gather = (uint32_t)atoi(v);
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
    il_render_stats st;
    if (il_scene_load(scene_name, NULL, &scene, &err) != IL_OK ||
        il_scene_commit(scene, &err) != IL_OK || il_film_create(w, h, &film, &err) != IL_OK ||
        il_render(scene, film, &rd, &st, &err) != IL_OK) {
        fprintf(stderr, "bench_photon: %s\n", err.message);
        il_film_release(film);
        il_scene_release(scene);
        return 1;
    }
    const il_photon_stats *p = &st.photon;
    const char *base = strrchr(scene_name, '/');
    base = base ? base + 1 : scene_name;
    printf("%-20s %7s %9s %9s %9s %8s %9s %8s %5s %8s %8s\n", "scene", "threads", "emitted",
           "global", "caustic", "trace_s", "Mphot/s", "build_s", "B/ph", "maps_MB", "frame_s");
    printf("%-20.20s %7d %9llu %9llu %9llu %8.3f %9.3f %8.3f %5u %8.1f %8.3f\n", base, rd.threads,
           (unsigned long long)p->emitted, (unsigned long long)p->stored_global,
           (unsigned long long)p->stored_caustic, p->seconds_trace,
           p->seconds_trace > 0.0 ? (double)p->emitted / p->seconds_trace * 1e-6 : 0.0,
           p->seconds_build, p->bytes_per_photon, (double)p->map_bytes / (1 << 20),
           p->seconds_render);
    il_film_release(film);
    il_scene_release(scene);
    return 0;
}
