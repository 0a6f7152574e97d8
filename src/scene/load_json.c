/* JSON scene files (docs/scene-format.md): meshes from files, inline arrays or
 * shapes, with transforms; materials; lights; camera; environment; render
 * settings.  Every error names the file and the key path, e.g.
 * "scene.json: lights[1].intensity: expected a number or [r,g,b]". */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "image/envmap.h"
#include "image/sky.h"
#include "scene/sun.h"
#include "scene/loader.h"
#include "scene/mesh_open.h"
#include "scene/scene.h"
#include "scene/xform.h"

#define WHERE_MAX 256

typedef struct named_material {
    char name[IL_NAME_MAX];
    uint32_t index;
} named_material;

typedef struct jctx {
    il_scene *scene;
    const char *path;
    char dir[1024];              /* the JSON file's folder with a trailing '/', or "" */
    named_material *mats;
    uint32_t num_mats;
    il_error *err;
} jctx;

static il_status bad(jctx *c, const char *where, const char *what)
{
    return il_fail(c->err, IL_ERR_FORMAT, "%s: %s: %s", c->path, where, what);
}

/* Key paths for messages; a very long one is cut short, which is harmless. */
static void child_key(char *out, const char *where, const char *key)
{
    if (snprintf(out, WHERE_MAX, "%s%s%s", where, where[0] ? "." : "", key) >= WHERE_MAX)
        out[WHERE_MAX - 2] = '~';
}

static void child_index(char *out, const char *where, int i)
{
    if (snprintf(out, WHERE_MAX, "%s[%d]", where, i) >= WHERE_MAX)
        out[WHERE_MAX - 2] = '~';
}

/* Warns about keys other than `allowed` (NULL-terminated).  Keys starting with
 * '_' and "comment" are for people and are skipped silently. */
static void check_keys(jctx *c, const cJSON *obj, const char *where, const char *const *allowed)
{
    const cJSON *it;
    cJSON_ArrayForEach(it, obj)
    {
        const char *k = it->string;
        if (!k || k[0] == '_' || strcmp(k, "comment") == 0)
            continue;
        bool ok = false;
        for (const char *const *a = allowed; *a && !ok; a++)
            ok = strcmp(*a, k) == 0;
        if (!ok) {
            char w[WHERE_MAX];
            child_key(w, where, k);
            il_scene_warn(c->scene, "%s: %s: unknown key, ignored", c->path, w);
        }
    }
}

/* ------------------------------------------------------------ value readers */

/* A finite number.  `present` (may be NULL) tells whether the key exists. */
static il_status get_number(jctx *c, const cJSON *obj, const char *key, const char *where,
                            double *out, bool *present)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (present)
        *present = v != NULL;
    if (!v)
        return IL_OK;
    char w[WHERE_MAX];
    child_key(w, where, key);
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
        return bad(c, w, "expected a number");
    *out = v->valuedouble;
    return IL_OK;
}

static il_status get_float_min(jctx *c, const cJSON *obj, const char *key, const char *where,
                               float min, float *out)
{
    double d = *out;
    bool present;
    il_status s = get_number(c, obj, key, where, &d, &present);
    if (s != IL_OK || !present)
        return s;
    if (!(d >= min)) {
        char w[WHERE_MAX], msg[96];
        child_key(w, where, key);
        snprintf(msg, sizeof msg, "expected a number >= %g", (double)min);
        return bad(c, w, msg);
    }
    *out = (float)d;
    return IL_OK;
}

/* A whole number in [min, max]. */
static il_status get_integer(jctx *c, const cJSON *obj, const char *key, const char *where,
                             double min, double max, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v)
        return IL_OK;
    char w[WHERE_MAX], msg[96];
    child_key(w, where, key);
    if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble) || v->valuedouble < min ||
        v->valuedouble > max) {
        snprintf(msg, sizeof msg, "expected a whole number in [%.0f, %.0f]", min, max);
        return bad(c, w, msg);
    }
    *out = v->valuedouble;
    return IL_OK;
}

/* Three numbers [x,y,z]; with `scalar_ok` a single number s also means [s,s,s]. */
static il_status parse_vec3(jctx *c, const cJSON *v, const char *w, bool scalar_ok, il_vec3 *out)
{
    const char *expected = scalar_ok ? "expected a number or [r,g,b]" : "expected [x,y,z]";
    if (scalar_ok && cJSON_IsNumber(v)) {
        if (!isfinite(v->valuedouble))
            return bad(c, w, expected);
        *out = v3s((float)v->valuedouble);
        return IL_OK;
    }
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3)
        return bad(c, w, expected);
    float f[3];
    for (int i = 0; i < 3; i++) {
        const cJSON *e = cJSON_GetArrayItem(v, i);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return bad(c, w, expected);
        f[i] = (float)e->valuedouble;
    }
    *out = v3(f[0], f[1], f[2]);
    return IL_OK;
}

static il_status get_vec3(jctx *c, const cJSON *obj, const char *key, const char *where,
                          bool scalar_ok, il_vec3 *out, bool *present)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (present)
        *present = v != NULL;
    if (!v)
        return IL_OK;
    char w[WHERE_MAX];
    child_key(w, where, key);
    return parse_vec3(c, v, w, scalar_ok, out);
}

/* A colour: a number or [r,g,b], all >= 0. */
static il_status get_colour(jctx *c, const cJSON *obj, const char *key, const char *where,
                            il_vec3 *out)
{
    il_vec3 v = *out;
    bool present;
    il_status s = get_vec3(c, obj, key, where, true, &v, &present);
    if (s != IL_OK || !present)
        return s;
    if (v.x < 0 || v.y < 0 || v.z < 0) {
        char w[WHERE_MAX];
        child_key(w, where, key);
        return bad(c, w, "expected values >= 0");
    }
    *out = v;
    return IL_OK;
}

static il_status get_string(jctx *c, const cJSON *obj, const char *key, const char *where,
                            const char **out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v)
        return IL_OK;
    char w[WHERE_MAX];
    child_key(w, where, key);
    if (!cJSON_IsString(v) || !v->valuestring[0])
        return bad(c, w, "expected a non-empty string");
    *out = v->valuestring;
    return IL_OK;
}

static il_status get_bool(jctx *c, const cJSON *obj, const char *key, const char *where, bool *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v)
        return IL_OK;
    char w[WHERE_MAX];
    child_key(w, where, key);
    if (!cJSON_IsBool(v))
        return bad(c, w, "expected true or false");
    *out = cJSON_IsTrue(v);
    return IL_OK;
}

static il_status expect_object(jctx *c, const cJSON *v, const char *where)
{
    return cJSON_IsObject(v) ? IL_OK : bad(c, where, "expected an object {...}");
}

/* A file path relative to the JSON file's folder. */
static il_status resolve_path(jctx *c, const char *where, const char *rel, char *out, size_t n)
{
    int len = rel[0] == '/' ? snprintf(out, n, "%s", rel) : snprintf(out, n, "%s%s", c->dir, rel);
    return len >= 0 && (size_t)len < n ? IL_OK : bad(c, where, "path too long");
}

/* --------------------------------------------------------------- materials */

static uint32_t find_material(const jctx *c, const char *name)
{
    for (uint32_t i = 0; i < c->num_mats; i++)
        if (strcmp(c->mats[i].name, name) == 0)
            return c->mats[i].index;
    return 0;
}

static uint32_t lookup_material(const char *name, void *user)
{
    return find_material(user, name);
}

static il_status parse_material(jctx *c, const cJSON *m, const char *name, const char *where)
{
    static const char *const keys[] = {"type", "diffuse", "texture", "specular", "exponent",
                                       "ior", "transmittance", "emission", "two_sided", NULL};
    il_status s = expect_object(c, m, where);
    if (s != IL_OK)
        return s;
    check_keys(c, m, where, keys);
    if (strlen(name) >= IL_NAME_MAX) {
        return bad(c, where, "material name too long");
    }
    il_material_desc d = {.name = name, .diffuse = v3s(0.8f)};
    const char *type = "diffuse";
    if ((s = get_string(c, m, "type", where, &type)) != IL_OK)
        return s;
    if (strcmp(type, "diffuse") == 0)
        d.type = IL_MATERIAL_DIFFUSE;
    else if (strcmp(type, "phong") == 0)
        d.type = IL_MATERIAL_PHONG;
    else if (strcmp(type, "mirror") == 0)
        d.type = IL_MATERIAL_MIRROR;
    else if (strcmp(type, "dielectric") == 0)
        d.type = IL_MATERIAL_DIELECTRIC;
    else if (strcmp(type, "thin_glass") == 0)
        d.type = IL_MATERIAL_THIN_GLASS;
    else {
        char w[WHERE_MAX];
        child_key(w, where, "type");
        return bad(c, w, "expected \"diffuse\", \"phong\", \"mirror\", \"dielectric\" or "
                         "\"thin_glass\"");
    }
    if (d.type == IL_MATERIAL_PHONG)
        d.specular = v3s(0.2f);
    if ((s = get_colour(c, m, "diffuse", where, &d.diffuse)) != IL_OK ||
        (s = get_colour(c, m, "specular", where, &d.specular)) != IL_OK ||
        (s = get_colour(c, m, "emission", where, &d.emission)) != IL_OK ||
        (s = get_float_min(c, m, "exponent", where, 0.0f, &d.exponent)) != IL_OK ||
        (s = get_float_min(c, m, "ior", where, 1.0f, &d.ior)) != IL_OK ||
        (s = get_float_min(c, m, "transmittance", where, 0.0f, &d.transmittance)) != IL_OK ||
        (s = get_bool(c, m, "two_sided", where, &d.two_sided)) != IL_OK)
        return s;
    const char *tex = NULL;
    if ((s = get_string(c, m, "texture", where, &tex)) != IL_OK)
        return s;
    if (tex) {
        char full[2048], w[WHERE_MAX];
        child_key(w, where, "texture");
        if ((s = resolve_path(c, w, tex, full, sizeof full)) != IL_OK)
            return s;
        il_image img = {0};
        il_error e = {0};
        il_status ts = il_image_read(full, &img, &e);
        if (ts == IL_OK)
            ts = il_scene_add_texture(c->scene, img.width, img.height, img.rgb,
                                      &d.diffuse_texture, &e);
        il_image_free(&img);
        if (ts != IL_OK) {
            d.diffuse_texture = 0;
            il_scene_warn(c->scene, "%s: %s.texture: %s not loaded (%s); using the material "
                          "colour", c->path, where, full, e.message);
        }
    }
    uint32_t idx;
    if ((s = il_scene_add_material(c->scene, &d, &idx, c->err)) != IL_OK)
        return il_load_prefix_error(c->err, s, c->path, where);
    named_material *g = realloc(c->mats, (c->num_mats + 1) * sizeof *g);
    if (!g)
        return il_fail(c->err, IL_ERR_MEMORY, "%s: out of memory", c->path);
    c->mats = g;
    snprintf(g[c->num_mats].name, IL_NAME_MAX, "%s", name);
    g[c->num_mats].index = idx;
    c->num_mats++;
    return IL_OK;
}

static il_status parse_materials(jctx *c, const cJSON *mats)
{
    il_status s = expect_object(c, mats, "materials");
    if (s != IL_OK)
        return s;
    const cJSON *it;
    cJSON_ArrayForEach(it, mats)
    {
        char w[WHERE_MAX];
        child_key(w, "materials", it->string);
        if ((s = parse_material(c, it, it->string, w)) != IL_OK)
            return s;
    }
    return IL_OK;
}

/* -------------------------------------------------------------- transforms */

/* Rotation by `deg` degrees about the unit axis (x,y,z): Rodrigues' formula
 * (e.g. pbrt-v4, section 3.9.6). */
static il_xform rotation_axis(double x, double y, double z, double deg)
{
    double l = sqrt(x * x + y * y + z * z);
    x /= l, y /= l, z /= l;
    double a = deg * 3.14159265358979323846 / 180.0, s = sin(a), co = cos(a), t = 1.0 - co;
    il_xform r = il_xform_identity();
    r.m[0][0] = t * x * x + co, r.m[0][1] = t * x * y - s * z, r.m[0][2] = t * x * z + s * y;
    r.m[1][0] = t * x * y + s * z, r.m[1][1] = t * y * y + co, r.m[1][2] = t * y * z - s * x;
    r.m[2][0] = t * x * z - s * y, r.m[2][1] = t * y * z + s * x, r.m[2][2] = t * z * z + co;
    return r;
}

/* A mesh's transform: "matrix" (16 numbers, row by row) or "transform"
 * {translate, rotate, scale} composed as T * R * S. */
static il_status parse_transform(jctx *c, const cJSON *mesh, const char *where, il_xform *out)
{
    *out = il_xform_identity();
    const cJSON *mat = cJSON_GetObjectItemCaseSensitive(mesh, "matrix");
    const cJSON *tr = cJSON_GetObjectItemCaseSensitive(mesh, "transform");
    char w[WHERE_MAX];
    if (mat && tr)
        return bad(c, where, "give either \"matrix\" or \"transform\", not both");
    if (mat) {
        child_key(w, where, "matrix");
        if (!cJSON_IsArray(mat) || cJSON_GetArraySize(mat) != 16)
            return bad(c, w, "expected 16 numbers (row by row)");
        for (int i = 0; i < 16; i++) {
            const cJSON *e = cJSON_GetArrayItem(mat, i);
            if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
                return bad(c, w, "expected 16 numbers (row by row)");
            out->m[i / 4][i % 4] = e->valuedouble;
        }
        if (out->m[3][0] != 0 || out->m[3][1] != 0 || out->m[3][2] != 0 || out->m[3][3] != 1)
            return bad(c, w, "the last row must be 0 0 0 1 (an affine transform)");
    } else if (tr) {
        static const char *const keys[] = {"translate", "rotate", "scale", NULL};
        child_key(w, where, "transform");
        il_status s = expect_object(c, tr, w);
        if (s != IL_OK)
            return s;
        check_keys(c, tr, w, keys);
        il_vec3 t = v3s(0.0f), sc = v3s(1.0f);
        if ((s = get_vec3(c, tr, "translate", w, false, &t, NULL)) != IL_OK ||
            (s = get_vec3(c, tr, "scale", w, true, &sc, NULL)) != IL_OK)
            return s;
        il_xform r = il_xform_identity();
        const cJSON *rot = cJSON_GetObjectItemCaseSensitive(tr, "rotate");
        if (rot) {
            char wr[WHERE_MAX];
            child_key(wr, w, "rotate");
            int n = cJSON_IsArray(rot) ? cJSON_GetArraySize(rot) : 0;
            double a[4] = {0};
            for (int i = 0; i < n && i < 4; i++) {
                const cJSON *e = cJSON_GetArrayItem(rot, i);
                if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
                    n = 0;
                else
                    a[i] = e->valuedouble;
            }
            if (n == 3) {
                /* Euler angles in degrees about x, then y, then z: R = Rz Ry Rx. */
                il_xform rx = rotation_axis(1, 0, 0, a[0]), ry = rotation_axis(0, 1, 0, a[1]),
                         rz = rotation_axis(0, 0, 1, a[2]);
                il_xform ryx = il_xform_mul(&ry, &rx);
                r = il_xform_mul(&rz, &ryx);
            } else if (n == 4 && (a[0] != 0 || a[1] != 0 || a[2] != 0)) {
                r = rotation_axis(a[0], a[1], a[2], a[3]);
            } else {
                return bad(c, wr, "expected [x,y,z] Euler degrees or [ax,ay,az,degrees]");
            }
        }
        if (sc.x == 0 || sc.y == 0 || sc.z == 0) {
            char ws[WHERE_MAX];
            child_key(ws, w, "scale");
            return bad(c, ws, "a scale of zero flattens the mesh");
        }
        il_xform S = il_xform_identity(), T = il_xform_identity();
        S.m[0][0] = sc.x, S.m[1][1] = sc.y, S.m[2][2] = sc.z;
        T.m[0][3] = t.x, T.m[1][3] = t.y, T.m[2][3] = t.z;
        il_xform rs = il_xform_mul(&r, &S);
        *out = il_xform_mul(&T, &rs);
    }
    return IL_OK;
}

/* ------------------------------------------------------------------ meshes */

/* Reads an array of numbers; `count` receives its length. */
static il_status number_array(jctx *c, const cJSON *v, const char *where, bool integers,
                              double **out, uint32_t *count)
{
    *out = NULL;
    *count = 0;
    const char *expected = integers ? "expected an array of whole numbers >= 0"
                                    : "expected an array of numbers";
    if (!cJSON_IsArray(v))
        return bad(c, where, expected);
    int n = cJSON_GetArraySize(v);
    double *a = il_malloc(((size_t)n + 1) * sizeof(double), c->err);
    if (!a)
        return IL_ERR_MEMORY;
    int i = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, v)
    {
        /* NaN cannot be written in JSON; very large numbers parse as inf. */
        if (!cJSON_IsNumber(e) ||
            (integers && (e->valuedouble < 0 || e->valuedouble != floor(e->valuedouble) ||
                          e->valuedouble > 4294967295.0))) {
            free(a);
            return bad(c, where, expected);
        }
        a[i++] = e->valuedouble;
    }
    *out = a;
    *count = (uint32_t)n;
    return IL_OK;
}

static il_status inline_mesh(jctx *c, const cJSON *mesh, const char *where, il_shape_mesh *out)
{
    memset(out, 0, sizeof *out);
    char w[WHERE_MAX];
    double *pos = NULL, *idx = NULL, *nrm = NULL, *uv = NULL;
    uint32_t np = 0, ni = 0, nn = 0, nu = 0;
    il_status s;
    const cJSON *v;

    child_key(w, where, "positions");
    if ((s = number_array(c, cJSON_GetObjectItemCaseSensitive(mesh, "positions"), w, false, &pos,
                          &np)) != IL_OK)
        goto done;
    if (np == 0 || np % 3 != 0) {
        s = bad(c, w, "expected 3 numbers per vertex");
        goto done;
    }
    uint32_t nv = np / 3;
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "indices"))) {
        child_key(w, where, "indices");
        if ((s = number_array(c, v, w, true, &idx, &ni)) != IL_OK)
            goto done;
        if (ni == 0 || ni % 3 != 0) {
            s = bad(c, w, "expected 3 indices per triangle");
            goto done;
        }
        for (uint32_t i = 0; i < ni; i++)
            if (idx[i] >= nv) {
                s = bad(c, w, "index out of range of the positions");
                goto done;
            }
    } else if (nv % 3 != 0) {
        child_key(w, where, "positions");
        s = bad(c, w, "without \"indices\", every 3 vertices make a triangle");
        goto done;
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "normals"))) {
        child_key(w, where, "normals");
        if ((s = number_array(c, v, w, false, &nrm, &nn)) != IL_OK)
            goto done;
        if (nn != np) {
            s = bad(c, w, "expected as many numbers as \"positions\"");
            goto done;
        }
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(mesh, "uvs"))) {
        child_key(w, where, "uvs");
        if ((s = number_array(c, v, w, false, &uv, &nu)) != IL_OK)
            goto done;
        if (nu != 2 * nv) {
            s = bad(c, w, "expected 2 numbers per vertex");
            goto done;
        }
    }
    uint32_t nt = idx ? ni / 3 : nv / 3;
    s = IL_ERR_MEMORY;
    out->num_vertices = nv;
    out->num_triangles = nt;
    out->positions = il_malloc((size_t)np * sizeof(float), c->err);
    out->indices = il_malloc((size_t)nt * 3 * sizeof(uint32_t), c->err);
    out->normals = nrm ? il_malloc((size_t)nn * sizeof(float), c->err) : NULL;
    out->uvs = uv ? il_malloc((size_t)nu * sizeof(float), c->err) : NULL;
    if (!out->positions || !out->indices || (nrm && !out->normals) || (uv && !out->uvs)) {
        il_shape_free(out);
        goto done;
    }
    for (uint32_t i = 0; i < np; i++)
        out->positions[i] = (float)pos[i];
    for (uint32_t i = 0; i < 3 * nt; i++)
        out->indices[i] = idx ? (uint32_t)idx[i] : i;
    for (uint32_t i = 0; nrm && i < nn; i++)
        out->normals[i] = (float)nrm[i];
    for (uint32_t i = 0; uv && i < nu; i++)
        out->uvs[i] = (float)uv[i];
    s = IL_OK;
done:
    free(pos);
    free(idx);
    free(nrm);
    free(uv);
    return s;
}

static il_status shape_mesh(jctx *c, const cJSON *mesh, const char *where, const char *shape,
                            il_shape_mesh *out)
{
    il_status s;
    char w[WHERE_MAX];
    if (strcmp(shape, "quad") == 0 || strcmp(shape, "box") == 0) {
        bool quad = shape[0] == 'q';
        il_vec3 size = v3s(1.0f);
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(mesh, "size");
        child_key(w, where, "size");
        if (cJSON_GetObjectItemCaseSensitive(mesh, "radius") || cJSON_GetObjectItemCaseSensitive(mesh, "segments"))
            il_scene_warn(c->scene, "%s: %s: \"radius\" and \"segments\" are a sphere's, ignored for a %s",
                          c->path, where, shape);
        if (v && quad && cJSON_IsArray(v) && cJSON_GetArraySize(v) != 2)
            return bad(c, w, "expected a number or [sx,sz]");
        if (v && quad && cJSON_IsArray(v) && cJSON_GetArraySize(v) == 2) {
            const cJSON *a = cJSON_GetArrayItem(v, 0), *b = cJSON_GetArrayItem(v, 1);
            if (!cJSON_IsNumber(a) || !cJSON_IsNumber(b))
                return bad(c, w, "expected a number or [sx,sz]");
            size = v3((float)a->valuedouble, 1.0f, (float)b->valuedouble);
        } else if (v && (s = parse_vec3(c, v, w, true, &size)) != IL_OK) {
            return quad ? bad(c, w, "expected a number or [sx,sz]") : s;
        }
        if (!(size.x > 0 && size.y > 0 && size.z > 0) || !v3_is_finite(size))
            return bad(c, w, "expected sizes > 0");
        return quad ? il_shape_quad(size.x, size.z, out, c->err)
                    : il_shape_box(size.x, size.y, size.z, out, c->err);
    }
    if (strcmp(shape, "sphere") == 0) {
        if (cJSON_GetObjectItemCaseSensitive(mesh, "size"))
            il_scene_warn(c->scene, "%s: %s: \"size\" is a quad's or a box's, ignored for a sphere "
                          "(give \"radius\")", c->path, where);
        float radius = 1.0f;
        double segments = 32;
        if ((s = get_float_min(c, mesh, "radius", where, 0.0f, &radius)) != IL_OK ||
            (s = get_integer(c, mesh, "segments", where, 3, 4096, &segments)) != IL_OK)
            return s;
        if (!(radius > 0.0f)) {
            child_key(w, where, "radius");
            return bad(c, w, "expected a number > 0");
        }
        return il_shape_sphere(radius, (uint32_t)segments, out, c->err);
    }
    child_key(w, where, "shape");
    return bad(c, w, "expected \"quad\", \"box\" or \"sphere\"");
}

static il_status parse_mesh(jctx *c, const cJSON *mesh, const char *where)
{
    static const char *const keys[] = {"file", "positions", "indices", "normals", "uvs", "shape",
                                       "size", "radius", "segments", "flip", "transform",
                                       "matrix", "material", "name", NULL};
    il_status s = expect_object(c, mesh, where);
    if (s != IL_OK)
        return s;
    check_keys(c, mesh, where, keys);
    const char *file = NULL, *shape = NULL, *material = NULL, *name = NULL;
    bool flip = false;
    if ((s = get_string(c, mesh, "file", where, &file)) != IL_OK ||
        (s = get_string(c, mesh, "shape", where, &shape)) != IL_OK ||
        (s = get_string(c, mesh, "material", where, &material)) != IL_OK ||
        (s = get_string(c, mesh, "name", where, &name)) != IL_OK ||
        (s = get_bool(c, mesh, "flip", where, &flip)) != IL_OK)
        return s;
    bool inl = cJSON_GetObjectItemCaseSensitive(mesh, "positions") != NULL;
    if ((file != NULL) + (shape != NULL) + inl != 1)
        return bad(c, where, "expected exactly one of \"file\", \"shape\" or \"positions\"");
    il_xform x;
    if ((s = parse_transform(c, mesh, where, &x)) != IL_OK)
        return s;
    uint32_t mat = 0;
    if (material) {
        mat = find_material(c, material);
        if (!mat) {
            char w[WHERE_MAX], msg[IL_NAME_MAX + 64];
            child_key(w, where, "material");
            snprintf(msg, sizeof msg, "no material named '%s' in \"materials\"", material);
            return bad(c, w, msg);
        }
    }

    if (file) {
        if (flip)
            il_scene_warn(c->scene, "%s: %s.flip: only for shapes and inline meshes, ignored",
                          c->path, where);
        char full[2048], w[WHERE_MAX];
        child_key(w, where, "file");
        if ((s = resolve_path(c, w, file, full, sizeof full)) != IL_OK)
            return s;
        float cm[16];
        il_xform_to_cm(&x, cm);
        il_assimp_options o = {.transform = cm, .material_override = mat,
                               .lookup = lookup_material, .lookup_user = c};
        return il_load_assimp_ex(c->scene, full, &o, c->err);
    }

    il_shape_mesh m;
    s = shape ? shape_mesh(c, mesh, where, shape, &m) : inline_mesh(c, mesh, where, &m);
    if (s != IL_OK)
        return s;
    if (flip)
        il_shape_flip(&m);
    il_mesh_desc d = {
        .name = name ? name : (shape ? shape : "inline"),
        .num_vertices = m.num_vertices,
        .num_triangles = m.num_triangles,
        .positions = m.positions,
        .normals = m.normals,
        .uvs = m.uvs,
        .indices = m.indices,
        .material = mat,
    };
    /* A dielectric sheet bends light in and never out, and light samples
     * cannot pass it: a window is a thin_glass pane.  Said, not changed: the
     * scene file chose the type (a water surface in a tank is one sheet). */
    bool open = false;
    if (mat < c->scene->num_materials && c->scene->materials[mat].type == IL_MATERIAL_DIELECTRIC &&
        il_mesh_is_open(m.positions, m.num_vertices, m.indices, m.num_triangles, &open, c->err) == IL_OK &&
        open)
        il_scene_warn(c->scene, "%s: %s: the dielectric '%s' is on an open mesh (a single sheet): "
                      "light refracted into it never leaves, and light samples cannot pass it; "
                      "for a window pane use \"type\": \"thin_glass\"", c->path, where,
                      c->scene->materials[mat].name);
    uint32_t before = c->scene->num_meshes;
    s = il_load_add_mesh(c->scene, &d, &x, c->err);
    il_shape_free(&m);
    if (s != IL_OK)
        return il_load_prefix_error(c->err, s, c->path, where);
    if (c->scene->num_meshes == before)
        return bad(c, where,
                   "no triangles (all dropped: NaN/Inf or out-of-range coordinates, or zero area)");
    return IL_OK;
}

/* ------------------------------------------------- lights, camera, the rest */

static il_status parse_light(jctx *c, const cJSON *l, const char *where)
{
    static const char *const keys[] = {"type", "position", "direction", "intensity", "angle",
                                       "exponent", "diameter", NULL};
    il_status s = expect_object(c, l, where);
    if (s != IL_OK)
        return s;
    check_keys(c, l, where, keys);
    const char *type = NULL;
    if ((s = get_string(c, l, "type", where, &type)) != IL_OK)
        return s;
    char w[WHERE_MAX];
    child_key(w, where, "type");
    il_light_desc d = {.intensity = v3s(1.0f)};
    if (!type)
        return bad(c, w, "missing: expected \"point\", \"spot\" or \"directional\"");
    if (strcmp(type, "point") == 0)
        d.type = IL_LIGHT_POINT;
    else if (strcmp(type, "spot") == 0)
        d.type = IL_LIGHT_SPOT;
    else if (strcmp(type, "directional") == 0)
        d.type = IL_LIGHT_DIRECTIONAL;
    else
        return bad(c, w, "expected \"point\", \"spot\" or \"directional\"");
    if ((s = get_vec3(c, l, "position", where, false, &d.position, NULL)) != IL_OK ||
        (s = get_vec3(c, l, "direction", where, false, &d.direction, NULL)) != IL_OK ||
        (s = get_colour(c, l, "intensity", where, &d.intensity)) != IL_OK ||
        (s = get_float_min(c, l, "angle", where, 0.0f, &d.spot_angle)) != IL_OK ||
        (s = get_float_min(c, l, "exponent", where, 0.0f, &d.spot_exponent)) != IL_OK ||
        (s = get_float_min(c, l, "diameter", where, 0.0f, &d.diameter)) != IL_OK)
        return s;
    /* Zero means the default in the library, a mistake in a file. */
    if (d.spot_angle > 180.0f || (cJSON_GetObjectItemCaseSensitive(l, "angle") && d.spot_angle == 0.0f)) {
        child_key(w, where, "angle");
        return bad(c, w, "expected degrees in (0, 180]");
    }
    if (cJSON_GetObjectItemCaseSensitive(l, "direction") && v3_is_zero(d.direction)) {
        child_key(w, where, "direction");
        return bad(c, w, "a zero vector gives no direction");
    }
    if (d.diameter > 90.0f || (d.diameter > 0.0f && d.type != IL_LIGHT_DIRECTIONAL)) {
        child_key(w, where, "diameter");
        return bad(c, w, "a directional light's disc: expected degrees in [0, 90]");
    }
    d.direction = v3_normalize(d.direction);
    if ((s = il_scene_add_light(c->scene, &d, c->err)) != IL_OK)
        return il_load_prefix_error(c->err, s, c->path, where);
    return IL_OK;
}

static il_status parse_camera(jctx *c, const cJSON *cam)
{
    static const char *const keys[] = {"position", "target", "up", "fov", NULL};
    il_status s = expect_object(c, cam, "camera");
    if (s != IL_OK)
        return s;
    check_keys(c, cam, "camera", keys);
    il_camera_desc d = {.position = v3(0, 0, 1)};
    bool has_pos, has_target;
    if ((s = get_vec3(c, cam, "position", "camera", false, &d.position, &has_pos)) != IL_OK ||
        (s = get_vec3(c, cam, "target", "camera", false, &d.target, &has_target)) != IL_OK ||
        (s = get_vec3(c, cam, "up", "camera", false, &d.up, NULL)) != IL_OK ||
        (s = get_float_min(c, cam, "fov", "camera", 0.0f, &d.fov_y)) != IL_OK)
        return s;
    if (!has_pos || !has_target)
        return bad(c, "camera", "\"position\" and \"target\" are required");
    /* In the library zero means the default; written in a file it is a mistake. */
    if (cJSON_GetObjectItemCaseSensitive(cam, "fov") && !(d.fov_y > 0.0f))
        return bad(c, "camera.fov", "expected degrees in (0, 180)");
    if (cJSON_GetObjectItemCaseSensitive(cam, "up") && v3_is_zero(d.up))
        return bad(c, "camera.up", "a zero vector gives no direction");
    if ((s = il_scene_set_camera(c->scene, &d, c->err)) != IL_OK)
        return il_load_prefix_error(c->err, s, c->path, NULL);
    return IL_OK;
}

/* "environment": {"sky": "overcast"|"clear"|"cie:N"} with "sky_lux",
 * "ground_albedo", and for a CIE sky its "sun": [altitude, azimuth] or
 * {"time", "latitude", "longitude"}, "north", "sun_lux" and "sun_diameter"
 * (docs/environment.md#skies, il_scene_set_daylight). */
static il_status parse_sky(jctx *c, const cJSON *env, const char *name)
{
    il_sky_desc d = {0};
    if (!il_sky_type_from_name(name, &d.cie_type))
        return bad(c, "environment.sky", "expected \"overcast\", \"clear\" or \"cie:1\" to \"cie:15\"");
    if (cJSON_GetObjectItemCaseSensitive(env, "radiance") || cJSON_GetObjectItemCaseSensitive(env, "map"))
        return bad(c, "environment", "\"sky\" and \"radiance\" or \"map\" exclude each other");
    const cJSON *sun = cJSON_GetObjectItemCaseSensitive(env, "sun");
    bool has_lux, has_albedo, has_north, has_sun_lux, has_diameter;
    double sun_lux = 0.0;
    int day = 0; /* of the year, for the sun model's season; 0 without a date */
    il_status s;
    if ((s = get_number(c, env, "sky_lux", "environment", &d.horizontal_lux, &has_lux)) != IL_OK ||
        (s = get_number(c, env, "ground_albedo", "environment", &d.ground_albedo, &has_albedo)) != IL_OK ||
        (s = get_number(c, env, "north", "environment", &d.north, &has_north)) != IL_OK ||
        (s = get_number(c, env, "sun_lux", "environment", &sun_lux, &has_sun_lux)) != IL_OK ||
        (s = get_number(c, env, "sun_diameter", "environment", &d.sun_diameter, &has_diameter)) != IL_OK)
        return s;
    if (has_lux && !(d.horizontal_lux > 0.0))
        return bad(c, "environment.sky_lux", "expected a number of lux > 0");
    if (has_albedo && !(d.ground_albedo >= 0.0 && d.ground_albedo <= 1.0))
        return bad(c, "environment.ground_albedo", "expected a number from 0 to 1");
    if (has_albedo && d.ground_albedo == 0.0)
        d.ground_albedo = -1.0; /* 0 in the desc means the default 0.2 */
    if (has_sun_lux && !(sun_lux >= 0.0))
        return bad(c, "environment.sun_lux", "expected a number of lux >= 0");
    if (has_diameter && !(d.sun_diameter >= 0.0 && d.sun_diameter <= 90.0))
        return bad(c, "environment.sun_diameter", "expected a number of degrees from 0 (a point) to 90");
    if (has_diameter && d.sun_diameter == 0.0)
        d.sun_diameter = -1.0; /* 0 in the desc means the sun's own size */
    if (d.cie_type == 0) {
        if (sun || has_north || has_sun_lux || has_diameter)
            return bad(c, "environment", "the overcast sky has no \"sun\", \"north\", \"sun_lux\" or "
                                         "\"sun_diameter\"");
    } else if (!sun) {
        return bad(c, "environment.sun", "a CIE sky needs its sun: [altitude, azimuth] or "
                                         "{\"time\", \"latitude\", \"longitude\"}");
    } else if (cJSON_IsArray(sun)) {
        if (cJSON_GetArraySize(sun) != 2 || !cJSON_IsNumber(cJSON_GetArrayItem(sun, 0)) ||
            !cJSON_IsNumber(cJSON_GetArrayItem(sun, 1)) || !isfinite(cJSON_GetArrayItem(sun, 1)->valuedouble))
            return bad(c, "environment.sun", "expected [altitude, azimuth] in degrees");
        d.sun_altitude = cJSON_GetArrayItem(sun, 0)->valuedouble;
        d.sun_azimuth = cJSON_GetArrayItem(sun, 1)->valuedouble;
        if (!(d.sun_altitude > 0.0 && d.sun_altitude <= 90.0))
            return bad(c, "environment.sun", "the altitude must be above the horizon, up to 90 degrees");
    } else {
        static const char *const sun_keys[] = {"time", "latitude", "longitude", NULL};
        const char *time = NULL;
        double lat = 0.0, lon = 0.0, seconds = 0.0;
        bool has_lat, has_lon;
        if ((s = expect_object(c, sun, "environment.sun")) != IL_OK)
            return s;
        check_keys(c, sun, "environment.sun", sun_keys);
        if ((s = get_string(c, sun, "time", "environment.sun", &time)) != IL_OK ||
            (s = get_number(c, sun, "latitude", "environment.sun", &lat, &has_lat)) != IL_OK ||
            (s = get_number(c, sun, "longitude", "environment.sun", &lon, &has_lon)) != IL_OK)
            return s;
        if (!time || !has_lat || !has_lon)
            return bad(c, "environment.sun", "expected \"time\", \"latitude\" and \"longitude\"");
        il_error e = {0};
        if (il_parse_moment(time, &seconds, &day, &e) != IL_OK ||
            il_sun_place(&d, lat, lon, seconds, time, &e) != IL_OK)
            return bad(c, "environment.sun", e.message);
    }
    d.sun_normal_lux = has_sun_lux ? sun_lux : il_sun_normal_lux(d.cie_type, d.sun_altitude, day);
    if ((s = il_scene_set_daylight(c->scene, &d, c->err)) != IL_OK)
        return il_load_prefix_error(c->err, s, c->path, "environment.sky");
    return IL_OK;
}

/* Calls parse(c, item, "where[i]") for each item of the array v in turn;
 * the first error ends it. */
static il_status parse_items(jctx *c, const cJSON *v, const char *where,
                             il_status (*parse)(jctx *, const cJSON *, const char *))
{
    int i = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, v)
    {
        char w[WHERE_MAX];
        child_index(w, where, i++);
        il_status s = parse(c, it, w);
        if (s != IL_OK)
            return s;
    }
    return IL_OK;
}

/* One of "environment.portals": a "quad" shape or inline "positions" and
 * "indices", with a transform, lighting the side its front faces ("flip"
 * turns it); a quad faces +y before its transform. */
static il_status parse_portal(jctx *c, const cJSON *portal, const char *where)
{
    static const char *const keys[] = {"shape", "size", "positions", "indices", "flip", "transform",
                                       "matrix", NULL};
    il_status s = expect_object(c, portal, where);
    if (s != IL_OK)
        return s;
    check_keys(c, portal, where, keys);
    const char *shape = NULL;
    bool flip = false;
    if ((s = get_string(c, portal, "shape", where, &shape)) != IL_OK ||
        (s = get_bool(c, portal, "flip", where, &flip)) != IL_OK)
        return s;
    bool inl = cJSON_GetObjectItemCaseSensitive(portal, "positions") != NULL;
    if ((shape != NULL) + inl != 1)
        return bad(c, where, "expected exactly one of \"shape\": \"quad\" or \"positions\"");
    if (shape && strcmp(shape, "quad") != 0) {
        char w[WHERE_MAX];
        child_key(w, where, "shape");
        return bad(c, w, "a portal is a \"quad\" (or inline \"positions\" and \"indices\")");
    }
    il_xform x;
    if ((s = parse_transform(c, portal, where, &x)) != IL_OK)
        return s;
    il_shape_mesh m;
    s = shape ? shape_mesh(c, portal, where, shape, &m) : inline_mesh(c, portal, where, &m);
    if (s != IL_OK)
        return s;
    if (flip)
        il_shape_flip(&m);
    il_vec3 *corners = il_malloc(sizeof *corners * 3 * (size_t)m.num_triangles, c->err);
    if (!corners) {
        il_shape_free(&m);
        return IL_ERR_MEMORY;
    }
    for (size_t k = 0; k < 3 * (size_t)m.num_triangles; k++) {
        const float *q = m.positions + 3 * (size_t)m.indices[k];
        corners[k] = il_xform_point(&x, q[0], q[1], q[2]);
    }
    s = il_scene_add_portal(c->scene, corners, m.num_triangles, c->err);
    free(corners);
    il_shape_free(&m);
    return s == IL_OK ? IL_OK : il_load_prefix_error(c->err, s, c->path, where);
}

/* "environment.portals": an array of portals (scene/portal.h). */
static il_status parse_portals(jctx *c, const cJSON *env)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(env, "portals");
    if (!v)
        return IL_OK;
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) == 0)
        return bad(c, "environment.portals", "expected a non-empty array [...] of portals");
    return parse_items(c, v, "environment.portals", parse_portal);
}

/* "environment": a constant "radiance", or a "map" (an image file relative
 * to the JSON file) with its "mapping" (default: from the image's shape,
 * image/envmap.h), "rotation" in degrees and "intensity"
 * (docs/environment.md); or a "sky" (parse_sky). */
static il_status parse_environment(jctx *c, const cJSON *env)
{
    static const char *const keys[] = {"radiance", "map", "mapping", "rotation", "intensity", "sky",
                                       "sky_lux", "ground_albedo", "sun", "north", "sun_lux",
                                       "sun_diameter", "portals", NULL};
    il_status s = expect_object(c, env, "environment");
    if (s != IL_OK)
        return s;
    check_keys(c, env, "environment", keys);
    if ((s = parse_portals(c, env)) != IL_OK)
        return s;
    const char *sky = NULL;
    if ((s = get_string(c, env, "sky", "environment", &sky)) != IL_OK)
        return s;
    if (sky)
        return parse_sky(c, env, sky);
    static const char *const sky_keys[] = {"sky_lux", "ground_albedo", "sun", "north", "sun_lux",
                                           "sun_diameter"};
    for (size_t k = 0; k < sizeof sky_keys / sizeof sky_keys[0]; k++)
        if (cJSON_GetObjectItemCaseSensitive(env, sky_keys[k]))
            return bad(c, "environment", "\"sky_lux\", \"ground_albedo\", \"sun\", \"north\", "
                                         "\"sun_lux\" and \"sun_diameter\" need a \"sky\"");
    il_environment_desc d = {0};
    const char *map = NULL, *mapping = NULL;
    double rotation = 0.0, intensity = 0.0;
    bool has_rotation, has_intensity;
    if ((s = get_colour(c, env, "radiance", "environment", &d.radiance)) != IL_OK ||
        (s = get_string(c, env, "map", "environment", &map)) != IL_OK ||
        (s = get_string(c, env, "mapping", "environment", &mapping)) != IL_OK ||
        (s = get_number(c, env, "rotation", "environment", &rotation, &has_rotation)) != IL_OK ||
        (s = get_number(c, env, "intensity", "environment", &intensity, &has_intensity)) != IL_OK)
        return s;
    if (!map && (mapping || has_rotation || has_intensity))
        return bad(c, "environment", "\"mapping\", \"rotation\" and \"intensity\" need a \"map\"");
    if (mapping && !il_envmap_mapping_from_name(mapping, &d.mapping))
        return bad(c, "environment.mapping", "expected \"latlong\", \"angular\" or \"cross\"");
    if (has_intensity && !(intensity > 0.0))
        return bad(c, "environment.intensity", "expected a number > 0");
    il_image img = {0};
    if (map) {
        char full[2048];
        if ((s = resolve_path(c, "environment.map", map, full, sizeof full)) != IL_OK)
            return s;
        if ((s = il_image_read(full, &img, c->err)) != IL_OK)
            return il_load_prefix_error(c->err, s, c->path, "environment.map");
        if (!mapping)
            d.mapping = il_envmap_mapping_for_size(img.width, img.height);
        d.map = &img;
        d.rotation = (float)rotation;
        d.intensity = (float)intensity;
    }
    s = il_scene_set_environment(c->scene, &d, c->err);
    il_image_free(&img);
    if (s != IL_OK)
        return il_load_prefix_error(c->err, s, c->path, map ? "environment.map" : NULL);
    return IL_OK;
}

static il_status parse_render(jctx *c, const cJSON *r)
{
    static const char *const keys[] = {"width", "height", "spp", "max_depth", "seed", "method",
                                       "time", NULL};
    il_status s = expect_object(c, r, "render");
    if (s != IL_OK)
        return s;
    check_keys(c, r, "render", keys);
    il_render_settings *o = &c->scene->render_settings;
    memset(o, 0, sizeof *o);
    double w = 0, h = 0, spp = 0, depth = 0, seed = 0, time = 0;
    const char *method = NULL;
    bool has_time;
    /* The ranges of illum render's --width, --height, --spp and --max-depth. */
    if ((s = get_integer(c, r, "width", "render", 1, 16384, &w)) != IL_OK ||
        (s = get_integer(c, r, "height", "render", 1, 16384, &h)) != IL_OK ||
        (s = get_integer(c, r, "spp", "render", 1, 16777216.0, &spp)) != IL_OK ||
        (s = get_integer(c, r, "max_depth", "render", 1, 1024, &depth)) != IL_OK ||
        (s = get_integer(c, r, "seed", "render", 0, 9007199254740992.0, &seed)) != IL_OK ||
        (s = get_number(c, r, "time", "render", &time, &has_time)) != IL_OK ||
        (s = get_string(c, r, "method", "render", &method)) != IL_OK)
        return s;
    if (has_time && !(time > 0 && time <= 365.0 * 24.0 * 3600.0))
        return bad(c, "render.time", "expected seconds > 0, at most a year");
    if (method && strlen(method) >= sizeof o->method)
        return bad(c, "render.method", "name too long");
    o->width = (uint32_t)w;
    o->height = (uint32_t)h;
    o->spp = (uint32_t)spp;
    o->max_depth = (uint32_t)depth;
    o->seed = (uint64_t)seed;
    o->time_limit = time;
    if (method)
        snprintf(o->method, sizeof o->method, "%s", method);
    c->scene->has_render_settings = true;
    return IL_OK;
}

/* "line L, column C" of the byte at `at` in `text`. */
static void line_col(const char *text, const char *at, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (const char *p = text; p < at && *p; p++) {
        if (*p == '\n')
            (*line)++, *col = 1;
        else
            (*col)++;
    }
}

static il_status parse_scene(jctx *c, const cJSON *root)
{
    static const char *const keys[] = {"meshes", "materials", "lights", "camera", "environment",
                                       "render", NULL};
    if (!cJSON_IsObject(root))
        return il_fail(c->err, IL_ERR_FORMAT, "%s: expected a JSON object {...} at the top level",
                       c->path);
    check_keys(c, root, "", keys);
    il_status s;
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "materials")) &&
        (s = parse_materials(c, v)) != IL_OK)
        return s;
    v = cJSON_GetObjectItemCaseSensitive(root, "meshes");
    if (!v)
        return il_fail(c->err, IL_ERR_FORMAT, "%s: meshes: missing (an array of meshes)", c->path);
    if (!cJSON_IsArray(v))
        return bad(c, "meshes", "expected an array [...]");
    if ((s = parse_items(c, v, "meshes", parse_mesh)) != IL_OK)
        return s;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "lights"))) {
        if (!cJSON_IsArray(v))
            return bad(c, "lights", "expected an array [...]");
        if ((s = parse_items(c, v, "lights", parse_light)) != IL_OK)
            return s;
    }
    /* After the meshes, so that it replaces a camera found in a mesh file. */
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "camera")) && (s = parse_camera(c, v)) != IL_OK)
        return s;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "environment")) &&
        (s = parse_environment(c, v)) != IL_OK)
        return s;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "render")) && (s = parse_render(c, v)) != IL_OK)
        return s;
    return IL_OK;
}

static int compare_keys(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* A key that appears twice in object o itself, or NULL: its keys sorted
 * (an object of materials may hold 10^5). */
static const char *repeated_key(const cJSON *o)
{
    size_t n = 0;
    for (const cJSON *a = o->child; a; a = a->next)
        n += a->string != NULL;
    if (n < 2)
        return NULL;
    const char **keys = malloc(n * sizeof *keys);
    if (!keys)
        return NULL;   /* no memory to check: the scene is read as cJSON reads it */
    n = 0;
    for (const cJSON *a = o->child; a; a = a->next)
        if (a->string)
            keys[n++] = a->string;
    qsort(keys, n, sizeof *keys, compare_keys);
    const char *dup = NULL;
    for (size_t i = 1; i < n && !dup; i++)
        if (!strcmp(keys[i - 1], keys[i]))
            dup = keys[i];
    free(keys);
    return dup;
}

const char *il_json_duplicate_key(const cJSON *j)
{
    const char *d = cJSON_IsObject(j) ? repeated_key(j) : NULL;
    for (const cJSON *a = j ? j->child : NULL; a && !d; a = a->next)
        d = il_json_duplicate_key(a);
    return d;
}

il_status il_load_json(il_scene *scene, const char *path, il_error *err)
{
    il_error local;
    if (!err)
        err = &local;
    char *text;
    size_t size;
    il_status s = il_load_read_file(path, &text, &size, err);
    if (s != IL_OK)
        return s;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, size, &end, false);
    if (!root) {
        int line, col;
        line_col(text, end ? end : text, &line, &col);
        s = il_fail(err, IL_ERR_FORMAT, "%s: invalid JSON near line %d, column %d", path, line,
                    col);
        free(text);
        return s;
    }
    /* What follows the scene's object must be blank: text after it is a
     * mistake (two objects, or a cut and paste) that would be ignored. */
    const char *rest = end, *dup;
    while (rest < text + size && *rest && strchr(" \t\r\n", *rest))
        rest++;
    if (rest < text + size) {
        int line, col;
        line_col(text, rest, &line, &col);
        s = il_fail(err, IL_ERR_FORMAT, "%s: text after the scene's JSON object, near line %d, "
                    "column %d", path, line, col);
    } else if ((dup = il_json_duplicate_key(root))) {
        s = il_fail(err, IL_ERR_FORMAT, "%s: the key \"%s\" appears twice in one object (only one "
                    "would be read)", path, dup);
    }
    if (s != IL_OK) {
        cJSON_Delete(root);
        free(text);
        return s;
    }
    jctx c = {.scene = scene, .path = path, .err = err};
    const char *slash = strrchr(path, '/');
    if (slash && (size_t)(slash - path + 1) < sizeof c.dir)
        memcpy(c.dir, path, (size_t)(slash - path + 1));
    s = parse_scene(&c, root);
    free(c.mats);
    cJSON_Delete(root);
    free(text);
    return s;
}
