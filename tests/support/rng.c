#include "rng.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>

static uint64_t splitmix64(uint64_t *x) {
    uint64_t z = (*x += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) {
    return (x << k) | (x >> (64 - k));
}

uint64_t cj_test_seed(const char *test_name, uint64_t fallback) {
    uint64_t seed = fallback;
    const char *env = getenv("CJ_SEED");
    if (env && *env) seed = strtoull(env, NULL, 0);
    printf("%s: seed %" PRIu64 " (replay with CJ_SEED=%" PRIu64 ")\n", test_name, seed, seed);
    fflush(stdout);
    return seed;
}

void cj_rng_init(cj_rng *r, uint64_t seed) {
    for (int i = 0; i < 4; ++i) r->s[i] = splitmix64(&seed);
}

uint64_t cj_rng_next(cj_rng *r) {
    uint64_t *s = r->s;
    const uint64_t result = rotl(s[1] * 5, 7) * 9;
    const uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double cj_rng_unit(cj_rng *r) {
    return (double)(cj_rng_next(r) >> 11) * 0x1p-53;
}

double cj_rng_range(cj_rng *r, double lo, double hi) {
    return lo + (hi - lo) * cj_rng_unit(r);
}

int cj_rng_int(cj_rng *r, int lo, int hi) {
    return lo + (int)(cj_rng_next(r) % (uint64_t)(hi - lo + 1));
}
