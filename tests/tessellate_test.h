/* Helpers shared by the tessellation test programs (test_tessellate, test_tessellate_rational). */
#ifndef CASTELJAU_TESSELLATE_TEST_H
#define CASTELJAU_TESSELLATE_TEST_H

#include "casteljau/patch.h"

#include <stddef.h>

/* C(n, k) as a double (exact for the degrees the tests use). */
double tess_binom(int n, int k);
/* The smallest K whose uniform K x K tessellation of the np patches has a proven bound <= tol,
 * and its triangle count in *tris. */
int tess_smallest_uniform(const cj_patch *p, size_t np, double tol, size_t *tris);

#endif
