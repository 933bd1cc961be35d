/* casteljau: VTK adapter for tensor-product Bézier patches — export to .vtu as
 * VTK_BEZIER_QUADRILATERAL cells, and VTK's own evaluation of those cells as an independent
 * cross-check of cj_patch_eval.
 *
 * Built only with CJ_WITH_VTK (VTK 9.1); C API in front, C++ inside.
 *
 * Cell layout. A patch of degree (m, n), m, n >= 1 (VTK has no degree-0 direction:
 * CJ_ERR_DEGREE), becomes one cell of (m+1)(n+1) points in VTK's node order for higher-order
 * quadrilaterals: the corners (0,0), (m,0), (m,n), (0,n); then the edge points without corners:
 * j = 0 for i = 1..m-1, i = m for j = 1..n-1, j = n for i = 1..m-1, i = 0 for j = 1..n-1 (each
 * edge in increasing i or j); then the interior points, i fastest (i = 1..m-1, j = 1..n-1).
 * Our control point b_ij (index j*(m+1)+i, patch.h) goes to that position; VTK's parametric
 * coordinates (r, s) are our (u, v). Cell data "HigherOrderDegrees" holds (m, n, 0); point data
 * "RationalWeights" is written when any patch is rational (weight 1 for polynomial ones).
 *
 * Files are written with vtkXMLUnstructuredGridWriter (binary, appended, uncompressed, doubles
 * round-trip exactly) to "<path>.tmp", renamed over path only on success. Failures are CJ_ERR_IO
 * naming the path.
 */
#ifndef CASTELJAU_VTK_PATCHES_H
#define CASTELJAU_VTK_PATCHES_H

#include "casteljau/patch.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Position of control point (i, j) of a degree (m, n) patch in the VTK cell's point list (the
 * order described above). No validation. */
int cj_vtk_quad_node(int m, int n, int i, int j);

/* CJ_OK if cj_vtk_quad_node agrees with VTK's own vtkHigherOrderQuadrilateral::
 * PointIndexFromIJK for every (i, j) of degree (m, n); CJ_ERR_UNSUPPORTED naming the first
 * disagreement otherwise. */
cj_status cj_vtk_quad_node_check(int m, int n);

/* Writes the patches, one VTK_BEZIER_QUADRILATERAL cell each, to the .vtu file at path.
 * CJ_ERR_EMPTY for count == 0; each patch is validated (cj_patch_check, degrees >= 1). */
cj_status cj_vtk_write_patches(const char *path, const cj_patch *patches, size_t count);

/* Number of cells and the degrees of the first cell of a .vtu file of Bézier quadrilaterals
 * (a minimal read-back check; degrees may be NULL). CJ_ERR_IO if unreadable. */
cj_status cj_vtk_read_patch_count(const char *path, size_t *ncells, int degrees[2]);

/* VTK's evaluation of our patch: builds the same one-cell grid as the writer and evaluates the
 * cell with vtkBezierQuadrilateral::EvaluateLocation at the parametric points
 * (uv[2k], uv[2k+1]) (each in [0,1], CJ_ERR_RANGE otherwise); out3 receives n points. */
cj_status cj_vtk_eval_patch(const cj_patch *p, const double *uv, size_t n, double *out3);

#ifdef __cplusplus
}
#endif
#endif
