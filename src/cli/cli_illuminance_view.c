/* `illum illuminance --view` (cli.h): a sensor on the surface each pixel
 * of the camera sees, then a false-colour picture or an image of lux. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"

int cli_view_sensors(const il_scene *scene, uint32_t width, uint32_t height, cli_sensor_grid *g,
                     cli_view *view)
{
    size_t n = (size_t)width * height;
    il_sensor *all = malloc(n * sizeof *all);
    bool *seen = malloc(n * sizeof *seen);
    view->width = width;
    view->height = height;
    view->pixel_of = malloc(n * sizeof *view->pixel_of);
    if (!all || !seen || !view->pixel_of) {
        free(all), free(seen);
        cli_error("out of memory for a %ux%u view", width, height);
        return IL_EXIT_RUNTIME;
    }
    il_error err = {0};
    il_status st = il_camera_sensors(scene, width, height, all, seen, &err);
    if (st != IL_OK) {
        free(all), free(seen);
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    /* Only the pixels that see a surface get a sensor. */
    g->count = 0;
    for (size_t i = 0; i < n; i++)
        if (seen[i]) {
            all[g->count] = all[i];
            view->pixel_of[g->count++] = (uint32_t)i;
        }
    g->sensors = all;
    free(seen);
    return IL_EXIT_OK;
}

/* One output of the view: a .png in false colour, else the lux in every
 * channel (EXR in full float). */
static int write_view(const char *path, const float *lux, const bool *seen, uint32_t w, uint32_t h,
                      double scale_max)
{
    const char *dot = strrchr(path, '.');
    il_image img = {0};
    if (dot && !strcasecmp(dot, ".png")) {
        (void)cli_falsecolor(lux, seen, w, h, scale_max, &img); /* rgb NULL when out of memory */
    } else if ((img.rgb = malloc((size_t)w * h * 3 * sizeof(float)))) {
        img.width = w, img.height = h;
        for (size_t i = 0; i < (size_t)w * h; i++)
            img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = lux[i];
    }
    if (!img.rgb) {
        cli_error("%s: out of memory", path);
        return IL_EXIT_RUNTIME;
    }
    il_write_desc wd = {.exr_precision = IL_EXR_FLOAT};
    il_error err = {0};
    il_status st = il_image_write(&img, path, &wd, &err);
    il_image_free(&img);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    return IL_EXIT_OK;
}

int cli_view_finish(const cli_view *view, const cli_sensor_grid *g, const il_illuminance *r,
                    double scale_max, const char *const *outputs, int num_outputs,
                    uint32_t samples, bool quiet, cli_view_summary *sum)
{
    uint32_t w = view->width, h = view->height;
    size_t n = (size_t)w * h;
    float *lux = calloc(n, sizeof *lux);
    bool *seen = calloc(n, sizeof *seen);
    if (!lux || !seen) {
        free(lux), free(seen);
        cli_error("out of memory for a %ux%u view", w, h);
        return IL_EXIT_RUNTIME;
    }
    for (size_t k = 0; k < g->count; k++) {
        lux[view->pixel_of[k]] = r[k].lux;
        seen[view->pixel_of[k]] = true;
    }
    *sum = (cli_view_summary){
        .minimum = cli_seen_quantile(lux, seen, n, 0.0),
        .median = cli_seen_quantile(lux, seen, n, 0.5),
        .maximum = cli_seen_quantile(lux, seen, n, 1.0),
        .palette_max = scale_max > 0.0 ? scale_max : cli_falsecolor_scale(lux, seen, n),
    };
    double top = sum->palette_max;
    printf("view %ux%u: %zu pixels see a surface, %u samples each\n", w, h, g->count, samples);
    if (g->count) {
        printf("lux         minimum %.4g, median %.4g, maximum %.4g\n", sum->minimum, sum->median,
               sum->maximum);
    } else if (!quiet) {
        fprintf(stderr, "illum: warning: the camera sees no surface\n");
    }
    printf("palette     0 .. %g lx\n", top);
    int rc = IL_EXIT_OK;
    for (int k = 0; rc == IL_EXIT_OK && k < num_outputs; k++)
        rc = write_view(outputs[k], lux, seen, w, h, top);
    free(lux), free(seen);
    return rc;
}
