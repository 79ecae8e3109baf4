/* image: framebuffer, EXR writer/reader on libOpenEXRCore, PNG on libpng. */
#include "image.h"

#include <math.h>
#include <openexr.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "outfile.h"

pm_status image_init(image *im, uint32_t width, uint32_t height)
{
    im->width = width;
    im->height = height;
    /* mem: a repeat's image reuses the last one's pages (mem_keep) */
    im->rgb = mem_zalloc(((size_t)width * height * 3 + 1) * sizeof(float));
    return im->rgb ? PM_OK : PM_ERR_NOMEM;
}

void image_free(image *im)
{
    mem_free(im->rgb);
    im->rgb = NULL;
    im->width = im->height = 0;
}

void image_mean(const image *im, double mean[3])
{
    double sum[3] = {0, 0, 0};
    size_t n = (size_t)im->width * im->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            sum[c] += im->rgb[3 * i + (size_t)c];
    for (int c = 0; c < 3; c++)
        mean[c] = n ? sum[c] / (double)n : 0.0;
}

uint64_t image_count_nonfinite(const image *im)
{
    uint64_t bad = 0;
    size_t n = (size_t)im->width * im->height;
    for (size_t i = 0; i < n; i++) {
        const float *p = im->rgb + 3 * i;
        bad += !(isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]));
    }
    return bad;
}

/* ---- OpenEXR ---- */

static void exr_quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* Writes "PATH: WHAT: the library's message for rc" into err; returns
 * PM_ERR_IO. */
static pm_status exr_fail(exr_result_t rc, const char *path, const char *what, char *err, size_t errlen)
{
    snprintf(err, errlen, "%s: %s: %s", path, what, exr_get_default_error_message(rc));
    return PM_ERR_IO;
}

/* OpenEXRCore 3.1 stores a ZIP chunk compressed even when the compressed size
 * equals the raw size exactly, but every reader takes a chunk whose stored
 * size equals its raw size as uncompressed: that chunk reads back as garbage
 * (NaN, 1e38; a 64x48 Cornell render has such chunks in rows 16-31). This
 * wraps the library's compressor and stores such a chunk raw. */
typedef struct {
    exr_result_t (*compress)(exr_encode_pipeline_t *);
} exr_compress_guard;

static exr_result_t exr_compress_unambiguous(exr_encode_pipeline_t *enc)
{
    const exr_compress_guard *g = enc->encoding_user_data;
    exr_result_t rc = g->compress(enc);
    if (rc == EXR_ERR_SUCCESS && enc->compressed_bytes == enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer && enc->compressed_alloc_size >= enc->packed_bytes)
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    return rc;
}

/* Writes the EXR to `file` (the temporary name). */
/* Writes im as OpenEXR to file (path names it in messages). Returns PM_OK,
 * PM_ERR_NOMEM, or PM_ERR_IO with the reason in err. */
static pm_status exr_write_to(const image *im, const char *file, const char *path, char *err, size_t errlen)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_quiet;
    exr_context_t ctx = NULL;
    exr_result_t rc = exr_start_write(&ctx, file, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc != EXR_ERR_SUCCESS)
        return exr_fail(rc, path, "cannot create", err, errlen);
    int part = 0;
    pm_status ok = PM_ERR_IO;
    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    int enc_init = 0;
    float *planes = NULL;
    exr_compress_guard guard = {NULL};
    if ((rc = exr_add_part(ctx, "rgb", EXR_STORAGE_SCANLINE, &part)) ||
        (rc = exr_initialize_required_attr_simple(ctx, part, (int32_t)im->width, (int32_t)im->height,
                                                  EXR_COMPRESSION_ZIP)) ||
        (rc = exr_add_channel(ctx, part, "R", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1)) ||
        (rc = exr_add_channel(ctx, part, "G", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1)) ||
        (rc = exr_add_channel(ctx, part, "B", EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1)) ||
        (rc = exr_set_version(ctx, part, 1)) || (rc = exr_write_header(ctx))) {
        exr_fail(rc, path, "cannot write header", err, errlen);
        goto done;
    }
    int32_t lines = 1;
    if ((rc = exr_get_scanlines_per_chunk(ctx, part, &lines))) {
        exr_fail(rc, path, "bad header", err, errlen);
        goto done;
    }
    /* one chunk's worth of planar R, G, B lines */
    size_t w = im->width;
    planes = malloc(sizeof(float) * w * 3 * (size_t)lines);
    if (!planes) {
        snprintf(err, errlen, "%s: out of memory", path);
        ok = PM_ERR_NOMEM;
        goto done;
    }
    for (int32_t y = 0; y < (int32_t)im->height; y += lines) {
        exr_chunk_info_t ci;
        if ((rc = exr_write_scanline_chunk_info(ctx, part, y, &ci))) {
            exr_fail(rc, path, "cannot start chunk", err, errlen);
            goto done;
        }
        for (int32_t l = 0; l < ci.height; l++) {
            const float *src = im->rgb + ((size_t)(y + l) * w) * 3;
            for (int c = 0; c < 3; c++) {
                float *dst = planes + ((size_t)c * (size_t)lines + (size_t)l) * w;
                for (size_t x = 0; x < w; x++)
                    dst[x] = src[3 * x + (size_t)c];
            }
        }
        rc = enc_init ? exr_encoding_update(ctx, part, &ci, &enc) : exr_encoding_initialize(ctx, part, &ci, &enc);
        if (rc) {
            exr_fail(rc, path, "cannot encode", err, errlen);
            goto done;
        }
        for (int c = 0; c < enc.channel_count; c++) {
            const char *nm = enc.channels[c].channel_name;
            int plane = nm[0] == 'R' ? 0 : nm[0] == 'G' ? 1 : 2;
            enc.channels[c].user_pixel_stride = sizeof(float);
            enc.channels[c].user_line_stride = (int32_t)(sizeof(float) * w);
            enc.channels[c].user_bytes_per_element = sizeof(float);
            enc.channels[c].user_data_type = EXR_PIXEL_FLOAT;
            enc.channels[c].encode_from_ptr = (const uint8_t *)(planes + (size_t)plane * (size_t)lines * w);
        }
        if (!enc_init) {
            if ((rc = exr_encoding_choose_default_routines(ctx, part, &enc))) {
                exr_fail(rc, path, "cannot encode", err, errlen);
                goto done;
            }
            enc_init = 1;
            if (enc.compress_fn) { /* see exr_compress_unambiguous */
                guard.compress = enc.compress_fn;
                enc.encoding_user_data = &guard;
                enc.compress_fn = exr_compress_unambiguous;
            }
        }
        if ((rc = exr_encoding_run(ctx, part, &enc))) {
            exr_fail(rc, path, "cannot write pixels", err, errlen);
            goto done;
        }
    }
    ok = PM_OK;
done:
    if (enc_init || enc.channels)
        exr_encoding_destroy(ctx, &enc);
    free(planes);
    rc = exr_finish(&ctx);
    if (ok == PM_OK && rc != EXR_ERR_SUCCESS)
        ok = exr_fail(rc, path, "cannot finish", err, errlen);
    return ok;
}

pm_status image_write_exr(const image *im, const char *path, char *err, size_t errlen)
{
    outfile o;
    pm_status rc;
    if ((rc = outfile_begin(&o, path, 0, err, errlen)) != PM_OK)
        return rc;
    if ((rc = exr_write_to(im, o.tmp, path, err, errlen)) != PM_OK) {
        outfile_abort(&o);
        return rc;
    }
    return outfile_commit(&o, err, errlen);
}

pm_status image_read_exr(image *im, const char *path, char *err, size_t errlen)
{
    memset(im, 0, sizeof *im);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_quiet;
    exr_context_t ctx = NULL;
    exr_result_t rc = exr_start_read(&ctx, path, &init);
    if (rc != EXR_ERR_SUCCESS)
        return exr_fail(rc, path, "cannot read", err, errlen);
    pm_status ok = PM_ERR_IO;
    exr_decode_pipeline_t dec;
    memset(&dec, 0, sizeof dec);
    int dec_init = 0;
    float *planes = NULL;
    exr_attr_box2i_t dw;
    int32_t lines = 1;
    if ((rc = exr_get_data_window(ctx, 0, &dw)) || (rc = exr_get_scanlines_per_chunk(ctx, 0, &lines))) {
        exr_fail(rc, path, "bad header", err, errlen);
        goto done;
    }
    uint32_t w = (uint32_t)(dw.max.x - dw.min.x + 1), h = (uint32_t)(dw.max.y - dw.min.y + 1);
    if (image_init(im, w, h) != PM_OK || !(planes = malloc(sizeof(float) * w * 3 * (size_t)lines))) {
        snprintf(err, errlen, "%s: out of memory", path);
        ok = PM_ERR_NOMEM;
        goto done;
    }
    for (int32_t y = dw.min.y; y <= dw.max.y; y += lines) {
        exr_chunk_info_t ci;
        if ((rc = exr_read_scanline_chunk_info(ctx, 0, y, &ci))) {
            exr_fail(rc, path, "cannot read chunk", err, errlen);
            goto done;
        }
        rc = dec_init ? exr_decoding_update(ctx, 0, &ci, &dec) : exr_decoding_initialize(ctx, 0, &ci, &dec);
        if (rc) {
            exr_fail(rc, path, "cannot decode", err, errlen);
            goto done;
        }
        memset(planes, 0, sizeof(float) * w * 3 * (size_t)lines);
        for (int c = 0; c < dec.channel_count; c++) {
            const char *nm = dec.channels[c].channel_name;
            int plane = !strcmp(nm, "R") ? 0 : !strcmp(nm, "G") ? 1 : !strcmp(nm, "B") ? 2 : -1;
            if (plane < 0) {
                dec.channels[c].decode_to_ptr = NULL;
                continue;
            }
            dec.channels[c].user_pixel_stride = sizeof(float);
            dec.channels[c].user_line_stride = (int32_t)(sizeof(float) * w);
            dec.channels[c].user_bytes_per_element = sizeof(float);
            dec.channels[c].user_data_type = EXR_PIXEL_FLOAT;
            dec.channels[c].decode_to_ptr = (uint8_t *)(planes + (size_t)plane * (size_t)lines * w);
        }
        if (!dec_init) {
            if ((rc = exr_decoding_choose_default_routines(ctx, 0, &dec))) {
                exr_fail(rc, path, "cannot decode", err, errlen);
                goto done;
            }
            dec_init = 1;
        }
        if ((rc = exr_decoding_run(ctx, 0, &dec))) {
            exr_fail(rc, path, "cannot decode pixels", err, errlen);
            goto done;
        }
        for (int32_t l = 0; l < ci.height; l++) {
            float *dst = im->rgb + ((size_t)(y - dw.min.y + l) * w) * 3;
            for (int c = 0; c < 3; c++) {
                const float *src = planes + ((size_t)c * (size_t)lines + (size_t)l) * w;
                for (size_t x = 0; x < w; x++)
                    dst[3 * x + (size_t)c] = src[x];
            }
        }
    }
    ok = PM_OK;
done:
    if (dec_init || dec.channels)
        exr_decoding_destroy(ctx, &dec);
    free(planes);
    exr_finish(&ctx);
    if (ok != PM_OK)
        image_free(im);
    return ok;
}

/* ---- PNG ---- */

static unsigned char srgb8(double v)
{
    if (!(v > 0.0))
        return 0;
    if (v >= 1.0)
        return 255;
    double s = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (unsigned char)lrint(s * 255.0);
}

pm_status image_write_png(const image *im, const char *path, double exposure, char *err, size_t errlen)
{
    outfile o;
    pm_status rc = outfile_begin(&o, path, 1, err, errlen);
    if (rc != PM_OK)
        return rc;
    unsigned char *row = malloc((size_t)im->width * 3 + 1);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!row || !png || !info) {
        snprintf(err, errlen, "%s: out of memory", path);
        png_destroy_write_struct(&png, &info);
        free(row);
        outfile_abort(&o);
        return PM_ERR_NOMEM;
    }
    if (setjmp(png_jmpbuf(png))) {
        snprintf(err, errlen, "%s: PNG write failed", path);
        png_destroy_write_struct(&png, &info);
        free(row);
        outfile_abort(&o);
        return PM_ERR_IO;
    }
    png_init_io(png, o.f);
    png_set_IHDR(png, info, im->width, im->height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (uint32_t y = 0; y < im->height; y++) {
        const float *src = im->rgb + (size_t)y * im->width * 3;
        for (size_t x = 0; x < (size_t)im->width * 3; x++)
            row[x] = srgb8(src[x] * exposure);
        png_write_row(png, row);
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    free(row);
    return outfile_commit(&o, err, errlen);
}
