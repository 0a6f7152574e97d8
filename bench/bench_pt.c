/* Path tracer samples per second.
 *
 *   bench_pt [--time SECONDS] [--width W] [--height H] [SCENE ...]
 *
 * Renders each scene (default: cornell, atrium) at 512x512, max depth 8, for
 * about SECONDS (default 10) with 1 and then 2 threads, and prints samples
 * (camera paths) per second and rays per second.  It prints figures and never
 * judges them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "illum/illum.h"

int main(int argc, char **argv)
{
    double seconds = 10.0;
    uint32_t w = 512, h = 512;
    const char *scenes[32];
    int num_scenes = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--time") && i + 1 < argc)
            seconds = atof(argv[++i]);
        else if (!strcmp(argv[i], "--width") && i + 1 < argc)
            w = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--height") && i + 1 < argc)
            h = (uint32_t)atoi(argv[++i]);
        else if (num_scenes < 32)
            scenes[num_scenes++] = argv[i];
    }
    if (num_scenes == 0) {
        scenes[num_scenes++] = "cornell";
        scenes[num_scenes++] = "atrium";
    }
    printf("%-60s %7s %5s %12s %12s\n", "scene", "threads", "spp", "Msamples/s", "Mrays/s");
    for (int s = 0; s < num_scenes; s++) {
        il_error err = {0};
        il_scene *scene = NULL;
        if (il_scene_load(scenes[s], NULL, &scene, &err) != IL_OK ||
            il_scene_commit(scene, &err) != IL_OK) {
            fprintf(stderr, "bench_pt: %s\n", err.message);
            il_scene_release(scene);
            return 1;
        }
        il_film *film = NULL;
        if (il_film_create(w, h, &film, &err) != IL_OK) {
            fprintf(stderr, "bench_pt: %s\n", err.message);
            return 1;
        }
        for (int threads = 1; threads <= 2; threads++) {
            il_render_desc rd = {.spp = 1u << 20, .time_limit = seconds, .max_depth = 8, .threads = threads};
            il_render_stats st;
            if (il_render(scene, film, &rd, &st, &err) != IL_OK) {
                fprintf(stderr, "bench_pt: %s\n", err.message);
                return 1;
            }
            printf("%-60s %7d %5u %12.3f %12.2f\n", scenes[s], threads, st.spp,
                   (double)w * h * st.spp / st.seconds * 1e-6, st.rays / st.seconds * 1e-6);
            fflush(stdout);
        }
        il_film_release(film);
        il_scene_release(scene);
    }
    return 0;
}
