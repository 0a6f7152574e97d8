/* il_image: allocation, and reading / writing by format.  Reading loads the
 * whole file and picks the decoder by its magic bytes (the extension only
 * names the expected format in the error message); writing picks the encoder
 * by extension and goes through a temporary file in the same directory that
 * is renamed over the target only once everything has been written, so a
 * failed or interrupted write never leaves a partial file. */
#include "image/image_io.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "image/tonemap.h"

il_status il_image_check_size(uint64_t width, uint64_t height, const char *path,
                              il_error *err)
{
    if (width == 0 || height == 0)
        return il_fail(err, IL_ERR_FORMAT, "%s: image has zero size (%llux%llu)", path,
                       (unsigned long long)width, (unsigned long long)height);
    if (width > IL_IMAGE_MAX_SIDE || height > IL_IMAGE_MAX_SIDE)
        return il_fail(err, IL_ERR_FORMAT, "%s: image size %llux%llu exceeds %u per side (corrupt?)",
                       path, (unsigned long long)width, (unsigned long long)height,
                       IL_IMAGE_MAX_SIDE);
    if (width * height > IL_IMAGE_MAX_PIXELS)
        return il_fail(err, IL_ERR_FORMAT, "%s: image size %llux%llu exceeds %llu pixels (corrupt?)",
                       path, (unsigned long long)width, (unsigned long long)height,
                       (unsigned long long)IL_IMAGE_MAX_PIXELS);
    return IL_OK;
}

il_status il_image_alloc(il_image *image, uint32_t width, uint32_t height, il_error *err)
{
    if (!image)
        return il_fail(err, IL_ERR_INVALID, "il_image_alloc: image is NULL");
    image->width = image->height = 0;
    image->rgb = NULL;
    if (width == 0 || height == 0 || width > IL_IMAGE_MAX_SIDE || height > IL_IMAGE_MAX_SIDE ||
        (uint64_t)width * height > IL_IMAGE_MAX_PIXELS)
        return il_fail(err, IL_ERR_INVALID, "image size %ux%u is out of range (1..%u per side, "
                       "%llu pixels)", width, height, IL_IMAGE_MAX_SIDE,
                       (unsigned long long)IL_IMAGE_MAX_PIXELS);
    /* 65536^2 * 3 floats fits in size_t on every 64-bit target; the check
     * keeps 32-bit targets honest. */
    size_t n = (size_t)width * height;
    if (n > SIZE_MAX / (3 * sizeof(float)))
        return il_fail(err, IL_ERR_MEMORY, "image size %ux%u is too large", width, height);
    float *rgb = il_calloc(n * 3, sizeof(float), err);
    if (!rgb)
        return IL_ERR_MEMORY;
    image->width = width;
    image->height = height;
    image->rgb = rgb;
    return IL_OK;
}

void il_image_free(il_image *image)
{
    if (!image)
        return;
    free(image->rgb);
    image->rgb = NULL;
    image->width = image->height = 0;
}

/* ------------------------------------------------------------------ read */

/* Loads the whole file.  A file that cannot be opened or read is IL_ERR_IO. */
static il_status read_file(const char *path, unsigned char **out_data, size_t *out_size,
                           il_error *err)
{
    *out_data = NULL;
    *out_size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return il_fail(err, IL_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    if (!il_input_is_file(f)) {
        fclose(f);
        return il_fail(err, IL_ERR_IO, "%s: not a file", path);
    }
    size_t cap = 1 << 16, size = 0;
    unsigned char *data = il_malloc(cap, err);
    if (!data) {
        fclose(f);
        return IL_ERR_MEMORY;
    }
    for (;;) {
        if (size == cap) {
            if (cap > SIZE_MAX / 2) {
                free(data);
                fclose(f);
                return il_fail(err, IL_ERR_MEMORY, "%s: file too large", path);
            }
            unsigned char *bigger = realloc(data, cap * 2);
            if (!bigger) {
                free(data);
                fclose(f);
                return il_fail(err, IL_ERR_MEMORY, "%s: out of memory reading the file", path);
            }
            data = bigger;
            cap *= 2;
        }
        size_t got = fread(data + size, 1, cap - size, f);
        size += got;
        if (got == 0)
            break;
    }
    int failed = ferror(f);
    int saved_errno = errno;
    fclose(f);
    if (failed) {
        free(data);
        return il_fail(err, IL_ERR_IO, "%s: cannot read: %s", path, strerror(saved_errno));
    }
    *out_data = data;
    *out_size = size;
    return IL_OK;
}

typedef enum image_format {
    FORMAT_UNKNOWN = 0,
    FORMAT_EXR,
    FORMAT_HDR,
    FORMAT_PFM,
    FORMAT_PNG,
    FORMAT_JPEG
} image_format;

static const char *format_name(image_format f)
{
    switch (f) {
    case FORMAT_EXR: return "OpenEXR";
    case FORMAT_HDR: return "Radiance HDR";
    case FORMAT_PFM: return "PFM";
    case FORMAT_PNG: return "PNG";
    case FORMAT_JPEG: return "JPEG";
    case FORMAT_UNKNOWN: break;
    }
    return "unknown";
}

static bool has_prefix(const unsigned char *data, size_t size, const char *magic, size_t n)
{
    return size >= n && memcmp(data, magic, n) == 0;
}

static image_format format_from_magic(const unsigned char *d, size_t n)
{
    if (has_prefix(d, n, "\x76\x2f\x31\x01", 4))
        return FORMAT_EXR;
    if (has_prefix(d, n, "\x89PNG\r\n\x1a\n", 8))
        return FORMAT_PNG;
    if (has_prefix(d, n, "\xff\xd8\xff", 3))
        return FORMAT_JPEG;
    if (has_prefix(d, n, "#?", 2))
        return FORMAT_HDR;
    if (n >= 3 && d[0] == 'P' && (d[1] == 'F' || d[1] == 'f') &&
        (d[2] == '\n' || d[2] == '\r' || d[2] == ' ' || d[2] == '\t'))
        return FORMAT_PFM;
    return FORMAT_UNKNOWN;
}

/* The extension of `path` (after the last '.' of the last path component),
 * or "" when there is none. */
static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot ? dot + 1 : "";
}

static image_format format_from_extension(const char *path)
{
    const char *ext = extension(path);
    if (strcasecmp(ext, "exr") == 0)
        return FORMAT_EXR;
    if (strcasecmp(ext, "hdr") == 0 || strcasecmp(ext, "rgbe") == 0 || strcasecmp(ext, "pic") == 0)
        return FORMAT_HDR;
    if (strcasecmp(ext, "pfm") == 0)
        return FORMAT_PFM;
    if (strcasecmp(ext, "png") == 0)
        return FORMAT_PNG;
    if (strcasecmp(ext, "jpg") == 0 || strcasecmp(ext, "jpeg") == 0)
        return FORMAT_JPEG;
    return FORMAT_UNKNOWN;
}

il_status il_image_read(const char *path, il_image *out, il_error *err)
{
    if (!out)
        return il_fail(err, IL_ERR_INVALID, "il_image_read: output image is NULL");
    out->width = out->height = 0;
    out->rgb = NULL;
    if (!path || !path[0])
        return il_fail(err, IL_ERR_INVALID, "il_image_read: empty path");

    unsigned char *data = NULL;
    size_t size = 0;
    il_status st = read_file(path, &data, &size, err);
    if (st != IL_OK)
        return st;

    image_format fmt = format_from_magic(data, size);
    switch (fmt) {
    case FORMAT_EXR: st = il_exr_read(data, size, path, out, err); break;
    case FORMAT_HDR: st = il_hdr_read(data, size, path, out, err); break;
    case FORMAT_PFM: st = il_pfm_read(data, size, path, out, err); break;
    case FORMAT_PNG: st = il_png_read(data, size, path, out, err); break;
    case FORMAT_JPEG: st = il_jpeg_read(data, size, path, out, err); break;
    case FORMAT_UNKNOWN: {
        image_format expected = format_from_extension(path);
        if (size == 0)
            st = il_fail(err, IL_ERR_FORMAT, "%s: file is empty", path);
        else if (expected != FORMAT_UNKNOWN)
            st = il_fail(err, IL_ERR_FORMAT, "%s: not a valid %s file (bad signature)", path,
                         format_name(expected));
        else
            st = il_fail(err, IL_ERR_FORMAT,
                         "%s: unknown image format (expected EXR, HDR, PFM, PNG or JPEG)", path);
        break;
    }
    }
    free(data);
    if (st != IL_OK)
        il_image_free(out);
    return st;
}

/* ----------------------------------------------------------------- write */

/* Writes the image into `f` in format `fmt`. */
static il_status encode(const il_image *image, image_format fmt, FILE *f, const char *path,
                        const il_write_desc *desc, il_error *err)
{
    switch (fmt) {
    case FORMAT_EXR: return il_exr_write(image, f, path, desc->exr_precision, err);
    case FORMAT_HDR: return il_hdr_write(image, f, path, err);
    case FORMAT_PFM: return il_pfm_write(image, f, path, err);
    case FORMAT_PNG:
        return desc->tonemap ? il_png_write_tonemapped(image, f, path, desc->tonemap, err)
                             : il_png_write(image, f, path, desc->exposure, err);
    case FORMAT_JPEG:
    case FORMAT_UNKNOWN: break;
    }
    return il_fail(err, IL_ERR_INVALID, "%s: cannot write this format", path);
}

il_status il_image_write(const il_image *image, const char *path, const il_write_desc *desc,
                         il_error *err)
{
    if (!path || !path[0])
        return il_fail(err, IL_ERR_INVALID, "il_image_write: empty path");
    if (!image || !image->rgb || image->width == 0 || image->height == 0)
        return il_fail(err, IL_ERR_INVALID, "%s: cannot write an empty image", path);
    if (image->width > IL_IMAGE_MAX_SIDE || image->height > IL_IMAGE_MAX_SIDE)
        return il_fail(err, IL_ERR_INVALID, "%s: image size %ux%u exceeds %u per side", path,
                       image->width, image->height, IL_IMAGE_MAX_SIDE);
    image_format fmt = format_from_extension(path);
    if (fmt == FORMAT_UNKNOWN || fmt == FORMAT_JPEG)
        return il_fail(err, IL_ERR_INVALID,
                       "%s: unknown output image format '.%s' (use .exr, .hdr, .pfm or .png)",
                       path, extension(path));
    il_write_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    /* Bad tone-mapping settings fail before any file is created. */
    if (fmt == FORMAT_PNG && desc->tonemap) {
        il_status bad = il_tonemap_check(desc->tonemap, err);
        if (bad != IL_OK)
            return bad;
    }

    il_atomic_file af;
    il_status st = il_atomic_open(&af, path, err);
    if (st != IL_OK)
        return st;
    return il_atomic_close(&af, encode(image, fmt, af.f, path, desc, err), err);
}
