/* Reading Radiance HDR pictures (RGBE and XYZE), our own decoder.  Sources:
 * the "Radiance file formats" notes (Radiance reference manual, "Picture file
 * format": header, resolution string, scanline encodings), Greg Ward, "Real
 * Pixels", Graphics Gems II (1991), II.5, and Radiance's own reader
 * (src/common/color.c: freadcolrs, oldreadcolrs, colr_color;
 * src/common/resolu.c: str2resolu), whose behaviour is followed where the
 * notes are silent.
 *
 * File layout:
 *
 *   #?RADIANCE                    magic: "#?" and a program name
 *   FORMAT=32-bit_rle_rgbe        header lines "NAME=value", comments, ...
 *   EXPOSURE=2.0
 *                                 an empty line ends the header
 *   -Y 512 +X 768                 the resolution line
 *   <pixels>                      one scanline after another
 *
 * Every scanline is decoded on its own, as Radiance does: it is new-style RLE
 * when its length is 8..32767 and it starts 2, 2, hi, lo with hi < 128 (then
 * hi:lo must equal the length; four runs of bytes follow, one per component:
 * a count byte c > 128 repeats the next byte c - 128 times, 0 < c <= 128
 * copies c literal bytes, c = 0 copies nothing); otherwise it is a sequence of
 * 4-byte RGBE pixels in which (1, 1, 1, n) is an old-style run: it repeats the
 * previous pixel n << s times, s = 0 for the first marker of a chain and 8
 * more for each following marker (so counts > 255 are written low byte
 * first).  A flat file is the special case without markers.
 *
 * Decisions where the format leaves room (docs/images.md lists them):
 * - The first line must start with "#?" (the program name after it is not
 *   checked: Radiance writes RADIANCE, others RGBE or their own name).  A
 *   file without it is refused: nothing else tells a picture from text.
 * - Header lines may end in "\r\n".  A missing FORMAT line means RGBE (as in
 *   Radiance); other formats, or FORMAT lines that disagree, are errors.
 * - EXPOSURE, COLORCORR and PIXASPECT values must be finite and positive, and
 *   their products within [1e-30, 1e30].  PIXASPECT is recorded only.
 * - A run may not cross the end of its scanline (Radiance would write past
 *   its buffer); an old-style run at the start of a scanline repeats the last
 *   pixel of the previous scanline, and one before any pixel is an error.
 * - Bytes after the last scanline are ignored.
 *
 * Every byte is read through a bounds check, every count is checked against
 * what remains of the scanline, every loop consumes input, and the output
 * image is allocated only after a first pass has decoded the whole pixel
 * stream, so a short file claiming a huge size costs no memory. */
#include "image/image_io.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/color.h"
#include "core/error.h"

/* ------------------------------------------------------------ header */

/* One line of the header, without its '\n' and a trailing '\r'. */
typedef struct hdr_line {
    const char *s;
    size_t n;
} hdr_line;

/* The line starting at *p; false when no '\n' ends it before `end`. */
static bool next_line(const unsigned char **p, const unsigned char *end, hdr_line *line)
{
    const unsigned char *nl = memchr(*p, '\n', (size_t)(end - *p));
    if (!nl)
        return false;
    line->s = (const char *)*p;
    line->n = (size_t)(nl - *p);
    if (line->n > 0 && line->s[line->n - 1] == '\r')
        line->n--;
    *p = nl + 1;
    return true;
}

static bool is_blank(char c) { return c == ' ' || c == '\t'; }

/* A printable copy of at most 40 characters of a line, for messages. */
static const char *quoted(const char *s, size_t n, char buf[48])
{
    size_t k = 0;
    for (; k < n && k < 40; k++)
        buf[k] = s[k] >= 0x20 && s[k] < 0x7f ? s[k] : '?';
    if (k < n)
        buf[k++] = '.', buf[k++] = '.', buf[k++] = '.';
    buf[k] = '\0';
    return buf;
}

/* If the line (after leading blanks) starts with `name`, sets `value` to the
 * rest with surrounding blanks removed. */
static bool header_var(hdr_line line, const char *name, hdr_line *value)
{
    size_t i = 0, len = strlen(name);
    while (i < line.n && is_blank(line.s[i]))
        i++;
    if (line.n - i < len || memcmp(line.s + i, name, len) != 0)
        return false;
    i += len;
    while (i < line.n && is_blank(line.s[i]))
        i++;
    size_t n = line.n;
    while (n > i && is_blank(line.s[n - 1]))
        n--;
    *value = (hdr_line){line.s + i, n - i};
    return true;
}

static bool value_is(hdr_line v, const char *word)
{
    return v.n == strlen(word) && memcmp(v.s, word, v.n) == 0;
}

/* Parses exactly `count` blank-separated numbers, each finite and positive. */
static bool parse_positive(hdr_line v, int count, double *out)
{
    char buf[256];
    if (v.n >= sizeof buf)
        return false;
    memcpy(buf, v.s, v.n);
    buf[v.n] = '\0';
    const char *s = buf;
    for (int k = 0; k < count; k++) {
        while (is_blank(*s))
            s++;
        char *stop;
        out[k] = strtod(s, &stop);
        if (stop == s || !isfinite(out[k]) || !(out[k] > 0.0))
            return false;
        s = stop;
    }
    while (is_blank(*s))
        s++;
    return *s == '\0';
}

/* Products of EXPOSURE, COLORCORR and PIXASPECT lines must stay in this
 * range, so that dividing by them keeps every decoded value finite. */
#define HDR_FACTOR_MIN 1e-30
#define HDR_FACTOR_MAX 1e30

static bool factor_ok(double f) { return f >= HDR_FACTOR_MIN && f <= HDR_FACTOR_MAX; }

/* Reads the header up to and including its empty line into `info`. */
static il_status read_header(const unsigned char **p, const unsigned char *end, const char *path,
                             il_hdr_info *info, il_error *err)
{
    char q[48];
    hdr_line line, v;
    if (!next_line(p, end, &line) || line.n < 2 || memcmp(line.s, "#?", 2) != 0)
        return il_fail(err, IL_ERR_FORMAT,
                       "%s: not a Radiance HDR file (no '#?RADIANCE' first line)", path);
    int format = -1; /* 0 RGBE, 1 XYZE, -1 not given */
    for (size_t lineno = 2;; lineno++) {
        if (!next_line(p, end, &line))
            return il_fail(err, IL_ERR_FORMAT,
                           "%s: HDR header is truncated (no empty line ends it)", path);
        if (line.n == 0)
            break;
        if (header_var(line, "FORMAT=", &v)) {
            int f = value_is(v, "32-bit_rle_rgbe") ? 0 : value_is(v, "32-bit_rle_xyze") ? 1 : -2;
            if (f == -2)
                return il_fail(err, IL_ERR_FORMAT,
                               "%s: unsupported HDR pixel format '%s' (line %zu; expected "
                               "32-bit_rle_rgbe or 32-bit_rle_xyze)",
                               path, quoted(v.s, v.n, q), lineno);
            if (format >= 0 && f != format)
                return il_fail(err, IL_ERR_FORMAT, "%s: HDR header has conflicting FORMAT lines",
                               path);
            format = f;
        } else if (header_var(line, "EXPOSURE=", &v)) {
            double e;
            if (!parse_positive(v, 1, &e))
                return il_fail(err, IL_ERR_FORMAT,
                               "%s: bad HDR EXPOSURE value '%s' (line %zu; need one positive "
                               "number)",
                               path, quoted(v.s, v.n, q), lineno);
            info->exposure *= e;
            if (!factor_ok(info->exposure))
                return il_fail(err, IL_ERR_FORMAT,
                               "%s: HDR EXPOSURE product %g is out of range (line %zu)", path,
                               info->exposure, lineno);
        } else if (header_var(line, "COLORCORR=", &v)) {
            double c[3];
            if (!parse_positive(v, 3, c))
                return il_fail(err, IL_ERR_FORMAT,
                               "%s: bad HDR COLORCORR value '%s' (line %zu; need three positive "
                               "numbers)",
                               path, quoted(v.s, v.n, q), lineno);
            for (int k = 0; k < 3; k++) {
                info->colorcorr[k] *= c[k];
                if (!factor_ok(info->colorcorr[k]))
                    return il_fail(err, IL_ERR_FORMAT,
                                   "%s: HDR COLORCORR product is out of range (line %zu)", path,
                                   lineno);
            }
        } else if (header_var(line, "PIXASPECT=", &v)) {
            double a;
            if (!parse_positive(v, 1, &a))
                return il_fail(err, IL_ERR_FORMAT,
                               "%s: bad HDR PIXASPECT value '%s' (line %zu; need one positive "
                               "number)",
                               path, quoted(v.s, v.n, q), lineno);
            info->pixaspect *= a;
            if (!factor_ok(info->pixaspect))
                return il_fail(err, IL_ERR_FORMAT,
                               "%s: HDR PIXASPECT product %g is out of range (line %zu)", path,
                               info->pixaspect, lineno);
        }
        /* Anything else (comments, the generating commands, SOFTWARE=,
         * VIEW=, PRIMARIES=, GAMMA=, ...) is ignored. */
    }
    info->xyze = format == 1;
    return IL_OK;
}

/* -------------------------------------------------------- resolution */

/* Which way the pixels run.  The resolution line names two axes, each with a
 * sign and a size, e.g. "-Y 512 +X 768".  The first axis varies slowest
 * (it counts the scanlines), the second fastest (pixels within a
 * scanline).  +X runs left to right, -X right to left; +Y runs bottom to top
 * (Radiance's y points up), -Y top to bottom.  The image is the X size wide
 * and the Y size high whatever the order.  For the file's i-th scanline and
 * its j-th pixel, our pixel (column x, row y from the top) is, with W, H the
 * X and Y sizes:
 *
 *   line             scanlines are      i-th scanline        pixels run     x, y
 *   -Y H +X W        rows, H of W px    row i from the top   left->right    j, i
 *   -Y H -X W        rows               row i from the top   right->left    W-1-j, i
 *   +Y H +X W        rows               row i from bottom    left->right    j, H-1-i
 *   +Y H -X W        rows               row i from bottom    right->left    W-1-j, H-1-i
 *   +X W +Y H        columns, W of H px column i from left   bottom->top    i, H-1-j
 *   +X W -Y H        columns            column i from left   top->bottom    i, j
 *   -X W +Y H        columns            column i from right  bottom->top    W-1-i, H-1-j
 *   -X W -Y H        columns            column i from right  top->bottom    W-1-i, j
 *
 * The first row is Radiance's standard: rows top to bottom, pixels left to
 * right, the layout of il_image. */
typedef struct hdr_orient {
    bool x_first;      /* scanlines are columns */
    bool x_decreasing; /* -X */
    bool y_increasing; /* +Y */
    uint64_t width, height;
} hdr_orient;

/* "[+-][XY] <blanks> <digits>": one axis of the resolution line. */
static bool parse_axis(const char **s, const char *end, char *sign, char *axis, uint64_t *size)
{
    const char *c = *s;
    if (end - c < 2 || (c[0] != '+' && c[0] != '-') || (c[1] != 'X' && c[1] != 'Y'))
        return false;
    *sign = c[0];
    *axis = c[1];
    c += 2;
    if (c == end || !is_blank(*c))
        return false;
    while (c < end && is_blank(*c))
        c++;
    uint64_t n = 0;
    int digits = 0;
    for (; c < end && *c >= '0' && *c <= '9'; c++, digits++)
        if (digits < 12) /* more digits than that is far beyond any size limit */
            n = n * 10 + (uint64_t)(*c - '0');
    if (digits == 0)
        return false;
    *size = digits > 12 ? UINT64_MAX : n;
    *s = c;
    return true;
}

static il_status read_resolution(const unsigned char **p, const unsigned char *end,
                                 const char *path, hdr_orient *o, char name[5], il_error *err)
{
    char q[48];
    hdr_line line;
    if (!next_line(p, end, &line))
        return il_fail(err, IL_ERR_FORMAT, "%s: HDR resolution line is missing or truncated",
                       path);
    const char *s = line.s, *e = line.s + line.n;
    char sign[2], axis[2];
    uint64_t size[2];
    bool ok = parse_axis(&s, e, &sign[0], &axis[0], &size[0]) && s < e && is_blank(*s);
    while (ok && s < e && is_blank(*s))
        s++;
    ok = ok && parse_axis(&s, e, &sign[1], &axis[1], &size[1]) && axis[0] != axis[1];
    while (ok && s < e && is_blank(*s))
        s++;
    if (!ok || s != e)
        return il_fail(err, IL_ERR_FORMAT,
                       "%s: bad HDR resolution line '%s' (expected e.g. '-Y 512 +X 768')", path,
                       quoted(line.s, line.n, q));
    o->x_first = axis[0] == 'X';
    int xi = o->x_first ? 0 : 1, yi = 1 - xi;
    o->x_decreasing = sign[xi] == '-';
    o->y_increasing = sign[yi] == '+';
    o->width = size[xi];
    o->height = size[yi];
    name[0] = sign[0], name[1] = axis[0], name[2] = sign[1], name[3] = axis[1], name[4] = '\0';
    return il_image_check_size(o->width, o->height, path, err);
}

/* ------------------------------------------------------------ pixels */

typedef struct pixel_stream {
    const unsigned char *p, *end;
    unsigned char last[4]; /* the last pixel decoded, for old-style runs */
    bool have_last;
    uint32_t flat, rle, runs; /* counts for il_hdr_info */
} pixel_stream;

/* New-style RLE scanline of n pixels (the 4 marker bytes already checked
 * and consumed): four components one after another. */
static const char *read_rle(pixel_stream *s, unsigned char *line, size_t n)
{
    for (int k = 0; k < 4; k++) {
        size_t x = 0;
        while (x < n) {
            if (s->p == s->end)
                return "pixel data is truncated";
            unsigned c = *s->p++;
            if (c > 128) { /* a run: c - 128 copies of the next byte */
                c -= 128;
                if (c > n - x)
                    return "a run overruns the scanline (corrupt)";
                if (s->p == s->end)
                    return "pixel data is truncated";
                unsigned char b = *s->p++;
                for (; c > 0; c--, x++)
                    line[x * 4 + k] = b;
            } else { /* c literal bytes (none when c = 0, as in Radiance) */
                if (c > n - x)
                    return "literal bytes overrun the scanline (corrupt)";
                if ((size_t)(s->end - s->p) < c)
                    return "pixel data is truncated";
                for (; c > 0; c--, x++)
                    line[x * 4 + k] = *s->p++;
            }
        }
    }
    s->rle++;
    return NULL;
}

/* Flat pixels with old-style runs (1, 1, 1, n): n << shift repeats of the
 * previous pixel, shift growing by 8 along a chain of markers. */
static const char *read_old(pixel_stream *s, unsigned char *line, size_t n)
{
    unsigned shift = 0;
    size_t x = 0;
    while (x < n) {
        if ((size_t)(s->end - s->p) < 4)
            return "pixel data is truncated";
        const unsigned char *px = s->p;
        s->p += 4;
        if (px[0] == 1 && px[1] == 1 && px[2] == 1) {
            if (!s->have_last)
                return "an old-style run repeats a pixel before the first one (corrupt)";
            /* n - x <= 65536 < 2^17: a shift of 24 or more with a non-zero
             * count always overruns, so the count is only formed below it. */
            if (px[3] != 0 && (shift >= 24 || ((size_t)px[3] << shift) > n - x))
                return "an old-style run overruns the scanline (corrupt)";
            size_t count = px[3] == 0 ? 0 : (size_t)px[3] << shift;
            for (; count > 0; count--, x++)
                memcpy(line + x * 4, s->last, 4);
            if (shift < 24)
                shift += 8;
            s->runs++;
        } else {
            memcpy(line + x * 4, px, 4);
            memcpy(s->last, px, 4);
            s->have_last = true;
            x++;
            shift = 0;
        }
    }
    s->flat++;
    return NULL;
}

/* Decodes the next scanline of n pixels into line (4 n bytes, RGBE or XYZE
 * with the exponent last); NULL, or what is wrong. */
static const char *read_scanline(pixel_stream *s, unsigned char *line, size_t n)
{
    const char *problem;
    if (n >= 8 && n <= 0x7fff && s->end - s->p >= 4 && s->p[0] == 2 && s->p[1] == 2 &&
        !(s->p[2] & 0x80)) {
        if (((size_t)s->p[2] << 8 | s->p[3]) != n)
            return "run-length encoded scanline has the wrong length (corrupt)";
        s->p += 4;
        problem = read_rle(s, line, n);
    } else {
        problem = read_old(s, line, n);
    }
    if (!problem) {
        memcpy(s->last, line + (n - 1) * 4, 4);
        s->have_last = true;
    }
    return problem;
}

/* --------------------------------------------------------- conversion */

/* From 4 file bytes to linear Rec.709: the value (m + 0.5) 2^(e - 136) of
 * each channel (il_rgbe_decode), divided by the EXPOSURE product and by the
 * channel's COLORCORR product ("Radiance file formats": both are multipliers
 * already applied to the pixels, cumulative over the header's lines); XYZE
 * then goes through the XYZ -> linear Rec.709 (D65) matrix of IEC
 * 61966-2-1:1999, equation (7), core/color.c's il_xyz_to_rec709.  Negative
 * results (XYZ colours outside the Rec.709 gamut) are clipped to 0 and values
 * beyond the float range to FLT_MAX.
 *
 * To keep il_xyz_to_rec709's float arguments in range, the per-channel
 * factor 1/(exposure cc_k) is split into ratio_k = (1/cc_k) / max_j (1/cc_j)
 * <= 1, applied to the 9-bit mantissas, and a common gain
 * max_j (1/cc_j) / exposure applied to the result in double. */
typedef struct hdr_convert {
    bool xyze;
    double ratio[3], gain;
} hdr_convert;

static hdr_convert make_convert(const il_hdr_info *info)
{
    hdr_convert c = {.xyze = info->xyze};
    double inv[3], top = 0.0;
    for (int k = 0; k < 3; k++) {
        inv[k] = 1.0 / info->colorcorr[k];
        top = fmax(top, inv[k]);
    }
    for (int k = 0; k < 3; k++)
        c.ratio[k] = inv[k] / top;
    c.gain = top / info->exposure;
    return c;
}

static float clamp_value(double v)
{
    if (!(v > 0.0))
        return 0.0f;
    return v < FLT_MAX ? (float)v : FLT_MAX;
}

static void convert_pixel(const hdr_convert *c, const unsigned char *px, float *rgb)
{
    if (px[3] == 0) { /* zero exponent: black */
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    double q[3];
    for (int k = 0; k < 3; k++)
        q[k] = (px[k] + 0.5) * c->ratio[k];
    if (c->xyze) {
        il_vec3 r = il_xyz_to_rec709((il_vec3){(float)q[0], (float)q[1], (float)q[2]});
        q[0] = r.x, q[1] = r.y, q[2] = r.z;
    }
    double scale = ldexp(c->gain, (int)px[3] - 136);
    for (int k = 0; k < 3; k++)
        rgb[k] = clamp_value(q[k] * scale);
}

/* -------------------------------------------------------------- read */

il_status il_hdr_read_info(const unsigned char *data, size_t size, const char *path,
                           il_image *out, il_hdr_info *info_out, il_error *err)
{
    out->width = out->height = 0;
    out->rgb = NULL;
    if (!data || size == 0)
        return il_fail(err, IL_ERR_FORMAT, "%s: HDR file is empty", path);
    const unsigned char *p = data, *end = data + size;
    il_hdr_info info = {.exposure = 1.0, .colorcorr = {1.0, 1.0, 1.0}, .pixaspect = 1.0};
    il_status st = read_header(&p, end, path, &info, err);
    hdr_orient o = {0};
    if (st == IL_OK)
        st = read_resolution(&p, end, path, &o, info.orientation, err);
    if (st != IL_OK)
        return st;

    size_t nfast = (size_t)(o.x_first ? o.height : o.width);
    size_t nslow = (size_t)(o.x_first ? o.width : o.height);
    unsigned char *line = il_malloc(nfast * 4, err);
    if (!line)
        return IL_ERR_MEMORY;

    /* Pass 1: decode every scanline, keeping nothing, to find a corrupt or
     * truncated stream before allocating the image. */
    pixel_stream s = {.p = p, .end = end};
    for (size_t i = 0; i < nslow; i++) {
        const char *problem = read_scanline(&s, line, nfast);
        if (problem) {
            free(line);
            return il_fail(err, IL_ERR_FORMAT, "%s: HDR scanline %zu of %zu: %s", path, i + 1,
                           nslow, problem);
        }
    }
    info.flat_scanlines = s.flat;
    info.rle_scanlines = s.rle;
    info.old_runs = s.runs;

    /* Pass 2: decode again into the image, in its orientation. */
    st = il_image_alloc(out, (uint32_t)o.width, (uint32_t)o.height, err);
    if (st != IL_OK) {
        free(line);
        return st;
    }
    hdr_convert conv = make_convert(&info);
    size_t w = out->width, h = out->height;
    s = (pixel_stream){.p = p, .end = end};
    for (size_t i = 0; i < nslow; i++) {
        (void)read_scanline(&s, line, nfast); /* succeeded in pass 1 */
        for (size_t j = 0; j < nfast; j++) {
            size_t x, y;
            if (o.x_first) {
                x = o.x_decreasing ? w - 1 - i : i;
                y = o.y_increasing ? h - 1 - j : j;
            } else {
                x = o.x_decreasing ? w - 1 - j : j;
                y = o.y_increasing ? h - 1 - i : i;
            }
            convert_pixel(&conv, line + j * 4, out->rgb + (y * w + x) * 3);
        }
    }
    free(line);
    if (info_out)
        *info_out = info;
    return IL_OK;
}

il_status il_hdr_read(const unsigned char *data, size_t size, const char *path, il_image *out,
                      il_error *err)
{
    return il_hdr_read_info(data, size, path, out, NULL, err);
}
