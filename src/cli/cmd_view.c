/* `illum view SCENE`: the interactive viewer (docs/viewer.md).  The options
 * are parsed here in every build; the window itself (src/viewer/) exists only
 * when the program was built with IL_VIEWER (GLFW and epoxy found). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#ifdef IL_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

static const char *help =
    "usage: illum view SCENE [options]\n"
    "\n"
    "Opens a window (OpenGL 3.3) on the scene and refines the chosen method's\n"
    "image while the camera rests; the keys are listed in docs/viewer.md.\n"
    "\n"
    "options:\n"
    "  --method M             pt (default), photon, sppm, radiosity, hr, ibl, linespace, rsm\n"
    "  --spp N                stop refining at N samples per pixel (default: never)\n"
    "  --width W --height H   image and window size (default 512 x 512)\n"
    "  --max-depth N          most bounces on a path (default 8)\n"
    "  --seed S               random seed\n"
    "  --threads N            render threads (default all cores)\n"
    "  --camera-pos X,Y,Z --camera-target X,Y,Z --camera-up X,Y,Z --fov DEGREES\n"
    "  --camera-file FILE     camera JSON, as 'illum render --camera-file' reads\n"
    "  --exposure EV          display exposure (keys + and -)\n"
    "  --tonemap OP           linear (default), gamma, reinhard, filmic (key T)\n"
    "  --env FILE ... | --sky overcast|clear|cie:N ...\n"
    "                         environment map or daylight sky, as for 'illum render'\n"
    "  --save PREFIX          F9/P write PREFIX.exr and PREFIX.png, C writes\n"
    "                         PREFIX-camera.json (default 'illum-view')\n"
    "  --frames N             scripted: exit after N frames once the image is complete\n"
    "                         (needs --spp)\n"
    "  --screenshot FILE.png  scripted: write the window's pixels at exit\n"
    "  --look-screenshot FILE.png\n"
    "                         scripted, radiosity/hr mesh: the window's pixels when it\n"
    "                         draws the first look at the solve in progress\n"
    "  --keys KEYS            scripted: press these keys one by one once the image is\n"
    "                         complete ('<' '>' orbit left/right, '~' orbits\n"
    "                         0.5 rad in 2 s and measures the frame rate),\n"
    "                         e.g. --keys '>PC'\n"
    "  --quiet                no warnings\n"
    "Each method's own options (see 'illum render --method M --help') apply when\n"
    "that method is shown.\n";

typedef struct view_options {
    const char *scene, *screenshot, *look_screenshot, *save, *keys;
    il_render_desc desc;
    uint32_t width, height, frames;
    double exposure;
    cli_tonemap_options tm;
    cli_env_options env;
    cli_method_options m;            /* each method's own options, as for render */
    cli_run_options run;             /* --spp, --max-depth, --seed, --threads, --quiet */
    bool has_method;
    cli_camera_options camera;       /* --camera-* and --fov */
} view_options;

static int parse_options(int argc, char **argv, view_options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = NULL;
        int opt_rc;
        if (cli_tonemap_option(argc, argv, &i, false, &o->tm, &opt_rc) ||
            cli_env_option(argc, argv, &i, &o->env, &opt_rc) ||
            cli_camera_option(argc, argv, &i, &o->camera, &opt_rc) ||
            cli_method_options_parse(argc, argv, &i, &o->m, &opt_rc) ||
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
            return -1;
        } else if (!strcmp(a, "--method")) {
            VALUE();
            if (!cli_method_from_name(v, &o->desc.method)) {
                cli_error("--method: unknown method '%s' "
                          "(available: " CLI_METHOD_NAMES ")", v);
                return IL_EXIT_BAD_INPUT;
            }
            o->has_method = true;
        } else if (!strcmp(a, "--width")) {
            VALUE();
            if (!cli_parse_u32(a, v, 8, 8192, &o->width))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--height")) {
            VALUE();
            if (!cli_parse_u32(a, v, 8, 8192, &o->height))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--exposure")) {
            VALUE();
            if (!cli_parse_exposure(a, v, &o->exposure))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--save")) {
            VALUE();
            o->save = v;
        } else if (!strcmp(a, "--frames")) {
            VALUE();
            if (!cli_parse_u32(a, v, 1, 1u << 30, &o->frames))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--screenshot")) {
            VALUE();
            o->screenshot = v;
        } else if (!strcmp(a, "--look-screenshot")) {
            VALUE();
            o->look_screenshot = v;
        } else if (!strcmp(a, "--keys")) {
            VALUE();
            o->keys = v;
        } else {
            int rc = cli_scene_argument("view", a, &o->scene);
            if (rc != IL_EXIT_OK)
                return rc;
        }
#undef VALUE
    }
    int rc = cli_require_scene("view", o->scene);
    if (rc != IL_EXIT_OK)
        return rc;
    if ((rc = cli_env_check("view", &o->env)) != IL_EXIT_OK ||
        (rc = cli_tonemap_check("view", &o->tm)) != IL_EXIT_OK)
        return rc;
    if (o->frames && !o->desc.spp) {
        cli_error("view: --frames needs --spp (the image must be complete to be compared)");
        return IL_EXIT_USAGE;
    }
    if (o->keys && !o->frames) {
        cli_error("view: --keys needs --frames");
        return IL_EXIT_USAGE;
    }
    if ((o->screenshot || o->look_screenshot) && !o->frames) {
        cli_error("view: --screenshot and --look-screenshot need --frames");
        return IL_EXIT_USAGE;
    }
    return IL_EXIT_OK;
}


int cmd_view(int argc, char **argv)
{
    view_options o = {.run.sampling = true};
    int rc = parse_options(argc, argv, &o);
    if (rc == -1)
        return IL_EXIT_OK;
    if (rc != IL_EXIT_OK)
        return rc;
    o.camera.quiet = o.run.quiet;
    if ((rc = cli_camera_read_file(&o.camera)) != IL_EXIT_OK)
        return rc;
#ifndef IL_HAVE_VIEWER
    cli_error("view: this illum was built without the viewer (configure with -DIL_VIEWER=ON; "
              "it needs GLFW 3 and libepoxy, see docs/viewer.md)");
    return IL_EXIT_RUNTIME;
#else
    const char *files[] = {o.screenshot, o.look_screenshot};
    if ((rc = cli_check_outputs(files, 2)) != IL_EXIT_OK)
        return rc;
    il_scene *scene = NULL;
    if ((rc = cli_load_scene_env(o.scene, o.run.quiet, &o.env, &scene)) != IL_EXIT_OK)
        return rc;
    if ((rc = cli_camera_apply(scene, &o.camera)) != IL_EXIT_OK) {
        il_scene_release(scene);
        return rc;
    }
    /* A JSON scene's "render" block supplies what the command line left
     * unset, as for `illum render`, except its spp: here that would stop
     * the refinement.  A size outside the window's range is left out. */
    il_render_settings rs;
    if (il_scene_get_render_settings(scene, &rs)) {
        if (!o.width && rs.width >= 8 && rs.width <= 8192)
            o.width = rs.width;
        if (!o.height && rs.height >= 8 && rs.height <= 8192)
            o.height = rs.height;
        if ((rc = cli_run_apply_settings(o.scene, &rs, o.has_method, &o.run, &o.desc)) != IL_EXIT_OK) {
            il_scene_release(scene);
            return rc;
        }
    }
    cli_method_options_install(&o.m, &o.desc);
    il_viewer_options vo = {
        .scene = scene, .scene_name = o.scene, .desc = o.desc,
        .width = o.width ? o.width : 512, .height = o.height ? o.height : 512,
        .exposure = (float)o.exposure, .op = o.tm.desc.op, .frames = o.frames,
        .screenshot = o.screenshot, .look_screenshot = o.look_screenshot, .keys = o.keys,
        .save_prefix = o.save ? o.save : "illum-view",
        .quiet = o.run.quiet};
    rc = il_viewer_run(&vo);
    il_scene_release(scene);
    return rc;
#endif
}
