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

#ifdef __cplusplus
}
#endif
#endif
