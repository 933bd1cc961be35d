/* casteljau report, section "flattening": the three methods x tolerances 1 .. 1e-6 on a fixed
 * set of planar cubics (seeded random ones, a near-cusp, a loop; all inside the unit square).
 * Per (method, tolerance): segments over the continuous optimum Σ max(1, I_c / sqrt(8 tol))
 * with I_c = ∫ sqrt(|κ|) ds of curve c (midpoint rule on 20000 steps), the largest proven bound
 * the flattener returned, the measured deviation (largest distance from 16 curve points per
 * segment, evaluated with the compensated method, to that segment's chord), and ns per curve. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/bezier.h"
#include "casteljau/flatten.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NMETH  3
#define NCURVE 8
static const cj_flatten_method METH[NMETH] = {CJ_FLATTEN_UNIFORM, CJ_FLATTEN_SUBDIVIDE,
                                              CJ_FLATTEN_NEAR_OPTIMAL};
static const char *const FNAME[NMETH] = {"uniform (Wang)", "subdivide", "near-optimal"};
static const cj_chart_marker FMARK[NMETH] = {CJ_MARKER_SQUARE, CJ_MARKER_TRIANGLE,
                                             CJ_MARKER_CIRCLE};
static const cj_rgba FCOL[NMETH] = {
    {0xff, 0x7f, 0x0e, 255}, {0x2c, 0xa0, 0x2c, 255}, {0x1f, 0x77, 0xb4, 255}};

static double curves[NCURVE][8];

static void make_curves(void) {
    unsigned s = 12345u;
    for (int c = 0; c < NCURVE - 2; ++c)
        for (int i = 0; i < 8; ++i) {
            s = s * 1103515245u + 12345u;
            curves[c][i] = (double)((s >> 8) & 0xffff) / 65535.0;
        }
    const double cusp[8] = {0.1, 0.1, 0.9, 0.9, 0.1, 0.9, 0.9, 0.1001};
    const double loop[8] = {0.1, 0.5, 1.0, 1.0, 0.0, 1.0, 0.9, 0.5};
    memcpy(curves[NCURVE - 2], cusp, sizeof cusp);
    memcpy(curves[NCURVE - 1], loop, sizeof loop);
}

/* ∫ sqrt(|κ|) ds = ∫ sqrt(|c' x c''|) / sqrt(|c'|) dt, midpoint rule. */
static double sqrt_kappa_integral(const double *b) {
    const int N = 20000;
    double sum = 0;
    for (int k = 0; k < N; ++k) {
        const double t = (k + 0.5) / N, s = 1 - t;
        double d1[2], d2[2];
        for (int j = 0; j < 2; ++j) {
            const double p0 = b[j], p1 = b[2 + j], p2 = b[4 + j], p3 = b[6 + j];
            d1[j] = 3 * (s * s * (p1 - p0) + 2 * s * t * (p2 - p1) + t * t * (p3 - p2));
            d2[j] = 6 * (s * (p2 - 2 * p1 + p0) + t * (p3 - 2 * p2 + p1));
        }
        const double cr = fabs(d1[0] * d2[1] - d1[1] * d2[0]), sp = hypot(d1[0], d1[1]);
        if (sp > 0) sum += sqrt(cr) / sqrt(sp);
    }
    return sum / N;
}

typedef struct coll {
    double *pts, *ts;
    size_t n, cap;
} coll;

static void collect(void *user, const double *pt, int dim, size_t piece, double t) {
    (void)dim;
    (void)piece;
    coll *c = user;
    if (c->n < c->cap) {
        c->pts[2 * c->n] = pt[0], c->pts[2 * c->n + 1] = pt[1];
        c->ts[c->n] = t;
    }
    c->n++;
}

static double seg_dist(const double *q, const double *a, const double *b) {
    const double vx = b[0] - a[0], vy = b[1] - a[1], L2 = vx * vx + vy * vy;
    double u = L2 > 0 ? ((q[0] - a[0]) * vx + (q[1] - a[1]) * vy) / L2 : 0;
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    return hypot(q[0] - a[0] - u * vx, q[1] - a[1] - u * vy);
}

#define CAPPTS (1u << 17)

int report_flatten_workload(const char *spec, long n) {
    int m = -1, e = 0;
    if (sscanf(spec, "flatten:%d:%d", &m, &e) != 2 || m < 0 || m >= NMETH || e < 0 || e > 12)
        return report_fail("bad workload '%s' (flatten:METHOD0-2:TOLEXP)", spec);
    make_curves();
    static double buf[2 * CAPPTS];
    const cj_flatten_opts o = cj_flatten_defaults(METH[m], pow(10.0, -e));
    for (long k = 0; k < n; ++k) {
        const cj_bezier c = cj_bezier_view(3, 2, curves[k % NCURVE]);
        size_t np = 0;
        if (cj_flatten_bezier(&c, &o, buf, CAPPTS, &np, NULL)) return 1;
    }
    return 0;
}

int report_flatten(report *r) {
    make_curves();
    static const int TE_FULL[] = {0, 1, 2, 3, 4, 5, 6}, TE_QUICK[] = {1, 3, 5};
    const int *tes = r->quick ? TE_QUICK : TE_FULL;
    const int nt = r->quick ? 3 : 7, runs = r->quick ? 5 : 21;
    const double min_ns = r->quick ? 2e4 : 2e5;
    double I[NCURVE];
    for (int c = 0; c < NCURVE; ++c) I[c] = sqrt_kappa_integral(curves[c]);
    static double buf[2 * CAPPTS], cpts[2 * CAPPTS], cts[CAPPTS];
    double segs_ratio[NMETH][7], bound[NMETH][7], dev[NMETH][7], ns[NMETH][7], spread[NMETH][7],
        instr[NMETH][7], segs[NMETH][7];
    for (int ti = 0; ti < nt; ++ti) {
        const double tol = pow(10.0, -tes[ti]);
        double opt = 0;
        for (int c = 0; c < NCURVE; ++c) opt += fmax(1.0, I[c] / sqrt(8 * tol));
        for (int m = 0; m < NMETH; ++m) {
            const cj_flatten_opts o = cj_flatten_defaults(METH[m], tol);
            size_t total = 0;
            double bmax = 0, dmax = 0;
            for (int c = 0; c < NCURVE; ++c) {
                const cj_bezier cv = cj_bezier_view(3, 2, curves[c]);
                coll cl = {cpts, cts, 0, CAPPTS};
                cj_flatten_stats st;
                if (cj_flatten_bezier_cb(&cv, &o, collect, &cl, &st) || cl.n > CAPPTS)
                    return report_error("flatten: %s", cj_last_error());
                total += st.segments;
                bmax = fmax(bmax, st.bound);
                for (size_t k = 0; k + 1 < cl.n; ++k)
                    for (int j = 1; j < 16; ++j) {
                        const double t = cl.ts[k] + (cl.ts[k + 1] - cl.ts[k]) * j / 16.0;
                        double q[2];
                        if (cj_bezier_eval(&cv, CJ_EVAL_COMPENSATED, t, q)) return 1;
                        dmax = fmax(dmax, seg_dist(q, cl.pts + 2 * k, cl.pts + 2 * k + 2));
                    }
            }
            segs[m][ti] = (double)total / NCURVE;
            segs_ratio[m][ti] = (double)total / opt;
            bound[m][ti] = bmax;
            dev[m][ti] = dmax;
        }
        double t[NMETH][32];
        for (int run = 0; run < runs; ++run)
            for (int m = 0; m < NMETH; ++m) {
                const cj_flatten_opts o = cj_flatten_defaults(METH[m], tol);
                long reps = 0;
                const double t0 = report_now_ns();
                double t1;
                do {
                    for (int c = 0; c < NCURVE; ++c) {
                        const cj_bezier cv = cj_bezier_view(3, 2, curves[c]);
                        size_t np = 0;
                        if (cj_flatten_bezier(&cv, &o, buf, CAPPTS, &np, NULL)) return 1;
                    }
                    reps++;
                } while ((t1 = report_now_ns()) - t0 < min_ns);
                t[m][run] = (t1 - t0) / (reps * (double)NCURVE);
            }
        for (int m = 0; m < NMETH; ++m) {
            ns[m][ti] = report_median(t[m], (size_t)runs, &spread[m][ti]);
            char spec[64];
            snprintf(spec, sizeof spec, "flatten:%d:%d", m, tes[ti]);
            instr[m][ti] = r->quick ? NAN : report_callgrind(r, spec, 400, NULL);
        }
    }
    /* Pareto over all (method, tolerance): cost ns per curve, error measured deviation */
    double cost[NMETH * 7], err[NMETH * 7];
    int dom[NMETH * 7];
    for (int m = 0; m < NMETH; ++m)
        for (int ti = 0; ti < nt; ++ti)
            cost[m * nt + ti] = ns[m][ti], err[m * nt + ti] = dev[m][ti];
    report_pareto((size_t)(NMETH * nt), cost, err, dom);
    fprintf(
        r->html,
        "<h2>Flattening</h2>\n<p>%d planar cubics (random, a near-cusp, a loop) in the unit "
        "square. Segments over the continuous optimum &Sigma; max(1, &int;&radic;|&kappa;| ds / "
        "&radic;(8 tol)); the largest proven bound and the measured deviation (16 curve "
        "points per segment against its chord); ns per curve (cj_flatten_bezier into a caller "
        "buffer). Pareto front over all (method, tolerance): cost ns per curve, error the "
        "measured deviation.</p>\n<table><tr><th class=l>method</th><th>tol</th><th>segments"
        "/curve</th><th>÷ optimum</th><th>bound</th><th>measured</th><th>ns/curve</th><th>"
        "spread</th><th>instr/curve</th><th class=l>Pareto</th></tr>\n",
        NCURVE);
    fprintf(r->md, "## Flattening\n\n| method | tol | segs ÷ optimum | bound | measured | ns/curve "
                   "| Pareto |\n|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < NMETH; ++m)
        for (int ti = 0; ti < nt; ++ti) {
            const int i = m * nt + ti;
            char par[96], ins[32];
            if (dom[i] < 0)
                snprintf(par, sizeof par, "front");
            else
                snprintf(par, sizeof par, "dominated by %s at tol 1e-%d", FNAME[dom[i] / nt],
                         tes[dom[i] % nt]);
            if (isfinite(instr[m][ti]))
                snprintf(ins, sizeof ins, "%.0f", instr[m][ti]);
            else
                snprintf(ins, sizeof ins, "—");
            fprintf(
                r->html,
                "<tr%s><td class=l>%s</td><td>1e-%d</td><td>%.1f</td><td>%.3f</td><td>%.3g</td>"
                "<td>%.3g</td><td>%.0f</td><td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", FNAME[m], tes[ti], segs[m][ti], segs_ratio[m][ti],
                bound[m][ti], dev[m][ti], ns[m][ti], spread[m][ti], ins, par);
            fprintf(r->md, "| %s | 1e-%d | %.3f | %.3g | %.3g | %.0f | %s |\n", FNAME[m], tes[ti],
                    segs_ratio[m][ti], bound[m][ti], dev[m][ti], ns[m][ti], par);
            fprintf(r->tsv, "flatten\t%s\t%.6g\t\t%.6g\t\t%.6g\t%.6g\t%.3f\t%.6g\t%.6g\t%s\n",
                    FNAME[m], pow(10.0, -tes[ti]), dev[m][ti], bound[m][ti], ns[m][ti],
                    spread[m][ti], instr[m][ti], segs_ratio[m][ti],
                    dom[i] < 0 ? "front" : "dominated");
        }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    /* chart 1: measured deviation against ns per curve; chart 2: segments ÷ optimum by tol */
    for (int k = 0; k < 2; ++k) {
        cj_chart *c = NULL;
        if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
        cj_chart_set_title(c, k ? "Flattening: segments / continuous optimum"
                                : "Flattening: deviation vs cost (ringed: dominated, tol)");
        cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
        cj_chart_set_axis(c, 0, CJ_CHART_LOG10, k ? "tolerance" : "ns per curve (median)");
        cj_chart_set_axis(c, 1, k ? CJ_CHART_LINEAR : CJ_CHART_LOG10,
                          k ? "segments / optimum" : "max distance curve - polyline");
        if (!k) report_front_series(c, (size_t)(NMETH * nt), cost, err, dom, 1e-17, "Pareto front");
        for (int m = 0; m < NMETH; ++m) {
            double x[7], y[7];
            for (int ti = 0; ti < nt; ++ti) {
                x[ti] = k ? pow(10.0, -tes[ti]) : ns[m][ti];
                y[ti] = k ? segs_ratio[m][ti] : fmax(dev[m][ti], 1e-17);
            }
            cj_chart_series_opts o = {FNAME[m], FCOL[m], 1.5, FMARK[m], 5.0};
            if (cj_chart_add_series(c, x, y, (size_t)nt, &o)) {
                cj_chart_destroy(c);
                return report_error("chart: %s", cj_last_error());
            }
            if (!k)
                for (int ti = 0; ti < nt; ++ti)
                    if (dom[m * nt + ti] >= 0) {
                        char txt[48];
                        snprintf(txt, sizeof txt, "1e-%d", tes[ti]);
                        cj_chart_annotate(c, x[ti], y[ti], txt,
                                          cj_rgba_make(0x60, 0x60, 0x60, 255));
                    }
        }
        char name[64];
        snprintf(name, sizeof name, "flatten_%d.png", k);
        const int st = report_chart(r, c, name, 760, 480);
        cj_chart_destroy(c);
        if (st) return st;
    }
    return 0;
}
