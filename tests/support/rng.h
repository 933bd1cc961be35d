/* Seeded generator for property tests: xoshiro256** seeded by splitmix64. Every property
 * test prints its seed; CJ_SEED=<n> in the environment replays a run. */
#ifndef CJ_TEST_RNG_H
#define CJ_TEST_RNG_H

#include <stdint.h>

typedef struct cj_rng {
    uint64_t s[4];
} cj_rng;

/* The seed: CJ_SEED from the environment if set, else `fallback`. Prints
 * "<test>: seed <n> (replay with CJ_SEED=<n>)" on stdout. */
uint64_t cj_test_seed(const char *test_name, uint64_t fallback);

void cj_rng_init(cj_rng *r, uint64_t seed);
uint64_t cj_rng_next(cj_rng *r);
/* Uniform in [0,1). */
double cj_rng_unit(cj_rng *r);
/* Uniform in [lo,hi). */
double cj_rng_range(cj_rng *r, double lo, double hi);
/* Uniform integer in [lo,hi]. */
int cj_rng_int(cj_rng *r, int lo, int hi);

#endif
