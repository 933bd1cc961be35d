/* Vector plots: a cj_plot_painter over cairo's SVG and PDF surfaces. Our coordinates have y up
 * from the bottom of the image; cairo's go down from the top, so y becomes height - y. Text is
 * set by cairo in the very font file the raster path uses (cj_font_find_default, opened with
 * FreeType for cairo-ft: no fontconfig lookup) at the same em size, stretched horizontally to
 * the advance the layout measured, so that labels end where the PNG's do. */
#define _POSIX_C_SOURCE 200809L /* mkstemp, fdopen, fsync, fchmod */
#include "plot_vector.h"

#include "casteljau/chart.h"
#include "casteljau/plot_paint.h"

#include <cairo-ft.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <errno.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

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

typedef struct painter_state {
    cairo_t *cr;
    double height;
    cairo_font_face_t *face;
} painter_state;

static void set_colour(cairo_t *cr, cj_rgba c) {
    cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
}

static void trace_path(painter_state *p, const double *xy, size_t n, int closed) {
    cairo_new_path(p->cr);
    for (size_t i = 0; i < n; ++i) cairo_line_to(p->cr, xy[2 * i], p->height - xy[2 * i + 1]);
    if (closed) cairo_close_path(p->cr);
}

static cj_status paint_stroke(void *user, const double *xy, size_t n, int closed, cj_rgba c,
                              double width) {
    painter_state *p = user;
    trace_path(p, xy, n, closed);
    if (n == 1) cairo_line_to(p->cr, xy[0], p->height - xy[1]); /* a dot: round caps */
    set_colour(p->cr, c);
    cairo_set_line_width(p->cr, width);
    cairo_set_line_cap(p->cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(p->cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke(p->cr);
    return CJ_OK;
}

static cj_status paint_fill(void *user, const double *xy, size_t n, cj_rgba c) {
    painter_state *p = user;
    trace_path(p, xy, n, 1);
    set_colour(p->cr, c);
    cairo_fill(p->cr);
    return CJ_OK;
}

static cj_status paint_disc(void *user, double x, double y, double r, cj_rgba c) {
    painter_state *p = user;
    cairo_new_path(p->cr);
    cairo_arc(p->cr, x, p->height - y, r, 0, 6.283185307179586);
    set_colour(p->cr, c);
    cairo_fill(p->cr);
    return CJ_OK;
}

static cj_status paint_text(void *user, double x, double y, double size_px, double advance,
                            cj_rgba c, const char *utf8) {
    painter_state *p = user;
    cairo_t *cr = p->cr;
    cairo_save(cr);
    cairo_set_font_face(cr, p->face);
    cairo_set_font_size(cr, size_px);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, utf8, &ext);
    double stretch = 1.0;
    if (ext.x_advance > 0 && advance > 0) stretch = advance / ext.x_advance;
    if (!(stretch > 0.8 && stretch < 1.25)) stretch = 1.0; /* another face: keep its shape */
    cairo_translate(cr, x, p->height - y);
    cairo_scale(cr, stretch, 1.0);
    cairo_move_to(cr, 0, 0);
    set_colour(cr, c);
    cairo_show_text(cr, utf8);
    cairo_restore(cr);
    return CJ_OK;
}

static void done_face(void *ft_face) {
    FT_Done_Face(ft_face);
}

static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int length) {
    return fwrite(data, 1, length, closure) == length ? CAIRO_STATUS_SUCCESS
                                                      : CAIRO_STATUS_WRITE_ERROR;
}

int plot_vector_write(plot_doc *doc, cj_font *font, const char *path, char *why, size_t why_size) {
    const int format = plot_vector_format(path);
    /* The raster path's font file, for cairo through FreeType. */
    const char *font_path = cj_font_find_default();
    FT_Library ft = NULL;
    FT_Face ft_face = NULL;
    if (!font_path || FT_Init_FreeType(&ft) || FT_New_Face(ft, font_path, 0, &ft_face)) {
        snprintf(why, why_size, "cannot open the font %s", font_path ? font_path : "(none found)");
        if (ft) FT_Done_FreeType(ft);
        return CJ_ERR_IO;
    }
    char tmp[4096];
    FILE *f = open_temp(path, tmp, sizeof tmp);
    if (!f) {
        snprintf(why, why_size, "%s: cannot create a file there (%s)", path, strerror(errno));
        FT_Done_Face(ft_face);
        FT_Done_FreeType(ft);
        return CJ_ERR_IO;
    }
    /* cairo keeps the face while any scaled font uses it: it releases the FreeType face
     * itself (user data), and the caches are flushed below before the library goes. */
    static const cairo_user_data_key_t face_key;
    cairo_font_face_t *face = cairo_ft_font_face_create_for_ft_face(ft_face, 0);
    if (cairo_font_face_set_user_data(face, &face_key, ft_face, done_face))
        FT_Done_Face(ft_face); /* (only when cairo is out of memory; the face is then unusable) */
    const double W = doc->width, H = doc->height;
    cairo_surface_t *surface;
    if (format == PLOT_VECTOR_SVG) {
        surface = cairo_svg_surface_create_for_stream(to_file, f, W, H);
        cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
    } else {
        surface = cairo_pdf_surface_create_for_stream(to_file, f, W, H);
    }
    cairo_t *cr = cairo_create(surface);
    painter_state state = {cr, H, face};
    const cj_plot_painter painter = {&state, paint_stroke, paint_fill, paint_disc, paint_text};

    /* As plot_doc_render: the background, then a grid of panels split exactly in pixels. */
    const double page[8] = {0, 0, W, 0, W, H, 0, H};
    paint_fill(&state, page, 4, doc->background);
    const int cols = doc->columns > 0 ? doc->columns : 1;
    const int rows = (int)((doc->npanels + (size_t)cols - 1) / (size_t)cols);
    int st = CJ_OK;
    for (size_t i = 0; !st && i < doc->npanels; ++i) {
        const int col = (int)(i % (size_t)cols), row = (int)(i / (size_t)cols);
        const int x0 = col * doc->width / cols, x1 = (col + 1) * doc->width / cols;
        const int ytop = doc->height - row * doc->height / rows;
        const int ybot = doc->height - (row + 1) * doc->height / rows;
        cairo_save(cr); /* a panel draws inside its rectangle only, as on a framebuffer */
        cairo_rectangle(cr, x0, doc->height - ytop, x1 - x0, ytop - ybot);
        cairo_clip(cr);
        st = doc->charts[i] ? (int)cj_chart_paint(doc->charts[i], x0, ybot, x1 - x0, ytop - ybot,
                                                  font, &painter)
                            : (int)cj_plot_paint(doc->panels[i], x0, ybot, x1 - x0, ytop - ybot,
                                                 font, &painter);
        cairo_restore(cr);
        if (st) {
            doc->failed = i;
            snprintf(why, why_size, "cannot render %s: %s", plot_doc_where(doc), cj_last_error());
        }
    }
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    const cairo_status_t cs = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    cairo_font_face_destroy(face);
    cairo_debug_reset_static_data(); /* drops cairo's font caches: the face goes now */
    FT_Done_FreeType(ft);
    if (!st && cs != CAIRO_STATUS_SUCCESS) {
        snprintf(why, why_size, "%s: cairo: %s", path, cairo_status_to_string(cs));
        st = cs == CAIRO_STATUS_NO_MEMORY ? CJ_ERR_NOMEM : CJ_ERR_IO;
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
