// The B-spline headers compile as C++ and link (extern "C"): a curve, a fit and a surface.
#include "casteljau/bspline.h"
#include "casteljau/bspline_fit.h"
#include "casteljau/bspline_surface.h"

#include <cmath>
#include <cstdio>

int main() {
    const double pts[] = {0, 0, 1, 2, 3, 2, 4, 0};
    const double knots[] = {0, 0, 0, 0, 1, 1, 1, 1};
    const cj_bspline c = cj_bspline_view(3, 2, 4, pts, nullptr, knots);
    double x[2];
    int fails = cj_bspline_eval(&c, 0.5, x) != CJ_OK || std::fabs(x[0] - 2.0) > 1e-15;
    double P[8], U[8];
    int m = 0;
    fails += cj_bspline_interpolate(pts, 4, 2, 3, CJ_FIT_CHORD, nullptr, nullptr, P, U, &m,
                                    nullptr) != CJ_OK ||
             m != 4;
    const double net[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
    const double k1[] = {0, 0, 1, 1};
    const cj_bspline_surface s = {1, 1, 2, 2, net, nullptr, k1, k1};
    double y[3];
    fails += cj_bspline_surface_eval(&s, 1.0, 1.0, y) != CJ_OK || y[2] != 1.0;
    std::printf("bspline.h, bspline_fit.h, bspline_surface.h compile as C++ and link: %s\n",
                fails ? "FAILED" : "ok");
    return fails ? 1 : 0;
}
