/* Certified nearest point on Bézier patches (casteljau/patch_nearest.h): the proven lower bound
 * is never beaten by a dense grid of exact (256-bit MPFR) distances, the reported distance is a
 * true upper bound at the reported (u,v); random bicubic and biquintic patches, a rational
 * cylinder patch seen from its axis (every point equidistant), points on the patch; bad input
 * refused with its name. */
#include "casteljau/patch_nearest.h"
#include "rng.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
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

static long exact_checks = 0;

/* Exact (256-bit) distance from q to S(u,v): tensor de Casteljau on homogeneous points. */
static double exact_distance(const cj_patch *p, double u, double v, const double q[3]) {
    int m = p->deg_u, n = p->deg_v;
    mpfr_t w[16][4], col[16][4], U, V, S, T, a, b;
    mpfr_inits2(256, U, V, S, T, a, b, (mpfr_ptr)0);
    mpfr_set_d(U, u, MPFR_RNDN);
    mpfr_set_d(V, v, MPFR_RNDN);
    mpfr_ui_sub(S, 1, U, MPFR_RNDN);
    mpfr_ui_sub(T, 1, V, MPFR_RNDN);
    for (int i = 0; i < 16; ++i)
        for (int k = 0; k < 4; ++k) mpfr_inits2(256, w[i][k], col[i][k], (mpfr_ptr)0);
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= m; ++i) {
            int idx = j * (m + 1) + i;
            double wt = p->weights ? p->weights[idx] : 1.0;
            for (int k = 0; k < 3; ++k) {
                mpfr_set_d(w[i][k], p->pts[3 * idx + k], MPFR_RNDN);
                mpfr_mul_d(w[i][k], w[i][k], wt, MPFR_RNDN);
            }
            mpfr_set_d(w[i][3], wt, MPFR_RNDN);
        }
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < 4; ++k) {
                    mpfr_mul(a, w[i][k], S, MPFR_RNDN);
                    mpfr_mul(b, w[i + 1][k], U, MPFR_RNDN);
                    mpfr_add(w[i][k], a, b, MPFR_RNDN);
                }
        for (int k = 0; k < 4; ++k) mpfr_set(col[j][k], w[0][k], MPFR_RNDN);
    }
    for (int r = n; r > 0; --r)
        for (int j = 0; j < r; ++j)
            for (int k = 0; k < 4; ++k) {
                mpfr_mul(a, col[j][k], T, MPFR_RNDN);
                mpfr_mul(b, col[j + 1][k], V, MPFR_RNDN);
                mpfr_add(col[j][k], a, b, MPFR_RNDN);
            }
    mpfr_set_ui(a, 0, MPFR_RNDN);
    for (int k = 0; k < 3; ++k) {
        mpfr_div(b, col[0][k], col[0][3], MPFR_RNDN);
        mpfr_sub_d(b, b, q[k], MPFR_RNDN);
        mpfr_sqr(b, b, MPFR_RNDN);
        mpfr_add(a, a, b, MPFR_RNDN);
    }
    mpfr_sqrt(a, a, MPFR_RNDN);
    double r = mpfr_get_d(a, MPFR_RNDN);
    for (int i = 0; i < 16; ++i)
        for (int k = 0; k < 4; ++k) mpfr_clears(w[i][k], col[i][k], (mpfr_ptr)0);
    mpfr_clears(U, V, S, T, a, b, (mpfr_ptr)0);
    return r;
}

static void check_query(const cj_patch *p, const double q[3], double tol, int grid,
                        const char *what, cj_patch_nearest_result *res) {
    cj_patch_nearest_result r;
    cj_status st = cj_patch_nearest(p, q, tol, &r);
    CHECK(st == CJ_OK, "%s: %s", what, cj_last_error());
    if (st != CJ_OK) return;
    CHECK(exact_distance(p, r.u, r.v, q) <= r.distance, "%s: distance not an upper bound", what);
    CHECK(r.lower <= r.distance && r.distance - r.lower <= tol, "%s: gap %g", what,
          r.distance - r.lower);
    for (int i = 0; i <= grid; ++i)
        for (int j = 0; j <= grid; ++j) {
            double d = exact_distance(p, (double)i / grid, (double)j / grid, q);
            CHECK(d >= r.lower, "%s: grid (%d,%d) at %.17g beats the lower bound %.17g", what, i, j,
                  d, r.lower);
            ++exact_checks;
        }
    if (res) *res = r;
}

int main(void) {
    uint64_t seed = cj_test_seed("test_patch_nearest", 23);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    long pieces = 0;
    int nq = 150;
    for (int k = 0; k < nq; ++k) {
        int deg = k % 3 == 2 ? 5 : 3, np = (deg + 1) * (deg + 1);
        double pts[3 * 36], q[3];
        for (int i = 0; i < 3 * np; ++i) pts[i] = cj_rng_range(&rng, -1, 1);
        for (int i = 0; i < 3; ++i) q[i] = cj_rng_range(&rng, -1.5, 1.5);
        cj_patch p = cj_patch_view(deg, deg, pts, NULL);
        char what[64];
        snprintf(what, sizeof what, "random %d (seed %llu)", k, (unsigned long long)seed);
        cj_patch_nearest_result r;
        memset(&r, 0, sizeof r);
        check_query(&p, q, 1e-9, 24, what, &r);
        pieces += r.pieces;
    }
    /* a quarter cylinder of radius 1 (rational in u, linear in v) seen from its axis */
    const double c = 0.70710678118654752;
    double cyl[] = {1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 2, 1, 1, 2, 0, 1, 2};
    double cw[] = {1, c, 1, 1, c, 1};
    cj_patch C = cj_patch_view(2, 1, cyl, cw);
    cj_patch_nearest_result r;
    check_query(&C, (double[]){0, 0, 1}, 1e-9, 30, "cylinder axis", &r);
    CHECK(fabs(r.distance - 1) < 1e-9 && r.lower > 1 - 2e-9, "cylinder: %.17g [%.17g]", r.distance,
          r.lower);
    /* a rational sphere octant seen from its centre: every point at distance 1, so no piece of
     * any size is prunable by its control box (this hit the work cap before the Bernstein bound
     * of the squared distance); also from a point just off the centre, nearly equidistant */
    {
        const double a[3][2] = {{1, 0}, {1, 1}, {0, 1}}, wa[3] = {1, c, 1};
        double sp[27], sw[9];
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                int idx = j * 3 + i;
                sp[3 * idx] = a[j][0] * a[i][0];
                sp[3 * idx + 1] = a[j][0] * a[i][1];
                sp[3 * idx + 2] = a[j][1];
                sw[idx] = wa[i] * wa[j];
            }
        cj_patch S = cj_patch_view(2, 2, sp, sw);
        check_query(&S, (double[]){0, 0, 0}, 1e-9, 30, "sphere centre", &r);
        CHECK(fabs(r.distance - 1) < 1e-9 && r.lower > 1 - 1e-9 && r.pieces < 100,
              "sphere centre: %.17g [%.17g] in %ld pieces", r.distance, r.lower, r.pieces);
        printf("sphere octant from its centre, tol 1e-9: distance %.17g, lower %.17g, %ld "
               "sub-patches\n",
               r.distance, r.lower, r.pieces);
        check_query(&S, (double[]){1e-7, -2e-7, 3e-8}, 1e-9, 30, "sphere near centre", &r);
        printf("sphere octant from (1e-7, -2e-7, 3e-8), tol 1e-9: distance %.17g, lower %.17g, "
               "%ld sub-patches\n",
               r.distance, r.lower, r.pieces);
        check_query(&S, (double[]){0, 0, 0}, 2e-11, 12, "sphere centre tol 2e-11", &r);
        CHECK(r.pieces < 100, "sphere centre tol 2e-11: %ld pieces", r.pieces);
    }
    /* a point of the patch: its corner */
    double flat[3 * 16];
    for (int i = 0; i < 3 * 16; ++i) flat[i] = cj_rng_range(&rng, -1, 1);
    cj_patch F = cj_patch_view(3, 3, flat, NULL);
    check_query(&F, flat, 1e-9, 10, "corner", &r);
    CHECK(r.distance <= 1e-9, "corner: distance %g", r.distance);
    /* bad input */
    CHECK(cj_patch_nearest(&F, (double[]){NAN, 0, 0}, 1e-9, &r) == CJ_ERR_NONFINITE &&
              strstr(cj_last_error(), "query point"),
          "NaN: %s", cj_last_error());
    CHECK(cj_patch_nearest(&F, (double[]){0, 0, 0}, 1e-16, &r) == CJ_ERR_ARGUMENT &&
              strstr(cj_last_error(), "tol 1e-16"),
          "tol: %s", cj_last_error());
    double big[3 * 17 * 17];
    for (int i = 0; i < 3 * 17 * 17; ++i) big[i] = i;
    cj_patch B = cj_patch_view(16, 16, big, NULL);
    CHECK(cj_patch_nearest(&B, (double[]){0, 0, 0}, 1e-6, &r) == CJ_ERR_DEGREE, "degree 16");
    printf("test_patch_nearest: %d random queries (bicubic, biquintic; %.0f sub-patches per "
           "query), a rational cylinder from its axis, a corner; %ld exact 256-bit grid "
           "distances, none below a certified lower bound; bad input refused: %s (%d "
           "failures)\n",
           nq, (double)pieces / nq, exact_checks, failures ? "FAILED" : "passed", failures);
    return failures ? 1 : 0;
}
