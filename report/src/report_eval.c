/* casteljau report, section "curve evaluation": the four methods x degrees x condition
 * numbers; relative error against the MPFR oracle in units of u = 2^-53 (max and mean over the
 * points of a class) next to the proven bound, against ns per point.
 *
 * The curves: condition 1 is a curve with random positive coefficients in [1, 2] (every
 * Σ|b_i|B_i/|p| is 1). Higher conditions use the classic ill-conditioned family p(s) =
 * c (s - 1/2)^n, Bernstein coefficients c (-1)^(n-i) 2^-n (exact in double), evaluated near its
 * root at t = 1/2 ± δ with cond(p, t) = (2|t - 1/2|)^-n, so δ = K^(-1/n) / 2 aims at condition
 * K; the condition actually reached is computed by the oracle at each double t and the class
 * reports its geometric mean. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/bezier.h"
#include "oracle_mpfr.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NM 4
static const cj_eval_method METHODS[NM] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER,
                                           CJ_EVAL_COMPENSATED};
static const char *const NAMES[NM] = {"de Casteljau", "Bernstein", "Horner (VS)", "compensated"};
static const cj_chart_marker MARK[NM] = {CJ_MARKER_CIRCLE, CJ_MARKER_SQUARE, CJ_MARKER_TRIANGLE,
                                         CJ_MARKER_DIAMOND};
static const cj_rgba COL[NM] = {{0x1f, 0x77, 0xb4, 255},
                                {0xff, 0x7f, 0x0e, 255},
                                {0x2c, 0xa0, 0x2c, 255},
                                {0xd6, 0x27, 0x28, 255}};
static const double U = 0x1p-53;

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double rnd(void) { /* splitmix64 -> [0, 1) */
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

static double gamma_k(int k) {
    return k * U / (1 - k * U);
}

/* Bernstein coefficients (1D) of the class: cond 1 = random positive, else c (s - 1/2)^n. */
static void make_curve(int n, double K, double *b) {
    const double c = 1.0 + rnd();
    for (int i = 0; i <= n; ++i)
        b[i] = K <= 1.0 ? 1.0 + rnd() : ((n - i) % 2 ? -c : c) * ldexp(1.0, -n);
}

static double make_t(int n, double K) {
    if (K <= 1.0) return rnd();
    const double d = 0.5 * pow(K, -1.0 / n) * (1.0 + 0.2 * rnd());
    return rnd() < 0.5 ? 0.5 - d : 0.5 + d;
}

/* ns per point of method m on curve c over the nt parameters ts: one run of >= min_ns. */
static double time_run(const cj_bezier *c, cj_eval_method m, const double *ts, size_t nt,
                       double *out, double min_ns) {
    long reps = 0;
    const double t0 = report_now_ns();
    double t1;
    do {
        if (cj_bezier_eval_batch(c, m, ts, nt, out)) return NAN;
        reps++;
    } while ((t1 = report_now_ns()) - t0 < min_ns);
    return (t1 - t0) / ((double)reps * (double)nt);
}

int report_eval_workload(const char *spec, long n) {
    int m = -1, deg = -1;
    if (sscanf(spec, "eval:%d:%d", &m, &deg) != 2 || m < 0 || m >= NM || deg < 1 || deg > 64)
        return report_fail("bad workload '%s' (eval:METHOD0-3:DEGREE)", spec);
    double b[2 * 65], ts[256], out[2 * 256];
    for (int i = 0; i <= deg; ++i) b[2 * i] = cos(i), b[2 * i + 1] = sin(3.0 * i);
    for (int i = 0; i < 256; ++i) ts[i] = (i + 0.5) / 256;
    const cj_bezier c = cj_bezier_view(deg, 2, b);
    double sink = 0;
    for (long done = 0; done < n; done += 256) {
        const size_t k = (size_t)(n - done < 256 ? n - done : 256);
        if (cj_bezier_eval_batch(&c, METHODS[m], ts, k, out)) return 1;
        sink += out[0];
    }
    return sink == 12345.678; /* keeps the loop; never true for these curves */
}

int report_eval(report *r) {
    static const int DEG_FULL[] = {3, 8, 20, 50}, DEG_QUICK[] = {3, 20};
    static const double K_FULL[] = {1, 1e5, 1e10, 1e15, 1e20, 1e30}, K_QUICK[] = {1, 1e10, 1e20};
    const int *degs = r->quick ? DEG_QUICK : DEG_FULL;
    const double *ks = r->quick ? K_QUICK : K_FULL;
    const int nd = r->quick ? 2 : 4, nk = r->quick ? 3 : 6;
    const int npts = r->quick ? 12 : 64, runs = r->quick ? 5 : 21;
    const double min_ns = r->quick ? 2e4 : 2e5;

    /* cost: ns per point by method and degree (independent of the condition), interleaved */
    double ns[NM][4], spread[NM][4], instr[NM][4];
    double rep_diff = NAN;
    for (int d = 0; d < nd; ++d) {
        double b[2 * 51], ts[256], out[2 * 256], t[NM][64];
        for (int i = 0; i <= degs[d]; ++i) b[2 * i] = cos(i), b[2 * i + 1] = sin(3.0 * i);
        for (int i = 0; i < 256; ++i) ts[i] = (i + 0.5) / 256;
        const cj_bezier c = cj_bezier_view(degs[d], 2, b);
        for (int run = 0; run < runs; ++run)
            for (int m = 0; m < NM; ++m) t[m][run] = time_run(&c, METHODS[m], ts, 256, out, min_ns);
        for (int m = 0; m < NM; ++m) {
            ns[m][d] = report_median(t[m], (size_t)runs, &spread[m][d]);
            char spec[64];
            snprintf(spec, sizeof spec, "eval:%d:%d", m, degs[d]);
            instr[m][d] = NAN;
            /* quick: only the repeatability check; full: every cell, the first one checked */
            if (!r->quick || (m == 0 && d == 0))
                instr[m][d] = report_callgrind(r, spec, 20000, m == 0 && d == 0 ? &rep_diff : NULL);
        }
    }
    if (r->callgrind && isfinite(rep_diff))
        snprintf(r->note, sizeof r->note,
                 "Callgrind repeatability: two runs of the same workload (de Casteljau, degree %d, "
                 "20000 points) differ by %.4f %% (required: at most 0.5 %%).",
                 degs[0], 100.0 * rep_diff);

    /* accuracy: errors against the oracle */
    static double emax[NM][4][6], emean[NM][4][6], kcls[4][6];
    mpfr_t val, mag;
    mpfr_inits2(256, val, mag, (mpfr_ptr)0);
    for (int d = 0; d < nd; ++d)
        for (int k = 0; k < nk; ++k) {
            const int n = degs[d];
            double b[51], logk = 0;
            make_curve(n, ks[k], b);
            const cj_bezier c = cj_bezier_view(n, 1, b);
            for (int m = 0; m < NM; ++m) emax[m][d][k] = emean[m][d][k] = 0;
            for (int i = 0; i < npts; ++i) {
                const double t = make_t(n, ks[k]);
                cj_oracle_bezier(b, n, 1, 0, t, 1 << 16, val, mag);
                const double kk = cj_oracle_up(mag) / fabs(mpfr_get_d(val, MPFR_RNDN));
                logk += log10(kk);
                for (int m = 0; m < NM; ++m) {
                    double y = 0;
                    if (cj_bezier_eval(&c, METHODS[m], t, &y)) return report_error("eval failed");
                    const double e = cj_oracle_rel_error(y, val) / U;
                    emax[m][d][k] = fmax(emax[m][d][k], e);
                    emean[m][d][k] += e / npts;
                }
            }
            kcls[d][k] = pow(10.0, logk / npts);
        }
    mpfr_clears(val, mag, (mpfr_ptr)0);

    /* page: table and Pareto per (degree, condition) among the four methods */
    fprintf(
        r->html,
        "<h2>Curve evaluation</h2>\n<p>Relative error against the exact value (MPFR oracle) in "
        "units of u = 2<sup>&minus;53</sup>, max and mean over %d parameters per class, next to "
        "the proven bound (de Casteljau &gamma;(3n)&middot;cond, compensated u + "
        "2&gamma;(3n)&sup2;&middot;cond; Bernstein and Horner have none in the library); cost in "
        "ns per point (cj_bezier_eval_batch, 256 parameters, planar curve). A choice is "
        "<i>dominated</i> when another method at the same degree and condition is at least as "
        "fast and at least as accurate (max error), one of them strictly.</p>\n<table><tr>"
        "<th>degree</th><th>cond</th><th class=l>method</th><th>max err/u</th><th>mean err/u</th>"
        "<th>bound/u</th><th>ns/point</th><th>spread</th><th>instr/point</th><th class=l>Pareto"
        "</th></tr>\n",
        npts);
    fprintf(r->md, "## Curve evaluation\n\n| degree | cond | method | max err/u | bound/u | ns/pt "
                   "| instr/pt | Pareto |\n|---|---|---|---|---|---|---|---|\n");
    for (int d = 0; d < nd; ++d)
        for (int k = 0; k < nk; ++k) {
            double cost[NM], err[NM];
            int dom[NM];
            for (int m = 0; m < NM; ++m) cost[m] = ns[m][d], err[m] = emax[m][d][k];
            report_pareto(NM, cost, err, dom);
            const int n = degs[d];
            for (int m = 0; m < NM; ++m) {
                const double K = kcls[d][k];
                double bound = NAN;
                if (METHODS[m] == CJ_EVAL_DECASTELJAU) bound = gamma_k(3 * n) * K / U;
                if (METHODS[m] == CJ_EVAL_COMPENSATED)
                    bound = (U + 2 * gamma_k(3 * n) * gamma_k(3 * n) * K) / U;
                char par[96], bnd[32], ins[32];
                if (dom[m] < 0)
                    snprintf(par, sizeof par, "front");
                else
                    snprintf(par, sizeof par, "dominated by %s", NAMES[dom[m]]);
                if (isfinite(bound))
                    snprintf(bnd, sizeof bnd, "%.3g", bound);
                else
                    snprintf(bnd, sizeof bnd, "—");
                if (isfinite(instr[m][d]))
                    snprintf(ins, sizeof ins, "%.0f", instr[m][d]);
                else
                    snprintf(ins, sizeof ins, "—");
                fprintf(
                    r->html,
                    "<tr%s><td>%d</td><td>%.2g</td><td class=l>%s</td><td>%.3g</td><td>%.3g</td>"
                    "<td>%s</td><td>%.1f</td><td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                    dom[m] < 0 ? "" : " class=dom", n, K, NAMES[m], emax[m][d][k], emean[m][d][k],
                    bnd, ns[m][d], spread[m][d], ins, par);
                if (k == 0 || k == nk - 1)
                    fprintf(r->md, "| %d | %.2g | %s | %.3g | %s | %.1f | %s | %s |\n", n, K,
                            NAMES[m], emax[m][d][k], bnd, ns[m][d], ins, par);
                fprintf(r->tsv, "eval\t%s\t%d\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.3f\t%.6g\t\t%s\n",
                        NAMES[m], n, K, emax[m][d][k], emean[m][d][k], bound, ns[m][d],
                        spread[m][d], instr[m][d], dom[m] < 0 ? "front" : "dominated");
            }
        }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n(lowest and highest condition shown; the page has them all)\n\n");

    /* charts: max error (log) against ns per point (log), one panel per condition shown,
     * a series per method through its degrees; errors of 0 are drawn at 0.01 u */
    const int shown[2] = {0, nk - 1};
    for (int s = 0; s < 2; ++s) {
        const int k = shown[s];
        cj_chart *c = NULL;
        if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
        char title[128];
        snprintf(title, sizeof title, "Evaluation, cond ~%.0e: error vs cost (ringed: dominated)",
                 ks[k]);
        cj_chart_set_title(c, title);
        cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
        cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ns per point (median)");
        cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max relative error / u");
        for (int m = 0; m < NM; ++m) {
            double x[4], y[4];
            for (int d = 0; d < nd; ++d) x[d] = ns[m][d], y[d] = fmax(emax[m][d][k], 0.01);
            cj_chart_series_opts o = {NAMES[m], COL[m], 1.5, MARK[m], 5.0};
            if (cj_chart_add_series(c, x, y, (size_t)nd, &o)) {
                cj_chart_destroy(c);
                return report_error("chart: %s", cj_last_error());
            }
            /* the bound, dashed-looking as small markers without a line */
            if (METHODS[m] == CJ_EVAL_DECASTELJAU || METHODS[m] == CJ_EVAL_COMPENSATED) {
                double bb[4];
                for (int d = 0; d < nd; ++d) {
                    const double g = gamma_k(3 * degs[d]);
                    bb[d] =
                        fmax(METHODS[m] == CJ_EVAL_DECASTELJAU ? g * kcls[d][k] / U
                                                               : (U + 2 * g * g * kcls[d][k]) / U,
                             0.01);
                }
                char lab[64];
                snprintf(lab, sizeof lab, "bound, %s", NAMES[m]);
                cj_chart_series_opts ob = {lab, COL[m], 0.0, CJ_MARKER_CIRCLE, 2.0};
                cj_chart_add_series(c, x, bb, (size_t)nd, &ob);
            }
        }
        /* mark the dominated choices with a ring and the degree */
        for (int d = 0; d < nd; ++d) {
            double cost[NM], err[NM];
            int dom[NM];
            for (int m = 0; m < NM; ++m) cost[m] = ns[m][d], err[m] = emax[m][d][k];
            report_pareto(NM, cost, err, dom);
            report_front_series(c, NM, cost, err, dom, 0.01,
                                d == 0 ? "Pareto front (per degree)" : NULL);
            for (int m = 0; m < NM; ++m)
                if (dom[m] >= 0) {
                    char txt[48];
                    snprintf(txt, sizeof txt, "n=%d", degs[d]);
                    cj_chart_annotate(c, ns[m][d], fmax(emax[m][d][k], 0.01), txt,
                                      cj_rgba_make(0x60, 0x60, 0x60, 255));
                }
        }
        char name[64];
        snprintf(name, sizeof name, "eval_cond%d.png", s);
        const int st = report_chart(r, c, name, 760, 480);
        cj_chart_destroy(c);
        if (st) return st;
    }
    return 0;
}
