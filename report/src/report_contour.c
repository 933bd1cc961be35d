/* casteljau report, section "implicit contouring": cj_implicit_contour by grid size x tolerance
 * of two curves in [-1, 1]², each with an exact measured deviation:
 *  - a circle (radius 0.8, off-centre): over a segment, | |p - c| - r | is largest at an end or
 *    where the segment comes closest to the centre (|p - c| is convex along it), so
 *    max(| |a-c| - r |, | |b-c| - r |, r - d_min) is the segment's deviation from the circle;
 *  - an ellipse (semi-axes 0.85 and 0.4, turned by 0.5 rad, off-centre): the distance of a point
 *    to it by Eberly's bisection (exact up to rounding, ~1e-16 here); along a segment the
 *    signed distance to the convex region inside is convex, so its largest value (outside) is
 *    at an end, and the largest distance inside is the maximum of a concave function, found by
 *    golden-section search on the segment (unimodal: the search converges to it).
 * Per choice: that deviation over all segments (bound: the tolerance), vertices emitted, µs per
 * contour (median of interleaved runs), and in the full report instructions per contour by
 * callgrind (all cells in one run, workload "contour:all", report_cgbatch.c). Pareto fronts per
 * curve. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/implicit.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double CX = 0.03, CY = 0.01, R = 0.8;
static const double EX = -0.02, EY = 0.04, ERX = 0.85, ERY = 0.4, EROT = 0.5;
enum { NSHAPE = 2 };
static const char *const SHAPE[NSHAPE] = {"circle", "ellipse"};

typedef struct acc {
    int measure, shape;
    double dev;
    size_t pts;
} acc;

/* Distance from (y0, y1) (first quadrant) to the ellipse with semi-axes e0 >= e1 > 0: the
 * closest point is (r0 y0 / (s + r0), y1 / (s + 1)) e-scaled, s the root of
 * (r0 z0 / (s + r0))² + (z1 / (s + 1))² = 1 (z = y / e, r0 = (e0/e1)²), which is monotone in s
 * on [z1 - 1, |(r0 z0, z1)| - 1] and found by bisection to the last bit (Eberly, "Distance
 * from a point to an ellipse, an ellipsoid, or a hyperellipsoid"). */
static double ellipse_dist_q1(double e0, double e1, double y0, double y1) {
    if (y1 > 0) {
        if (y0 > 0) {
            const double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
            if (g == 0) return 0;
            const double r0 = (e0 / e1) * (e0 / e1), n0 = r0 * z0;
            double s0 = z1 - 1, s1 = g < 0 ? 0 : hypot(n0, z1) - 1, s = 0;
            for (int i = 0; i < 1100; ++i) {
                s = 0.5 * (s0 + s1);
                if (s == s0 || s == s1) break;
                const double a = n0 / (s + r0), b = z1 / (s + 1), gs = a * a + b * b - 1;
                if (gs > 0)
                    s0 = s;
                else if (gs < 0)
                    s1 = s;
                else
                    break;
            }
            const double x0 = r0 * y0 / (s + r0), x1 = y1 / (s + 1);
            return hypot(x0 - y0, x1 - y1);
        }
        return fabs(y1 - e1);
    }
    const double numer = e0 * y0, denom = e0 * e0 - e1 * e1;
    if (numer < denom) {
        const double xd = numer / denom, x0 = e0 * xd, x1 = e1 * sqrt(1 - xd * xd);
        return hypot(x0 - y0, x1);
    }
    return fabs(y0 - e0);
}

/* Signed distance to the ellipse: negative inside. */
static double ellipse_sdist(double x, double y) {
    const double c = cos(EROT), s = sin(EROT), dx = x - EX, dy = y - EY;
    const double u = c * dx + s * dy, v = -s * dx + c * dy; /* the ellipse's frame */
    const double d = ellipse_dist_q1(ERX, ERY, fabs(u), fabs(v));
    return (u / ERX) * (u / ERX) + (v / ERY) * (v / ERY) < 1 ? -d : d;
}

/* Largest distance of the segment a-b to the ellipse (see the top of the file). */
static double ellipse_segment_dev(const double *a, const double *b) {
    double dev = fmax(fabs(ellipse_sdist(a[0], a[1])), fabs(ellipse_sdist(b[0], b[1])));
    const double phi = 0.6180339887498949;
    double lo = 0, hi = 1, m1 = hi - phi * (hi - lo), m2 = lo + phi * (hi - lo);
    double f1 = -ellipse_sdist(a[0] + m1 * (b[0] - a[0]), a[1] + m1 * (b[1] - a[1]));
    double f2 = -ellipse_sdist(a[0] + m2 * (b[0] - a[0]), a[1] + m2 * (b[1] - a[1]));
    for (int it = 0; it < 80 && hi - lo > 1e-15; ++it) { /* maximise the concave -sdist */
        if (f1 < f2) {
            lo = m1, m1 = m2, f1 = f2, m2 = lo + phi * (hi - lo);
            f2 = -ellipse_sdist(a[0] + m2 * (b[0] - a[0]), a[1] + m2 * (b[1] - a[1]));
        } else {
            hi = m2, m2 = m1, f2 = f1, m1 = hi - phi * (hi - lo);
            f1 = -ellipse_sdist(a[0] + m1 * (b[0] - a[0]), a[1] + m1 * (b[1] - a[1]));
        }
        dev = fmax(dev, fmax(f1, f2));
    }
    return dev;
}

static cj_status emit(void *user, const double *xy, size_t npts, int closed, double res) {
    (void)closed, (void)res;
    acc *a = user;
    a->pts += npts;
    if (!a->measure) return CJ_OK;
    if (a->shape) {
        for (size_t i = 0; i + 1 < npts; ++i)
            a->dev = fmax(a->dev, ellipse_segment_dev(xy + 2 * i, xy + 2 * i + 2));
        if (npts == 1) a->dev = fmax(a->dev, fabs(ellipse_sdist(xy[0], xy[1])));
        return CJ_OK;
    }
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

static cj_status make_shape(int which, cj_implicit_shape *shape, cj_implicit *f) {
    return which ? cj_implicit_ellipse(EX, EY, ERX, ERY, EROT, shape, f)
                 : cj_implicit_circle(CX, CY, R, shape, f);
}

static const int G_FULL[] = {8, 32, 128, 512};
static const double T_FULL[] = {1e-2, 1e-4, 1e-6, 1e-8};
enum { NG_FULL = 4, NT_FULL = 4 };

/* Cell i of the full table (curve i / 16, grid (i / 4) % 4, tolerance i % 4): `units`
 * contours; 0 units: the curve's set-up only. */
static int contour_cell(void *ctx, int i, long units) {
    (void)ctx;
    const int which = i / (NG_FULL * NT_FULL), g = (i / NT_FULL) % NG_FULL, t = i % NT_FULL;
    cj_implicit_shape shape;
    cj_implicit f;
    if (make_shape(which, &shape, &f)) return 1;
    const double box[4] = {-1, -1, 1, 1};
    const cj_contour_options o = {G_FULL[g], G_FULL[g], T_FULL[t], NULL};
    for (long k = 0; k < units; ++k) {
        acc a = {0, which, 0, 0};
        if (cj_implicit_contour(&f, box, &o, emit, &a, NULL)) return 1;
    }
    return 0;
}

/* n contours at "contour:GRID:TOL[:SHAPE]" (SHAPE 0 circle (default), 1 ellipse; no
 * measuring); "contour:all": every cell of the full table (report_cells_workload). */
int report_contour_workload(const char *spec, long n) {
    if (!strcmp(spec, "contour:all"))
        return report_cells_workload(NSHAPE * NG_FULL * NT_FULL, n, contour_cell, NULL);
    int g = 0, which = 0;
    double tol = 0;
    if (sscanf(spec, "contour:%d:%lf:%d", &g, &tol, &which) < 2 || g < 1 || g > 4096 ||
        !(tol > 0) || which < 0 || which >= NSHAPE)
        return report_fail("bad workload '%s' (contour:GRID:TOL[:SHAPE])", spec);
    cj_implicit_shape shape;
    cj_implicit f;
    if (make_shape(which, &shape, &f)) return 1;
    const double box[4] = {-1, -1, 1, 1};
    const cj_contour_options o = {g, g, tol, NULL};
    for (long k = 0; k < n; ++k) {
        acc a = {0, which, 0, 0};
        if (cj_implicit_contour(&f, box, &o, emit, &a, NULL)) return 1;
    }
    return 0;
}

enum { NC = 16 };

/* Table rows and chart of one curve's ng x nt choices. */
static void contour_output(report *r, int which, const int *gs, int ng, const double *tols, int nt,
                           const double *us, const double *spread, const double *dev,
                           const double *pts, const double *instr) {
    const int n = ng * nt;
    double err[NC];
    int dom[NC];
    for (int i = 0; i < n; ++i) err[i] = fmax(dev[i], 1e-17);
    report_pareto((size_t)n, us, err, dom);
    for (int i = 0; i < n; ++i) {
        char par[96], ins[32], name[32];
        snprintf(name, sizeof name, which ? "grid %d (ellipse)" : "grid %d", gs[i / nt]);
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
                "<tr%s><td class=l>%s</td><td>%d</td><td>%.0e</td><td>%.3g</td><td>%.0f</td>"
                "<td>%.1f</td><td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", SHAPE[which], gs[i / nt], tols[i % nt], dev[i],
                pts[i], us[i], spread[i], ins, par);
        fprintf(r->md, "| %s | %d | %.0e | %.3g | %.0f | %.1f | %s | %s |\n", SHAPE[which],
                gs[i / nt], tols[i % nt], dev[i], pts[i], us[i], ins, par);
        fprintf(r->tsv, "contour\t%s\t%.6g\t\t%.6g\t\t%.6g\t%.3f\t%.6g\t%.6g\t%.0f\t%s\n", name,
                tols[i % nt], dev[i], tols[i % nt], 1e3 * us[i], spread[i], instr[i], pts[i],
                dom[i] < 0 ? "front" : "dominated");
    }
}

static int contour_chart(report *r, int which, const int *gs, int ng, const double *tols, int nt,
                         const double *us, const double *dev) {
    const int n = ng * nt;
    double err[NC];
    int dom[NC];
    for (int i = 0; i < n; ++i) err[i] = fmax(dev[i], 1e-17);
    report_pareto((size_t)n, us, err, dom);
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    char title[96];
    snprintf(title, sizeof title, "Contouring %s: deviation vs cost (ringed: dominated, tol)",
             which ? "an ellipse" : "a circle");
    cj_chart_set_title(c, title);
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "µs per contour (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10,
                      which ? "max distance polyline - ellipse" : "max distance polyline - circle");
    report_front_series(c, (size_t)n, us, err, dom, 1e-17, "Pareto front");
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
    const int st = report_chart(r, c, which ? "contour_ellipse.png" : "contour.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}

int report_contour(report *r) {
    static const int G_QUICK[] = {8, 64}, G_QUICK_E[] = {64};
    static const double T_QUICK[] = {1e-3, 1e-6};
    const double *tols = r->quick ? T_QUICK : T_FULL;
    const int nt = r->quick ? 2 : NT_FULL, runs = r->quick ? 3 : 11;
    const double box[4] = {-1, -1, 1, 1};
    static double us[NSHAPE][NC], spread[NSHAPE][NC], dev[NSHAPE][NC], pts[NSHAPE][NC],
        instr[NSHAPE][NC];
    const int *gsof[NSHAPE];
    int ngof[NSHAPE];
    for (int which = 0; which < NSHAPE; ++which) {
        /* quick: the ellipse on one grid only */
        gsof[which] = r->quick ? (which ? G_QUICK_E : G_QUICK) : G_FULL;
        ngof[which] = r->quick ? (which ? 1 : 2) : NG_FULL;
        const int *gs = gsof[which];
        cj_implicit_shape shape;
        cj_implicit f;
        if (make_shape(which, &shape, &f)) return report_error("contour: %s", cj_last_error());
        for (int i = 0; i < ngof[which] * nt; ++i) {
            const cj_contour_options o = {gs[i / nt], gs[i / nt], tols[i % nt], NULL};
            double tm[16];
            for (int run = 0; run < runs; ++run) {
                acc a = {0, which, 0, 0};
                const double t0 = report_now_ns();
                if (cj_implicit_contour(&f, box, &o, emit, &a, NULL))
                    return report_error("contour: %s", cj_last_error());
                tm[run] = (report_now_ns() - t0) / 1e3;
            }
            us[which][i] = report_median(tm, (size_t)runs, &spread[which][i]);
            acc a = {1, which, 0, 0};
            if (cj_implicit_contour(&f, box, &o, emit, &a, NULL))
                return report_error("contour: %s", cj_last_error());
            dev[which][i] = a.dev, pts[which][i] = (double)a.pts;
            instr[which][i] = NAN;
        }
    }
    /* instructions per contour, every cell in one callgrind run (1 contour each) */
    if (!r->quick)
        report_callgrind_cells(r, "contour:all", 1, NSHAPE * NG_FULL * NT_FULL, &instr[0][0]);
    fprintf(r->html,
            "<h2>Implicit contouring</h2>\n<p>Two curves in [&minus;1, 1]&sup2;, contoured by "
            "cj_implicit_contour on an n&times;n grid at a tolerance: the circle of radius %.2g "
            "about (%.2g, %.2g), and the ellipse with semi-axes %.2g and %.2g about (%.2g, %.2g) "
            "turned by %.2g rad. Deviation: the exact largest distance of the polyline from the "
            "curve (circle: per segment, its ends and its closest approach to the centre; "
            "ellipse: point distances by Eberly's bisection, per segment its ends and the maximum "
            "of the concave inside distance by golden-section search). Cost: &micro;s per "
            "contour. Pareto front per curve.</p>\n<table><tr><th class=l>curve</th><th>grid"
            "</th><th>tol</th><th>deviation</th><th>vertices</th><th>&micro;s</th><th>spread"
            "</th><th>instr</th><th class=l>Pareto</th></tr>\n",
            R, CX, CY, ERX, ERY, EX, EY, EROT);
    fprintf(r->md, "## Implicit contouring (circle, ellipse)\n\n| curve | grid | tol | deviation | "
                   "vertices | µs | instr | Pareto |\n|---|---|---|---|---|---|---|---|\n");
    for (int which = 0; which < NSHAPE; ++which)
        contour_output(r, which, gsof[which], ngof[which], tols, nt, us[which], spread[which],
                       dev[which], pts[which], instr[which]);
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    for (int which = 0; which < NSHAPE; ++which) {
        const int st =
            contour_chart(r, which, gsof[which], ngof[which], tols, nt, us[which], dev[which]);
        if (st) return st;
    }
    return 0;
}
