/* Vector plots, the program's side: the layout of cj_plot_doc_render painted through the cairo
 * module (plot_vector_cairo.c, libcasteljau_cairo.so, opened only for an SVG or PDF so that
 * no other launch maps cairo and the X11 libraries it brings), into a temporary file renamed
 * into place when complete. */
#define _POSIX_C_SOURCE 200809L /* mkstemp, fdopen, fsync, fchmod */
#include "plot_vector.h"
#include "plot_vector_plugin.h"

#include "casteljau/chart.h"
#include "casteljau/plot_paint.h"
#include "module_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef CJ_CAIRO_PLUGIN_BUILD
#define CJ_CAIRO_PLUGIN_BUILD NULL
#endif
#ifndef CJ_CAIRO_PLUGIN_INSTALL
#define CJ_CAIRO_PLUGIN_INSTALL NULL
#endif

static const plot_vector_plugin *load_cairo(char *why, size_t why_size) {
    static const cj_module_spec spec = {CJ_CAIRO_PLUGIN_FILE,
                                        "CJ_CAIRO_PLUGIN",
                                        CJ_CAIRO_PLUGIN_BUILD,
                                        CJ_CAIRO_PLUGIN_INSTALL,
                                        CJ_CAIRO_PLUGIN_SYMBOL,
                                        "the vector plot module",
                                        "SVG and PDF plots need cairo: Debian's libcairo2"};
    const plot_vector_plugin *table =
        (const plot_vector_plugin *)cj_module_open(&spec, why, why_size);
    if (table && table->abi != PLOT_VECTOR_PLUGIN_ABI) {
        snprintf(why, why_size, "the vector plot module is of another version (ABI %d, want %d)",
                 table->abi, PLOT_VECTOR_PLUGIN_ABI);
        return NULL;
    }
    return table;
}

int plot_vector_format(const char *path) {
    const size_t n = strlen(path);
    if (n > 4 && !strcasecmp(path + n - 4, ".svg")) return PLOT_VECTOR_SVG;
    if (n > 4 && !strcasecmp(path + n - 4, ".pdf")) return PLOT_VECTOR_PDF;
    return PLOT_VECTOR_NONE;
}

/* A temporary file beside path: its name in tmp[size], the open stream returned. */
static FILE *open_temp(const char *path, char *tmp, size_t size) {
    if ((size_t)snprintf(tmp, size, "%s.XXXXXX", path) >= size) {
        errno = ENAMETOOLONG;
        return NULL;
    }
    const int fd = mkstemp(tmp);
    if (fd < 0) return NULL;
    const mode_t mask = umask(0); /* the finished file gets the usual 0666 & ~umask */
    umask(mask);
    if (fchmod(fd, 0666 & ~mask) != 0) {
        close(fd);
        unlink(tmp);
        return NULL;
    }
    FILE *f = fdopen(fd, "wb");
    if (!f) {
        close(fd);
        unlink(tmp);
    }
    return f;
}

int plot_vector_check(const char *path, char *why, size_t why_size) {
    if (!load_cairo(why, why_size)) return -1; /* before any work */
    char tmp[4096];
    FILE *f = open_temp(path, tmp, sizeof tmp);
    if (!f) {
        snprintf(why, why_size, "%s: cannot create a file there (%s)", path, strerror(errno));
        return -1;
    }
    fclose(f);
    unlink(tmp);
    return 0;
}

int plot_vector_write(cj_plot_doc *doc, cj_font *font, const char *path, char *why,
                      size_t why_size) {
    const plot_vector_plugin *cairo = load_cairo(why, why_size);
    if (!cairo) return CJ_ERR_UNSUPPORTED;
    const int format = plot_vector_format(path);
    /* The raster path's font file, for cairo through FreeType. */
    const char *font_path = cj_font_find_default();
    char tmp[4096];
    FILE *f = open_temp(path, tmp, sizeof tmp);
    if (!f) {
        snprintf(why, why_size, "%s: cannot create a file there (%s)", path, strerror(errno));
        return CJ_ERR_IO;
    }
    const double W = doc->width, H = doc->height;
    cj_plot_painter painter;
    plot_vector_surface *surface =
        cairo->begin(format, W, H, font_path, f, &painter, why, why_size);
    if (!surface) {
        fclose(f);
        unlink(tmp);
        return CJ_ERR_IO;
    }

    /* As cj_plot_doc_render: the background, then a grid of panels split exactly in pixels. */
    const double page[8] = {0, 0, W, 0, W, H, 0, H};
    painter.fill(painter.user, page, 4, doc->background);
    const int cols = doc->columns > 0 ? doc->columns : 1;
    const int rows = (int)((doc->npanels + (size_t)cols - 1) / (size_t)cols);
    int st = CJ_OK;
    for (size_t i = 0; !st && i < doc->npanels; ++i) {
        const int col = (int)(i % (size_t)cols), row = (int)(i / (size_t)cols);
        const int x0 = col * doc->width / cols, x1 = (col + 1) * doc->width / cols;
        const int ytop = doc->height - row * doc->height / rows;
        const int ybot = doc->height - (row + 1) * doc->height / rows;
        cairo->clip(surface, x0, ytop, x1 - x0, ytop - ybot);
        st = doc->charts[i] ? (int)cj_chart_paint(doc->charts[i], x0, ybot, x1 - x0, ytop - ybot,
                                                  font, &painter)
                            : (int)cj_plot_paint(doc->panels[i], x0, ybot, x1 - x0, ytop - ybot,
                                                 font, &painter);
        cairo->unclip(surface);
        if (st) {
            doc->failed = i;
            snprintf(why, why_size, "cannot render %s: %s", cj_plot_doc_where(doc),
                     cj_last_error());
        }
    }
    char end_why[512] = "";
    const int es = cairo->end(surface, path, end_why, sizeof end_why);
    if (!st && es) {
        snprintf(why, why_size, "%s", end_why);
        st = es;
    }
    if (fflush(f) != 0 || fsync(fileno(f)) != 0) {
        if (!st) snprintf(why, why_size, "%s: writing failed (%s)", path, strerror(errno));
        if (!st) st = CJ_ERR_IO;
    }
    if (fclose(f) != 0 && !st) {
        snprintf(why, why_size, "%s: writing failed (%s)", path, strerror(errno));
        st = CJ_ERR_IO;
    }
    if (!st && rename(tmp, path) != 0) {
        snprintf(why, why_size, "%s: cannot rename the finished file into place (%s)", path,
                 strerror(errno));
        st = CJ_ERR_IO;
    }
    if (st) unlink(tmp);
    return st;
}
