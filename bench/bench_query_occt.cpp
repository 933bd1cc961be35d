// bench_query_occt: OpenCASCADE (Debian libocct-*-dev) on the same seeded random cubics as
// bench_query, in the same run as ours: Geom2dAPI_InterCurveCurve per pair and
// Geom2dAPI_ProjectPointOnCurve per query, with agreement counts; kurbo 0.7 (linked in, a Rust
// static library) on the same nearest-point queries and on curve-line intersections (the only
// intersection it has); offsets against OpenCASCADE's (bench_query_offset_peer.cpp). The
// adversarial pairs are the CTest test_query_adversarial. Where the two disagree, our
// answers carry proofs (enclosures proven to hold exactly one root; a proven lower bound of the
// distance), so the line says which side each disagreement falls on.
#include "bench_clock.h"
#include "bench_query_peers.h"

#include "casteljau/intersect.h"
#include "casteljau/nearest.h"

#include <Geom2dAPI_InterCurveCurve.hxx>
#include <Geom2dAPI_ProjectPointOnCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Line.hxx>
#include <gp_Dir2d.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

static uint64_t state = 0x9e3779b97f4a7c15u;
static double unit() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (double)(state >> 11) * 0x1p-53;
}

enum { NCURVES = 2000, REPS = 5, NOFFSETS = 200 };

static Handle(Geom2d_BezierCurve) occ_curve(const double *p, int n) {
    TColgp_Array1OfPnt2d poles(1, n + 1);
    for (int j = 0; j <= n; ++j) poles(j + 1) = gp_Pnt2d(p[2 * j], p[2 * j + 1]);
    return new Geom2d_BezierCurve(poles);
}

#ifdef CJ_HAVE_KURBO
// kurbo in the same process: nearest points on the same queries (accuracy 1e-10, as ours), and
// the intersection of each cubic with a random line (ours certified, kurbo's
// PathSeg::intersect_line on a segment long enough to cross the whole unit square).
static void kurbo_rows(const double (*curves)[8],
                       const std::vector<Handle(Geom2d_BezierCurve)> &occ, const double *qx,
                       const double *qy, const double *dours, const double *lours,
                       double t_ours_nearest) {
    std::vector<double> dk(NCURVES), tk(NCURVES);
    double times[REPS];
    for (int r = 0; r < REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        for (int i = 0; i < NCURVES; ++i)
            dk[i] = cj_bench_kurbo_nearest(curves[i], qx[i], qy[i], 1e-10, &tk[i]);
        times[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
    }
    double mk = cj_bench_median(times, REPS);
    // kurbo measures the distance to its quadratic approximation of the cubic (within the
    // accuracy), so its figure can lie below the true minimum: the cubic is re-evaluated at its
    // parameter in long double, which no true distance can undercut our proven lower bound.
    int agree = 0, farther = 0, below = 0, true_below = 0;
    double worst = 0.0, under = 0.0;
    for (int i = 0; i < NCURVES; ++i) {
        if (std::fabs(dk[i] - dours[i]) <= 1e-9)
            ++agree;
        else if (dk[i] > dours[i])
            ++farther, worst = std::fmax(worst, dk[i] - dours[i]);
        long double s = 1.0L - tk[i], u = tk[i], x = 0, y = 0;
        long double w[4] = {s * s * s, 3 * s * s * u, 3 * s * u * u, u * u * u};
        for (int k = 0; k < 4; ++k) x += w[k] * curves[i][2 * k], y += w[k] * curves[i][2 * k + 1];
        double exact = (double)hypotl(x - qx[i], y - qy[i]);
        under = std::fmax(under, exact - dk[i]);
        if (dk[i] < lours[i] - 1e-12) ++below;
        if (exact < lours[i] - 1e-15) ++true_below;
    }
    printf("nearest point, cubic:  kurbo 0.7 %8.2f us (CubicBez::nearest, accuracy 1e-10, not "
           "certified): %.1fx ours; agree within 1e-9 on %d of %d (kurbo farther on %d, by up to "
           "%.3g); its reported distance is below our proven lower bound on %d, being the "
           "distance to its quadratic approximation (up to %.3g under the cubic's at its own t); "
           "the cubic's distance at kurbo's t below that bound on %d\n",
           1e6 * mk, mk / t_ours_nearest, agree, NCURVES, farther, worst, below, under, true_below);
    // curve-line intersections
    std::vector<double> lines(4 * NCURVES);
    for (int i = 0; i < NCURVES; ++i) {
        double a = 6.283185307179586 * unit();
        lines[4 * i] = unit(), lines[4 * i + 1] = unit();
        lines[4 * i + 2] = std::cos(a), lines[4 * i + 3] = std::sin(a);
    }
    std::vector<int> nours(NCURVES), nk(NCURVES), nocc(NCURVES);
    std::vector<Handle(Geom2d_Line)> occ_lines(NCURVES);
    for (int i = 0; i < NCURVES; ++i)
        occ_lines[i] = new Geom2d_Line(gp_Pnt2d(lines[4 * i], lines[4 * i + 1]),
                                       gp_Dir2d(lines[4 * i + 2], lines[4 * i + 3]));
    double t_ours[REPS], t_k[REPS], t_occ[REPS];
    cj_isect res[16];
    for (int r = 0; r < REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        for (int i = 0; i < NCURVES; ++i) {
            cj_bezier2 c = cj_bezier2_view(3, curves[i], NULL);
            int n = 0;
            cj_intersect_line(&c, &lines[4 * i], &lines[4 * i + 2], 1e-9, res, 16, &n);
            nours[i] = n;
        }
        t_ours[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
        t0 = cj_bench_thread_cpu();
        for (int i = 0; i < NCURVES; ++i) {
            const double *l = &lines[4 * i];
            double ts[3];
            nk[i] = (int)cj_bench_kurbo_intersect_line(curves[i], l[0] - 3 * l[2], l[1] - 3 * l[3],
                                                       l[0] + 3 * l[2], l[1] + 3 * l[3], ts);
        }
        t_k[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
        t0 = cj_bench_thread_cpu();
        for (int i = 0; i < NCURVES; ++i) {
            Geom2dAPI_InterCurveCurve inter(occ[i], occ_lines[i], 1e-9);
            nocc[i] = inter.NbPoints() + inter.NbSegments();
        }
        t_occ[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
    }
    int lagree = 0, kfewer = 0, kmore = 0, oagree = 0;
    for (int i = 0; i < NCURVES; ++i) {
        oagree += nocc[i] == nours[i];
        if (nours[i] == nk[i])
            ++lagree;
        else if (nk[i] < nours[i])
            ++kfewer;
        else
            ++kmore;
    }
    double mo = cj_bench_median(t_ours, REPS);
    mk = cj_bench_median(t_k, REPS);
    printf("intersect cubic-line:  casteljau %8.2f us (certified), kurbo 0.7 %8.2f us (cubic "
           "solve, not certified): %.2fx; counts agree on %d of %d (kurbo fewer on %d, more on "
           "%d)\n",
           1e6 * mo, 1e6 * mk, mk / mo, lagree, NCURVES, kfewer, kmore);
    double mc = cj_bench_median(t_occ, REPS);
    printf("intersect cubic-line:  OpenCASCADE %8.2f us (Geom2dAPI_InterCurveCurve with a "
           "Geom2d_Line): %.2fx ours; counts agree with ours on %d of %d\n",
           1e6 * mc, mc / mo, oagree, NCURVES);
    printf("kurbo 0.7 has no curve-curve intersection, no self-intersection and no offsets (its "
           "offset module came later): those rows are ours and OpenCASCADE's only\n");
}
#endif

// `bench_query_occt offsets [1|2]` runs the offset rows alone, OpenCASCADE with one setting
// (for callgrind, with --toggle-collect=cj_offset_curve or Geom2dConvert_ApproxCurve's
// constructor).
int main(int argc, char **argv) {
    static double curves[NCURVES][8];
    for (int i = 0; i < NCURVES; ++i)
        for (int k = 0; k < 8; ++k) curves[i][k] = unit();
    std::vector<Handle(Geom2d_BezierCurve)> occ(NCURVES);
    for (int i = 0; i < NCURVES; ++i) {
        TColgp_Array1OfPnt2d poles(1, 4);
        for (int j = 0; j < 4; ++j) poles(j + 1) = gp_Pnt2d(curves[i][2 * j], curves[i][2 * j + 1]);
        occ[i] = new Geom2d_BezierCurve(poles);
    }
    if (argc > 1 && std::strcmp(argv[1], "offsets") == 0) {
        cj_bench_offsets_vs_occt(curves, NOFFSETS, 0.05, 1e-4, argc > 2 ? std::atoi(argv[2]) : 0);
        return 0;
    }
    // intersections: ours and OCCT's, counts compared per pair
    cj_isect res[64];
    std::vector<int> ours(NCURVES / 2), theirs(NCURVES / 2);
    double t_ours[REPS], t_occ[REPS];
    for (int r = 0; r < REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        for (int i = 0; i + 1 < NCURVES; i += 2) {
            cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL);
            cj_bezier2 b = cj_bezier2_view(3, curves[i + 1], NULL);
            int n = 0;
            cj_intersect_curves(&a, &b, 1e-9, res, 64, &n);
            ours[i / 2] = n;
        }
        t_ours[r] = (cj_bench_thread_cpu() - t0) / (NCURVES / 2);
        t0 = cj_bench_thread_cpu();
        for (int i = 0; i + 1 < NCURVES; i += 2) {
            Geom2dAPI_InterCurveCurve inter(occ[i], occ[i + 1], 1e-9);
            theirs[i / 2] = inter.NbPoints() + inter.NbSegments();
        }
        t_occ[r] = (cj_bench_thread_cpu() - t0) / (NCURVES / 2);
    }
    int agree = 0, occ_fewer = 0, occ_more = 0;
    for (int i = 0; i < NCURVES / 2; ++i) {
        if (ours[i] == theirs[i])
            ++agree;
        else if (theirs[i] < ours[i])
            ++occ_fewer;
        else
            ++occ_more;
    }
    double mo = cj_bench_median(t_ours, REPS), mc = cj_bench_median(t_occ, REPS);
    printf("intersect cubic pair:  casteljau %8.2f us (certified), OpenCASCADE %8.2f us: %.2fx; "
           "counts agree on %d of %d pairs (OCCT fewer on %d, more on %d)\n",
           1e6 * mo, 1e6 * mc, mc / mo, agree, NCURVES / 2, occ_fewer, occ_more);
    // nearest points
    std::vector<double> qx(NCURVES), qy(NCURVES), dours(NCURVES), lours(NCURVES), docc(NCURVES);
    for (int i = 0; i < NCURVES; ++i) qx[i] = unit(), qy[i] = unit();
    for (int r = 0; r < REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        for (int i = 0; i < NCURVES; ++i) {
            cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL);
            double q[2] = {qx[i], qy[i]};
            cj_nearest nr;
            cj_nearest_curve(&a, q, 1e-10, &nr);
            dours[i] = nr.distance;
            lours[i] = nr.lower;
        }
        t_ours[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
        t0 = cj_bench_thread_cpu();
        for (int i = 0; i < NCURVES; ++i) {
            Geom2dAPI_ProjectPointOnCurve proj(gp_Pnt2d(qx[i], qy[i]), occ[i]);
            double d = INFINITY;
            if (proj.NbPoints() > 0) d = proj.LowerDistance();
            // the ends are candidates OCCT's extrema do not always include
            d = std::fmin(d, std::hypot(curves[i][0] - qx[i], curves[i][1] - qy[i]));
            d = std::fmin(d, std::hypot(curves[i][6] - qx[i], curves[i][7] - qy[i]));
            docc[i] = d;
        }
        t_occ[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
    }
    int nagree = 0, occ_worse = 0, occ_below_proof = 0;
    double worst = 0.0, mean = 0.0;
    for (int i = 0; i < NCURVES; ++i) mean += dours[i] / NCURVES;
    for (int i = 0; i < NCURVES; ++i) {
        if (std::fabs(docc[i] - dours[i]) <= 1e-9)
            ++nagree;
        else if (docc[i] > dours[i])
            ++occ_worse, worst = std::fmax(worst, docc[i] - dours[i]);
        if (docc[i] < lours[i] - 1e-12) ++occ_below_proof;
    }
    mo = cj_bench_median(t_ours, REPS), mc = cj_bench_median(t_occ, REPS);
    printf("nearest point, cubic:  casteljau %8.2f us (certified), OpenCASCADE %8.2f us (ends "
           "added): %.2fx; distances agree within 1e-9 on %d of %d (OCCT farther on %d, by up to "
           "%.3g; below our proven lower bound on %d); our mean distance %.12f\n",
           1e6 * mo, 1e6 * mc, mc / mo, nagree, NCURVES, occ_worse, worst, occ_below_proof, mean);
#ifdef CJ_HAVE_KURBO
    kurbo_rows(curves, occ, qx.data(), qy.data(), dours.data(), lours.data(), mo);
#else
    printf("kurbo: not linked (cargo or librust-kurbo-dev missing)\n");
#endif
    cj_bench_offsets_vs_occt(curves, NOFFSETS, 0.05, 1e-4, 0);
    return 0;
}
