/* PNG through libpng (see image_png_internal.h). libpng reports errors by calling our handler,
 * which records the message and longjmps back to the setjmp in encode_rows / decode_rows. Those
 * two functions modify no local after their setjmp: every resource that must be released on
 * an error lives in a png_job owned by the caller, which frees it on both paths. */
#include "image_png_internal.h"

#include "casteljau/image_io.h"
#include "casteljau/status.h"

#include <png.h>

#include <errno.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct png_job {
    char *why;
    size_t why_size;
    int status; /* what a libpng error means: CJ_ERR_IO unless a callback said otherwise */
    /* encoding: the growing output */
    unsigned char *out;
    size_t out_size, out_cap;
    /* decoding */
    FILE *fp;
    uint8_t *pixels;
    png_bytep *rows;
} png_job;

static void PNGCBAPI on_error(png_structp png, png_const_charp msg) {
    png_job *job = (png_job *)png_get_error_ptr(png);
    /* A callback of ours may have written a better reason before raising the error. */
    if (!job->why[0]) snprintf(job->why, job->why_size, "libpng: %s", msg ? msg : "error");
    png_longjmp(png, 1);
}

/* Warnings (an unknown chunk, a bad sRGB profile) do not stop the decode and are not printed:
 * the tool's messages are its own, one line each. */
static void PNGCBAPI on_warning(png_structp png, png_const_charp msg) {
    (void)png;
    (void)msg;
}

int cj_png_is_png_name(const char *name) {
    const char *slash = strrchr(name, '/');
    const char *base = slash ? slash + 1 : name;
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base) return 0;
    return (dot[1] == 'p' || dot[1] == 'P') && (dot[2] == 'n' || dot[2] == 'N') &&
           (dot[3] == 'g' || dot[3] == 'G') && dot[4] == '\0';
}

int cj_png_file_is_png(const char *path) {
    FILE *f = fopen(path, "rbe");
    if (!f) return 0;
    unsigned char sig[8];
    const size_t got = fread(sig, 1, sizeof sig, f);
    fclose(f);
    return got == sizeof sig && png_sig_cmp(sig, 0, sizeof sig) == 0;
}

/* ---- writing ------------------------------------------------------------------------------ */

static void PNGCBAPI write_bytes(png_structp png, png_bytep data, size_t n) {
    png_job *job = (png_job *)png_get_io_ptr(png);
    if (n > job->out_cap - job->out_size) {
        size_t cap = job->out_cap;
        while (cap - job->out_size < n) {
            if (cap > SIZE_MAX / 2) {
                job->status = CJ_ERR_NOMEM;
                snprintf(job->why, job->why_size, "the encoded PNG outgrows memory");
                png_error(png, "size");
            }
            cap *= 2;
        }
        unsigned char *grown = (unsigned char *)realloc(job->out, cap);
        if (!grown) {
            job->status = CJ_ERR_NOMEM;
            snprintf(job->why, job->why_size, "no memory for %zu encoded PNG bytes", cap);
            png_error(png, "memory");
        }
        job->out = grown;
        job->out_cap = cap;
    }
    memcpy(job->out + job->out_size, data, n);
    job->out_size += n;
}

static void PNGCBAPI flush_bytes(png_structp png) {
    (void)png;
}

static int encode_rows(png_structp png, png_infop info, const cj_image_pixels *px, png_job *job) {
    if (setjmp(png_jmpbuf(png))) return job->status;
    png_set_write_fn(png, job, write_bytes, flush_bytes);
    png_set_IHDR(png, info, (png_uint_32)px->width, (png_uint_32)px->height, 8,
                 PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    /* The samples are sRGB-encoded 8-bit values (raster/'s output transfer). */
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_set_compression_level(png, CJ_PNG_ZLIB_LEVEL);
    png_write_info(png, info);
    /* Files are stored top row first; our rows are bottom-up. */
    for (int y = px->height - 1; y >= 0; --y)
        png_write_row(png, (png_const_bytep)px->pixels + (size_t)y * px->row_stride);
    png_write_end(png, info);
    return CJ_OK;
}

int cj_png_encode(const cj_image_pixels *px, unsigned char **bytes, size_t *size, char *why,
                  size_t why_size) {
    *bytes = NULL;
    *size = 0;
    why[0] = '\0';
    if (px->is_float) {
        snprintf(why, why_size,
                 "the png format stores no floating-point samples (use .exr, .tif, .hdr or .pfm "
                 "for a linear float image)");
        return CJ_ERR_ARGUMENT;
    }
    png_job job = {why, why_size, CJ_ERR_IO, NULL, 0, 0, NULL, NULL, NULL};
    /* A first guess of the compressed size, so that most images need no reallocation. */
    job.out_cap = (size_t)px->width * (size_t)px->height + 1024;
    job.out = (unsigned char *)malloc(job.out_cap);
    if (!job.out) {
        snprintf(why, why_size, "no memory to encode a %d x %d PNG", px->width, px->height);
        return CJ_ERR_NOMEM;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        free(job.out);
        snprintf(why, why_size, "no memory for libpng's encoder");
        return CJ_ERR_NOMEM;
    }
    const int code = encode_rows(png, info, px, &job);
    png_destroy_write_struct(&png, &info);
    if (code != CJ_OK) {
        free(job.out);
        return code;
    }
    *bytes = job.out;
    *size = job.out_size;
    return CJ_OK;
}

/* ---- reading ------------------------------------------------------------------------------ */

/* fread with a message of our own: a short read is a truncated file, not "Read Error". */
static void PNGCBAPI read_bytes(png_structp png, png_bytep data, size_t n) {
    png_job *job = (png_job *)png_get_io_ptr(png);
    if (fread(data, 1, n, job->fp) == n) return;
    if (ferror(job->fp))
        snprintf(job->why, job->why_size, "read error: %s", strerror(errno));
    else
        snprintf(job->why, job->why_size, "the PNG file ends early (truncated)");
    png_error(png, "read");
}

static int decode_rows(png_structp png, png_infop info, png_job *job, int *width, int *height) {
    if (setjmp(png_jmpbuf(png))) return job->status;
    png_set_read_fn(png, job, read_bytes);
    png_read_info(png, info);
    const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    /* The header's claim, checked before decoding: a small file can declare a huge image. */
    if (w > CJ_IMAGE_MAX_SIDE || h > CJ_IMAGE_MAX_SIDE ||
        (long long)w * (long long)h > CJ_IMAGE_MAX_PIXELS) {
        snprintf(job->why, job->why_size,
                 "%u x %u pixels is over the limit of %d pixels a side and %lld pixels in all",
                 (unsigned)w, (unsigned)h, CJ_IMAGE_MAX_SIDE, (long long)CJ_IMAGE_MAX_PIXELS);
        return CJ_ERR_RANGE;
    }
    const int color = png_get_color_type(png, info);
    /* To RGBA8 as the OpenImageIO path gave it: palette and low depths expanded, tRNS as
     * alpha, gray replicated, 16 bits rounded to 8, no gamma applied. */
    png_set_expand(png);
    png_set_scale_16(png);
    if (!(color & PNG_COLOR_MASK_COLOR)) png_set_gray_to_rgb(png);
    if (!(color & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    (void)png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)w * 4) {
        snprintf(job->why, job->why_size, "unexpected PNG row layout (%zu bytes for %u pixels)",
                 (size_t)png_get_rowbytes(png, info), (unsigned)w);
        return CJ_ERR_IO;
    }
    job->pixels = (uint8_t *)malloc((size_t)w * h * 4);
    job->rows = (png_bytep *)malloc(sizeof(png_bytep) * h);
    if (!job->pixels || !job->rows) {
        snprintf(job->why, job->why_size, "no memory for a %u x %u image", (unsigned)w,
                 (unsigned)h);
        return CJ_ERR_NOMEM;
    }
    for (png_uint_32 y = 0; y < h; ++y) /* file rows top-down, ours bottom-up */
        job->rows[y] = job->pixels + (size_t)(h - 1 - y) * w * 4;
    png_read_image(png, job->rows);
    *width = (int)w;
    *height = (int)h;
    return CJ_OK;
}

int cj_png_read_rgba8(const char *path, int *width, int *height, uint8_t **rgba, char *why,
                      size_t why_size) {
    why[0] = '\0';
    png_job job = {why, why_size, CJ_ERR_IO, NULL, 0, 0, NULL, NULL, NULL};
    job.fp = fopen(path, "rbe");
    if (!job.fp) {
        snprintf(why, why_size, "%s", strerror(errno));
        return CJ_ERR_IO;
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        fclose(job.fp);
        snprintf(why, why_size, "no memory for libpng's decoder");
        return CJ_ERR_NOMEM;
    }
    int w = 0, h = 0;
    const int code = decode_rows(png, info, &job, &w, &h);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(job.fp);
    free(job.rows);
    if (code != CJ_OK) {
        free(job.pixels);
        return code;
    }
    *width = w;
    *height = h;
    *rgba = job.pixels;
    return CJ_OK;
}
