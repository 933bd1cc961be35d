// Shared by the OpenCASCADE cross-check and bench: a casteljau B-spline (3D, clamped) as an
// OCCT Geom_BSplineCurve (knots with multiplicities, 1-based arrays, weights if rational).
#ifndef CJ_TEST_OCCT_BSPLINE_H
#define CJ_TEST_OCCT_BSPLINE_H

#include "casteljau/bspline.h"

#include <Geom_BSplineCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>

#include <vector>

static inline Handle(Geom_BSplineCurve) cj_to_occt(const cj_bspline &c) {
    std::vector<double> k;
    std::vector<int> m;
    const int nk = c.npts + c.degree + 1;
    for (int i = 0; i < nk; ++i) {
        if (!k.empty() && k.back() == c.knots[i])
            ++m.back();
        else {
            k.push_back(c.knots[i]);
            m.push_back(1);
        }
    }
    TColgp_Array1OfPnt poles(1, c.npts);
    for (int i = 0; i < c.npts; ++i)
        poles.SetValue(i + 1, gp_Pnt(c.pts[3 * i], c.pts[3 * i + 1], c.pts[3 * i + 2]));
    TColStd_Array1OfReal knots(1, (int)k.size());
    TColStd_Array1OfInteger mults(1, (int)k.size());
    for (size_t i = 0; i < k.size(); ++i) {
        knots.SetValue((int)i + 1, k[i]);
        mults.SetValue((int)i + 1, m[i]);
    }
    if (c.weights) {
        TColStd_Array1OfReal w(1, c.npts);
        for (int i = 0; i < c.npts; ++i) w.SetValue(i + 1, c.weights[i]);
        return new Geom_BSplineCurve(poles, w, knots, mults, c.degree);
    }
    return new Geom_BSplineCurve(poles, knots, mults, c.degree);
}

#endif
