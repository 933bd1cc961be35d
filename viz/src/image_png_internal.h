/* Private: PNG through libpng directly (image_png.c), used by image_io.c for every .png it
 * writes and every PNG file it reads, so that the commands whose images are PNG never open the
 * OpenImageIO plug-in (which costs ~0.4 s and ~130 MB at start-up). The pixels match what the
 * plug-in wrote and read (tests/test_image_png.c decodes both and compares).
 *
 * Same conventions as image_plugin.h: each function returns a cj_status value and, on failure,
 * writes a one-line reason to why[why_size] (libpng's own error text, never printed: libpng's
 * errors and warnings go to handlers of ours, and its longjmp never crosses an allocation that
 * would leak). */
#ifndef CASTELJAU_IMAGE_PNG_INTERNAL_H
#define CASTELJAU_IMAGE_PNG_INTERNAL_H

#include "image_plugin.h"

#include <stddef.h>
#include <stdint.h>

/* The zlib level of every PNG written, with libpng's adaptive row filters: 3. On 1024-pixel
 * renders it encodes in ~0.55x the time of zlib's default 6 for files ~1.15x larger (level 9:
 * 7x the time for 7 % less); docs/cli.md gives the figures. */
#define CJ_PNG_ZLIB_LEVEL 3

/* 1 when the last path component of `name` ends in ".png" (any case), else 0. */
int cj_png_is_png_name(const char *name);

/* 1 when the file starts with the 8-byte PNG signature, else 0 (also when it cannot be read:
 * the caller's reader then reports why). */
int cj_png_file_is_png(const char *path);

/* Encodes px (RGBA8 only: px->is_float must be 0; bottom-up rows) as an 8-bit RGBA PNG
 * marked sRGB, into *bytes (malloc'd, freed by the caller) and *size.
 * Status: CJ_OK, CJ_ERR_NOMEM, CJ_ERR_IO (libpng refused; why carries its message). */
int cj_png_encode(const cj_image_pixels *px, unsigned char **bytes, size_t *size, char *why,
                  size_t why_size);

/* cj_image_read's contract for a PNG file: RGBA8, bottom-up rows, malloc'd. Palette, gray and
 * low bit depths are expanded, tRNS becomes alpha, 16-bit samples are rounded to 8 bits
 * (v * 255 / 65535, to nearest), no gamma is applied. The header's size is checked against
 * CJ_IMAGE_MAX_SIDE / CJ_IMAGE_MAX_PIXELS before any pixel is decoded (CJ_ERR_RANGE).
 * Status: CJ_OK, CJ_ERR_IO (unreadable, not a PNG, corrupt or truncated), CJ_ERR_RANGE,
 * CJ_ERR_NOMEM. */
int cj_png_read_rgba8(const char *path, int *width, int *height, uint8_t **rgba, char *why,
                      size_t why_size);

#endif
