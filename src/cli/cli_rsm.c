/* The reflective-shadow-map options of `illum render --method rsm`: parsing
 * into an il_rsm_desc, their help text, the "rsm" object of --stats JSON and
 * the summary line (docs/rsm.md lists every option, its default and range). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_rsm_help[] =
    "reflective shadow map options (--method rsm; docs/rsm.md):\n"
    "  --rsm-size N           texels per side of each light's map, 1 to 4096\n"
    "                         (default 512)\n"
    "  --rsm-samples N|all    texels gathered per shading point and map, 1 to 65536\n"
    "                         (default 400), or all: the exact sum over every texel\n"
    "  --rsm-radius R         radius r_max of the sampling disk around the point's\n"
    "                         projection, as a fraction of the map's side, 0.001 to 2\n"
    "                         (default 1.5: the whole map, unbiased; smaller is\n"
    "                         faster to converge but misses distant texels)\n"
    "  --rsm-maps N|all       maps gathered per shading point when there are more\n"
    "                         (a point light has six), chosen at random by their\n"
    "                         flux: an unbiased estimate of the sum over every map;\n"
    "                         1 to 4096 (default 8), or all\n"
    "  --rsm-shadow-test on|off\n"
    "                         cast a shadow ray to every texel gathered (Nilles 2017,\n"
    "                         eq. 11; default off: indirect light passes through\n"
    "                         walls, as in Dachsbacher & Stamminger 2005)\n";

static const char *const names[] = {"--rsm-size", "--rsm-samples", "--rsm-radius", "--rsm-maps",
                                    "--rsm-shadow-test"};
#define COUNT(a) (sizeof a / sizeof a[0])

/* "all", or a count from 1 to max. */
static bool parse_count_or_all(const char *name, const char *v, uint32_t max, bool *all,
                               uint32_t *count)
{
    *all = !strcmp(v, "all");
    return *all || cli_parse_u32(name, v, 1, max, count);
}

static bool parse_value(const char *name, const char *v, il_rsm_desc *d)
{
    if (!strcmp(name, "--rsm-size"))
        return cli_parse_u32(name, v, 1, 4096, &d->resolution);
    if (!strcmp(name, "--rsm-samples"))
        return parse_count_or_all(name, v, 65536, &d->all_texels, &d->samples);
    if (!strcmp(name, "--rsm-maps"))
        return parse_count_or_all(name, v, 4096, &d->all_maps, &d->maps);
    if (!strcmp(name, "--rsm-radius")) {
        double x = 0.0;
        bool ok = cli_parse_double(name, v, 0.001, 2.0, &x);
        d->radius = (float)x;
        return ok;
    }
    /* --rsm-shadow-test */
    return cli_parse_on_off(name, v, &d->shadow_test);
}

bool cli_rsm_option(int argc, char **argv, int *i, cli_rsm_options *o, int *rc)
{
    const char *v = NULL;
    const char *name = cli_method_option(argc, argv, i, names, COUNT(names), &o->note, &v);
    if (!name)
        return false;
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    *rc = parse_value(name, v, &o->desc) ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    return true;
}

void cli_rsm_stats_json(cJSON *parent, const il_rsm_desc *d, const il_rsm_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "rsm");
    cJSON_AddNumberToObject(r, "resolution", s->resolution);
    if (d->all_texels)
        cJSON_AddStringToObject(r, "samples", "all");
    else
        cJSON_AddNumberToObject(r, "samples", d->samples ? d->samples : 400);
    cJSON_AddNumberToObject(r, "radius", d->radius > 0.0f ? d->radius : 1.5);
    cJSON_AddBoolToObject(r, "shadow_test", d->shadow_test);
    cJSON_AddNumberToObject(r, "maps", s->maps);
    cJSON_AddNumberToObject(r, "maps_per_point", s->maps_per_point);
    cJSON_AddNumberToObject(r, "texels", (double)s->texels);
    cJSON_AddNumberToObject(r, "map_bytes", (double)s->map_bytes);
    cJSON_AddNumberToObject(r, "gathered", (double)s->gathered);
    cJSON_AddNumberToObject(r, "shadow_rays", (double)s->shadow_rays);
    cJSON_AddNumberToObject(r, "seconds_build", s->seconds_build);
    cJSON_AddNumberToObject(r, "seconds_gather", s->seconds_gather);
}

void cli_rsm_summary(const il_rsm_desc *d, const il_rsm_stats *s)
{
    char samples[32];
    if (d->all_texels)
        snprintf(samples, sizeof samples, "all texels");
    else
        snprintf(samples, sizeof samples, "%u samples", d->samples ? d->samples : 400u);
    fprintf(stderr,
            "illum: rsm: %u maps of %u^2 (%u a shading point), %llu texels lit, %.1f MB; %s, "
            "r_max %.3g, shadow test %s, %llu shadow rays (maps %.2f s, gather %.2f s)\n",
            s->maps, s->resolution, s->maps_per_point, (unsigned long long)s->texels,
            (double)s->map_bytes / (1024.0 * 1024.0), samples,
            d->radius > 0.0f ? (double)d->radius : 1.5, d->shadow_test ? "on" : "off",
            (unsigned long long)s->shadow_rays, s->seconds_build, s->seconds_gather);
    if (s->maps == 0) /* a valid render, but likely not what was meant */
        fprintf(stderr, "illum: warning: rsm: the scene has no point, spot or directional light, "
                        "so it has no map and the image holds direct light only (area lights and "
                        "the environment get no map: docs/rsm.md)\n");
}
