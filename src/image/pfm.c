/* Portable Float Map (Paul Debevec's HDR Shop format, also written by pbrt
 * and Mitsuba):
 *
 *     "PF" (RGB) or "Pf" (grey) \n  width height \n  scale \n  raw floats
 *
 * The sign of `scale` gives the byte order (negative: little-endian), its
 * magnitude a multiplier applied on reading (as pbrt-v4 does); rows are
 * stored bottom to top.  We write RGB, little-endian, scale -1.0, so a round
 * trip is bit-exact. */
#include "image/image_io.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

/* Header parsing over a bounded buffer. */
typedef struct cursor {
    const unsigned char *p, *end;
} cursor;

static void skip_space(cursor *c)
{
    while (c->p < c->end && isspace(*c->p))
        c->p++;
}

/* Copies the next whitespace-delimited token (at most cap-1 chars) into buf;
 * false when there is none or it is too long. */
static bool next_token(cursor *c, char *buf, size_t cap)
{
    skip_space(c);
    size_t n = 0;
    while (c->p < c->end && !isspace(*c->p)) {
        if (n + 1 >= cap)
            return false;
        buf[n++] = (char)*c->p++;
    }
    buf[n] = '\0';
    return n > 0;
}

static bool parse_uint(const char *s, uint64_t *out)
{
    if (!isdigit((unsigned char)s[0]))
        return false;
    char *end;
    unsigned long long v = strtoull(s, &end, 10);
    if (*end != '\0')
        return false;
    *out = v;
    return true;
}

static float load_f32(const unsigned char *b, bool little)
{
    uint32_t u = little ? (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                              (uint32_t)b[3] << 24
                        : (uint32_t)b[3] | (uint32_t)b[2] << 8 | (uint32_t)b[1] << 16 |
                              (uint32_t)b[0] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

il_status il_pfm_read(const unsigned char *data, size_t size, const char *path, il_image *out,
                      il_error *err)
{
    cursor c = {data, data + size};
    char tok[64];
    if (!next_token(&c, tok, sizeof tok) || (strcmp(tok, "PF") != 0 && strcmp(tok, "Pf") != 0))
        return il_fail(err, IL_ERR_FORMAT, "%s: not a PFM file (expected 'PF' or 'Pf')", path);
    int channels = tok[1] == 'F' ? 3 : 1;

    uint64_t w, h;
    if (!next_token(&c, tok, sizeof tok) || !parse_uint(tok, &w) ||
        !next_token(&c, tok, sizeof tok) || !parse_uint(tok, &h))
        return il_fail(err, IL_ERR_FORMAT, "%s: PFM header has no valid width and height", path);
    il_status st = il_image_check_size(w, h, path, err);
    if (st != IL_OK)
        return st;

    char *end;
    if (!next_token(&c, tok, sizeof tok))
        return il_fail(err, IL_ERR_FORMAT, "%s: PFM header has no scale", path);
    double scale = strtod(tok, &end);
    if (*end != '\0' || !isfinite(scale) || scale == 0.0)
        return il_fail(err, IL_ERR_FORMAT, "%s: PFM scale '%s' is not a non-zero number", path, tok);
    /* Exactly one whitespace character separates the header from the data. */
    if (c.p >= c.end || !isspace(*c.p))
        return il_fail(err, IL_ERR_FORMAT, "%s: PFM header is truncated", path);
    c.p++;

    bool little = scale < 0.0;
    float mult = (float)fabs(scale);
    uint64_t need = w * h * (uint64_t)channels * 4u; /* <= 2^32 * 12: no overflow */
    if ((uint64_t)(c.end - c.p) < need)
        return il_fail(err, IL_ERR_FORMAT,
                       "%s: PFM data is truncated (%llu bytes of pixels, %llu needed)", path,
                       (unsigned long long)(c.end - c.p), (unsigned long long)need);

    st = il_image_alloc(out, (uint32_t)w, (uint32_t)h, err);
    if (st != IL_OK)
        return st;
    const unsigned char *src = c.p;
    for (uint64_t row = 0; row < h; row++) {
        /* File rows run bottom to top. */
        float *dst = out->rgb + (h - 1 - row) * w * 3;
        for (uint64_t x = 0; x < w; x++) {
            for (int k = 0; k < 3; k++) {
                const unsigned char *b = src + (channels == 3 ? k : 0) * 4;
                float v = load_f32(b, little);
                dst[x * 3 + k] = mult == 1.0f ? v : v * mult;
            }
            src += (size_t)channels * 4;
        }
    }
    return IL_OK;
}

il_status il_pfm_write(const il_image *image, FILE *f, const char *path, il_error *err)
{
    uint32_t w = image->width, h = image->height;
    if (fprintf(f, "PF\n%u %u\n-1.0\n", w, h) < 0)
        return il_fail(err, IL_ERR_IO, "%s: cannot write", path);
    unsigned char *row = il_malloc((size_t)w * 12, err);
    if (!row)
        return IL_ERR_MEMORY;
    il_status st = IL_OK;
    for (uint32_t y = h; y-- > 0;) {
        const float *src = image->rgb + (size_t)y * w * 3;
        for (size_t i = 0; i < (size_t)w * 3; i++) {
            uint32_t u;
            memcpy(&u, &src[i], 4);
            row[i * 4 + 0] = (unsigned char)(u & 0xff);
            row[i * 4 + 1] = (unsigned char)(u >> 8 & 0xff);
            row[i * 4 + 2] = (unsigned char)(u >> 16 & 0xff);
            row[i * 4 + 3] = (unsigned char)(u >> 24);
        }
        if (fwrite(row, 1, (size_t)w * 12, f) != (size_t)w * 12) {
            st = il_fail(err, IL_ERR_IO, "%s: cannot write", path);
            break;
        }
    }
    free(row);
    return st;
}
