/* Certified intersections (casteljau/intersect.h) against independent oracles: 256-bit MPFR
 * Newton for every crossing (the high-precision root must lie in the reported enclosure), and
 * long-double polyline crossings for the count (0 missed, 0 duplicated) on 10^5 random pairs;
 * adversarial cases: tangencies, near-tangencies, joints, coincident pieces, cusps, loops,
 * huge and tiny coordinates, high degree, rational arcs; bad input refused with its name. */
#include "casteljau/intersect.h"
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

#define CAP 256
static cj_isect res[CAP];

static qo_curve qc(const cj_bezier2 *c) {
    qo_curve q = {c->degree, c->pts, c->weights};
    return q;
}

/* The 256-bit root from the reported estimate lies in the enclosure. Returns 1 if so. */
static int root_inside(const cj_bezier2 *a, const cj_bezier2 *b, const cj_isect *r) {
    qo_curve A = qc(a), B = qc(b);
    mpfr_t s, t;
    mpfr_inits2(256, s, t, (mpfr_ptr)0);
    double resid = qo_newton(&A, &B, r->s, r->t, s, t), scale = 0.0;
    for (int i = 0; i <= a->degree; ++i)
        scale = fmax(scale, fmax(fabs(a->pts[2 * i]), fabs(a->pts[2 * i + 1])));
    int ok = resid <= 1e-60 * scale && mpfr_cmp_d(s, r->s_lo) >= 0 && mpfr_cmp_d(s, r->s_hi) <= 0 &&
             mpfr_cmp_d(t, r->t_lo) >= 0 && mpfr_cmp_d(t, r->t_hi) <= 0;
    if (!ok)
        printf("  root check: residual %g, s %.17g in [%.17g, %.17g]? t %.17g in [%.17g, %.17g]?\n",
               resid, mpfr_get_d(s, MPFR_RNDN), r->s_lo, r->s_hi, mpfr_get_d(t, MPFR_RNDN), r->t_lo,
               r->t_hi);
    mpfr_clears(s, t, (mpfr_ptr)0);
    return ok;
}

static int count_kind(const cj_isect *r, int n, cj_isect_kind k) {
    int c = 0;
    for (int i = 0; i < n; ++i) c += r[i].kind == k;
    return c;
}

/* ---- adversarial cases ------------------------------------------------------------------ */

static void test_tangencies(void) {
    double par[] = {-1, 1, 0, -1, 1, 1}; /* y = x^2, x = 2s - 1 */
    cj_bezier2 P = cj_bezier2_view(2, par, NULL);
    int checked = 0;
    for (int k = 0; k < 5; ++k) {
        double dy[] = {0.0, 1e-6, -1e-6, 1e-24, 0x1p-60};
        double seg[] = {-1, dy[k], 1, dy[k]};
        cj_bezier2 S = cj_bezier2_view(1, seg, NULL);
        int n = 0;
        cj_status st = cj_intersect_curves(&P, &S, 1e-9, res, CAP, &n);
        CHECK(st == CJ_OK, "tangency %d: %s", k, cj_last_error());
        if (k == 0) {
            CHECK(n == 1 && res[0].kind == CJ_ISECT_CONTACT && res[0].s_lo <= 0.5 &&
                      res[0].s_hi >= 0.5 && res[0].t_lo <= 0.5 && res[0].t_hi >= 0.5,
                  "exact tangency: %d results, first %s", n,
                  n ? cj_isect_kind_name(res[0].kind) : "-");
        } else if (k == 1) {
            CHECK(n == 2 && count_kind(res, n, CJ_ISECT_CROSSING) == 2,
                  "near-tangency 1e-6: %d results", n);
            for (int i = 0; i < n; ++i) CHECK(root_inside(&P, &S, &res[i]), "near-tangency root");
        } else if (k == 2) {
            CHECK(count_kind(res, n, CJ_ISECT_CROSSING) == 0, "miss by 1e-6: %d crossings", n);
        } else {
            /* roots at x = ±sqrt(dy): every one inside a reported box (crossings or a contact) */
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double x = sgn * sqrt(dy[k]), s = (x + 1) / 2, t = (x + 1) / 2;
                int in = 0;
                for (int i = 0; i < n; ++i)
                    in |= res[i].s_lo <= s && s <= res[i].s_hi && res[i].t_lo <= t &&
                          t <= res[i].t_hi;
                CHECK(in, "near-tangency dy=%g: root x=%g not covered (%d results)", dy[k], x, n);
            }
            CHECK(n >= 1 && n <= 2, "near-tangency dy=%g: %d results", dy[k], n);
        }
        ++checked;
    }
    printf("tangencies: %d cases (exact tangency a contact, 1e-6 two certified crossings, a "
           "miss by 1e-6 none, 1e-24 and 2^-60 covered)\n",
           checked);
}

static void test_joints_overlaps(void) {
    double a[] = {0, 0, 1, 2, 2, -1, 3, 1};
    cj_bezier2 A = cj_bezier2_view(3, a, NULL);
    int n;
    /* a transversal joint: exact corner */
    double j1[] = {3, 1, 4, 0, 5, 2};
    cj_bezier2 J1 = cj_bezier2_view(2, j1, NULL);
    CHECK(cj_intersect_curves(&A, &J1, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_CROSSING && res[0].s_lo == 1.0 && res[0].s_hi == 1.0 &&
              res[0].t_lo == 0.0 && res[0].t_hi == 0.0 && res[0].at_end,
          "transversal joint: %d results", n);
    /* a tangent (G1) joint: a contact holding the corner */
    double j2[] = {3, 1, 4, 3, 5, 0};
    cj_bezier2 J2 = cj_bezier2_view(2, j2, NULL);
    CHECK(cj_intersect_curves(&A, &J2, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_CONTACT && res[0].s_hi == 1.0 && res[0].t_lo == 0.0,
          "tangent joint: %d results", n);
    /* coincident: itself, reversed, a sub-piece, two overlapping sub-pieces */
    double rev[8], sub[8], left[8], right[8];
    for (int i = 0; i < 4; ++i) {
        rev[2 * i] = a[2 * (3 - i)];
        rev[2 * i + 1] = a[2 * (3 - i) + 1];
    }
    CHECK(cj_intersect_curves(&A, &A, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_OVERLAP && res[0].s_lo == 0 && res[0].s_hi == 1,
          "itself: %d results", n);
    cj_bezier2 R = cj_bezier2_view(3, rev, NULL);
    CHECK(cj_intersect_curves(&A, &R, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_OVERLAP, "reversed: %d results", n);
    /* sub-piece on [0.25, 0.75] by exact de Casteljau in binary fractions: written out */
    {
        double t0 = 0.25, t1 = 0.75; /* blossom: sub_i = blossom(t0 x (3-i), t1 x i) */
        for (int i = 0; i < 4; ++i) {
            double w[4][2];
            for (int j = 0; j < 4; ++j) {
                w[j][0] = a[2 * j];
                w[j][1] = a[2 * j + 1];
            }
            for (int r = 0; r < 3; ++r) {
                double u = r < 3 - i ? t0 : t1;
                for (int j = 0; j < 3 - r; ++j)
                    for (int k = 0; k < 2; ++k) w[j][k] = (1 - u) * w[j][k] + u * w[j + 1][k];
            }
            sub[2 * i] = w[0][0];
            sub[2 * i + 1] = w[0][1];
        }
    }
    cj_bezier2 S = cj_bezier2_view(3, sub, NULL);
    CHECK(cj_intersect_curves(&A, &S, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_OVERLAP && fabs(res[0].s_lo - 0.25) < 1e-9 &&
              fabs(res[0].s_hi - 0.75) < 1e-9 && res[0].deviation <= 1e-9,
          "sub-piece: %d results, first %s [%g, %g]", n, n ? cj_isect_kind_name(res[0].kind) : "",
          n ? res[0].s_lo : 0, n ? res[0].s_hi : 0);
    /* A on [0, 0.5] and A on [0.25, 1] overlap on s in [0.25, 0.5] */
    {
        for (int i = 0; i < 8; ++i) left[i] = right[i] = 0;
        double w[4][2];
        for (int j = 0; j < 4; ++j) w[j][0] = a[2 * j], w[j][1] = a[2 * j + 1];
        /* left half: de Casteljau at 1/2 */
        double l[4][2], tmp[4][2];
        memcpy(tmp, w, sizeof w);
        for (int k = 0; k < 2; ++k) l[0][k] = tmp[0][k];
        for (int r = 1; r <= 3; ++r) {
            for (int j = 0; j + r <= 3; ++j)
                for (int k = 0; k < 2; ++k) tmp[j][k] = 0.5 * (tmp[j][k] + tmp[j + 1][k]);
            for (int k = 0; k < 2; ++k) l[r][k] = tmp[0][k];
        }
        for (int i = 0; i < 4; ++i) left[2 * i] = l[i][0], left[2 * i + 1] = l[i][1];
        /* right part from 1/4: split at 1/4 */
        memcpy(tmp, w, sizeof w);
        double rr[4][2];
        for (int k = 0; k < 2; ++k) rr[3][k] = tmp[3][k];
        for (int r = 1; r <= 3; ++r) {
            for (int j = 0; j + r <= 3; ++j)
                for (int k = 0; k < 2; ++k) tmp[j][k] = 0.75 * tmp[j][k] + 0.25 * tmp[j + 1][k];
            for (int k = 0; k < 2; ++k) rr[3 - r][k] = tmp[3 - r][k];
        }
        for (int i = 0; i < 4; ++i) right[2 * i] = rr[i][0], right[2 * i + 1] = rr[i][1];
    }
    cj_bezier2 Lf = cj_bezier2_view(3, left, NULL), Rt = cj_bezier2_view(3, right, NULL);
    CHECK(cj_intersect_curves(&Lf, &Rt, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_OVERLAP && fabs(res[0].s_lo - 0.5) < 1e-8 &&
              fabs(res[0].s_hi - 1.0) < 1e-12 && fabs(res[0].t_lo) < 1e-12 &&
              fabs(res[0].t_hi - 1.0 / 3.0) < 1e-8,
          "partial overlap: %d results, first %s s [%g, %g] t [%g, %g]", n,
          n ? cj_isect_kind_name(res[0].kind) : "", n ? res[0].s_lo : 0, n ? res[0].s_hi : 0,
          n ? res[0].t_lo : 0, n ? res[0].t_hi : 0);
    printf("joints and overlaps: transversal joint exact, tangent joint a contact, itself, "
           "reversed, a sub-piece and a partial overlap each one overlap\n");
}

static void test_scales_and_kinds(void) {
    double a[] = {0, 0, 1, 2, 2, -1, 3, 1}, b[] = {0, 1, 1, -1, 2, 2, 3, 0};
    int checked = 0;
    for (int e = -4; e <= 2; ++e) {
        double f = pow(10.0, 75.0 * e), sa[8], sb[8];
        for (int i = 0; i < 8; ++i) sa[i] = a[i] * f, sb[i] = b[i] * f + 1e-3 * f;
        cj_bezier2 A = cj_bezier2_view(3, sa, NULL), B = cj_bezier2_view(3, sb, NULL);
        int n;
        CHECK(cj_intersect_curves(&A, &B, 1e-9 * f, res, CAP, &n) == CJ_OK, "scale %g: %s", f,
              cj_last_error());
        CHECK(n == 3 && count_kind(res, n, CJ_ISECT_CROSSING) == 3, "scale %g: %d results", f, n);
        for (int i = 0; i < n; ++i) {
            CHECK(root_inside(&A, &B, &res[i]), "scale %g root %d", f, i);
            ++checked;
        }
    }
    /* rational: quarter circle against the diagonal, root at s = 1/2, t = sqrt(2)/2 */
    double w[] = {1, 0.70710678118654752, 1}, circ[] = {1, 0, 1, 1, 0, 1}, ln[] = {0, 0, 1, 1};
    cj_bezier2 C = cj_bezier2_view(2, circ, w), L = cj_bezier2_view(1, ln, NULL);
    int n;
    CHECK(cj_intersect_curves(&C, &L, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_CROSSING && root_inside(&C, &L, &res[0]),
          "circle/diagonal: %d results", n);
    ++checked;
    /* the infinite line y = 0.5 against a: λ is the x coordinate */
    double p[2] = {0, 0.5}, d[2] = {1, 0}, line[] = {0, 0.5, 1, 0.5};
    cj_bezier2 A = cj_bezier2_view(3, a, NULL), Ln = cj_bezier2_view(1, line, NULL);
    CHECK(cj_intersect_line(&A, p, d, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 3, "line: %d results", n);
    for (int i = 0; i < n; ++i) {
        CHECK(res[i].kind == CJ_ISECT_CROSSING && root_inside(&A, &Ln, &res[i]), "line root %d", i);
        ++checked;
    }
    /* self-intersections: a loop, a cusp, a simple curve, a closed curve */
    double loop[] = {0, 0, 3, 3, -1, 3, 2, 0}, cusp[] = {0, 0, 2, 2, 0, 2, 2, 0};
    double simple[] = {0, 0, 1, 1, 2, -1, 3, 0}, closed[] = {0, 0, 2, 3, -2, 3, 0, 0};
    cj_bezier2 Lo = cj_bezier2_view(3, loop, NULL), Cu = cj_bezier2_view(3, cusp, NULL);
    cj_bezier2 Si = cj_bezier2_view(3, simple, NULL), Cl = cj_bezier2_view(3, closed, NULL);
    CHECK(cj_intersect_self(&Lo, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_CROSSING && root_inside(&Lo, &Lo, &res[0]) &&
              res[0].s_hi < res[0].t_lo,
          "loop: %d results", n);
    CHECK(cj_intersect_self(&Cu, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_CONTACT && res[0].s_lo <= 0.5 && res[0].t_hi >= 0.5,
          "cusp: %d results", n);
    CHECK(cj_intersect_self(&Si, 1e-9, res, CAP, &n) == CJ_OK && n == 0, "simple: %d results", n);
    CHECK(cj_intersect_self(&Cl, 1e-9, res, CAP, &n) == CJ_OK, "%s", cj_last_error());
    CHECK(n == 1 && res[0].kind == CJ_ISECT_CROSSING && res[0].s_lo == 0 && res[0].t_hi == 1,
          "closed: %d results", n);
    checked += 4;
    printf("scales 1e-300..1e150, rational arc, infinite line, self (loop, cusp, simple, "
           "closed): %d results checked against 256-bit Newton or by construction\n",
           checked);
}

static void test_bad_input(void) {
    double a[] = {0, 0, 1, 2, 2, -1, 3, 1}, nan_pts[] = {0, 0, 1, NAN, 2, 0};
    double pt[] = {1, 1, 1, 1, 1, 1}, w0[] = {1, 0, 1};
    cj_bezier2 A = cj_bezier2_view(3, a, NULL), N = cj_bezier2_view(2, nan_pts, NULL);
    cj_bezier2 P = cj_bezier2_view(2, pt, NULL), W = cj_bezier2_view(2, a, w0);
    cj_bezier2 D = cj_bezier2_view(CJ_QUERY_MAX_DEGREE + 1, a, NULL);
    int n;
    struct {
        cj_status st, want;
        const char *needle;
    } cases[] = {
        {cj_intersect_curves(&A, &N, 1e-9, res, CAP, &n), CJ_ERR_NONFINITE,
         "curve b: control point 1, coordinate 1 is NaN"},
        {cj_intersect_curves(&P, &A, 1e-9, res, CAP, &n), CJ_ERR_DEGENERATE, "curve a: all 3"},
        {cj_intersect_curves(&A, &W, 1e-9, res, CAP, &n), CJ_ERR_ARGUMENT, "curve b: weight 1"},
        {cj_intersect_curves(&A, &D, 1e-9, res, CAP, &n), CJ_ERR_DEGREE, "curve b: degree 49"},
        {cj_intersect_curves(&A, &A, 1e-20, res, CAP, &n), CJ_ERR_ARGUMENT, "tol 1e-20"},
        {cj_intersect_curves(&A, &A, NAN, res, CAP, &n), CJ_ERR_NONFINITE, "tol"},
        {cj_intersect_self(&P, 1e-9, res, CAP, &n), CJ_ERR_DEGENERATE, "curve: all"},
        {cj_intersect_line(&A, (double[]){0, 0}, (double[]){0, 0}, 1e-9, res, CAP, &n),
         CJ_ERR_DEGENERATE, "line direction"},
    };
    int nc = (int)(sizeof cases / sizeof cases[0]);
    for (int i = 0; i < nc; ++i) {
        CHECK(cases[i].st == cases[i].want, "bad input %d: status %d, want %d", i, cases[i].st,
              cases[i].want);
    }
    /* messages: re-run each to read its own message */
    cj_intersect_curves(&A, &N, 1e-9, res, CAP, &n);
    CHECK(strstr(cj_last_error(), cases[0].needle), "message '%s'", cj_last_error());
    cj_intersect_curves(&A, &A, 1e-20, res, CAP, &n);
    CHECK(strstr(cj_last_error(), "below what doubles resolve"), "message '%s'", cj_last_error());
    printf("bad input: %d cases refused with the right status, messages name the input\n", nc);
}

/* ---- random pairs ----------------------------------------------------------------------- */

static void random_curve(cj_rng *r, int n, double f, double off, double *pts) {
    for (int i = 0; i <= n; ++i) {
        pts[2 * i] = (cj_rng_unit(r) + off) * f;
        pts[2 * i + 1] = (cj_rng_unit(r) + off) * f;
    }
}

/* Matches the oracle's crossings to the reported results; 1 if they agree. */
static int agree(const cj_isect *r, int n, const double *st, int no, double slack) {
    int used[CAP] = {0};
    if (count_kind(r, n, CJ_ISECT_CROSSING) != no) return 0;
    for (int i = 0; i < no; ++i) {
        int best = -1;
        double bd = slack;
        for (int j = 0; j < n; ++j) {
            if (used[j] || r[j].kind != CJ_ISECT_CROSSING) continue;
            double d = fabs(r[j].s - st[2 * i]) + fabs(r[j].t - st[2 * i + 1]);
            if (d <= bd) bd = d, best = j;
        }
        if (best < 0) return 0;
        used[best] = 1;
    }
    return 1;
}

static void test_random_pairs(uint64_t seed, long npairs) {
    cj_rng r;
    cj_rng_init(&r, seed);
    long crossings = 0, contacts = 0, refined = 0, dup = 0, missed = 0, extra = 0, roots = 0;
    long highdeg = 0, nrational = 0;
    double maxw = 0.0;
    static double st[2 * 4096];
    for (long k = 0; k < npairs; ++k) {
        int na = 3, nb = 3;
        if (k % 8 == 7) na = cj_rng_int(&r, 1, 7), nb = cj_rng_int(&r, 1, 7);
        if (k % 1000 == 999) na = cj_rng_int(&r, 12, 24), nb = cj_rng_int(&r, 12, 24), ++highdeg;
        double f = 1.0, off = 0.0;
        if (k % 4 == 3) f = ldexp(1.0, cj_rng_int(&r, -400, 400)), off = cj_rng_range(&r, -8, 8);
        double a[2 * 25], b[2 * 25], wa[25], wb[25];
        random_curve(&r, na, f, off, a);
        random_curve(&r, nb, f, off, b);
        int rational = k % 8 == 5;
        for (int i = 0; i <= na; ++i) wa[i] = rational ? cj_rng_range(&r, 0.3, 3.0) : 1.0;
        for (int i = 0; i <= nb; ++i) wb[i] = rational ? cj_rng_range(&r, 0.3, 3.0) : 1.0;
        nrational += rational;
        cj_bezier2 A = cj_bezier2_view(na, a, rational ? wa : NULL);
        cj_bezier2 B = cj_bezier2_view(nb, b, rational ? wb : NULL);
        int n = 0;
        cj_status s = cj_intersect_curves(&A, &B, 1e-9 * f * (1 + fabs(off)), res, CAP, &n);
        if (s != CJ_OK) {
            CHECK(0, "pair %ld: %s", k, cj_last_error());
            continue;
        }
        crossings += count_kind(res, n, CJ_ISECT_CROSSING);
        contacts += count_kind(res, n, CJ_ISECT_CONTACT);
        for (int i = 0; i + 1 < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (fabs(res[i].s - res[j].s) < 1e-12 && fabs(res[i].t - res[j].t) < 1e-12) ++dup;
        for (int i = 0; i < n; ++i) {
            if (res[i].kind != CJ_ISECT_CROSSING) continue;
            maxw = fmax(maxw, fmax(res[i].s_hi - res[i].s_lo, res[i].t_hi - res[i].t_lo));
            if (k % 10 == 0 || na > 7 || rational) {
                CHECK(root_inside(&A, &B, &res[i]), "pair %ld (seed %llu) root %d", k,
                      (unsigned long long)seed, i);
                ++roots;
            }
        }
        qo_curve QA = qc(&A), QB = qc(&B);
        double eb;
        int N = na > 7 || nb > 7 ? 1024 : 128;
        int no = qo_polyline_crossings(&QA, &QB, N, st, 4096, &eb);
        if (agree(res, n, st, no, 0.05)) continue;
        ++refined;
        no = qo_polyline_crossings(&QA, &QB, 16 * N, st, 4096, &eb);
        if (agree(res, n, st, no, 0.01)) continue;
        int nc = count_kind(res, n, CJ_ISECT_CROSSING);
        if (no > nc + count_kind(res, n, CJ_ISECT_CONTACT) * 2)
            ++missed;
        else if (no < nc)
            ++extra;
        else
            continue; /* a contact standing for oracle crossings: allowed */
        CHECK(0, "pair %ld (seed %llu): oracle %d crossings, reported %d results", k,
              (unsigned long long)seed, no, n);
    }
    CHECK(dup == 0, "%ld duplicated results", dup);
    CHECK(maxw < 1e-10, "widest crossing enclosure %g", maxw);
    printf(
        "random pairs: %ld pairs (%ld of high degree 12..24, %ld rational, a quarter scaled "
        "by 2^-400..2^400), %ld crossings, %ld contacts; polyline oracle agreed on all (%ld after "
        "refining it 16x); %ld missed, %ld extra, %ld duplicated; %ld roots inside their "
        "enclosures by 256-bit Newton; widest enclosure %.3g\n",
        npairs, highdeg, nrational, crossings, contacts, refined, missed, extra, dup, roots, maxw);
}

static void test_random_self(uint64_t seed, int ncurves) {
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x5e1f);
    long loops = 0, contacts = 0, roots = 0, refined = 0;
    static double st[2 * 256];
    for (int k = 0; k < ncurves; ++k) {
        int n = k % 4 == 3 ? 5 : 3;
        double a[12];
        random_curve(&r, n, 1.0, 0.0, a);
        cj_bezier2 A = cj_bezier2_view(n, a, NULL);
        int cnt = 0;
        cj_status s = cj_intersect_self(&A, 1e-9, res, CAP, &cnt);
        if (s != CJ_OK) {
            CHECK(0, "self %d: %s", k, cj_last_error());
            continue;
        }
        loops += count_kind(res, cnt, CJ_ISECT_CROSSING);
        contacts += count_kind(res, cnt, CJ_ISECT_CONTACT);
        for (int i = 0; i < cnt; ++i)
            if (res[i].kind == CJ_ISECT_CROSSING) {
                CHECK(res[i].s_hi < res[i].t_lo && root_inside(&A, &A, &res[i]),
                      "self %d (seed %llu) root %d", k, (unsigned long long)seed, i);
                ++roots;
            }
        qo_curve Q = qc(&A);
        double eb;
        int no = qo_polyline_self_crossings(&Q, 256, st, 256, &eb);
        if (agree(res, cnt, st, no, 0.05)) continue;
        ++refined;
        no = qo_polyline_self_crossings(&Q, 4096, st, 256, &eb);
        if (agree(res, cnt, st, no, 0.01)) continue;
        if (count_kind(res, cnt, CJ_ISECT_CONTACT) > 0) continue; /* a cusp-like unresolved piece */
        CHECK(0, "self %d (seed %llu): oracle %d self-crossings, reported %d results", k,
              (unsigned long long)seed, no, cnt);
    }
    printf("random self-intersections: %d curves (cubics, quintics), %ld crossings (each root "
           "inside its enclosure by 256-bit Newton), %ld contacts; polyline oracle agreed on all "
           "(%ld after refining it 16x)\n",
           ncurves, loops, contacts, refined);
}

/* The search runs code instantiated for cubics and quadratics (constant degrees, unrolled):
 * every mix of the two, every crossing's root checked inside its enclosure by 256-bit Newton,
 * counts against the polyline oracle. */
static void test_small_degrees(uint64_t seed, int npairs) {
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x3c2);
    long crossings = 0, contacts = 0, roots = 0, mixes[2][2] = {{0, 0}, {0, 0}};
    static double st[2 * 4096];
    for (int k = 0; k < npairs; ++k) {
        int na = cj_rng_int(&r, 2, 3), nb = cj_rng_int(&r, 2, 3);
        ++mixes[na - 2][nb - 2];
        double a[8], b[8];
        random_curve(&r, na, 1.0, 0.0, a);
        random_curve(&r, nb, 1.0, 0.0, b);
        cj_bezier2 A = cj_bezier2_view(na, a, NULL), B = cj_bezier2_view(nb, b, NULL);
        int n = 0;
        cj_status s = cj_intersect_curves(&A, &B, 1e-9, res, CAP, &n);
        if (s != CJ_OK) {
            CHECK(0, "small pair %d: %s", k, cj_last_error());
            continue;
        }
        crossings += count_kind(res, n, CJ_ISECT_CROSSING);
        contacts += count_kind(res, n, CJ_ISECT_CONTACT);
        for (int i = 0; i + 1 < n; ++i)
            for (int j = i + 1; j < n; ++j)
                CHECK(!(fabs(res[i].s - res[j].s) < 1e-12 && fabs(res[i].t - res[j].t) < 1e-12),
                      "small pair %d (seed %llu): results %d and %d duplicated", k,
                      (unsigned long long)seed, i, j);
        for (int i = 0; i < n; ++i) {
            if (res[i].kind != CJ_ISECT_CROSSING) continue;
            CHECK(root_inside(&A, &B, &res[i]), "small pair %d (seed %llu) root %d", k,
                  (unsigned long long)seed, i);
            ++roots;
        }
        qo_curve QA = qc(&A), QB = qc(&B);
        double eb;
        int no = qo_polyline_crossings(&QA, &QB, 128, st, 4096, &eb);
        if (agree(res, n, st, no, 0.05)) continue;
        no = qo_polyline_crossings(&QA, &QB, 2048, st, 4096, &eb);
        if (agree(res, n, st, no, 0.01)) continue;
        int nx = count_kind(res, n, CJ_ISECT_CROSSING), nt = count_kind(res, n, CJ_ISECT_CONTACT);
        if (nt > 0 && no >= nx && no <= nx + 2 * nt)
            continue; /* a contact standing for oracle crossings: allowed */
        CHECK(0, "small pair %d (seed %llu): oracle %d crossings, reported %d results", k,
              (unsigned long long)seed, no, n);
    }
    printf("quadratics and cubics: %d pairs (2x2 %ld, 2x3 %ld, 3x2 %ld, 3x3 %ld), %ld crossings "
           "(%ld roots inside their enclosures by 256-bit Newton), %ld contacts, none duplicated; "
           "polyline oracle agreed on all\n",
           npairs, mixes[0][0], mixes[0][1], mixes[1][0], mixes[1][1], crossings, roots, contacts);
}

int main(void) {
    uint64_t seed = cj_test_seed("test_intersect", 23);
    const char *np = getenv("CJ_QUERY_PAIRS");
    long npairs = np ? atol(np) : 100000;
    test_tangencies();
    test_joints_overlaps();
    test_scales_and_kinds();
    test_bad_input();
    test_random_pairs(seed, npairs);
    test_small_degrees(seed, 5000);
    test_random_self(seed, 5000);
    printf("test_intersect: %s (%d failures)\n", failures ? "FAILED" : "passed", failures);
    return failures ? 1 : 0;
}
