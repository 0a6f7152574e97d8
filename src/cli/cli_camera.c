/* The camera options shared by render and view: --camera-pos, --camera-target,
 * --camera-up, --fov and --camera-file (docs/cli.md). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"
#include "scene/loader.h"

bool cli_camera_option(int argc, char **argv, int *i, cli_camera_options *o, int *rc)
{
    const char *a = argv[*i];
    il_vec3 *vec = NULL;
    bool *has = NULL;
    if (!strcmp(a, "--camera-pos"))
        vec = &o->pos, has = &o->has_pos;
    else if (!strcmp(a, "--camera-target"))
        vec = &o->target, has = &o->has_target;
    else if (!strcmp(a, "--camera-up"))
        vec = &o->up, has = &o->has_up;
    else if (strcmp(a, "--fov") && strcmp(a, "--camera-file"))
        return false;
    const char *v = cli_value(argc, argv, i);
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    *rc = IL_EXIT_OK;
    if (!strcmp(a, "--camera-file")) {
        o->file = v;
    } else if (!strcmp(a, "--fov")) {
        if (!cli_parse_double(a, v, 0.01, 179.0, &o->fov))
            *rc = IL_EXIT_BAD_INPUT;
        o->has_fov = true;
    } else {
        if (!cli_parse_vec3(a, v, vec))
            *rc = IL_EXIT_BAD_INPUT;
        *has = true;
    }
    return true;
}

static bool read_vec3(const cJSON *obj, const char *key, il_vec3 *out, bool *has, const char *file)
{
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!a)
        return true;
    if (!cJSON_IsArray(a) || cJSON_GetArraySize(a) != 3) {
        cli_error("%s: \"%s\" must be an array of three numbers", file, key);
        return false;
    }
    float v[3];
    for (int k = 0; k < 3; k++) {
        const cJSON *e = cJSON_GetArrayItem(a, k);
        if (!cJSON_IsNumber(e)) {
            cli_error("%s: \"%s\" must be an array of three numbers", file, key);
            return false;
        }
        v[k] = (float)e->valuedouble;
    }
    *out = (il_vec3){v[0], v[1], v[2]};
    *has = true;
    return true;
}

int cli_camera_read_file(cli_camera_options *o)
{
    if (!o->file)
        return IL_EXIT_OK;
    FILE *f = fopen(o->file, "rb");
    if (!f) {
        cli_error("%s: cannot open the camera file", o->file);
        return IL_EXIT_BAD_INPUT;
    }
    char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    /* One object and nothing after it (cJSON would ignore the rest). */
    cJSON *root = cJSON_ParseWithOpts(buf, NULL, true);
    if (!root || !cJSON_IsObject(root) || !root->child) {
        cli_error("%s: not a JSON object with a camera's keys (\"position\", \"target\", \"up\", "
                  "\"fov\")", o->file);
        cJSON_Delete(root);
        return IL_EXIT_BAD_INPUT;
    }
    const char *dup = il_json_duplicate_key(root);
    if (dup) {
        cli_error("%s: the key \"%s\" appears twice", o->file, dup);
        cJSON_Delete(root);
        return IL_EXIT_BAD_INPUT;
    }
    for (const cJSON *k = root->child; k; k = k->next) {
        static const char *const known[] = {"position", "target", "up", "fov"};
        bool ok = false;
        for (int i = 0; i < 4; i++)
            ok |= k->string && !strcmp(k->string, known[i]);
        if (!ok && !o->quiet)
            cli_error("warning: %s: unknown key \"%s\" ignored (a camera file has \"position\", "
                      "\"target\", \"up\" and \"fov\")", o->file, k->string ? k->string : "");
    }
    cli_camera_options file = {0};
    bool ok = read_vec3(root, "position", &file.pos, &file.has_pos, o->file) &&
              read_vec3(root, "target", &file.target, &file.has_target, o->file) &&
              read_vec3(root, "up", &file.up, &file.has_up, o->file);
    const cJSON *fov = cJSON_GetObjectItemCaseSensitive(root, "fov");
    if (ok && fov) {
        if (!cJSON_IsNumber(fov)) {
            cli_error("%s: \"fov\" must be a number", o->file);
            ok = false;
        } else {
            file.fov = fov->valuedouble;
            file.has_fov = true;
        }
    }
    cJSON_Delete(root);
    if (!ok)
        return IL_EXIT_BAD_INPUT;
    /* What the command line gave wins over the file. */
    if (!o->has_pos && file.has_pos) { o->pos = file.pos; o->has_pos = true; }
    if (!o->has_target && file.has_target) { o->target = file.target; o->has_target = true; }
    if (!o->has_up && file.has_up) { o->up = file.up; o->has_up = true; }
    if (!o->has_fov && file.has_fov) { o->fov = file.fov; o->has_fov = true; }
    return IL_EXIT_OK;
}

int cli_camera_apply(il_scene *scene, const cli_camera_options *o)
{
    if (!(o->has_pos || o->has_target || o->has_up || o->has_fov))
        return IL_EXIT_OK;
    /* In the library zero means the default; given here it is a mistake. */
    if (o->has_up && o->up.x == 0.0f && o->up.y == 0.0f && o->up.z == 0.0f) {
        cli_error("the camera's up (--camera-up or the camera file's \"up\") is zero: it gives no direction");
        return IL_EXIT_BAD_INPUT;
    }
    if (o->has_fov && !(o->fov > 0.0 && o->fov < 180.0)) {
        cli_error("the camera's fov %g (--fov or the camera file's \"fov\") must be in (0, 180) degrees",
                  o->fov);
        return IL_EXIT_BAD_INPUT;
    }
    il_camera_desc cam;
    il_scene_get_camera(scene, &cam);
    if (o->has_pos)
        cam.position = o->pos;
    if (o->has_target)
        cam.target = o->target;
    if (o->has_up)
        cam.up = o->up;
    if (o->has_fov)
        cam.fov_y = (float)o->fov;
    il_error err = {0};
    if (il_scene_set_camera(scene, &cam, &err) != IL_OK) {
        cli_error("%s", err.message);
        return IL_EXIT_BAD_INPUT;
    }
    return IL_EXIT_OK;
}
