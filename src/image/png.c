/* PNG and JPEG through stb_image / stb_image_write.
 *
 * Reading: 8-bit (and 16-bit PNG) sRGB codes are decoded to linear values with
 * the exact sRGB EOTF (IEC 61966-2-1); grey is replicated into R, G and B and
 * alpha is dropped (stb_image's conversion to 3 channels).  stb_image
 * tolerates some truncated files (a PNG cut inside its IEND chunk decodes
 * fine; older versions decode a JPEG cut in its scan data as grey), so the
 * chunk / marker structure of the whole file is checked first.
 *
 * Writing: PNG, 8-bit RGB: value * 2^exposure, sRGB OETF, clamped to [0,1],
 * rounded to the nearest code; NaN and Inf become 0.  With a tone-mapping
 * desc the codes are round(255 v) of il_tonemap's display values v instead
 * (tonemap.c; docs/tonemapping.md). */
#include "image/image_io.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "core/error.h"
#include "image/srgb.h"
#include "image/tonemap.h"

/* ------------------------------------------------------------ structure */

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* PNG (ISO/IEC 15948, section 5): signature, then chunks of length, type,
 * data and CRC, up to and including IEND.  Each chunk's CRC-32 (5.5: over
 * its type and data, polynomial 0xEDB88320, reflected) is checked: stb_image
 * ignores it, and a flipped byte in the image data decodes as other
 * pixels without a word. */
static il_status png_check_structure(const unsigned char *data, size_t size, const char *path,
                                     il_error *err)
{
    uint32_t table[256];
    for (uint32_t n = 0; n < 256; n++) {
        uint32_t c = n;
        for (int k = 0; k < 8; k++)
            c = c & 1u ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    size_t off = 8;
    bool first = true;
    for (;;) {
        if (size - off < 12)
            return il_fail(err, IL_ERR_FORMAT, "%s: PNG file is truncated (no IEND chunk)", path);
        uint32_t len = be32(data + off);
        const unsigned char *type = data + off + 4;
        if (len > 0x7fffffffu)
            return il_fail(err, IL_ERR_FORMAT, "%s: PNG chunk length is corrupt", path);
        if (first && memcmp(type, "IHDR", 4) != 0)
            return il_fail(err, IL_ERR_FORMAT, "%s: PNG file does not start with IHDR", path);
        first = false;
        if (size - off - 12 < len)
            return il_fail(err, IL_ERR_FORMAT, "%s: PNG file is truncated (chunk '%.4s')", path,
                           (const char *)type);
        uint32_t crc = 0xFFFFFFFFu;
        for (size_t k = 0; k < 4 + (size_t)len; k++)
            crc = table[(crc ^ type[k]) & 0xFFu] ^ (crc >> 8);
        if ((crc ^ 0xFFFFFFFFu) != be32(type + 4 + len))
            return il_fail(err, IL_ERR_FORMAT, "%s: PNG chunk '%.4s' is corrupt (its CRC does not "
                           "match)", path, (const char *)type);
        /* stb_image calls an image of no pixels an "unknown image type". */
        if (memcmp(type, "IHDR", 4) == 0 && len >= 8) {
            il_status st = il_image_check_size(be32(type + 4), be32(type + 8), path, err);
            if (st != IL_OK)
                return st;
        }
        off += 12 + (size_t)len;
        if (memcmp(type, "IEND", 4) == 0)
            return IL_OK;
    }
}

/* JPEG (ITU-T T.81, annex B): markers with 16-bit lengths; after SOS the
 * entropy-coded data runs to the next marker that is not a stuffed 0xFF00 or
 * a restart marker.  The file is complete when EOI is reached. */
static il_status jpeg_check_structure(const unsigned char *data, size_t size, const char *path,
                                      il_error *err)
{
    const unsigned char *p = data + 2, *end = data + size;
    for (;;) {
        if (p >= end)
            return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is truncated (no end marker)", path);
        if (*p != 0xff)
            return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is corrupt (expected a marker)", path);
        while (p < end && *p == 0xff) /* fill bytes */
            p++;
        if (p >= end)
            return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is truncated", path);
        unsigned code = *p++;
        if (code == 0xd9) /* EOI */
            return IL_OK;
        if (code == 0xd8 || code == 0x00)
            return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is corrupt (marker 0x%02x)", path,
                           code);
        if ((code >= 0xd0 && code <= 0xd7) || code == 0x01) /* no length */
            continue;
        if (end - p < 2)
            return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is truncated", path);
        size_t len = (size_t)p[0] << 8 | p[1];
        if (len < 2 || (size_t)(end - p) < len)
            return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is truncated (segment 0x%02x)", path,
                           code);
        p += len;
        if (code != 0xda) /* not SOS */
            continue;
        for (;;) { /* entropy-coded data */
            if (end - p < 2)
                return il_fail(err, IL_ERR_FORMAT, "%s: JPEG file is truncated (in scan data)",
                               path);
            if (p[0] != 0xff) {
                p++;
                continue;
            }
            unsigned next = p[1];
            if (next == 0x00 || (next >= 0xd0 && next <= 0xd7))
                p += 2;
            else if (next == 0xff)
                p++;
            else
                break; /* a real marker: back to the outer loop */
        }
    }
}

/* ---------------------------------------------------------------- read */

static il_status stb_read(const unsigned char *data, size_t size, const char *path,
                          const char *what, il_image *out, il_error *err)
{
    if (size > INT_MAX)
        return il_fail(err, IL_ERR_FORMAT, "%s: %s file is too large (%zu bytes)", path, what,
                       size);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(data, (int)size, &w, &h, &comp))
        return il_fail(err, IL_ERR_FORMAT, "%s: cannot read %s header: %s", path, what,
                       stbi_failure_reason());
    il_status st = il_image_check_size((uint64_t)(w < 0 ? 0 : w), (uint64_t)(h < 0 ? 0 : h),
                                       path, err);
    if (st != IL_OK)
        return st;

    size_t n = (size_t)w * (size_t)h * 3;
    if (stbi_is_16_bit_from_memory(data, (int)size)) {
        stbi_us *px = stbi_load_16_from_memory(data, (int)size, &w, &h, &comp, 3);
        if (!px)
            return il_fail(err, IL_ERR_FORMAT, "%s: cannot decode %s: %s", path, what,
                           stbi_failure_reason());
        st = il_image_alloc(out, (uint32_t)w, (uint32_t)h, err);
        if (st == IL_OK)
            for (size_t i = 0; i < n; i++)
                out->rgb[i] = (float)il_srgb_to_linear(px[i] / 65535.0);
        stbi_image_free(px);
        return st;
    }
    stbi_uc *px = stbi_load_from_memory(data, (int)size, &w, &h, &comp, 3);
    if (!px)
        return il_fail(err, IL_ERR_FORMAT, "%s: cannot decode %s: %s", path, what,
                       stbi_failure_reason());
    st = il_image_alloc(out, (uint32_t)w, (uint32_t)h, err);
    if (st == IL_OK) {
        float lut[256];
        for (int i = 0; i < 256; i++)
            lut[i] = (float)il_srgb_to_linear(i / 255.0);
        for (size_t i = 0; i < n; i++)
            out->rgb[i] = lut[px[i]];
    }
    stbi_image_free(px);
    return st;
}

il_status il_png_read(const unsigned char *data, size_t size, const char *path, il_image *out,
                      il_error *err)
{
    il_status st = png_check_structure(data, size, path, err);
    return st != IL_OK ? st : stb_read(data, size, path, "PNG", out, err);
}

il_status il_jpeg_read(const unsigned char *data, size_t size, const char *path, il_image *out,
                       il_error *err)
{
    il_status st = jpeg_check_structure(data, size, path, err);
    return st != IL_OK ? st : stb_read(data, size, path, "JPEG", out, err);
}

/* --------------------------------------------------------------- write */

typedef struct png_sink {
    FILE *f;
    bool failed;
} png_sink;

static void png_sink_write(void *context, void *data, int size)
{
    png_sink *s = context;
    if (size > 0 && fwrite(data, 1, (size_t)size, s->f) != (size_t)size)
        s->failed = true;
}

/* Encodes w x h RGB codes; `px` is freed. */
static il_status png_encode(unsigned char *px, size_t w, size_t h, FILE *f, const char *path,
                            il_error *err)
{
    png_sink sink = {f, false};
    int ok = stbi_write_png_to_func(png_sink_write, &sink, (int)w, (int)h, 3, px, (int)(w * 3));
    free(px);
    if (!ok)
        return il_fail(err, IL_ERR_MEMORY, "%s: PNG encoder failed (out of memory)", path);
    if (sink.failed)
        return il_fail(err, IL_ERR_IO, "%s: cannot write", path);
    return IL_OK;
}

/* stb_image_write keeps sizes in int. */
static il_status png_check_size(const il_image *image, const char *path, il_error *err)
{
    size_t w = image->width, h = image->height;
    if ((w * 3 + 1) * h > INT_MAX / 2)
        return il_fail(err, IL_ERR_INVALID, "%s: image %zux%zu is too large for the PNG writer",
                       path, w, h);
    return IL_OK;
}

il_status il_png_write(const il_image *image, FILE *f, const char *path, float exposure,
                       il_error *err)
{
    size_t w = image->width, h = image->height;
    il_status st = png_check_size(image, path, err);
    if (st != IL_OK)
        return st;
    unsigned char *px = il_malloc(w * h * 3, err);
    if (!px)
        return IL_ERR_MEMORY;
    double mult = exposure != 0.0f ? exp2((double)exposure) : 1.0;
    for (size_t i = 0; i < w * h * 3; i++) {
        float v = image->rgb[i];
        px[i] = isfinite(v) ? il_linear_to_srgb8(v * mult) : 0;
    }
    return png_encode(px, w, h, f, path, err);
}

il_status il_png_write_tonemapped(const il_image *image, FILE *f, const char *path,
                                  const il_tonemap_desc *desc, il_error *err)
{
    size_t w = image->width, h = image->height;
    il_status st = png_check_size(image, path, err);
    if (st != IL_OK)
        return st;
    il_tonemap_plan plan;
    if ((st = il_tonemap_plan_make(image, desc, &plan, err)) != IL_OK)
        return st;
    unsigned char *px = il_malloc(w * h * 3, err);
    if (px)
        il_tonemap_run(&plan, NULL, px);
    il_tonemap_plan_free(&plan);
    if (!px)
        return IL_ERR_MEMORY;
    return png_encode(px, w, h, f, path, err);
}
