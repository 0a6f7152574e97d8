/* Radiance HDR (RGBE) pixels and writing: Greg Ward, "Real Pixels", Graphics
 * Gems II (1991), section II.5, and the "Radiance file formats" notes
 * (Radiance reference manual, "Picture file format").  Reading is in
 * rgbe_read.c.
 *
 * The writer writes a standard header (FORMAT=32-bit_rle_rgbe, "-Y H +X W"),
 * then new-style run-length encoded scanlines for widths 8..32767 and flat
 * (uncompressed) ones for other widths, which new-style RLE cannot express. */
#include "image/image_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

/* ------------------------------------------------------------ pixels */

/* Exponent byte b stands for 2^(b - 128): value = (m + 0.5) 2^(b - 136). */
#define RGBE_EXCESS 128
#define RGBE_MAX_EXP 127 /* byte 255 */

static double rgbe_sanitize(float v)
{
    if (!(v > 0.0f)) /* NaN and negatives: RGBE cannot represent them */
        return 0.0;
    return v;
}

/* Ward's setcolr (Graphics Gems II, II.5): with v the largest channel and
 * v = f 2^e, f in [0.5, 1), each mantissa is m = floor(c 2^(8-e)) < 256 and
 * the exponent byte e + 128.  Decoding by (m + 0.5) 2^(e-8) puts every
 * channel within half a mantissa step, 2^(e-9) <= 2^-8 v, of its value: the
 * same bound as rounding to nearest with an m 2^(e-8) decoder, but matching
 * the standard decoder (Radiance's colr_color).  As in Radiance, a pixel whose
 * largest channel is at most 1e-32 is black; values too large for the format
 * (+Inf included) are clamped to its largest exponent. */
void il_rgbe_encode(const float rgb[3], unsigned char rgbe[4])
{
    double c[3] = {rgbe_sanitize(rgb[0]), rgbe_sanitize(rgb[1]), rgbe_sanitize(rgb[2])};
    double v = fmax(c[0], fmax(c[1], c[2]));
    if (!(v > 1e-32)) {
        memset(rgbe, 0, 4);
        return;
    }
    int e = RGBE_MAX_EXP + 1;
    if (isfinite(v))
        (void)frexp(v, &e); /* v = f 2^e, f in [0.5, 1) */
    if (e > RGBE_MAX_EXP)
        e = RGBE_MAX_EXP; /* the largest channel saturates at m = 255 below */
    double scale = ldexp(1.0, 8 - e); /* exact: a power of two */
    for (int k = 0; k < 3; k++) {
        double m = floor(c[k] * scale); /* exact in double; Inf stays Inf */
        rgbe[k] = (unsigned char)(m > 255.0 ? 255.0 : m);
    }
    rgbe[3] = (unsigned char)(e + RGBE_EXCESS);
}

/* Radiance's colr_color: (m + 0.5) 2^(e - 136); a zero exponent byte is
 * black.  Exact in float: a 9-bit significand times a power of two no smaller
 * than 2^-136 (a float subnormal, representable down to 2^-149). */
void il_rgbe_decode(const unsigned char rgbe[4], float rgb[3])
{
    if (rgbe[3] == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    for (int k = 0; k < 3; k++)
        rgb[k] = ldexpf((float)rgbe[k] + 0.5f, (int)rgbe[3] - (RGBE_EXCESS + 8));
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
