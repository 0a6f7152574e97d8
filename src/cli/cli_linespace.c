/* The Linespace options of `illum render --method linespace`: parsing into
 * an il_linespace_desc, their help text, the "linespace" object of --stats
 * JSON and the summary line (docs/linespace.md lists every option). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_linespace_help[] =
    "linespace options (--method linespace; docs/linespace.md):\n"
    "  --grid N               voxels along the scene's longest side, 1 to 256\n"
    "                         (default 8)\n"
    "  --linespace-n N        patches per voxel face side; 15 N^4 shafts per voxel,\n"
    "                         1 to 8 (default 4)\n"
    "  --inject-rays N        light paths injected, 1 to 10^10 (default 1000000)\n"
    "  --inject-depth N       bounces a light path takes, 1 to 1024 (default\n"
    "                         max-depth - 1)\n"
    "  --blur R               jitter the lookup point on a disk of radius R voxel\n"
    "                         sides, 0 to 4 (default 0: none)\n"
    "  --occlusion-test on|off  test the shaft's triangles between the point and\n"
    "                         the voxel's face (default on)\n"
    "  --fallback occluded|on|off\n"
    "                         which entries trace on instead of being read: an\n"
    "                         occluded one (default; an empty one reads as no\n"
    "                         light), an occluded or empty one (on), none (off)\n"
    "  --solid-angle on|off   normalise each shaft by its own measure (default on)\n"
    "                         or as if all shafts were equal (off: the thesis)\n"
    "  --coarse on|off        an entry with too few deposits reads a coarser level\n"
    "                         (N / its smallest prime factor) before falling back\n"
    "                         (default off)\n"
    "  --coarse-below K       with --coarse on, too few is below K deposits, 1 to\n"
    "                         255 (default 32; 1: only empty entries)\n"
    "  --trace-first-bounce on|off\n"
    "                         trace on from the first diffuse or glossy hit and\n"
    "                         read the Linespace at the next one: a final gather\n"
    "                         (default off)\n"
    "  --glossy-n1 E          Phong exponents below E read the Linespace (default 10)\n"
    "  --glossy-n2 E          Phong exponents above E trace on, blend between\n"
    "                         (default 100); both 0.001 to 10^6\n"
    "  --portal-light on|off  in a scene with portals and light from outside, start\n"
    "                         most light paths at the portals and lay the grid over\n"
    "                         the interior the camera sees (default on; off: the\n"
    "                         whole scene, all paths from the lights)\n";

static const char *const names[] = {"--grid", "--linespace-n", "--inject-rays", "--inject-depth",
                                    "--blur", "--occlusion-test", "--fallback", "--solid-angle",
                                    "--coarse", "--coarse-below", "--trace-first-bounce",
                                    "--glossy-n1", "--glossy-n2"};
#define COUNT(a) (sizeof a / sizeof a[0])

/* An on/off option stored as its "no_" flag. */
static bool parse_onoff(const char *name, const char *v, bool *off)
{
    bool on = true;
    if (!cli_parse_on_off(name, v, &on))
        return false;
    *off = !on;
    return true;
}

static bool parse_value(const char *name, const char *v, il_linespace_desc *d)
{
    double x = 0.0;
    bool ok;
    if (!strcmp(name, "--grid"))
        return cli_parse_u32(name, v, 1, 256, &d->grid);
    if (!strcmp(name, "--linespace-n"))
        return cli_parse_u32(name, v, 1, 8, &d->n);
    if (!strcmp(name, "--inject-depth"))
        return cli_parse_u32(name, v, 1, 1024, &d->inject_depth);
    if (!strcmp(name, "--inject-rays"))
        return cli_parse_count(name, v, &d->inject_rays);
    if (!strcmp(name, "--blur")) {
        ok = cli_parse_double(name, v, 0.0, 4.0, &x);
        d->blur = (float)x;
        return ok;
    }
    if (!strcmp(name, "--occlusion-test"))
        return parse_onoff(name, v, &d->no_occlusion_test);
    if (!strcmp(name, "--fallback")) {
        bool occluded = !strcmp(v, "occluded"), on = !strcmp(v, "on"), off = !strcmp(v, "off");
        if (!occluded && !on && !off) {
            cli_error("%s: '%s' is none of occluded, on and off", name, v);
            return false;
        }
        d->no_fallback = off;
        d->fallback_empty = on;
        return true;
    }
    if (!strcmp(name, "--solid-angle"))
        return parse_onoff(name, v, &d->no_solid_angle);
    if (!strcmp(name, "--coarse"))
        return cli_parse_on_off(name, v, &d->coarse);
    if (!strcmp(name, "--coarse-below"))
        return cli_parse_u32(name, v, 1, 255, &d->coarse_below);
    if (!strcmp(name, "--trace-first-bounce"))
        return cli_parse_on_off(name, v, &d->trace_first_bounce);
    ok = cli_parse_double(name, v, 0.001, 1e6, &x);
    if (!strcmp(name, "--glossy-n1"))
        d->glossy_n1 = (float)x;
    else
        d->glossy_n2 = (float)x;
    return ok;
}

bool cli_linespace_option(int argc, char **argv, int *i, cli_linespace_options *o, int *rc)
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
    if (*rc == IL_EXIT_OK) {
        float n1 = o->desc.glossy_n1 > 0.0f ? o->desc.glossy_n1 : 10.0f;
        float n2 = o->desc.glossy_n2 > 0.0f ? o->desc.glossy_n2 : 100.0f;
        if ((!strcmp(name, "--glossy-n1") || !strcmp(name, "--glossy-n2")) && o->desc.glossy_n1 > 0.0f &&
            o->desc.glossy_n2 > 0.0f && n2 < n1) {
            cli_error("%s: --glossy-n2 (%g) is below --glossy-n1 (%g)", name, (double)n2, (double)n1);
            *rc = IL_EXIT_BAD_INPUT;
        }
    }
    return true;
}

static bool on_step(const il_linespace_progress *p, void *user)
{
    cli_linespace_options *o = user;
    return cli_solve_line_update(&o->line, p->seconds, false,
                                 "linespace: injecting %llu / %llu light paths, %.1fs",
                                 (unsigned long long)p->injected, (unsigned long long)p->total,
                                 p->seconds);
}

void cli_linespace_install_progress(cli_linespace_options *o, bool quiet,
                                    const volatile sig_atomic_t *stop)
{
    cli_solve_line_start(&o->line, quiet, stop);
    o->desc.on_step = on_step;
    o->desc.on_step_user = o;
}

void cli_linespace_end_progress(cli_linespace_options *o) { cli_solve_line_end(&o->line); }

void cli_linespace_stats_json(cJSON *parent, const il_linespace_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "linespace");
    cJSON *g = cJSON_AddArrayToObject(r, "grid");
    for (int k = 0; k < 3; k++)
        cJSON_AddItemToArray(g, cJSON_CreateNumber(s->grid[k]));
    cJSON *lo = cJSON_AddArrayToObject(r, "grid_min"), *hi = cJSON_AddArrayToObject(r, "grid_max");
    for (int k = 0; k < 3; k++) {
        cJSON_AddItemToArray(lo, cJSON_CreateNumber(s->grid_min[k]));
        cJSON_AddItemToArray(hi, cJSON_CreateNumber(s->grid_max[k]));
    }
    cJSON_AddBoolToObject(r, "interior", s->interior);
    cJSON_AddNumberToObject(r, "n", s->n);
    cJSON_AddNumberToObject(r, "voxels", (double)s->voxels);
    cJSON_AddNumberToObject(r, "shafts", (double)s->shafts);
    cJSON_AddNumberToObject(r, "candidates", (double)s->candidates);
    cJSON_AddNumberToObject(r, "overflow_shafts", (double)s->overflow_shafts);
    cJSON_AddNumberToObject(r, "memory_bytes", (double)s->memory_bytes);
    cJSON_AddNumberToObject(r, "inject_rays", (double)s->inject_rays);
    cJSON_AddNumberToObject(r, "injected_segments", (double)s->injected_segments);
    cJSON_AddNumberToObject(r, "lookups", (double)s->lookups);
    cJSON_AddNumberToObject(r, "lookup_hits", (double)s->lookup_hits);
    cJSON_AddNumberToObject(r, "lookup_empty", (double)s->lookup_empty);
    cJSON_AddNumberToObject(r, "lookup_occluded", (double)s->lookup_occluded);
    cJSON_AddNumberToObject(r, "lookup_coarse", (double)s->lookup_coarse);
    cJSON_AddNumberToObject(r, "outside", (double)s->outside);
    cJSON_AddNumberToObject(r, "seconds_build", s->seconds_build);
    cJSON_AddNumberToObject(r, "seconds_inject", s->seconds_inject);
    cJSON_AddNumberToObject(r, "seconds_sample", s->seconds_sample);
    cJSON_AddBoolToObject(r, "stopped", s->stopped);
}

void cli_linespace_summary(const il_linespace_stats *s)
{
    double hit = s->lookups ? 100.0 * (double)s->lookup_hits / (double)s->lookups : 0.0;
    char coarse[64] = "";
    if (s->lookup_coarse > 0)
        snprintf(coarse, sizeof coarse, ", %.1f%% of them from the coarse level",
                 100.0 * (double)s->lookup_coarse / (double)s->lookup_hits);
    fprintf(stderr,
            "illum: linespace: grid %ux%ux%u%s, N %u, %llu voxels, %llu shafts, %.1f MB; %llu paths "
            "injected; %.1f%% of lookups found light%s (build %.2f s, inject %.2f s, sample %.2f s)\n",
            s->grid[0], s->grid[1], s->grid[2], s->interior ? " over the interior in view" : "", s->n,
            (unsigned long long)s->voxels,
            (unsigned long long)s->shafts, (double)s->memory_bytes / (1024.0 * 1024.0),
            (unsigned long long)s->inject_rays, hit, coarse, s->seconds_build, s->seconds_inject,
            s->seconds_sample);
}
