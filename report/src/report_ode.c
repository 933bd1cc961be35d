/* casteljau report, section "integrators": cj_ode2_step on the damped oscillator
 * x'' = -ω² x - 2ζω x' (ω = 2π, ζ = 0.1, x(0) = 1, x'(0) = 0) over [0, 2] with N steps, against
 * its closed form x(t) = e^(-ζωt) (cos ω_d t + ζω/ω_d sin ω_d t), ω_d = ω sqrt(1 - ζ²). Per
 * (integrator, N): max |x_n - x(t_n)| over the steps, µs per integration (median of
 * interleaved runs), in the full report instructions per integration by callgrind (all cells
 * in one run, workload "ode:all", report_cgbatch.c). No bound is claimed; the test checks the
 * orders (RK4 gains >= 100x from N = 32 to 256, the Euler methods >= 4x). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/springs.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double W = 6.283185307179586, ZETA = 0.1, T_END = 2.0;

static void accel(void *user, double t, const double *x, const double *v, double *a) {
    (void)user, (void)t;
    a[0] = -W * W * x[0] - 2 * ZETA * W * v[0];
}

static void jac(void *user, double t, const double *x, const double *v, double *dadx,
                double *dadv) {
    (void)user, (void)t, (void)x, (void)v;
    dadx[0] = -W * W, dadv[0] = -2 * ZETA * W;
}

static double exact(double t) {
    const double wd = W * sqrt(1 - ZETA * ZETA);
    return exp(-ZETA * W * t) * (cos(wd * t) + ZETA * W / wd * sin(wd * t));
}

/* Integrates with N steps; returns the max error (NAN on a failed step). */
static double run(cj_integrator m, int N, int measure) {
    const cj_ode2 sys = {1, NULL, accel, jac};
    double work[64], x = 1, v = 0, emax = 0;
    int ipiv[1];
    const double h = T_END / N;
    for (int k = 0; k < N; ++k) {
        if (cj_ode2_step(&sys, m, k * h, h, &x, &v, work, ipiv, NULL)) return NAN;
        if (measure) emax = fmax(emax, fabs(x - exact((k + 1) * h)));
    }
    return measure ? emax : x;
}

static const int N_FULL[] = {16, 64, 256, 1024, 4096};
enum { NM = 4, NN_FULL = 5 };

/* Cell i of the full table (integrator i / 5, N_FULL[i % 5]): `units` integrations. */
static int ode_cell(void *ctx, int i, long units) {
    (void)ctx;
    volatile double sink = 0;
    for (long k = 0; k < units; ++k) {
        const double x = run((cj_integrator)(i / NN_FULL), N_FULL[i % NN_FULL], 0);
        if (!isfinite(x)) return 1;
        sink += x;
    }
    (void)sink;
    return 0;
}

/* n integrations over [0, 2] at "ode:M:N" (integrator M, N steps; no measuring); "ode:all":
 * every cell of the full table (report_cells_workload). */
int report_ode_workload(const char *spec, long n) {
    if (!strcmp(spec, "ode:all")) return report_cells_workload(NM * NN_FULL, n, ode_cell, NULL);
    int m = -1, N = 0;
    if (sscanf(spec, "ode:%d:%d", &m, &N) != 2 || m < 0 || m > 3 || N < 1 || N > 1 << 24)
        return report_fail("bad workload '%s' (ode:INTEGRATOR0-3:STEPS)", spec);
    volatile double sink = 0;
    for (long k = 0; k < n; ++k) {
        const double x = run((cj_integrator)m, N, 0);
        if (!isfinite(x)) return 1;
        sink += x;
    }
    (void)sink;
    return 0;
}

int report_ode(report *r) {
    static const int N_QUICK[] = {32, 256};
    const int *Ns = r->quick ? N_QUICK : N_FULL;
    const int nn = r->quick ? 2 : NN_FULL, runs = r->quick ? 3 : 11;
    for (int m = 0; m < NM; ++m)
        if (cj_ode2_work_size(1, (cj_integrator)m) > 64)
            return report_error("integrators: work space too large");
    double us[NM * 5], spread[NM * 5], err[NM * 5], instr[NM * 5];
    for (int i = 0; i < NM * 5; ++i) instr[i] = NAN;
    for (int i = 0; i < nn; ++i) {
        double tm[NM][16];
        volatile double sink = 0;
        for (int k = 0; k < runs; ++k)
            for (int m = 0; m < NM; ++m) {
                const double t0 = report_now_ns();
                sink += run((cj_integrator)m, Ns[i], 0);
                tm[m][k] = (report_now_ns() - t0) / 1e3;
            }
        (void)sink;
        for (int m = 0; m < NM; ++m) {
            us[m * nn + i] = report_median(tm[m], (size_t)runs, &spread[m * nn + i]);
            err[m * nn + i] = run((cj_integrator)m, Ns[i], 1);
            if (!isfinite(err[m * nn + i])) return report_error("integrators: %s", cj_last_error());
        }
    }
    /* instructions per integration, every cell in one callgrind run (4 integrations each) */
    if (!r->quick) report_callgrind_cells(r, "ode:all", 4, NM * NN_FULL, instr);
    int dom[NM * 5];
    report_pareto((size_t)(NM * nn), us, err, dom);
    fprintf(r->html,
            "<h2>Integrators</h2>\n<p>cj_ode2_step on x'' = &minus;&omega;&sup2;x &minus; "
            "2&zeta;&omega;x' (&omega; = 2&pi;, &zeta; = %.2g) over [0, %.0f] with N steps, "
            "against the closed form. Error: max |x<sub>n</sub> &minus; x(t<sub>n</sub>)|; cost: "
            "&micro;s per integration. Pareto front over all choices.</p>\n<table><tr>"
            "<th class=l>integrator</th><th>N</th><th>h&omega;</th><th>max err</th>"
            "<th>&micro;s</th><th>spread</th><th>instr</th><th class=l>Pareto</th></tr>\n",
            ZETA, T_END);
    fprintf(r->md, "## Integrators (damped oscillator)\n\n| integrator | N | max err | µs | instr "
                   "| Pareto |\n|---|---|---|---|---|---|\n");
    for (int i = 0; i < NM * nn; ++i) {
        const int m = i / nn, N = Ns[i % nn];
        char par[96], ins[32];
        if (isfinite(instr[i]))
            snprintf(ins, sizeof ins, "%.0f", instr[i]);
        else
            snprintf(ins, sizeof ins, "—");
        if (dom[i] < 0)
            snprintf(par, sizeof par, "front");
        else
            snprintf(par, sizeof par, "dominated by %s N=%d",
                     cj_integrator_name((cj_integrator)(dom[i] / nn)), Ns[dom[i] % nn]);
        const char *name = cj_integrator_name((cj_integrator)m);
        fprintf(r->html,
                "<tr%s><td class=l>%s</td><td>%d</td><td>%.3g</td><td>%.3g</td><td>%.2f</td>"
                "<td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", name, N, T_END / N * W, err[i], us[i], spread[i],
                ins, par);
        fprintf(r->md, "| %s | %d | %.3g | %.2f | %s | %s |\n", name, N, err[i], us[i], ins, par);
        fprintf(r->tsv, "ode\t%s\t%d\t\t%.6g\t\t\t%.3f\t%.6g\t%.6g\t%d\t%s\n", name, N, err[i],
                1e3 * us[i], spread[i], instr[i], N, dom[i] < 0 ? "front" : "dominated");
    }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    cj_chart_set_title(c, "Damped oscillator: error vs cost (ringed: dominated, N)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "µs per integration (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max |x_n - x(t_n)|");
    report_front_series(c, (size_t)(NM * nn), us, err, dom, 1e-300, "Pareto front");
    static const cj_rgba COL[NM] = {{0xd6, 0x27, 0x28, 255},
                                    {0xff, 0x7f, 0x0e, 255},
                                    {0x1f, 0x77, 0xb4, 255},
                                    {0x2c, 0xa0, 0x2c, 255}};
    static const cj_chart_marker MK[NM] = {CJ_MARKER_SQUARE, CJ_MARKER_TRIANGLE, CJ_MARKER_CIRCLE,
                                           CJ_MARKER_SQUARE};
    for (int m = 0; m < NM; ++m) {
        cj_chart_series_opts o = {cj_integrator_name((cj_integrator)m), COL[m], 1.5, MK[m], 5.0};
        cj_chart_add_series(c, us + m * nn, err + m * nn, (size_t)nn, &o);
        for (int i = 0; i < nn; ++i) {
            if (dom[m * nn + i] < 0) continue; /* the annotation rings its point */
            char txt[16];
            snprintf(txt, sizeof txt, "%d", Ns[i]);
            cj_chart_annotate(c, us[m * nn + i], err[m * nn + i], txt,
                              cj_rgba_make(0x60, 0x60, 0x60, 255));
        }
    }
    const int st = report_chart(r, c, "ode.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}
