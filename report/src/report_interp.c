/* casteljau report, section "interpolation": Runge's function f(t) = 1/(1 + 25 t²) on [-1, 1]
 * interpolated by cj_interp_points at n+1 equispaced against n+1 Chebyshev parameters, by
 * degree n. Per choice: the max and mean |c(t) - f(t)| over 2001 equispaced t (the interpolant
 * evaluated by de Casteljau; f in double, exact to ~u, far below every error measured), the
 * condition estimate of the solve, ns per fit (median of interleaved runs). For Chebyshev
 * parameters the classical bound for functions analytic in the Bernstein ellipse E_ρ (the
 * aliasing argument, Trefethen ATAP Thm 8.2, holds for both kinds of Chebyshev points):
 * |f - p_n| <= 4 M ρ^-n / (ρ - 1), M the max of |f| on E_ρ (sampled at 20000 points, which
 * include the maximum on the imaginary axis, times 1.01), at the best of 40 ρ in (1, 1.21]
 * (the poles ±i/5 lie on E_1.2198), plus a rounding allowance of
 * 16 u cond. Equispaced parameters have no such bound (Runge's phenomenon): the error grows.
 * Full report: instructions per fit by callgrind (all cells in one run, workload "interp:all",
 * report_cgbatch.c). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/bezier.h"
#include "casteljau/interp.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define NSAMPLE 2001

static double runge(double t) {
    return 1.0 / (1.0 + 25.0 * t * t);
}

static double ellipse_max(double rho) {
    double m = 0;
    for (int i = 0; i < 20000; ++i) {
        const double th = 6.283185307179586 * i / 20000.0;
        const double complex w = rho * cexp(I * th), z = 0.5 * (w + 1.0 / w);
        m = fmax(m, cabs(1.0 / (1.0 + 25.0 * z * z)));
    }
    return 1.01 * m;
}

static cj_status fit(int m, int n, double *ts, double *vals, double *bez, double *cond) {
    cj_status st = m ? cj_interp_chebyshev(n, -1, 1, ts) : cj_interp_equispaced(n, -1, 1, ts);
    if (st) return st;
    for (int k = 0; k <= n; ++k) vals[k] = runge(ts[k]);
    return cj_interp_points(ts, vals, (size_t)n + 1, 1, -1, 1, bez, NULL, cond);
}

static const int DEG_FULL[] = {4, 8, 12, 16, 20, 24, 32};
enum { ND_FULL = 7 };

/* Cell i of the full table (parameters i / 7, DEG_FULL[i % 7]): `units` fits. */
static int interp_cell(void *ctx, int i, long units) {
    (void)ctx;
    double ts[CJ_INTERP_MAX_DEGREE + 1], vals[CJ_INTERP_MAX_DEGREE + 1],
        bez[CJ_INTERP_MAX_DEGREE + 1], cond = 0;
    for (long k = 0; k < units; ++k)
        if (fit(i / ND_FULL, DEG_FULL[i % ND_FULL], ts, vals, bez, &cond)) return 1;
    return 0;
}

/* n fits (parameters, values, solve) at "interp:M:DEG", M = 0 equispaced, 1 Chebyshev;
 * "interp:all": every cell of the full table (report_cells_workload). */
int report_interp_workload(const char *spec, long n) {
    if (!strcmp(spec, "interp:all"))
        return report_cells_workload(2 * ND_FULL, n, interp_cell, NULL);
    int m = -1, deg = 0;
    if (sscanf(spec, "interp:%d:%d", &m, &deg) != 2 || m < 0 || m > 1 || deg < 1 ||
        deg > CJ_INTERP_MAX_DEGREE)
        return report_fail("bad workload '%s' (interp:0|1:DEGREE)", spec);
    double ts[CJ_INTERP_MAX_DEGREE + 1], vals[CJ_INTERP_MAX_DEGREE + 1],
        bez[CJ_INTERP_MAX_DEGREE + 1], cond = 0;
    for (long k = 0; k < n; ++k)
        if (fit(m, deg, ts, vals, bez, &cond)) return 1;
    return 0;
}

int report_interp(report *r) {
    static const int DEG_QUICK[] = {4, 12, 24};
    const int *degs = r->quick ? DEG_QUICK : DEG_FULL;
    const int nd = r->quick ? 3 : ND_FULL, runs = r->quick ? 5 : 15, reps = r->quick ? 10 : 50;
    /* the bound at its best ρ in (1, 1.21] (ρ near the poles: M explodes; near 1: ρ^-n does
     * not decay), minimised per degree over 40 ellipses */
    double rhos[40], Ms[40];
    for (int j = 0; j < 40; ++j) rhos[j] = 1 + 0.21 * (j + 1) / 40, Ms[j] = ellipse_max(rhos[j]);
    double ns[2][7], spread[2][7], emax[2][7], emean[2][7], bound[2][7], cond[2][7], instr[2][7];
    double ts[CJ_INTERP_MAX_DEGREE + 1], vals[CJ_INTERP_MAX_DEGREE + 1],
        bez[CJ_INTERP_MAX_DEGREE + 1];
    /* instructions per fit, every cell in one callgrind run (20 fits each) */
    for (int i = 0; i < 2 * 7; ++i) instr[i / 7][i % 7] = NAN;
    if (!r->quick) report_callgrind_cells(r, "interp:all", 20, 2 * ND_FULL, &instr[0][0]);
    for (int d = 0; d < nd; ++d) {
        const int n = degs[d];
        double tm[2][16];
        for (int run = 0; run < runs; ++run)
            for (int m = 0; m < 2; ++m) {
                const double t0 = report_now_ns();
                for (int rep = 0; rep < reps; ++rep)
                    if (fit(m, n, ts, vals, bez, &cond[m][d]))
                        return report_error("interpolation: %s", cj_last_error());
                tm[m][run] = (report_now_ns() - t0) / reps;
            }
        for (int m = 0; m < 2; ++m) {
            ns[m][d] = report_median(tm[m], (size_t)runs, &spread[m][d]);
            if (fit(m, n, ts, vals, bez, &cond[m][d]))
                return report_error("interpolation: %s", cj_last_error());
            const cj_bezier c = cj_bezier_view(n, 1, bez);
            emax[m][d] = emean[m][d] = 0;
            for (int i = 0; i < NSAMPLE; ++i) {
                const double u = (double)i / (NSAMPLE - 1), t = 2 * u - 1;
                double v;
                if (cj_bezier_eval(&c, CJ_EVAL_DECASTELJAU, u, &v))
                    return report_error("interpolation: %s", cj_last_error());
                const double e = fabs(v - runge(t));
                emax[m][d] = fmax(emax[m][d], e), emean[m][d] += e / NSAMPLE;
            }
            bound[m][d] = NAN;
            for (int j = 0; m && j < 40; ++j) {
                const double b = 4 * Ms[j] * pow(rhos[j], -n) / (rhos[j] - 1);
                if (!(b >= bound[m][d])) bound[m][d] = b;
            }
            if (m) bound[m][d] += 16 * 0x1p-53 * cond[m][d];
        }
    }
    static const char *const NAME[2] = {"equispaced", "Chebyshev"};
    double cost[14], err[14];
    int dom[14];
    for (int m = 0; m < 2; ++m)
        for (int d = 0; d < nd; ++d) cost[m * nd + d] = ns[m][d], err[m * nd + d] = emax[m][d];
    report_pareto((size_t)(2 * nd), cost, err, dom);
    fprintf(
        r->html,
        "<h2>Interpolation</h2>\n<p>Runge's function 1/(1+25t&sup2;) on [&minus;1, 1] "
        "interpolated by cj_interp_points at n+1 equispaced or Chebyshev parameters. Error: "
        "max |c(t) &minus; f(t)| over %d points. Bound (Chebyshev only): 4M&rho;<sup>&minus;n"
        "</sup>/(&rho;&minus;1), M the max of |f| on the Bernstein ellipse E<sub>&rho;</sub>, at "
        "the best of 40 &rho; in (1, 1.21] (the poles &plusmn;i/5 lie on E<sub>1.2198</sub>), "
        "plus 16u&middot;cond. Cost: ns per fit (parameters, values, solve). Pareto front over "
        "all choices.</p>\n<table><tr><th class=l>parameters</th><th>degree</th><th>cond</th>"
        "<th>max err</th><th>mean err</th><th>bound</th><th>ns/fit</th><th>spread</th>"
        "<th>instr/fit</th><th class=l>Pareto</th></tr>\n",
        NSAMPLE);
    fprintf(r->md,
            "## Interpolation (Runge's function)\n\n| parameters | degree | cond | max err | "
            "bound | ns/fit | instr/fit | Pareto |\n|---|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < 2; ++m)
        for (int d = 0; d < nd; ++d) {
            const int i = m * nd + d;
            char par[96], ins[32], bnd[32];
            if (isfinite(instr[m][d]))
                snprintf(ins, sizeof ins, "%.0f", instr[m][d]);
            else
                snprintf(ins, sizeof ins, "—");
            if (dom[i] < 0)
                snprintf(par, sizeof par, "front");
            else
                snprintf(par, sizeof par, "dominated by %s at degree %d", NAME[dom[i] / nd],
                         degs[dom[i] % nd]);
            fprintf(r->html,
                    "<tr%s><td class=l>%s</td><td>%d</td><td>%.3g</td><td>%.3g</td><td>%.3g</td>"
                    "<td>%s</td><td>%.0f</td><td>%.0f %%</td><td>%s</td><td class=l>%s</td>"
                    "</tr>\n",
                    dom[i] < 0 ? "" : " class=dom", NAME[m], degs[d], cond[m][d], emax[m][d],
                    emean[m][d], report_g3(bnd, bound[m][d]), ns[m][d], spread[m][d], ins, par);
            fprintf(r->md, "| %s | %d | %.3g | %.3g | %s | %.0f | %s | %s |\n", NAME[m], degs[d],
                    cond[m][d], emax[m][d], bnd, ns[m][d], ins, par);
            fprintf(r->tsv, "interp\t%s\t%d\t%.6g\t%.6g\t%.6g\t%.6g\t%.3f\t%.6g\t%.6g\t%d\t%s\n",
                    NAME[m], degs[d], cond[m][d], emax[m][d], emean[m][d], bound[m][d], ns[m][d],
                    spread[m][d], instr[m][d], degs[d], dom[i] < 0 ? "front" : "dominated");
        }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    cj_chart_set_title(c,
                       "Interpolating Runge's function: error vs cost (ringed: dominated, degree)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ns per fit (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max |c(t) - f(t)|");
    report_front_series(c, (size_t)(2 * nd), cost, err, dom, 1e-300, "Pareto front");
    static const cj_rgba COL[2] = {{0xff, 0x7f, 0x0e, 255}, {0x1f, 0x77, 0xb4, 255}};
    for (int m = 0; m < 2; ++m) {
        cj_chart_series_opts o = {NAME[m], COL[m], 1.5, m ? CJ_MARKER_CIRCLE : CJ_MARKER_SQUARE,
                                  5.0};
        cj_chart_add_series(c, ns[m], emax[m], (size_t)nd, &o);
        for (int d = 0; d < nd; ++d) {
            if (dom[m * nd + d] < 0) continue; /* the annotation rings its point */
            char txt[16];
            snprintf(txt, sizeof txt, "%d", degs[d]);
            cj_chart_annotate(c, ns[m][d], emax[m][d], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
        }
    }
    const int st = report_chart(r, c, "interp.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}
