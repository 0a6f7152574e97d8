/* `illum illuminance SCENE`: light-meter readings in lux on a work plane,
 * at given points, or over what the camera sees (docs/illuminance.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

static const char *help =
    "usage: illum illuminance SCENE (--plane AXIS=VALUE | --points FILE | --surface NAME |\n"
    "                                 --view) [options]\n"
    "\n"
    "Measures the illuminance (lux) that a light meter would read, from every light\n"
    "of the scene and their interreflections, with the path tracer's paths.\n"
    "Prints the average, minimum, maximum and uniformity, and the grid of readings\n"
    "when it fits the terminal.  Sensors block no light.  Lengths are metres.\n"
    "\n"
    "where:\n"
    "  --plane AXIS=VALUE     a grid of sensors on the plane AXIS = VALUE (x, y or z),\n"
    "                         facing +AXIS; -AXIS=VALUE faces -AXIS (-y=2.4: a ceiling)\n"
    "  --area A0,B0,A1,B1     the part of the plane measured, from (A0,B0) to (A1,B1)\n"
    "                         in its two other coordinates (y plane: x,z; x: y,z;\n"
    "                         z: x,y); default: the scene's bounds\n"
    "  --margin M             keep M metres from the edges of the area (default 0)\n"
    "  --spacing S            cells of about S metres, a sensor at the centre of each;\n"
    "                         default: EN 12464-1's largest cell, 0.2 * 5^log10(d)\n"
    "  --surface NAME         sensors spread over the meshes whose name (or whose\n"
    "                         material's) contains NAME, one per --spacing^2 (default\n"
    "                         0.1 m), each on the front of its triangle; --facing +y\n"
    "                         (or any axis, or X,Y,Z) keeps the faces within 45 degrees\n"
    "  --points FILE          sensors from a text file: one 'x y z [nx ny nz]' a line\n"
    "                         (commas or spaces; normal +y when omitted; '#' comments)\n"
    "  --view                 a sensor on the surface each pixel of the camera sees:\n"
    "                         a false-colour picture (PNG, with a legend) or the lux\n"
    "                         values (EXR, HDR, PFM); --width W --height H (default\n"
    "                         512), --camera-pos/-target/-up, --fov, --camera-file as\n"
    "                         for render; --scale-max LUX tops the palette (default:\n"
    "                         a round value at the 99th percentile)\n"
    "options:\n"
    "  --samples N            paths per sensor (default 1024; with --view 64)\n"
    "  --max-depth D          bounces, the sensor counting as the first: 1 is direct\n"
    "                         light only (default 8)\n"
    "  --sampler sobol|pcg    (default sobol)\n"
    "  --seed S  --threads T  -q, --quiet\n"
    "  --stats STATS.json     the summary as JSON (the figures printed, the run's\n"
    "                         samples, rays and seconds)\n"
    "  -o OUT.csv             every reading: x,y,z,nx,ny,nz,lux,lux_error,\n"
    "                         irradiance_r,irradiance_g,irradiance_b (W/m^2);\n"
    "                         with --view: -o OUT.png|exr|hdr|pfm, up to 4 times\n";

#define MAX_OUTPUTS 4

typedef struct options {
    const char *scene, *stats, *surface;
    const char *outputs[MAX_OUTPUTS];
    int num_outputs;
    bool view;
    cli_sensor_place place;
    double scale_max;
    uint32_t width, height;
    cli_camera_options camera;
    il_illuminance_desc desc;
    il_render_desc run;               /* --seed, --threads through cli_run_option */
    cli_run_options run_opts;
    cli_env_options env;
    il_vec3 facing;                   /* --facing: zero when not given */
    il_surface_sensor_info surface_info;
} options;

/* "+y", "-x", "z" or "X,Y,Z". */
static bool parse_direction(const char *opt, const char *s, il_vec3 *out)
{
    float sign;
    const char *rest;
    int axis = cli_signed_axis(s, &sign, &rest);
    if (axis >= 0 && *rest == '\0') {
        *out = (il_vec3){axis == 0 ? sign : 0.0f, axis == 1 ? sign : 0.0f, axis == 2 ? sign : 0.0f};
        return true;
    }
    if (!cli_parse_vec3(opt, s, out))
        return false;
    if (out->x == 0.0f && out->y == 0.0f && out->z == 0.0f) {
        cli_error("%s: the direction must not be zero", opt);
        return false;
    }
    return true;
}

/* The options of this command (not the shared ones) that take a value. */
static bool takes_value(const char *a)
{
    static const char *const names[] = {"--plane", "--area", "--margin", "--spacing", "--points",
                                        "--surface", "--facing", "--width", "--height",
                                        "--scale-max", "--samples", "--max-depth", "--sampler",
                                        "--stats", "-o", "--output"};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(a, names[k]))
            return true;
    return false;
}

static int parse_options(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = NULL;
        int rc;
        if (cli_env_option(argc, argv, &i, &o->env, &rc) ||
            cli_camera_option(argc, argv, &i, &o->camera, &rc) ||
            cli_run_option(argc, argv, &i, &o->run, &o->run_opts, &rc)) {
            if (rc != IL_EXIT_OK)
                return rc;
            continue;
        }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            fputs(cli_env_help, stdout);
            return -1;
        }
        if (!strcmp(a, "--view")) {
            o->view = true;
            continue;
        }
        if (!takes_value(a)) {
            rc = cli_scene_argument("illuminance", a, &o->scene);
            if (rc != IL_EXIT_OK)
                return rc;
            continue;
        }
        if (!(v = cli_value(argc, argv, &i)))
            return IL_EXIT_USAGE;
        bool ok = true;
        if (cli_sensor_place_option(a, v, &o->place, &ok)) {
            /* --plane, --area, --margin, --spacing, --points */
        } else if (!strcmp(a, "--stats")) {
            o->stats = v;
        } else if (!strcmp(a, "--surface")) {
            if (o->surface) {
                cli_error("--surface: given twice (one a run; name several meshes with a shared "
                          "name or material instead)");
                return IL_EXIT_BAD_INPUT;
            }
            o->surface = v;
            if (!v[0]) {
                cli_error("--surface: an empty name matches no mesh (give a mesh's or material's name)");
                ok = false;
            }
        } else if (!strcmp(a, "--facing")) {
            ok = parse_direction(a, v, &o->facing);
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height")) {
            ok = cli_parse_u32(a, v, 1, 16384, !strcmp(a, "--width") ? &o->width : &o->height);
        } else if (!strcmp(a, "--scale-max")) {
            ok = cli_parse_double(a, v, 1e-9, 1e9, &o->scale_max);
        } else if (!strcmp(a, "--samples")) {
            ok = cli_parse_u32(a, v, 1, 1u << 24, &o->desc.samples);
        } else if (!strcmp(a, "--max-depth")) {
            ok = cli_parse_u32(a, v, 1, 1024, &o->desc.max_depth);
        } else if (!strcmp(a, "--sampler")) {
            ok = cli_parse_sampler(a, v, &o->desc.sampler);
        } else if (o->num_outputs == MAX_OUTPUTS) {
            cli_error("illuminance: at most %d outputs", MAX_OUTPUTS);
            return IL_EXIT_USAGE;
        } else {
            o->outputs[o->num_outputs++] = v;
        }
        if (!ok)
            return IL_EXIT_BAD_INPUT;
    }
    if (cli_require_scene("illuminance", o->scene) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    if (o->place.has_plane + (o->place.points != NULL) + (o->surface != NULL) + o->view != 1) {
        cli_error("illuminance: give one of --plane AXIS=VALUE, --points FILE, --surface NAME and "
                  "--view (see 'illum illuminance --help')");
        return IL_EXIT_USAGE;
    }
    if (!o->place.has_plane && (o->place.has_area || o->place.margin > 0.0)) {
        cli_error("illuminance: --area and --margin shape a --plane grid");
        return IL_EXIT_USAGE;
    }
    if (!o->place.has_plane && !o->surface && o->place.spacing > 0.0) {
        cli_error("illuminance: --spacing goes with --plane or --surface");
        return IL_EXIT_USAGE;
    }
    if (!o->surface && (o->facing.x != 0.0f || o->facing.y != 0.0f || o->facing.z != 0.0f)) {
        cli_error("illuminance: --facing goes with --surface");
        return IL_EXIT_USAGE;
    }
    bool camera = o->camera.file || o->camera.has_pos || o->camera.has_target ||
                  o->camera.has_up || o->camera.has_fov;
    if (!o->view && (o->width || o->height || o->scale_max > 0.0 || camera)) {
        cli_error("illuminance: --width, --height, --scale-max and the camera options go with --view");
        return IL_EXIT_USAGE;
    }
    for (int k = 0; k < o->num_outputs; k++) {
        const char *dot = strrchr(o->outputs[k], '.');
        bool csv = dot && !strcasecmp(dot, ".csv");
        bool image = dot && (!strcasecmp(dot, ".png") || !strcasecmp(dot, ".exr") ||
                             !strcasecmp(dot, ".hdr") || !strcasecmp(dot, ".pfm"));
        if (o->view ? !image : !csv) {
            cli_error("%s: %s", o->outputs[k],
                      o->view ? "--view writes .png (false colour), .exr, .hdr or .pfm (lux)"
                              : "the readings are written as .csv (images need --view)");
            return IL_EXIT_BAD_INPUT;
        }
    }
    return cli_env_check("illuminance", &o->env);
}

/* The progress line on a terminal; Ctrl-C stops at the next round. */
static bool on_progress(double fraction, double seconds, void *user)
{
    return cli_solve_line_update(user, seconds, false, "illuminance: %3.0f%%, %.1f s",
                                 100.0 * fraction, seconds);
}

static int write_csv(const char *path, const cli_sensor_grid *g, const il_illuminance *r)
{
    size_t cap = 160 * g->count + 128, len = 0;
    char *text = malloc(cap);
    if (!text) {
        cli_error("%s: out of memory", path);
        return IL_EXIT_RUNTIME;
    }
    len += (size_t)snprintf(text, cap,
                            "x,y,z,nx,ny,nz,lux,lux_error,irradiance_r,irradiance_g,irradiance_b\n");
    for (size_t i = 0; i < g->count; i++) {
        il_vec3 p = g->sensors[i].position, n = g->sensors[i].normal;
        len += (size_t)snprintf(text + len, cap - len, "%g,%g,%g,%g,%g,%g,%.6g,%.3g,%.6g,%.6g,%.6g\n",
                                (double)p.x, (double)p.y, (double)p.z, (double)n.x, (double)n.y,
                                (double)n.z, (double)r[i].lux, (double)r[i].lux_error,
                                (double)r[i].irradiance.x, (double)r[i].irradiance.y,
                                (double)r[i].irradiance.z);
    }
    bool ok = cli_write_text_atomic(path, text);
    free(text);
    return ok ? IL_EXIT_OK : IL_EXIT_RUNTIME;
}

/* Lux as people write them: whole numbers from 1000 on, else 4 digits. */
static const char *lux_text(double v, char buf[32])
{
    snprintf(buf, 32, v >= 1000.0 ? "%.0f" : "%.4g", v);
    return buf;
}

/* The figures of a plane's or a file's readings. */
typedef struct summary {
    size_t lo, hi, dark;             /* the sensors of the least and most lux; how many read 0 */
    double average, worst_rel;       /* lux; the largest standard error over its reading */
    double outdoor;                  /* the overcast sky's lux when it is the only light, else 0 */
    bool lamps_too;                  /* the overcast sky and other lights */
} summary;

static summary summarize(const il_scene *scene, const cli_sensor_grid *g, const il_illuminance *r)
{
    summary m = {0};
    double sum = 0.0;
    for (size_t i = 0; i < g->count; i++) {
        sum += r[i].lux;
        m.dark += r[i].lux == 0.0f;
        m.lo = r[i].lux < r[m.lo].lux ? i : m.lo;
        m.hi = r[i].lux > r[m.hi].lux ? i : m.hi;
        if (r[i].lux > 0.0f)
            m.worst_rel = fmax(m.worst_rel, r[i].lux_error / r[i].lux);
    }
    m.average = sum / (double)g->count;
    /* The daylight factor needs the overcast sky (--sky overcast or the
     * scene file's) as the only light: --sky-only, or a scene without
     * lamps. */
    il_sky_desc sky;
    il_scene_info info;
    il_scene_get_info(scene, &info);
    if (il_scene_get_daylight(scene, &sky) && sky.cie_type == 0) {
        if (info.num_lights == 0 && info.num_emissive_triangles == 0)
            m.outdoor = sky.horizontal_lux;
        else
            m.lamps_too = true;
    }
    return m;
}

static void print_summary(const options *o, const cli_sensor_grid *g, const il_illuminance *r,
                          const il_illuminance_stats *st, const summary *m)
{
    static const char names[] = "xyz";
    size_t lo = m->lo, hi = m->hi, dark = m->dark;
    double avg = m->average, worst_rel = m->worst_rel;
    if (o->surface)
        printf("%zu sensors on '%s': %llu triangles, %.4g m^2, one sensor per %.3g m^2\n", g->count,
               o->surface, (unsigned long long)o->surface_info.triangles, o->surface_info.area,
               o->surface_info.area / (double)g->count);
    else
        cli_print_sensors(g, &o->place);
    il_vec3 pl = g->sensors[lo].position, ph = g->sensors[hi].position;
    char b[32];
    printf("average     %s lx\n", lux_text(avg, b));
    printf("minimum     %s lx at (%g, %g, %g)\n", lux_text(r[lo].lux, b), (double)pl.x,
           (double)pl.y, (double)pl.z);
    printf("maximum     %s lx at (%g, %g, %g)\n", lux_text(r[hi].lux, b), (double)ph.x,
           (double)ph.y, (double)ph.z);
    if (avg > 0.0)
        printf("uniformity  %.3f (minimum / average), %.3f (minimum / maximum)\n",
               (double)r[lo].lux / avg, r[hi].lux > 0.0f ? (double)r[lo].lux / r[hi].lux : 0.0);
    if (m->lamps_too)
        printf("daylight    the scene's own lights count too: --sky-only gives the daylight factor\n");
    if (m->outdoor > 0.0) {
        /* The daylight factor: indoor over unobstructed outdoor horizontal
         * illuminance under the overcast sky (CIE), in per cent. */
        double out = m->outdoor;
        printf("daylight    factor %.3g%% average, %.3g%% minimum, %.3g%% maximum (%g lx outdoors)\n",
               100.0 * avg / out, 100.0 * r[lo].lux / out, 100.0 * r[hi].lux / out, out);
    }
    printf("noise       %u samples a sensor; standard error at most %.2g%% of a reading\n",
           st->samples, 100.0 * worst_rel);
    /* The readings as a plan when the grid fits 80 columns: rows from the
     * largest second coordinate down, as a plan is drawn. */
    if (g->cols && g->cols <= 10 && g->rows <= 40) {
        printf("\nlux, %c across (%.3g .. %.3g), %c down (%.3g .. %.3g):\n", names[g->axes[0]],
               (double)cli_axis_coord(g->sensors[0].position, g->axes[0]),
               (double)cli_axis_coord(g->sensors[g->cols - 1].position, g->axes[0]), names[g->axes[1]],
               (double)cli_axis_coord(g->sensors[g->count - 1].position, g->axes[1]),
               (double)cli_axis_coord(g->sensors[0].position, g->axes[1]));
        for (uint32_t row = g->rows; row-- > 0;) {
            for (uint32_t c = 0; c < g->cols; c++)
                printf("%8s", lux_text(r[(size_t)row * g->cols + c].lux, b));
            putchar('\n');
        }
    }
    if (dark && !o->run_opts.quiet)
        fprintf(stderr, "illum: warning: %zu of %zu sensors read 0 lx: inside an object, or "
                "facing away from all light?\n", dark, g->count);
}

/* --stats: the run and the figures of the summary. */
static int write_stats(const options *o, const il_scene *scene, size_t sensors, const il_illuminance_stats *st,
                       const il_illuminance *r, const summary *m, const cli_view_summary *v)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "scene", o->scene);
    cJSON_AddStringToObject(j, "mode", o->view ? "view" : o->place.points ? "points" : o->surface ? "surface" : "plane");
    cJSON_AddNumberToObject(j, "sensors", (double)sensors);
    cJSON_AddNumberToObject(j, "samples", st->samples);
    cJSON_AddNumberToObject(j, "max_depth", o->desc.max_depth ? o->desc.max_depth : 8);
    cJSON_AddNumberToObject(j, "seed", (double)o->desc.seed);
    cJSON_AddNumberToObject(j, "seconds", st->seconds);
    cJSON_AddNumberToObject(j, "rays", (double)st->rays);
    cJSON_AddNumberToObject(j, "nonfinite_samples", (double)st->nonfinite_samples);
    cJSON *lux = cJSON_AddObjectToObject(j, "lux");
    if (v) {
        cJSON_AddNumberToObject(lux, "minimum", v->minimum);
        cJSON_AddNumberToObject(lux, "median", v->median);
        cJSON_AddNumberToObject(lux, "maximum", v->maximum);
        cJSON_AddNumberToObject(lux, "palette_max", v->palette_max);
    } else {
        double lo = r[m->lo].lux, hi = r[m->hi].lux;
        cJSON_AddNumberToObject(lux, "average", m->average);
        cJSON_AddNumberToObject(lux, "minimum", lo);
        cJSON_AddNumberToObject(lux, "maximum", hi);
        cJSON_AddNumberToObject(lux, "uniformity_min_average", m->average > 0.0 ? lo / m->average : 0.0);
        cJSON_AddNumberToObject(lux, "uniformity_min_maximum", hi > 0.0 ? lo / hi : 0.0);
        cJSON_AddNumberToObject(lux, "largest_relative_error", m->worst_rel);
        cJSON_AddNumberToObject(lux, "dark_sensors", (double)m->dark);
        if (m->outdoor > 0.0) {
            cJSON *df = cJSON_AddObjectToObject(j, "daylight_factor");
            cJSON_AddNumberToObject(df, "outdoor_lux", m->outdoor);
            cJSON_AddNumberToObject(df, "average", 100.0 * m->average / m->outdoor);
            cJSON_AddNumberToObject(df, "minimum", 100.0 * lo / m->outdoor);
            cJSON_AddNumberToObject(df, "maximum", 100.0 * hi / m->outdoor);
        }
    }
    cli_sky_stats_json(j, scene);
    bool ok = cli_write_json(o->stats, j);
    cJSON_Delete(j);
    return ok ? IL_EXIT_OK : IL_EXIT_RUNTIME;
}

/* --surface: counted first, then placed. */
static int surface_sensors(options *o, const il_scene *scene, cli_sensor_grid *g)
{
    il_surface_sensor_desc d = {.name = o->surface, .facing = o->facing, .spacing = (float)o->place.spacing};
    il_error err = {0};
    il_status st = il_surface_sensors(scene, &d, NULL, 0, &o->surface_info, &err);
    if (st == IL_OK && o->surface_info.count > CLI_MAX_SENSORS) {
        cli_error("%zu sensors on '%s' are more than %u; give a larger --spacing",
                  o->surface_info.count, o->surface, CLI_MAX_SENSORS);
        return IL_EXIT_BAD_INPUT;
    }
    if (st == IL_OK && o->surface_info.count == 0) {
        cli_error("the surfaces named like '%s' (%.3g m^2) are smaller than one --spacing cell; "
                  "give a smaller --spacing", o->surface, o->surface_info.area);
        return IL_EXIT_BAD_INPUT;
    }
    if (st == IL_OK && !(g->sensors = malloc(o->surface_info.count * sizeof *g->sensors))) {
        cli_error("out of memory for %zu sensors", o->surface_info.count);
        return IL_EXIT_RUNTIME;
    }
    if (st == IL_OK)
        st = il_surface_sensors(scene, &d, g->sensors, o->surface_info.count, &o->surface_info, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    g->count = o->surface_info.count;
    return IL_EXIT_OK;
}

/* The sensors of the chosen mode: a file's, a plane's grid, or the view's
 * (view->pixel_of set). */
static int make_sensors(options *o, il_scene *scene, cli_sensor_grid *g, cli_view *view)
{
    if (o->place.points)
        return cli_read_sensors(o->place.points, g);
    if (o->surface)
        return surface_sensors(o, scene, g);
    if (o->view) {
        int rc = cli_camera_apply(scene, &o->camera);
        if (rc != IL_EXIT_OK)
            return rc;
        return cli_view_sensors(scene, o->width ? o->width : 512, o->height ? o->height : 512, g,
                                view);
    }
    return cli_plane_sensors(scene, &o->place, g);
}

int cmd_illuminance(int argc, char **argv)
{
    options o;
    memset(&o, 0, sizeof o);
    int rc = parse_options(argc, argv, &o);
    if (rc != IL_EXIT_OK)
        return rc < 0 ? IL_EXIT_OK : rc;
    const char *files[MAX_OUTPUTS + 1];
    for (int k = 0; k < o.num_outputs; k++)
        files[k] = o.outputs[k];
    files[o.num_outputs] = o.stats;
    o.camera.quiet = o.run_opts.quiet;
    if ((rc = cli_camera_read_file(&o.camera)) != IL_EXIT_OK ||
        (rc = cli_check_outputs(files, o.num_outputs + 1)) != IL_EXIT_OK)
        return rc;

    il_scene *scene = NULL;
    if ((rc = cli_load_scene_env(o.scene, o.run_opts.quiet, &o.env, &scene)) != IL_EXIT_OK)
        return rc;
    cli_sensor_grid g = {0};
    cli_view view = {0};
    rc = make_sensors(&o, scene, &g, &view);
    il_illuminance *r = rc == IL_EXIT_OK ? calloc(g.count ? g.count : 1, sizeof *r) : NULL;
    if (rc == IL_EXIT_OK && !r) {
        cli_error("out of memory for %zu readings", g.count);
        rc = IL_EXIT_RUNTIME;
    }
    if (rc != IL_EXIT_OK) {
        il_scene_release(scene);
        free(g.sensors);
        free(view.pixel_of);
        return rc;
    }

    cli_solve_line line;
    struct sigaction old_int;
    cli_interrupted = 0;
    cli_interrupt_catch(o.run_opts.quiet, &old_int);
    cli_solve_line_start(&line, o.run_opts.quiet, &cli_interrupted);
    if (o.desc.samples == 0)
        o.desc.samples = o.view ? 64u : 1024u;
    o.desc.seed = o.run.seed;
    o.desc.threads = o.run.threads;
    o.desc.progress = on_progress;
    o.desc.progress_user = &line;
    il_illuminance_stats st;
    il_error err = {0};
    il_status s = il_measure_illuminance(scene, g.sensors, g.count, &o.desc, r, &st, &err);
    cli_solve_line_end(&line);
    cli_interrupt_release(&old_int);
    if (s != IL_OK) {
        cli_error("%s", err.message);
        rc = cli_exit_for(s);
    } else {
        cli_view_summary vs;
        summary sm = {0};
        if (o.view) {
            rc = cli_view_finish(&view, &g, r, o.scale_max, o.outputs, o.num_outputs, st.samples,
                                 o.run_opts.quiet, &vs);
        } else {
            sm = summarize(scene, &g, r);
            print_summary(&o, &g, r, &st, &sm);
        }
        if (!o.run_opts.quiet)
            fprintf(stderr, "illuminance: %.2f s, %.3g M rays/s%s\n", st.seconds,
                    st.seconds > 0.0 ? (double)st.rays / st.seconds * 1e-6 : 0.0,
                    st.nonfinite_samples ? " (some samples were NaN or infinite and were dropped)" : "");
        for (int k = 0; !o.view && rc == IL_EXIT_OK && k < o.num_outputs; k++)
            rc = write_csv(o.outputs[k], &g, r);
        if (rc == IL_EXIT_OK && o.stats)
            rc = write_stats(&o, scene, g.count, &st, r, &sm, o.view ? &vs : NULL);
        if (rc == IL_EXIT_OK && cli_interrupted)
            rc = IL_EXIT_INTERRUPTED;
    }
    free(r);
    free(g.sensors);
    free(view.pixel_of);
    il_scene_release(scene);
    return rc;
}
