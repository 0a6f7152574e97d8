/* libFuzzer target for the Radiance .hdr reader (fuzz/README.md).
 *
 * Every input goes through il_hdr_read_info.  Beyond "no crash, no
 * out-of-bounds access, no undefined behaviour" (ASan + UBSan), it checks the
 * reader's contract and aborts when it is broken:
 * - failure: IL_ERR_FORMAT (or IL_ERR_MEMORY), a message naming the file,
 *   and an empty image;
 * - success: a size within IL_IMAGE_MAX_SIDE, every value finite and >= 0;
 *   and for images of up to 2^16 pixels, writing the image with il_hdr_write
 *   and reading it back gives every channel within 2^-8 of its pixel's
 *   largest channel (the RGBE round-trip bound, il_rgbe_encode) -- values
 *   below 1e-32 of the format's range aside, which the writer makes black.
 *
 * The same file is built without libFuzzer, with gcc, as the ctest
 * unit/test_hdr_corpus (fuzz/replay.c), which replays fuzz/corpus/hdr. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_io.h"

#define FUZZ_PATH "fuzz-input.hdr"

static void fail(const char *what, const char *message)
{
    fprintf(stderr, "fuzz_hdr: %s (%s)\n", what, message ? message : "");
    abort();
}

/* Writes `im` as .hdr into memory and reads it back: round-trip check. */
static void round_trip(const il_image *im)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return;
    il_error err = {0};
    il_status st = il_hdr_write(im, f, "round-trip.hdr", &err);
    if (fclose(f) != 0 || st != IL_OK) {
        free(buf);
        if (st != IL_OK && st != IL_ERR_MEMORY)
            fail("il_hdr_write failed", err.message);
        return;
    }
    il_image back = {0};
    st = il_hdr_read((const unsigned char *)buf, len, "round-trip.hdr", &back, &err);
    free(buf);
    if (st != IL_OK)
        fail("cannot read back what il_hdr_write wrote", err.message);
    if (back.width != im->width || back.height != im->height)
        fail("round trip changed the size", NULL);
    size_t n = (size_t)im->width * im->height;
    for (size_t i = 0; i < n; i++) {
        const float *a = im->rgb + 3 * i, *b = back.rgb + 3 * i;
        double m = fmax(a[0], fmax(a[1], a[2]));
        double bound = m > 1e-32 ? ldexp(m, -8) * (1 + 1e-6) : 1e-32;
        if (m >= ldexp(1.0, 127)) /* beyond RGBE's largest value: clamped */
            continue;
        for (int k = 0; k < 3; k++)
            if (!(fabs((double)b[k] - a[k]) <= bound))
                fail("round trip is not within RGBE precision", NULL);
    }
    il_image_free(&back);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    il_image im = {0};
    il_hdr_info info;
    il_error err = {0};
    il_status st = il_hdr_read_info(data, size, FUZZ_PATH, &im, &info, &err);
    if (st != IL_OK) {
        if (st != IL_ERR_FORMAT && st != IL_ERR_MEMORY)
            fail("unexpected status", err.message);
        if (st == IL_ERR_FORMAT && !strstr(err.message, FUZZ_PATH))
            fail("error message does not name the file", err.message);
        if (im.rgb || im.width || im.height)
            fail("failed read left an image behind", err.message);
        return 0;
    }
    if (!im.rgb || im.width == 0 || im.height == 0 || im.width > IL_IMAGE_MAX_SIDE ||
        im.height > IL_IMAGE_MAX_SIDE)
        fail("bad image size", NULL);
    size_t n = (size_t)im.width * im.height * 3;
    for (size_t i = 0; i < n; i++)
        if (!(im.rgb[i] >= 0.0f) || !isfinite(im.rgb[i]))
            fail("negative, NaN or infinite value", NULL);
    if (!(info.exposure > 0) || !(info.pixaspect > 0) || info.orientation[4] != '\0' ||
        info.flat_scanlines + info.rle_scanlines != (info.orientation[1] == 'X' ? im.width
                                                                                : im.height))
        fail("inconsistent il_hdr_info", NULL);
    if ((size_t)im.width * im.height <= 65536)
        round_trip(&im);
    il_image_free(&im);
    return 0;
}
