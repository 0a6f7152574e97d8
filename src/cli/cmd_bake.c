/* `illum bake SCENE -o OUT.ply|OUT.glb|OUT.gltf`: solve the scene with a
 * method that can bake (radiosity, hr) and write the meshes with per-vertex
 * radiance (il_bake, il_bake_write; docs/radiosity.md, "Baking"). */
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

static const char *help =
    "usage: illum bake SCENE -o OUT.ply|OUT.glb|OUT.gltf [options]\n"
    "\n"
    "Solves SCENE (a mesh file, a .json scene file, or a built-in name: cornell,\n"
    "atrium, simple-room, shadow-room, box-room, office, cornell-spheres) and writes\n"
    "its meshes with the outgoing radiance at every vertex: PLY with 8-bit sRGB\n"
    "colours and float properties radiance_r/g/b, or glTF 2.0 with COLOR_0 (display\n"
    "colours) and COLOR_1 (float radiance).\n"
    "\n"
    "  -o, --output FILE      the output, by extension: .ply .glb .gltf (required)\n"
    "  --method radiosity|hr  the method: progressive radiosity (the default) or\n"
    "                         hierarchical radiosity\n"
    "  --exposure EV          8-bit/display colours: radiance * 2^EV (default 0)\n"
    "  --seed S               random seed (default 0)\n"
    "  --threads T            worker threads (default: all cores)\n"
    "  --stats FILE           write statistics as JSON\n"
    "  --quiet                no progress and no warnings\n"
    "\n";

typedef struct bake_options {
    const char *scene;
    const char *output;
    const char *stats;
    il_render_desc desc;
    il_bake_write_desc write;
    cli_run_options run;             /* --seed, --threads, --quiet */
    cli_radiosity_options rad;
    cli_hr_options hr;
    cli_env_options env;             /* --env and its settings */
} bake_options;

static bool known_bake_extension(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && (!strcasecmp(dot, ".ply") || !strcasecmp(dot, ".glb") || !strcasecmp(dot, ".gltf"));
}

static int parse_options(int argc, char **argv, bake_options *o)
{
    o->desc.method = IL_METHOD_RADIOSITY;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = NULL;
        int opt_rc;
        if (cli_radiosity_option(argc, argv, &i, &o->rad, &opt_rc) ||
            cli_hr_option(argc, argv, &i, &o->hr, &opt_rc) ||
            cli_run_option(argc, argv, &i, &o->desc, &o->run, &opt_rc)) {
            if (opt_rc != IL_EXIT_OK)
                return opt_rc;
            continue;
        }
        if (cli_env_option(argc, argv, &i, &o->env, &opt_rc)) {
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
            fputs(cli_radiosity_help, stdout);
            fputs(cli_hr_help, stdout);
            fputs(cli_env_help, stdout);
            return -1;
        } else if (!strcmp(a, "--method")) {
            VALUE();
            if (!cli_method_from_name(v, &o->desc.method) ||
                (o->desc.method != IL_METHOD_RADIOSITY && o->desc.method != IL_METHOD_HR)) {
                cli_error("--method: '%s' cannot bake (available: radiosity, hr)", v);
                return IL_EXIT_BAD_INPUT;
            }
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            VALUE();
            if (o->output) {
                cli_error("bake: one output at a time ('%s' is extra)", v);
                return IL_EXIT_USAGE;
            }
            if (!known_bake_extension(v)) {
                cli_error("%s: unknown bake format (use .ply, .glb or .gltf)", v);
                return IL_EXIT_BAD_INPUT;
            }
            o->output = v;
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
            int rc = cli_scene_argument("bake", a, &o->scene);
            if (rc != IL_EXIT_OK)
                return rc;
        }
#undef VALUE
    }
    if (cli_require_scene("bake", o->scene) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    if (cli_env_check("bake", &o->env) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    if (!o->output) {
        cli_error("bake: no output given: -o OUT.ply, OUT.glb or OUT.gltf");
        return IL_EXIT_USAGE;
    }
    if (o->rad.note.given && o->desc.method != IL_METHOD_RADIOSITY)
        return cli_method_mismatch("bake", &o->rad.note, "radiosity", "radiosity");
    if (o->hr.note.given && o->desc.method != IL_METHOD_HR)
        return cli_method_mismatch("bake", &o->hr.note, "hierarchical radiosity", "hr");
    return IL_EXIT_OK;
}

static bool write_stats(const bake_options *o, const il_bake_result *b, double wall)
{
    uint64_t vertices = 0, triangles = 0;
    for (uint32_t i = 0; i < b->num_meshes; i++) {
        vertices += b->meshes[i].num_vertices;
        triangles += b->meshes[i].num_triangles;
    }
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "scene", o->scene);
    cJSON_AddStringToObject(j, "method", cli_method_name(o->desc.method));
    cJSON_AddStringToObject(j, "output", o->output);
    cJSON_AddNumberToObject(j, "meshes", b->num_meshes);
    cJSON_AddNumberToObject(j, "vertices", (double)vertices);
    cJSON_AddNumberToObject(j, "triangles", (double)triangles);
    cJSON_AddNumberToObject(j, "seed", (double)o->desc.seed);
    cJSON_AddNumberToObject(j, "threads", o->desc.threads);
    cJSON_AddNumberToObject(j, "exposure", o->write.exposure);
    cJSON_AddNumberToObject(j, "total_seconds", wall);
    cJSON_AddBoolToObject(j, "interrupted", cli_interrupted != 0);
    if (o->desc.method == IL_METHOD_HR)
        cli_hr_stats_json(j, &b->stats.hr);
    else
        cli_radiosity_stats_json(j, &b->stats.radiosity);
    bool ok = cli_write_json(o->stats, j);
    cJSON_Delete(j);
    return ok;
}

int cmd_bake(int argc, char **argv)
{
    double t0 = cli_now_seconds();
    bake_options o = {0};
    int rc = parse_options(argc, argv, &o);
    if (rc == -1)
        return IL_EXIT_OK;
    if (rc != IL_EXIT_OK)
        return rc;

    /* A .gltf writes its buffer to NAME.bin beside it (export_assimp.c). */
    char bin[4096] = "";
    const char *dot = strrchr(o.output, '.');
    if (dot && !strcasecmp(dot, ".gltf"))
        snprintf(bin, sizeof bin, "%.*s.bin", (int)(dot - o.output), o.output);
    if (bin[0] && o.stats && !strcmp(bin, o.stats)) {
        cli_error("%s: %s writes its buffer there; give --stats another name", o.stats, o.output);
        return IL_EXIT_BAD_INPUT;
    }
    const char *files[] = {o.output, o.stats, bin[0] ? bin : NULL};
    if ((rc = cli_check_outputs(files, 3)) != IL_EXIT_OK)
        return rc;
    il_scene *scene = NULL;
    if ((rc = cli_load_scene_env(o.scene, o.run.quiet, &o.env, &scene)) != IL_EXIT_OK)
        return rc;

    cli_radiosity_install_progress(&o.rad, o.run.quiet, &cli_interrupted);
    cli_hr_install_progress(&o.hr, o.run.quiet, &cli_interrupted);
    o.desc.radiosity = &o.rad.desc;
    o.desc.hr = &o.hr.desc;
    struct sigaction old_sa;
    cli_interrupt_catch(o.run.quiet, &old_sa);
    il_error err = {0};
    il_bake_result *bake = NULL;
    il_status st = il_bake(scene, &o.desc, &bake, &err);
    cli_interrupt_release(&old_sa);
    cli_radiosity_end_progress(&o.rad);
    cli_hr_end_progress(&o.hr);
    if (st == IL_OK)
        st = il_bake_write(bake, o.output, &o.write, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        il_bake_release(bake);
        il_scene_release(scene);
        return cli_exit_for(st);
    }
    if (!o.run.quiet) {
        if (o.desc.method == IL_METHOD_HR)
            cli_hr_summary(&bake->stats.hr);
        else
            cli_radiosity_summary(&bake->stats.radiosity);
        fprintf(stderr, "illum: baked %u meshes -> %s\n", bake->num_meshes, o.output);
    }
    if (o.stats && !write_stats(&o, bake, cli_now_seconds() - t0))
        rc = IL_EXIT_BAD_INPUT;
    il_bake_release(bake);
    il_scene_release(scene);
    if (rc == IL_EXIT_OK && cli_interrupted) {
        cli_error("interrupted: the solve stopped early; the bake so far is written");
        return IL_EXIT_INTERRUPTED;
    }
    return rc;
}
