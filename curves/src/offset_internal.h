/* Private: circular arcs as cubic pieces with a proven radial bound, for the round joins and
 * caps of offsets (offset_arc.c, used by offset.c and offset_outline.c). */
#ifndef CASTELJAU_OFFSET_INTERNAL_H
#define CASTELJAU_OFFSET_INTERNAL_H

#define CJ_OFFSET_ARC_MAX 64

/* Cubic pieces (8 doubles each, at most CJ_OFFSET_ARC_MAX) for the arc of the circle of radius r
 * about C from A to B, turning by `sweep` radians (> 0 counter-clockwise; |sweep| <= 2 pi): the
 * first piece starts at A and the last ends at B bit for bit (A and B need only lie near the
 * circle), each piece the usual cubic with handles (4/3) tan(theta/4) r. *bound receives a PROVEN
 * bound of the distance between the pieces and the arc, both ways: from the Bernstein coefficients
 * of |q(u) - C|^2 (degree 6, in interval arithmetic) the radius of every point of the pieces is
 * within it of r, and the pieces turn monotonically from A to B. The number of pieces grows until
 * *bound <= tol (or the maximum is reached: then *bound says how far). Returns the count. */
int cj_offset_arc(const double C[2], double r, const double A[2], const double B[2], double sweep,
                  double tol, double *out, double *bound);

#endif
