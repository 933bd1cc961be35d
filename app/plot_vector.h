/* Private to the casteljau tool: `casteljau plot -o x.svg | x.pdf`, the plot document painted by
 * cairo (Debian libcairo2-dev) with the layout of the PNG (casteljau/plot_paint.h): same size
 * (one pixel = one SVG px = one PDF point), same panels, items, ticks, labels and title. */
#ifndef CASTELJAU_APP_PLOT_VECTOR_H
#define CASTELJAU_APP_PLOT_VECTOR_H

#include "plot_json.h"
#include "plot_vector_plugin.h" /* PLOT_VECTOR_SVG, PLOT_VECTOR_PDF */

#include <stddef.h>

/* PLOT_VECTOR_SVG or _PDF from the extension of path (any case), else PLOT_VECTOR_NONE. */
int plot_vector_format(const char *path);

/* Before any work: a file can be created beside `path` (a temporary one is made and removed).
 * 0, or -1 with the reason in why. */
int plot_vector_check(const char *path, char *why, size_t why_size);

/* Paints doc into path (written to a temporary file renamed into place when complete, so an
 * existing file is kept on failure); chart panels ("kind": "chart") too. Returns CJ_OK or a status
 * with the reason in why: CJ_ERR_IO, CJ_ERR_NOMEM (the writer), or the status of a panel that
 * cannot be drawn. */
int plot_vector_write(cj_plot_doc *doc, cj_font *font, const char *path, char *why,
                      size_t why_size);

#endif
