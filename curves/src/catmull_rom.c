/* Catmull-Rom (uniform, centripetal, chordal), Kochanek–Bartels and cubic Hermite splines as
 * cubic Bézier segments. Formulas: see casteljau/catmull_rom.h. */
#include "casteljau/catmull_rom.h"
#include "casteljau/bezier.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

cj_spline_options cj_spline_defaults(void) {
    cj_spline_options o;
    o.kind = CJ_SPLINE_CATMULL_ROM;
    o.tension = 0.5;
    o.continuity = 0.0;
    o.bias = 0.0;
    o.closed = 0;
    return o;
}

size_t cj_spline_segment_count(size_t npts, int closed) {
    if (closed) return npts >= 3 ? npts : 0;
    return npts >= 2 ? npts - 1 : 0;
}

static cj_status check_input(const double *pts, size_t npts, int dim, const cj_spline_options *o) {
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    if (o->closed && npts < 3)
        return cj_fail(CJ_ERR_EMPTY, "a closed spline needs at least 3 points, got %zu", npts);
    if (npts < 2) return cj_fail(CJ_ERR_EMPTY, "a spline needs at least 2 points, got %zu", npts);
    if ((unsigned)o->kind > (unsigned)CJ_SPLINE_KOCHANEK_BARTELS)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown spline kind %d", (int)o->kind);
    if (!isfinite(o->tension)) return cj_fail(CJ_ERR_NONFINITE, "spline tension is not finite");
    if (!isfinite(o->continuity))
        return cj_fail(CJ_ERR_NONFINITE, "spline continuity is not finite");
    if (!isfinite(o->bias)) return cj_fail(CJ_ERR_NONFINITE, "spline bias is not finite");
    assert(pts != NULL);
    return cj_check_points(pts, npts, dim, "spline point");
}

static double dist(const double *p, const double *q, int d) {
    double s = 0.0, m = 0.0;
    for (int k = 0; k < d; ++k) m = fmax(m, fabs(q[k] - p[k]));
    if (m == 0.0) return 0.0;
    for (int k = 0; k < d; ++k) {
        double v = (q[k] - p[k]) / m;
        s += v * v;
    }
    return m * sqrt(s);
}

/* Knot spacing of segment j (from point j to point j+1, cyclic when closed): 1 for uniform
 * kinds, |Δp|^α otherwise. Fails for a zero spacing of a non-uniform kind. */
static cj_status spacing(const double *pts, size_t npts, int d, const cj_spline_options *o,
                         size_t j, double *delta) {
    if (o->kind != CJ_SPLINE_CENTRIPETAL && o->kind != CJ_SPLINE_CHORDAL) {
        *delta = 1.0;
        return CJ_OK;
    }
    size_t j1 = (j + 1) % npts;
    double len = dist(pts + j * (size_t)d, pts + j1 * (size_t)d, d);
    if (isnan(len) || isinf(len))
        return cj_fail(CJ_ERR_RANGE,
                       "spline points %zu and %zu are too far apart: their distance overflows "
                       "the double range",
                       j, j1);
    if (!(len > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE,
                       "spline points %zu and %zu coincide: a %s spline needs distinct "
                       "consecutive points",
                       j, j1, o->kind == CJ_SPLINE_CENTRIPETAL ? "centripetal" : "chordal");
    *delta = o->kind == CJ_SPLINE_CENTRIPETAL ? sqrt(len) : len;
    if (!isfinite(*delta) || *delta == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "knot spacing between spline points %zu and %zu is %g", j,
                       j1, *delta);
    return CJ_OK;
}

/* Outgoing (out) and incoming (in) tangent at point j, per unit of knot parameter. For
 * non-uniform kinds dprev/dnext are the spacings of the segments before/after p_j. */
static void tangent_at(const double *pts, size_t npts, int d, const cj_spline_options *o, size_t j,
                       double dprev, double dnext, double *out, double *in) {
    const double *p = pts + j * (size_t)d;
    const int closed = o->closed;
    const int first = !closed && j == 0, last = !closed && j == npts - 1;
    const double *pm = first ? NULL : pts + ((j + npts - 1) % npts) * (size_t)d;
    const double *pp = last ? NULL : pts + ((j + 1) % npts) * (size_t)d;
    const double kap =
        o->kind == CJ_SPLINE_KOCHANEK_BARTELS ? 0.5 * (1.0 - o->tension) : o->tension;
    if (first || last) {
        /* Seed end tangents: κ (p_1 − p_0) and κ (p_{N−1} − p_{N−2}), per unit knot. */
        const double *a = first ? p : pm, *b = first ? pp : p;
        const double delta = first ? dnext : dprev;
        for (int k = 0; k < d; ++k) out[k] = in[k] = kap * (b[k] - a[k]) / delta;
        return;
    }
    switch (o->kind) {
    case CJ_SPLINE_CATMULL_ROM:
        for (int k = 0; k < d; ++k) out[k] = in[k] = kap * (pp[k] - pm[k]);
        break;
    case CJ_SPLINE_CENTRIPETAL:
    case CJ_SPLINE_CHORDAL:
        for (int k = 0; k < d; ++k) {
            double g =
                (p[k] - pm[k]) / dprev - (pp[k] - pm[k]) / (dprev + dnext) + (pp[k] - p[k]) / dnext;
            out[k] = in[k] = 2.0 * kap * g;
        }
        break;
    case CJ_SPLINE_KOCHANEK_BARTELS: {
        const double T = o->tension, C = o->continuity, B = o->bias;
        const double oa = (1 - T) * (1 + B) * (1 + C) / 2, ob = (1 - T) * (1 - B) * (1 - C) / 2;
        const double ia = (1 - T) * (1 + B) * (1 - C) / 2, ib = (1 - T) * (1 - B) * (1 + C) / 2;
        for (int k = 0; k < d; ++k) {
            double back = p[k] - pm[k], fwd = pp[k] - p[k];
            out[k] = oa * back + ob * fwd;
            in[k] = ia * back + ib * fwd;
        }
        break;
    }
    }
}

/* Shared driver: computes spacings on the fly (each is needed by three tangents). */
cj_status cj_catmull_rom_tangents(const double *pts, size_t npts, int dim,
                                  const cj_spline_options *opts, double *out_tan, double *in_tan) {
    cj_spline_options o = opts ? *opts : cj_spline_defaults();
    cj_status st = check_input(pts, npts, dim, &o);
    if (st) return st;
    const size_t nseg = cj_spline_segment_count(npts, o.closed);
    /* Validate all spacings before writing anything. */
    for (size_t j = 0; j < nseg; ++j) {
        double dl;
        if ((st = spacing(pts, npts, dim, &o, j, &dl))) return st;
    }
    for (size_t j = 0; j < npts; ++j) {
        double dprev = 1.0, dnext = 1.0, to[CJ_MAX_DIM], ti[CJ_MAX_DIM];
        if (o.closed || j > 0) spacing(pts, npts, dim, &o, (j + npts - 1) % npts, &dprev);
        if (o.closed || j + 1 < npts) spacing(pts, npts, dim, &o, j, &dnext);
        tangent_at(pts, npts, dim, &o, j, dprev, dnext, to, ti);
        if (out_tan) memcpy(out_tan + j * (size_t)dim, to, sizeof(double) * (size_t)dim);
        if (in_tan) memcpy(in_tan + j * (size_t)dim, ti, sizeof(double) * (size_t)dim);
    }
    return CJ_OK;
}

cj_status cj_catmull_rom(const double *pts, size_t npts, int dim, const cj_spline_options *opts,
                         double *segs, size_t cap_segs, size_t *nsegs, double *knots) {
    cj_spline_options o = opts ? *opts : cj_spline_defaults();
    cj_status st = check_input(pts, npts, dim, &o);
    if (st) return st;
    const size_t nseg = cj_spline_segment_count(npts, o.closed);
    if (cap_segs < nseg)
        return cj_fail(CJ_ERR_BUFFER, "spline needs %zu segments, buffer holds %zu", nseg,
                       cap_segs);
    assert(segs != NULL);
    for (size_t j = 0; j < nseg; ++j) {
        double dl;
        if ((st = spacing(pts, npts, dim, &o, j, &dl))) return st;
    }
    const size_t d = (size_t)dim;
    for (size_t j = 0; j < nseg; ++j) {
        const size_t j1 = (j + 1) % npts;
        double dj, dprev = 1.0, dnext = 1.0;
        double out0[CJ_MAX_DIM], in0[CJ_MAX_DIM], out1[CJ_MAX_DIM], in1[CJ_MAX_DIM];
        spacing(pts, npts, dim, &o, j, &dj);
        if (o.closed || j > 0) spacing(pts, npts, dim, &o, (j + npts - 1) % npts, &dprev);
        tangent_at(pts, npts, dim, &o, j, dprev, dj, out0, in0);
        if (o.closed || j1 + 1 < npts) spacing(pts, npts, dim, &o, j1, &dnext);
        tangent_at(pts, npts, dim, &o, j1, dj, dnext, out1, in1);
        double *s = segs + j * 4 * d;
        const double *p0 = pts + j * d, *p1 = pts + j1 * d;
        for (size_t k = 0; k < d; ++k) {
            s[k] = p0[k];
            s[d + k] = p0[k] + dj * out0[k] / 3.0;
            s[2 * d + k] = p1[k] - dj * in1[k] / 3.0;
            s[3 * d + k] = p1[k];
        }
        for (size_t k = 0; k < 4 * d; ++k)
            if (!isfinite(s[k]))
                return cj_fail(CJ_ERR_RANGE,
                               "spline segment %zu (points %zu to %zu): control point %zu "
                               "overflows the double range (points, tension, continuity or bias "
                               "too large)",
                               j, j, j1, k / d);
    }
    if (knots) {
        knots[0] = 0.0;
        for (size_t j = 0; j < nseg; ++j) {
            double dj;
            spacing(pts, npts, dim, &o, j, &dj);
            knots[j + 1] = knots[j] + dj;
        }
    }
    if (nsegs) *nsegs = nseg;
    return CJ_OK;
}

cj_status cj_hermite_segment(const double *p0, const double *v0, const double *p1, const double *v1,
                             int dim, double *out) {
    assert(p0 && v0 && p1 && v1 && out);
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    cj_status st;
    if ((st = cj_check_finite(p0, (size_t)dim, "Hermite start point coordinate"))) return st;
    if ((st = cj_check_finite(v0, (size_t)dim, "Hermite start tangent coordinate"))) return st;
    if ((st = cj_check_finite(p1, (size_t)dim, "Hermite end point coordinate"))) return st;
    if ((st = cj_check_finite(v1, (size_t)dim, "Hermite end tangent coordinate"))) return st;
    for (int k = 0; k < dim; ++k) {
        out[k] = p0[k];
        out[dim + k] = p0[k] + v0[k] / 3.0;
        out[2 * dim + k] = p1[k] - v1[k] / 3.0;
        out[3 * dim + k] = p1[k];
    }
    return CJ_OK;
}

cj_status cj_hermite_spline(const double *pts, const double *tans, const double *knots, size_t npts,
                            int dim, double *segs, size_t cap_segs, size_t *nsegs) {
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    if (npts < 2)
        return cj_fail(CJ_ERR_EMPTY, "a Hermite spline needs at least 2 points, got %zu", npts);
    assert(pts && tans);
    cj_status st;
    if ((st = cj_check_points(pts, npts, dim, "Hermite point"))) return st;
    if ((st = cj_check_points(tans, npts, dim, "Hermite tangent"))) return st;
    if (knots) {
        if ((st = cj_check_finite(knots, npts, "Hermite knot"))) return st;
        for (size_t j = 0; j + 1 < npts; ++j)
            if (!(knots[j + 1] > knots[j]))
                return cj_fail(CJ_ERR_ARGUMENT,
                               "Hermite knots %zu and %zu (%.17g, %.17g) do not increase", j, j + 1,
                               knots[j], knots[j + 1]);
    }
    if (cap_segs < npts - 1)
        return cj_fail(CJ_ERR_BUFFER, "spline needs %zu segments, buffer holds %zu", npts - 1,
                       cap_segs);
    assert(segs != NULL);
    const size_t d = (size_t)dim;
    for (size_t j = 0; j + 1 < npts; ++j) {
        double dj = knots ? knots[j + 1] - knots[j] : 1.0;
        double *s = segs + j * 4 * d;
        for (size_t k = 0; k < d; ++k) {
            s[k] = pts[j * d + k];
            s[d + k] = pts[j * d + k] + dj * tans[j * d + k] / 3.0;
            s[2 * d + k] = pts[(j + 1) * d + k] - dj * tans[(j + 1) * d + k] / 3.0;
            s[3 * d + k] = pts[(j + 1) * d + k];
        }
    }
    if (nsegs) *nsegs = npts - 1;
    return CJ_OK;
}
