/* casteljau report, section "implicit contouring": cj_implicit_contour of a circle (radius 0.8,
 * off-centre in [-1, 1]²) by grid size x tolerance. The measured distance is exact: over a
 * segment, | |p - c| - r | is largest at an end or where the segment comes closest to the
 * centre (|p - c| is convex along it), so max(| |a-c| - r |, | |b-c| - r |, r - d_min) is the
 * segment's deviation from the circle. Per choice: that deviation over all segments (bound:
 * the tolerance), vertices emitted, µs per contour (median of interleaved runs), and in the full
 * report instructions per contour by callgrind (workload "contour:GRID:TOL"). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/implicit.h"
#include "cli.h"

#include <math.h>
#include <stdio.h>

static const double CX = 0.03, CY = 0.01, R = 0.8;

typedef struct acc {
    int measure;
    double dev;
    size_t pts;
} acc;

static cj_status emit(void *user, const double *xy, size_t npts, int closed, double res) {
    (void)closed, (void)res;
    acc *a = user;
    a->pts += npts;
    if (!a->measure) return CJ_OK;
    for (size_t i = 0; i < npts; ++i) {
        const double ax = xy[2 * i] - CX, ay = xy[2 * i + 1] - CY;
        a->dev = fmax(a->dev, fabs(hypot(ax, ay) - R));
        if (i + 1 == npts) break;
        const double bx = xy[2 * i + 2] - CX, by = xy[2 * i + 3] - CY;
        const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
        double s = l2 > 0 ? -(ax * dx + ay * dy) / l2 : 0;
        s = fmin(1, fmax(0, s));
        a->dev = fmax(a->dev, R - hypot(ax + s * dx, ay + s * dy));
    }
    return CJ_OK;
}

/* n contours of the circle at "contour:GRID:TOL" (no measuring). */
int report_contour_workload(const char *spec, long n) {
    int g = 0;
    double tol = 0;
    if (sscanf(spec, "contour:%d:%lf", &g, &tol) != 2 || g < 1 || g > 4096 || !(tol > 0))
        return cli_fail("report", "bad workload '%s' (contour:GRID:TOL)", spec);
    cj_implicit_shape shape;
    cj_implicit f;
    if (cj_implicit_circle(CX, CY, R, &shape, &f)) return 1;
    const double box[4] = {-1, -1, 1, 1};
    const cj_contour_options o = {g, g, tol, NULL};
    for (long k = 0; k < n; ++k) {
        acc a = {0, 0, 0};
        if (cj_implicit_contour(&f, box, &o, emit, &a, NULL)) return 1;
    }
    return 0;
}

int report_contour(report *r) {
    static const int G_FULL[] = {8, 32, 128, 512}, G_QUICK[] = {8, 64};
    static const double T_FULL[] = {1e-2, 1e-4, 1e-6, 1e-8}, T_QUICK[] = {1e-3, 1e-6};
    const int *gs = r->quick ? G_QUICK : G_FULL;
    const double *tols = r->quick ? T_QUICK : T_FULL;
    const int ng = r->quick ? 2 : 4, nt = r->quick ? 2 : 4, runs = r->quick ? 3 : 11;
    cj_implicit_shape shape;
    cj_implicit f;
    if (cj_implicit_circle(CX, CY, R, &shape, &f))
        return cli_error("report", "contour: %s", cj_last_error());
    const double box[4] = {-1, -1, 1, 1};
    enum { NC = 16 };
    double us[NC], spread[NC], dev[NC], pts[NC], instr[NC];
    for (int i = 0; i < ng * nt; ++i) {
        const cj_contour_options o = {gs[i / nt], gs[i / nt], tols[i % nt], NULL};
        double tm[16];
        for (int run = 0; run < runs; ++run) {
            acc a = {0, 0, 0};
            const double t0 = report_now_ns();
            if (cj_implicit_contour(&f, box, &o, emit, &a, NULL))
                return cli_error("report", "contour: %s", cj_last_error());
            tm[run] = (report_now_ns() - t0) / 1e3;
        }
        us[i] = report_median(tm, (size_t)runs, &spread[i]);
        acc a = {1, 0, 0};
        if (cj_implicit_contour(&f, box, &o, emit, &a, NULL))
            return cli_error("report", "contour: %s", cj_last_error());
        dev[i] = a.dev, pts[i] = (double)a.pts;
        char spec[64];
        snprintf(spec, sizeof spec, "contour:%d:%.17g", gs[i / nt], tols[i % nt]);
        instr[i] = r->quick ? NAN : report_callgrind(r, spec, 1, NULL);
    }
    double err[NC];
    int dom[NC];
    for (int i = 0; i < ng * nt; ++i) err[i] = fmax(dev[i], 1e-17);
    report_pareto((size_t)(ng * nt), us, err, dom);
    fprintf(r->html,
            "<h2>Implicit contouring</h2>\n<p>The circle of radius %.2g about (%.2g, %.2g) in "
            "[&minus;1, 1]&sup2;, contoured by cj_implicit_contour on an n&times;n grid at a "
            "tolerance. Deviation: the exact largest distance of the polyline from the circle. "
            "Cost: &micro;s per contour. Pareto front over all choices.</p>\n<table><tr>"
            "<th>grid</th><th>tol</th><th>deviation</th><th>vertices</th><th>&micro;s</th>"
            "<th>spread</th><th>instr</th><th class=l>Pareto</th></tr>\n",
            R, CX, CY);
    fprintf(r->md, "## Implicit contouring (circle)\n\n| grid | tol | deviation | vertices | µs | "
                   "instr | Pareto |\n|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < ng * nt; ++i) {
        char par[96], ins[32];
        if (isfinite(instr[i]))
            snprintf(ins, sizeof ins, "%.0f", instr[i]);
        else
            snprintf(ins, sizeof ins, "—");
        if (dom[i] < 0)
            snprintf(par, sizeof par, "front");
        else
            snprintf(par, sizeof par, "dominated by grid %d at %.0e", gs[dom[i] / nt],
                     tols[dom[i] % nt]);
        fprintf(r->html,
                "<tr%s><td>%d</td><td>%.0e</td><td>%.3g</td><td>%.0f</td><td>%.1f</td>"
                "<td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", gs[i / nt], tols[i % nt], dev[i], pts[i], us[i],
                spread[i], ins, par);
        fprintf(r->md, "| %d | %.0e | %.3g | %.0f | %.1f | %s | %s |\n", gs[i / nt], tols[i % nt],
                dev[i], pts[i], us[i], ins, par);
        fprintf(r->tsv, "contour\tgrid %d\t%.6g\t\t%.6g\t\t%.6g\t%.3f\t%.6g\t%.6g\t%.0f\t%s\n",
                gs[i / nt], tols[i % nt], dev[i], tols[i % nt], 1e3 * us[i], spread[i], instr[i],
                pts[i], dom[i] < 0 ? "front" : "dominated");
    }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return cli_error("report", "%s", cj_last_error());
    cj_chart_set_title(c, "Contouring a circle: deviation vs cost (ringed: dominated, tol)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "µs per contour (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max distance polyline - circle");
    report_front_series(c, (size_t)(ng * nt), us, err, dom, 1e-17, "Pareto front");
    static const cj_rgba COL[4] = {{0xff, 0x7f, 0x0e, 255},
                                   {0x2c, 0xa0, 0x2c, 255},
                                   {0x1f, 0x77, 0xb4, 255},
                                   {0xd6, 0x27, 0x28, 255}};
    static const cj_chart_marker MK[4] = {CJ_MARKER_SQUARE, CJ_MARKER_TRIANGLE, CJ_MARKER_CIRCLE,
                                          CJ_MARKER_SQUARE};
    for (int g = 0; g < ng; ++g) {
        char name[32];
        snprintf(name, sizeof name, "grid %d", gs[g]);
        cj_chart_series_opts o = {name, COL[g], 1.5, MK[g], 5.0};
        cj_chart_add_series(c, us + g * nt, err + g * nt, (size_t)nt, &o);
        for (int t = 0; t < nt; ++t) {
            if (dom[g * nt + t] < 0) continue; /* the annotation rings its point */
            char txt[16];
            snprintf(txt, sizeof txt, "%.0e", tols[t]);
            cj_chart_annotate(c, us[g * nt + t], err[g * nt + t], txt,
                              cj_rgba_make(0x60, 0x60, 0x60, 255));
        }
    }
    const int st = report_chart(r, c, "contour.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}
