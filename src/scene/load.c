/* il_scene_load: a scene from a file (by extension) or a built-in name. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "core/error.h"
#include "core/input_file.h"
#include "scene/builtin.h"
#include "scene/loader.h"
#include "scene/scene.h"
#include "scene/xform.h"

/* True when path ends in ext (case-insensitive; ext includes the dot). */
static bool has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), m = strlen(ext);
    return n > m && strcasecmp(path + n - m, ext) == 0;
}

il_status il_scene_load(const char *path, const il_load_desc *desc, il_scene **out, il_error *err)
{
    *out = NULL;
    il_error local;
    if (!err)
        err = &local;
    if (!path || !path[0])
        return il_fail(err, IL_ERR_INVALID, "no scene given (a file or a built-in name)");

    /* A file of that name wins over a built-in scene of the same name. */
    struct stat st;
    bool exists = stat(path, &st) == 0;
    if (!exists && !il_builtin_exists(path))
        return il_fail(err, IL_ERR_IO, "%s: no such file", path);
    if (exists && S_ISDIR(st.st_mode))
        return il_fail(err, IL_ERR_IO, "%s: is a directory, not a scene file", path);
    if (exists) {
        FILE *f = fopen(path, "rb");
        if (!f)
            return il_fail(err, IL_ERR_IO, "%s: cannot be read: %s", path, strerror(errno));
        fclose(f);
    }

    il_scene *scene = NULL;
    il_status s = il_scene_create(&scene, err);
    if (s != IL_OK)
        return s;
    if (desc) {
        scene->log = desc->log;
        scene->log_user = desc->log_user;
    }

    if (!exists)
        s = il_builtin_load(scene, path, err);
    else if (has_extension(path, ".json"))
        s = il_load_json(scene, path, err);
    else
        s = il_load_assimp(scene, path, NULL, 0, err);

    if (s == IL_OK && scene->num_meshes == 0)
        s = scene->dropped_triangles
                ? il_fail(err, IL_ERR_INVALID, "%s: no triangles (all %llu dropped: NaN/Inf or "
                          "out-of-range coordinates, or zero area)", path,
                          (unsigned long long)scene->dropped_triangles)
                : il_fail(err, IL_ERR_INVALID, "%s: no triangles", path);
    if (s != IL_OK) {
        il_scene_release(scene);
        return s;
    }
    *out = scene;
    return IL_OK;
}

bool il_scene_get_render_settings(const il_scene *scene, il_render_settings *out)
{
    memset(out, 0, sizeof *out);
    if (!scene->has_render_settings)
        return false;
    *out = scene->render_settings;
    return true;
}

il_status il_load_read_file(const char *path, char **out, size_t *size, il_error *err)
{
    *out = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return il_fail(err, IL_ERR_IO, "%s: %s", path,
                       errno == ENOENT ? "no such file" : strerror(errno));
    if (!il_input_is_file(f)) {
        fclose(f);
        return il_fail(err, IL_ERR_IO, "%s: not a file", path);
    }
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (cap - len < 65536) {
            size_t ncap = cap ? cap * 2 : 65536;
            char *p = realloc(buf, ncap + 1);
            if (!p) {
                free(buf);
                fclose(f);
                return il_fail(err, IL_ERR_MEMORY, "%s: out of memory reading the file", path);
            }
            buf = p;
            cap = ncap;
        }
        size_t n = fread(buf + len, 1, cap - len, f);
        len += n;
        if (n == 0)
            break;
    }
    bool failed = ferror(f);
    fclose(f);
    if (failed) {
        free(buf);
        return il_fail(err, IL_ERR_IO, "%s: read error", path);
    }
    buf[len] = '\0';
    *out = buf;
    *size = len;
    return IL_OK;
}

il_status il_load_add_mesh(il_scene *scene, const il_mesh_desc *d, const il_xform *x,
                           il_error *err)
{
    size_t nv = d->num_vertices, nt = d->num_triangles;
    float *pos = il_malloc(nv * 3 * sizeof(float) + 1, err);
    float *nrm = d->normals ? il_malloc(nv * 3 * sizeof(float) + 1, err) : NULL;
    uint32_t *idx = il_malloc(nt * 3 * sizeof(uint32_t) + 1, err);
    if (!pos || !idx || (d->normals && !nrm)) {
        free(pos);
        free(nrm);
        free(idx);
        return IL_ERR_MEMORY;
    }
    il_xform nx = il_xform_normal_matrix(x);
    for (size_t v = 0; v < nv; v++) {
        const float *p = d->positions + 3 * v;
        il_vec3 q = il_xform_point(x, p[0], p[1], p[2]);
        pos[3 * v] = q.x, pos[3 * v + 1] = q.y, pos[3 * v + 2] = q.z;
        if (nrm) {
            const float *n = d->normals + 3 * v;
            il_vec3 w = il_xform_vector(&nx, n[0], n[1], n[2]);
            nrm[3 * v] = w.x, nrm[3 * v + 1] = w.y, nrm[3 * v + 2] = w.z;
        }
    }
    bool flip = il_xform_det3(x) < 0.0;
    for (size_t t = 0; t < nt; t++) {
        idx[3 * t] = d->indices[3 * t];
        idx[3 * t + 1] = d->indices[3 * t + (flip ? 2 : 1)];
        idx[3 * t + 2] = d->indices[3 * t + (flip ? 1 : 2)];
    }
    il_mesh_desc m = *d;
    m.positions = pos;
    m.normals = nrm;
    m.indices = idx;
    il_status s = il_scene_add_mesh(scene, &m, err);
    free(pos);
    free(nrm);
    free(idx);
    return s;
}

il_status il_load_prefix_error(il_error *err, il_status status, const char *file, const char *where)
{
    char msg[sizeof err->message];
    memcpy(msg, err->message, sizeof msg);
    msg[sizeof msg - 1] = '\0';
    if (where)
        return il_fail(err, status, "%s: %s: %s", file, where, msg);
    return il_fail(err, status, "%s: %s", file, msg);
}
