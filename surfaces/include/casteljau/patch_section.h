/* casteljau: the section of a Bézier patch (polynomial or rational) by a plane, as polylines
 * with a proven deviation.
 *
 * The plane is n . x = d (n need not be unit). On the patch, f(u,v) = n . S(u,v) - d has the
 * sign of the scalar tensor-product Bézier polynomial with coefficients
 *     F_ij = w_ij (n . b_ij - d)            (w_ij = 1 for a polynomial patch),
 * because S = P/W with W > 0. The parameter square is split by exact halvings (the longer
 * side in space first) into cells whose F coefficients and homogeneous control points carry
 * a tracked bound on their rounding. A cell whose F coefficients all have one proven sign
 * holds no point of the section and is dropped. A cell is a leaf once the box of its control
 * points (every point of the sub-patch lies in it) has a diagonal <= tol. In a leaf, f is
 * evaluated at the four corners (one deterministic evaluation of the whole patch, so that
 * neighbouring cells agree on a shared corner; f >= 0 counts as +), each edge whose corners
 * differ in sign is bisected to the double where f changes sign, and the crossings are
 * joined by marching squares (a cell with four crossings, a saddle, is paired by the sign of
 * f at its centre and counted in `ambiguous`: a branch point of the section, where the plane
 * is tangent to the surface, or two sheets closer than the cell). Segments are chained into
 * polylines through their shared crossings; a chain that returns to its start is closed.
 *
 * WHAT IS PROVEN. Every point of the true section lies in some leaf; both it and the segments
 * of that leaf lie in the box of the leaf's control points, so every point of the section is
 * within `deviation` (the largest leaf diagonal, <= tol unless a cell hit the depth limit)
 * of a segment, and every segment point within `deviation` of a crossing on its cell's edges.
 * A leaf whose coefficients change sign but whose corners do not (a loop or a touching point
 * smaller than the cell, or nothing: the coefficient test is not exact) yields no segment; its
 * centre point is listed in `unresolved` instead, so nothing is ever silently missed. The
 * crossings are where f changes sign in double precision along an edge: `plane_gap` reports
 * the largest |n . S - d| / |n| measured at them (a few units of rounding of the patch's size).
 *
 * Output (owned by the result, released by cj_patch_section_free): `pts` holds `npts` points
 * (x y z) and `uv` their parameters; polyline k is points starts[k] .. starts[k+1]-1 (starts has
 * nlines+1 entries) and closed[k] says whether it closes (its last point joins the first; the
 * first point is not repeated).
 *
 * Errors: the patch as cj_patch_check; degree above CJ_PATCH_SECTION_MAX_DEGREE:
 * CJ_ERR_DEGREE; a NaN/Inf in n or d: CJ_ERR_NONFINITE; n = 0: CJ_ERR_DEGENERATE; tol not
 * finite, <= 0 or below 2^-36 times the patch's size: CJ_ERR_ARGUMENT naming tol; no memory:
 * CJ_ERR_NOMEM; more than CJ_PATCH_SECTION_MAX_CELLS leaves: CJ_ERR_CAP (nothing written).
 */
#ifndef CASTELJAU_PATCH_SECTION_H
#define CASTELJAU_PATCH_SECTION_H

#include "casteljau/patch.h"
#include "casteljau/status.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CJ_PATCH_SECTION_MAX_DEGREE 15
#define CJ_PATCH_SECTION_MAX_CELLS  4000000L

typedef struct cj_patch_section {
    double *pts;           /* npts points, x y z */
    double *uv;            /* npts parameter pairs */
    int *starts;           /* nlines + 1 offsets into the points */
    unsigned char *closed; /* nlines flags */
    int npts, nlines;
    double *unresolved; /* nunresolved points (x y z): leaves that may hold a tiny piece */
    int nunresolved;
    int ambiguous;    /* saddle leaves (four crossings), paired by the centre's sign */
    long cells;       /* cells examined (the work done) */
    double deviation; /* proven: see above */
    double plane_gap; /* measured: largest distance of a crossing to the plane */
} cj_patch_section;

cj_status cj_patch_section_plane(const cj_patch *p, const double n[3], double d, double tol,
                                 cj_patch_section *out);

/* Releases what cj_patch_section_plane allocated and zeroes the result (NULL is fine). */
void cj_patch_section_free(cj_patch_section *s);

/* The section of a MODEL (count patches, e.g. the teapot or a B-spline surface's Bézier
 * patches) by the plane n . x = d, as chains of cubic Bézier pieces joined across the patches.
 *
 * Each patch is cut by cj_patch_section_plane at tol / 4. The open polylines end on patch
 * edges; two ends of different polylines (or of one) within join_eps = tol / 256 of each other
 * are the same point of the section seen from two patches sharing an edge, and are joined,
 * closest pairs first; the joined point is one point, bit for bit, in both chains' data.
 * A chain that comes back to its first end is closed. Every polyline of a patch between two
 * joins (a "run") is fitted by cubic Bézier pieces: end points at polyline vertices (which lie on
 * the section to rounding), end tangents along n x N (N the surface normal at the vertex),
 * tangent lengths by least squares on the chord-length parameters of the vertices between,
 * halving the vertex range until the piece is within the allowed error. Consecutive pieces share
 * their end point bit for bit (also across patch edges and where a closed chain closes).
 *
 * WHAT IS PROVEN: deviation bounds the distance between the cubic pieces and the true section,
 * both ways. Per piece, with e_v the largest distance from a vertex of its range to the cubic
 * (at an evaluated point of the cubic, so an upper bound) and e_s the largest distance of S
 * samples of the cubic to the polyline of its range, plus 3L/(2S) (L the largest control
 * polygon leg: the cubic moves at most that far between samples), the piece's bound is
 * poly_deviation + max(e_v, e_s) (every point of the section is within poly_deviation of a
 * vertex of its cell, and every polyline point within poly_deviation of the section). The bound
 * is <= tol unless a range of one segment still misses it (then it is a straight piece and the
 * bound says how far it is). An unresolved cell whose centre lies within tol - poly_deviation of a
 * piece is covered by the pieces (its section points are within poly_deviation of its centre): it
 * is dropped and the deviation raised to cover it, still <= tol (a plane holding a patch edge: the
 * patch on one side finds the edge as a polyline, the one on the other side only such cells).
 * Rounding in the distance evaluations (~1e-16 of the size) is added as 2^-44 times the model's
 * size.
 *
 * Output (owned, released by cj_section_curves_free): piece k has control points
 * ctrl[12k .. 12k+11] (4 points x y z); chain c is pieces piece_starts[c] .. piece_starts[c+1]-1
 * and polyline vertices pt_starts[c] .. pt_starts[c+1]-1 of pts (joined; a closed chain's first
 * point is not repeated); closed[c] flags a closed chain. unresolved as cj_patch_section (points
 * of all patches); ambiguous and cells summed; plane_gap the largest over the patches;
 * join_gap the largest distance between two joined ends before they were made one.
 *
 * Errors: as cj_patch_section_plane for each patch (the message names the patch index); count
 * = 0: CJ_ERR_ARGUMENT; no memory: CJ_ERR_NOMEM (nothing written). */
typedef struct cj_section_curves {
    double *ctrl; /* npieces x 4 points x 3 */
    int *piece_starts;
    double *pts; /* npts polyline vertices x 3, chains joined */
    int *pt_starts;
    unsigned char *closed;
    int npieces, nchains, npts;
    double *unresolved;
    int nunresolved;
    int ambiguous, joins;
    long cells;
    double deviation;      /* proven: cubic pieces vs the true section, both ways */
    double poly_deviation; /* proven: polylines vs the true section (largest over the patches) */
    double join_gap;       /* largest distance between two ends joined into one point */
    double plane_gap;      /* measured: largest distance of a vertex to the plane */
} cj_section_curves;

cj_status cj_patches_section_curves(const cj_patch *patches, size_t count, const double n[3],
                                    double d, double tol, cj_section_curves *out);

/* Releases what cj_patches_section_curves allocated and zeroes it (NULL is fine). */
void cj_section_curves_free(cj_section_curves *s);

#ifdef __cplusplus
}
#endif
#endif
