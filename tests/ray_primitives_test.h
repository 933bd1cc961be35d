/* Shared by the two source files of test_ray_primitives. */
#ifndef CJ_TEST_RAY_PRIMITIVES_H
#define CJ_TEST_RAY_PRIMITIVES_H

#include "casteljau/vec.h"
#include "rng.h"
#include <stdint.h>

/* The run's seed (CJ_SEED replays) and a uniformly random unit vector. */
extern uint64_t rp_seed;
cj_vec3 rp_rand_unit(cj_rng *r);

/* ray_primitives_surfaces.c */
void test_torus(void **state);
void test_patches(void **state);
void test_triangles(void **state);
void test_polygons_and_planar(void **state);
void test_offsets(void **state);

#endif
