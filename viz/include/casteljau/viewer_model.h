/* casteljau: the editor model of `casteljau view` for 2D curves, usable without a window.
 *
 * A cj_vdoc is a list of 2D curves (Bézier of any degree, rational Bézier, interpolating
 * splines of the Catmull-Rom kinds, B-splines and NURBS of any degree and knot vector) with their
 * plot styles, plus a COMMAND LOG: every edit is recorded with the exact curves it replaced and
 * produced, so undo and redo restore geometry bit for bit. Edits made after an undo drop the undone
 * commands (the usual linear history).
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

#include "casteljau/bspline.h"
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
    CJ_VCURVE_SPLINE,     /* interpolating spline through the points (spline.kind) */
    CJ_VCURVE_BSPLINE     /* B-spline (weights NULL) or NURBS: degree, count + degree + 1 knots */
} cj_vcurve_kind;

/* One curve. Coordinates are point-major (x, y); weights for CJ_VCURVE_RATIONAL, and for a
 * CJ_VCURVE_BSPLINE that is a NURBS. */
typedef struct cj_vcurve {
    cj_vcurve_kind kind;
    size_t count;
    double *pts;         /* 2*count */
    double *weights;     /* count, or NULL */
    int degree;          /* CJ_VCURVE_BSPLINE: the degree p (other kinds: unused) */
    double *knot_vector; /* CJ_VCURVE_BSPLINE: count + degree + 1 knots (bspline.h); else NULL */
    cj_spline_options spline;
    /* plot style (casteljau/plot.h) */
    cj_rgba color;
    double width;
    int control_polygon, control_points, hull, normals;
    int knots; /* knot markers (splines: the points passed through; B-splines: the domain knots) */
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
/* Sets the weight of point i of a rational curve or a B-spline (w > 0, finite); a polynomial
 * B-spline becomes a NURBS with every other weight 1. */
cj_status cj_vdoc_set_weight(cj_vdoc *doc, size_t ci, size_t i, double w);
/* Inserts a point before index i (i = count appends) at (x, y), weight 1 for rational
 * curves. The curve's degree grows by one (Bézier) or it passes through one more point.
 * B-splines: CJ_ERR_ARGUMENT (their knots fix the count: insert a knot instead). */
cj_status cj_vdoc_insert_point(cj_vdoc *doc, size_t ci, size_t i, double x, double y);
/* Deletes point i (a Bézier keeps at least 1 point, a spline at least 2). B-splines:
 * CJ_ERR_ARGUMENT. */
cj_status cj_vdoc_delete_point(cj_vdoc *doc, size_t ci, size_t i);
/* Degree elevation by one (cj_bezier_elevate; rational curves in homogeneous form): the same
 * curve with one more control point. Splines and B-splines: CJ_ERR_ARGUMENT. */
cj_status cj_vdoc_elevate(cj_vdoc *doc, size_t ci);
/* Splits a Bézier / rational curve at t in [0, 1] (cj_bezier_split / cj_rbezier_split): curve
 * ci becomes the piece on [0, t] and the piece on [t, 1] is inserted after it with the same
 * style. Splines and B-splines: CJ_ERR_ARGUMENT. */
cj_status cj_vdoc_split(cj_vdoc *doc, size_t ci, double t);

/* Inserts the knot u once into B-spline curve ci (Boehm, cj_bspline_insert_knot): one more
 * control point, the same curve (up to rounding: the new points are convex combinations of
 * old ones). CJ_ERR_ARGUMENT if the curve is not a B-spline, and what cj_bspline_insert_knot
 * reports (u outside the domain, a multiplicity above the degree). */
cj_status cj_vdoc_insert_knot(cj_vdoc *doc, size_t ci, double u);

/* The B-spline view of a CJ_VCURVE_BSPLINE curve (dimension 2). */
cj_bspline cj_vcurve_bspline(const cj_vcurve *c);

/* The parameter range of the knot spans control point i of a B-spline influences (its basis
 * function's support [u_i, u_{i+p+1}] clipped to the domain): moving the point changes the
 * curve there and nowhere else. CJ_ERR_ARGUMENT if c is not a B-spline or i is out of range. */
cj_status cj_vcurve_support(const cj_vcurve *c, size_t i, double *u0, double *u1);

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

/* ---- queries: snapping and intersections (casteljau/nearest.h, casteljau/intersect.h) ----- */

/* A curve as Bézier pieces: piece j has degree `degree`, control points pts[j*(degree+1)*2 ..]
 * and (rational pieces) weights w[j*(degree+1) ..] (w NULL: polynomial), and covers the
 * curve's own parameter range [breaks[j], breaks[j+1]]: [0, 1] for a Bézier or rational curve
 * (one piece), the knot spans for a B-spline (cj_bspline_to_bezier), [j, j+1] for segment j of
 * a spline. */
typedef struct cj_vpieces {
    int n, degree;
    double *pts, *w, *breaks;
} cj_vpieces;
cj_status cj_vcurve_pieces(const cj_vcurve *c, cj_vpieces *out);
void cj_vpieces_free(cj_vpieces *p);

/* The certified nearest point of the document's curves to a point q (data units). */
typedef struct cj_vsnap {
    long curve;      /* the curve it lies on; -1 when no curve could be queried */
    double u;        /* its parameter on that curve (the curve's own, as cj_vpieces) */
    double point[2]; /* the nearest point found, c(u) rounded to doubles */
    double distance; /* proven upper bound of |c(u) - q| */
    double lower;    /* proven lower bound of the distance from q to every curve queried */
    double on_curve; /* proven upper bound of the distance from `point` to the curve */
    long pieces;     /* work: pieces examined by the branch and bound */
} cj_vsnap;

/* Nearest point of every curve except curve `skip` (-1: none) to q, each Bézier piece through
 * cj_nearest_curve (a global minimum, not a local Newton root): distance - lower <= tol, so no
 * point of those curves is nearer to q than distance - tol. Pieces that are single points (a
 * degenerate piece) are skipped. tol: data units, raised to 2^-39 times the scale when below
 * what doubles resolve. CJ_ERR_EMPTY if no curve could be queried; errors of the queries. */
cj_status cj_vdoc_snap(const cj_vdoc *doc, const double q[2], long skip, double tol, cj_vsnap *out);

/* The same for one curve (out->curve is 0). */
cj_status cj_vcurve_nearest(const cj_vcurve *c, const double q[2], double tol, cj_vsnap *out);

/* One intersection of two different curves of the document (cj_intersect_curves on each pair
 * of their pieces): the point, its kind and the two curves and parameters. */
typedef struct cj_vmark {
    double point[2];
    int kind; /* cj_isect_kind */
    size_t a, b;
    double ua, ub;
} cj_vmark;

/* Every intersection between pieces of different curves, at tolerance tol (data units, as in
 * intersect.h; raised to 2^-39 times the scale when below what doubles resolve). A crossing at
 * the joint of two pieces (at_end) is kept once: one within 4 tol of a mark of the same two
 * curves is dropped. *out (malloc'ed, free() it; NULL when none) and *count. Pairs whose query
 * fails (a degenerate piece, CJ_ERR_CAP) are left out and counted in *failed (may be NULL). */
cj_status cj_vdoc_intersections(const cj_vdoc *doc, double tol, cj_vmark **out, size_t *count,
                                size_t *failed);

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
 * one writer (formats/, cj_plot_json_write_page): width, height, background, "axes": false,
 * "margin": 0, the view, and one item per curve ("bezier" with weights for rational curves,
 * "catmull-rom", "bspline" with its knots, weights and drawing options), every number in the
 * shortest form that reads back bit-identical, printed by cJSON. Atomic: a temporary file beside
 * `path`, flushed, synced and renamed; on failure an existing file is kept. CJ_ERR_IO naming the
 * path, CJ_ERR_NOMEM. Kochanek–Bartels splines have no plot JSON form: CJ_ERR_UNSUPPORTED. */
cj_status cj_vdoc_save_json(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                            const char *path);

/* Reads a plot JSON file of one plot (no "panels") whose items are "bezier", "catmull-rom" or
 * (2D) "bspline" through the format's one reader (formats/, cj_plot_json_read_page: the checks and
 * messages of `casteljau plot`; rational Bézier weights scaled so the largest is in [1, 2),
 * B-spline weights kept as written) into a new document (empty log), its view (the file's
 * "view", else fitted with a 10 % border; width/height from the file, else 800 × 600) and
 * display state. CJ_ERR_IO (cannot read), CJ_ERR_PARSE (syntax, a missing, unknown or ill-typed
 * field, a value out of range, an item kind the editor cannot edit), CJ_ERR_RANGE /
 * CJ_ERR_NONFINITE (values the document refuses), CJ_ERR_NOMEM; messages name the file and the
 * JSON path. */
cj_status cj_vdoc_load_json(const char *path, cj_vdoc **out, cj_vview *v, cj_vdoc_display *disp);

/* Builds the plot the viewer shows (and `casteljau plot` draws from the saved file). */
cj_status cj_vdoc_build_plot(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                             cj_plot **out);

#ifdef __cplusplus
}
#endif
#endif
