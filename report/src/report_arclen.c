/* casteljau report, section "arc length": cj_bezier_arclength (adaptive Gauss-Kronrod 7/15) at
 * tolerances 1e-2 .. 1e-12 against the chord sum of N uniform parameter steps, on two sets of
 * 8 fixed curves:
 *  - parabolas (quadratic Béziers: 4 random, 4 sharp turns), reference the closed form of
 *    ∫ sqrt(a t² + b t + c) dt evaluated in long double (its own error ~1e-18 of the length);
 *  - cubics (5 random, a near-cusp, a loop, an S), reference an MPFR quadrature with a proven
 *    error bound (cubic_length below: composite Gauss-Legendre, 48 nodes per panel, 256 bits,
 *    panels halved until the speed's nearest complex root lies outside the Bernstein ellipse
 *    E_4 of the panel; ~1e-46 per panel).
 * Both references are far below every tolerance measured. Per choice: max and mean absolute
 * error over the curves, the largest error estimate the function returned, ns per call (median
 * of interleaved runs), and in the full report instructions per call by callgrind (workload
 * "arclen:all": all cells in one run, report_cgbatch.c). Pareto fronts per set. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/bezier.h"

#include <complex.h>
#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <string.h>

#define NCURVE 8
static double curves[NCURVE][6], cubics[NCURVE][8];

/* Fixed parabolas: four from a seeded LCG (the report must be the same every run) with the
 * middle point pushed off the chord, and four sharp turns (ends 2d apart, apex 1 away, d =
 * 1e-1 .. 1e-4), where the speed nearly vanishes at the apex and the quadrature must refine. */
static void make_curves(void) {
    unsigned long s = 12345;
    for (int k = 0; k < NCURVE / 2; ++k) {
        for (int i = 0; i < 6; ++i) {
            s = s * 6364136223846793005UL + 1442695040888963407UL;
            curves[k][i] = (double)(s >> 11) / 9007199254740992.0;
        }
        const double dx = curves[k][4] - curves[k][0], dy = curves[k][5] - curves[k][1];
        curves[k][2] = 0.5 * (curves[k][0] + curves[k][4]) - 0.6 * dy;
        curves[k][3] = 0.5 * (curves[k][1] + curves[k][5]) + 0.6 * dx;
    }
    double d = 1e-1;
    for (int k = NCURVE / 2; k < NCURVE; ++k, d *= 0.1) {
        const double p[6] = {0.5 - d, 0.0, 0.5, 1.0, 0.5 + d, 0.0};
        for (int i = 0; i < 6; ++i) curves[k][i] = p[i];
    }
    /* cubics: five random ones in the unit square, then a near-cusp (the speed nearly vanishes
     * at t ≈ 0.500016: the nearest root of |c'|² is 4.9e-10 off the real axis), a loop and an
     * S (the first two as in the flattening section) */
    for (int k = 0; k < 5; ++k)
        for (int i = 0; i < 8; ++i) {
            s = s * 6364136223846793005UL + 1442695040888963407UL;
            cubics[k][i] = (double)(s >> 11) / 9007199254740992.0;
        }
    static const double special[3][8] = {{0.1, 0.1, 0.9, 0.9, 0.1, 0.9, 0.9, 0.1001},
                                         {0.1, 0.5, 1.0, 1.0, 0.0, 1.0, 0.9, 0.5},
                                         {0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0}};
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 8; ++i) cubics[5 + k][i] = special[k][i];
}

/* Exact length of a quadratic Bézier: c'(t) = A + B t, A = 2(P1 - P0), B = 2(P2 - 2P1 + P0);
 * |c'|² = a t² + b t + c with a = |B|², b = 2 A·B, c = |A|². With u = t + b/(2a) and
 * k = c/a - u0² = (A x B)² / a² >= 0 (computed from the cross product: no cancellation): ∫ sqrt(a)
 * sqrt(u² + k) du = sqrt(a)/2 [u r + k asinh(u / sqrt k)]. */
static long double exact_length(const double *p) {
    const long double Ax = 2.0L * ((long double)p[2] - p[0]),
                      Ay = 2.0L * ((long double)p[3] - p[1]);
    const long double Bx = 2.0L * ((long double)p[4] - 2.0L * p[2] + p[0]),
                      By = 2.0L * ((long double)p[5] - 2.0L * p[3] + p[1]);
    const long double a = Bx * Bx + By * By, b = 2 * (Ax * Bx + Ay * By), c = Ax * Ax + Ay * Ay;
    const long double u0 = b / (2 * a), cr = Ax * By - Ay * Bx, k = cr * cr / (a * a),
                      sk = sqrtl(k);
    (void)c;
    long double F[2];
    for (int e = 0; e < 2; ++e) {
        const long double u = e + u0;
        F[e] = u * sqrtl(u * u + k) + k * asinhl(u / sk);
    }
    return sqrtl(a) / 2 * (F[1] - F[0]);
}

/* ---- the MPFR oracle for the length of a planar cubic --------------------------------------
 * L = ∫_0^1 sqrt(q(t)) dt, q = x'² + y'² (a quartic; x', y' quadratics with exact monomial
 * coefficients). q = (x' + i y')(x' − i y') vanishes only at the two roots z of x' + i y' and
 * their conjugates, so on a panel [m − h, m + h] sqrt(q) is analytic inside the Bernstein
 * ellipse E_ρ0 (foci the panel's ends) through the nearest root, and on E_ρ, ρ < ρ0, it is
 * bounded by M = sqrt(X² + Y²), X = |x'(m)| + |x''(m)| h R + |a2| h² R² (Taylor at m; R = (ρ +
 * 1/ρ)/2 bounds |s| on E_ρ, t = m + h s), Y likewise. The n-point Gauss-Legendre rule then errs
 * by at most h · 64 M / (15 (ρ² − 1) ρ^(2n)) (Trefethen, Approximation Theory and Approximation
 * Practice, Thm 19.3). Panels are halved until ρ0 >= 4; then ρ = 3, n = 48: 3^-96 ≈ 1.6e-46,
 * so each panel's bound is ~1e-46 M h. The nodes and weights come from Newton's method on P_48
 * at 256 bits (converged to 2^-240); the sums are rounded at 256 bits. The result is returned
 * in long double (rounding 2^-64 of L, ~1e-19), with the summed quadrature bound. */
#define GL_N    48
#define GL_PREC 256
static mpfr_t gl_x[GL_N], gl_w[GL_N];
static int gl_ready;

static void gl_init(void) {
    if (gl_ready) return;
    mpfr_t x, p0, p1, p2, dp, dx;
    mpfr_inits2(GL_PREC, x, p0, p1, p2, dp, dx, (mpfr_ptr)0);
    for (int i = 0; i < GL_N; ++i) {
        mpfr_set_d(x, cos(3.14159265358979323846 * (i + 0.75) / (GL_N + 0.5)), MPFR_RNDN);
        for (int it = 0; it < 100; ++it) {
            mpfr_set_ui(p0, 1, MPFR_RNDN); /* P_0, P_1, ..., P_n by the three-term recurrence */
            mpfr_set(p1, x, MPFR_RNDN);
            for (int k = 2; k <= GL_N; ++k) {
                mpfr_mul(p2, x, p1, MPFR_RNDN);
                mpfr_mul_ui(p2, p2, (unsigned long)(2 * k - 1), MPFR_RNDN);
                mpfr_mul_ui(dx, p0, (unsigned long)(k - 1), MPFR_RNDN);
                mpfr_sub(p2, p2, dx, MPFR_RNDN);
                mpfr_div_ui(p2, p2, (unsigned long)k, MPFR_RNDN);
                mpfr_set(p0, p1, MPFR_RNDN);
                mpfr_set(p1, p2, MPFR_RNDN);
            }
            /* P_n' = n (x P_n − P_{n−1}) / (x² − 1) */
            mpfr_mul(dp, x, p1, MPFR_RNDN);
            mpfr_sub(dp, dp, p0, MPFR_RNDN);
            mpfr_mul_ui(dp, dp, GL_N, MPFR_RNDN);
            mpfr_sqr(dx, x, MPFR_RNDN);
            mpfr_sub_ui(dx, dx, 1, MPFR_RNDN);
            mpfr_div(dp, dp, dx, MPFR_RNDN);
            mpfr_div(dx, p1, dp, MPFR_RNDN);
            mpfr_sub(x, x, dx, MPFR_RNDN);
            if (mpfr_zero_p(dx) || mpfr_get_exp(dx) < -240) break;
        }
        mpfr_init2(gl_x[i], GL_PREC);
        mpfr_init2(gl_w[i], GL_PREC);
        mpfr_set(gl_x[i], x, MPFR_RNDN);
        /* w = 2 / ((1 − x²) P_n'(x)²), with P_n' from the last iteration (x moved by < 2^-240) */
        mpfr_sqr(dx, x, MPFR_RNDN);
        mpfr_ui_sub(dx, 1, dx, MPFR_RNDN);
        mpfr_sqr(p2, dp, MPFR_RNDN);
        mpfr_mul(dx, dx, p2, MPFR_RNDN);
        mpfr_ui_div(gl_w[i], 2, dx, MPFR_RNDN);
    }
    mpfr_clears(x, p0, p1, p2, dp, dx, (mpfr_ptr)0);
    gl_ready = 1;
}

typedef struct cubic_oracle {
    double a[3], b[3];      /* x' = a0 + a1 t + a2 t², y' likewise, rounded to double */
    double complex root[2]; /* roots of x' + i y' (NAN when absent) */
    mpfr_t ma[3], mb[3], t, u, v, sum;
    double bound;
    int panels;
} cubic_oracle;

/* Bernstein-ellipse parameter of the panel [m − h, m + h] through the point z. */
static double ellipse_rho(double complex z, double m, double h) {
    const double complex w = (z - m) / h, r = csqrt(w - 1) * csqrt(w + 1);
    return fmax(cabs(w + r), cabs(w - r));
}

static int cubic_panel(cubic_oracle *o, double m, double h, int depth) {
    double rho0 = INFINITY;
    for (int k = 0; k < 2; ++k)
        if (isfinite(creal(o->root[k]))) rho0 = fmin(rho0, ellipse_rho(o->root[k], m, h));
    if (rho0 < 4) {
        if (depth >= 60) return -1; /* a root on the interval: a true cusp */
        return cubic_panel(o, m - h / 2, h / 2, depth + 1) ||
               cubic_panel(o, m + h / 2, h / 2, depth + 1);
    }
    const double rho = 3, R = (rho + 1 / rho) / 2;
    const double X = fabs(o->a[0] + o->a[1] * m + o->a[2] * m * m) +
                     fabs(o->a[1] + 2 * o->a[2] * m) * h * R + fabs(o->a[2]) * h * h * R * R;
    const double Y = fabs(o->b[0] + o->b[1] * m + o->b[2] * m * m) +
                     fabs(o->b[1] + 2 * o->b[2] * m) * h * R + fabs(o->b[2]) * h * h * R * R;
    const double M = 1.000001 * sqrt(X * X + Y * Y);
    o->bound += h * 64 * M / (15 * (rho * rho - 1) * pow(rho, 2 * GL_N));
    o->panels++;
    for (int i = 0; i < GL_N; ++i) { /* sum += h w_i sqrt(x'(t)² + y'(t)²), t = m + h x_i */
        mpfr_mul_d(o->t, gl_x[i], h, MPFR_RNDN);
        mpfr_add_d(o->t, o->t, m, MPFR_RNDN);
        mpfr_fma(o->u, o->ma[2], o->t, o->ma[1], MPFR_RNDN);
        mpfr_fma(o->u, o->u, o->t, o->ma[0], MPFR_RNDN);
        mpfr_fma(o->v, o->mb[2], o->t, o->mb[1], MPFR_RNDN);
        mpfr_fma(o->v, o->v, o->t, o->mb[0], MPFR_RNDN);
        mpfr_hypot(o->u, o->u, o->v, MPFR_RNDN);
        mpfr_mul(o->u, o->u, gl_w[i], MPFR_RNDN);
        mpfr_mul_d(o->u, o->u, h, MPFR_RNDN);
        mpfr_add(o->sum, o->sum, o->u, MPFR_RNDN);
    }
    return 0;
}

/* Length of the cubic p (4 planar points) into *len, the quadrature's proven error bound into
 * *bound; -1 when the speed vanishes on [0, 1] (not analytic there). */
static int cubic_length(const double *p, long double *len, double *bound, int *panels) {
    gl_init();
    cubic_oracle o;
    /* c' = 3[d0 + 2t(d1 − d0) + t²(d0 − 2 d1 + d2)], d_i = P_{i+1} − P_i; the coefficients are
     * formed at 256 bits (exact: sums of a few doubles) and rounded to double only to place the
     * roots and bound M, where a relative 1e-16 does not matter */
    mpfr_inits2(GL_PREC, o.t, o.u, o.v, o.sum, (mpfr_ptr)0);
    for (int c = 0; c < 2; ++c) {
        mpfr_t *co = c ? o.mb : o.ma;
        double *cd = c ? o.b : o.a;
        for (int j = 0; j < 3; ++j) mpfr_init2(co[j], GL_PREC);
        mpfr_set_d(o.t, p[2 + c], MPFR_RNDN);
        mpfr_sub_d(co[0], o.t, p[c], MPFR_RNDN); /* d0 */
        mpfr_set_d(o.u, p[4 + c], MPFR_RNDN);
        mpfr_sub_d(o.u, o.u, p[2 + c], MPFR_RNDN); /* d1 */
        mpfr_set_d(o.v, p[6 + c], MPFR_RNDN);
        mpfr_sub_d(o.v, o.v, p[4 + c], MPFR_RNDN); /* d2 */
        mpfr_sub(co[1], o.u, co[0], MPFR_RNDN);    /* d1 − d0 */
        mpfr_sub(co[2], o.v, o.u, MPFR_RNDN);      /* d2 − d1 */
        mpfr_sub(co[2], co[2], co[1], MPFR_RNDN);  /* d0 − 2 d1 + d2 */
        mpfr_mul_ui(co[0], co[0], 3, MPFR_RNDN);
        mpfr_mul_ui(co[1], co[1], 6, MPFR_RNDN);
        mpfr_mul_ui(co[2], co[2], 3, MPFR_RNDN);
        for (int j = 0; j < 3; ++j) cd[j] = mpfr_get_d(co[j], MPFR_RNDN);
    }
    const double complex A = o.a[2] + I * o.b[2], B = o.a[1] + I * o.b[1], C = o.a[0] + I * o.b[0];
    o.root[0] = o.root[1] = NAN;
    if (cabs(A) > 0) {
        const double complex D = csqrt(B * B - 4 * A * C);
        const double complex q = -0.5 * (cabs(B + D) >= cabs(B - D) ? B + D : B - D);
        if (cabs(q) > 0)
            o.root[0] = q / A, o.root[1] = C / q;
        else
            o.root[0] = o.root[1] = 0; /* B = C = 0: a double root at 0 */
    } else if (cabs(B) > 0) {
        o.root[0] = -C / B;
    }
    o.bound = 0, o.panels = 0;
    mpfr_set_ui(o.sum, 0, MPFR_RNDN);
    const int st = cubic_panel(&o, 0.5, 0.5, 0);
    *len = mpfr_get_ld(o.sum, MPFR_RNDN);
    *bound = o.bound;
    *panels = o.panels;
    mpfr_clears(o.t, o.u, o.v, o.sum, o.ma[0], o.ma[1], o.ma[2], o.mb[0], o.mb[1], o.mb[2],
                (mpfr_ptr)0);
    return st;
}

static double chord_sum(const cj_bezier *c, int N) {
    double prev[2], q[2], len = 0;
    cj_bezier_eval(c, CJ_EVAL_DECASTELJAU, 0.0, prev);
    for (int i = 1; i <= N; ++i) {
        cj_bezier_eval(c, CJ_EVAL_DECASTELJAU, (double)i / N, q);
        len += hypot(q[0] - prev[0], q[1] - prev[1]);
        prev[0] = q[0], prev[1] = q[1];
    }
    return len;
}

enum { NSET = 2, NP = 6 };
static const char *const SETNAME[NSET] = {"parabolas", "cubics"};

static cj_bezier set_curve(int set, int k) {
    return set ? cj_bezier_view(3, 2, cubics[k]) : cj_bezier_view(2, 2, curves[k]);
}

/* One measured call: method 0 cj_bezier_arclength at tol p, 1 the chord sum of p steps. */
static cj_status one_length(const cj_bezier *c, int m, double p, double *L, double *e) {
    *e = 0;
    if (m) {
        *L = chord_sum(c, (int)p);
        return CJ_OK;
    }
    const cj_status st = cj_bezier_arclength(c, 0, 1, p, L, e);
    return st == CJ_ERR_CAP ? CJ_OK : st; /* CAP: best value, its estimate above tol */
}

static const double TOL_FULL[NP] = {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12};
static const int N_FULL[NP] = {8, 32, 128, 512, 2048, 8192};

/* Cell i of the full table (set i / 12, method (i / 6) % 2, parameter i % 6): `units` calls,
 * the curves in turn. */
static int arclen_cell(void *ctx, int i, long units) {
    (void)ctx;
    const int set = i / (2 * NP), m = (i / NP) % 2, p = i % NP;
    const double prm = m ? (double)N_FULL[p] : TOL_FULL[p];
    volatile double sink = 0;
    for (long k = 0; k < units; ++k) {
        const cj_bezier c = set_curve(set, (int)(k % NCURVE));
        double L = 0, e = 0;
        if (one_length(&c, m, prm, &L, &e)) return 1;
        sink += L;
    }
    (void)sink;
    return 0;
}

/* n calls (the curves in turn, so 8 units are the table's mean over them): "arclen:0:TOL[:SET]"
 * is cj_bezier_arclength at tolerance TOL, "arclen:1:N[:SET]" the chord sum of N steps; SET 0
 * parabolas (default), 1 cubics; "arclen:all": every cell of the full table
 * (report_cells_workload). */
int report_arclen_workload(const char *spec, long n) {
    if (!strcmp(spec, "arclen:all")) {
        make_curves();
        return report_cells_workload(NSET * 2 * NP, n, arclen_cell, NULL);
    }
    int m = -1, set = 0;
    double p = 0;
    if (sscanf(spec, "arclen:%d:%lf:%d", &m, &p, &set) < 2 || m < 0 || m > 1 || set < 0 ||
        set >= NSET || (m == 0 && !(p >= 1e-15 && p <= 1)) || (m == 1 && !(p >= 1 && p <= 1 << 20)))
        return report_fail("bad workload '%s' (arclen:0:TOL[:SET] or arclen:1:N[:SET])", spec);
    make_curves();
    volatile double sink = 0;
    for (long k = 0; k < n; ++k) {
        const cj_bezier c = set_curve(set, (int)(k % NCURVE));
        double L = 0, e = 0;
        if (one_length(&c, m, p, &L, &e)) return 1;
        sink += L;
    }
    (void)sink;
    return 0;
}

typedef struct arc_cell {
    double ns, spread, emax, emean, est, instr;
} arc_cell;

int report_arclen(report *r) {
    make_curves();
    long double ref[NSET][NCURVE];
    double oracle_bound = 0;
    int max_panels = 0;
    for (int k = 0; k < NCURVE; ++k) {
        ref[0][k] = exact_length(curves[k]);
        double b = 0;
        int panels = 0;
        if (cubic_length(cubics[k], &ref[1][k], &b, &panels))
            return report_error("arc length: the oracle failed on cubic %d", k);
        oracle_bound = fmax(oracle_bound, b),
        max_panels = panels > max_panels ? panels : max_panels;
    }
    static const double TOL_QUICK[] = {1e-3, 1e-6, 1e-9};
    static const int N_QUICK[] = {16, 256, 4096};
    const double *tols = r->quick ? TOL_QUICK : TOL_FULL;
    const int *Ns = r->quick ? N_QUICK : N_FULL;
    const int np = r->quick ? 3 : 6, runs = r->quick ? 5 : 15, reps = r->quick ? 20 : 200;
    static arc_cell C[NSET][2][NP];
    /* instructions per call, every cell in one callgrind run (8 calls each: every curve once) */
    double cells[NSET * 2 * NP];
    for (int i = 0; i < NSET * 2 * NP; ++i) cells[i] = NAN;
    if (!r->quick) report_callgrind_cells(r, "arclen:all", NCURVE, NSET * 2 * NP, cells);
    for (int set = 0; set < NSET; ++set)
        for (int p = 0; p < np; ++p) {
            double tm[2][16];
            volatile double sink = 0;
            for (int run = 0; run < runs; ++run)
                for (int m = 0; m < 2; ++m) {
                    const double prm = m ? (double)Ns[p] : tols[p], t0 = report_now_ns();
                    for (int rep = 0; rep < reps; ++rep)
                        for (int k = 0; k < NCURVE; ++k) {
                            const cj_bezier c = set_curve(set, k);
                            double L = 0, e = 0;
                            if (one_length(&c, m, prm, &L, &e))
                                return report_error("arc length: %s", cj_last_error());
                            sink += L;
                        }
                    tm[m][run] = (report_now_ns() - t0) / (double)(reps * NCURVE);
                }
            (void)sink;
            for (int m = 0; m < 2; ++m) {
                arc_cell *e = &C[set][m][p];
                const double prm = m ? (double)Ns[p] : tols[p];
                e->ns = report_median(tm[m], (size_t)runs, &e->spread);
                e->instr = cells[(set * 2 + m) * NP + p];
                e->emax = e->emean = 0, e->est = m ? NAN : 0;
                for (int k = 0; k < NCURVE; ++k) {
                    const cj_bezier c = set_curve(set, k);
                    double L = 0, est = 0;
                    if (one_length(&c, m, prm, &L, &est))
                        return report_error("arc length: %s", cj_last_error());
                    const double err = (double)fabsl((long double)L - ref[set][k]);
                    e->emax = fmax(e->emax, err), e->emean += err / NCURVE;
                    if (m == 0) e->est = fmax(e->est, est);
                }
            }
        }
    static const char *const NAME[2] = {"adaptive G-K 7/15", "chord sum"};
    double cost[NSET][2 * NP], err[NSET][2 * NP];
    int dom[NSET][2 * NP];
    for (int set = 0; set < NSET; ++set) {
        for (int m = 0; m < 2; ++m)
            for (int p = 0; p < np; ++p)
                cost[set][m * np + p] = C[set][m][p].ns,
                                   err[set][m * np + p] = fmax(C[set][m][p].emax, 1e-300);
        report_pareto((size_t)(2 * np), cost[set], err[set], dom[set]);
    }
    fprintf(r->html,
            "<h2>Arc length</h2>\n<p>Two sets of %d curves. Parabolas (quadratic B&eacute;ziers: "
            "4 random in the unit square, 4 sharp turns with the ends 2d apart, d = 1e-1 .. "
            "1e-4), reference the closed form of &int;&radic;(at&sup2;+bt+c) in long double. "
            "Cubics (5 random in the unit square, a near-cusp, a loop, an S), reference an MPFR "
            "quadrature (composite 48-point Gauss&ndash;Legendre at 256 bits, panels halved until "
            "the Bernstein-ellipse bound of each is below ~1e-46 of its length; at most %d "
            "panels) whose proven error is at most %.1e, in long double. cj_bezier_arclength at "
            "absolute tolerances against the chord sum of N uniform steps. Error: max |L &minus; "
            "exact| over the curves; estimate: the largest error estimate returned. Pareto front "
            "per set (cost ns/call, error max).</p>\n"
            "<table><tr><th class=l>method</th><th>tol / N</th><th>max err</th><th>mean err</th>"
            "<th>estimate</th><th>ns/call</th><th>spread</th><th>instr/call</th>"
            "<th class=l>Pareto</th></tr>\n",
            NCURVE, max_panels, oracle_bound);
    fprintf(r->md,
            "## Arc length (parabolas, cubics)\n\n| method | tol / N | max err | mean err | "
            "estimate | ns/call | instr/call | Pareto |\n|---|---|---|---|---|---|---|---|\n");
    for (int set = 0; set < NSET; ++set)
        for (int m = 0; m < 2; ++m)
            for (int p = 0; p < np; ++p) {
                const int i = m * np + p, d = dom[set][i];
                const arc_cell *e = &C[set][m][p];
                char par[96], param[32], ins[32], name[48], est[32];
                snprintf(name, sizeof name, "%s%s", NAME[m], set ? " (cubics)" : "");
                if (isfinite(e->instr))
                    snprintf(ins, sizeof ins, "%.0f", e->instr);
                else
                    snprintf(ins, sizeof ins, "—");
                if (m)
                    snprintf(param, sizeof param, "N=%d", Ns[p]);
                else
                    snprintf(param, sizeof param, "%.0e", tols[p]);
                if (d < 0)
                    snprintf(par, sizeof par, "front");
                else if (d / np)
                    snprintf(par, sizeof par, "dominated by %s N=%d", NAME[1], Ns[d % np]);
                else
                    snprintf(par, sizeof par, "dominated by %s at %.0e", NAME[0], tols[d % np]);
                fprintf(r->html,
                        "<tr%s><td class=l>%s</td><td>%s</td><td>%.3g</td><td>%.3g</td><td>%s"
                        "</td><td>%.1f</td><td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                        d < 0 ? "" : " class=dom", name, param, e->emax, e->emean,
                        report_g3(est, e->est), e->ns, e->spread, ins, par);
                fprintf(r->md, "| %s | %s | %.3g | %.3g | %s | %.1f | %s | %s |\n", name, param,
                        e->emax, e->emean, est, e->ns, ins, par);
                fprintf(r->tsv, "arclen\t%s\t%.6g\t\t%.6g\t%.6g\t%.6g\t%.3f\t%.6g\t%.6g\t%d\t%s\n",
                        name, m ? (double)Ns[p] : tols[p], e->emax, e->emean, e->est, e->ns,
                        e->spread, e->instr, m ? Ns[p] : 0, d < 0 ? "front" : "dominated");
            }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    cj_chart_set_title(c, "Arc length: error vs cost (ringed: dominated)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ns per call (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max |L - exact|");
    static const cj_rgba COL[NSET][2] = {{{0x1f, 0x77, 0xb4, 255}, {0xff, 0x7f, 0x0e, 255}},
                                         {{0x2c, 0xa0, 0x2c, 255}, {0xd6, 0x27, 0x28, 255}}};
    static const cj_chart_marker MK[NSET][2] = {{CJ_MARKER_CIRCLE, CJ_MARKER_SQUARE},
                                                {CJ_MARKER_DIAMOND, CJ_MARKER_TRIANGLE}};
    for (int set = 0; set < NSET; ++set) {
        double y[2 * NP];
        for (int i = 0; i < 2 * np; ++i) y[i] = fmax(err[set][i], 1e-18);
        report_front_series(c, (size_t)(2 * np), cost[set], y, dom[set], 1e-18,
                            set ? NULL : "Pareto front (per set)");
        for (int m = 0; m < 2; ++m) {
            char name[48];
            snprintf(name, sizeof name, "%s, %s", m ? "chord sum" : "adaptive G-K", SETNAME[set]);
            cj_chart_series_opts o = {name, COL[set][m], 1.5, MK[set][m], 5.0};
            if (cj_chart_add_series(c, cost[set] + m * np, y + m * np, (size_t)np, &o)) {
                cj_chart_destroy(c);
                return report_error("chart: %s", cj_last_error());
            }
            for (int p = 0; p < np; ++p)
                if (dom[set][m * np + p] >= 0) {
                    char txt[48];
                    if (m)
                        snprintf(txt, sizeof txt, "N=%d", Ns[p]);
                    else
                        snprintf(txt, sizeof txt, "%.0e", tols[p]);
                    cj_chart_annotate(c, cost[set][m * np + p], y[m * np + p], txt,
                                      cj_rgba_make(0x60, 0x60, 0x60, 255));
                }
        }
    }
    const int st = report_chart(r, c, "arclen.png", 860, 480);
    cj_chart_destroy(c);
    return st;
}
