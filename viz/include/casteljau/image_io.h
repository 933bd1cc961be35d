/* casteljau: image files through OpenImageIO (viz/, built when CJ_WITH_OIIO is ON).
 *
 * Pixel layout used by every function here: RGBA, 4 samples per pixel (uint8_t, or float for
 * cj_image_write_float), rows stored BOTTOM-UP: row 0 is the lowest row of the picture, as in
 * the raster/ framebuffer (origin at the lower-left pixel, OpenGL style). Image files are stored
 * top row first, so writing flips the rows and reading flips them back: a buffer written and
 * read again is bit-identical (for the lossless formats).
 *
 * Writes are atomic and checked: the image is encoded, then written to a temporary file in the
 * destination's directory (".<name>.tmp-<pid>-<n>"); every write(2), the fsync(2) and the
 * close(2) are checked, and only then is the file renamed onto `path` (and the directory
 * synced). On any failure - a full disk, a file-size limit, a missing directory - the
 * temporary file is removed and `path` is left as it was (absent or with its previous
 * content): a failed run never leaves a half-written image.
 *
 * PNG is written and read through libpng directly (8-bit RGBA marked sRGB, zlib level 3; any
 * file starting with the PNG signature is read by libpng): no plug-in is opened for it.
 * OpenImageIO, for every other format, is not linked into the program: it sits in a plug-in,
 * libcasteljau_image_oiio.so, opened with dlopen on the first call that needs it, so that
 * programs which never touch such an image do not load it (and the ~260 libraries it pulls
 * in). The plug-in is looked for next to the program or library that contains this code, in its
 * casteljau/ and ../lib/casteljau/ folders (the install layout), then where it was built and
 * installed; the environment variable CJ_IMAGE_PLUGIN names it explicitly. When it cannot be
 * found or opened, every function that needs it returns CJ_ERR_UNSUPPORTED saying where it
 * looked.
 */
#ifndef CASTELJAU_IMAGE_IO_H
#define CASTELJAU_IMAGE_IO_H

#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes a width x height RGBA8 image in the format `path`'s extension names (any case):
 * .png through libpng; through OpenImageIO .tif/.tiff, .exr (stored as half floats, values /
 * 255), .bmp, .tga, .ppm, .webp, ... Formats without an alpha channel (.jpg/.jpeg, .ppm, .bmp
 * ...) get the colour composited over black (rgb * alpha / 255, rounded); JPEG is written at
 * quality 95.
 *   rgba        pixel data, bottom-up rows (see above); not modified
 *   row_stride  bytes from one row to the next (>= 4*width; 0 means exactly 4*width)
 * Returns CJ_OK, or
 *   CJ_ERR_ARGUMENT    width or height < 1 or > 65535, row_stride < 4*width, an empty path,
 *                      or an extension that names no format OpenImageIO can write (the file
 *                      is not created)
 *   CJ_ERR_IO          the temporary file cannot be created (missing directory, no
 *                      permission), the encoder fails, a write, fsync or close fails (full
 *                      disk), or the rename fails; the message names the path and the reason.
 *                      Nothing is left behind and an existing `path` is untouched.
 *   CJ_ERR_NOMEM       no memory to encode
 *   CJ_ERR_UNSUPPORTED the OpenImageIO plug-in cannot be found or opened (see above; never
 *                      for .png) */
cj_status cj_image_write(const char *path, int width, int height, const uint8_t *rgba,
                         size_t row_stride);

/* Writes a width x height linear float RGBA image (bottom-up rows, row_stride in bytes >=
 * 16*width, 0 means exactly 16*width) to a format that stores floating-point samples: .exr
 * (OpenEXR, stored as 32-bit floats; alpha is written as given, and OpenEXR's convention is
 * colour premultiplied by alpha), .tif/.tiff, .pfm (32-bit float), .hdr (RGBE; no alpha, the
 * colour is multiplied by alpha). No transfer curve is applied: the values are stored as they
 * are. NO INFINITY IS EVER WRITTEN: a sample that is infinite or NaN refuses the whole image
 * with CJ_ERR_NONFINITE naming the pixel (x, y from the lower-left corner) and the channel.
 * Same atomic, checked write and the same status codes as cj_image_write; an extension
 * naming an 8-bit-only format (.png, .jpg, ...) is CJ_ERR_ARGUMENT (convert to sRGB 8-bit and
 * call cj_image_write instead). */
cj_status cj_image_write_float(const char *path, int width, int height, const float *rgba,
                               size_t row_stride);

/* Flags of cj_image_write_float_with_flags. */
enum {
    CJ_IMAGE_FLOAT_HALF = 1u /* OpenEXR: store half floats (16-bit) instead of 32-bit ones */
};

/* cj_image_write_float with flags (0: the same). With CJ_IMAGE_FLOAT_HALF an EXR is stored as
 * half floats, and a sample beyond the largest half (65504), which would become infinity, is
 * CJ_ERR_RANGE naming the pixel (nothing is written); other formats ignore the flag. */
cj_status cj_image_write_float_with_flags(const char *path, int width, int height,
                                          const float *rgba, size_t row_stride, unsigned flags);

/* Checks, before any expensive work, that an image could be written to `path`: the name is not
 * empty or a directory, its extension names a format that can store the pixels (is_float
 * selects cj_image_write_float's rules), and a file can be created in its directory (a
 * temporary file is created and removed). Returns CJ_OK or the status cj_image_write would
 * return (CJ_ERR_ARGUMENT, CJ_ERR_IO, CJ_ERR_UNSUPPORTED). A later write can still fail (a disk
 * that fills in between). */
cj_status cj_image_check_destination(const char *path, int is_float);

/* The name and version of the image back end ("OpenImageIO 2.4.7"), loading the plug-in if
 * needed; NULL (with cj_last_error() saying why) when it cannot be opened. */
const char *cj_image_backend(void);

/* Writes a width x height RGBA8 image as PNG to `path`, whatever its extension (kept for
 * existing callers; cj_image_write chooses the format from the extension). Same arguments,
 * atomic checked write and status codes as cj_image_write (never CJ_ERR_ARGUMENT for the
 * extension). */
cj_status cj_image_write_png(const char *path, int width, int height, const uint8_t *rgba,
                             size_t row_stride);

/* Reads a PNG (libpng) or any image OpenImageIO understands (first subimage) into a newly
 * allocated RGBA8 buffer of 4*width*height bytes, bottom-up rows. Gray images are replicated
 * into R, G, B; images without alpha get alpha 255 (a PNG's tRNS becomes alpha); channels
 * beyond four are ignored; other bit depths are converted to 8 bits (16-bit PNG samples
 * rounded to nearest, as OpenImageIO does; no gamma is applied). Free the buffer with
 * cj_image_free().
 * Hostile files cost little: `path` must be a regular file (not /dev/zero, a pipe or a folder)
 * of at most CJ_IMAGE_MAX_FILE_BYTES, and the dimensions in its header are checked against
 * CJ_IMAGE_MAX_SIDE and CJ_IMAGE_MAX_PIXELS before any pixel is decoded (a 249 kB PNG may
 * claim 16000 x 16000 pixels: 1 GB decoded). Messages of the image library (libpng's
 * warnings, OpenImageIO's errors) are captured into cj_last_error(), never printed.
 * Returns CJ_OK, or CJ_ERR_IO (missing or unreadable file, decoder error; the message names
 * the path), CJ_ERR_ARGUMENT (not a regular file), CJ_ERR_RANGE (file or dimensions over the
 * caps; the message gives both), CJ_ERR_NOMEM, CJ_ERR_UNSUPPORTED (no plug-in). Outputs are
 * untouched on failure. */
#define CJ_IMAGE_MAX_FILE_BYTES ((size_t)256 << 20)
#define CJ_IMAGE_MAX_SIDE       32768
#define CJ_IMAGE_MAX_PIXELS     ((long long)1 << 26) /* 8192 x 8192: 256 MiB as RGBA8 */
cj_status cj_image_read(const char *path, int *width, int *height, uint8_t **rgba);

/* Frees a buffer returned by cj_image_read (NULL is allowed). */
void cj_image_free(uint8_t *rgba);

#ifdef __cplusplus
}
#endif
#endif
