/* Certified nearest points (casteljau/nearest.h): the proven lower bound is never beaten by
 * dense sampling re-checked exactly (256-bit MPFR distances), the reported distance is a true
 * upper bound at the reported parameter, and the gap is within tol. Random polynomial and
 * rational curves at many scales, points on the curve, equidistant points (circle centre, a
 * symmetry axis), high degree; bad input refused with its name. */
#include "casteljau/nearest.h"
#include "query_oracle.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++failures;                                                                            \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                                            \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

static long samples_checked = 0;
static double worst_gap = 0.0;

/* One query checked: the certificate against nsamples exact distances. */
static void check_query(const cj_bezier2 *c, const double q[2], double tol, int nsamples,
                        const char *what) {
    cj_nearest r;
    cj_status st = cj_nearest_curve(c, q, tol, &r);
    CHECK(st == CJ_OK, "%s: %s", what, cj_last_error());
    if (st != CJ_OK) return;
    qo_curve Q = {c->degree, c->pts, c->weights};
    double exact_at_t = qo_distance(&Q, r.t, q);
    CHECK(exact_at_t <= r.distance, "%s: distance %.17g below the exact %.17g at t", what,
          r.distance, exact_at_t);
    CHECK(r.lower <= r.distance && r.distance - r.lower <= tol, "%s: gap %g above tol %g", what,
          r.distance - r.lower, tol);
    worst_gap = fmax(worst_gap, (r.distance - r.lower) / tol);
    for (int j = 0; j <= nsamples; ++j) {
        double t = (double)j / nsamples;
        double d = qo_distance(&Q, t, q);
        CHECK(d >= r.lower,
              "%s: sample t=%.17g at exact distance %.17g beats the lower bound "
              "%.17g",
              what, t, d, r.lower);
        ++samples_checked;
    }
    /* sampling near the reported point too, where a wrong minimum would show */
    for (int j = -50; j <= 50; ++j) {
        double t = r.t + j * 1e-7;
        if (t < 0 || t > 1) continue;
        double d = qo_distance(&Q, t, q);
        CHECK(d >= r.lower, "%s: near sample t=%.17g beats the lower bound", what, t);
        ++samples_checked;
    }
}

static void test_adversarial(void) {
    /* on the curve: an end point and an interior point */
    double a[] = {0, 0, 1, 2, 2, -1, 3, 1};
    cj_bezier2 A = cj_bezier2_view(3, a, NULL);
    check_query(&A, (double[]){0, 0}, 1e-9, 1000, "end point on the curve");
    check_query(&A, (double[]){1.5, 0.5}, 1e-9, 1000, "interior point on the curve");
    cj_nearest r;
    cj_nearest_curve(&A, (double[]){0, 0}, 1e-9, &r);
    CHECK(r.distance <= 1e-9 && r.t < 1e-6, "end point: t %g distance %g", r.t, r.distance);
    /* equidistant: the centre of a quarter circle (every point at distance 1) */
    double w[] = {1, 0.70710678118654752, 1}, circ[] = {1, 0, 1, 1, 0, 1};
    cj_bezier2 C = cj_bezier2_view(2, circ, w);
    check_query(&C, (double[]){0, 0}, 1e-9, 2000, "circle centre");
    cj_nearest_curve(&C, (double[]){0, 0}, 1e-9, &r);
    CHECK(fabs(r.distance - 1.0) < 1e-9 && r.lower > 1 - 2e-9, "circle centre: %.17g [%.17g]",
          r.distance, r.lower);
    /* two symmetric minima: a symmetric arch and a point on its axis */
    double arch[] = {0, 0, 0, 2, 2, 2, 2, 0};
    cj_bezier2 Ar = cj_bezier2_view(3, arch, NULL);
    check_query(&Ar, (double[]){1, 0.2}, 1e-9, 2000, "symmetry axis");
    /* huge and tiny scales, high degree, rational */
    cj_rng rng;
    cj_rng_init(&rng, 7);
    for (int e = -2; e <= 2; ++e) {
        double f = pow(10.0, 70.0 * e), s[8];
        for (int i = 0; i < 8; ++i) s[i] = a[i] * f;
        cj_bezier2 S = cj_bezier2_view(3, s, NULL);
        check_query(&S, (double[]){1.2 * f, 0.9 * f}, 1e-9 * f, 500, "scaled");
    }
    double hd[2 * 41];
    for (int i = 0; i < 82; ++i) hd[i] = cj_rng_unit(&rng);
    cj_bezier2 H = cj_bezier2_view(40, hd, NULL);
    check_query(&H, (double[]){0.5, 0.5}, 1e-9, 4000, "degree 40");
    printf("adversarial: points on the curve, circle centre (all equidistant), symmetry axis, "
           "scales 1e-140..1e140, degree 40\n");
}

static void test_random(uint64_t seed, int nq) {
    cj_rng r;
    cj_rng_init(&r, seed);
    long pieces = 0;
    for (int k = 0; k < nq; ++k) {
        int n = k % 5 == 4 ? cj_rng_int(&r, 1, 10) : 3;
        double pts[2 * 11], w[11], q[2];
        for (int i = 0; i < 2 * (n + 1); ++i) pts[i] = cj_rng_range(&r, -1, 1);
        for (int i = 0; i <= n; ++i) w[i] = cj_rng_range(&r, 0.2, 3);
        q[0] = cj_rng_range(&r, -1.5, 1.5);
        q[1] = cj_rng_range(&r, -1.5, 1.5);
        cj_bezier2 c = cj_bezier2_view(n, pts, k % 3 == 2 ? w : NULL);
        char what[64];
        snprintf(what, sizeof what, "query %d (seed %llu)", k, (unsigned long long)seed);
        check_query(&c, q, 1e-10, 200, what);
        cj_nearest res;
        if (cj_nearest_curve(&c, q, 1e-10, &res) == CJ_OK) pieces += res.pieces;
    }
    printf("random: %d queries (a third rational, degrees 1..10), %.1f pieces per query\n", nq,
           (double)pieces / nq);
}

/* Cases aimed at the polynomial fast path (roots of (c - q).c' isolated on its Bernstein
 * coefficients, nearest_roots.c) and its hand-over to the branch and bound: points at and near
 * centres of curvature (a double or triple root of g, or two roots closer than rounding), a cusp,
 * a straight cubic, the degrees around its limit of 12. */
static void test_fast_path(uint64_t seed, int nc) {
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x5bd1e995u);
    const double eps[] = {0.0, 1e-12, -1e-12, 1e-8, -1e-8, 1e-4, -1e-4};
    int nq = 0;
    for (int k = 0; k < nc; ++k) {
        double p[8];
        for (int i = 0; i < 8; ++i) p[i] = cj_rng_range(&r, -1, 1);
        cj_bezier2 c = cj_bezier2_view(3, p, NULL);
        double t = cj_rng_unit(&r), s = 1 - t, d1[2], d2[2], pt[2];
        for (int j = 0; j < 2; ++j) {
            pt[j] = s * s * s * p[j] + 3 * s * s * t * p[2 + j] + 3 * s * t * t * p[4 + j] +
                    t * t * t * p[6 + j];
            d1[j] = 3 * (s * s * (p[2 + j] - p[j]) + 2 * s * t * (p[4 + j] - p[2 + j]) +
                         t * t * (p[6 + j] - p[4 + j]));
            d2[j] = 6 * (s * (p[4 + j] - 2 * p[2 + j] + p[j]) +
                         t * (p[6 + j] - 2 * p[4 + j] + p[2 + j]));
        }
        double sp2 = d1[0] * d1[0] + d1[1] * d1[1], cross = d1[0] * d2[1] - d1[1] * d2[0];
        if (fabs(cross) < 1e-3) continue;
        /* centre of curvature: c + c'^perp |c'|^2 / (c' x c'') */
        double ctr[2] = {pt[0] - d1[1] * sp2 / cross, pt[1] + d1[0] * sp2 / cross};
        if (fabs(ctr[0]) > 10 || fabs(ctr[1]) > 10) continue;
        double e = eps[k % 7],
               q[2] = {pt[0] + (ctr[0] - pt[0]) * (1 + e), pt[1] + (ctr[1] - pt[1]) * (1 + e)};
        char what[80];
        snprintf(what, sizeof what, "centre of curvature %d (1%+g, seed %llu)", k, e,
                 (unsigned long long)seed);
        check_query(&c, q, 1e-10, 300, what);
        ++nq;
    }
    double cusp[] = {0, 0, 2, 2, 0, 2, 2, 0}, line[] = {0, 0, 1, 1, 2, 2, 3, 3};
    cj_bezier2 C = cj_bezier2_view(3, cusp, NULL), L = cj_bezier2_view(3, line, NULL);
    check_query(&C, (double[]){1, 1.5}, 1e-10, 2000, "at the cusp");
    check_query(&C, (double[]){1, 1.6}, 1e-10, 2000, "above the cusp");
    check_query(&C, (double[]){1, 1.2}, 1e-10, 2000, "below the cusp");
    check_query(&L, (double[]){1, 2}, 1e-10, 2000, "off a straight cubic");
    check_query(&L, (double[]){4, 4.5}, 1e-10, 2000, "past the end of a straight cubic");
    check_query(&L, (double[]){1.5, 1.5}, 1e-10, 2000, "on a straight cubic");
    for (int n = 11; n <= 13; ++n)
        for (int k = 0; k < 10; ++k) {
            double hp[2 * 14];
            for (int i = 0; i < 2 * (n + 1); ++i) hp[i] = cj_rng_range(&r, -1, 1);
            cj_bezier2 H = cj_bezier2_view(n, hp, NULL);
            check_query(&H, (double[]){cj_rng_range(&r, -1, 1), cj_rng_range(&r, -1, 1)}, 1e-10,
                        1000, "degree 11..13");
        }
    printf("fast path: %d points at and near (1 +- 1e-12, 1e-8, 1e-4) centres of curvature, a "
           "cusp, a straight cubic, 30 curves of degrees 11..13\n",
           nq);
}

static void test_bad_input(void) {
    double a[] = {0, 0, 1, 2, 2, -1, 3, 1}, pt[] = {1, 1, 1, 1};
    cj_bezier2 A = cj_bezier2_view(3, a, NULL), P = cj_bezier2_view(1, pt, NULL);
    cj_nearest r;
    CHECK(cj_nearest_curve(&A, (double[]){NAN, 0}, 1e-9, &r) == CJ_ERR_NONFINITE &&
              strstr(cj_last_error(), "query point"),
          "NaN point: %s", cj_last_error());
    CHECK(cj_nearest_curve(&A, (double[]){0, 0}, 1e-18, &r) == CJ_ERR_ARGUMENT &&
              strstr(cj_last_error(), "tol 1e-18"),
          "tiny tol: %s", cj_last_error());
    CHECK(cj_nearest_curve(&P, (double[]){0, 0}, 1e-9, &r) == CJ_ERR_DEGENERATE &&
              strstr(cj_last_error(), "coincide"),
          "point curve: %s", cj_last_error());
    printf("bad input: NaN point, tol below the doubles' resolution, a point for a curve\n");
}

int main(void) {
    uint64_t seed = cj_test_seed("test_nearest", 23);
    test_adversarial();
    test_random(seed, 2000);
    test_fast_path(seed, 1400);
    test_bad_input();
    printf("test_nearest: %ld exact (256-bit) sample distances, none below a certified lower "
           "bound; largest gap %.3g of tol; %s (%d failures)\n",
           samples_checked, worst_gap, failures ? "FAILED" : "passed", failures);
    return failures ? 1 : 0;
}
