/* The photon-mapping options of `illum render --method photon|sppm`:
 * parsing into an il_photon_desc, their help text, the "photon" object of
 * --stats JSON and the summary line (docs/photon-mapping.md lists every
 * option, its default and range). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_photon_help[] =
    "photon mapping options (--method photon or sppm; docs/photon-mapping.md):\n"
    "  --photons N            photons emitted (photon: default 1000000; sppm: per\n"
    "                         pass, default 250000), 1 to 10^10\n"
    "  --lookup kdtree|grid   photon search: k nearest in a kd-tree (default) or all\n"
    "                         within the radius in a hashed grid\n"
    "  --radius X             largest search radius (kd-tree) or the radius (grid), as\n"
    "                         a fraction of the scene's size, 1e-6 to 1 (default\n"
    "                         0.02; the size: the bounding box's diagonal, or the\n"
    "                         diagonal of what the camera sees where that is less\n"
    "                         than half of it)\n"
    "  --photon-depth N       most bounces a photon takes, 1 to 1024 (default\n"
    "                         max-depth - 1)\n"
    "  --portal-light on|off  in a scene with portals and light from outside, start\n"
    "                         most photons at the portals (default on; off: all\n"
    "                         leave the lights)\n"
    "photon only:\n"
    "  --k N                  photons per kd-tree estimate, 1 to 100000 (default 100)\n"
    "  --photon-filter cone|epanechnikov\n"
    "                         density-estimation kernel (default cone)\n"
    "  --final-gather N       N rays per camera hit gather indirect light from the\n"
    "                         global map at their hits, 1 to 65536 (default: none,\n"
    "                         the global map is read at the camera hit)\n"
    "  --precomputed-irradiance on|off\n"
    "                         read the global map at Lambertian surfaces from the\n"
    "                         irradiance precomputed at every 4th photon (default\n"
    "                         on), or by a full estimate at every hit (off)\n"
    "sppm only:\n"
    "  --alpha X              fraction of new photons kept per pass, 0.01 to 0.99\n"
    "                         (default 0.7)\n"
    "  --initial-radius X     first per-pixel radius as a fraction of the scene's\n"
    "                         size, 1e-6 to 1 (default 0.01)\n";

/* --portal-light, which Linespace takes too, is cli_method.c's. */
static const char *const common_names[] = {"--photons", "--lookup", "--radius", "--photon-depth"};
static const char *const photon_names[] = {"--k", "--photon-filter", "--final-gather",
                                           "--precomputed-irradiance"};
static const char *const sppm_names[] = {"--alpha", "--initial-radius"};
#define COUNT(a) (sizeof a / sizeof a[0])

/* An on|off option whose library field is a "no_" flag: 0 for on, 1 for off. */
static bool parse_off_flag(const char *name, const char *v, uint32_t *no)
{
    bool on;
    if (!cli_parse_on_off(name, v, &on))
        return false;
    *no = !on;
    return true;
}

static bool parse_value(const char *name, const char *v, il_photon_desc *d)
{
    double x = 0.0;
    /* Zero means "the default" to the library, so the lower bounds are above 0. */
    if (!strcmp(name, "--photons"))
        return cli_parse_count(name, v, &d->photons);
    if (!strcmp(name, "--lookup")) {
        if (!strcmp(v, "kdtree"))
            d->lookup = IL_PHOTON_KDTREE;
        else if (!strcmp(v, "grid"))
            d->lookup = IL_PHOTON_GRID;
        else {
            cli_error("%s: unknown search '%s' (available: kdtree, grid)", name, v);
            return false;
        }
        return true;
    }
    if (!strcmp(name, "--photon-filter")) {
        if (!strcmp(v, "cone"))
            d->filter = IL_PHOTON_CONE;
        else if (!strcmp(v, "epanechnikov"))
            d->filter = IL_PHOTON_EPANECHNIKOV;
        else {
            cli_error("%s: unknown filter '%s' (available: cone, epanechnikov)", name, v);
            return false;
        }
        return true;
    }
    if (!strcmp(name, "--precomputed-irradiance"))
        return parse_off_flag(name, v, &d->no_precomputed_irradiance);
    if (!strcmp(name, "--radius")) {
        bool ok = cli_parse_double(name, v, 1e-6, 1.0, &x);
        d->max_radius = (float)x;
        return ok;
    }
    if (!strcmp(name, "--initial-radius")) {
        bool ok = cli_parse_double(name, v, 1e-6, 1.0, &x);
        d->initial_radius = (float)x;
        return ok;
    }
    if (!strcmp(name, "--alpha")) {
        bool ok = cli_parse_double(name, v, 0.01, 0.99, &x);
        d->alpha = (float)x;
        return ok;
    }
    if (!strcmp(name, "--photon-depth"))
        return cli_parse_u32(name, v, 1, 1024, &d->max_photon_depth);
    if (!strcmp(name, "--k"))
        return cli_parse_u32(name, v, 1, 100000, &d->k);
    return cli_parse_u32(name, v, 1, 65536, &d->final_gather); /* --final-gather */
}

bool cli_photon_option(int argc, char **argv, int *i, cli_photon_options *o, int *rc)
{
    const char *v = NULL;
    const char *name = cli_method_option(argc, argv, i, common_names, COUNT(common_names), &o->note, &v);
    if (!name)
        name = cli_method_option(argc, argv, i, photon_names, COUNT(photon_names), &o->photon_only, &v);
    if (!name)
        name = cli_method_option(argc, argv, i, sppm_names, COUNT(sppm_names), &o->sppm_only, &v);
    if (!name)
        return false;
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    *rc = parse_value(name, v, &o->desc) ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    return true;
}

int cli_photon_check_method(const char *command, const cli_photon_options *o, il_method method)
{
    bool photon = method == IL_METHOD_PHOTON, sppm = method == IL_METHOD_SPPM;
    if (o->note.given && !photon && !sppm) {
        cli_error("%s is a photon mapping option; it needs --method photon or --method sppm "
                  "(see 'illum %s --method photon --help')",
                  o->note.first, command);
        return IL_EXIT_USAGE;
    }
    if (o->photon_only.given && !photon)
        return cli_method_mismatch(command, &o->photon_only, "photon-mapping", "photon");
    if (o->sppm_only.given && !sppm)
        return cli_method_mismatch(command, &o->sppm_only, "progressive photon mapping", "sppm");
    return IL_EXIT_OK;
}

/* "photon: tracing N / M photons", then "photon: irradiance N / M points". */
static bool on_step(const il_photon_progress *p, void *user)
{
    cli_photon_options *o = user;
    const char *what = p->phase == IL_PHOTON_TRACING ? "tracing" : "irradiance at";
    const char *unit = p->phase == IL_PHOTON_TRACING ? "photons" : "points";
    return cli_solve_line_update(&o->line, p->seconds, false, "photon: %s %llu / %llu %s, %.1fs",
                                 what, (unsigned long long)p->done, (unsigned long long)p->total,
                                 unit, p->seconds);
}

void cli_photon_install_progress(cli_photon_options *o, bool quiet,
                                 const volatile sig_atomic_t *stop)
{
    cli_solve_line_start(&o->line, quiet, stop);
    o->desc.on_step = on_step;
    o->desc.on_step_user = o;
}

void cli_photon_end_progress(cli_photon_options *o) { cli_solve_line_end(&o->line); }

void cli_photon_stats_json(cJSON *parent, const il_photon_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "photon");
    cJSON_AddNumberToObject(r, "emitted", (double)s->emitted);
    cJSON_AddNumberToObject(r, "stored_global", (double)s->stored_global);
    cJSON_AddNumberToObject(r, "stored_caustic", (double)s->stored_caustic);
    cJSON_AddNumberToObject(r, "stored", (double)s->stored);
    cJSON_AddNumberToObject(r, "photon_rays", (double)s->photon_rays);
    cJSON_AddNumberToObject(r, "passes", s->passes);
    cJSON_AddNumberToObject(r, "seconds_trace", s->seconds_trace);
    cJSON_AddNumberToObject(r, "seconds_build", s->seconds_build);
    cJSON_AddNumberToObject(r, "seconds_render", s->seconds_render);
    cJSON_AddNumberToObject(r, "photons_per_second",
                            s->seconds_trace > 0.0 ? (double)s->emitted / s->seconds_trace : 0.0);
    cJSON_AddNumberToObject(r, "map_bytes", (double)s->map_bytes);
    cJSON_AddNumberToObject(r, "bytes_per_photon", s->bytes_per_photon);
    cJSON_AddBoolToObject(r, "stopped", s->stopped);
}

void cli_photon_summary(il_method method, const il_photon_stats *s)
{
    double rate = s->seconds_trace > 0.0 ? (double)s->emitted / s->seconds_trace * 1e-6 : 0.0;
    if (method == IL_METHOD_SPPM)
        fprintf(stderr,
                "illum: sppm: %u passes, %llu photons emitted (%.3g M/s), %llu stored "
                "(trace %.2f s, maps %.2f s, camera and gather %.2f s)\n",
                s->passes, (unsigned long long)s->emitted, rate, (unsigned long long)s->stored,
                s->seconds_trace, s->seconds_build, s->seconds_render);
    else
        fprintf(stderr,
                "illum: photon: %llu photons emitted (%.3g M/s), %llu global + %llu caustic stored, "
                "%.1f MB (trace %.2f s, maps %.2f s, render %.2f s)\n",
                (unsigned long long)s->emitted, rate, (unsigned long long)s->stored_global,
                (unsigned long long)s->stored_caustic, (double)s->map_bytes / (1024.0 * 1024.0),
                s->seconds_trace, s->seconds_build, s->seconds_render);
}
