/* The many-light options of `illum render --method ibl`: parsing into an
 * il_ibl_desc, their help text, the "ibl" object of --stats JSON and the
 * summary line (docs/ibl.md lists every option, its default and range). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_ibl_help[] =
    "many-light environment options (--method ibl; docs/ibl.md):\n"
    "  --lights N             directional lights the environment becomes, 1 to\n"
    "                         16777216 (default 1024)\n"
    "  --light-selection importance-sobol|importance|sobol|random\n"
    "                         how their directions are chosen: the map's importance\n"
    "                         distribution or uniform over the sphere, with Sobol\n"
    "                         (stratified) or random points (default importance-sobol)\n"
    "  --shadows rays|maps|none\n"
    "                         visibility: a shadow ray per light and sample (exact,\n"
    "                         default), a shadow map per light, or none\n"
    "  --batch N              lights added per progressive step; the image is\n"
    "                         complete after each, 1 to 16777216 (default 64)\n"
    "  --shadow-map-size N    shadow-map texels per side, 1 to 8192 (default 512)\n"
    "  --shadow-bias X        shadow-map depth bias as a fraction of the scene's\n"
    "                         diagonal, 1e-7 to 1 (default 0.001)\n"
    "  --pcf N                percentage-closer filter width in texels, odd, 1 to 15\n"
    "                         (default 3)\n"
    "  The camera takes --spp samples per pixel (default 1 for ibl; every sample is\n"
    "  shaded by every light); --max-depth counts mirror and glass bounces plus the\n"
    "  shaded surface (default 8); the reference is --method pt --max-depth 1.\n";

static const char *const names[] = {"--lights",          "--light-selection", "--shadows",
                                    "--batch",           "--shadow-map-size", "--shadow-bias",
                                    "--pcf"};
#define COUNT(a) (sizeof a / sizeof a[0])

static bool parse_value(const char *name, const char *v, il_ibl_desc *d)
{
    if (!strcmp(name, "--lights"))
        return cli_parse_u32(name, v, 1, 1u << 24, &d->lights);
    if (!strcmp(name, "--batch"))
        return cli_parse_u32(name, v, 1, 1u << 24, &d->batch);
    if (!strcmp(name, "--shadow-map-size"))
        return cli_parse_u32(name, v, 1, 8192, &d->shadow_map_size);
    if (!strcmp(name, "--pcf")) {
        if (!cli_parse_u32(name, v, 1, 15, &d->pcf_taps))
            return false;
        if (d->pcf_taps % 2 == 0) {
            cli_error("%s: %s is even (the filter is centred on a texel: 1, 3, 5, ... 15)", name, v);
            return false;
        }
        return true;
    }
    if (!strcmp(name, "--shadow-bias")) {
        double x = 0.0;
        bool ok = cli_parse_double(name, v, 1e-7, 1.0, &x);
        d->shadow_bias = (float)x;
        return ok;
    }
    if (!strcmp(name, "--light-selection")) {
        if (!strcmp(v, "importance-sobol"))
            d->selection = IL_IBL_IMPORTANCE_SOBOL;
        else if (!strcmp(v, "importance"))
            d->selection = IL_IBL_IMPORTANCE;
        else if (!strcmp(v, "sobol"))
            d->selection = IL_IBL_SOBOL;
        else if (!strcmp(v, "random"))
            d->selection = IL_IBL_RANDOM;
        else {
            cli_error("%s: unknown selection '%s' (available: importance-sobol, importance, "
                      "sobol, random)",
                      name, v);
            return false;
        }
        return true;
    }
    /* --shadows */
    if (!strcmp(v, "rays"))
        d->shadows = IL_IBL_SHADOW_RAYS;
    else if (!strcmp(v, "maps"))
        d->shadows = IL_IBL_SHADOW_MAPS;
    else if (!strcmp(v, "none"))
        d->shadows = IL_IBL_SHADOW_NONE;
    else {
        cli_error("%s: unknown shadow method '%s' (available: rays, maps, none)", name, v);
        return false;
    }
    return true;
}

bool cli_ibl_option(int argc, char **argv, int *i, cli_ibl_options *o, int *rc)
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

static const char *selection_name(il_ibl_selection s)
{
    switch (s) {
    case IL_IBL_IMPORTANCE:
        return "importance";
    case IL_IBL_SOBOL:
        return "sobol";
    case IL_IBL_RANDOM:
        return "random";
    case IL_IBL_IMPORTANCE_SOBOL:
    default:
        return "importance-sobol";
    }
}

static const char *shadows_name(il_ibl_shadows s)
{
    return s == IL_IBL_SHADOW_MAPS ? "maps" : (s == IL_IBL_SHADOW_NONE ? "none" : "rays");
}

void cli_ibl_stats_json(cJSON *parent, const il_ibl_desc *d, const il_ibl_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "ibl");
    cJSON_AddNumberToObject(r, "lights", s->lights);
    cJSON_AddStringToObject(r, "selection", selection_name(d->selection));
    cJSON_AddStringToObject(r, "shadows", shadows_name(d->shadows));
    cJSON_AddNumberToObject(r, "batch", d->batch ? d->batch : 64);
    cJSON_AddNumberToObject(r, "shadow_rays", (double)s->shadow_rays);
    cJSON_AddNumberToObject(r, "seconds_lights", s->seconds_lights);
    cJSON_AddNumberToObject(r, "seconds_shade", s->seconds_shade);
}

void cli_ibl_summary(const il_ibl_desc *d, const il_ibl_stats *s)
{
    fprintf(stderr,
            "illum: ibl: %u lights (%s), shadows %s, %llu shadow rays (lights %.2f s, shading "
            "%.2f s)\n",
            s->lights, selection_name(d->selection), shadows_name(d->shadows),
            (unsigned long long)s->shadow_rays, s->seconds_lights, s->seconds_shade);
}
