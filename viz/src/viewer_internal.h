/* Private to the viewer (viz/src/viewer*.c): exact pick comparisons shared by the 2D and 3D
 * editor models. */
#ifndef CASTELJAU_VIEWER_INTERNAL_H
#define CASTELJAU_VIEWER_INTERNAL_H

/* Sign of |a − c|² − |b − c|² computed exactly (-1: a is nearer to c). */
int cj_vpick_closer(double ax, double ay, double bx, double by, double cx, double cy);
/* 1 if |a − c|² <= radius², exactly. */
int cj_vpick_within(double ax, double ay, double cx, double cy, double radius);

#endif
