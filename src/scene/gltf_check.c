/* glTF 2.0: the file's layout and its byte ranges checked before assimp
 * reads it.
 *
 * assimp 5.2 trusts a glTF's numbers: a bufferView whose byteOffset is
 * 2^64 - 1 makes it copy from before its buffer (a heap overflow), and a
 * GLB chunk that claims 2 GB makes it allocate that much before it fails
 * with "No suitable reader found".  This checks what the glTF 2.0
 * specification (Khronos, 2021) requires of them, and refuses the file
 * naming what is wrong:
 * - a GLB (section 4.4): magic, version 2, a total length the file holds,
 *   chunks inside it, the first one JSON (a version 1 GLB, KHR_binary_glTF,
 *   is left to assimp);
 * - the JSON parses (the line and column where it breaks);
 * - buffers (5.10): a byteLength that the GLB's BIN chunk, the data: URI or
 *   the file it names holds (a file not found as named is left to assimp);
 * - bufferViews (5.11): their buffer exists, byteOffset + byteLength
 *   within its byteLength, byteStride 4 to 252;
 * - accessors (5.1): their bufferView exists, a known componentType and
 *   type, count >= 1, and the last element's bytes within the view.
 * What it does not check (sparse accessors, which views a mesh uses) is
 * left to assimp. */
#include <cjson/cJSON.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/error.h"
#include "scene/loader.h"

/* Integers in a glTF are JSON numbers; beyond 2^53 a double no longer
 * holds every integer, and no file is that large. */
#define GLTF_MAX_INT 9007199254740992.0

typedef struct gltf_ctx {
    const char *path;
    il_error *err;
    const cJSON *root;
    uint64_t bin_length;  /* a GLB's BIN chunk, UINT64_MAX without one */
} gltf_ctx;

static uint32_t le32(const unsigned char *u)
{
    return u[0] | (uint32_t)u[1] << 8 | (uint32_t)u[2] << 16 | (uint32_t)u[3] << 24;
}

/* The GLB header and chunks (spec 4.4); *json and *json_len the JSON chunk. */
static il_status glb_layout(gltf_ctx *c, const unsigned char *u, size_t n, const char **json,
                            size_t *json_len)
{
    if (n < 12)
        return il_fail(c->err, IL_ERR_FORMAT, "%s: truncated GLB file (%zu bytes, less than its "
                       "12-byte header)", c->path, n);
    uint32_t version = le32(u + 4), length = le32(u + 8);
    if (version != 2)
        return il_fail(c->err, IL_ERR_FORMAT, "%s: GLB version %u (illum reads glTF 2.0 and the "
                       "binary glTF 1.0 of KHR_binary_glTF)", c->path, version);
    if (length > n)
        return il_fail(c->err, IL_ERR_FORMAT, "%s: truncated GLB file (%zu bytes, the header says %u)",
                       c->path, n, length);
    *json = NULL;
    c->bin_length = UINT64_MAX;
    for (size_t at = 12; at < length;) {
        if (length - at < 8)
            return il_fail(c->err, IL_ERR_FORMAT, "%s: GLB chunk header cut off at byte %zu", c->path, at);
        uint32_t len = le32(u + at), type = le32(u + at + 4);
        if (len > length - at - 8)
            return il_fail(c->err, IL_ERR_FORMAT, "%s: GLB chunk at byte %zu claims %u bytes, more than "
                           "the %zu left: the file is corrupt or truncated", c->path, at, len,
                           length - at - 8);
        if (at == 12 && (type != 0x4E4F534Au || len == 0))
            return il_fail(c->err, IL_ERR_FORMAT, "%s: the first GLB chunk is not a JSON chunk with "
                           "content", c->path);
        if (at == 12) {
            *json = (const char *)u + at + 8;
            *json_len = len;
        } else if (type == 0x004E4942u && c->bin_length == UINT64_MAX) {
            c->bin_length = len;
        }
        at += 8 + (size_t)len;
    }
    if (!*json)
        return il_fail(c->err, IL_ERR_FORMAT, "%s: the GLB file has no chunks", c->path);
    return IL_OK;
}

/* Where a JSON text stops parsing, as "line L, column C". */
static il_status json_broken(gltf_ctx *c, const char *text, size_t n, const char *end)
{
    unsigned line = 1, col = 1;
    for (const char *p = text; end && p < end && p < text + n; p++)
        line += *p == '\n', col = *p == '\n' ? 1 : col + 1;
    return il_fail(c->err, IL_ERR_FORMAT, "%s: broken glTF JSON near line %u, column %u%s", c->path,
                   line, col, end && end >= text + n ? " (the file ends too early)" : "");
}

/* Member `key` of object o as a whole number in [0, 2^53] into *v (def
 * when absent and def >= 0); false, with the error set, otherwise. */
static bool get_uint(gltf_ctx *c, const cJSON *o, const char *what, int index, const char *key,
                     double def, double *v)
{
    const cJSON *j = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!j && def >= 0) {
        *v = def;
        return true;
    }
    double x = cJSON_IsNumber(j) ? j->valuedouble : -1.0;
    if (x >= 0 && x <= GLTF_MAX_INT && x == (double)(uint64_t)x) {
        *v = x;
        return true;
    }
    il_fail(c->err, IL_ERR_FORMAT, "%s: %s[%d].%s is %s (a whole number from 0 is required)", c->path,
            what, index, key, j ? "out of range" : "missing");
    return false;
}

/* The bytes buffer i's uri gives: a data: URI's decoded size (rounded
 * up), or the size of the file it names beside the glTF; -1 when there is
 * no such file as written (it may be percent-encoded: left to assimp). */
static double uri_bytes(const gltf_ctx *c, const char *uri)
{
    if (!strncmp(uri, "data:", 5)) {
        const char *comma = strchr(uri, ',');
        return comma ? (double)strlen(comma + 1) / 4.0 * 3.0 : -1.0;
    }
    const char *slash = strrchr(c->path, '/');
    size_t dir = slash ? (size_t)(slash - c->path) + 1 : 0;
    size_t len = dir + strlen(uri) + 1;
    char *file = malloc(len);
    if (!file)
        return -1.0;
    snprintf(file, len, "%.*s%s", (int)dir, c->path, uri);
    struct stat st;
    double bytes = stat(file, &st) == 0 && S_ISREG(st.st_mode) ? (double)st.st_size : -1.0;
    free(file);
    return bytes;
}

static il_status check_buffers(gltf_ctx *c, double **lengths, int *count)
{
    const cJSON *bufs = cJSON_GetObjectItemCaseSensitive(c->root, "buffers");
    *count = cJSON_IsArray(bufs) ? cJSON_GetArraySize(bufs) : 0;
    *lengths = calloc(*count ? (size_t)*count : 1, sizeof **lengths);
    if (!*lengths)
        return il_fail(c->err, IL_ERR_MEMORY, "%s: out of memory", c->path);
    for (int i = 0; i < *count; i++) {
        const cJSON *b = cJSON_GetArrayItem(bufs, i);
        if (!get_uint(c, b, "buffers", i, "byteLength", -1.0, &(*lengths)[i]))
            return IL_ERR_FORMAT;
        const cJSON *uri = cJSON_GetObjectItemCaseSensitive(b, "uri");
        double have;
        if (cJSON_IsString(uri))
            have = uri_bytes(c, uri->valuestring);
        else if (i == 0 && c->bin_length != UINT64_MAX)
            have = (double)c->bin_length;
        else
            return il_fail(c->err, IL_ERR_FORMAT, "%s: buffers[%d] has no uri and no GLB BIN chunk",
                           c->path, i);
        if (have >= 0 && (*lengths)[i] > have)
            return il_fail(c->err, IL_ERR_FORMAT, "%s: buffers[%d] claims %.0f bytes, but holds %.0f: "
                           "the file is corrupt or truncated", c->path, i, (*lengths)[i], have);
    }
    return IL_OK;
}

/* Each view's byteLength and byteStride into view_len / view_stride. */
static il_status check_views(gltf_ctx *c, const double *buf_len, int num_bufs, double **view_len,
                             double **view_stride, int *count)
{
    const cJSON *views = cJSON_GetObjectItemCaseSensitive(c->root, "bufferViews");
    *count = cJSON_IsArray(views) ? cJSON_GetArraySize(views) : 0;
    *view_len = calloc(*count ? (size_t)*count : 1, sizeof **view_len);
    *view_stride = calloc(*count ? (size_t)*count : 1, sizeof **view_stride);
    if (!*view_len || !*view_stride)
        return il_fail(c->err, IL_ERR_MEMORY, "%s: out of memory", c->path);
    for (int i = 0; i < *count; i++) {
        const cJSON *v = cJSON_GetArrayItem(views, i);
        double buf, off, len, stride;
        if (!get_uint(c, v, "bufferViews", i, "buffer", -1.0, &buf) ||
            !get_uint(c, v, "bufferViews", i, "byteOffset", 0.0, &off) ||
            !get_uint(c, v, "bufferViews", i, "byteLength", -1.0, &len) ||
            !get_uint(c, v, "bufferViews", i, "byteStride", 0.0, &stride))
            return IL_ERR_FORMAT;
        if (buf >= num_bufs)
            return il_fail(c->err, IL_ERR_FORMAT, "%s: bufferViews[%d].buffer %.0f: there are %d "
                           "buffers", c->path, i, buf, num_bufs);
        if (off + len > buf_len[(int)buf])
            return il_fail(c->err, IL_ERR_FORMAT, "%s: bufferViews[%d] (bytes %.0f to %.0f) runs past "
                           "its buffer's %.0f bytes", c->path, i, off, off + len, buf_len[(int)buf]);
        if (stride != 0 && (stride < 4 || stride > 252))
            return il_fail(c->err, IL_ERR_FORMAT, "%s: bufferViews[%d].byteStride %.0f is outside 4 to "
                           "252", c->path, i, stride);
        (*view_len)[i] = len;
        (*view_stride)[i] = stride;
    }
    return IL_OK;
}

/* Bytes of one component of a componentType (spec 5.1.3), 0 if unknown. */
static int component_bytes(double t)
{
    switch ((int)t) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
    }
}

/* Components of an accessor type (spec 5.1.6), 0 if unknown. */
static int type_components(const char *t)
{
    static const struct { const char *name; int n; } types[] = {
        {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (!strcmp(t, types[i].name))
            return types[i].n;
    return 0;
}

static il_status check_accessors(gltf_ctx *c, const double *view_len, const double *view_stride,
                                 int num_views)
{
    const cJSON *accs = cJSON_GetObjectItemCaseSensitive(c->root, "accessors");
    int count = cJSON_IsArray(accs) ? cJSON_GetArraySize(accs) : 0;
    for (int i = 0; i < count; i++) {
        const cJSON *a = cJSON_GetArrayItem(accs, i);
        const cJSON *type = cJSON_GetObjectItemCaseSensitive(a, "type");
        double ctype, n, view, off;
        if (!get_uint(c, a, "accessors", i, "componentType", -1.0, &ctype) ||
            !get_uint(c, a, "accessors", i, "count", -1.0, &n) ||
            !get_uint(c, a, "accessors", i, "byteOffset", 0.0, &off))
            return IL_ERR_FORMAT;
        int comps = cJSON_IsString(type) ? type_components(type->valuestring) : 0;
        if (!component_bytes(ctype) || !comps || n < 1)
            return il_fail(c->err, IL_ERR_FORMAT, "%s: accessors[%d] needs a known componentType and "
                           "type and a count of at least 1", c->path, i);
        if (!cJSON_GetObjectItemCaseSensitive(a, "bufferView"))
            continue;   /* all zeros (or sparse): nothing read from a buffer */
        if (!get_uint(c, a, "accessors", i, "bufferView", -1.0, &view))
            return IL_ERR_FORMAT;
        if (view >= num_views)
            return il_fail(c->err, IL_ERR_FORMAT, "%s: accessors[%d].bufferView %.0f: there are %d "
                           "bufferViews", c->path, i, view, num_views);
        double element = (double)component_bytes(ctype) * comps;
        double stride = view_stride[(int)view] > 0 ? view_stride[(int)view] : element;
        double last = off + (n - 1) * stride + element;
        if (last > view_len[(int)view])
            return il_fail(c->err, IL_ERR_FORMAT, "%s: accessors[%d]: %.0f elements from byte %.0f run "
                           "past its bufferView's %.0f bytes", c->path, i, n, off, view_len[(int)view]);
    }
    return IL_OK;
}

il_status il_gltf_check(const char *path, il_error *err)
{
    char *buf;
    size_t n;
    il_status s = il_load_read_file(path, &buf, &n, err);
    if (s != IL_OK)
        return s;
    gltf_ctx c = {.path = path, .err = err, .bin_length = UINT64_MAX};
    const char *json = buf;
    size_t json_len = n;
    bool glb = n >= 4 && memcmp(buf, "glTF", 4) == 0;
    if (glb && n >= 8 && le32((const unsigned char *)buf + 4) == 1) {
        free(buf);    /* binary glTF 1.0: another layout, left to assimp */
        return IL_OK;
    }
    if (glb)
        s = glb_layout(&c, (const unsigned char *)buf, n, &json, &json_len);
    cJSON *root = NULL;
    if (s == IL_OK) {
        const char *end = NULL;
        root = cJSON_ParseWithLengthOpts(json, json_len, &end, false);
        if (!root)
            s = json_broken(&c, json, json_len, end);
    }
    double *buf_len = NULL, *view_len = NULL, *view_stride = NULL;
    int num_bufs = 0, num_views = 0;
    c.root = root;
    if (s == IL_OK)
        s = check_buffers(&c, &buf_len, &num_bufs);
    if (s == IL_OK)
        s = check_views(&c, buf_len, num_bufs, &view_len, &view_stride, &num_views);
    if (s == IL_OK)
        s = check_accessors(&c, view_len, view_stride, num_views);
    free(buf_len);
    free(view_len);
    free(view_stride);
    cJSON_Delete(root);
    free(buf);
    return s;
}
