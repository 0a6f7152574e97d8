/* OpenEXR through the OpenEXR Core C API (<OpenEXR/openexr.h>, OpenEXR 3.1).
 *
 * Writing: one scanline part, channels R, G, B as half (default; clamped to
 * +-65504, the largest half, so nothing turns into infinity) or float,
 * ZIP compression (16 scanlines per chunk; a chunk that does not shrink is
 * stored raw, see compress_raw_when_no_smaller), through a custom write callback
 * into the temporary file of image.c.
 *
 * Reading: the first part, scanline or tiled (level 0 of a mip/rip map), from
 * memory through custom read/size callbacks (so the library validates every
 * offset against the true file size).  R, G and B are read as float whatever
 * their stored type; a file with only Y is grey.  The library's error
 * messages are captured instead of printed. */
#include "image/image_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <OpenEXR/openexr.h>

#include "core/error.h"

/* What the custom stream callbacks and the error handler share. */
typedef struct exr_stream {
    const unsigned char *data; /* reading */
    size_t size;
    int fd; /* writing */
    char message[256];         /* the library's first error message */
} exr_stream;

static void on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    if (!ctxt || exr_get_user_data(ctxt, &user) != EXR_ERR_SUCCESS || !user)
        return;
    exr_stream *s = user;
    if (!s->message[0])
        snprintf(s->message, sizeof s->message, "%s", msg ? msg : exr_get_default_error_message(code));
}

static int64_t mem_read(exr_const_context_t ctxt, void *user, void *buffer, uint64_t sz,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    exr_stream *s = user;
    if (offset >= s->size)
        return 0;
    uint64_t n = s->size - offset;
    if (n > sz)
        n = sz;
    memcpy(buffer, s->data + offset, (size_t)n);
    return (int64_t)n;
}

static int64_t mem_size(exr_const_context_t ctxt, void *user)
{
    (void)ctxt;
    return (int64_t)((exr_stream *)user)->size;
}

static int64_t fd_write(exr_const_context_t ctxt, void *user, const void *buffer, uint64_t sz,
                        uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    exr_stream *s = user;
    const unsigned char *p = buffer;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pwrite(s->fd, p + done, (size_t)(sz - done), (off_t)(offset + done));
        if (n <= 0)
            return -1;
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

/* The library's message when it gave one, else its text for the code. */
static const char *exr_message(const exr_stream *s, exr_result_t rv)
{
    return s->message[0] ? s->message : exr_get_default_error_message(rv);
}

/* ----------------------------------------------------------------- read */

/* Decodes one chunk into the image: channel c of `out` (0..2) receives file
 * channel chan[c] (NULL: not read). */
static exr_result_t decode_chunk(exr_context_t ctxt, const exr_chunk_info_t *cinfo,
                                 exr_decode_pipeline_t *dec, bool *initialized, il_image *out,
                                 int32_t x0, int32_t y0, const char *chan[3])
{
    exr_result_t rv = *initialized ? exr_decoding_update(ctxt, 0, cinfo, dec)
                                   : exr_decoding_initialize(ctxt, 0, cinfo, dec);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    *initialized = true;
    /* Pixel (x0, y0) of the chunk in image coordinates. */
    float *base = out->rgb + ((size_t)y0 * out->width + (size_t)x0) * 3;
    for (int i = 0; i < dec->channel_count; i++) {
        exr_coding_channel_info_t *ch = &dec->channels[i];
        ch->decode_to_ptr = NULL;
        for (int c = 0; c < 3; c++) {
            if (chan[c] && strcmp(ch->channel_name, chan[c]) == 0) {
                ch->decode_to_ptr = (uint8_t *)(base + c);
                ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
                ch->user_line_stride = (int32_t)(out->width * 3 * sizeof(float));
                ch->user_data_type = EXR_PIXEL_FLOAT;
                ch->user_bytes_per_element = (int16_t)sizeof(float);
            }
        }
    }
    rv = exr_decoding_choose_default_routines(ctxt, 0, dec);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    return exr_decoding_run(ctxt, 0, dec);
}

static exr_result_t read_pixels(exr_context_t ctxt, exr_storage_t storage,
                                const exr_attr_box2i_t *dw, il_image *out, const char *chan[3])
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool initialized = false;
    exr_result_t rv = EXR_ERR_SUCCESS;
    exr_chunk_info_t cinfo;
    if (storage == EXR_STORAGE_SCANLINE) {
        int32_t lines = 0;
        rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
        if (rv == EXR_ERR_SUCCESS && lines < 1)
            rv = EXR_ERR_INVALID_ATTR;
        for (int64_t y = dw->min.y; rv == EXR_ERR_SUCCESS && y <= dw->max.y; y += lines) {
            rv = exr_read_scanline_chunk_info(ctxt, 0, (int)y, &cinfo);
            if (rv != EXR_ERR_SUCCESS)
                break;
            if (cinfo.start_y < dw->min.y || cinfo.start_x != dw->min.x ||
                cinfo.start_y + cinfo.height - 1 > dw->max.y || cinfo.width != (int32_t)out->width) {
                rv = EXR_ERR_CORRUPT_CHUNK;
                break;
            }
            rv = decode_chunk(ctxt, &cinfo, &dec, &initialized, out, 0, cinfo.start_y - dw->min.y,
                              chan);
        }
    } else {
        uint32_t tw = 0, th = 0;
        exr_tile_level_mode_t level_mode;
        exr_tile_round_mode_t round_mode;
        rv = exr_get_tile_descriptor(ctxt, 0, &tw, &th, &level_mode, &round_mode);
        if (rv == EXR_ERR_SUCCESS && (tw == 0 || th == 0))
            rv = EXR_ERR_INVALID_ATTR;
        uint32_t nx = rv == EXR_ERR_SUCCESS ? (out->width + tw - 1) / tw : 0;
        uint32_t ny = rv == EXR_ERR_SUCCESS ? (out->height + th - 1) / th : 0;
        for (uint32_t ty = 0; rv == EXR_ERR_SUCCESS && ty < ny; ty++) {
            for (uint32_t tx = 0; rv == EXR_ERR_SUCCESS && tx < nx; tx++) {
                rv = exr_read_tile_chunk_info(ctxt, 0, (int)tx, (int)ty, 0, 0, &cinfo);
                if (rv != EXR_ERR_SUCCESS)
                    break;
                uint64_t x0 = (uint64_t)tx * tw, y0 = (uint64_t)ty * th;
                if (cinfo.width < 1 || cinfo.height < 1 ||
                    x0 + (uint64_t)cinfo.width > out->width ||
                    y0 + (uint64_t)cinfo.height > out->height) {
                    rv = EXR_ERR_CORRUPT_CHUNK;
                    break;
                }
                rv = decode_chunk(ctxt, &cinfo, &dec, &initialized, out, (int32_t)x0, (int32_t)y0,
                                  chan);
            }
        }
    }
    if (initialized)
        exr_decoding_destroy(ctxt, &dec);
    return rv;
}

il_status il_exr_read(const unsigned char *data, size_t size, const char *path, il_image *out,
                      il_error *err)
{
    exr_stream s = {.data = data, .size = size, .fd = -1};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = &s;
    init.read_fn = mem_read;
    init.size_fn = mem_size;
    init.max_image_width = (int)IL_IMAGE_MAX_SIDE;
    init.max_image_height = (int)IL_IMAGE_MAX_SIDE;
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE;

    exr_context_t ctxt = NULL;
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        il_status st = il_fail(err, rv == EXR_ERR_OUT_OF_MEMORY ? IL_ERR_MEMORY : IL_ERR_FORMAT,
                               "%s: invalid OpenEXR file: %s", path, exr_message(&s, rv));
        exr_finish(&ctxt);
        return st;
    }

    il_status st = IL_OK;
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *chlist = NULL;
    if (exr_get_storage(ctxt, 0, &storage) != EXR_ERR_SUCCESS ||
        exr_get_data_window(ctxt, 0, &dw) != EXR_ERR_SUCCESS ||
        exr_get_channels(ctxt, 0, &chlist) != EXR_ERR_SUCCESS || !chlist) {
        st = il_fail(err, IL_ERR_FORMAT, "%s: OpenEXR header is incomplete: %s", path,
                     exr_message(&s, EXR_ERR_MISSING_REQ_ATTR));
        goto done;
    }
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
        st = il_fail(err, IL_ERR_FORMAT, "%s: deep OpenEXR images are not supported", path);
        goto done;
    }
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    st = il_image_check_size(w > 0 ? (uint64_t)w : 0, h > 0 ? (uint64_t)h : 0, path, err);
    if (st != IL_OK)
        goto done;

    /* Which channels to read. */
    bool has[4] = {false, false, false, false}; /* R G B Y */
    static const char *const names[4] = {"R", "G", "B", "Y"};
    for (int i = 0; i < chlist->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &chlist->entries[i];
        for (int k = 0; k < 4; k++) {
            if (e->name.str && strcmp(e->name.str, names[k]) == 0) {
                if (e->x_sampling != 1 || e->y_sampling != 1) {
                    st = il_fail(err, IL_ERR_FORMAT,
                                 "%s: subsampled OpenEXR channel %s is not supported", path,
                                 names[k]);
                    goto done;
                }
                has[k] = true;
            }
        }
    }
    const char *chan[3];
    bool grey = false;
    if (has[0] && has[1] && has[2]) {
        chan[0] = "R", chan[1] = "G", chan[2] = "B";
    } else if (has[3]) {
        chan[0] = "Y", chan[1] = chan[2] = NULL;
        grey = true;
    } else {
        st = il_fail(err, IL_ERR_FORMAT, "%s: OpenEXR file has no R, G, B channels (nor Y)", path);
        goto done;
    }

    st = il_image_alloc(out, (uint32_t)w, (uint32_t)h, err);
    if (st != IL_OK)
        goto done;
    rv = read_pixels(ctxt, storage, &dw, out, chan);
    if (rv != EXR_ERR_SUCCESS) {
        st = il_fail(err, rv == EXR_ERR_OUT_OF_MEMORY ? IL_ERR_MEMORY : IL_ERR_FORMAT,
                     "%s: corrupt or truncated OpenEXR pixel data: %s", path, exr_message(&s, rv));
        goto done;
    }
    if (grey) {
        size_t n = (size_t)out->width * out->height;
        for (size_t i = 0; i < n; i++)
            out->rgb[i * 3 + 1] = out->rgb[i * 3 + 2] = out->rgb[i * 3];
    }
done:
    exr_finish(&ctxt);
    return st;
}

/* ---------------------------------------------------------------- write */

/* The library's ZIP compressor, then the file format's rule: a chunk whose
 * compressed size is not below its raw size is stored raw, and a reader
 * takes a chunk whose stored size equals its raw size as raw.  The OpenEXR
 * Core library kept the compressed bytes when the two sizes were equal
 * until March 2026 (openexr issue #2306, pull request #2307; Debian 12 has
 * 3.1.5), so every reader decoded zlib bytes as pixels: a 32x32 float image
 * of ibl's lit bunny came back with its first 16 rows as garbage.  Storing
 * that chunk raw is what the fixed library does.  encoding_user_data holds
 * the library's compressor. */
typedef exr_result_t (*exr_compress_fn)(exr_encode_pipeline_t *);
typedef struct exr_compressor {
    exr_compress_fn library;
} exr_compressor;

static exr_result_t compress_raw_when_no_smaller(exr_encode_pipeline_t *enc)
{
    const exr_compressor *c = enc->encoding_user_data;
    exr_result_t rv = c->library(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes == enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer)
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    return rv;
}

/* A half can hold magnitudes up to 65504; the library turns anything
 * beyond into infinity (the sun's disc holds up to about 2e6).  A copy of
 * the image clamped to that range when it needs one, else NULL. */
static float *clamped_to_half(const il_image *image, il_error *err, bool *failed)
{
    size_t n = (size_t)image->width * image->height * 3, i = 0;
    *failed = false;
    while (i < n && fabsf(image->rgb[i]) <= IL_EXR_HALF_MAX)
        i++;
    if (i == n)
        return NULL;
    float *copy = il_malloc(n * sizeof(float), err);
    if (!copy) {
        *failed = true;
        return NULL;
    }
    for (i = 0; i < n; i++)
        copy[i] = fmaxf(-IL_EXR_HALF_MAX, fminf(image->rgb[i], IL_EXR_HALF_MAX));
    return copy;
}

il_status il_exr_write(const il_image *image, FILE *f, const char *path,
                       il_exr_precision precision, il_error *err)
{
    float *clamped = NULL;
    if (precision != IL_EXR_FLOAT) {
        bool failed;
        clamped = clamped_to_half(image, err, &failed);
        if (failed)
            return IL_ERR_MEMORY;
    }
    const float *pixels = clamped ? clamped : image->rgb;

    exr_stream s = {.fd = fileno(f)};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = &s;
    init.write_fn = fd_write;

    exr_pixel_type_t ptype = precision == IL_EXR_FLOAT ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF;
    exr_context_t ctxt = NULL;
    int part = 0;
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctxt, "rgb", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, (int32_t)image->width,
                                                 (int32_t)image->height, EXR_COMPRESSION_ZIP);
    /* Channels are kept sorted by name in the file: B, G, R. */
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_channel(ctxt, part, "R", ptype, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_channel(ctxt, part, "G", ptype, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_channel(ctxt, part, "B", ptype, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_set_version(ctxt, part, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);

    int32_t lines = 0;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    if (rv == EXR_ERR_SUCCESS && lines < 1)
        rv = EXR_ERR_INVALID_ATTR;

    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_compressor compressor;
    bool initialized = false;
    for (int32_t y = 0; rv == EXR_ERR_SUCCESS && y < (int32_t)image->height; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = initialized ? exr_encoding_update(ctxt, part, &cinfo, &enc)
                         : exr_encoding_initialize(ctxt, part, &cinfo, &enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        initialized = true;
        const float *row = pixels + (size_t)cinfo.start_y * image->width * 3;
        for (int i = 0; i < enc.channel_count; i++) {
            exr_coding_channel_info_t *ch = &enc.channels[i];
            int c = ch->channel_name[0] == 'R' ? 0 : ch->channel_name[0] == 'G' ? 1 : 2;
            ch->encode_from_ptr = (const uint8_t *)(row + c);
            ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(image->width * 3 * sizeof(float));
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = (int16_t)sizeof(float);
        }
        rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
        if (rv == EXR_ERR_SUCCESS && enc.compress_fn) {
            compressor.library = enc.compress_fn;
            enc.encoding_user_data = &compressor;
            enc.compress_fn = compress_raw_when_no_smaller;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, part, &enc);
    }
    if (initialized)
        exr_encoding_destroy(ctxt, &enc);
    exr_result_t frv = exr_finish(&ctxt);
    free(clamped);
    if (rv == EXR_ERR_SUCCESS)
        rv = frv;
    if (rv != EXR_ERR_SUCCESS)
        return il_fail(err, rv == EXR_ERR_WRITE_IO ? IL_ERR_IO : IL_ERR_RUNTIME,
                       "%s: cannot write OpenEXR: %s", path, exr_message(&s, rv));
    return IL_OK;
}
