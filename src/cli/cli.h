/* Shared pieces of the `illum` program: exit codes, option parsing, logging. */
#ifndef IL_CLI_CLI_H
#define IL_CLI_CLI_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "illum/illum.h"

struct cJSON;

/* Exit status of every sub-command (docs/cli.md). */
enum {
    IL_EXIT_OK = 0,
    IL_EXIT_BAD_INPUT = 1,   /* scene, file or option value */
    IL_EXIT_USAGE = 2,       /* unknown command or option, missing argument */
    IL_EXIT_RUNTIME = 3,     /* the render or a dependency failed */
    IL_EXIT_DIFFERENT = 4,   /* compare: images differ more than --max-rmse/--max-rel-mse */
    IL_EXIT_INTERRUPTED = 130
};

/* Prints "illum: <message>" to stderr. */
void cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Parsers of option values; on failure they print which option and why and return false. */
bool cli_parse_u32(const char *opt, const char *s, uint32_t min, uint32_t max, uint32_t *out);
bool cli_parse_u64(const char *opt, const char *s, uint64_t *out);
/* A count in [1, 10^10] (photons, light paths): "out of range" otherwise. */
bool cli_parse_count(const char *opt, const char *s, uint64_t *out);
bool cli_parse_double(const char *opt, const char *s, double min, double max, double *out);
bool cli_parse_vec3(const char *opt, const char *s, il_vec3 *out);
/* n finite numbers separated by commas into out; the message says "expected FORM". */
bool cli_parse_numbers(const char *opt, const char *s, int n, const char *form, double *out);
/* "sobol" or "pcg" (--sampler). */
bool cli_parse_sampler(const char *opt, const char *s, il_sampler_type *out);
bool cli_parse_on_off(const char *opt, const char *s, bool *out); /* "on" or "off" */

/* Argument cursor: fetches the value after option argv[*i], or reports a usage error. */
const char *cli_value(int argc, char **argv, int *i);

/* An argument no option of command `cmd` took: an unknown option is a
 * usage error, else it is the scene (one at most).  Returns IL_EXIT_OK or
 * IL_EXIT_USAGE (message printed). */
int cli_scene_argument(const char *cmd, const char *arg, const char **scene);
/* After the arguments: IL_EXIT_OK when a scene was given, else a usage error. */
int cli_require_scene(const char *cmd, const char *scene);

/* The log callback that prints loader warnings ("illum: warning: ...") unless quiet. */
void cli_log(il_log_level level, const char *message, void *user);

/* The reason a radiosity or hr solve that stopped converging gives. */
#define CLI_NO_FINITE_SOLUTION \
    "light that cannot leave the scene, such as a closed room of albedo 1, has no finite solution"

/* Exit status for an il_status. */
int cli_exit_for(il_status st);

/* Seconds on the monotonic clock, for the durations the commands report. */
double cli_now_seconds(void);

/* Writes text to path through a temporary file and a rename. */
bool cli_write_text_atomic(const char *path, const char *text);
/* The folder of path into dir: "." for a bare name, "/" for one in the root. */
void cli_folder_of(const char *path, char *dir, size_t size);

/* Before a command spends time: each non-NULL path of `paths` can be written
 * (il_atomic_check).  Prints the first problem and returns its exit status. */
int cli_check_outputs(const char *const *paths, int n);

/* Loads SCENE (file or built-in name) and commits it, printing errors. */
int cli_load_scene(const char *path, bool quiet, il_scene **out);

/* Writes a JSON object, pretty-printed with a final newline, atomically. */
bool cli_write_json(const char *path, struct cJSON *json);

/* Method names and the pieces every method's own option set shares (cli_method.c). */
bool cli_method_from_name(const char *name, il_method *out); /* one of CLI_METHOD_NAMES */
#define CLI_METHOD_NAMES "pt, radiosity, hr, photon, sppm, ibl, linespace, rsm"
const char *cli_method_name(il_method method);

/* Which options of one method's set the command line gave. */
typedef struct cli_method_note {
    bool given;
    const char *first;               /* the first one given, for messages */
} cli_method_note;

/* When argv[*i] is one of names[0..n-1], returns that name and consumes its
 * value into *value (NULL after a usage message when it is missing), noting
 * the option in *note; returns NULL when argv[*i] is none of them. */
const char *cli_method_option(int argc, char **argv, int *i, const char *const *names, size_t n,
                              cli_method_note *note, const char **value);
/* True when the command line has "--method METHOD" (for --help). */
bool cli_help_wants_method(int argc, char **argv, const char *method);
/* Prints "OPTION is a LABEL option; it needs --method METHOD (see 'illum
 * COMMAND --method METHOD --help')" and returns IL_EXIT_USAGE. */
int cli_method_mismatch(const char *command, const cli_method_note *note, const char *label,
                        const char *method);

/* Ctrl-C during render and bake (cli_interrupt.c): the first sets
 * cli_interrupted (the work stops early and its result is written) and says
 * that a second one quits at once, without output (SIGINT's default action
 * is restored). */
extern volatile sig_atomic_t cli_interrupted;
void cli_interrupt_catch(bool quiet, struct sigaction *old);
void cli_interrupt_release(const struct sigaction *old);

/* The progress line of a radiosity or hr solve (before the camera pass's
 * bar), redrawn in place on a terminal at most ten times a second, and the
 * Ctrl-C flag that ends the solve early (cli_common.c). */
typedef struct cli_solve_line {
    bool draw, drawn;
    double last_draw;                /* solve seconds when it was last drawn */
    const volatile sig_atomic_t *stop; /* set by Ctrl-C */
} cli_solve_line;

void cli_solve_line_start(cli_solve_line *l, bool quiet, const volatile sig_atomic_t *stop);
/* Draws the printf-style text when due (or when `now` is true); returns
 * false once Ctrl-C asked to stop. */
bool cli_solve_line_update(cli_solve_line *l, double seconds, bool now, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* Ends the line (a newline after the last drawing). */
void cli_solve_line_end(cli_solve_line *l);

/* The radiosity options (cli_radiosity.c), shared by render and bake. */
typedef struct cli_radiosity_options {
    il_radiosity_desc desc;
    cli_method_note note;            /* any radiosity option on the command line */
    cli_solve_line line;
} cli_radiosity_options;

extern const char cli_radiosity_help[];
/* When argv[*i] is a radiosity option, consumes it (and its value), sets *rc
 * to IL_EXIT_OK or the exit status of a bad value, and returns true. */
bool cli_radiosity_option(int argc, char **argv, int *i, cli_radiosity_options *o, int *rc);
/* Installs desc.on_step: "radiosity: step N, unshot X%" on a terminal unless
 * quiet; the solve stops early once *stop is set. */
void cli_radiosity_install_progress(cli_radiosity_options *o, bool quiet,
                                    const volatile sig_atomic_t *stop);
void cli_radiosity_end_progress(cli_radiosity_options *o);
/* "auto", "hemicube" or "raycast": the words of --form-factors. */
const char *cli_form_factor_name(il_form_factor_method method);
/* Adds the "radiosity" object of --stats to `parent`. */
void cli_radiosity_stats_json(struct cJSON *parent, const il_radiosity_stats *stats);
/* One line on stderr: patches, steps, unshot fraction, time per phase. */
void cli_radiosity_summary(const il_radiosity_stats *stats);

/* The hierarchical-radiosity options (cli_hr.c), shared by render and bake. */
typedef struct cli_hr_options {
    il_hr_desc desc;
    cli_method_note note;            /* any hr option on the command line */
    cli_solve_line line;
} cli_hr_options;

extern const char cli_hr_help[];
/* As cli_radiosity_option, for --bf-eps, --area-eps, --energy-eps,
 * --vis-rays and --max-iterations. */
bool cli_hr_option(int argc, char **argv, int *i, cli_hr_options *o, int *rc);
/* Installs desc.on_step: "hr: iteration N, ..." on a terminal unless quiet;
 * the solve stops early once *stop is set. */
void cli_hr_install_progress(cli_hr_options *o, bool quiet, const volatile sig_atomic_t *stop);
void cli_hr_end_progress(cli_hr_options *o);
/* Adds the "hr" object of --stats (every il_hr_stats field) to `parent`. */
void cli_hr_stats_json(struct cJSON *parent, const il_hr_stats *stats);
/* One line on stderr: patches, elements, links, iterations, rays, time per phase. */
void cli_hr_summary(const il_hr_stats *stats);

/* The photon-mapping options (cli_photon.c), for render. */
typedef struct cli_photon_options {
    il_photon_desc desc;
    cli_method_note note;            /* an option of both photon and sppm */
    cli_method_note photon_only;     /* --k, --photon-filter, --final-gather */
    cli_method_note sppm_only;       /* --alpha, --initial-radius */
    cli_solve_line line;             /* photon's set-up */
} cli_photon_options;

extern const char cli_photon_help[];
/* As cli_radiosity_option, for the options cli_photon_help lists. */
bool cli_photon_option(int argc, char **argv, int *i, cli_photon_options *o, int *rc);
/* The usage error when an option given does not belong to `method`. */
int cli_photon_check_method(const char *command, const cli_photon_options *o, il_method method);
/* Installs desc.on_step (--method photon's set-up): "photon: tracing N / M"
 * on a terminal unless quiet; the set-up stops early once *stop is set. */
void cli_photon_install_progress(cli_photon_options *o, bool quiet,
                                 const volatile sig_atomic_t *stop);
void cli_photon_end_progress(cli_photon_options *o);
/* Adds the "photon" object of --stats (every il_photon_stats field) to `parent`. */
void cli_photon_stats_json(struct cJSON *parent, const il_photon_stats *stats);
/* One line on stderr: photons, rate, maps, time per phase. */
void cli_photon_summary(il_method method, const il_photon_stats *stats);

/* The many-light environment options (cli_ibl.c), for render --method ibl. */
typedef struct cli_ibl_options {
    il_ibl_desc desc;
    cli_method_note note;            /* any ibl option on the command line */
} cli_ibl_options;

extern const char cli_ibl_help[];
/* As cli_radiosity_option, for --lights, --light-selection, --shadows,
 * --batch, --shadow-map-size, --shadow-bias and --pcf. */
bool cli_ibl_option(int argc, char **argv, int *i, cli_ibl_options *o, int *rc);
/* Adds the "ibl" object of --stats (the options in effect and every
 * il_ibl_stats field) to `parent`. */
void cli_ibl_stats_json(struct cJSON *parent, const il_ibl_desc *desc, const il_ibl_stats *stats);
/* One line on stderr: lights, selection, shadows, shadow rays, time per phase. */
void cli_ibl_summary(const il_ibl_desc *desc, const il_ibl_stats *stats);

/* The Linespace options (cli_linespace.c), for render --method linespace. */
typedef struct cli_linespace_options {
    il_linespace_desc desc;
    cli_method_note note;            /* any linespace option on the command line */
    cli_solve_line line;             /* the light injection */
} cli_linespace_options;

extern const char cli_linespace_help[];
/* As cli_radiosity_option, for --grid, --linespace-n, --inject-rays,
 * --inject-depth, --blur, --occlusion-test, --fallback, --solid-angle,
 * --coarse, --coarse-below, --trace-first-bounce, --glossy-n1 and --glossy-n2. */
bool cli_linespace_option(int argc, char **argv, int *i, cli_linespace_options *o, int *rc);
/* Adds the "linespace" object of --stats (every il_linespace_stats field). */
void cli_linespace_stats_json(struct cJSON *parent, const il_linespace_stats *stats);
/* Installs desc.on_step: "linespace: injecting N / M light paths" on a
 * terminal unless quiet; the injection stops early once *stop is set. */
void cli_linespace_install_progress(cli_linespace_options *o, bool quiet,
                                    const volatile sig_atomic_t *stop);
void cli_linespace_end_progress(cli_linespace_options *o);
/* One line on stderr: grid, shafts, memory, injection and sampling times. */
void cli_linespace_summary(const il_linespace_stats *stats);

/* The reflective-shadow-map options (cli_rsm.c), for render --method rsm. */
typedef struct cli_rsm_options {
    il_rsm_desc desc;
    cli_method_note note;            /* any rsm option on the command line */
} cli_rsm_options;

extern const char cli_rsm_help[];
/* As cli_radiosity_option, for --rsm-size, --rsm-samples, --rsm-radius and
 * --rsm-shadow-test. */
bool cli_rsm_option(int argc, char **argv, int *i, cli_rsm_options *o, int *rc);
/* Adds the "rsm" object of --stats (the options in effect and every
 * il_rsm_stats field) to `parent`. */
void cli_rsm_stats_json(struct cJSON *parent, const il_rsm_desc *desc, const il_rsm_stats *stats);
/* One line on stderr: maps, texels, gathering, shadow rays, time per phase. */
void cli_rsm_summary(const il_rsm_desc *desc, const il_rsm_stats *stats);

/* The tone-mapping options (cli_tonemap.c), shared by render and tonemap:
 * --tonemap OP (also --op when op_alias), --auto-exposure [PERCENTILE],
 * --gamma G, --white W, --bloom K, --bloom-threshold T, --bloom-radius R.
 * --exposure stays each command's own option. */
typedef struct cli_tonemap_options {
    il_tonemap_desc desc;
    bool given;                      /* any of the options above */
    const char *gamma_opt, *white_opt; /* given, for the operator check */
} cli_tonemap_options;

extern const char cli_tonemap_help[];
/* As cli_radiosity_option; "--auto-exposure" takes the next argument as its
 * percentile only when that is a number. */
bool cli_tonemap_option(int argc, char **argv, int *i, bool op_alias, cli_tonemap_options *o,
                        int *rc);
/* After parsing: --gamma needs the gamma operator and --white reinhard
 * (usage error, exit 2, naming `command`). */
int cli_tonemap_check(const char *command, const cli_tonemap_options *o);
/* The desc for PNG outputs, its exposure set to `exposure`; NULL when no
 * tone-mapping option was given (the plain PNG transfer, as before). */
const il_tonemap_desc *cli_tonemap_desc(cli_tonemap_options *o, float exposure);

/* The environment-map options (cli_env.c), shared by render, bake, view
 * and illuminance: --env FILE, --env-mapping M, --env-intensity K,
 * --env-rotate DEGREES, or --sky overcast [--sky-lux E] [--ground-albedo R];
 * --sky-only with either. */
typedef struct cli_env_options {
    const char *file;                /* --env: NULL when not given */
    il_env_mapping mapping;
    bool has_mapping;                /* else guessed from the image's shape */
    double intensity;                /* 0: 1 */
    double rotation;                 /* degrees */
    const char *first_setting;       /* the first --env-* option given, for messages */
    bool sky;                        /* --sky: a sky for daylight instead of a file */
    bool sky_only;                   /* --sky-only: the scene's own lights switched off */
    il_sky_desc sky_desc;            /* --sky's type (cie_type 0: overcast), --sky-lux,
                                        --ground-albedo, --north, --sun ALT,AZ */
    const char *first_sky_setting;   /* the first of those given, for messages */
    const char *first_sun_setting;   /* the first --sun* option, --north, --latitude or
                                        --longitude given, for messages */
    bool has_sun;                    /* --sun ALT,AZ */
    const char *sun_time;            /* --sun-time, as given */
    double sun_seconds;              /* ... in seconds since 1970-01-01T00:00Z */
    int sun_day_of_year;             /* ... the local date's day of the year */
    double latitude, longitude;      /* --latitude, --longitude */
    bool has_latitude, has_longitude;
    double sun_lux;                  /* --sun-lux; has_sun_lux false: the IES model's */
    bool has_sun_lux;
} cli_env_options;

extern const char cli_env_help[];
/* As cli_radiosity_option, for the options above. */
bool cli_env_option(int argc, char **argv, int *i, cli_env_options *o, int *rc);
/* After parsing: an --env-* setting without --env, a sky setting without
 * --sky, or both --env and --sky is a usage error (and cli_sun_check's). */
int cli_env_check(const char *command, const cli_env_options *o);
/* Reads o->file (or makes the sky) and sets it as the scene's environment
 * (before commit), after switching the scene's own lights off for
 * --sky-only (which alone keeps the scene's own sky, an error when it has
 * none); prints the error (a missing, corrupt or misshapen map) and
 * returns its exit status.  Does nothing when o is NULL or asks for none
 * of this. */
int cli_env_apply(il_scene *scene, const cli_env_options *o, bool quiet);
/* The scene's daylight sky (--sky or the scene file's), as "sky": {type,
 * sky_lux, ground_albedo and, for a CIE sky, sun_altitude, sun_azimuth,
 * north, sun_normal_lux} in parent; nothing when it has none. */
void cli_sky_stats_json(struct cJSON *parent, const il_scene *scene);

/* The sun of a CIE sky (cli_sun.c, docs/environment.md#skies). */
/* --sun, --sun-time, --latitude, --longitude, --north, --sun-lux, as
 * cli_env_option (which calls it first) does for the rest. */
bool cli_sun_option(int argc, char **argv, int *i, cli_env_options *o, int *rc);
/* Usage errors among those: IL_EXIT_OK or IL_EXIT_USAGE (message printed). */
int cli_sun_check(const char *command, const cli_env_options *o);
/* Fills desc's sun (its position from --sun or from the moment and place,
 * its illuminance from --sun-lux or the model) for a CIE sky and prints
 * it unless quiet; a sun below the horizon is an error (exit 1). */
int cli_sun_resolve(const cli_env_options *o, il_sky_desc *desc, bool quiet);
/* cli_load_scene with the environment map of `env` (may be NULL) set
 * between loading and committing. */
int cli_load_scene_env(const char *path, bool quiet, const cli_env_options *env, il_scene **out);

/* Compute devices (cli_device.c, docs/cuda.md): `illum info --devices`
 * prints the CPU and every CUDA GPU (or why there is none); --device NAME is
 * "cpu" or "cuda"; cli_device_require_cuda returns IL_EXIT_OK when a GPU
 * can render, else prints why not and returns IL_EXIT_RUNTIME (no GPU, no
 * driver, or a build without CUDA). */
int cli_devices_list(void);
bool cli_device_from_name(const char *name, bool *cuda);
int cli_device_require_cuda(void);
/* Where a GPU render hands its running image (--write-every): write gets
 * the mean so far after a launch that ends `every` seconds or more after
 * the last call (every 0: never). */
typedef struct cli_running_image {
    double every;
    void (*write)(const il_image *img, void *user);
    void *user;
} cli_running_image;
/* Renders --method pt, photon or radiosity on the GPU into *out (freed
 * with il_image_free), handing pt's and photon's running image to
 * `running` (may be NULL); IL_ERR_INVALID for what the GPU kernels do not
 * do (other methods, a time limit, scenes the GPU scene packer refuses). */
il_status cli_device_render_cuda(const il_scene *scene, const il_render_desc *desc, uint32_t width,
                                 uint32_t height, const cli_running_image *running, il_image *out,
                                 il_render_stats *rs, il_error *err);

/* Every method's own options together, as render and view take them
 * (cli_method.c). */
typedef struct cli_method_options {
    cli_radiosity_options rad;
    cli_hr_options hr;
    cli_photon_options photon;
    cli_ibl_options ibl;
    cli_rsm_options rsm;
    cli_linespace_options linespace;
    cli_method_note light_paths;     /* --portal-light: photon, sppm and linespace */
} cli_method_options;

/* As cli_radiosity_option, for an option of any method. */
bool cli_method_options_parse(int argc, char **argv, int *i, cli_method_options *m, int *rc);
/* A usage message and IL_EXIT_USAGE when m holds an option of the methods
 * with light paths (--portal-light) and `method` is none of them; else
 * IL_EXIT_OK. */
int cli_method_light_paths_check(const char *command, const cli_method_options *m, il_method method);
/* Points desc's per-method option pointers at m's descs. */
void cli_method_options_install(cli_method_options *m, il_render_desc *desc);

/* The run options render, view and bake share (cli_run.c): --seed S,
 * --threads T (1 to 4096), --quiet (-q) and, when `sampling`, --spp N
 * (1 to 2^24) and --max-depth D (1 to 1024). */
typedef struct cli_run_options {
    bool sampling;                   /* set by the command: it takes --spp and --max-depth */
    bool quiet;                      /* --quiet or -q */
    bool has_seed;                   /* --seed was given */
} cli_run_options;

/* As cli_radiosity_option, for the options above, into desc. */
bool cli_run_option(int argc, char **argv, int *i, il_render_desc *desc, cli_run_options *o, int *rc);
/* What render and view take from a JSON scene's "render" block when the
 * command line left it unset (cli_run.c): the method (unless method_given),
 * max_depth and seed (unless o->has_seed).  An unknown method name is exit 1
 * with a message naming scene_path. */
int cli_run_apply_settings(const char *scene_path, const il_render_settings *rs, bool method_given,
                           const cli_run_options *o, il_render_desc *desc);
/* --exposure EV of every command that writes display colours: -50 to 50. */
bool cli_parse_exposure(const char *opt, const char *s, double *out);

/* The camera options of render and view (cli_camera.c): --camera-pos,
 * --camera-target, --camera-up, --fov, --camera-file. */
typedef struct cli_camera_options {
    const char *file;                /* --camera-file: NULL when not given */
    bool has_pos, has_target, has_up, has_fov;
    il_vec3 pos, target, up;
    double fov;                      /* vertical, degrees */
    bool quiet;                      /* the file's warnings are not printed */
} cli_camera_options;

/* As cli_radiosity_option, for the five options above. */
bool cli_camera_option(int argc, char **argv, int *i, cli_camera_options *o, int *rc);
/* Fills what the command line left unset from the camera JSON file
 * {"position":[..],"target":[..],"up":[..],"fov":deg}; IL_EXIT_OK without a file. */
int cli_camera_read_file(cli_camera_options *o);
/* Overrides the scene's camera with what was given (before rendering). */
int cli_camera_apply(il_scene *scene, const cli_camera_options *o);

/* Where `illum illuminance` measures (cli_sensors.c), at most this many sensors. */
#define CLI_MAX_SENSORS 10000000u

typedef struct cli_plane {
    int axis;                        /* 0 x, 1 y, 2 z: the plane is axis = value */
    float sign;                      /* +1: sensors face +axis, -1: -axis */
    float value;
} cli_plane;

typedef struct cli_sensor_grid {
    il_sensor *sensors;              /* malloc'd; freed by the caller */
    size_t count;
    uint32_t cols, rows;             /* a plane's grid; 0 for a file's points */
    int axes[2];                     /* the coordinates along the columns and the rows */
    double cell[2];                  /* the cell size along each, metres */
} cli_sensor_grid;

/* Coordinate `axis` (0 x, 1 y, 2 z) of v. */
float cli_axis_coord(il_vec3 v, int axis);
/* The axis (0 x, 1 y, 2 z; -1: none) that s starts with, after an optional
 * sign ("-y": 1, sign -1); *rest points past it. */
int cli_signed_axis(const char *s, float *sign, const char **rest);
/* --area "A0,B0,A1,B1": the second corner beyond the first in both. */
bool cli_parse_area(const char *opt, const char *s, double area[4]);
/* "y=0.85" (facing +y) or "-y=2.4" (facing -y). */
bool cli_parse_plane(const char *opt, const char *s, cli_plane *out);
/* The plane's area within the bounds lo..hi, inset by margin: {min0, min1,
 * max0, max1} along the grid's two axes (x before z, y before z). */
void cli_plane_area(const cli_plane *plane, il_vec3 lo, il_vec3 hi, double margin, double area[4]);
/* A sensor at the centre of every cell of the plane's area: cells of about
 * `spacing` (0: EN 12464-1's largest cell for the area).  Prints the error. */
int cli_plane_grid(const cli_plane *plane, const double area[4], double spacing, cli_sensor_grid *g);
/* Where sensors go on a plane or at a file's points: --plane, --area,
 * --margin, --spacing and --points (illuminance and sunhours). */
typedef struct cli_sensor_place {
    const char *points;
    bool has_plane, has_area;
    cli_plane plane;
    double area[4], margin, spacing;
} cli_sensor_place;
/* Option a with value v, when it is one of those (*ok: v was good, and
 * --plane, --area or --points not given before). */
bool cli_sensor_place_option(const char *a, const char *v, cli_sensor_place *p, bool *ok);
/* The grid of --plane over --area, inset by the margin, or over the
 * scene's bounds (p->area is then filled in), as cli_plane_grid. */
int cli_plane_sensors(const il_scene *scene, cli_sensor_place *p, cli_sensor_grid *g);
/* The first line of a summary: a plane's grid ("N sensors on y = 0.8
 * facing +y: ...") or a file's points ("N sensors from FILE"). */
void cli_print_sensors(const cli_sensor_grid *g, const cli_sensor_place *p);
/* The sensors of a text file: one 'x y z [nx ny nz]' a line (normal +y when
 * omitted), '#' comments, an optional header line.  Prints the error. */
int cli_read_sensors(const char *path, cli_sensor_grid *g);

/* False colour for `illum illuminance --view` (cli_falsecolor.c): the
 * picture of w x h lux values (row by row from the top; seen false: no
 * surface, dark grey), 0 to scale_max lx on a linear palette from dark blue
 * to red, and a legend strip on its right (the bar, "lx", six labelled
 * ticks), as linear values for il_image_write's PNG.  False when out of
 * memory. */
bool cli_falsecolor(const float *lux, const bool *seen, uint32_t w, uint32_t h, double scale_max,
                    il_image *out);
/* A round top for the scale: 1, 2, 2.5 or 5 times a power of ten, at or
 * above the 99th percentile of the seen values (1 when there are none). */
double cli_falsecolor_scale(const float *lux, const bool *seen, size_t n);
/* The value at fraction q (0: the least, 1: the largest) of the finite
 * values v[i] with seen[i]; 0 when there are none. */
double cli_seen_quantile(const float *v, const bool *seen, size_t n, double q);

/* `illum illuminance --view` (cli_illuminance_view.c): a sensor on the
 * surface each pixel sees, and the pictures of their readings. */
typedef struct cli_view {
    uint32_t width, height;
    uint32_t *pixel_of;              /* malloc'd: the pixel of each sensor */
} cli_view;

/* Fills g with a sensor for every pixel that sees a surface.  Prints the error. */
int cli_view_sensors(const il_scene *scene, uint32_t width, uint32_t height, cli_sensor_grid *g,
                     cli_view *view);
/* What a view's summary says (and --stats writes). */
typedef struct cli_view_summary {
    double minimum, median, maximum; /* lux over the pixels that see a surface */
    double palette_max;              /* the top of the false-colour scale */
} cli_view_summary;
/* Prints what the view holds into *sum and stdout and writes each output:
 * .png in false colour (0 to scale_max lx; 0: cli_falsecolor_scale),
 * .exr/.hdr/.pfm with the lux in every channel.  Returns the exit status. */
int cli_view_finish(const cli_view *view, const cli_sensor_grid *g, const il_illuminance *r,
                    double scale_max, const char *const *outputs, int num_outputs,
                    uint32_t samples, bool quiet, cli_view_summary *sum);

int cmd_illuminance(int argc, char **argv);
int cmd_sunhours(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_tonemap(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_bake(int argc, char **argv);
int cmd_envmap(int argc, char **argv);
int cmd_view(int argc, char **argv);    /* cmd_view.c; the window needs IL_VIEWER */

#endif
