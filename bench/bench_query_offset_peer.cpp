// Offsets of the same cubics by casteljau and by OpenCASCADE, in the same run (issue 23).
// OpenCASCADE's offset is Geom2d_OffsetCurve of the Bézier curve (exact, evaluated on demand),
// approximated to the same tolerance by Geom2dConvert_ApproxCurve (Geom2d's own conversion to a
// B-spline): once with cubic spans and C1 joints, the class of curve ours returns, once with its
// defaults for a designer (C2, degree up to 14). Both outputs go through the same dense check:
// every output piece (ours: a cubic on [breaks[k], breaks[k+1]]; OCCT's: a knot span) sampled at
// 33 parameters, each compared with the exact offset at the same parameter computed in long
// double. A parametric distance bounds the geometric one, so "tolerance met" is fair both ways.
#include "bench_query_peers.h"

#include "bench_clock.h"

#include "casteljau/offset.h"

#include <Geom2dConvert_ApproxCurve.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_OffsetCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

enum { SAMPLES_PER_PIECE = 33, OFFSET_REPS = 3, OFFSET_CAP = 4096 };

// The exact offset of the cubic p at parameter t, in long double: c(t) + d N(t), N the unit
// left normal (c' turned +90 degrees).
static void exact_offset(const double *p, double d, double t, long double out[2]) {
    long double s = 1.0L - t, u = t;
    long double b[4] = {s * s * s, 3 * s * s * u, 3 * s * u * u, u * u * u};
    long double db[3] = {3 * s * s, 6 * s * u, 3 * u * u};
    long double c[2] = {0, 0}, dc[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        for (int i = 0; i < 4; ++i) c[k] += b[i] * p[2 * i + k];
        for (int i = 0; i < 3; ++i) dc[k] += db[i] * (p[2 * i + 2 + k] - p[2 * i + k]);
    }
    long double len = sqrtl(dc[0] * dc[0] + dc[1] * dc[1]);
    out[0] = c[0] - d * dc[1] / len;
    out[1] = c[1] + d * dc[0] / len;
}

static double dist_to_exact(const double *p, double d, double t, double x, double y) {
    long double o[2];
    exact_offset(p, d, t, o);
    return (double)hypotl(x - o[0], y - o[1]);
}

// Largest sampled distance of our pieces (8 doubles each, piece k on [br[k], br[k+1]]) to the
// exact offset at the same parameter.
static double check_ours(const double *p, double d, const double *pts, const double *br, int np) {
    double worst = 0.0;
    for (int k = 0; k < np; ++k) {
        const double *q = pts + 8 * k;
        for (int j = 0; j < SAMPLES_PER_PIECE; ++j) {
            double u = (double)j / (SAMPLES_PER_PIECE - 1), s = 1.0 - u;
            double w[4] = {s * s * s, 3 * s * s * u, 3 * s * u * u, u * u * u};
            double x = 0, y = 0;
            for (int i = 0; i < 4; ++i) x += w[i] * q[2 * i], y += w[i] * q[2 * i + 1];
            double t = br[k] + u * (br[k + 1] - br[k]);
            worst = std::fmax(worst, dist_to_exact(p, d, t, x, y));
        }
    }
    return worst;
}

// The same for OCCT's B-spline, per knot span.
static double check_occt(const double *p, double d, const Handle(Geom2d_BSplineCurve) & bs) {
    double worst = 0.0;
    for (int k = 1; k < bs->NbKnots(); ++k) {
        double a = bs->Knot(k), b = bs->Knot(k + 1);
        for (int j = 0; j < SAMPLES_PER_PIECE; ++j) {
            double t = a + (b - a) * j / (SAMPLES_PER_PIECE - 1);
            gp_Pnt2d v = bs->Value(t);
            worst = std::fmax(worst, dist_to_exact(p, d, t, v.X(), v.Y()));
        }
    }
    return worst;
}

struct occt_setting {
    const char *what;
    GeomAbs_Shape order;
    int max_degree;
};

void cj_bench_offsets_vs_occt(const double (*curves)[8], int ncurves, double d, double tol,
                              int only_setting) {
    std::vector<double> pts(8 * OFFSET_CAP), br(OFFSET_CAP + 1);
    double times[OFFSET_REPS];
    // ours: timed, then checked
    long pieces = 0;
    int done = 0;
    for (int r = 0; r < OFFSET_REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        pieces = done = 0;
        for (int i = 0; i < ncurves; ++i) {
            cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL);
            int np = 0;
            double dev;
            if (cj_offset_curve(&a, d, tol, pts.data(), br.data(), OFFSET_CAP, &np, &dev, NULL) ==
                CJ_OK)
                pieces += np, ++done;
        }
        times[r] = (cj_bench_thread_cpu() - t0) / ncurves;
    }
    double t_ours = cj_bench_median(times, OFFSET_REPS);
    int met = 0;
    double worst = 0.0, worst_proven = 0.0;
    for (int i = 0; i < ncurves; ++i) {
        cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL);
        int np = 0;
        double dev = 0.0;
        if (cj_offset_curve(&a, d, tol, pts.data(), br.data(), OFFSET_CAP, &np, &dev, NULL) !=
            CJ_OK)
            continue;
        double e = check_ours(curves[i], d, pts.data(), br.data(), np);
        worst = std::fmax(worst, e), worst_proven = std::fmax(worst_proven, dev);
        met += e <= tol;
    }
    printf("offset a cubic by %g, tol %g: casteljau %8.1f us per curve (proven), %5.1f cubic "
           "pieces per curve; %d of %d offset, dense check: %d within tol, worst %.3g (proven "
           "bound %.3g)\n",
           d, tol, 1e6 * t_ours, done ? (double)pieces / done : 0.0, done, ncurves, met, ncurves,
           worst, worst_proven);
    // OpenCASCADE: ours offsets to the left (+d); Geom2d_OffsetCurve along T ^ Z, to the right,
    // so it gets -d. The Bézier curves and offset curves are built outside the timing.
    std::vector<Handle(Geom2d_OffsetCurve)> off(ncurves);
    for (int i = 0; i < ncurves; ++i) {
        TColgp_Array1OfPnt2d poles(1, 4);
        for (int j = 0; j < 4; ++j) poles(j + 1) = gp_Pnt2d(curves[i][2 * j], curves[i][2 * j + 1]);
        off[i] = new Geom2d_OffsetCurve(new Geom2d_BezierCurve(poles), -d);
    }
    gp_Pnt2d probe = off[0]->Value(0.3);
    long double o[2];
    exact_offset(curves[0], d, 0.3, o);
    printf("  (OCCT's offset at t = 0.3 of curve 0 is %.3g from the exact one: same side)\n",
           (double)hypotl(probe.X() - o[0], probe.Y() - o[1]));
    const occt_setting settings[] = {
        {"C1 cubic spans (our class)", GeomAbs_C1, 3},
        {"C2, degree <= 14 (its defaults)", GeomAbs_C2, 14},
    };
    for (int si = 0; si < 2; ++si) {
        const occt_setting &s = settings[si];
        if (only_setting && only_setting != si + 1) continue;
        long spans = 0;
        int ok = 0, failed = 0, claimed = 0, top_degree = 0;
        std::vector<Handle(Geom2d_BSplineCurve)> out(ncurves);
        for (int r = 0; r < OFFSET_REPS; ++r) {
            double t0 = cj_bench_thread_cpu();
            spans = ok = failed = claimed = top_degree = 0;
            for (int i = 0; i < ncurves; ++i) {
                try {
                    Geom2dConvert_ApproxCurve approx(off[i], tol, s.order, 1000, s.max_degree);
                    if (!approx.HasResult()) {
                        ++failed;
                        continue;
                    }
                    out[i] = approx.Curve();
                    spans += out[i]->NbKnots() - 1, ++ok;
                    top_degree = std::max(top_degree, out[i]->Degree());
                    claimed += approx.IsDone() && approx.MaxError() <= tol;
                } catch (const Standard_Failure &) {
                    ++failed;
                }
            }
            times[r] = (cj_bench_thread_cpu() - t0) / ncurves;
        }
        double t_occ = cj_bench_median(times, OFFSET_REPS);
        int occ_met = 0;
        double occ_worst = 0.0;
        for (int i = 0; i < ncurves; ++i) {
            if (out[i].IsNull()) continue;
            double e = check_occt(curves[i], d, out[i]);
            occ_worst = std::fmax(occ_worst, e);
            occ_met += e <= tol;
        }
        printf(
            "  OpenCASCADE %-32s %8.1f us per curve: %.2fx ours; %5.1f spans per curve "
            "(degree up to %d); %d of %d approximated (%d failed), %d claim MaxError <= tol; dense "
            "check: %d within tol, worst %.3g\n",
            s.what, 1e6 * t_occ, t_occ / t_ours, ok ? (double)spans / ok : 0.0, top_degree, ok,
            ncurves, failed, claimed, occ_met, ncurves, occ_worst);
    }
}
