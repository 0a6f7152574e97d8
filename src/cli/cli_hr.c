/* The hierarchical-radiosity options shared by `illum render --method hr`
 * and `illum bake --method hr`: parsing into an il_hr_desc, their help
 * text, the "hr" object of --stats JSON and the summary line
 * (docs/hierarchical-radiosity.md lists every option, its default and
 * range). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_hr_help[] =
    "hierarchical radiosity options (--method hr; docs/hierarchical-radiosity.md):\n"
    "  --bf-eps X             refine a link while F * B * V / B_ref > X, B_ref the\n"
    "                         scene's mean emitted radiance, 1e-7 to 1 (default\n"
    "                         0.015, SPLASH-2's BF epsilon)\n"
    "  --area-eps X           ... and the larger element's area > X * (the scene's\n"
    "                         bounding-box diagonal)^2, 1e-9 to 1 (default 6.92e-4,\n"
    "                         SPLASH-2's 2000 in a room about 1700 units wide)\n"
    "  --energy-eps X         stop when the relative change of total energy < X,\n"
    "                         1e-9 to 1 (default 0.005)\n"
    "  --vis-rays N           visibility rays per link, 1 to 4096 (default 16; with\n"
    "                         16, 64, 256, ... a link may settle after 4)\n"
    "  --max-iterations N     at most N gather + push-pull iterations, 1 to 100000\n"
    "                         (default 100)\n";

bool cli_hr_option(int argc, char **argv, int *i, cli_hr_options *o, int *rc)
{
    static const char *const names[] = {"--bf-eps", "--area-eps", "--energy-eps", "--vis-rays",
                                        "--max-iterations"};
    const char *v = NULL;
    const char *name =
        cli_method_option(argc, argv, i, names, sizeof names / sizeof names[0], &o->note, &v);
    if (!name)
        return false;
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    il_hr_desc *d = &o->desc;
    bool ok = true;
    double x = 0.0;
    /* Zero means "the default" to the library, so the lower bounds are above 0. */
    if (!strcmp(name, "--bf-eps")) {
        ok = cli_parse_double(name, v, 1e-7, 1.0, &x);
        d->bf_eps = (float)x;
    } else if (!strcmp(name, "--area-eps")) {
        ok = cli_parse_double(name, v, 1e-9, 1.0, &x);
        d->area_eps = (float)x;
    } else if (!strcmp(name, "--energy-eps")) {
        ok = cli_parse_double(name, v, 1e-9, 1.0, &x);
        d->energy_eps = (float)x;
    } else if (!strcmp(name, "--vis-rays")) {
        ok = cli_parse_u32(name, v, 1, 4096, &d->vis_rays);
    } else if (!strcmp(name, "--max-iterations")) {
        ok = cli_parse_u32(name, v, 1, 100000, &d->max_iterations);
    }
    *rc = ok ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    return true;
}

void cli_hr_stats_json(cJSON *parent, const il_hr_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "hr");
    cJSON_AddNumberToObject(r, "patches", s->patches);
    cJSON_AddNumberToObject(r, "elements", (double)s->elements);
    cJSON_AddNumberToObject(r, "leaves", (double)s->leaves);
    cJSON_AddNumberToObject(r, "links", (double)s->links);
    cJSON_AddNumberToObject(r, "iterations", s->iterations);
    cJSON_AddNumberToObject(r, "visibility_rays", (double)s->visibility_rays);
    cJSON_AddNumberToObject(r, "seconds_setup", s->seconds_setup);
    cJSON_AddNumberToObject(r, "seconds_refine", s->seconds_refine);
    cJSON_AddNumberToObject(r, "seconds_gather", s->seconds_gather);
    cJSON_AddNumberToObject(r, "seconds_average", s->seconds_average);
    cJSON_AddNumberToObject(r, "seconds_render", s->seconds_render);
    cJSON_AddNumberToObject(r, "peak_bytes", (double)s->peak_bytes);
}

void cli_hr_summary(const il_hr_stats *s)
{
    fprintf(stderr,
            "illum: hr: %u patches, %llu elements, %llu links, %u iterations, %llu visibility rays "
            "(setup %.2f s, refine %.2f s, gather %.2f s, average %.2f s, render %.2f s, "
            "%.1f MB)\n",
            s->patches, (unsigned long long)s->elements, (unsigned long long)s->links,
            s->iterations, (unsigned long long)s->visibility_rays, s->seconds_setup,
            s->seconds_refine, s->seconds_gather, s->seconds_average, s->seconds_render,
            (double)s->peak_bytes / (1024.0 * 1024.0));
}
