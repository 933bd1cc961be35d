/* bench_eval: cost and accuracy of the four Bézier evaluation methods.
 *
 * Part 1, cost: ns per evaluation for degrees 3, 8, 20 (planar curves, 256 parameters spread
 * over [0,1]), batch (cj_bezier_eval_batch), single (cj_bezier_eval per parameter, which
 * validates the curve each time) and unchecked (cj_bezier_eval_unchecked per parameter, the
 * curve validated once), median of 41 runs of at least 0.25 ms each, the methods
 * interleaved run by run so that a busy machine slows them alike; ratios to de Casteljau.
 * Part 2, accuracy: the hard case p(s) = (s-1)(s-3/4)^7 in Bernstein form near s = 3/4: the
 * condition number and relative errors measured against an exact MPFR oracle, next to the
 * a-priori bounds gamma(3n) cond (de Casteljau) and u + 2 gamma(3n)^2 cond (compensated) and
 * the a-posteriori bound returned by cj_bezier_eval_compensated. */
#define _POSIX_C_SOURCE 199309L
#include "casteljau/bezier.h"
#include "oracle_mpfr.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "bench_clock.h"

#define NT   256
#define RUNS 41

static volatile double sink;

typedef enum { MODE_BATCH, MODE_SINGLE, MODE_BOUND, MODE_UNCHECKED } mode;

/* One run: reps passes over the NT parameters; returns ns per evaluation. */
static double run_once(const cj_bezier *c, cj_eval_method m, mode md, const double *ts, double *out,
                       long reps) {
    double bnd[CJ_MAX_DIM] = {0};
    const double t0 = (1e9 * cj_bench_wall());
    for (long r = 0; r < reps; ++r) {
        if (md == MODE_BATCH) {
            if (cj_bezier_eval_batch(c, m, ts, NT, out)) abort();
        } else if (md == MODE_UNCHECKED) {
            for (int j = 0; j < NT; ++j)
                cj_bezier_eval_unchecked(c, m, ts[j], out + (size_t)j * (size_t)c->dim);
        } else if (md == MODE_SINGLE) {
            for (int j = 0; j < NT; ++j)
                if (cj_bezier_eval(c, m, ts[j], out + (size_t)j * (size_t)c->dim)) abort();
        } else {
            for (int j = 0; j < NT; ++j)
                if (cj_bezier_eval_compensated(c, ts[j], out + (size_t)j * (size_t)c->dim, bnd))
                    abort();
        }
        sink += out[(size_t)(r % NT) * (size_t)c->dim] + bnd[0] * 0.0;
    }
    const double t1 = (1e9 * cj_bench_wall());
    return (t1 - t0) / ((double)reps * NT);
}

/* Calibrates reps so that one run lasts at least 0.25 ms: short runs are rarely interrupted by
 * other processes on a shared machine, and the median over many of them ignores those that
 * were. */
static long calibrate(const cj_bezier *c, cj_eval_method m, mode md, const double *ts,
                      double *out) {
    long reps = 1;
    while (run_once(c, m, md, ts, out, reps) * (double)reps * NT < 2.5e5 && reps < (1L << 24))
        reps *= 2;
    return reps;
}

#define NCOL 13 /* 4 methods x (batch, single) + compensated with bound + 4 unchecked */

static void cost_table(void) {
    static const struct {
        const char *name;
        cj_eval_method m;
    } methods[] = {{"decasteljau", CJ_EVAL_DECASTELJAU},
                   {"bernstein", CJ_EVAL_BERNSTEIN},
                   {"horner", CJ_EVAL_HORNER},
                   {"compensated", CJ_EVAL_COMPENSATED}};
    static const int degrees[] = {3, 8, 20};
    double ts[NT], out[NT * 2];
    for (int j = 0; j < NT; ++j) ts[j] = (j + 0.5) / NT;
    uint64_t x = 0x9e3779b97f4a7c15u;
    printf("cost: dimension 2, %d parameters in (0,1), ns per evaluation, median of %d runs "
           "(interleaved), fma %s\n",
           NT, RUNS,
#if defined(__FMA__) || defined(FP_FAST_FMA)
           "in hardware"
#else
           "in software"
#endif
    );
    printf("%-6s %-18s %10s %10s %10s %11s %11s %11s\n", "degree", "method", "batch ns",
           "single ns", "unchkd ns", "batch/dc", "single/dc", "unchkd/dc");
    for (size_t di = 0; di < sizeof degrees / sizeof degrees[0]; ++di) {
        const int n = degrees[di];
        double pts[(20 + 1) * 2];
        for (int i = 0; i < (n + 1) * 2; ++i) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            pts[i] = (double)(x >> 11) * 0x1p-53 * 2.0 - 1.0;
        }
        const cj_bezier c = cj_bezier_view(n, 2, pts);
        long reps[NCOL];
        static double v[NCOL][RUNS];
        /* columns 0-7: (batch, single) per method; 8: compensated+bound; 9-12: unchecked */
#define COL_MODE(col)                                                                              \
    ((col) == 8 ? MODE_BOUND : (col) > 8 ? MODE_UNCHECKED : ((col) % 2 ? MODE_SINGLE : MODE_BATCH))
#define COL_METHOD(col) methods[(col) == 8 ? 3 : (col) > 8 ? (col)-9 : (col) / 2].m
        for (int col = 0; col < NCOL; ++col)
            reps[col] = calibrate(&c, COL_METHOD(col), COL_MODE(col), ts, out);
        for (int r = 0; r < RUNS; ++r)
            for (int col = 0; col < NCOL; ++col)
                v[col][r] = run_once(&c, COL_METHOD(col), COL_MODE(col), ts, out, reps[col]);
        double med[NCOL];
        for (int col = 0; col < NCOL; ++col) med[col] = cj_bench_median(v[col], (size_t)(RUNS));
        for (int mi = 0; mi < 4; ++mi)
            printf("%-6d %-18s %10.1f %10.1f %10.1f %10.2fx %10.2fx %10.2fx\n", n, methods[mi].name,
                   med[2 * mi], med[2 * mi + 1], med[9 + mi], med[2 * mi] / med[0],
                   med[2 * mi + 1] / med[1], med[9 + mi] / med[9]);
        printf("%-6d %-18s %10s %10.1f %10s %11s %10.2fx %11s\n", n, "compensated+bound", "-",
               med[8], "-", "-", med[8] / med[1], "-");
        printf("%-6d horner per call vs de Casteljau per call: %.2fx faster (single), %.2fx faster "
               "(unchecked)\n",
               n, med[1] / med[5], med[9] / med[11]);
    }
}

static void accuracy_table(void) {
    /* b_i = -(8-i)/8 (-3/4)^(7-i) (1/4)^i, b_8 = 0: (1-s) times the degree-7 Bernstein form
     * of (s-3/4)^7, elevated. Every coefficient is a dyadic rational with few bits, so exact. */
    double b[9];
    for (int i = 0; i <= 8; ++i)
        b[i] = i == 8 ? 0.0 : -(8.0 - i) / 8.0 * pow(-0.75, 7 - i) * pow(0.25, i);
    const cj_bezier c = cj_bezier_view(8, 1, b);
    const double u = CJ_UNIT_ROUNDOFF, g = cj_gamma(24);
    printf("\naccuracy: p(s) = (s-1)(s-3/4)^7, degree 8, s = 3/4 + delta; relative errors\n"
           "against an exact MPFR value; bounds relative to |p(s)|\n");
    printf("%-7s %9s | %9s %9s | %9s %9s %9s | %9s %9s\n", "delta", "cond", "decast.", "g3n*cond",
           "compens.", "u+2g^2c", "a-post.", "bernst.", "horner");
    mpfr_t val, mag;
    mpfr_inits2(256, val, mag, (mpfr_ptr)0);
    for (int e = 2; e <= 20; ++e) {
        const double s = 0.75 + pow(10.0, -0.5 * e);
        cj_oracle_bezier(b, 8, 1, 0, s, 1 << 16, val, mag);
        mpfr_t cond;
        mpfr_init2(cond, 64);
        mpfr_div(cond, mag, val, MPFR_RNDN);
        mpfr_abs(cond, cond, MPFR_RNDN);
        const double cnd = mpfr_get_d(cond, MPFR_RNDN);
        mpfr_clear(cond);
        double vd, vc, vb, vh, bound;
        cj_bezier_eval(&c, CJ_EVAL_DECASTELJAU, s, &vd);
        cj_bezier_eval_compensated(&c, s, &vc, &bound);
        cj_bezier_eval(&c, CJ_EVAL_BERNSTEIN, s, &vb);
        cj_bezier_eval(&c, CJ_EVAL_HORNER, s, &vh);
        const double absval = fabs(mpfr_get_d(val, MPFR_RNDN));
        printf("%-7.1e %9.2e | %9.2e %9.2e | %9.2e %9.2e %9.2e | %9.2e %9.2e\n",
               pow(10.0, -0.5 * e), cnd, cj_oracle_rel_error(vd, val), g * cnd,
               cj_oracle_rel_error(vc, val), u + 2 * g * g * cnd, bound / absval,
               cj_oracle_rel_error(vb, val), cj_oracle_rel_error(vh, val));
    }
    mpfr_clears(val, mag, (mpfr_ptr)0);
}

int main(void) {
    cost_table();
    accuracy_table();
    printf("(checksum %g)\n", sink);
    return 0;
}
