/* Internal interface of the image module: one reader and one writer per file
 * format, each in its own file, behind the dispatch in image.c.
 *
 * Readers decode a whole file already loaded into memory (`data`, `size`);
 * `path` is only used in error messages.  They fill `out` (allocated with
 * il_image_alloc) and report a corrupt or truncated file as IL_ERR_FORMAT
 * naming the file; they never read outside [data, data + size).
 *
 * Writers write an already validated, non-empty image to an open stream (the
 * temporary file of image.c's atomic write); they report IL_ERR_IO when a
 * write fails.  Rename and clean-up are image.c's job. */
#ifndef IL_IMAGE_IMAGE_IO_H
#define IL_IMAGE_IMAGE_IO_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "illum/illum.h"

/* Largest width or height any reader accepts; a header claiming more is
 * treated as corrupt. */
#define IL_IMAGE_MAX_SIDE 65536u
/* ... and at most this many pixels (16384 x 16384, 3 GB of float RGB): a
 * corrupt header of 65536 x 65536 would ask for 48 GB. */
#define IL_IMAGE_MAX_PIXELS (16384ull * 16384ull)

/* Checks dimensions read from a file: both in 1..IL_IMAGE_MAX_SIDE.  Reports
 * IL_ERR_FORMAT naming `path` otherwise. */
il_status il_image_check_size(uint64_t width, uint64_t height, const char *path,
                              il_error *err);

/* exr.c: OpenEXR through the OpenEXR Core C API. */
il_status il_exr_read(const unsigned char *data, size_t size, const char *path,
                      il_image *out, il_error *err);
il_status il_exr_write(const il_image *image, FILE *f, const char *path,
                       il_exr_precision precision, il_error *err);

/* rgbe_read.c, rgbe.c: Radiance HDR (RGBE and XYZE), our own reader and
 * writer (docs/images.md, "Radiance .hdr").  The reader takes every
 * orientation, flat, old-style RLE and new-style RLE scanlines, and applies
 * EXPOSURE and COLORCORR; the writer writes "-Y H +X W" RGBE, new-style RLE
 * for widths 8..32767 and flat otherwise. */
il_status il_hdr_read(const unsigned char *data, size_t size, const char *path,
                      il_image *out, il_error *err);
il_status il_hdr_write(const il_image *image, FILE *f, const char *path, il_error *err);

/* What a .hdr file said besides its pixels, as il_hdr_read_info reports it
 * (for tests, tools and the fuzz target). */
typedef struct il_hdr_info {
    bool xyze;               /* FORMAT=32-bit_rle_xyze (converted to Rec.709) */
    double exposure;         /* product of the EXPOSURE lines (1 if none) */
    double colorcorr[3];     /* per-channel products of the COLORCORR lines */
    double pixaspect;        /* product of the PIXASPECT lines (1 if none);
                              * recorded only, pixels are not resampled */
    char orientation[5];     /* the resolution line's axes, e.g. "-Y+X" */
    uint32_t flat_scanlines; /* scanlines stored flat or old-style RLE */
    uint32_t rle_scanlines;  /* scanlines stored new-style (per-channel) RLE */
    uint32_t old_runs;       /* old-style repeat markers (1,1,1,n) met */
} il_hdr_info;

/* il_hdr_read that also fills `info` (when not NULL) on success.  On failure
 * `out` is left empty (width = height = 0, rgb = NULL). */
il_status il_hdr_read_info(const unsigned char *data, size_t size, const char *path,
                           il_image *out, il_hdr_info *info, il_error *err);

/* Ward's shared-exponent encoding of one pixel (Graphics Gems II, II.5):
 * mantissas truncated, decoded as (m + 0.5) 2^(e - 136), so every channel
 * comes back within 2^-8 of the pixel's largest channel.  Exposed for tests
 * and for the environment-map code. */
void il_rgbe_encode(const float rgb[3], unsigned char rgbe[4]);
void il_rgbe_decode(const unsigned char rgbe[4], float rgb[3]);

/* pfm.c: Portable Float Map. */
il_status il_pfm_read(const unsigned char *data, size_t size, const char *path,
                      il_image *out, il_error *err);
il_status il_pfm_write(const il_image *image, FILE *f, const char *path, il_error *err);

/* png.c: PNG and JPEG through stb_image / stb_image_write. */
il_status il_png_read(const unsigned char *data, size_t size, const char *path,
                      il_image *out, il_error *err);
il_status il_jpeg_read(const unsigned char *data, size_t size, const char *path,
                       il_image *out, il_error *err);
il_status il_png_write(const il_image *image, FILE *f, const char *path, float exposure,
                       il_error *err);

#endif
