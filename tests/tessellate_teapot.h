/* The teapot checks of test_tessellate (tessellate_teapot.c). */
#ifndef CASTELJAU_TESSELLATE_TEAPOT_H
#define CASTELJAU_TESSELLATE_TEAPOT_H

/* The .bpt data: 32 patches whose shared edges match. */
void test_teapot_data(void **state);
/* Tessellations at 1e-2, 3e-3 and 1e-3 of the size and uniform 12 x 12: within tolerance, and
 * no cracks along the shared edges. */
void test_teapot_tolerances_and_cracks(void **state);

#endif
