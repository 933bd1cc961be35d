/* Private: the wide-curve view of a B-spline surface shared by bspline_surface.c and
 * bspline_surface_ops.c. */
#ifndef CASTELJAU_BSPLINE_SURFACE_INTERNAL_H
#define CASTELJAU_BSPLINE_SURFACE_INTERNAL_H

#include "bspline_internal.h"
#include "casteljau/bspline_surface.h"

/* Number of non-empty spans of the domain of a knot vector. */
int cj_bsurf_spans(const double *knots, int npts, int p);

/* The surface as a wide polynomial curve in direction dir (0: u, 1: v): point a along dir holds
 * the homogeneous points (3 or 4 coordinates) of its whole row/column, in order of the other
 * index; room for extra more points. CJ_ERR_NOMEM on failure. */
cj_status cj_bsurf_wide(const cj_bspline_surface *s, int dir, cj_bsp_h *w, int extra);

/* Writes wide homogeneous points back (point a along dir, b across) to the cj_patch-like layout
 * with w->n1 points along dir and other across (pts, and wt for a NURBS). */
void cj_bsurf_unwide(const cj_bsp_h *w, int dir, int other, int rational, double *pts, double *wt);

#endif
