// bench_bspline: casteljau's B-splines against OpenCASCADE in the same run (issue 22): NURBS
// evaluation per point, knot insertion, interpolation and approximation of 1e4 points. Times are
// thread CPU seconds, the median of repetitions; the ratio column is OCCT time / ours.
#include "bench_clock.h"
#include "occt_bspline.h"

extern "C" {
#include "rng.h"
}
#include "casteljau/bspline.h"
#include "casteljau/bspline_fit.h"

#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt.hxx>

#include <cmath>
#include <cstdio>
#include <vector>

template <class F> static double median_time(int reps, F f) {
    std::vector<double> t(reps);
    for (int r = 0; r < reps; ++r) {
        const double t0 = cj_bench_thread_cpu();
        f();
        t[r] = cj_bench_thread_cpu() - t0;
    }
    return cj_bench_median(t.data(), t.size());
}

static volatile double sink;

static void row(const char *what, double ours, double occt, const char *unit, double scale) {
    std::printf("%-44s %10.1f %10.1f %s   x%.2f\n", what, ours * scale, occt * scale, unit,
                occt / ours);
}

int main() {
    cj_rng r;
    cj_rng_init(&r, 2026);
    std::printf("%-44s %10s %10s\n", "", "casteljau", "OCCT");
    // ---- evaluation: cubic, 100 control points, 3D, polynomial and rational
    const int n = 100, p = 3, NT = 1000000;
    std::vector<double> pts(3 * n), w(n), k(n + p + 1), ts(NT), out(3 * NT);
    for (auto &x : pts) x = cj_rng_range(&r, -1, 1);
    for (auto &x : w) x = cj_rng_range(&r, 0.5, 2);
    cj_bspline_uniform_knots(n, p, 0.0, 1.0, 1, k.data());
    for (auto &t : ts) t = cj_rng_unit(&r);
    for (int rational = 0; rational < 2; ++rational) {
        const cj_bspline c =
            cj_bspline_view(p, 3, n, pts.data(), rational ? w.data() : nullptr, k.data());
        Handle(Geom_BSplineCurve) g = cj_to_occt(c);
        const double ours =
            median_time(5, [&] { cj_bspline_eval_batch(&c, ts.data(), NT, out.data()); });
        const double unchecked = median_time(5, [&] {
            for (int j = 0; j < NT; ++j) cj_bspline_eval_unchecked(&c, ts[j], out.data() + 3 * j);
        });
        const double checked = median_time(3,
                                           [&] {
                                               for (int j = 0; j < NT / 10; ++j)
                                                   cj_bspline_eval(&c, ts[j], out.data() + 3 * j);
                                           }) *
                               10;
        const double occt = median_time(5, [&] {
            gp_Pnt P;
            double s = 0;
            for (int j = 0; j < NT; ++j) {
                g->D0(ts[j], P);
                s += P.X();
            }
            sink = s;
        });
        char label[80];
        std::snprintf(label, sizeof label, "eval %s, p=3, 100 pts (batch), ns/point",
                      rational ? "NURBS" : "B-spline");
        row(label, ours / NT, occt / NT, "ns", 1e9);
        std::snprintf(label, sizeof label, "  unchecked per call, ns/point");
        row(label, unchecked / NT, occt / NT, "ns", 1e9);
        std::snprintf(label, sizeof label, "  checked cj_bspline_eval, ns/point");
        row(label, checked / NT, occt / NT, "ns", 1e9);
        // derivatives up to 2
        const double d2 = median_time(3,
                                      [&] {
                                          double d[9];
                                          double s = 0;
                                          for (int j = 0; j < NT / 10; ++j) {
                                              cj_bspline_eval_derivs(&c, ts[j], 2, d);
                                              s += d[0];
                                          }
                                          sink = s;
                                      }) *
                          10;
        const double od2 = median_time(3,
                                       [&] {
                                           gp_Pnt P;
                                           gp_Vec V1, V2;
                                           double s = 0;
                                           for (int j = 0; j < NT / 10; ++j) {
                                               g->D2(ts[j], P, V1, V2);
                                               s += P.X();
                                           }
                                           sink = s;
                                       }) *
                           10;
        std::snprintf(label, sizeof label, "  point + 2 derivatives (checked), ns/point");
        row(label, d2 / NT, od2 / NT, "ns", 1e9);
        const double u2 = median_time(3,
                                      [&] {
                                          double d[9];
                                          double s = 0;
                                          for (int j = 0; j < NT / 10; ++j) {
                                              cj_bspline_eval_derivs_unchecked(&c, ts[j], 2, d);
                                              s += d[0];
                                          }
                                          sink = s;
                                      }) *
                          10;
        std::snprintf(label, sizeof label, "  point + 2 derivatives (unchecked), ns/point");
        row(label, u2 / NT, od2 / NT, "ns", 1e9);
    }
    // ---- knot insertion into a 1000-point cubic NURBS, one knot
    {
        const int N = 1000, R = 200;
        std::vector<double> P(3 * N), W(N), K(N + 4), xs(R), op(3 * (N + 1)), ow(N + 1), ok(N + 5);
        for (auto &x : P) x = cj_rng_range(&r, -1, 1);
        for (auto &x : W) x = cj_rng_range(&r, 0.5, 2);
        cj_bspline_uniform_knots(N, 3, 0.0, 1.0, 1, K.data());
        for (auto &x : xs) x = 0.001 + 0.998 * cj_rng_unit(&r);
        const cj_bspline c = cj_bspline_view(3, 3, N, P.data(), W.data(), K.data());
        const double ours = median_time(5, [&] {
            for (int j = 0; j < R; ++j)
                cj_bspline_insert_knot(&c, xs[j], 1, op.data(), ow.data(), ok.data());
        });
        Handle(Geom_BSplineCurve) g = cj_to_occt(c);
        std::vector<Handle(Geom_BSplineCurve)> copies(R);
        double occt_total = 0;
        std::vector<double> samples;
        for (int rep = 0; rep < 5; ++rep) {
            for (int j = 0; j < R; ++j) copies[j] = Handle(Geom_BSplineCurve)::DownCast(g->Copy());
            const double t0 = cj_bench_thread_cpu();
            for (int j = 0; j < R; ++j) copies[j]->InsertKnot(xs[j], 1, 0.0);
            samples.push_back(cj_bench_thread_cpu() - t0);
        }
        occt_total = cj_bench_median(samples.data(), samples.size());
        row("insert 1 knot, cubic NURBS of 1000 pts, us", ours / R, occt_total / R, "us", 1e6);
    }
    // ---- fitting 1e4 points of a helix
    {
        const int N = 10000;
        std::vector<double> q(3 * N), ts2(N), P(3 * N), U(N + 4);
        for (int i = 0; i < N; ++i) {
            const double a = 20.0 * i / (N - 1);
            q[3 * i] = std::cos(a), q[3 * i + 1] = std::sin(a), q[3 * i + 2] = 0.1 * a;
        }
        cj_fit_params(q.data(), N, 3, CJ_FIT_CHORD, ts2.data());
        int m = 0;
        const double ours = median_time(5, [&] {
            cj_bspline_interpolate(q.data(), N, 3, 3, CJ_FIT_CHORD, nullptr, nullptr, P.data(),
                                   U.data(), &m, nullptr);
        });
        Handle(TColgp_HArray1OfPnt) hp = new TColgp_HArray1OfPnt(1, N);
        Handle(TColStd_HArray1OfReal) hprm = new TColStd_HArray1OfReal(1, N);
        for (int i = 0; i < N; ++i) {
            hp->SetValue(i + 1, gp_Pnt(q[3 * i], q[3 * i + 1], q[3 * i + 2]));
            hprm->SetValue(i + 1, ts2[i]);
        }
        const double occt = median_time(3, [&] {
            GeomAPI_Interpolate gi(hp, hprm, Standard_False, 1e-12);
            gi.Perform();
            sink = gi.IsDone();
        });
        row("interpolate 1e4 points (cubic), ms", ours, occt, "ms", 1e3);
        double dev = 0;
        const double tol = 1e-5;
        const double oa = median_time(3, [&] {
            cj_bspline_approximate(q.data(), N, 3, 3, CJ_FIT_CHORD, tol, N, P.data(), U.data(), &m,
                                   &dev);
        });
        TColgp_Array1OfPnt arr(1, N);
        for (int i = 0; i < N; ++i)
            arr.SetValue(i + 1, gp_Pnt(q[3 * i], q[3 * i + 1], q[3 * i + 2]));
        int occt_poles = 0;
        const double ob = median_time(1, [&] {
            GeomAPI_PointsToBSpline pb(arr, 3, 3, GeomAbs_C2, tol);
            occt_poles = pb.IsDone() ? pb.Curve()->NbPoles() : -1;
        });
        char label[90];
        std::snprintf(label, sizeof label, "approximate 1e4 points to 1e-5, ms");
        row(label, oa, ob, "ms", 1e3);
        std::printf("  (ours: %d control points, deviation at the data %.3g; OCCT: %d poles)\n", m,
                    dev, occt_poles);
    }
    return 0;
}
