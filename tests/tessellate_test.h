/* Helpers shared by the tessellation test programs (test_tessellate, test_tessellate_rational). */
#ifndef CASTELJAU_TESSELLATE_TEST_H
#define CASTELJAU_TESSELLATE_TEST_H

#include "casteljau/mesh.h"
#include "casteljau/patch.h"
#include "rng.h"

#include <stddef.h>

/* C(n, k) as a double (exact for the degrees the tests use). */
double tess_binom(int n, int k);
/* The smallest K whose uniform K x K tessellation of the np patches has a proven bound <= tol,
 * and its triangle count in *tris. */
int tess_smallest_uniform(const cj_patch *p, size_t np, double tol, size_t *tris);

/* Control point q of a random (m, n) net: the grid point (i/m, j/n, 0) moved by up to 0.4 in
 * x and y, with z in [-0.8, 0.8] (three draws from r, in that order). */
void tess_random_point(cj_rng *r, int m, int n, int q, double p[3]);

/* Independent evaluation of patch p at (u, v): the Bernstein sum (polynomial or rational). */
void bern_eval(const cj_patch *p, double u, double v, double out[3]);
/* max over triangles of max over the barycentric lattice (step 1/L) of |S(x) - L(x)|, with
 * S evaluated by bern_eval at the interpolated (u,v); also checks every vertex lies on its
 * patch (within 1e-12 of the size). */
double sample_deviation(const cj_mesh *mesh, const cj_patch *patches, int L, double size);
/* qsort order of 3D points: lexicographic by x, y, z. */
int cmp3(const void *a, const void *b);

#endif
