/* The environment-map options shared by render, bake, view and illuminance
 * (docs/environment.md): --env FILE, --env-mapping, --env-intensity,
 * --env-rotate, or --sky overcast|clear|cie:N with --sky-lux,
 * --ground-albedo and the sun's options (cli_sun.c).  The
 * map is set on the scene after loading and before commit
 * (cli_load_scene_env). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "image/envmap.h"
#include "image/sky.h"

const char cli_env_help[] =
    "\n"
    "environment map (every method):\n"
    "  --env FILE             light the scene by an environment map (.hdr .exr .pfm);\n"
    "                         it replaces the scene's own sky\n"
    "  --env-mapping latlong|angular|cross\n"
    "                         how FILE covers the sphere (default: from its shape,\n"
    "                         1:1 angular, 3:4 cross, else latlong)\n"
    "  --env-intensity K      multiply the map's radiance by K (default 1)\n"
    "  --env-rotate DEGREES   turn the map about +y, counter-clockwise seen from\n"
    "                         above (default 0)\n"
    "  --sky overcast|clear|cie:N\n"
    "                         a sky for daylight studies instead of a map: the CIE\n"
    "                         standard overcast sky, or the CIE general sky type N\n"
    "                         (1 overcast ... 15 cloudless; clear is type 12) with\n"
    "                         its sun; an unobstructed horizontal surface gets\n"
    "                         --sky-lux E from the sky (default 10000 lx); below\n"
    "                         the horizon a ground of --ground-albedo R (default\n"
    "                         0.2) lit by sky and sun\n"
    "  --sun ALT,AZ           the sun of a CIE sky: altitude and azimuth in degrees\n"
    "                         (azimuth clockwise from north: east 90, south 180)\n"
    "  --sun-time T --latitude DEG --longitude DEG\n"
    "                         ... or where it stands at moment T (with its UTC\n"
    "                         offset: 2026-06-21T14:30+02:00) seen from that place\n"
    "                         (north and east positive)\n"
    "  --north DEG            north in the scene: -z turned DEG counter-clockwise\n"
    "                         seen from above (default 0: north -z, east +x)\n"
    "  --sun-lux E            the sun's illuminance facing it (default: the IES\n"
    "                         model for the sky type and altitude; 0: no sun)\n"
    "  --sun-diameter DEG     the sun's disc, which softens shadow edges (default\n"
    "                         0.533, the sun's own; 0: a point, sharp shadows)\n"
    "  --sky-only             light the scene by the sky alone (--env, --sky or the\n"
    "                         scene's own): its lights and emitters are switched\n"
    "                         off, a CIE sky's sun stays\n";

bool cli_env_option(int argc, char **argv, int *i, cli_env_options *o, int *rc)
{
    const char *a = argv[*i];
    if (!strcmp(a, "--sky-only")) {
        o->sky_only = true;
        *rc = IL_EXIT_OK;
        return true;
    }
    if (cli_sun_option(argc, argv, i, o, rc))
        return true;
    if (strcmp(a, "--env") && strcmp(a, "--env-mapping") && strcmp(a, "--env-intensity") &&
        strcmp(a, "--env-rotate") && strcmp(a, "--sky") && strcmp(a, "--sky-lux") &&
        strcmp(a, "--ground-albedo"))
        return false;
    *rc = IL_EXIT_OK;
    const char *v = cli_value(argc, argv, i);
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    if (!strcmp(a, "--env")) {
        o->file = v;
        return true;
    }
    if (!strcmp(a, "--sky")) {
        if (!il_sky_type_from_name(v, &o->sky_desc.cie_type)) {
            cli_error("--sky: expected overcast, clear or cie:1 to cie:15, got '%s'", v);
            *rc = IL_EXIT_BAD_INPUT;
        }
        o->sky = true;
        return true;
    }
    if (!strcmp(a, "--sky-lux") || !strcmp(a, "--ground-albedo")) {
        if (!o->first_sky_setting)
            o->first_sky_setting = a;
        bool lux = !strcmp(a, "--sky-lux");
        double x = 0.0;
        if (!cli_parse_double(a, v, lux ? 1e-3 : 0.0, lux ? 1e7 : 1.0, &x))
            *rc = IL_EXIT_BAD_INPUT;
        else if (lux)
            o->sky_desc.horizontal_lux = x;
        else
            o->sky_desc.ground_albedo = x > 0.0 ? x : -1.0; /* 0 in the desc means 0.2 */
        return true;
    }
    if (!o->first_setting)
        o->first_setting = a;
    if (!strcmp(a, "--env-mapping")) {
        if (!il_envmap_mapping_from_name(v, &o->mapping)) {
            cli_error("--env-mapping: expected latlong, angular or cross, got '%s'", v);
            *rc = IL_EXIT_BAD_INPUT;
        }
        o->has_mapping = true;
    } else if (!strcmp(a, "--env-intensity")) {
        double k = -1.0;
        if (!cli_parse_double(a, v, 0.0, 1e12, &k)) {
            *rc = IL_EXIT_BAD_INPUT;
        } else if (!(k > 0.0)) {
            cli_error("--env-intensity: must be more than 0, got '%s'", v);
            *rc = IL_EXIT_BAD_INPUT;
        }
        o->intensity = k;
    } else {
        if (!cli_parse_double(a, v, -1e6, 1e6, &o->rotation))
            *rc = IL_EXIT_BAD_INPUT;
    }
    return true;
}

int cli_env_check(const char *command, const cli_env_options *o)
{
    if (o->first_setting && !o->file) {
        cli_error("%s: %s needs --env FILE (see 'illum %s --help')", command, o->first_setting, command);
        return IL_EXIT_USAGE;
    }
    if (o->first_sky_setting && !o->sky) {
        cli_error("%s: %s needs --sky (see 'illum %s --help')", command, o->first_sky_setting, command);
        return IL_EXIT_USAGE;
    }
    if (o->sky && o->file) {
        cli_error("%s: --env and --sky both set the sky; give one", command);
        return IL_EXIT_USAGE;
    }
    return cli_sun_check(command, o);
}

int cli_env_apply(il_scene *scene, const cli_env_options *o, bool quiet)
{
    if (!o || (!o->file && !o->sky && !o->sky_only))
        return IL_EXIT_OK;
    il_error err = {0};
    il_image img = {0};
    if (o->sky_only && !o->file && !o->sky) {
        il_scene_info info;
        il_scene_get_info(scene, &info);
        if (!info.has_environment) {
            cli_error("--sky-only: the scene has no sky of its own; give --sky or --env FILE");
            return IL_EXIT_BAD_INPUT;
        }
    }
    if (o->sky_only && il_scene_remove_lights(scene, &err) != IL_OK) {
        cli_error("--sky-only: %s", err.message);
        return cli_exit_for(err.status);
    }
    if (!o->file && !o->sky)
        return IL_EXIT_OK; /* the scene's own sky */
    if (o->sky) {
        il_sky_desc sky = o->sky_desc;
        int rc = cli_sun_resolve(o, &sky, quiet);
        if (rc != IL_EXIT_OK)
            return rc;
        if (il_scene_set_daylight(scene, &sky, &err) != IL_OK) {
            cli_error("--sky: %s", err.message);
            return cli_exit_for(err.status);
        }
        return IL_EXIT_OK;
    }
    il_status st = il_image_read(o->file, &img, &err);
    if (st != IL_OK) {
        cli_error("--env: %s", err.message);
        return cli_exit_for(st);
    }
    il_env_mapping m = o->has_mapping ? o->mapping : il_envmap_mapping_for_size(img.width, img.height);
    if (!o->has_mapping && m == IL_ENV_LATLONG && img.width != 2 * img.height && !quiet)
        fprintf(stderr,
                "illum: warning: %s is %ux%u, not 2:1: taken as a lat-long map (see --env-mapping)\n",
                o->file, img.width, img.height);
    il_environment_desc d = {.map = &img, .mapping = m, .rotation = (float)o->rotation,
                             .intensity = (float)o->intensity};
    st = il_scene_set_environment(scene, &d, &err);
    il_image_free(&img);
    if (st != IL_OK) {
        cli_error("%s: %s", o->file, err.message);
        return cli_exit_for(st);
    }
    return IL_EXIT_OK;
}

void cli_sky_stats_json(struct cJSON *parent, const il_scene *scene)
{
    il_sky_desc d;
    if (!il_scene_get_daylight(scene, &d))
        return;
    cJSON *sky = cJSON_AddObjectToObject(parent, "sky");
    char type[16];
    snprintf(type, sizeof type, d.cie_type ? "cie:%d" : "overcast", d.cie_type);
    cJSON_AddStringToObject(sky, "type", type);
    cJSON_AddNumberToObject(sky, "sky_lux", d.horizontal_lux);
    cJSON_AddNumberToObject(sky, "ground_albedo", fmax(d.ground_albedo, 0.0));
    if (!d.cie_type)
        return;
    cJSON_AddNumberToObject(sky, "sun_altitude", d.sun_altitude);
    cJSON_AddNumberToObject(sky, "sun_azimuth", d.sun_azimuth);
    cJSON_AddNumberToObject(sky, "north", d.north);
    cJSON_AddNumberToObject(sky, "sun_normal_lux", d.sun_normal_lux);
    cJSON_AddNumberToObject(sky, "sun_diameter", d.sun_diameter > 0.0 ? d.sun_diameter : 0.0);
}
