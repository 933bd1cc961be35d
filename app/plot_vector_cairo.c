/* The cairo side of vector plots (plot_vector_plugin.h), built as the module
 * libcasteljau_cairo.so: a cj_plot_painter over cairo's SVG and PDF surfaces. Our coordinates
 * have y up from the bottom of the image; cairo's go down from the top, so y becomes
 * height - y. Text is set by cairo in the very font file the raster path uses (opened with
 * FreeType for cairo-ft) at the same em size, stretched horizontally to the advance the layout
 * measured, so that labels end where the PNG's do. */
#include "plot_vector_plugin.h"

#include <cairo-ft.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <stdio.h>
#include <stdlib.h>

typedef struct painter_state {
    cairo_t *cr;
    double height;
    cairo_font_face_t *face;
    cairo_surface_t *surface;
    FT_Library ft;
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

static plot_vector_surface *begin(int format, double width, double height, const char *font_path,
                                  FILE *f, cj_plot_painter *painter, char *why, size_t why_size) {
    FT_Library ft = NULL;
    FT_Face ft_face = NULL;
    if (!font_path || FT_Init_FreeType(&ft) || FT_New_Face(ft, font_path, 0, &ft_face)) {
        snprintf(why, why_size, "cannot open the font %s", font_path ? font_path : "(none found)");
        if (ft) FT_Done_FreeType(ft);
        return NULL;
    }
    painter_state *p = calloc(1, sizeof *p);
    if (!p) {
        snprintf(why, why_size, "no memory for a vector plot");
        FT_Done_Face(ft_face);
        FT_Done_FreeType(ft);
        return NULL;
    }
    /* cairo keeps the face while any scaled font uses it: it releases the FreeType face
     * itself (user data), and the caches are flushed in `end` before the library goes. */
    static const cairo_user_data_key_t face_key;
    cairo_font_face_t *face = cairo_ft_font_face_create_for_ft_face(ft_face, 0);
    if (cairo_font_face_set_user_data(face, &face_key, ft_face, done_face))
        FT_Done_Face(ft_face); /* (only when cairo is out of memory; the face is then unusable) */
    cairo_surface_t *surface;
    if (format == PLOT_VECTOR_SVG) {
        surface = cairo_svg_surface_create_for_stream(to_file, f, width, height);
        cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PX);
    } else {
        surface = cairo_pdf_surface_create_for_stream(to_file, f, width, height);
    }
    p->cr = cairo_create(surface);
    p->height = height;
    p->face = face;
    p->surface = surface;
    p->ft = ft;
    const cj_plot_painter painted = {p, paint_stroke, paint_fill, paint_disc, paint_text};
    *painter = painted;
    return (plot_vector_surface *)p;
}

static void clip(plot_vector_surface *s, double x, double y_top, double w, double h) {
    painter_state *p = (painter_state *)s;
    cairo_save(p->cr); /* a panel draws inside its rectangle only, as on a framebuffer */
    cairo_rectangle(p->cr, x, p->height - y_top, w, h);
    cairo_clip(p->cr);
}

static void unclip(plot_vector_surface *s) {
    cairo_restore(((painter_state *)s)->cr);
}

static int end(plot_vector_surface *s, const char *path, char *why, size_t why_size) {
    painter_state *p = (painter_state *)s;
    cairo_destroy(p->cr);
    cairo_surface_finish(p->surface);
    const cairo_status_t cs = cairo_surface_status(p->surface);
    cairo_surface_destroy(p->surface);
    cairo_font_face_destroy(p->face);
    cairo_debug_reset_static_data(); /* drops cairo's font caches: the face goes now */
    FT_Done_FreeType(p->ft);
    free(p);
    if (cs != CAIRO_STATUS_SUCCESS) {
        snprintf(why, why_size, "%s: cairo: %s", path, cairo_status_to_string(cs));
        return cs == CAIRO_STATUS_NO_MEMORY ? CJ_ERR_NOMEM : CJ_ERR_IO;
    }
    return CJ_OK;
}

__attribute__((visibility("default"))) const plot_vector_plugin *cj_cairo_plugin_v1(void);

const plot_vector_plugin *cj_cairo_plugin_v1(void) {
    static const plot_vector_plugin table = {PLOT_VECTOR_PLUGIN_ABI, begin, clip, unclip, end};
    return &table;
}
