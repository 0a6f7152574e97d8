/* `illum render SCENE`: load, render progressively, write images and stats. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "cli/cli_mpi.h"

static const char *help =
    "usage: illum render SCENE [options]\n"
    "\n"
    "Renders SCENE (a mesh file, a .json scene file, or a built-in name: cornell,\n"
    "atrium, simple-room, shadow-room, box-room, office, cornell-spheres) through\n"
    "its camera and writes the image(s).\n"
    "\n"
    "  --method pt|radiosity|hr|photon|sppm|ibl|linespace|rsm\n"
    "                         rendering method (pt: path tracing, the default;\n"
    "                         radiosity: progressive radiosity; hr: hierarchical\n"
    "                         radiosity; photon: photon mapping; sppm: stochastic\n"
    "                         progressive photon mapping, one photon pass per spp;\n"
    "                         ibl: the environment as many directional lights;\n"
    "                         linespace: light injected into a grid of Linespaces;\n"
    "                         rsm: reflective shadow maps, one indirect bounce;\n"
    "                         'illum render --method M --help' lists a method's own\n"
    "                         options)\n"
    "  --spp N                samples per pixel (default 16; with --time: at most N)\n"
    "  --time SECONDS         render passes until SECONDS have passed\n"
    "  --width W --height H   image size in pixels (default 512 x 512)\n"
    "  --max-depth D          most bounces on a path; 1 = direct light only (default 8)\n"
    "  --seed S               random seed (default 0); same seed, same image\n"
    "  --threads T            worker threads (default: all cores)\n"
    "  --device cpu|cuda      compute device (default cpu; cuda: see docs/cuda.md and\n"
    "                         'illum info --devices')\n"
    "  --sampler sobol|pcg    sample sequence (default sobol: Owen-scrambled Sobol)\n"
    "  --filter box|gaussian  pixel filter (default box)\n"
    "  --camera-pos X,Y,Z --camera-target X,Y,Z --camera-up X,Y,Z --fov DEGREES\n"
    "                         override the scene's camera (fov is vertical)\n"
    "  --camera-file FILE     camera from a JSON file {\"position\":[..],\"target\":[..],\n"
    "                         \"up\":[..],\"fov\":deg}\n"
    "  -o, --output FILE      output image, by extension: .exr .hdr .pfm .png; may be\n"
    "                         given more than once (default SCENE-NAME.exr)\n"
    "  --exr-float            write EXR as 32-bit float (default half)\n"
    "  --exposure EV          PNG only: scale by 2^EV before the sRGB transfer (or\n"
    "                         before the tone curve of --tonemap, listed below)\n"
    "  --stats FILE           write render statistics as JSON\n"
    "  --write-every S        also write the outputs every S seconds while rendering\n"
    "                         (after the pass that crosses each mark)\n"
    "  --checkpoint-every S   under mpirun (pt): save the finished tiles every S seconds;\n"
    "                         the same command run again continues from them\n"
    "  --checkpoint FILE      the checkpoint file (default: the first output + .ckpt)\n"
    "  -q, --quiet            no progress bar and no warnings\n"
    "\n"
    "While rendering, a progress bar with ETA and rays/s is drawn on stderr when it\n"
    "is a terminal.  Ctrl-C stops after the current pass and writes what is done.\n";

#define MAX_OUTPUTS 8

typedef struct render_options {
    const char *scene;
    const char *outputs[MAX_OUTPUTS];
    int num_outputs;
    const char *stats;
    double write_every;              /* --write-every seconds; 0: only at the end */
    cli_mpi_job mpi;                 /* --checkpoint, --checkpoint-every (under mpirun) */
    uint32_t width, height;
    il_render_desc desc;
    il_write_desc write;
    cli_tonemap_options tm;          /* --tonemap and the rest: PNG outputs */
    cli_run_options run;             /* --spp, --max-depth, --seed, --threads, --quiet */
    bool cuda;                       /* --device cuda */
    cli_camera_options camera;       /* --camera-* and --fov */
    bool has_method;
    cli_method_options m;            /* each method's own options */
    cli_env_options env;             /* --env and its settings */
} render_options;

typedef struct progress_state {
    bool draw;
    bool drawn;
    bool lights;                     /* ibl: passes_done counts lights */
    const render_options *o;         /* outputs written by --write-every */
    double next_write;               /* render seconds of the next --write-every write */
} progress_state;

/* --write-every: every output written like the final one (each file
 * atomically replaced); a failure is a warning, the render goes on. */
static void write_running_outputs(const il_image *img, void *user)
{
    const render_options *o = user;
    il_error err = {0};
    il_status st = IL_OK;
    for (int i = 0; st == IL_OK && i < o->num_outputs; i++)
        st = il_image_write(img, o->outputs[i], &o->write, &err);
    if (st != IL_OK)
        cli_error("warning: writing the running image: %s", err.message);
}

/* The film is complete after every pass, so the running image is its
 * resolved image (a GPU render hands its own: cli_running_image). */
static void write_running_image(progress_state *ps, const il_render_progress *p)
{
    const render_options *o = ps->o;
    if (!o || !(o->write_every > 0.0) || !p->film || p->seconds < ps->next_write)
        return;
    while (ps->next_write <= p->seconds)
        ps->next_write += o->write_every;
    il_error err = {0};
    il_image img = {0};
    if (il_film_resolve(p->film, &img, &err) == IL_OK)
        write_running_outputs(&img, (void *)o);
    else
        cli_error("warning: writing the running image: %s", err.message);
    il_image_free(&img);
}

static bool on_progress(const il_render_progress *p, void *user)
{
    progress_state *ps = user;
    write_running_image(ps, p);
    if (ps->draw) {
        double frac = p->passes_total ? (double)p->passes_done / p->passes_total : 0.0;
        if (p->time_limit > 0.0) {
            double tf = p->seconds / p->time_limit;
            frac = frac > tf ? frac : tf;
        }
        if (frac > 1.0)
            frac = 1.0;
        double eta = frac > 0.0 ? p->seconds * (1.0 - frac) / frac : 0.0;
        double mrays = p->seconds > 0.0 ? (double)p->rays / p->seconds * 1e-6 : 0.0;
        char bar[31];
        int filled = (int)(frac * 30.0);
        for (int i = 0; i < 30; i++)
            bar[i] = i < filled ? '#' : '.';
        bar[30] = '\0';
        fprintf(stderr, "\r[%s] %3d%%  %u %s  %.1fs  ETA %.1fs  %.2f Mrays/s   ", bar,
                (int)(frac * 100.0), p->passes_done, ps->lights ? "lights" : "spp", p->seconds, eta,
                mrays);
        fflush(stderr);
        ps->drawn = true;
    }
    return !cli_interrupted;
}

/* A half EXR holds magnitudes up to IL_EXR_HALF_MAX, and the writer clamps
 * to it: says so when a pixel is brighter (a camera that sees the sun). */
static void warn_half_exr(const il_image *img, const render_options *o)
{
    bool half_exr = false;
    for (int i = 0; i < o->num_outputs; i++) {
        const char *dot = strrchr(o->outputs[i], '.');
        half_exr |= dot && !strcasecmp(dot, ".exr") && o->write.exr_precision != IL_EXR_FLOAT;
    }
    if (!half_exr || o->run.quiet)
        return;
    size_t clamped = 0, pixels = (size_t)img->width * img->height;
    for (size_t p = 0; p < pixels; p++) {
        const float *c = img->rgb + 3 * p;
        clamped += fabsf(c[0]) > IL_EXR_HALF_MAX || fabsf(c[1]) > IL_EXR_HALF_MAX ||
                   fabsf(c[2]) > IL_EXR_HALF_MAX;
    }
    if (clamped)
        cli_error("warning: %zu pixel%s brighter than %g, the most a half EXR holds, written as %g "
                  "(--exr-float keeps them)", clamped, clamped == 1 ? " is" : "s are",
                  (double)IL_EXR_HALF_MAX, (double)IL_EXR_HALF_MAX);
}

static bool known_image_extension(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (!dot)
        return false;
    return !strcasecmp(dot, ".exr") || !strcasecmp(dot, ".hdr") || !strcasecmp(dot, ".pfm") ||
           !strcasecmp(dot, ".png");
}

/* A method's own options need that method.  Without --method a JSON
 * scene's "render" block may still choose it, so cmd_render checks again
 * (final) once the scene is loaded. */
static int check_method_options(const render_options *o, bool final)
{
    if (!o->has_method && !final)
        return IL_EXIT_OK;
    if (o->m.rad.note.given && o->desc.method != IL_METHOD_RADIOSITY)
        return cli_method_mismatch("render", &o->m.rad.note, "radiosity", "radiosity");
    if (o->m.hr.note.given && o->desc.method != IL_METHOD_HR)
        return cli_method_mismatch("render", &o->m.hr.note, "hierarchical radiosity", "hr");
    if (o->m.ibl.note.given && o->desc.method != IL_METHOD_IBL)
        return cli_method_mismatch("render", &o->m.ibl.note, "many-light environment", "ibl");
    if (o->m.linespace.note.given && o->desc.method != IL_METHOD_LINESPACE)
        return cli_method_mismatch("render", &o->m.linespace.note, "linespace", "linespace");
    if (o->m.rsm.note.given && o->desc.method != IL_METHOD_RSM)
        return cli_method_mismatch("render", &o->m.rsm.note, "reflective shadow map", "rsm");
    int rc = cli_method_light_paths_check("render", &o->m, o->desc.method);
    return rc != IL_EXIT_OK ? rc : cli_photon_check_method("render", &o->m.photon, o->desc.method);
}

static int parse_options(int argc, char **argv, render_options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = NULL;
        int opt_rc;
        if (cli_tonemap_option(argc, argv, &i, false, &o->tm, &opt_rc) ||
            cli_method_options_parse(argc, argv, &i, &o->m, &opt_rc)) {
            if (opt_rc != IL_EXIT_OK)
                return opt_rc;
            continue;
        }
        if (cli_env_option(argc, argv, &i, &o->env, &opt_rc) ||
            cli_camera_option(argc, argv, &i, &o->camera, &opt_rc) ||
            cli_run_option(argc, argv, &i, &o->desc, &o->run, &opt_rc)) {
            if (opt_rc != IL_EXIT_OK)
                return opt_rc;
            continue;
        }
#define VALUE()                                   \
    do {                                          \
        if (!(v = cli_value(argc, argv, &i)))     \
            return IL_EXIT_USAGE;                 \
    } while (0)
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            fputs(cli_tonemap_help, stdout);
            fputs(cli_env_help, stdout);
            if (cli_help_wants_method(argc, argv, "radiosity"))
                fputs(cli_radiosity_help, stdout);
            if (cli_help_wants_method(argc, argv, "hr"))
                fputs(cli_hr_help, stdout);
            if (cli_help_wants_method(argc, argv, "photon") || cli_help_wants_method(argc, argv, "sppm"))
                fputs(cli_photon_help, stdout);
            if (cli_help_wants_method(argc, argv, "ibl"))
                fputs(cli_ibl_help, stdout);
            if (cli_help_wants_method(argc, argv, "linespace"))
                fputs(cli_linespace_help, stdout);
            if (cli_help_wants_method(argc, argv, "rsm"))
                fputs(cli_rsm_help, stdout);
            return -1;
        } else if (!strcmp(a, "--method")) {
            VALUE();
            if (!cli_method_from_name(v, &o->desc.method)) {
                cli_error("--method: unknown method '%s' "
                          "(available: " CLI_METHOD_NAMES ")", v);
                return IL_EXIT_BAD_INPUT;
            }
            o->has_method = true;
        } else if (!strcmp(a, "--time")) {
            VALUE();
            if (!cli_parse_double(a, v, 1e-3, 1e7, &o->desc.time_limit))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--width")) {
            VALUE();
            if (!cli_parse_u32(a, v, 1, 16384, &o->width))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--height")) {
            VALUE();
            if (!cli_parse_u32(a, v, 1, 16384, &o->height))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--device")) {
            VALUE();
            if (!cli_device_from_name(v, &o->cuda)) {
                cli_error("--device: unknown device '%s' (available: cpu, cuda)", v);
                return IL_EXIT_BAD_INPUT;
            }
        } else if (!strcmp(a, "--sampler")) {
            VALUE();
            if (!cli_parse_sampler(a, v, &o->desc.sampler))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--filter")) {
            VALUE();
            if (!strcmp(v, "box"))
                o->desc.filter = IL_FILTER_BOX;
            else if (!strcmp(v, "gaussian"))
                o->desc.filter = IL_FILTER_GAUSSIAN;
            else {
                cli_error("--filter: expected box or gaussian, got '%s'", v);
                return IL_EXIT_BAD_INPUT;
            }
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            VALUE();
            if (o->num_outputs == MAX_OUTPUTS) {
                cli_error("at most %d outputs", MAX_OUTPUTS);
                return IL_EXIT_USAGE;
            }
            if (!known_image_extension(v)) {
                cli_error("%s: unknown image format (use .exr, .hdr, .pfm or .png)", v);
                return IL_EXIT_BAD_INPUT;
            }
            o->outputs[o->num_outputs++] = v;
        } else if (!strcmp(a, "--write-every")) {
            VALUE();
            if (!cli_parse_double(a, v, 0.001, 1e9, &o->write_every))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--checkpoint-every")) {
            VALUE();
            if (!cli_parse_double(a, v, 0.001, 1e9, &o->mpi.checkpoint_every))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--checkpoint")) {
            VALUE();
            o->mpi.checkpoint = v;
        } else if (!strcmp(a, "--exr-float")) {
            o->write.exr_precision = IL_EXR_FLOAT;
        } else if (!strcmp(a, "--exposure")) {
            VALUE();
            double ev;
            if (!cli_parse_exposure(a, v, &ev))
                return IL_EXIT_BAD_INPUT;
            o->write.exposure = (float)ev;
        } else if (!strcmp(a, "--stats")) {
            VALUE();
            o->stats = v;
        } else {
            int rc = cli_scene_argument("render", a, &o->scene);
            if (rc != IL_EXIT_OK)
                return rc;
        }
#undef VALUE
    }
    if (cli_require_scene("render", o->scene) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    if (cli_env_check("render", &o->env) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    int tm_rc = cli_tonemap_check("render", &o->tm);
    if (tm_rc != IL_EXIT_OK)
        return tm_rc;
    return check_method_options(o, false);
}

/* SCENE-NAME.exr in the current directory: the file name without folder and extension. */
static void default_output(const char *scene, char *buf, size_t size)
{
    const char *base = strrchr(scene, '/');
    base = base ? base + 1 : scene;
    const char *dot = strrchr(base, '.');
    int len = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(buf, size, "%.*s.exr", len, base);
}

/* A JSON scene's "render" block supplies what the command line left unset. */
static int apply_scene_settings(const il_scene *scene, render_options *o)
{
    il_render_settings rs;
    if (!il_scene_get_render_settings(scene, &rs))
        return IL_EXIT_OK;
    int rc = cli_run_apply_settings(o->scene, &rs, o->has_method, &o->run, &o->desc);
    if (rc != IL_EXIT_OK)
        return rc;
    if (o->width == 0)
        o->width = rs.width;
    if (o->height == 0)
        o->height = rs.height;
    if (o->desc.spp == 0 && o->desc.time_limit == 0.0) {
        o->desc.spp = rs.spp;
        o->desc.time_limit = rs.time_limit;
    }
    return IL_EXIT_OK;
}

static bool write_stats(const render_options *o, const il_render_stats *rs, const il_scene *scene,
                        double wall)
{
    il_scene_info in;
    il_scene_get_info(scene, &in);
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "scene", o->scene);
    cJSON_AddStringToObject(j, "method", cli_method_name(o->desc.method));
    cJSON_AddNumberToObject(j, "width", o->width);
    cJSON_AddNumberToObject(j, "height", o->height);
    cJSON_AddNumberToObject(j, "spp", rs->spp);
    cJSON_AddNumberToObject(j, "max_depth", o->desc.max_depth ? o->desc.max_depth : 8);
    cJSON_AddNumberToObject(j, "seed", (double)o->desc.seed);
    cJSON_AddNumberToObject(j, "threads", o->desc.threads);
    cJSON_AddNumberToObject(j, "triangles", (double)in.num_triangles);
    cJSON_AddNumberToObject(j, "render_seconds", rs->seconds);
    cJSON_AddNumberToObject(j, "total_seconds", wall);
    cJSON_AddNumberToObject(j, "rays", (double)rs->rays);
    double secs = rs->seconds > 0.0 ? rs->seconds : 1e-9;
    cJSON_AddNumberToObject(j, "rays_per_second", (double)rs->rays / secs);
    cJSON_AddNumberToObject(j, "samples_per_second",
                            (double)o->width * o->height * rs->spp / secs);
    cJSON_AddBoolToObject(j, "interrupted", cli_interrupted != 0);
    cJSON *outs = cJSON_AddArrayToObject(j, "outputs");
    for (int i = 0; i < o->num_outputs; i++)
        cJSON_AddItemToArray(outs, cJSON_CreateString(o->outputs[i]));
    if (o->desc.method == IL_METHOD_RADIOSITY)
        cli_radiosity_stats_json(j, &rs->radiosity);
    else if (o->desc.method == IL_METHOD_HR)
        cli_hr_stats_json(j, &rs->hr);
    else if (o->desc.method == IL_METHOD_PHOTON || o->desc.method == IL_METHOD_SPPM)
        cli_photon_stats_json(j, &rs->photon);
    else if (o->desc.method == IL_METHOD_IBL)
        cli_ibl_stats_json(j, &o->m.ibl.desc, &rs->ibl);
    else if (o->desc.method == IL_METHOD_LINESPACE)
        cli_linespace_stats_json(j, &rs->linespace);
    else if (o->desc.method == IL_METHOD_RSM)
        cli_rsm_stats_json(j, &o->m.rsm.desc, &rs->rsm);
    cli_sky_stats_json(j, scene);
    bool ok = cli_write_json(o->stats, j);
    cJSON_Delete(j);
    return ok;
}

int cmd_render(int argc, char **argv)
{
    double t0 = cli_now_seconds();
    render_options o = {.run.sampling = true};
    int rc = parse_options(argc, argv, &o);
    if (rc == -1)
        return IL_EXIT_OK;
    if (rc != IL_EXIT_OK)
        return rc;
    if (o.cuda && (rc = cli_device_require_cuda()) != IL_EXIT_OK)
        return rc;
    if (cli_mpi_rank() > 0)
        o.run.quiet = true; /* under mpirun only rank 0 reports */
    if ((o.mpi.checkpoint_every > 0.0 || o.mpi.checkpoint) && !cli_mpi_active()) {
        cli_error("--checkpoint-every and --checkpoint work under mpirun (mpirun -np 1 for one process)");
        return IL_EXIT_USAGE;
    }
    o.camera.quiet = o.run.quiet;
    if ((rc = cli_camera_read_file(&o.camera)) != IL_EXIT_OK)
        return rc;
    char default_out[512];
    if (o.num_outputs == 0) {
        default_output(o.scene, default_out, sizeof default_out);
        o.outputs[o.num_outputs++] = default_out;
    }
    o.mpi.output = o.outputs[0];
    o.mpi.write_every = o.write_every;
    if (cli_mpi_rank() == 0) {
        /* A folder that is missing or read-only is found now, not after the render. */
        const char *files[MAX_OUTPUTS + 2] = {o.stats, o.mpi.checkpoint};
        memcpy(files + 2, o.outputs, (size_t)o.num_outputs * sizeof *files);
        if ((rc = cli_check_outputs(files, o.num_outputs + 2)) != IL_EXIT_OK)
            return rc;
    }

    il_scene *scene = NULL;
    if ((rc = cli_load_scene_env(o.scene, o.run.quiet, &o.env, &scene)) != IL_EXIT_OK)
        return rc;
    if ((rc = apply_scene_settings(scene, &o)) != IL_EXIT_OK ||
        (rc = check_method_options(&o, true)) != IL_EXIT_OK) {
        il_scene_release(scene);
        return rc;
    }
    if (o.width == 0)
        o.width = 512;
    if (o.height == 0)
        o.height = 512;
    if ((rc = cli_camera_apply(scene, &o.camera)) != IL_EXIT_OK) {
        il_scene_release(scene);
        return rc;
    }

    il_error err = {0};
    il_film *film = NULL;
    if (il_film_create(o.width, o.height, &film, &err) != IL_OK) {
        cli_error("%s", err.message);
        il_scene_release(scene);
        return cli_exit_for(err.status);
    }
    o.write.tonemap = cli_tonemap_desc(&o.tm, o.write.exposure);
    progress_state ps = {.draw = !o.run.quiet && isatty(STDERR_FILENO), .o = &o,
                         .next_write = o.write_every};
    o.desc.progress = on_progress;
    o.desc.progress_user = &ps;
    if (o.desc.method == IL_METHOD_RADIOSITY) {
        /* The solve draws its own line and ends early on Ctrl-C; the camera
         * pass after it draws the usual bar. */
        cli_radiosity_install_progress(&o.m.rad, o.run.quiet, &cli_interrupted);
    } else if (o.desc.method == IL_METHOD_HR) {
        cli_hr_install_progress(&o.m.hr, o.run.quiet, &cli_interrupted);
    } else if (o.desc.method == IL_METHOD_PHOTON) {
        cli_photon_install_progress(&o.m.photon, o.run.quiet, &cli_interrupted);
    } else if (o.desc.method == IL_METHOD_LINESPACE) {
        cli_linespace_install_progress(&o.m.linespace, o.run.quiet, &cli_interrupted);
    }
    cli_method_options_install(&o.m, &o.desc);
    ps.lights = o.desc.method == IL_METHOD_IBL;
    struct sigaction old_sa;
    cli_interrupt_catch(o.run.quiet, &old_sa);

    il_render_stats rs = {0};
    il_image cuda_img = {0};
    cli_running_image running = {.every = o.write_every, .write = write_running_outputs, .user = &o};
    il_status st = o.cuda             ? cli_device_render_cuda(scene, &o.desc, o.width, o.height, &running,
                                                               &cuda_img, &rs, &err)
                   : cli_mpi_active() ? cli_mpi_render(scene, film, &o.desc, &o.mpi, &rs, !o.run.quiet, &err)
                                      : il_render(scene, film, &o.desc, &rs, &err);
    cli_interrupt_release(&old_sa);
    cli_radiosity_end_progress(&o.m.rad);
    cli_hr_end_progress(&o.m.hr);
    cli_photon_end_progress(&o.m.photon);
    cli_linespace_end_progress(&o.m.linespace);
    if (ps.drawn)
        fputc('\n', stderr);
    if (cli_mpi_rank() > 0) { /* rank 0 writes the outputs and reports errors */
        il_film_release(film);
        il_scene_release(scene);
        return st == IL_OK ? IL_EXIT_OK : cli_exit_for(st);
    }
    if (st != IL_OK) {
        cli_error("%s", err.message);
        il_film_release(film);
        il_scene_release(scene);
        return cli_exit_for(st);
    }

    il_image img = cuda_img;
    st = o.cuda ? IL_OK : il_film_resolve(film, &img, &err);
    for (int i = 0; st == IL_OK && i < o.num_outputs; i++)
        st = il_image_write(&img, o.outputs[i], &o.write, &err);
    if (st == IL_OK)
        warn_half_exr(&img, &o);
    il_image_free(&img);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        il_film_release(film);
        il_scene_release(scene);
        return cli_exit_for(st);
    }
    if (!o.run.quiet) {
        if (o.desc.method == IL_METHOD_RADIOSITY)
            cli_radiosity_summary(&rs.radiosity);
        else if (o.desc.method == IL_METHOD_HR)
            cli_hr_summary(&rs.hr);
        else if (o.desc.method == IL_METHOD_PHOTON || o.desc.method == IL_METHOD_SPPM)
            cli_photon_summary(o.desc.method, &rs.photon);
        else if (o.desc.method == IL_METHOD_IBL)
            cli_ibl_summary(&o.m.ibl.desc, &rs.ibl);
        else if (o.desc.method == IL_METHOD_LINESPACE)
            cli_linespace_summary(&rs.linespace);
        else if (o.desc.method == IL_METHOD_RSM)
            cli_rsm_summary(&o.m.rsm.desc, &rs.rsm);
        /* Radiosity's solve casts rays it does not count (or none, with
         * the hemicube) and hr's counts them apart: their camera rays over
         * the whole time would be no ray rate at all. */
        bool ray_rate = o.desc.method != IL_METHOD_RADIOSITY && o.desc.method != IL_METHOD_HR;
        fprintf(stderr, "illum: %u spp in %.2f s (", rs.spp, rs.seconds);
        if (ray_rate)
            fprintf(stderr, "%.3g Mrays/s, ", rs.seconds > 0 ? (double)rs.rays / rs.seconds * 1e-6 : 0.0);
        fprintf(stderr, "%.3g Msamples/s) -> ",
                rs.seconds > 0 ? (double)o.width * o.height * rs.spp / rs.seconds * 1e-6 : 0.0);
        for (int i = 0; i < o.num_outputs; i++)
            fprintf(stderr, "%s%s", i ? ", " : "", o.outputs[i]);
        fputc('\n', stderr);
    }
    rc = IL_EXIT_OK;
    if (o.stats && !write_stats(&o, &rs, scene, cli_now_seconds() - t0))
        rc = IL_EXIT_BAD_INPUT;
    il_film_release(film);
    il_scene_release(scene);
    if (rc == IL_EXIT_OK && cli_interrupted) {
        if (o.desc.method == IL_METHOD_RADIOSITY)
            cli_error("interrupted: the radiosity solve stopped at %.3g%% unshot; the image of "
                      "that solution is written",
                      100.0 * rs.radiosity.unshot_fraction);
        else if (o.desc.method == IL_METHOD_HR && rs.hr.stopped)
            cli_error("interrupted: the hr solve stopped after %u iteration%s%s; the image of "
                      "that solution is written",
                      rs.hr.iterations, rs.hr.iterations == 1 ? "" : "s",
                      rs.hr.iterations == 0 ? " (no light exchanged between surfaces yet)" : "");
        else if (o.desc.method == IL_METHOD_PHOTON && rs.photon.stopped)
            cli_error("interrupted: photon mapping's set-up stopped after %llu photons; the image "
                      "with those is written",
                      (unsigned long long)rs.photon.emitted);
        else if (o.desc.method == IL_METHOD_LINESPACE && rs.linespace.stopped)
            cli_error("interrupted: the Linespace injection stopped after %llu light paths; the "
                      "image with those is written",
                      (unsigned long long)rs.linespace.inject_rays);
        else
            cli_error("interrupted after %u spp; the image so far is written", rs.spp);
        return IL_EXIT_INTERRUPTED;
    }
    return rc;
}
