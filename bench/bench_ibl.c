/* The many-light environment renderer (--method ibl): time of a frame, and
 * the error of the four light sets at equal time.
 *
 *   bench_ibl SCENE --env MAP.hdr [--lights N] [--selection S] [--shadows rays|maps|none]
 *             [--equal-time SECONDS] [--reference-lights N] [--threads T]
 *             [--width W] [--height H] [--spp N] [--out IMAGE]
 *
 * Without --equal-time: renders N lights (default 1480) once and prints the
 * wall and CPU seconds, lights, shadow rays and their rate.
 *
 * With --equal-time S: renders a reference with --reference-lights lights
 * (default 32768, importance + Sobol, the same camera samples, on every
 * core), then each
 * of the four light sets (random, sobol, importance, importance-sobol) for
 * S seconds (lights added in batches of 16 until the time is up), and
 * prints for each the lights it reached and its RMSE and relative MSE
 * against the reference.  The camera samples (seed 0) are the same in
 * every render, so the error is the light set's alone.
 *
 * The scene gets its environment here (the scene files have none): MAP as
 * a lat-long map.  It prints figures and never judges them (bench/ibl.sh
 * runs the matrix of issue 6). */
#include <sys/resource.h>
#include <time.h>

#include "bench_common.h"

typedef struct ibl_bench {
    il_ibl_desc ibl;
    const char *env;
    const char *out;
    double equal_time;
    uint32_t reference_lights;
} ibl_bench;

static bool ibl_option(const char *a, const char *v, void *user)
{
    ibl_bench *o = user;
    if (!strcmp(a, "--env"))
        o->env = v;
    else if (!strcmp(a, "--out"))
        o->out = v;
    else if (!strcmp(a, "--lights"))
        o->ibl.lights = (uint32_t)atoi(v);
    else if (!strcmp(a, "--batch"))
        o->ibl.batch = (uint32_t)atoi(v);
    else if (!strcmp(a, "--equal-time"))
        o->equal_time = atof(v);
    else if (!strcmp(a, "--reference-lights"))
        o->reference_lights = (uint32_t)atoi(v);
    else if (!strcmp(a, "--selection")) {
        if (!strcmp(v, "importance-sobol"))
            o->ibl.selection = IL_IBL_IMPORTANCE_SOBOL;
        else if (!strcmp(v, "importance"))
            o->ibl.selection = IL_IBL_IMPORTANCE;
        else if (!strcmp(v, "sobol"))
            o->ibl.selection = IL_IBL_SOBOL;
        else if (!strcmp(v, "random"))
            o->ibl.selection = IL_IBL_RANDOM;
        else
            return false;
    } else if (!strcmp(a, "--shadows")) {
        if (!strcmp(v, "rays"))
            o->ibl.shadows = IL_IBL_SHADOW_RAYS;
        else if (!strcmp(v, "maps"))
            o->ibl.shadows = IL_IBL_SHADOW_MAPS;
        else if (!strcmp(v, "none"))
            o->ibl.shadows = IL_IBL_SHADOW_NONE;
        else
            return false;
    } else
        return false;
    return true;
}

static double cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Loads the scene, gives it the map, commits. */
static bool load(bench_run *b, const char *env)
{
    il_error err = {0};
    il_image map = {0};
    bool ok = il_scene_load(b->scene_name, NULL, &b->scene, &err) == IL_OK &&
              il_image_read(env, &map, &err) == IL_OK;
    if (ok) {
        il_environment_desc ed = {.map = &map, .mapping = IL_ENV_LATLONG};
        ok = il_scene_set_environment(b->scene, &ed, &err) == IL_OK &&
             il_scene_commit(b->scene, &err) == IL_OK &&
             il_film_create(b->width, b->height, &b->film, &err) == IL_OK;
    }
    il_image_free(&map);
    if (!ok)
        fprintf(stderr, "%s: %s\n", b->prog, err.message);
    return ok;
}

static bool render(bench_run *b, il_image *img)
{
    il_error err = {0};
    if (il_render(b->scene, b->film, &b->rd, &b->stats, &err) != IL_OK ||
        (img && il_film_resolve(b->film, img, &err) != IL_OK)) {
        fprintf(stderr, "%s: %s\n", b->prog, err.message);
        return false;
    }
    return true;
}

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

static int timing(bench_run *b, ibl_bench *o)
{
    if (!o->ibl.lights)
        o->ibl.lights = 1480;
    double w0 = wall_seconds(), c0 = cpu_seconds();
    il_image img = {0};
    if (!render(b, o->out ? &img : NULL))
        return 1;
    double wall = wall_seconds() - w0, cpu = cpu_seconds() - c0;
    const il_ibl_stats *s = &b->stats.ibl;
    printf("%-18s %-16s %7s %6s %8s %9s %8s %8s %10s\n", "scene", "env", "threads", "lights",
           "shadows", "wall_s", "cpu_s", "Mrays", "Mrays/s");
    printf("%-18.18s %-16.16s %7d %6u %8s %9.3f %8.3f %8.1f %10.2f\n", base_name(b->scene_name),
           base_name(o->env), b->rd.threads, s->lights,
           o->ibl.shadows == IL_IBL_SHADOW_MAPS ? "maps"
                                                : (o->ibl.shadows == IL_IBL_SHADOW_NONE ? "none" : "rays"),
           wall, cpu, (double)b->stats.rays * 1e-6,
           b->stats.seconds > 0.0 ? (double)b->stats.rays / b->stats.seconds * 1e-6 : 0.0);
    if (o->out) {
        il_error err = {0};
        if (il_image_write(&img, o->out, NULL, &err) != IL_OK)
            fprintf(stderr, "%s: %s\n", b->prog, err.message);
    }
    il_image_free(&img);
    return 0;
}

static int equal_time(bench_run *b, ibl_bench *o)
{
    static const struct {
        il_ibl_selection sel;
        const char *name;
    } sets[] = {{IL_IBL_RANDOM, "random"},
                {IL_IBL_SOBOL, "sobol"},
                {IL_IBL_IMPORTANCE, "importance"},
                {IL_IBL_IMPORTANCE_SOBOL, "importance-sobol"}};
    il_image ref = {0};
    il_ibl_desc rd = o->ibl;
    rd.selection = IL_IBL_IMPORTANCE_SOBOL;
    rd.lights = o->reference_lights ? o->reference_lights : 32768;
    rd.batch = rd.lights;
    b->rd.ibl = &rd;
    int threads = b->rd.threads;
    b->rd.threads = 0; /* the reference on every core */
    double w0 = wall_seconds();
    if (!render(b, &ref))
        return 1;
    b->rd.threads = threads;
    fprintf(stderr, "%s: reference: %u lights in %.1f s\n", b->prog, rd.lights, wall_seconds() - w0);
    printf("%-18s %-16s %-17s %6s %8s %12s %12s\n", "scene", "env", "selection", "time_s", "lights",
           "rmse", "rel_mse");
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++) {
        il_ibl_desc d = o->ibl;
        d.selection = sets[k].sel;
        d.lights = 1u << 24;
        d.batch = o->ibl.batch ? o->ibl.batch : 16;
        b->rd.ibl = &d;
        b->rd.time_limit = o->equal_time;
        il_image img = {0};
        if (!render(b, &img)) {
            il_image_free(&ref);
            return 1;
        }
        il_compare_result c;
        il_error err = {0};
        if (il_image_compare(&img, &ref, &c, NULL, &err) != IL_OK) {
            fprintf(stderr, "%s: %s\n", b->prog, err.message);
            il_image_free(&img);
            il_image_free(&ref);
            return 1;
        }
        printf("%-18.18s %-16.16s %-17s %6.2f %8u %12.5g %12.5g\n", base_name(b->scene_name),
               base_name(o->env), sets[k].name, b->stats.seconds, b->stats.ibl.lights, c.rmse,
               c.rel_mse);
        fflush(stdout);
        il_image_free(&img);
    }
    il_image_free(&ref);
    return 0;
}

int main(int argc, char **argv)
{
    ibl_bench o = {0};
    bench_run b = {.prog = "bench_ibl",
                   .usage = "bench_ibl SCENE --env MAP.hdr [--lights N] [--selection S] "
                            "[--shadows rays|maps|none] [--batch N] [--equal-time SECONDS] "
                            "[--reference-lights N] [--threads T] [--width W] [--height H] "
                            "[--spp N] [--out IMAGE]",
                   .width = 512,
                   .height = 512,
                   .rd = {.method = IL_METHOD_IBL, .spp = 1, .ibl = &o.ibl}};
    if (!bench_parse(argc, argv, &b, ibl_option, &o))
        return 2;
    if (!o.env) {
        fprintf(stderr, "usage: %s\n", b.usage);
        return 2;
    }
    int rc = 1;
    if (load(&b, o.env))
        rc = o.equal_time > 0.0 ? equal_time(&b, &o) : timing(&b, &o);
    bench_release(&b);
    return rc;
}
