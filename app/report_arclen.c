/* casteljau report, section "arc length": cj_bezier_arclength (adaptive Gauss-Kronrod 7/15) at
 * tolerances 1e-2 .. 1e-12 against the chord sum of N uniform parameter steps, on 8 fixed
 * parabolas (quadratic Béziers: 4 random, 4 sharp turns). The reference is the closed form of
 * ∫ sqrt(a t² + b t + c) dt evaluated in long double, so its own error (~1e-18 of the length)
 * is far below every tolerance measured. Per choice: max and mean absolute error over the
 * curves, the largest error estimate the function returned, ns per call (median of
 * interleaved runs), and in the full report instructions per call by callgrind (workload
 * "arclen:M:TOL_OR_N", every curve once). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/bezier.h"
#include "cli.h"

#include <math.h>
#include <stdio.h>

#define NCURVE 8
static double curves[NCURVE][6];

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

/* n calls (the curves in turn, so 8 units are the table's mean over them): "arclen:0:TOL" is
 * cj_bezier_arclength at tolerance TOL, "arclen:1:N" the chord sum of N steps. */
int report_arclen_workload(const char *spec, long n) {
    int m = -1;
    double p = 0;
    if (sscanf(spec, "arclen:%d:%lf", &m, &p) != 2 || m < 0 || m > 1 ||
        (m == 0 && !(p >= 1e-15 && p <= 1)) || (m == 1 && !(p >= 1 && p <= 1 << 20)))
        return cli_fail("report", "bad workload '%s' (arclen:0:TOL or arclen:1:N)", spec);
    make_curves();
    volatile double sink = 0;
    for (long k = 0; k < n; ++k) {
        const cj_bezier c = cj_bezier_view(2, 2, curves[k % NCURVE]);
        double L = 0, e = 0;
        if (m == 0) {
            const cj_status st = cj_bezier_arclength(&c, 0, 1, p, &L, &e);
            if (st && st != CJ_ERR_CAP) return 1;
        } else {
            L = chord_sum(&c, (int)p);
        }
        sink += L;
    }
    (void)sink;
    return 0;
}

int report_arclen(report *r) {
    make_curves();
    long double ref[NCURVE];
    for (int k = 0; k < NCURVE; ++k) ref[k] = exact_length(curves[k]);
    static const double TOL_FULL[] = {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12},
                        TOL_QUICK[] = {1e-3, 1e-6, 1e-9};
    static const int N_FULL[] = {8, 32, 128, 512, 2048, 8192}, N_QUICK[] = {16, 256, 4096};
    const double *tols = r->quick ? TOL_QUICK : TOL_FULL;
    const int *Ns = r->quick ? N_QUICK : N_FULL;
    const int np = r->quick ? 3 : 6, runs = r->quick ? 5 : 15, reps = r->quick ? 20 : 200;
    double ns[2][6], spread[2][6], emax[2][6], emean[2][6], est[2][6], instr[2][6];
    for (int p = 0; p < np; ++p) {
        double tm[2][16];
        volatile double sink = 0;
        for (int run = 0; run < runs; ++run)
            for (int m = 0; m < 2; ++m) {
                const double t0 = report_now_ns();
                for (int rep = 0; rep < reps; ++rep)
                    for (int k = 0; k < NCURVE; ++k) {
                        const cj_bezier c = cj_bezier_view(2, 2, curves[k]);
                        double L = 0, e = 0;
                        if (m == 0) {
                            const cj_status st = cj_bezier_arclength(&c, 0, 1, tols[p], &L, &e);
                            if (st && st != CJ_ERR_CAP) /* CAP: best value, estimate above tol */
                                return cli_error("report", "arc length: %s", cj_last_error());
                        } else {
                            L = chord_sum(&c, Ns[p]);
                        }
                        sink += L;
                    }
                tm[m][run] = (report_now_ns() - t0) / (double)(reps * NCURVE);
            }
        (void)sink;
        for (int m = 0; m < 2; ++m) {
            ns[m][p] = report_median(tm[m], (size_t)runs, &spread[m][p]);
            /* 8 and 16 calls: every curve once and twice (a few Mi instructions at most) */
            char spec[64];
            snprintf(spec, sizeof spec, "arclen:%d:%.17g", m, m ? (double)Ns[p] : tols[p]);
            instr[m][p] = r->quick ? NAN : report_callgrind(r, spec, NCURVE, NULL);
            emax[m][p] = emean[m][p] = 0, est[m][p] = m ? NAN : 0;
            for (int k = 0; k < NCURVE; ++k) {
                const cj_bezier c = cj_bezier_view(2, 2, curves[k]);
                double L = 0, e = 0;
                if (m == 0)
                    cj_bezier_arclength(&c, 0, 1, tols[p], &L, &e);
                else
                    L = chord_sum(&c, Ns[p]);
                const double err = (double)fabsl((long double)L - ref[k]);
                emax[m][p] = fmax(emax[m][p], err), emean[m][p] += err / NCURVE;
                if (m == 0) est[m][p] = fmax(est[m][p], e);
            }
        }
    }
    static const char *const NAME[2] = {"adaptive G-K 7/15", "chord sum"};
    double cost[12], err[12];
    int dom[12];
    for (int m = 0; m < 2; ++m)
        for (int p = 0; p < np; ++p)
            cost[m * np + p] = ns[m][p], err[m * np + p] = fmax(emax[m][p], 1e-300);
    report_pareto((size_t)(2 * np), cost, err, dom);
    fprintf(r->html,
            "<h2>Arc length</h2>\n<p>%d parabolas (quadratic B&eacute;ziers: 4 random in the unit "
            "square, 4 sharp turns with the ends 2d apart, d = 1e-1 .. 1e-4); "
            "reference: the closed form of &int;&radic;(at&sup2;+bt+c) in long double. "
            "cj_bezier_arclength at absolute tolerances against the chord sum of N uniform "
            "steps. Error: max |L &minus; exact| over the curves; estimate: the largest error "
            "estimate returned. Pareto front over all choices (cost ns/call, error max).</p>\n"
            "<table><tr><th class=l>method</th><th>tol / N</th><th>max err</th><th>mean err</th>"
            "<th>estimate</th><th>ns/call</th><th>spread</th><th>instr/call</th>"
            "<th class=l>Pareto</th></tr>\n",
            NCURVE);
    fprintf(r->md,
            "## Arc length (parabolas)\n\n| method | tol / N | max err | mean err | "
            "estimate | ns/call | instr/call | Pareto |\n|---|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < 2; ++m)
        for (int p = 0; p < np; ++p) {
            const int i = m * np + p;
            char par[96], param[32], ins[32];
            if (isfinite(instr[m][p]))
                snprintf(ins, sizeof ins, "%.0f", instr[m][p]);
            else
                snprintf(ins, sizeof ins, "—");
            if (m)
                snprintf(param, sizeof param, "N=%d", Ns[p]);
            else
                snprintf(param, sizeof param, "%.0e", tols[p]);
            if (dom[i] < 0)
                snprintf(par, sizeof par, "front");
            else if (dom[i] / np)
                snprintf(par, sizeof par, "dominated by %s N=%d", NAME[1], Ns[dom[i] % np]);
            else
                snprintf(par, sizeof par, "dominated by %s at %.0e", NAME[0], tols[dom[i] % np]);
            fprintf(r->html,
                    "<tr%s><td class=l>%s</td><td>%s</td><td>%.3g</td><td>%.3g</td><td>%.3g</td>"
                    "<td>%.1f</td><td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                    dom[i] < 0 ? "" : " class=dom", NAME[m], param, emax[m][p], emean[m][p],
                    est[m][p], ns[m][p], spread[m][p], ins, par);
            fprintf(r->md, "| %s | %s | %.3g | %.3g | %.3g | %.1f | %s | %s |\n", NAME[m], param,
                    emax[m][p], emean[m][p], est[m][p], ns[m][p], ins, par);
            fprintf(r->tsv, "arclen\t%s\t%.6g\t\t%.6g\t%.6g\t%.6g\t%.3f\t%.6g\t%.6g\t%d\t%s\n",
                    NAME[m], m ? (double)Ns[p] : tols[p], emax[m][p], emean[m][p], est[m][p],
                    ns[m][p], spread[m][p], instr[m][p], m ? Ns[p] : 0,
                    dom[i] < 0 ? "front" : "dominated");
        }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return cli_error("report", "%s", cj_last_error());
    cj_chart_set_title(c, "Arc length of parabolas: error vs cost (ringed: dominated)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ns per call (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max |L - exact|");
    report_front_series(c, (size_t)(2 * np), cost, err, dom, 1e-18, "Pareto front");
    static const cj_rgba COL[2] = {{0x1f, 0x77, 0xb4, 255}, {0xff, 0x7f, 0x0e, 255}};
    for (int m = 0; m < 2; ++m) {
        cj_chart_series_opts o = {NAME[m], COL[m], 1.5, m ? CJ_MARKER_SQUARE : CJ_MARKER_CIRCLE,
                                  5.0};
        double y[6];
        for (int p = 0; p < np; ++p) y[p] = fmax(emax[m][p], 1e-18);
        cj_chart_add_series(c, ns[m], y, (size_t)np, &o);
        for (int p = 0; p < np; ++p)
            if (dom[m * np + p] >= 0) {
                char txt[48];
                if (m)
                    snprintf(txt, sizeof txt, "N=%d", Ns[p]);
                else
                    snprintf(txt, sizeof txt, "%.0e", tols[p]);
                cj_chart_annotate(c, ns[m][p], y[p], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
            }
    }
    const int st = report_chart(r, c, "arclen.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}
