/* test_pow_poly: the rasterizer's polynomial c^a (raster/src/pow_poly.h) against MPFR at 140
 * bits over its domain (c normal in (0, 2], a in [0, 4096]): random points (log-uniform c, a
 * from several scales) and a grid near the hard places (c near 1, near √2 and its halvings,
 * tiny c, a = 0, integer a). Checks the header's bounds
 *   |p − c^a| <= 4e-7 · c^a · (1 + |a log2 c|)   and, where c <= 1, |p − c^a| <= 5e-7,
 * the exact cases (a = 0 or c = 1 give 1), and that an 8-lane loop gives bit-identical values
 * to scalar calls. Prints the worst relative and absolute errors seen. CJ_SEED replays. */
#include "pow_poly.h"

#include "support/check.h"
#include "support/rng.h"

#include <float.h>
#include <math.h>
#include <mpfr.h>
#include <stdio.h>

static double worst_rel = 0.0, worst_abs = 0.0, worst_rel_c = 0.0, worst_rel_a = 0.0;
static long checked = 0;

/* c^a in 140-bit MPFR, rounded to double (ample for a float-accuracy check) */
static double oracle(float c, float a) {
    mpfr_t x, y, r;
    mpfr_inits2(140, x, y, r, (mpfr_ptr)0);
    mpfr_set_flt(x, c, MPFR_RNDN);
    mpfr_set_flt(y, a, MPFR_RNDN);
    mpfr_pow(r, x, y, MPFR_RNDN);
    double v = mpfr_get_d(r, MPFR_RNDN);
    mpfr_clears(x, y, r, (mpfr_ptr)0);
    return v;
}

static void check_point(float c, float a) {
    if (!(c >= FLT_MIN)) return; /* subnormal: outside the domain */
    const double exact = oracle(c, a);
    const double y = (double)a * log2((double)c);
    if (y < -125.0 || y > 125.0) return; /* outside the unclamped range */
    const double p = cj_pow_poly(c, a), err = fabs(p - exact);
    const double rel = err / (exact * (1.0 + fabs(y)));
    ++checked;
    CHECK(rel <= 4e-7, "c=%.9g a=%.9g: %.12g vs %.12g (relative %.3g)", c, a, p, exact, rel);
    if (c <= 1.0f) {
        CHECK(err <= 5e-7, "c=%.9g a=%.9g: absolute error %.3g", c, a, err);
        if (err > worst_abs) worst_abs = err;
    }
    if (rel > worst_rel) {
        worst_rel = rel;
        worst_rel_c = c;
        worst_rel_a = a;
    }
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_pow_poly", 20261126);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    /* random: c log-uniform in [2^-40, 2], a from four scales */
    const double scales[4] = {1.0, 16.0, 256.0, 4096.0};
    for (int i = 0; i < 600000; ++i) {
        const float c = (float)exp2(cj_rng_range(&rng, -40.0, 1.0));
        const float a = (float)(cj_rng_unit(&rng) * scales[i & 3]);
        check_point(c, a);
    }
    /* grid: c near 1 (both sides), near √2 · 2^k, tiny c; a = 0, integers, fractions */
    const float centres[6] = {1.0f, 1.41421354f, 0.707106769f, 0.353553385f, 2.0f, FLT_MIN};
    for (int ci = 0; ci < 6; ++ci) {
        float c = centres[ci];
        for (int step = 0; step < 1500; ++step) {
            for (int a = 0; a <= 128; a += 1) check_point(c, (float)a);
            check_point(c, 0.5f);
            check_point(c, 1e-3f);
            c = step & 1 ? nextafterf(c, 0.0f) : nextafterf(c, 4.0f);
            if (step & 1)
                for (int j = 0; j < step / 64; ++j) c = nextafterf(c, 0.0f);
        }
    }
    /* exact cases */
    int exact_ones = 1;
    for (int i = 0; i < 10000; ++i) {
        const float c = (float)exp2(cj_rng_range(&rng, -126.0, 1.0));
        if (cj_pow_poly(c, 0.0f) != 1.0f) exact_ones = 0;
        if (cj_pow_poly(1.0f, (float)cj_rng_range(&rng, 0.0, 1e4)) != 1.0f) exact_ones = 0;
    }
    CHECK(exact_ones, "a = 0 or c = 1 must give exactly 1");
    /* lanes: an 8-wide loop equals scalar calls bit for bit */
    int lanes_equal = 1;
    for (int i = 0; i < 20000; ++i) {
        float c[8], a[8], out[8];
        for (int j = 0; j < 8; ++j) {
            c[j] = (float)exp2(cj_rng_range(&rng, -30.0, 1.0));
            a[j] = (float)cj_rng_range(&rng, 0.0, 200.0);
        }
        for (int j = 0; j < 8; ++j) out[j] = cj_pow_poly(c[j], a[j]);
        for (int j = 0; j < 8; ++j) {
            volatile float cs = c[j], as = a[j];
            if (out[j] != cj_pow_poly(cs, as)) lanes_equal = 0;
        }
    }
    CHECK(lanes_equal, "8-lane loop differs from scalar calls");
    printf("test_pow_poly: seed %llu, %ld points against MPFR (140 bits): worst relative error "
           "%.3g of c^a (1 + |a log2 c|) at c=%.9g a=%.9g (bound 4e-7); worst absolute error for "
           "c <= 1: %.3g (bound 5e-7); a = 0 and c = 1 exact; 8 lanes = scalar\n",
           (unsigned long long)seed, checked, worst_rel, worst_rel_c, worst_rel_a, worst_abs);
    return cj_check_exit();
}
