/* Rational Bézier curves: homogeneous de Casteljau, quotient-rule derivatives, subdivision,
 * and exact conic arcs. See casteljau/rational.h. */
#include "casteljau/rational.h"
#include "bezier_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#define RB_WORK      ((CJ_BEZIER_MAX_DEGREE + 1) * CJ_MAX_DIM)
#define RB_MAX_DERIV 64

cj_status cj_rbezier_check(const cj_rbezier *c) {
    assert(c != NULL);
    if (c->degree < 0)
        return cj_fail(CJ_ERR_EMPTY, "rational curve has no control points (degree %d)", c->degree);
    if (c->degree > CJ_BEZIER_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "degree %d exceeds the limit of %d", c->degree,
                       CJ_BEZIER_MAX_DEGREE);
    if (c->dim < 1 || c->dim > CJ_RBEZIER_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "rational curve dimension %d is outside 1..%d", c->dim,
                       CJ_RBEZIER_MAX_DIM);
    assert(c->pts != NULL && c->weights != NULL);
    cj_status st = cj_check_points(c->pts, (size_t)c->degree + 1, c->dim, "control point");
    if (st) return st;
    if ((st = cj_check_finite(c->weights, (size_t)c->degree + 1, "weight"))) return st;
    for (int i = 0; i <= c->degree; ++i)
        if (!(c->weights[i] > 0.0))
            return cj_fail(CJ_ERR_ARGUMENT, "weight %d is %.17g; weights must be positive", i,
                           c->weights[i]);
    return CJ_OK;
}

/* Homogeneous points (w b, w) into h[(n+1)*(d+1)]. */
static void to_homogeneous(const cj_rbezier *c, double *h) {
    const int d = c->dim, e = d + 1;
    for (int i = 0; i <= c->degree; ++i) {
        const double w = c->weights[i];
        for (int k = 0; k < d; ++k) h[i * e + k] = w * c->pts[i * d + k];
        h[i * e + d] = w;
    }
}

cj_status cj_rbezier_homogeneous(const cj_rbezier *c, double *out) {
    assert(out != NULL);
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    to_homogeneous(c, out);
    return CJ_OK;
}

cj_status cj_rbezier_eval(const cj_rbezier *c, double t, double *out) {
    assert(out != NULL);
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    if ((st = cj_check_param(t, "parameter t"))) return st;
    const int n = c->degree, d = c->dim, e = d + 1;
    double w[RB_WORK];
    to_homogeneous(c, w);
    const double s = 1.0 - t;
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * e; ++i) w[i] = s * w[i] + t * w[i + e];
    if (!(w[d] > 0.0) || !isfinite(w[d]))
        return cj_fail(CJ_ERR_DEGENERATE, "denominator of the rational curve is %g at t = %.17g",
                       w[d], t);
    for (int k = 0; k < d; ++k) out[k] = w[k] / w[d];
    return CJ_OK;
}

cj_status cj_rbezier_eval_derivs(const cj_rbezier *c, double t, int kmax, double *out) {
    assert(out != NULL);
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    if ((st = cj_check_param(t, "parameter t"))) return st;
    if (kmax < 0 || kmax > RB_MAX_DERIV)
        return cj_fail(CJ_ERR_ARGUMENT, "derivative order %d is outside 0..%d", kmax, RB_MAX_DERIV);
    const int n = c->degree, d = c->dim, e = d + 1;
    double h[RB_WORK];
    to_homogeneous(c, h);
    /* Homogeneous derivatives of orders 0..kmax (orders above n are zero). */
    double hd[(RB_MAX_DERIV + 1) * CJ_MAX_DIM];
    cj_bezier hc = cj_bezier_view(n, e, h);
    if ((st = cj_bezier_eval_derivs(&hc, t, kmax, hd))) return st;
    const double w = hd[d];
    if (!(w > 0.0) || !isfinite(w))
        return cj_fail(CJ_ERR_DEGENERATE, "denominator of the rational curve is %g at t = %.17g", w,
                       t);
    /* c^(j) = (A^(j) − Σ_{i=1..j} C(j,i) w^(i) c^(j−i)) / w. */
    for (int j = 0; j <= kmax; ++j) {
        double binom = 1.0; /* C(j, i), updated as i grows */
        double acc[CJ_MAX_DIM];
        for (int k = 0; k < d; ++k) acc[k] = hd[j * e + k];
        for (int i = 1; i <= j; ++i) {
            binom = binom * (double)(j - i + 1) / (double)i;
            const double wi = hd[i * e + d];
            if (wi == 0.0) continue;
            for (int k = 0; k < d; ++k) acc[k] -= binom * wi * out[(j - i) * d + k];
        }
        for (int k = 0; k < d; ++k) out[j * d + k] = acc[k] / w;
    }
    return CJ_OK;
}

cj_status cj_rbezier_split(const cj_rbezier *c, double t, double *left_pts, double *left_w,
                           double *right_pts, double *right_w) {
    assert((left_pts == NULL) == (left_w == NULL));
    assert((right_pts == NULL) == (right_w == NULL));
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    if ((st = cj_check_param(t, "split parameter t"))) return st;
    if (t < 0.0 || t > 1.0)
        return cj_fail(CJ_ERR_RANGE, "split parameter t = %.17g is outside [0,1]", t);
    const int n = c->degree, d = c->dim, e = d + 1;
    double h[RB_WORK], l[RB_WORK], r[RB_WORK];
    to_homogeneous(c, h);
    cj_bezier hc = cj_bezier_view(n, e, h);
    if ((st = cj_bezier_split(&hc, t, l, r))) return st;
    for (int i = 0; i <= n; ++i) {
        if (left_pts) {
            const double w = l[i * e + d];
            for (int k = 0; k < d; ++k) left_pts[i * d + k] = l[i * e + k] / w;
            left_w[i] = w;
        }
        if (right_pts) {
            const double w = r[i * e + d];
            for (int k = 0; k < d; ++k) right_pts[i * d + k] = r[i * e + k] / w;
            right_w[i] = w;
        }
    }
    return CJ_OK;
}

cj_status cj_rbezier_normalize_weights(const cj_rbezier *c, double *weights_out) {
    assert(weights_out != NULL);
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    const int n = c->degree;
    if (n == 0) {
        weights_out[0] = 1.0;
        return CJ_OK;
    }
    /* t -> ρt/((ρ−1)t + 1) multiplies w_i by ρ^i up to a common factor; choose
     * ρ = (w_0/w_n)^(1/n) so that the end weights become equal, then divide by w_0. */
    const double w0 = c->weights[0];
    const double rho = pow(w0 / c->weights[n], 1.0 / n);
    double f = 1.0;
    for (int i = 0; i <= n; ++i) {
        weights_out[i] = c->weights[i] * f / w0;
        f *= rho;
    }
    weights_out[0] = 1.0;
    weights_out[n] = 1.0;
    return CJ_OK;
}

/* ---- conic arcs ------------------------------------------------------------------------ */

#define CJ_PI 3.14159265358979323846

int cj_rbezier_arc_pieces(double a0, double a1) {
    if (!isfinite(a0) || !isfinite(a1)) return 0;
    const double sweep = fabs(a1 - a0);
    if (sweep > 2.0 * CJ_PI * (1.0 + 1e-12)) return 0;
    int k = (int)ceil(sweep / (0.5 * CJ_PI) * (1.0 - 1e-12));
    return k < 1 ? 1 : k;
}

static cj_status check_ellipse(double cx, double cy, double rx, double ry, double rot, double a0,
                               double a1) {
    const double v[7] = {cx, cy, rx, ry, rot, a0, a1};
    static const char *names[7] = {"centre x", "centre y",    "radius rx", "radius ry",
                                   "rotation", "start angle", "end angle"};
    for (int i = 0; i < 7; ++i)
        if (!isfinite(v[i])) return cj_fail(CJ_ERR_NONFINITE, "ellipse %s is not finite", names[i]);
    if (!(rx > 0.0) || !(ry > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "ellipse radii must be positive (rx = %g, ry = %g)", rx,
                       ry);
    if (a1 == a0) return cj_fail(CJ_ERR_DEGENERATE, "ellipse arc has zero sweep");
    return CJ_OK;
}

/* Maps a point (x, y) of the unit circle's plane to the ellipse. */
static void ellipse_map(double cx, double cy, double rx, double ry, double cr, double sr, double x,
                        double y, double *out) {
    const double u = rx * x, v = ry * y;
    out[0] = cx + (cr * u - sr * v);
    out[1] = cy + (sr * u + cr * v);
}

/* One arc whose end points p0, p2 were already computed (so shared ends are identical). */
static void arc_piece(double cx, double cy, double rx, double ry, double cr, double sr, double a0,
                      double a1, const double *p0, const double *p2, double *pts, double *w) {
    const double half = 0.5 * (a1 - a0), mid = 0.5 * (a0 + a1);
    const double ch = cos(half);
    pts[0] = p0[0];
    pts[1] = p0[1];
    ellipse_map(cx, cy, rx, ry, cr, sr, cos(mid) / ch, sin(mid) / ch, pts + 2);
    pts[4] = p2[0];
    pts[5] = p2[1];
    w[0] = 1.0;
    w[1] = ch;
    w[2] = 1.0;
}

cj_status cj_rbezier_ellipse_arc(double cx, double cy, double rx, double ry, double rot, double a0,
                                 double a1, double pts[6], double weights[3]) {
    assert(pts != NULL && weights != NULL);
    cj_status st = check_ellipse(cx, cy, rx, ry, rot, a0, a1);
    if (st) return st;
    if (!(fabs(a1 - a0) < CJ_PI))
        return cj_fail(CJ_ERR_RANGE,
                       "a single rational quadratic arc needs a sweep below pi, got %.17g",
                       a1 - a0);
    const double cr = cos(rot), sr = sin(rot);
    double p0[2], p2[2];
    ellipse_map(cx, cy, rx, ry, cr, sr, cos(a0), sin(a0), p0);
    ellipse_map(cx, cy, rx, ry, cr, sr, cos(a1), sin(a1), p2);
    arc_piece(cx, cy, rx, ry, cr, sr, a0, a1, p0, p2, pts, weights);
    return CJ_OK;
}

cj_status cj_rbezier_ellipse_arcs(double cx, double cy, double rx, double ry, double rot, double a0,
                                  double a1, double *pts, double *weights, int cap_pieces,
                                  int *npieces) {
    assert(pts != NULL && weights != NULL);
    cj_status st = check_ellipse(cx, cy, rx, ry, rot, a0, a1);
    if (st) return st;
    const int k = cj_rbezier_arc_pieces(a0, a1);
    if (k == 0) return cj_fail(CJ_ERR_RANGE, "ellipse arc sweep %.17g exceeds 2 pi", a1 - a0);
    if (cap_pieces < k)
        return cj_fail(CJ_ERR_BUFFER, "arc needs %d pieces, buffer holds %d", k, cap_pieces);
    const double cr = cos(rot), sr = sin(rot);
    const int full = fabs(fabs(a1 - a0) - 2.0 * CJ_PI) <= 1e-12 * 2.0 * CJ_PI;
    double first[2], prev[2];
    ellipse_map(cx, cy, rx, ry, cr, sr, cos(a0), sin(a0), first);
    prev[0] = first[0];
    prev[1] = first[1];
    double aprev = a0;
    for (int i = 0; i < k; ++i) {
        const double an = i + 1 == k ? a1 : a0 + (a1 - a0) * (double)(i + 1) / (double)k;
        double next[2];
        if (i + 1 == k && full) {
            next[0] = first[0];
            next[1] = first[1];
        } else {
            ellipse_map(cx, cy, rx, ry, cr, sr, cos(an), sin(an), next);
        }
        arc_piece(cx, cy, rx, ry, cr, sr, aprev, an, prev, next, pts + 6 * i, weights + 3 * i);
        prev[0] = next[0];
        prev[1] = next[1];
        aprev = an;
    }
    if (npieces) *npieces = k;
    return CJ_OK;
}
