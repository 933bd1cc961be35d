/* casteljau: VTK adapter — our Bézier curves as VTK Bézier cells (export to .vtu, and VTK's own
 * evaluation of them as an independent cross-check), plus VTK's Kochanek spline.
 *
 * Built only with CJ_WITH_VTK (VTK 9.1 from Debian's libvtk9-dev); C API in front, C++ inside.
 *
 * Cell layout. A curve of degree n becomes one VTK_BEZIER_CURVE cell with n+1 points in VTK's
 * node order: the two end points first, then the interior points in order, i.e. VTK point k of
 * the cell is our control point b_0, b_n, b_1, ..., b_{n-1} for k = 0, 1, 2, ..., n. Points are
 * 3D in VTK: curves of dimension 1 or 2 are padded with zero coordinates (dimension above 3 is
 * CJ_ERR_DIMENSION). Cell data "HigherOrderDegrees" (3 components: n, 0, 0) is set as the
 * grid's higher-order-degrees attribute; rational curves add point data "RationalWeights" (set
 * as the rational-weights attribute; polynomial curves in the same grid get weight 1).
 *
 * Files are written with vtkXMLUnstructuredGridWriter (binary, appended, uncompressed, so that
 * doubles round-trip exactly) to "<path>.tmp" first and renamed over path only on success: a
 * failed write leaves no partial file. Failures are CJ_ERR_IO naming the path.
 */
#ifndef CASTELJAU_VTK_EXPORT_H
#define CASTELJAU_VTK_EXPORT_H

#include "casteljau/bezier.h"
#include "casteljau/rational.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes ncurves polynomial curves, then nrcurves rational curves (either list may be empty,
 * not both: CJ_ERR_EMPTY), one cell each in that order, to the .vtu file at path. Each curve is
 * validated (cj_bezier_check / cj_rbezier_check; dimension <= 3). */
cj_status cj_vtk_write_curves(const char *path, const cj_bezier *curves, size_t ncurves,
                              const cj_rbezier *rcurves, size_t nrcurves);

/* Reads a .vtu file of VTK_BEZIER_CURVE cells back (count-then-fill). For each cell, in file
 * order: degrees[cell] = n, and its n+1 control points (3 coordinates each) in OUR order
 * (b_0..b_n, converted back from VTK's node order) appended to pts3; weights (may be NULL)
 * receives one weight per control point (1 when the file has no RationalWeights array).
 * *ncells and *npts (total control points) are always written when the file was read; if
 * cap_cells or cap_pts is too small, nothing else is written and CJ_ERR_BUFFER is returned, so
 * a first call with capacities 0 asks for the sizes. *rational (may be NULL) is 1 if the file
 * carries rational weights. A cell of another type is CJ_ERR_UNSUPPORTED; an unreadable file
 * CJ_ERR_IO. */
cj_status cj_vtk_read_curves(const char *path, int *degrees, size_t cap_cells, double *pts3,
                             double *weights, size_t cap_pts, size_t *ncells, size_t *npts,
                             int *rational);

/* VTK's evaluation of our curve: builds the same one-cell grid as the writer and evaluates the
 * cell with vtkBezierCurve::EvaluateLocation at the parametric coordinates ts[nt] (each in
 * [0,1], CJ_ERR_RANGE otherwise); out receives nt points of 3 coordinates. */
cj_status cj_vtk_eval_bezier(const cj_bezier *c, const double *ts, size_t nt, double *out3);
cj_status cj_vtk_eval_rbezier(const cj_rbezier *c, const double *ts, size_t nt, double *out3);

/* VTK's Kochanek–Bartels spline (vtkKochanekSpline, one per coordinate) through pts[npts*dim]
 * (dim 1..3, npts >= 2) at parameters t_j = j (parameterised by index, not by length) with the
 * given default tension, continuity and bias. Open splines use end constraint type 1 (first
 * derivative prescribed) with the values of our end tangents, (1 − T)/2 (p_1 − p_0) and
 * (1 − T)/2 (p_{N−1} − p_{N−2}) per coordinate, so the ends match cj_catmull_rom's Kochanek–
 * Bartels kind; closed splines use VTK's periodic mode. Evaluated at ts[nt] (global parameter
 * in [0, npts−1], or [0, npts] when closed); out receives nt*dim values. */
cj_status cj_vtk_kochanek_eval(const double *pts, size_t npts, int dim, double tension,
                               double continuity, double bias, int closed, const double *ts,
                               size_t nt, double *out);

#ifdef __cplusplus
}
#endif
#endif
