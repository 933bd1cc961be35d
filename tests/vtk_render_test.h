/* Shared by the two source files of test_vtk_render. */
#ifndef CJ_TEST_VTK_RENDER_H
#define CJ_TEST_VTK_RENDER_H

#include "casteljau/mesh.h"
#include "casteljau/vec.h"

/* A lat-long sphere of nu x nv cells around c; *delta receives how far inside the sphere its
 * flattest triangle lies (the mesh contains the ball of radius r - delta). */
cj_mesh *sphere_mesh(cj_vec3 c, double r, int nu, int nv, double *delta);
/* Writes the picture as PNG into $CJ_VTK_RENDER_DUMP when that is set. */
void dump_png(const char *name, int w, int h, const float *rgba);

/* vtk_render_sphere.c */
void test_vtk_sphere_perspective(void **state);
void test_vtk_sphere_orthographic(void **state);

#endif
