/* casteljau: lines, anti-aliased lines, wide polylines with joins and caps, and curves.
 *
 * Coordinates follow framebuffer.h: pixel (x, y) is the unit square [x, x+1) x [y, y+1) with
 * centre (x + 0.5, y + 0.5), row 0 at the bottom. Lines and polyline strokes come in two forms:
 * one draws into a cj_framebuffer, the other ("_visit") hands each pixel to a callback together
 * with a clip rectangle, so tests and other consumers can collect the exact pixel set (or the
 * coverage) without a framebuffer.
 *
 * 1. Exact lines (Bresenham, integer arithmetic only)
 *
 * The line between integer pixels (x0, y0) and (x1, y1) is the pixel set
 *   - x-major when |dx| >= |dy| (dx = x1 - x0, dy = y1 - y0): for every x between x0 and x1
 *     the pixel (x, Y(x)) with  Y(x) = floor( y0 + (x - x0) dy/dx + 1/2 );
 *   - y-major when |dy| > |dx|: for every y the pixel (X(y), y), X(y) = floor(x0 +
 *     (y - y0) dx/dy + 1/2).
 * TIE RULE: when the exact rational minor coordinate lies exactly halfway between two pixels,
 * the pixel with the LARGER minor coordinate is taken (round half up, towards +infinity). The
 * rule depends only on the exact value on the line, so the pixel set is the same whatever the
 * order of the end points. There is exactly one pixel per step along the major axis (the same
 * brightness whatever the slope), both end points are drawn, and the count is
 * max(|dx|, |dy|) + 1.
 *
 * Clipping happens BEFORE stepping and is exact: the first and last visible major steps are
 * computed with 128-bit integer arithmetic from the formula above, so the pixels drawn are
 * exactly the pixels of the unclipped line that lie in the clip rectangle, and a line from
 * (-1e9, -1e9) to (1e9, 1e9) costs only its visible pixels.
 *
 * Double end points are mapped to the pixel containing them, (floor(x), floor(y)), and then
 * drawn as above. End points must satisfy |coordinate| <= CJ_LINE_COORD_MAX.
 *
 * 2. Anti-aliased thin lines (Xiaolin Wu): one pair of pixels per major step whose coverages
 *    sum to 1 (the fractional end steps are weighted by their overlap). Fast; for plots.
 *
 * 3. Strokes (and the convex/disc fills at the end): a polyline (or a curve flattened to one) drawn
 * with a width, a join (miter/round/bevel) at interior vertices and a cap (butt/round/square) at
 * the two ends. Coverage is the EXACT AREA of (pixel square ∩ stroke), a one-pixel box filter: the
 * stroke is cut into non-overlapping convex pieces (a rectangle per segment, a wedge or circular
 *    sector on the outer side of each join, the caps), the inner overlap of consecutive
 *    rectangles is subtracted, and each piece's area inside each pixel is computed by clipping
 *    it to the pixel square. Round parts are polygons within 0.02 px of the circle with the
 *    exact sector area. So a straight stroke of length L and width w has total coverage L*w
 *    (plus the caps), at any angle and for any w > 0 (thin strokes simply get partial
 *    coverage). Where non-adjacent parts of one polyline overlap (self-intersections, very
 *    short segments at sharp turns) coverage adds up and is clamped at 1.
 *
 * Statuses: CJ_ERR_NONFINITE for a NaN/Inf coordinate, width, tolerance (naming it);
 * CJ_ERR_RANGE for a coordinate beyond CJ_LINE_COORD_MAX, a width <= 0 or above
 * CJ_LINE_MAX_WIDTH, a tolerance <= 0, a miter limit < 1; CJ_ERR_EMPTY for a polyline with no
 * point; CJ_ERR_ARGUMENT for an unknown join/cap; CJ_ERR_NOMEM if the framebuffer's stroke
 * scratch cannot be allocated (once, on the first stroke); CJ_ERR_BUFFER if a visit workspace
 * is too small. Flattening statuses come from flatten.h. Nothing is drawn on failure.
 */
#ifndef CASTELJAU_LINE_H
#define CASTELJAU_LINE_H

#include "casteljau/bezier.h"
#include "casteljau/flatten.h"
#include "casteljau/rational.h"
#include "casteljau/framebuffer.h"
#include "casteljau/status.h"
#include "casteljau/vec.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest |coordinate| of a line end point (2^52: floor() of such a double is exact, and every
 * clipping product fits in 128 bits). */
#define CJ_LINE_COORD_MAX 4503599627370496.0
/* Largest stroke width in pixels. */
#define CJ_LINE_MAX_WIDTH 65536.0
/* Default flattening tolerance for curves, in pixels. */
#define CJ_LINE_DEFAULT_TOL 0.25

/* Inclusive pixel rectangle [x0, x1] x [y0, y1]; empty when x1 < x0 or y1 < y0. */
typedef struct cj_line_rect {
    int x0, y0, x1, y1;
} cj_line_rect;

/* The whole framebuffer as a clip rectangle. */
static inline cj_line_rect cj_line_rect_of(const cj_framebuffer *fb) {
    cj_line_rect r;
    r.x0 = 0;
    r.y0 = 0;
    r.x1 = fb->width - 1;
    r.y1 = fb->height - 1;
    return r;
}

/* Receives one pixel of an exact line, in order from one end to the other. */
typedef void (*cj_line_pixel_fn)(void *user, int x, int y);
/* Receives one pixel with its coverage in (0, 1]. */
typedef void (*cj_line_cover_fn)(void *user, int x, int y, float coverage);

/* ---- exact (Bresenham) lines ------------------------------------------------------------- */

/* Visits the pixels of the line (x0,y0)-(x1,y1) that lie in `clip`, each once, calling fn for
 * each (fn may be NULL to only count). *visited (may be NULL) receives the number of pixels
 * visited. Work is proportional to the visited pixels plus a constant. */
cj_status cj_line_visit(long long x0, long long y0, long long x1, long long y1, cj_line_rect clip,
                        cj_line_pixel_fn fn, void *user, long long *visited);

/* As cj_line_visit for double end points, mapped to pixels by floor(). */
cj_status cj_line_visit_d(double x0, double y0, double x1, double y1, cj_line_rect clip,
                          cj_line_pixel_fn fn, void *user, long long *visited);

/* Draws the exact line into fb with colour c (stored when c.a == 255, else blended
 * source-over). Inner loop: pointer stepping, no per-pixel bounds checks. */
cj_status cj_line_draw(cj_framebuffer *fb, long long x0, long long y0, long long x1, long long y1,
                       cj_rgba c);
cj_status cj_line_draw_d(cj_framebuffer *fb, double x0, double y0, double x1, double y1, cj_rgba c);

/* ---- anti-aliased thin lines (Wu) --------------------------------------------------------- */

/* Visits the Wu pixels of the segment between the points (x0,y0) and (x1,y1) (continuous
 * coordinates, pixel centres at +0.5) that lie in clip. The output does not depend on the order
 * of the end points. Coverages: per major step the two pixels straddling the line get 1 - f and
 * f (f the fractional distance), times the overlap of the step with the segment at the ends. */
cj_status cj_line_aa_visit(double x0, double y0, double x1, double y1, cj_line_rect clip,
                           cj_line_cover_fn fn, void *user);
cj_status cj_line_draw_aa(cj_framebuffer *fb, double x0, double y0, double x1, double y1,
                          cj_rgba c);

/* ---- strokes ------------------------------------------------------------------------------ */

typedef enum cj_line_join {
    CJ_JOIN_MITER = 0, /* sharp corner, bevelled when longer than miter_limit * width / 2 */
    CJ_JOIN_ROUND,     /* disc of radius width/2 at the vertex */
    CJ_JOIN_BEVEL      /* corner cut straight */
} cj_line_join;

typedef enum cj_line_cap {
    CJ_CAP_BUTT = 0, /* ends exactly at the end point */
    CJ_CAP_ROUND,    /* half disc of radius width/2 */
    CJ_CAP_SQUARE    /* extended by width/2 */
} cj_line_cap;

typedef struct cj_line_stroke {
    double width; /* > 0, <= CJ_LINE_MAX_WIDTH, in pixels */
    cj_line_join join;
    cj_line_cap cap;
    double miter_limit; /* >= 1: max ratio (miter length)/(width/2) = 1/sin(angle/2), as SVG */
} cj_line_stroke;

/* width, round joins, round caps, miter limit 4. */
static inline cj_line_stroke cj_line_stroke_defaults(double width) {
    cj_line_stroke s;
    s.width = width;
    s.join = CJ_JOIN_ROUND;
    s.cap = CJ_CAP_ROUND;
    s.miter_limit = 4.0;
    return s;
}

/* Strokes the polyline pts[0..n-1] (closed: also the segment back to pts[0], with joins
 * everywhere and no caps) with colour c, blending round(c.a * coverage) source-over.
 * Consecutive equal points are skipped; a polyline whose points are all equal draws a dot
 * (round: disc, square: square, butt: nothing). The first call allocates the framebuffer's
 * stroke scratch (one float and two ints per row/pixel); later calls allocate nothing. */
cj_status cj_line_stroke_polyline(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, int closed,
                                  const cj_line_stroke *style, cj_rgba c);

/* Bytes of workspace cj_line_stroke_polyline_visit needs for clip (0 for an empty clip). */
size_t cj_line_stroke_work_size(cj_line_rect clip);

/* As cj_line_stroke_polyline, but each covered pixel of clip goes to fn (row by row, from
 * the bottom). work: work_bytes >= cj_line_stroke_work_size(clip) bytes, suitably aligned
 * (from malloc), contents on entry ignored; CJ_ERR_BUFFER if too small. */
cj_status cj_line_stroke_polyline_visit(const cj_vec2 *pts, size_t n, int closed,
                                        const cj_line_stroke *style, cj_line_rect clip, void *work,
                                        size_t work_bytes, cj_line_cover_fn fn, void *user);

/* Strokes a 2D Bézier curve (c->dim must be 2, else CJ_ERR_DIMENSION) flattened at tolerance
 * tol pixels (CJ_LINE_DEFAULT_TOL is a good choice) with the near-optimal method of
 * flatten.h. The flattener's vertices stream straight into the stroker (joins between all
 * consecutive segments, caps at the two ends), so any length works without allocation.
 * Flattening statuses (CJ_ERR_CAP, CJ_ERR_RANGE for tol, ...) are passed on and nothing is drawn
 * then. *bound (may be NULL) receives the proven distance bound between the curve and the
 * stroked polyline (<= tol). */
cj_status cj_line_stroke_bezier(cj_framebuffer *fb, const cj_bezier *curve, double tol,
                                const cj_line_stroke *style, cj_rgba c, double *bound);

/* As cj_line_stroke_bezier for a rational 2D curve (rational.h; weights > 0). */
cj_status cj_line_stroke_rbezier(cj_framebuffer *fb, const cj_rbezier *curve, double tol,
                                 const cj_line_stroke *style, cj_rgba c, double *bound);

/* Strokes a sequence of 2D pieces (a spline or interpolant as flatten.h's cj_flatten_piece,
 * polynomial or rational) as ONE polyline, with joins between pieces; see
 * cj_flatten_sequence for how pieces that do not meet are connected. */
cj_status cj_line_stroke_sequence(cj_framebuffer *fb, const cj_flatten_piece *pieces, size_t count,
                                  double tol, const cj_line_stroke *style, cj_rgba c,
                                  double *bound);

/* ---- filled shapes (same exact-area coverage as strokes) -------------------------------- */

/* Fills the convex polygon pts[0..n-1] (either orientation; collinear points allowed) with
 * colour c, coverage = exact area of (pixel ∩ polygon). CJ_ERR_EMPTY if n < 3,
 * CJ_ERR_NONFINITE / CJ_ERR_RANGE for a bad point, CJ_ERR_ARGUMENT if the polygon is not convex
 * (naming the vertex where the turn changes sign). A polygon of zero area draws nothing. */
cj_status cj_line_fill_convex(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, cj_rgba c);

/* Fills the disc of the given centre and radius (> 0) with exact-area coverage (the circle is a
 * polygon within 0.02 px with the exact area). */
cj_status cj_line_fill_disc(cj_framebuffer *fb, cj_vec2 centre, double radius, cj_rgba c);

#ifdef __cplusplus
}
#endif
#endif
