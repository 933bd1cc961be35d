/* casteljau: text in raster images through FreeType (anti-aliased, 8-bit coverage).
 *
 * A cj_font owns a FreeType library instance and one face; it is not thread-safe (use one per
 * thread). Text is UTF-8; characters the face lacks are drawn as the face's missing-glyph box.
 * Positions are in framebuffer pixels with the raster/ conventions: origin at the lower-left
 * pixel, y up, pixel (i, j) covering [i, i+1) x [j, j+1). The pen starts at (x, y) on the
 * baseline; glyphs are placed at whole pixels (x and y are rounded), kerning applied when the
 * face has it.
 *
 * Font lookup (cj_font_open with path NULL), in order:
 *   1. the environment variable CJ_FONT, if set (it must name a readable font file);
 *   2. fontconfig's best scalable match for CJ_FONT_FAMILY ("DejaVu Sans", Debian package
 *      fonts-dejavu-core), wherever the system keeps it; fontconfig's rules may offer another
 *      sans-serif face when DejaVu is missing (text then keeps its place but changes shape).
 * If none is found the status is CJ_ERR_UNSUPPORTED and the message says what to install or set.
 */
#ifndef CASTELJAU_TEXT_H
#define CASTELJAU_TEXT_H

#include "casteljau/framebuffer.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_font cj_font;

/* The family asked of fontconfig for the default font. */
#define CJ_FONT_FAMILY "DejaVu Sans"
/* Where Debian installs it (for reference; the lookup goes through fontconfig). */
#define CJ_FONT_DEFAULT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

/* Finds the default font as described above (fontconfig is asked once per process; thread-
 * safe). Returns a static string, or NULL (with cj_last_error() explaining, status
 * CJ_ERR_UNSUPPORTED) when none is found. */
const char *cj_font_find_default(void);

/* Opens a font file (TrueType/OpenType/anything FreeType reads); path NULL = the default.
 * *out receives the font, to be released with cj_font_close. Returns CJ_OK,
 * CJ_ERR_UNSUPPORTED (no default font found), CJ_ERR_IO (file missing or not a font; the message
 * names the path and FreeType's error code), CJ_ERR_NOMEM. */
cj_status cj_font_open(const char *path, cj_font **out);

/* Releases a font (NULL allowed). */
void cj_font_close(cj_font *font);

/* Measures a string at a pixel size (the em height, 4 <= size_px <= 512):
 *   *advance  horizontal advance of the whole string in pixels (pen movement)
 *   *ascent   height of the face above the baseline, *descent depth below it (positive),
 *             both for this size, from the face metrics (so all strings share them).
 * Any output may be NULL. Returns CJ_OK, CJ_ERR_RANGE (size), CJ_ERR_PARSE (invalid UTF-8). */
cj_status cj_font_measure(cj_font *font, double size_px, const char *utf8, double *advance,
                          double *ascent, double *descent);

/* Draws a string into a framebuffer with the pen starting at (x, y) on the baseline. Each glyph
 * pixel is blended with cj_framebuffer_blend_coverage (colour alpha x glyph coverage, straight
 * alpha source-over). Pixels outside the framebuffer are clipped. Same statuses as
 * cj_font_measure, plus CJ_ERR_NONFINITE for a NaN/Inf position. */
cj_status cj_font_draw(cj_font *font, cj_framebuffer *fb, double x, double y, double size_px,
                       cj_rgba color, const char *utf8);

#ifdef __cplusplus
}
#endif
#endif
