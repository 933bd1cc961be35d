/* casteljau: the editor model of `casteljau view` for 2D curves, usable without a window.
 *
 * A cj_vdoc is a list of 2D curves (Bézier of any degree, rational Bézier, interpolating
 * splines of the Catmull-Rom kinds) with their plot styles, plus a COMMAND LOG: every edit is
 * recorded with the exact curves it replaced and produced, so undo and redo restore geometry
 * bit for bit. Edits made after an undo drop the undone commands (the usual linear history).
 *
 * The picture is the plot of casteljau/plot.h drawn with an explicit view box, no axes, no
 * title and no margin, so that data -> pixel is the known affine map of cj_vview (the same
 * arithmetic as the plot's): picking and dragging are exact in pixels, and the file written by
 * cj_vdoc_save_json renders with `casteljau plot` to the very pixels the viewer shows.
 *
 * Pixel coordinates here are framebuffer coordinates: origin at the lower-left corner of the
 * image, y up, pixel (x, y) covering [x, x+1) × [y, y+1).
 *
 * OWNERSHIP: the document owns its curves (every function copies its input); pointers from
 * cj_vdoc_curve stay valid until the next edit, undo or redo.
 *
 * Status codes: CJ_ERR_ARGUMENT (an index that names nothing, an edit the curve kind has not got,
 * e.g. elevating a spline), CJ_ERR_RANGE (t outside [0, 1], a weight <= 0, a degree above
 * CJ_BEZIER_MAX_DEGREE, fewer points than the kind needs), CJ_ERR_NONFINITE (a NaN/Inf
 * coordinate), CJ_ERR_EMPTY (nothing to undo/redo), CJ_ERR_NOMEM; the document is unchanged
 * on failure.
 */
#ifndef CASTELJAU_VIEWER_MODEL_H
#define CASTELJAU_VIEWER_MODEL_H

#include "casteljau/catmull_rom.h"
#include "casteljau/framebuffer.h"
#include "casteljau/plot.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_vcurve_kind {
    CJ_VCURVE_BEZIER = 0, /* polynomial Bézier, count-1 = degree */
    CJ_VCURVE_RATIONAL,   /* rational Bézier, one weight > 0 per point */
    CJ_VCURVE_SPLINE      /* interpolating spline through the points (spline.kind) */
} cj_vcurve_kind;

/* One curve. Coordinates are point-major (x, y); weights only for CJ_VCURVE_RATIONAL. */
typedef struct cj_vcurve {
    cj_vcurve_kind kind;
    size_t count;
    double *pts;     /* 2*count */
    double *weights; /* count, or NULL */
    cj_spline_options spline;
    /* plot style (casteljau/plot.h) */
    cj_rgba color;
    double width;
    int control_polygon, control_points, hull, normals, knots;
    size_t nframes;
    double frames_t[CJ_PLOT_MAX_FRAMES];
} cj_vcurve;

/* A curve with the plot's default style (cj_plot_bezier_defaults), knots shown. pts/weights
 * are NOT copied here: fill them and pass to cj_vdoc_add_curve, which copies. */
cj_vcurve cj_vcurve_init(cj_vcurve_kind kind, size_t count, const double *pts,
                         const double *weights);

/* The data -> pixel map of a plot drawn with view box (x0, y0)–(x1, y1) into a width × height
 * framebuffer with no axes, title or margin:
 *   s = min(width/(x1-x0), height/(y1-y0)),  px = width/2 + s (x - (x0+x1)/2),
 *   py = height/2 + s (y - (y0+y1)/2). */
typedef struct cj_vview {
    double x0, y0, x1, y1;
    int width, height;
} cj_vview;

void cj_vview_to_px(const cj_vview *v, double x, double y, double out[2]);
void cj_vview_from_px(const cj_vview *v, double px, double py, double out[2]);
/* Pixels per data unit. */
double cj_vview_scale(const cj_vview *v);
/* Fits the view to the control points of every curve with `border` (fraction of the larger
 * side) around them, keeping the size; an empty document gets [-1, 1]². */
typedef struct cj_vdoc cj_vdoc;
void cj_vview_fit(cj_vview *v, const cj_vdoc *doc, double border);

cj_status cj_vdoc_create(cj_vdoc **out);
void cj_vdoc_destroy(cj_vdoc *doc); /* NULL allowed */

size_t cj_vdoc_curve_count(const cj_vdoc *doc);
const cj_vcurve *cj_vdoc_curve(const cj_vdoc *doc, size_t i);

/* ---- edits (each one command of the log) ---------------------------------------------- */

/* Appends a copy of c (validated: finite points, counts, weights > 0, degree range). */
cj_status cj_vdoc_add_curve(cj_vdoc *doc, const cj_vcurve *c);
/* Removes curve ci. */
cj_status cj_vdoc_remove_curve(cj_vdoc *doc, size_t ci);
/* Moves point i of curve ci to (x, y). Consecutive moves of the same point while a drag is
 * open (cj_vdoc_begin_drag .. cj_vdoc_end_drag) are one command. */
cj_status cj_vdoc_move_point(cj_vdoc *doc, size_t ci, size_t i, double x, double y);
void cj_vdoc_begin_drag(cj_vdoc *doc);
void cj_vdoc_end_drag(cj_vdoc *doc);
/* Sets the weight of point i of a rational curve (w > 0, finite). */
cj_status cj_vdoc_set_weight(cj_vdoc *doc, size_t ci, size_t i, double w);
/* Inserts a point before index i (i = count appends) at (x, y), weight 1 for rational
 * curves. The curve's degree grows by one (Bézier) or it passes through one more point. */
cj_status cj_vdoc_insert_point(cj_vdoc *doc, size_t ci, size_t i, double x, double y);
/* Deletes point i (a Bézier keeps at least 1 point, a spline at least 2). */
cj_status cj_vdoc_delete_point(cj_vdoc *doc, size_t ci, size_t i);
/* Degree elevation by one (cj_bezier_elevate; rational curves in homogeneous form): the same
 * curve with one more control point. Splines: CJ_ERR_ARGUMENT. */
cj_status cj_vdoc_elevate(cj_vdoc *doc, size_t ci);
/* Splits a Bézier / rational curve at t in [0, 1] (cj_bezier_split / cj_rbezier_split): curve
 * ci becomes the piece on [0, t] and the piece on [t, 1] is inserted after it with the same
 * style. Splines: CJ_ERR_ARGUMENT. */
cj_status cj_vdoc_split(cj_vdoc *doc, size_t ci, double t);

/* Sets the plot style of curve ci (colour, width, control polygon/points, hull, normals, knots,
 * frames) to style's; the points stay. */
cj_status cj_vdoc_set_style(cj_vdoc *doc, size_t ci, const cj_vcurve *style);

/* Undo / redo one command; CJ_ERR_EMPTY when there is none. */
cj_status cj_vdoc_undo(cj_vdoc *doc);
cj_status cj_vdoc_redo(cj_vdoc *doc);
size_t cj_vdoc_undo_depth(const cj_vdoc *doc);
/* Forgets every command (the current curves stay). */
void cj_vdoc_clear_log(cj_vdoc *doc);
size_t cj_vdoc_redo_depth(const cj_vdoc *doc);

/* ---- picking ---------------------------------------------------------------------------- */

/* The control point nearest to the pixel position (px, py) within `radius` pixels, by the
 * squared distance between (px, py) and the point's pixel position (cj_vview_to_px), compared
 * EXACTLY (error-free products and sums: no rounding decides between two points); ties go to
 * the lowest curve index, then the lowest point index. Returns 1 and sets *ci, *pi, or 0 when
 * no point is within the radius. */
int cj_vdoc_pick(const cj_vdoc *doc, const cj_vview *v, double px, double py, double radius,
                 size_t *ci, size_t *pi);

/* Exact comparison of ax² + ay² with bx² + by² (-1, 0, +1), for finite doubles. */
int cj_vpick_compare(double ax, double ay, double bx, double by);

/* ---- files ------------------------------------------------------------------------------ */

/* Display state saved with the document (so the plot file shows what the viewer showed). */
typedef struct cj_vdoc_display {
    cj_rgba background;
    long curve;       /* the curve the parameter t is shown on, or -1 */
    double t;         /* in [0, 1] */
    int construction; /* draw its de Casteljau construction at t (plot construction_t) */
    int frame;        /* draw its tangent and normal at t (one more plot frames_t entry) */
} cj_vdoc_display;

/* Writes the document as a plot JSON file (the format of `casteljau plot`) through the format's
 * one writer (formats/, plot_json_write_page): width, height, background, "axes": false,
 * "margin": 0, the view, and one item per curve ("bezier" with weights for rational curves,
 * "catmull-rom"), every number in the shortest form that reads back bit-identical, printed by
 * cJSON. Atomic: a temporary file beside `path`, flushed, synced and renamed; on failure an
 * existing file is kept. CJ_ERR_IO naming the path, CJ_ERR_NOMEM. Kochanek–Bartels splines have
 * no plot JSON form: CJ_ERR_UNSUPPORTED. */
cj_status cj_vdoc_save_json(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                            const char *path);

/* Reads a plot JSON file of one plot (no "panels") whose items are "bezier" or "catmull-rom"
 * through the format's one reader (formats/, plot_json_read_page: the checks and messages of
 * `casteljau plot`; rational weights scaled so the largest is in [1, 2)) into a new document
 * (empty log), its view (the file's "view", else fitted with a 10 % border; width/height from
 * the file, else 800 × 600) and display state. CJ_ERR_IO (cannot read), CJ_ERR_PARSE (syntax, a
 * missing, unknown or ill-typed field, a value out of range, an item kind the editor cannot
 * edit), CJ_ERR_RANGE / CJ_ERR_NONFINITE (values the document refuses), CJ_ERR_NOMEM; messages
 * name the file and the JSON path. */
cj_status cj_vdoc_load_json(const char *path, cj_vdoc **out, cj_vview *v, cj_vdoc_display *disp);

/* Builds the plot the viewer shows (and `casteljau plot` draws from the saved file). */
cj_status cj_vdoc_build_plot(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                             cj_plot **out);

#ifdef __cplusplus
}
#endif
#endif
