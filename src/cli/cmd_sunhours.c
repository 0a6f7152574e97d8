/* `illum sunhours SCENE`: hours of direct sun on a plane or at points over
 * a period (a day by default) under a cloudless sky
 * (docs/illuminance.md#sun-hours). */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "scene/sun.h"

static const char *help =
    "usage: illum sunhours SCENE (--plane AXIS=VALUE | --points FILE) --from MOMENT\n"
    "                            --latitude DEG --longitude DEG [options]\n"
    "\n"
    "Counts the hours the sun shines on each sensor over a period: the sun's\n"
    "centre above --min-altitude, in front of the sensor and not hidden by the\n"
    "scene.  No clouds (the sunlight checks of EN 17037 and BR 209 assume none).\n"
    "The scene needs no lights.  Sensors block no light.  Lengths are metres.\n"
    "\n"
    "where:\n"
    "  --plane AXIS=VALUE     a grid of sensors on the plane AXIS = VALUE, facing\n"
    "                         +AXIS (-AXIS=VALUE faces -AXIS); --area A0,B0,A1,B1,\n"
    "                         --margin M and --spacing S as for illuminance\n"
    "  --points FILE          sensors from a text file: one 'x y z [nx ny nz]' a line\n"
    "                         (normal +y when omitted; a window: its outward normal)\n"
    "  --from MOMENT          the period's start with its UTC offset, such as\n"
    "                         2026-03-21T00:00+01:00 (midnight starting that day)\n"
    "  --latitude DEG --longitude DEG\n"
    "                         the place, north and east positive\n"
    "options:\n"
    "  --hours H              the period's length (default 24, at most a leap year)\n"
    "  --step MIN             minutes between the sun's places (default 1, at most 60)\n"
    "  --min-altitude DEG     count the sun only above this altitude (default 0)\n"
    "  --north DEG            north in the scene: -z turned DEG counter-clockwise\n"
    "                         seen from above (default 0: north -z, east +x)\n"
    "  --at-least H           also report the share of sensors with at least H hours\n"
    "  --threads T  --quiet\n"
    "  --stats STATS.json     the summary as JSON\n"
    "  -o OUT.csv             every sensor: x,y,z,nx,ny,nz,sun_hours\n"
    "Ctrl-C stops at the next hundredth of the period and writes the hours of the\n"
    "part counted (exit 130).\n";

typedef struct options {
    const char *scene, *stats, *output, *from;
    bool has_lat, has_lon, quiet;
    cli_sensor_place place;
    double at_least;
    il_sun_hours_desc desc;
} options;

static bool takes_value(const char *a)
{
    static const char *const names[] = {"--plane", "--area", "--margin", "--spacing", "--points",
                                        "--from", "--latitude", "--longitude", "--hours", "--step",
                                        "--min-altitude", "--north", "--at-least", "--threads",
                                        "--stats", "-o", "--output"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(a, names[k]))
            return true;
    return false;
}

static int parse_value(const char *a, const char *v, options *o)
{
    bool ok = true;
    uint32_t threads = 0;
    if (cli_sensor_place_option(a, v, &o->place, &ok)) {
        /* --plane, --area, --margin, --spacing, --points */
    } else if (!strcmp(a, "--from")) {
        il_error err = {0};
        int day;
        o->from = v;
        ok = il_parse_moment(v, &o->desc.start, &day, &err) == IL_OK;
        if (!ok)
            cli_error("--from: %s", err.message);
    } else if (!strcmp(a, "--latitude")) {
        ok = cli_parse_double(a, v, -90.0, 90.0, &o->desc.latitude);
        o->has_lat = true;
    } else if (!strcmp(a, "--longitude")) {
        ok = cli_parse_double(a, v, -180.0, 180.0, &o->desc.longitude);
        o->has_lon = true;
    } else if (!strcmp(a, "--hours")) {
        ok = cli_parse_double(a, v, 1.0 / 60.0, 366.0 * 24.0, &o->desc.hours);
    } else if (!strcmp(a, "--step")) {
        ok = cli_parse_double(a, v, 0.01, 60.0, &o->desc.step_minutes);
    } else if (!strcmp(a, "--min-altitude")) {
        ok = cli_parse_double(a, v, 0.0, 89.9, &o->desc.min_altitude);
    } else if (!strcmp(a, "--north")) {
        ok = cli_parse_double(a, v, -360.0, 360.0, &o->desc.north);
    } else if (!strcmp(a, "--at-least")) {
        ok = cli_parse_double(a, v, 0.0, 366.0 * 24.0, &o->at_least);
    } else if (!strcmp(a, "--threads")) {
        ok = cli_parse_u32(a, v, 1, 4096, &threads);
        o->desc.threads = (int)threads;
    } else if (!strcmp(a, "--stats")) {
        o->stats = v;
    } else {
        o->output = v;
    }
    return ok ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
}

static int parse_options(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int rc;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return -1;
        }
        if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            o->quiet = true;
            continue;
        }
        if (!takes_value(a)) {
            if ((rc = cli_scene_argument("sunhours", a, &o->scene)) != IL_EXIT_OK)
                return rc;
            continue;
        }
        const char *v = cli_value(argc, argv, &i);
        if (!v)
            return IL_EXIT_USAGE;
        if ((rc = parse_value(a, v, o)) != IL_EXIT_OK)
            return rc;
    }
    if (cli_require_scene("sunhours", o->scene) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    if (o->place.has_plane + (o->place.points != NULL) != 1) {
        cli_error("sunhours: give one of --plane AXIS=VALUE and --points FILE (see 'illum sunhours --help')");
        return IL_EXIT_USAGE;
    }
    if (!o->place.has_plane && (o->place.has_area || o->place.margin > 0.0 || o->place.spacing > 0.0)) {
        cli_error("sunhours: --area, --margin and --spacing shape a --plane grid");
        return IL_EXIT_USAGE;
    }
    if (!o->from || !o->has_lat || !o->has_lon) {
        cli_error("sunhours: give the period and the place: --from 2026-03-21T00:00+01:00 "
                  "--latitude DEG --longitude DEG");
        return IL_EXIT_USAGE;
    }
    /* The whole period within the years the sun's position covers
     * (scene/sun.c: 1900-01-01 to 2101-01-01 UTC), said now, not mid-count. */
    double end = o->desc.start + (o->desc.hours > 0.0 ? o->desc.hours : 24.0) * 3600.0;
    if (!(o->desc.start >= -2208988800.0 && end <= 4133980800.0)) {
        cli_error("--from %s with --hours: the period must lie within the years 1900 to 2100 (UTC)",
                  o->from);
        return IL_EXIT_BAD_INPUT;
    }
    const char *dot = o->output ? strrchr(o->output, '.') : NULL;
    if (o->output && !(dot && !strcasecmp(dot, ".csv"))) {
        cli_error("%s: the hours are written as .csv", o->output);
        return IL_EXIT_BAD_INPUT;
    }
    return IL_EXIT_OK;
}

/* The sensors of --plane or --points. */
static int make_sensors(options *o, const il_scene *scene, cli_sensor_grid *g)
{
    if (o->place.points)
        return cli_read_sensors(o->place.points, g);
    return cli_plane_sensors(scene, &o->place, g);
}

static int write_csv(const char *path, const cli_sensor_grid *g, const double *hours)
{
    size_t cap = 120 * g->count + 64, len = 0;
    char *text = malloc(cap);
    if (!text) {
        cli_error("%s: out of memory", path);
        return IL_EXIT_RUNTIME;
    }
    len += (size_t)snprintf(text, cap, "x,y,z,nx,ny,nz,sun_hours\n");
    for (size_t i = 0; i < g->count; i++) {
        il_vec3 p = g->sensors[i].position, n = g->sensors[i].normal;
        len += (size_t)snprintf(text + len, cap - len, "%g,%g,%g,%g,%g,%g,%.4f\n", (double)p.x, (double)p.y,
                                (double)p.z, (double)n.x, (double)n.y, (double)n.z, hours[i]);
    }
    bool ok = cli_write_text_atomic(path, text);
    free(text);
    return ok ? IL_EXIT_OK : IL_EXIT_RUNTIME;
}

typedef struct summary {
    size_t lo, hi, enough;
    double average;
} summary;

static summary summarize(const options *o, const cli_sensor_grid *g, const double *hours)
{
    summary m = {0};
    double sum = 0.0;
    for (size_t i = 0; i < g->count; i++) {
        sum += hours[i];
        m.lo = hours[i] < hours[m.lo] ? i : m.lo;
        m.hi = hours[i] > hours[m.hi] ? i : m.hi;
        m.enough += hours[i] >= o->at_least;
    }
    m.average = g->count ? sum / (double)g->count : 0.0;
    return m;
}

static void print_summary(const options *o, const cli_sensor_grid *g, const double *hours,
                          const il_sun_hours_stats *st, const summary *m)
{
    cli_print_sensors(g, &o->place);
    double period = o->desc.hours > 0.0 ? o->desc.hours : 24.0;
    if (st->stopped)
        printf("period      %.2f h of %g from %s (stopped); the sun above %g degrees for %.2f h\n",
               st->hours_done, period, o->from, o->desc.min_altitude, st->sun_up_hours);
    else
        printf("period      %g h from %s; the sun above %g degrees for %.2f h\n", period, o->from,
               o->desc.min_altitude, st->sun_up_hours);
    il_vec3 pl = g->sensors[m->lo].position, ph = g->sensors[m->hi].position;
    printf("average     %.2f h of sun\n", m->average);
    printf("minimum     %.2f h at (%g, %g, %g)\n", hours[m->lo], (double)pl.x, (double)pl.y, (double)pl.z);
    printf("maximum     %.2f h at (%g, %g, %g)\n", hours[m->hi], (double)ph.x, (double)ph.y, (double)ph.z);
    if (o->at_least > 0.0)
        printf("at least    %g h on %.1f%% of the sensors (%zu of %zu)\n", o->at_least,
               100.0 * (double)m->enough / (double)g->count, m->enough, g->count);
}

static int write_stats(const options *o, size_t sensors, const il_sun_hours_stats *st, const double *hours,
                       const summary *m)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "scene", o->scene);
    cJSON_AddStringToObject(j, "mode", o->place.points ? "points" : "plane");
    cJSON_AddNumberToObject(j, "sensors", (double)sensors);
    cJSON_AddStringToObject(j, "from", o->from);
    cJSON_AddNumberToObject(j, "hours", o->desc.hours > 0.0 ? o->desc.hours : 24.0);
    cJSON_AddNumberToObject(j, "step_minutes", o->desc.step_minutes > 0.0 ? o->desc.step_minutes : 1.0);
    cJSON_AddNumberToObject(j, "latitude", o->desc.latitude);
    cJSON_AddNumberToObject(j, "longitude", o->desc.longitude);
    cJSON_AddNumberToObject(j, "north", o->desc.north);
    cJSON_AddNumberToObject(j, "min_altitude", o->desc.min_altitude);
    cJSON_AddNumberToObject(j, "sun_up_hours", st->sun_up_hours);
    cJSON_AddNumberToObject(j, "hours_done", st->hours_done);
    cJSON_AddBoolToObject(j, "stopped", st->stopped);
    cJSON_AddNumberToObject(j, "rays", (double)st->rays);
    cJSON_AddNumberToObject(j, "seconds", st->seconds);
    cJSON *h = cJSON_AddObjectToObject(j, "sun_hours");
    cJSON_AddNumberToObject(h, "average", m->average);
    cJSON_AddNumberToObject(h, "minimum", hours[m->lo]);
    cJSON_AddNumberToObject(h, "maximum", hours[m->hi]);
    if (o->at_least > 0.0) {
        cJSON_AddNumberToObject(h, "at_least", o->at_least);
        cJSON_AddNumberToObject(h, "share_at_least", (double)m->enough / (double)sensors);
    }
    bool ok = cli_write_json(o->stats, j);
    cJSON_Delete(j);
    return ok ? IL_EXIT_OK : IL_EXIT_RUNTIME;
}

/* The progress line on a terminal; Ctrl-C stops at the next round. */
static bool on_progress(double fraction, double seconds, void *user)
{
    return cli_solve_line_update(user, seconds, false, "sunhours: %3.0f%%, %.1f s", 100.0 * fraction, seconds);
}

int cmd_sunhours(int argc, char **argv)
{
    options o;
    memset(&o, 0, sizeof o);
    int rc = parse_options(argc, argv, &o);
    if (rc != IL_EXIT_OK)
        return rc < 0 ? IL_EXIT_OK : rc;
    const char *files[2] = {o.output, o.stats};
    if ((rc = cli_check_outputs(files, 2)) != IL_EXIT_OK)
        return rc;
    /* Loaded, not committed: the sun needs no light in the scene. */
    bool quiet = o.quiet;
    il_load_desc ld = {.log = cli_log, .log_user = &quiet};
    il_scene *scene = NULL;
    il_error err = {0};
    il_status st = il_scene_load(o.scene, &ld, &scene, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    cli_sensor_grid g = {0};
    double *hours = NULL;
    if ((rc = make_sensors(&o, scene, &g)) == IL_EXIT_OK && !(hours = malloc((g.count ? g.count : 1) * sizeof *hours))) {
        cli_error("out of memory for %zu sensors", g.count);
        rc = IL_EXIT_RUNTIME;
    }
    il_sun_hours_stats stats;
    if (rc == IL_EXIT_OK) {
        cli_solve_line line;
        struct sigaction old_int;
        cli_interrupted = 0;
        cli_interrupt_catch(o.quiet, &old_int);
        cli_solve_line_start(&line, o.quiet, &cli_interrupted);
        o.desc.progress = on_progress;
        o.desc.progress_user = &line;
        st = il_sun_hours(scene, g.sensors, g.count, &o.desc, hours, &stats, &err);
        cli_solve_line_end(&line);
        cli_interrupt_release(&old_int);
        if (st != IL_OK) {
            cli_error("%s", err.message);
            rc = cli_exit_for(st);
        }
    }
    if (rc == IL_EXIT_OK) {
        summary m = summarize(&o, &g, hours);
        print_summary(&o, &g, hours, &stats, &m);
        if (!o.quiet)
            fprintf(stderr, "sunhours: %.2f s, %.3g M rays\n", stats.seconds, (double)stats.rays * 1e-6);
        if (o.output)
            rc = write_csv(o.output, &g, hours);
        if (rc == IL_EXIT_OK && o.stats)
            rc = write_stats(&o, g.count, &stats, hours, &m);
        if (rc == IL_EXIT_OK && stats.stopped)
            rc = IL_EXIT_INTERRUPTED;
    }
    free(hours);
    free(g.sensors);
    il_scene_release(scene);
    return rc;
}
