/* Radiance HDR (RGBE) files: Greg Ward, "Real Pixels", Graphics Gems II
 * (1991), section II.5, and the Radiance file format notes (header,
 * "-Y H +X W" resolution string, new-style run-length encoded scanlines).
 *
 * Writing is our own: flat scanlines for widths the RLE cannot express
 * (< 8 or >= 32768), new-style RLE otherwise.  Reading goes through
 * stb_image's stbi_loadf; because stb_image silently fills a truncated file
 * with zeros (and can loop forever on a truncated RLE stream), the file's
 * structure is first checked here, byte for byte, against what stb_image
 * will read. */
#include "image/image_io.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <stb/stb_image.h>

#include "core/error.h"

/* ------------------------------------------------------------ pixels */

/* Largest/smallest exponent byte: value = mantissa * 2^(byte - 136). */
#define RGBE_MAX_EXP 127
#define RGBE_MIN_EXP (-127)

static float rgbe_sanitize(float v)
{
    if (!(v > 0.0f)) /* NaN and negatives: RGBE cannot represent them */
        return 0.0f;
    return v;
}

void il_rgbe_encode(const float rgb[3], unsigned char rgbe[4])
{
    double c[3] = {rgbe_sanitize(rgb[0]), rgbe_sanitize(rgb[1]), rgbe_sanitize(rgb[2])};
    double v = fmax(c[0], fmax(c[1], c[2]));
    if (v <= 0.0) {
        memset(rgbe, 0, 4);
        return;
    }
    int e = RGBE_MAX_EXP + 1;
    if (isfinite(v))
        (void)frexp(v, &e); /* v = m 2^e, m in [0.5, 1) */
    if (e > RGBE_MAX_EXP) {
        /* Beyond the format's range (or +Inf): clamp to the largest value. */
        e = RGBE_MAX_EXP;
        for (int k = 0; k < 3; k++)
            c[k] = c[k] >= v ? 255.0 : fmin(255.0, c[k] * ldexp(1.0, 8 - e));
        for (int k = 0; k < 3; k++)
            rgbe[k] = (unsigned char)lrint(c[k]);
        rgbe[3] = (unsigned char)(e + 128);
        return;
    }
    if (e < RGBE_MIN_EXP)
        e = RGBE_MIN_EXP;
    /* Ward truncates; rounding to nearest halves the error to at most 2^-8
     * of the largest component.  Rounding can carry the largest mantissa to
     * 256, then the exponent goes up by one. */
    double scale = ldexp(1.0, 8 - e);
    if (lrint(v * scale) > 255 && e < RGBE_MAX_EXP) {
        e++;
        scale = ldexp(1.0, 8 - e);
    }
    for (int k = 0; k < 3; k++) {
        long m = lrint(c[k] * scale);
        rgbe[k] = (unsigned char)(m > 255 ? 255 : m);
    }
    rgbe[3] = (unsigned char)(e + 128);
}

void il_rgbe_decode(const unsigned char rgbe[4], float rgb[3])
{
    if (rgbe[3] == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    /* Same formula as stb_image (no +0.5 offset: our encoder rounds). */
    float f = ldexpf(1.0f, (int)rgbe[3] - (128 + 8));
    for (int k = 0; k < 3; k++)
        rgb[k] = rgbe[k] * f;
}

/* ------------------------------------------------------------ write */

/* New-style RLE of one component of a scanline: runs of 4 or more equal
 * bytes become (128 + n, value), n <= 127; the rest is dumped as (n, n
 * bytes), n <= 128. */
static size_t rle_component(const unsigned char *b, size_t w, unsigned char *out)
{
    size_t o = 0, i = 0;
    while (i < w) {
        size_t j = i, run = 0;
        while (j < w) {
            run = 1;
            while (j + run < w && run < 127 && b[j + run] == b[j])
                run++;
            if (run >= 4)
                break;
            j += run;
            run = 0;
        }
        while (i < j) {
            size_t n = j - i < 128 ? j - i : 128;
            out[o++] = (unsigned char)n;
            memcpy(out + o, b + i, n);
            o += n;
            i += n;
        }
        if (run >= 4) {
            out[o++] = (unsigned char)(128 + run);
            out[o++] = b[j];
            i = j + run;
        }
    }
    return o;
}

il_status il_hdr_write(const il_image *image, FILE *f, const char *path, il_error *err)
{
    size_t w = image->width, h = image->height;
    if (fprintf(f, "#?RADIANCE\n# written by illum\nFORMAT=32-bit_rle_rgbe\n\n-Y %zu +X %zu\n",
                h, w) < 0)
        return il_fail(err, IL_ERR_IO, "%s: cannot write", path);
    bool rle = w >= 8 && w < 32768;
    unsigned char *pix = il_malloc(w * 4, err);                   /* RGBE, interleaved */
    unsigned char *plane = il_malloc(w, err);                     /* one component */
    unsigned char *out = il_malloc(4 + 4 * (w + w / 128 + 2), err); /* encoded scanline */
    il_status st = IL_OK;
    if (!pix || !plane || !out) {
        st = IL_ERR_MEMORY;
        goto done;
    }
    for (size_t y = 0; y < h; y++) {
        const float *src = image->rgb + y * w * 3;
        for (size_t x = 0; x < w; x++)
            il_rgbe_encode(src + x * 3, pix + x * 4);
        size_t n;
        if (rle) {
            out[0] = 2;
            out[1] = 2;
            out[2] = (unsigned char)(w >> 8);
            out[3] = (unsigned char)(w & 0xff);
            n = 4;
            for (int k = 0; k < 4; k++) {
                for (size_t x = 0; x < w; x++)
                    plane[x] = pix[x * 4 + k];
                n += rle_component(plane, w, out + n);
            }
            if (fwrite(out, 1, n, f) != n) {
                st = il_fail(err, IL_ERR_IO, "%s: cannot write", path);
                break;
            }
        } else if (fwrite(pix, 1, w * 4, f) != w * 4) {
            st = il_fail(err, IL_ERR_IO, "%s: cannot write", path);
            break;
        }
    }
done:
    free(pix);
    free(plane);
    free(out);
    return st;
}

/* ------------------------------------------------------------- read */

/* Reads one header line (without its '\n') into buf; false at the end of the
 * data (a header line must end with '\n').  Overlong lines are cut, as
 * stb_image does. */
static bool header_line(const unsigned char **p, const unsigned char *end, char *buf, size_t cap)
{
    size_t n = 0;
    while (*p < end && **p != '\n') {
        if (n + 1 < cap)
            buf[n++] = (char)**p;
        (*p)++;
    }
    buf[n] = '\0';
    if (*p >= end)
        return false;
    (*p)++; /* the '\n' */
    return true;
}

static bool parse_dim(const char **s, long *out)
{
    if (**s < '0' || **s > '9')
        return false;
    char *end;
    *out = strtol(*s, &end, 10);
    *s = end;
    return true;
}

/* Checks the pixel stream that starts at p: complete, and well-formed the
 * way stb_image's decoder expects (which otherwise reads past the end as
 * zeros). */
static il_status check_pixels(const unsigned char *p, const unsigned char *end, size_t w,
                              size_t h, const char *path, il_error *err)
{
    size_t avail = (size_t)(end - p);
    bool flat = w < 8 || w >= 32768;
    if (!flat && avail >= 4 && !(p[0] == 2 && p[1] == 2 && !(p[2] & 0x80)))
        flat = true; /* an uncompressed file of RLE-able width */
    if (flat) {
        if (avail / 4 / w < h)
            return il_fail(err, IL_ERR_FORMAT, "%s: HDR pixel data is truncated", path);
        return IL_OK;
    }
    for (size_t y = 0; y < h; y++) {
        if ((size_t)(end - p) < 4)
            return il_fail(err, IL_ERR_FORMAT, "%s: HDR pixel data is truncated (scanline %zu)",
                           path, y);
        if (p[0] != 2 || p[1] != 2 || (p[2] & 0x80))
            return il_fail(err, IL_ERR_FORMAT,
                           "%s: HDR scanline %zu is not run-length encoded like the others", path,
                           y);
        if (((size_t)p[2] << 8 | p[3]) != w)
            return il_fail(err, IL_ERR_FORMAT, "%s: HDR scanline %zu has the wrong length", path, y);
        p += 4;
        for (int k = 0; k < 4; k++) {
            size_t x = 0;
            while (x < w) {
                if (p >= end)
                    return il_fail(err, IL_ERR_FORMAT,
                                   "%s: HDR pixel data is truncated (scanline %zu)", path, y);
                unsigned count = *p++;
                if (count > 128) {
                    count -= 128;
                    if (count > w - x || p >= end)
                        return il_fail(err, IL_ERR_FORMAT,
                                       "%s: HDR scanline %zu has a bad run (corrupt or truncated)",
                                       path, y);
                    p++;
                } else {
                    if (count == 0 || count > w - x || (size_t)(end - p) < count)
                        return il_fail(err, IL_ERR_FORMAT,
                                       "%s: HDR scanline %zu has bad data (corrupt or truncated)",
                                       path, y);
                    p += count;
                }
                x += count;
            }
        }
    }
    return IL_OK;
}

il_status il_hdr_read(const unsigned char *data, size_t size, const char *path, il_image *out,
                      il_error *err)
{
    const unsigned char *p = data, *end = data + size;
    char line[1024];
    if (!header_line(&p, end, line, sizeof line) ||
        (strcmp(line, "#?RADIANCE") != 0 && strcmp(line, "#?RGBE") != 0))
        return il_fail(err, IL_ERR_FORMAT, "%s: not a Radiance HDR file (expected '#?RADIANCE')",
                       path);
    bool rgbe = false;
    for (;;) {
        if (!header_line(&p, end, line, sizeof line))
            return il_fail(err, IL_ERR_FORMAT, "%s: HDR header is truncated", path);
        if (line[0] == '\0')
            break;
        if (strcmp(line, "FORMAT=32-bit_rle_rgbe") == 0)
            rgbe = true;
        else if (strncmp(line, "FORMAT=", 7) == 0)
            return il_fail(err, IL_ERR_FORMAT, "%s: unsupported HDR pixel format '%s'", path,
                           line + 7);
    }
    if (!rgbe)
        return il_fail(err, IL_ERR_FORMAT, "%s: HDR header lacks FORMAT=32-bit_rle_rgbe", path);
    if (!header_line(&p, end, line, sizeof line))
        return il_fail(err, IL_ERR_FORMAT, "%s: HDR resolution line is missing or truncated",
                       path);
    const char *s = line;
    long h = 0, w = 0;
    bool ok = strncmp(s, "-Y ", 3) == 0;
    if (ok) {
        s += 3;
        ok = parse_dim(&s, &h);
    }
    while (ok && *s == ' ')
        s++;
    ok = ok && strncmp(s, "+X ", 3) == 0;
    if (ok) {
        s += 3;
        ok = parse_dim(&s, &w) && *s == '\0';
    }
    if (!ok)
        return il_fail(err, IL_ERR_FORMAT,
                       "%s: unsupported HDR orientation or bad resolution line '%s' (need '-Y H +X W')",
                       path, line);
    il_status st = il_image_check_size((uint64_t)w, (uint64_t)h, path, err);
    if (st == IL_OK)
        st = check_pixels(p, end, (size_t)w, (size_t)h, path, err);
    if (st != IL_OK)
        return st;
    if (size > INT_MAX)
        return il_fail(err, IL_ERR_FORMAT, "%s: HDR file is too large (%zu bytes)", path, size);

    int sw = 0, sh = 0, comp = 0;
    float *pixels = stbi_loadf_from_memory(data, (int)size, &sw, &sh, &comp, 3);
    if (!pixels)
        return il_fail(err, IL_ERR_FORMAT, "%s: cannot decode HDR: %s", path,
                       stbi_failure_reason());
    if (sw != w || sh != h) {
        stbi_image_free(pixels);
        return il_fail(err, IL_ERR_FORMAT, "%s: HDR decoder disagrees on the size", path);
    }
    st = il_image_alloc(out, (uint32_t)w, (uint32_t)h, err);
    if (st == IL_OK)
        memcpy(out->rgb, pixels, (size_t)w * (size_t)h * 3 * sizeof(float));
    stbi_image_free(pixels);
    return st;
}
