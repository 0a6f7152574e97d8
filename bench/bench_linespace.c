/* Linespace light injection against the path tracer: samples per second
 * of each camera pass, injection time and memory, and the error of both
 * against a long path-traced reference at equal time.
 *
 *   bench_linespace SCENE [--variant diffuse|glossy|mirror|glass]
 *                   [--inject-rays N] [--grid N] [--linespace-n N] [--blur R]
 *                   [--fallback occluded|on|off] [--occlusion-test on|off] [--coarse on|off]
 *                   [--coarse-below K] [--trace-first-bounce on|off]
 *                   [--max-depth D] [--ref-spp N] [--time S] [--spp N]
 *                   [--threads T] [--width W] [--height H]
 *
 * --variant replaces the material of the Cornell box's tall block (the
 * built-in `cornell`): Lambertian white (as built), Phong exponent 50
 * (between the default glossy thresholds: blended), a mirror, or glass.
 * Steps (all at max depth D, default 4; 128x128):
 *   1. reference: the path tracer at ref-spp (default 1024) samples/pixel;
 *   2. linespace: build + inject, then a camera pass of S seconds (default
 *      1; --spp N caps it); its rate is pixels*spp / seconds of the pass;
 *   3. the path tracer for the same S seconds: its rate, and the error at
 *      equal sampling time (rmse_pt; the Linespace is precomputed for a
 *      static scene);
 *   4. the path tracer for S + build + inject seconds: the error at equal
 *      total time (rmse_pt+).
 * Errors are the RMS luminance difference to the reference relative to the
 * reference's mean.  Prints figures, never judges (bench/linespace.sh). */
#include <math.h>
#include <omp.h>

#include "bench_common.h"
#include "scene/scene.h"

typedef struct ls_opts {
    il_linespace_desc ld;
    const char *variant;
    uint32_t max_depth, ref_spp;
    double seconds;
} ls_opts;

static bool ls_option(const char *a, const char *v, void *user)
{
    ls_opts *o = user;
    if (!strcmp(a, "--variant"))
        o->variant = v;
    else if (!strcmp(a, "--inject-rays"))
        o->ld.inject_rays = strtoull(v, NULL, 10);
    else if (!strcmp(a, "--grid"))
        o->ld.grid = (uint32_t)atoi(v);
    else if (!strcmp(a, "--linespace-n"))
        o->ld.n = (uint32_t)atoi(v);
    else if (!strcmp(a, "--blur"))
        o->ld.blur = (float)atof(v);
    else if (!strcmp(a, "--fallback")) {
        o->ld.no_fallback = !strcmp(v, "off");
        o->ld.fallback_empty = !strcmp(v, "on");
    }
    else if (!strcmp(a, "--occlusion-test"))
        o->ld.no_occlusion_test = !strcmp(v, "off");
    else if (!strcmp(a, "--coarse"))
        o->ld.coarse = !strcmp(v, "on");
    else if (!strcmp(a, "--coarse-below"))
        o->ld.coarse_below = (uint32_t)atoi(v);
    else if (!strcmp(a, "--trace-first-bounce"))
        o->ld.trace_first_bounce = !strcmp(v, "on");
    else if (!strcmp(a, "--max-depth"))
        o->max_depth = (uint32_t)atoi(v);
    else if (!strcmp(a, "--time"))
        o->seconds = atof(v);
    else if (!strcmp(a, "--ref-spp"))
        o->ref_spp = (uint32_t)atoi(v);
    else
        return false;
    return true;
}

/* The tall block's material replaced (the scene not yet committed). */
static bool apply_variant(il_scene *s, const char *variant, il_error *err)
{
    il_material_desc m = {.name = "tall_block_variant"};
    if (!strcmp(variant, "diffuse"))
        return true;
    if (!strcmp(variant, "glossy")) {
        m.type = IL_MATERIAL_PHONG;
        m.diffuse = (il_vec3){0.25f, 0.25f, 0.25f};
        m.specular = (il_vec3){0.5f, 0.5f, 0.5f};
        m.exponent = 50.0f;
    } else if (!strcmp(variant, "mirror")) {
        m.type = IL_MATERIAL_MIRROR;
        m.specular = (il_vec3){0.9f, 0.9f, 0.9f};
    } else if (!strcmp(variant, "glass")) {
        m.type = IL_MATERIAL_DIELECTRIC;
        m.ior = 1.5f;
    } else {
        fprintf(stderr, "bench_linespace: unknown variant '%s'\n", variant);
        return false;
    }
    uint32_t id;
    if (il_scene_add_material(s, &m, &id, err) != IL_OK)
        return false;
    for (uint32_t k = 0; k < s->num_meshes; k++)
        if (!strcmp(s->meshes[k].name, "tall_block"))
            s->meshes[k].material = id;
    return true;
}

static bool render(il_scene *s, uint32_t w, uint32_t h, const il_render_desc *rd, il_image *img,
                   il_render_stats *st, il_error *err)
{
    il_film *film = NULL;
    bool ok = il_film_create(w, h, &film, err) == IL_OK && il_render(s, film, rd, st, err) == IL_OK &&
              il_film_resolve(film, img, err) == IL_OK;
    il_film_release(film);
    return ok;
}

static double rel_rmse(const il_image *a, const il_image *ref)
{
    double se = 0.0, mean = 0.0;
    size_t n = (size_t)a->width * a->height;
    for (size_t i = 0; i < n; i++) {
        const float *p = a->rgb + 3 * i, *q = ref->rgb + 3 * i;
        double la = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        double lb = 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2];
        se += (la - lb) * (la - lb);
        mean += lb;
    }
    mean /= (double)n;
    return mean > 0.0 ? sqrt(se / (double)n) / mean : 0.0;
}

int main(int argc, char **argv)
{
    ls_opts o = {.variant = "diffuse", .max_depth = 4, .ref_spp = 1024, .seconds = 1.0};
    bench_run b = {.prog = "bench_linespace",
                   .usage = "bench_linespace SCENE [--variant diffuse|glossy|mirror|glass] "
                            "[--inject-rays N] [--grid N] [--linespace-n N] [--blur R] "
                            "[--fallback occluded|on|off] [--occlusion-test on|off] [--max-depth D] "
                            "[--ref-spp N] [--time S] [--spp N] [--threads T] [--width W] [--height H]",
                   .width = 128,
                   .height = 128,
                   .rd = {.spp = 0}};
    if (!bench_parse(argc, argv, &b, ls_option, &o))
        return 2;
    il_error err = {0};
    il_scene *s = NULL;
    if (il_scene_load(b.scene_name, NULL, &s, &err) != IL_OK || !apply_variant(s, o.variant, &err) ||
        il_scene_commit(s, &err) != IL_OK) {
        fprintf(stderr, "bench_linespace: %s\n", err.message);
        il_scene_release(s);
        return 1;
    }
    const uint32_t w = b.width, h = b.height;
    il_render_desc ref_d = {.method = IL_METHOD_PT, .spp = o.ref_spp, .max_depth = o.max_depth,
                            .threads = b.rd.threads, .seed = 99};
    il_render_desc ls_d = {.method = IL_METHOD_LINESPACE, .spp = b.rd.spp, .time_limit = o.seconds,
                           .max_depth = o.max_depth, .threads = b.rd.threads, .seed = 1,
                           .linespace = &o.ld};
    il_render_desc pt_d = {.method = IL_METHOD_PT, .spp = b.rd.spp, .time_limit = o.seconds,
                           .max_depth = o.max_depth, .threads = b.rd.threads, .seed = 1};
    il_image ref = {0}, ls = {0}, pt = {0}, pt_tot = {0};
    il_render_stats st_ref, st_ls, st_pt, st_tot;
    bool ok = render(s, w, h, &ref_d, &ref, &st_ref, &err) && render(s, w, h, &ls_d, &ls, &st_ls, &err) &&
              render(s, w, h, &pt_d, &pt, &st_pt, &err);
    const il_linespace_stats *l = &st_ls.linespace;
    /* Equal total time: the path tracer also gets the build and injection. */
    il_render_desc tot_d = pt_d;
    tot_d.time_limit = l->seconds_sample + l->seconds_build + l->seconds_inject;
    ok = ok && render(s, w, h, &tot_d, &pt_tot, &st_tot, &err);
    if (!ok) {
        fprintf(stderr, "bench_linespace: %s\n", err.message);
        return 1;
    }
    double px = (double)w * h;
    double ls_rate = px * st_ls.spp / l->seconds_sample, pt_rate = px * st_pt.spp / st_pt.seconds;
    double lookups = l->lookups ? (double)l->lookups : 1.0;
    printf("%-10s %-8s %4s %9s %9s %6s %8s %8s %8s %9s %6s %7s %8s %8s %8s %8s\n", "scene", "variant", "thr",
           "pt_spp/s", "ls_spp/s", "ratio", "build_s", "inject_s", "mem_MB", "shafts", "found%", "coarse%",
           "sample_s", "rmse_pt", "rmse_ls", "rmse_pt+");
    printf("%-10s %-8s %4d %9.3g %9.3g %6.2f %8.3f %8.3f %8.1f %9llu %6.1f %7.1f %8.2f %8.4f %8.4f %8.4f\n",
           b.scene_name, o.variant, b.rd.threads, pt_rate, ls_rate, ls_rate / pt_rate, l->seconds_build,
           l->seconds_inject, l->memory_bytes / 1048576.0, (unsigned long long)l->shafts,
           100.0 * (double)l->lookup_hits / lookups, 100.0 * (double)l->lookup_coarse / lookups,
           l->seconds_sample, rel_rmse(&pt, &ref), rel_rmse(&ls, &ref), rel_rmse(&pt_tot, &ref));
    printf("# reference %u spp in %.1f s; equal sampling time: pt %u spp, linespace %u spp (%llu paths); "
           "pt with build+inject time too: %u spp\n",
           st_ref.spp, st_ref.seconds, st_pt.spp, st_ls.spp, (unsigned long long)l->inject_rays, st_tot.spp);
    il_image_free(&ref);
    il_image_free(&ls);
    il_image_free(&pt);
    il_image_free(&pt_tot);
    il_scene_release(s);
    return 0;
}
