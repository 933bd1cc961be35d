/* casteljau: tessellation of Bézier patches (uniform and adaptive to a tolerance, watertight)
 * and of parametric surfaces, into a cj_mesh.
 *
 * PATCHES. Each patch becomes a triangulation of its parameter square whose vertices lie on
 * the surface; triangle orientation is counter-clockwise in (u,v), hence counter-clockwise
 * seen from the side S_u x S_v points to. Per patch:
 *  - every boundary edge gets k_e segments (K in uniform mode; adaptive: see below), the
 *    SAME count on every patch sharing that edge, and its points are evaluated from the
 *    edge's own control points in one canonical direction (the lexicographically smaller of
 *    the control sequence and its reverse; corners are the control points themselves): the
 *    j-th point is the edge curve at j/k_e, a function of the edge curve and k_e only. Two
 *    patches sharing an edge (same control points, either direction) therefore produce
 *    bit-identical vertices along it: no cracks. A collapsed edge (all control points
 *    identical) maps every one of its vertices to that point exactly; its count follows the
 *    interior (it cannot crack) and the triangles that degenerate there (two vertices at the
 *    same position) are dropped.
 *  - the interior is a tensor grid of nu x nv cells; where edge counts differ from the grid,
 *    the outer ring of cells is replaced by a zipper strip between the edge points and the
 *    first inner grid row/column.
 *
 * PROVEN BOUND. For a triangle T with vertex parameters p_i and barycentric λ_i, the linear
 * interpolant L satisfies S(x) - L(x) = -Σ λ_i R_i with R_i the Taylor remainder of S from x
 * to p_i, so |S(x) - L(x)| <= ½ Σ λ_i Q(p_i - x), Q(h,k) = Muu h² + 2 Muv |h||k| + Mvv k²,
 * where Muu >= |S_uu|, Muv >= |S_uv|, Mvv >= |S_vv| on the region. Since Σλ_i(u_i-u)² <= du²/4
 * (du = the triangle's extent in u) and likewise in v (Cauchy-Schwarz for the mixed term):
 *     |S(x) - L(x)| <= (Muu du² + 2 Muv du dv + Mvv dv²) / 8.
 * The M's come from the control net over the triangle's grid cell (or, zipper triangles, over
 * the pieces of its own (u,v) box between consecutive side and grid parameters), by the convex
 * hull property of the derivative patches:
 *     Muu = m(m-1) max |Δ²_u b_ij|,  Muv = m n max |Δ_u Δ_v b_ij|,  Mvv = n(n-1) max |Δ²_v b_ij|,
 * over the box's sub-net in the patch's parameters; computed as the restrictions to the box of
 * the whole net's difference nets (differencing commutes with restriction; see
 * tess_bounds_poly.c and docs/tessellation.md), inflated for the rounding of the differences
 * and restrictions, plus the rounding error of evaluating the vertices (gamma(3(m+n)+4)
 * max|b|, twice). Since S(x) lies
 * within that distance of the point L(x) of the mesh, it bounds the distance surface -> mesh.
 * RATIONAL PATCHES. S = X / w with X (3D) and w > 0 the polynomial patches of the homogeneous
 * net (w_ij b_ij, w_ij). Each triangle's bound is the smaller of two proven bounds, each on the
 * distance from S(x) to a point of the mesh triangle (hence, like the polynomial bound, on the
 * distance surface -> mesh, and mesh -> surface since x -> that point maps the parameter
 * triangle onto the mesh triangle). B is the triangle's grid cell or (u,v) box; wlo, whi the
 * smallest and largest weight of B's sub-net (w lies between them on B: Bernstein
 * coefficients); the M's come from second differences of sub-nets over B as above.
 *  (L) |S - L| with L the mesh's linear interpolant: S - L = F / w with F = X - w L, a
 *      polynomial patch of degree (m+1, n+1) (L in bilinear Bernstein form, multiplied into w's
 *      net) that vanishes at the triangle's vertices up to rounding, so
 *          |S - L| <= [ (Fuu du^2 + 2 Fuv du dv + Fvv dv^2)/8 + whi (vertex error + e) ] / wlo + e,
 *      e bounding the residual of the computed affine L at the vertices. F's second
 *      derivatives are w S_uu + 2 w_u (S_u - L_u) + w_uu (S - L) (etc.): as tight as the
 *      polynomial bound (exact for a cylinder's straight direction).
 *  (Q) |S - Q| with Q(x) = Σ λ_i w_i V_i / Σ λ_i w_i (the homogeneous linear interpolant,
 *      projected; a point of the triangle): for any point c, with Y = X - c w (net
 *      w_ij (b_ij - c)), S - Q = [(Y - Yl) - (Q - c)(w - wl)] / w (Yl, wl the linear
 *      interpolants), so |S - Q| <= [(Y and w interpolation bounds) with M = (M_Y + R M_w)] / wlo,
 *      c the centre of the box of B's Euclidean sub-net points b'_ij, R = max |b'_ij - c|
 *      >= |Q - c|. Exact for a rational-linear parametrisation (e.g. a segment with unequal
 *      weights), where (L) pays for the uneven speed.
 * Both add the rounding of the sub-nets, of F or Y, and of the vertices (derivation and
 * rounding terms in tessellate.c, rational_tri_bound). On exact sphere and torus patches the
 * measured deviation is 0.6-0.76 of the bound, on a quarter cylinder 0.9-0.99. Adaptive and
 * uniform modes both use it; the adaptive grid densities of a rational patch come from |S_uu|,
 * |S_uv|, |S_vv| sampled on 16 x 16 cells (and the (Q) M's of those cells, whichever is smaller).
 * Scaling every weight by a constant changes neither the surface nor the bound (up to rounding).
 * ADAPTIVE CHOICE. Interior: a tensor grid of nu x nv cells whose lines equidistribute the
 * density sqrt(max(Muu, Muv)) along u (sqrt(max(Mvv, Muv)) along v), the bounds taken on 16
 * slabs per direction (1D-optimal spacing for a second-order error); nu and nv scale together,
 * and the scale is the smallest (predicted from the bound's 1/s^2 law, then bracketed to 3%)
 * for which the per-triangle bound above is <= tol. Uniform K x K grids with fewer triangles
 * are then tried (smallest passing K by bisection) and the grid with the fewest triangles wins.
 * Polynomial patches try grids BOUNDS-ONLY (the triangles enumerated and bounded, no vertex
 * evaluated, nothing added to the mesh; report->trials) and build only the grid kept, once,
 * with the bound its trial computed; rational patches try grids by building them (their bound
 * needs the vertices). report->builds counts the meshes built.
 * Edge counts, in two passes over all patches. (1) Planning: each patch runs the search above
 * with every non-collapsed side at k = max(k_flat, grid count along that side), where k_flat
 * is the smallest k with d(d-1) max|Δ²b| / (8 k²) <= tol/4 (the chord error bound of the edge
 * curve); so a side has at least as many segments as the grid has cells along it (a straight
 * edge across which the patch twists would otherwise get 1 segment and long zipper slivers
 * whose twist term forces the whole interior finer). Each patch requests the counts of its
 * winning build. (2) Every edge shared by several patches (bit-identical control points,
 * either direction) gets the largest count requested for it; each patch is then built with
 * those counts, trying its planned grid first (it passes unless a neighbour raised a count
 * and the new zipper misses tol, in which case the search reruns with the counts fixed, which
 * succeeds on a fine enough grid since k >= k_flat). The bound is always that of the build
 * kept. Planning and building one patch are functions of that patch (and its four counts) and
 * tol alone: casteljau/tess_cache.h reuses them between calls.
 * UNIFORM MODE: K x K cells and K segments on every edge (seed 5.9), same bound.
 * MEMORY: the mesh grows through its allocator; temporaries (index grids, one per patch build)
 * also come from the mesh's allocator.
 * MEASURED DEVIATION (opt->measure = L > 0): for every triangle, max |S(x) - L(x)| over the
 * barycentric lattice of step 1/L (including dropped triangles), i.e. a sampled value of the
 * quantity the bound bounds; for a rational patch min(|S(x) - L(x)|, |S(x) - Q(x)|) with Q
 * as above (both are points of the mesh triangle; the bound is the smaller of (L) and (Q)).
 */
#ifndef CASTELJAU_TESSELLATE_H
#define CASTELJAU_TESSELLATE_H

#include "casteljau/mesh.h"
#include "casteljau/patch.h"
#include "casteljau/status.h"
#include "casteljau/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Default cap on the segments per direction of one patch. */
#define CJ_TESS_DEFAULT_MAX_SEGMENTS 4096

typedef struct cj_tess_options {
    double tol;       /* adaptive: bound on the distance surface -> mesh, > 0 and finite */
    int uniform;      /* > 0: uniform K x K segments per patch (seed 5.9); tol is then unused */
    int measure;      /* > 0: measure the deviation on a lattice of step 1/measure per triangle */
    int max_segments; /* cap per direction and patch; 0 = CJ_TESS_DEFAULT_MAX_SEGMENTS */
} cj_tess_options;

typedef struct cj_tess_report {
    size_t triangles;   /* triangles added to the mesh */
    size_t vertices;    /* vertices added */
    size_t dropped;     /* degenerate triangles dropped (collapsed edges) */
    double bound;       /* proven max distance from the patches to the mesh */
    double measured;    /* measured max deviation (-1 when opt->measure == 0) */
    int max_nu, max_nv; /* largest grid used by a patch */
    size_t builds;      /* patch meshes built (planning and final; 1 per patch when planned
                         * bounds meet tol as built: see ADAPTIVE CHOICE) */
    size_t trials;      /* bounds-only trials of grids (no mesh built) */
} cj_tess_report;

/* Tessellates `count` patches into `mesh` (appending; triangle_patch = patch index). Vertices
 * are per patch (each carries its patch's (u,v) and normal); positions along shared edges
 * are bit-identical, so cj_mesh_weld() or the OBJ writer merge them into a watertight mesh.
 * Polynomial and rational patches may be mixed.
 * Status: errors of cj_patch_check (naming the patch), CJ_ERR_ARGUMENT (bad options: tol <= 0
 * in adaptive mode, negative counts), CJ_ERR_NONFINITE (tol), CJ_ERR_CAP (a patch needs more
 * than max_segments per direction: the mesh holds the patches before the first one that
 * failed and report describes them), CJ_ERR_NOMEM. Adaptive mode plans every patch before
 * building any (see ADAPTIVE CHOICE); each trial stops at its first triangle whose bound
 * exceeds tol. A degenerate patch, whose every triangle collapses (all control points equal,
 * a degree-(0,0) patch), is CJ_ERR_DEGENERATE naming it: never an empty mesh called success. */
cj_status cj_tessellate_patches(const cj_patch *patches, size_t count, const cj_tess_options *opt,
                                cj_mesh *mesh, cj_tess_report *report);

/* Predicts, before any work, the number of triangles cj_tessellate_patches will make with
 * `opt` (as a double: it may exceed any integer type). Uniform mode: exactly 2 K^2 per patch.
 * Adaptive mode: the sum over patches of the adaptive search's starting grid (2 nu nv, from
 * the second-derivative densities; cost O(SLABS) sub-net bounds per patch, no mesh built);
 * the mesh finally built had 1.0-1.5x as many triangles in our measurements (teapot at
 * 1e-2..1e-4 of its size: 1.27-1.42x; a stretched bilinear patch 1.0x; a rational patch with
 * one weight 4096.5: 1.49x). Use it to refuse or warn before a run that would exhaust memory.
 * Status: the errors of cj_patch_check (naming the patch), CJ_ERR_ARGUMENT, CJ_ERR_NONFINITE
 * (bad options, as cj_tessellate_patches), CJ_ERR_NOMEM. */
cj_status cj_tessellate_predict(const cj_patch *patches, size_t count, const cj_tess_options *opt,
                                double *triangles);

/* The edge-flatness rule (k_flat above, called with tol/4; adaptive edge counts are at least
 * this): the number of segments (>= 1) for a polynomial edge curve of the given degree
 * (3D control points, degree+1 of them) so that the chord error bound
 * d(d-1) max|Δ²b| / (8 k²) is <= tol. Capped at `cap` (returns cap+1 if more are needed). */
int cj_tess_edge_segments(const double *pts, int degree, double tol, int cap);

/* Uniform grid of a parametric surface (cj_param_surface of surface.h): nu x nv cells over the
 * domain, vertices S(u_i, v_j) with cj_surface_normal normals and (u,v). Closure flags are
 * honoured: a periodic direction reuses its first column/row instead of evaluating the last
 * (so the seam is shared), a collapsed edge becomes a single vertex, and the triangles that
 * degenerate there are dropped (*dropped, may be NULL). Triangles are CCW in (u,v), i.e.
 * outward for the library's closed surfaces. nu, nv >= 1 (>= 3 in a periodic direction).
 * Status: CJ_ERR_ARGUMENT (counts), errors of the surface callbacks, CJ_ERR_NOMEM. */
cj_status cj_tessellate_surface(const cj_param_surface *s, int nu, int nv, int32_t id,
                                cj_mesh *mesh, size_t *dropped);

#ifdef __cplusplus
}
#endif
#endif
