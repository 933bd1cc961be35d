/* casteljau: image files through OpenImageIO (viz/, built when CJ_WITH_OIIO is ON).
 *
 * Pixel layout used by every function here: 8-bit RGBA, 4 bytes per pixel, rows stored
 * BOTTOM-UP: row 0 is the lowest row of the picture, as in the raster/ framebuffer (origin at
 * the lower-left pixel, OpenGL style). Image files are stored top row first, so writing flips
 * the rows and reading flips them back: a buffer written and read again is bit-identical.
 *
 * Writes are atomic: the image goes to a temporary file in the destination's directory
 * (".<name>.tmp-XXXXXX"), which is renamed onto `path` only after the encoder has finished and
 * closed it. On any failure the temporary file is removed and `path` is left as it was (absent
 * or with its previous content): a failed run never leaves a half-written image.
 */
#ifndef CASTELJAU_IMAGE_IO_H
#define CASTELJAU_IMAGE_IO_H

#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes a width x height RGBA8 image as PNG to `path` (whatever its extension).
 *   rgba        pixel data, bottom-up rows (see above); not modified
 *   row_stride  bytes from one row to the next (>= 4*width; 0 means exactly 4*width)
 * Returns CJ_OK, or
 *   CJ_ERR_ARGUMENT  width or height < 1 or > 65535, or row_stride < 4*width
 *   CJ_ERR_IO        the temporary file cannot be created (missing directory, no permission),
 *                    the encoder fails, or the rename fails; the message names the path and
 *                    OpenImageIO's or the system's reason. Nothing is left behind. */
cj_status cj_image_write_png(const char *path, int width, int height, const uint8_t *rgba,
                             size_t row_stride);

/* Reads any image OpenImageIO understands (first subimage) into a newly allocated RGBA8
 * buffer of 4*width*height bytes, bottom-up rows. Gray images are replicated into R, G, B;
 * images without alpha get alpha 255; channels beyond four are ignored; other bit depths are
 * converted to 8 bits by OpenImageIO. Free the buffer with cj_image_free().
 * Returns CJ_OK, or CJ_ERR_IO (missing or unreadable file, decoder error; the message names
 * the path), CJ_ERR_NOMEM. Outputs are untouched on failure. */
cj_status cj_image_read(const char *path, int *width, int *height, uint8_t **rgba);

/* Frees a buffer returned by cj_image_read (NULL is allowed). */
void cj_image_free(uint8_t *rgba);

#ifdef __cplusplus
}
#endif
#endif
