/* Tensor-product Bézier patches: validation, evaluation (plain and compensated), partial
 * derivatives, the normal with its limit rule, subdivision, elevation, iso and boundary
 * curves. Rational patches run in homogeneous coordinates (w b, w). */
#include "casteljau/patch.h"
#include "error_internal.h"
#include "eft_internal.h"
#include "patch_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

cj_status cj_patch_check(const cj_patch *p) {
    assert(p != NULL);
    if (p->deg_u < 0 || p->deg_v < 0)
        return cj_fail(CJ_ERR_EMPTY, "patch has no control points (degree %d,%d)", p->deg_u,
                       p->deg_v);
    if (p->deg_u > CJ_PATCH_MAX_DEGREE || p->deg_v > CJ_PATCH_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "patch degree (%d,%d) exceeds the limit %d", p->deg_u,
                       p->deg_v, CJ_PATCH_MAX_DEGREE);
    assert(p->pts != NULL);
    const int m1 = p->deg_u + 1;
    const size_t count = cj_patch_point_count(p);
    for (size_t q = 0; q < count; ++q)
        for (int k = 0; k < 3; ++k)
            if (!isfinite(p->pts[3 * q + (size_t)k]))
                return cj_fail(CJ_ERR_NONFINITE, "control point (i=%d, j=%d), coordinate %d is %s",
                               (int)(q % (size_t)m1), (int)(q / (size_t)m1), k,
                               isnan(p->pts[3 * q + (size_t)k]) ? "NaN" : "infinite");
    if (p->weights)
        for (size_t q = 0; q < count; ++q) {
            const double w = p->weights[q];
            if (!isfinite(w))
                return cj_fail(CJ_ERR_NONFINITE, "weight (i=%d, j=%d) is %s", (int)(q % (size_t)m1),
                               (int)(q / (size_t)m1), isnan(w) ? "NaN" : "infinite");
            if (!(w > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "weight (i=%d, j=%d) = %.17g is not positive",
                               (int)(q % (size_t)m1), (int)(q / (size_t)m1), w);
        }
    return CJ_OK;
}

static cj_status check_uv(double u, double v) {
    if (!isfinite(u))
        return cj_fail(CJ_ERR_NONFINITE, "parameter u is %s", isnan(u) ? "NaN" : "infinite");
    if (!isfinite(v))
        return cj_fail(CJ_ERR_NONFINITE, "parameter v is %s", isnan(v) ? "NaN" : "infinite");
    return CJ_OK;
}

int cj_patch_load_h(const cj_patch *p, double *h) {
    const size_t count = cj_patch_point_count(p);
    if (!p->weights) {
        memcpy(h, p->pts, sizeof(double) * 3 * count);
        return 3;
    }
    for (size_t q = 0; q < count; ++q) {
        const double w = p->weights[q];
        h[4 * q + 0] = w * p->pts[3 * q + 0];
        h[4 * q + 1] = w * p->pts[3 * q + 1];
        h[4 * q + 2] = w * p->pts[3 * q + 2];
        h[4 * q + 3] = w;
    }
    return 4;
}

void cj_patch_store_h(const double *h, int hd, size_t count, double *pts, double *w) {
    if (hd == 3) {
        memcpy(pts, h, sizeof(double) * 3 * count);
        return;
    }
    for (size_t q = 0; q < count; ++q) {
        const double ww = h[4 * q + 3];
        pts[3 * q + 0] = h[4 * q + 0] / ww;
        pts[3 * q + 1] = h[4 * q + 1] / ww;
        pts[3 * q + 2] = h[4 * q + 2] / ww;
        w[q] = ww;
    }
}

/* de Casteljau on n+1 points of dimension d stored with point stride `stride` (in doubles),
 * collapsing into out[d]. */
static void dc_strided(const double *src, int n, int d, size_t stride, double t, double *out) {
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < d; ++k) w[i * d + k] = src[(size_t)i * stride + (size_t)k];
    const double s = 1.0 - t;
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    memcpy(out, w, sizeof(double) * (size_t)d);
}

void cj_patch_eval_h(const double *h, int hd, int m, int n, double u, double v, double *out) {
    double col[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    const size_t row = (size_t)(m + 1) * (size_t)hd;
    for (int j = 0; j <= n; ++j)
        dc_strided(h + (size_t)j * row, m, hd, (size_t)hd, u, col + j * hd);
    dc_strided(col, n, hd, (size_t)hd, v, out);
}

/* Compensated de Casteljau over n+1 points given as values b and first-order corrections db
 * (both length (n+1)*d, modified in place); returns value in out_b[d], correction in
 * out_db[d] (not added). */
static void comp_dc(double *b, double *db, int n, int d, double t, double *out_b, double *out_db) {
    double r, rho;
    cj_two_sum(1.0, -t, &r, &rho);
    for (int lvl = n; lvl > 0; --lvl)
        for (int i = 0; i < lvl * d; ++i) {
            double s, ps, vv, pv, sum, sig;
            cj_two_prod(r, b[i], &s, &ps);
            cj_two_prod(t, b[i + d], &vv, &pv);
            cj_two_sum(s, vv, &sum, &sig);
            const double w = (ps + pv) + fma(rho, b[i], sig);
            db[i] = fma(r, db[i], fma(t, db[i + d], w));
            b[i] = sum;
        }
    memcpy(out_b, b, sizeof(double) * (size_t)d);
    memcpy(out_db, db, sizeof(double) * (size_t)d);
}

static void eval_compensated_h(const double *h, int hd, int m, int n, double u, double v,
                               double *out) {
    double cb[(CJ_PATCH_MAX_DEGREE + 1) * 4], cdb[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    double b[(CJ_PATCH_MAX_DEGREE + 1) * 4], db[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    const size_t row = (size_t)(m + 1) * (size_t)hd;
    for (int j = 0; j <= n; ++j) {
        memcpy(b, h + (size_t)j * row, sizeof(double) * row);
        memset(db, 0, sizeof(double) * row);
        comp_dc(b, db, m, hd, u, cb + j * hd, cdb + j * hd);
    }
    double vb[4], vdb[4];
    comp_dc(cb, cdb, n, hd, v, vb, vdb);
    for (int k = 0; k < hd; ++k) out[k] = vb[k] + vdb[k];
}

cj_status cj_patch_eval(const cj_patch *p, cj_eval_method method, double u, double v,
                        double out[3]) {
    assert(out != NULL);
    if (method != CJ_EVAL_DECASTELJAU && method != CJ_EVAL_COMPENSATED)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "evaluation method %d is not available for patches (use de Casteljau "
                       "or compensated)",
                       (int)method);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if ((st = check_uv(u, v))) return st;
    double h[CJ_PATCH_NET_MAX];
    const int hd = cj_patch_load_h(p, h);
    double r[4];
    if (method == CJ_EVAL_COMPENSATED)
        eval_compensated_h(h, hd, p->deg_u, p->deg_v, u, v, r);
    else
        cj_patch_eval_h(h, hd, p->deg_u, p->deg_v, u, v, r);
    if (hd == 4) {
        out[0] = r[0] / r[3];
        out[1] = r[1] / r[3];
        out[2] = r[2] / r[3];
    } else {
        memcpy(out, r, sizeof(double) * 3);
    }
    return CJ_OK;
}

/* Homogeneous partials D^{a,b}H for a <= ku, b <= kv at (u,v) into out[hd*(a*(kv+1)+b)]. */
static void derivs_h(const double *h, int hd, int m, int n, double u, double v, int ku, int kv,
                     double *out) {
    /* rows: derivatives in u of each row j, up to ku: rd[(j*(ku+1)+a)*hd] */
    double rd[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DERIV + 1) * 4];
    const size_t row = (size_t)(m + 1) * (size_t)hd;
    for (int j = 0; j <= n; ++j) {
        cj_bezier c = cj_bezier_view(m, hd, h + (size_t)j * row);
        double tmp[(CJ_PATCH_MAX_DERIV + 1) * 4];
        (void)cj_bezier_eval_derivs(&c, u, ku, tmp);
        memcpy(rd + (size_t)j * (size_t)(ku + 1) * (size_t)hd, tmp,
               sizeof(double) * (size_t)(ku + 1) * (size_t)hd);
    }
    for (int a = 0; a <= ku; ++a) {
        double colpts[(CJ_PATCH_MAX_DEGREE + 1) * 4];
        for (int j = 0; j <= n; ++j)
            memcpy(colpts + j * hd, rd + ((size_t)j * (size_t)(ku + 1) + (size_t)a) * (size_t)hd,
                   sizeof(double) * (size_t)hd);
        cj_bezier c = cj_bezier_view(n, hd, colpts);
        double tmp[(CJ_PATCH_MAX_DERIV + 1) * 4];
        (void)cj_bezier_eval_derivs(&c, v, kv, tmp);
        for (int b = 0; b <= kv; ++b)
            memcpy(out + (size_t)(a * (kv + 1) + b) * (size_t)hd, tmp + b * hd,
                   sizeof(double) * (size_t)hd);
    }
}

static double binom(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (double)(n - k + i) / (double)i;
    return r;
}

void cj_patch_derivs_unchecked(const cj_patch *p, const double *h, int hd, double u, double v,
                               int ku, int kv, double *out) {
    double hdv[(CJ_PATCH_MAX_DERIV + 1) * (CJ_PATCH_MAX_DERIV + 1) * 4];
    derivs_h(h, hd, p->deg_u, p->deg_v, u, v, ku, kv, hdv);
    const int kv1 = kv + 1;
    if (hd == 3) {
        memcpy(out, hdv, sizeof(double) * 3 * (size_t)(ku + 1) * (size_t)kv1);
        return;
    }
    const double w = hdv[3];
    for (int a = 0; a <= ku; ++a)
        for (int b = 0; b <= kv; ++b) {
            double acc[3];
            for (int k = 0; k < 3; ++k) acc[k] = hdv[4 * (a * kv1 + b) + k];
            for (int c = 0; c <= a; ++c)
                for (int d = 0; d <= b; ++d) {
                    if (c == 0 && d == 0) continue;
                    const double f = binom(a, c) * binom(b, d) * hdv[4 * (c * kv1 + d) + 3];
                    for (int k = 0; k < 3; ++k)
                        acc[k] -= f * out[3 * ((a - c) * kv1 + (b - d)) + k];
                }
            for (int k = 0; k < 3; ++k) out[3 * (a * kv1 + b) + k] = acc[k] / w;
        }
}

cj_status cj_patch_eval_derivs(const cj_patch *p, double u, double v, int ku, int kv, double *out) {
    assert(out != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if ((st = check_uv(u, v))) return st;
    if (ku < 0 || kv < 0 || ku > CJ_PATCH_MAX_DERIV || kv > CJ_PATCH_MAX_DERIV)
        return cj_fail(CJ_ERR_ARGUMENT, "derivative orders (%d,%d) outside 0..%d", ku, kv,
                       CJ_PATCH_MAX_DERIV);
    double h[CJ_PATCH_NET_MAX];
    const int hd = cj_patch_load_h(p, h);
    cj_patch_derivs_unchecked(p, h, hd, u, v, ku, kv, out);
    return CJ_OK;
}

cj_status cj_patch_deriv(const cj_patch *p, int a, int b, double u, double v, double out[3]) {
    double all[3 * (CJ_PATCH_MAX_DERIV + 1) * (CJ_PATCH_MAX_DERIV + 1)];
    cj_status st = cj_patch_eval_derivs(p, u, v, a, b, all);
    if (st) return st;
    memcpy(out, all + 3 * (a * (b + 1) + b), sizeof(double) * 3);
    return CJ_OK;
}

static void cross3(const double *a, const double *b, double *c) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static double norm3(const double *a) {
    return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

#define NORMAL_MAX_ORDER 4

cj_status cj_patch_normal_unchecked(const cj_patch *p, const double *h, int hd, double u, double v,
                                    double n[3], int *order) {
    enum { K = NORMAL_MAX_ORDER + 1 };
    { /* regular case first: only the first partials */
        double d1[3 * 4];
        cj_patch_derivs_unchecked(p, h, hd, u, v, 1, 1, d1);
        double c[3];
        cross3(d1 + 6, d1 + 3, c); /* D^{1,0} = d1[6..8], D^{0,1} = d1[3..5] */
        const double cn = norm3(c);
        if (cn > 64.0 * CJ_UNIT_ROUNDOFF * norm3(d1 + 6) * norm3(d1 + 3) && cn > 0.0 &&
            isfinite(cn)) {
            for (int k = 0; k < 3; ++k) n[k] = c[k] / cn;
            if (order) *order = 0;
            return CJ_OK;
        }
    }
    double D[3 * (K + 1) * (K + 1)];
    cj_patch_derivs_unchecked(p, h, hd, u, v, K, K, D);
#define DS(i, j) (D + 3 * ((i) * (K + 1) + (j)))
    double hh = 0.5 - u, kk = 0.5 - v;
    if (hh == 0.0 && kk == 0.0) hh = 1.0;
    const double len = hypot(hh, kk);
    hh /= len;
    kk /= len;
    double A[NORMAL_MAX_ORDER + 1][3], B[NORMAL_MAX_ORDER + 1][3];
    double fact[K + 1];
    fact[0] = 1.0;
    for (int i = 1; i <= K; ++i) fact[i] = fact[i - 1] * i;
    for (int s = 0; s <= NORMAL_MAX_ORDER; ++s) {
        for (int k = 0; k < 3; ++k) A[s][k] = B[s][k] = 0.0;
        for (int i = 0; i <= s; ++i) {
            const int j = s - i;
            const double c = pow(hh, i) * pow(kk, j) / (fact[i] * fact[j]);
            for (int k = 0; k < 3; ++k) {
                A[s][k] += c * DS(i + 1, j)[k];
                B[s][k] += c * DS(i, j + 1)[k];
            }
        }
    }
#undef DS
    for (int r = 0; r <= NORMAL_MAX_ORDER; ++r) {
        double c[3] = {0, 0, 0}, mag = 0.0;
        for (int s = 0; s <= r; ++s) {
            double x[3];
            cross3(A[s], B[r - s], x);
            for (int k = 0; k < 3; ++k) c[k] += x[k];
            mag += norm3(A[s]) * norm3(B[r - s]);
        }
        const double cn = norm3(c);
        if (cn > 64.0 * CJ_UNIT_ROUNDOFF * mag && cn > 0.0 && isfinite(cn)) {
            for (int k = 0; k < 3; ++k) n[k] = c[k] / cn;
            if (order) *order = r;
            return CJ_OK;
        }
    }
    return cj_fail(CJ_ERR_DEGENERATE,
                   "the patch normal at (u,v) = (%.17g, %.17g) is undefined: S_u x S_v and its "
                   "derivatives up to order %d vanish",
                   u, v, NORMAL_MAX_ORDER);
}

cj_status cj_patch_normal(const cj_patch *p, double u, double v, double n[3], int *order) {
    assert(n != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if ((st = check_uv(u, v))) return st;
    double h[CJ_PATCH_NET_MAX];
    const int hd = cj_patch_load_h(p, h);
    return cj_patch_normal_unchecked(p, h, hd, u, v, n, order);
}

/* ---- subdivision --------------------------------------------------------------------- */

/* Splits n+1 points of dimension d (point stride `stride`) at t into left/right (same
 * stride); either may be NULL. */
static void split_strided(const double *src, int n, int d, size_t stride, double t, double *left,
                          double *right) {
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < d; ++k) w[i * d + k] = src[(size_t)i * stride + (size_t)k];
    const double s = 1.0 - t;
    for (int r = n;; --r) {
        for (int k = 0; k < d; ++k) {
            if (left) left[(size_t)(n - r) * stride + (size_t)k] = w[k];
            if (right) right[(size_t)r * stride + (size_t)k] = w[r * d + k];
        }
        if (r == 0) break;
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    }
}

/* Splits the homogeneous net h in direction dir (0 = u, 1 = v) at t. */
static void split_h(const double *h, int hd, int m, int n, int dir, double t, double *left,
                    double *right) {
    const size_t row = (size_t)(m + 1) * (size_t)hd;
    if (dir == 0) {
        for (int j = 0; j <= n; ++j)
            split_strided(h + j * row, m, hd, (size_t)hd, t, left ? left + j * row : NULL,
                          right ? right + j * row : NULL);
    } else {
        for (int i = 0; i <= m; ++i)
            split_strided(h + (size_t)i * (size_t)hd, n, hd, row, t,
                          left ? left + (size_t)i * (size_t)hd : NULL,
                          right ? right + (size_t)i * (size_t)hd : NULL);
    }
}

static cj_status check_out_w(const cj_patch *p, const double *pts, const double *w,
                             const char *what) {
    if (pts && p->weights && !w)
        return cj_fail(CJ_ERR_ARGUMENT, "%s: the patch is rational but no weight buffer given",
                       what);
    return CJ_OK;
}

static cj_status split_dir(const cj_patch *p, int dir, double t, double *lp, double *lw, double *rp,
                           double *rw) {
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "split parameter is not finite");
    if (t < 0.0 || t > 1.0)
        return cj_fail(CJ_ERR_RANGE, "split parameter %.17g is outside [0,1]", t);
    if ((st = check_out_w(p, lp, lw, "left half"))) return st;
    if ((st = check_out_w(p, rp, rw, "right half"))) return st;
    double h[CJ_PATCH_NET_MAX], l[CJ_PATCH_NET_MAX], r[CJ_PATCH_NET_MAX];
    const int hd = cj_patch_load_h(p, h);
    split_h(h, hd, p->deg_u, p->deg_v, dir, t, lp ? l : NULL, rp ? r : NULL);
    const size_t count = cj_patch_point_count(p);
    if (lp) cj_patch_store_h(l, hd, count, lp, lw);
    if (rp) cj_patch_store_h(r, hd, count, rp, rw);
    return CJ_OK;
}

cj_status cj_patch_split_u(const cj_patch *p, double t, double *left_pts, double *left_w,
                           double *right_pts, double *right_w) {
    return split_dir(p, 0, t, left_pts, left_w, right_pts, right_w);
}

cj_status cj_patch_split_v(const cj_patch *p, double t, double *left_pts, double *left_w,
                           double *right_pts, double *right_w) {
    return split_dir(p, 1, t, left_pts, left_w, right_pts, right_w);
}

void cj_patch_sub_h(const double *h, int hd, int m, int n, double u0, double u1, double v0,
                    double v1, double *out) {
    double a[CJ_PATCH_NET_MAX], b[CJ_PATCH_NET_MAX];
    const size_t count = (size_t)(m + 1) * (size_t)(n + 1) * (size_t)hd;
    memcpy(a, h, sizeof(double) * count);
    /* u: keep [0,u1], then its part [u0/u1, 1]. */
    if (u1 < 1.0) {
        split_h(a, hd, m, n, 0, u1, b, NULL);
        memcpy(a, b, sizeof(double) * count);
    }
    if (u0 > 0.0) {
        split_h(a, hd, m, n, 0, u0 / u1, NULL, b);
        memcpy(a, b, sizeof(double) * count);
    }
    if (v1 < 1.0) {
        split_h(a, hd, m, n, 1, v1, b, NULL);
        memcpy(a, b, sizeof(double) * count);
    }
    if (v0 > 0.0) {
        split_h(a, hd, m, n, 1, v0 / v1, NULL, b);
        memcpy(a, b, sizeof(double) * count);
    }
    memcpy(out, a, sizeof(double) * count);
}

cj_status cj_patch_subpatch(const cj_patch *p, double u0, double u1, double v0, double v1,
                            double *out_pts, double *out_w) {
    assert(out_pts != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    const double prm[4] = {u0, u1, v0, v1};
    static const char *names[4] = {"u0", "u1", "v0", "v1"};
    for (int k = 0; k < 4; ++k) {
        if (!isfinite(prm[k]))
            return cj_fail(CJ_ERR_NONFINITE, "sub-patch %s is not finite", names[k]);
        if (prm[k] < 0.0 || prm[k] > 1.0)
            return cj_fail(CJ_ERR_RANGE, "sub-patch %s = %.17g is outside [0,1]", names[k], prm[k]);
    }
    if (!(u0 < u1))
        return cj_fail(CJ_ERR_RANGE, "sub-patch needs u0 < u1 (got %.17g, %.17g)", u0, u1);
    if (!(v0 < v1))
        return cj_fail(CJ_ERR_RANGE, "sub-patch needs v0 < v1 (got %.17g, %.17g)", v0, v1);
    if ((st = check_out_w(p, out_pts, out_w, "sub-patch"))) return st;
    double h[CJ_PATCH_NET_MAX], o[CJ_PATCH_NET_MAX];
    const int hd = cj_patch_load_h(p, h);
    cj_patch_sub_h(h, hd, p->deg_u, p->deg_v, u0, u1, v0, v1, o);
    cj_patch_store_h(o, hd, cj_patch_point_count(p), out_pts, out_w);
    return CJ_OK;
}

/* Elevates n+1 points (stride) by one degree into n+2 points (same stride). */
static void elevate_strided(const double *src, int n, int d, size_t stride, double *dst) {
    for (int k = 0; k < d; ++k) {
        dst[k] = src[k];
        dst[(size_t)(n + 1) * stride + (size_t)k] = src[(size_t)n * stride + (size_t)k];
    }
    for (int i = 1; i <= n; ++i) {
        const double a = (double)i / (double)(n + 1);
        for (int k = 0; k < d; ++k)
            dst[(size_t)i * stride + (size_t)k] = a * src[(size_t)(i - 1) * stride + (size_t)k] +
                                                  (1.0 - a) * src[(size_t)i * stride + (size_t)k];
    }
}

cj_status cj_patch_elevate(const cj_patch *p, int ru, int rv, double *out_pts, double *out_w) {
    assert(out_pts != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if (ru < 0 || rv < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "elevation steps (%d,%d) must be >= 0", ru, rv);
    if (p->deg_u + ru > CJ_PATCH_MAX_DEGREE || p->deg_v + rv > CJ_PATCH_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "elevated degree (%d,%d) exceeds the limit %d", p->deg_u + ru,
                       p->deg_v + rv, CJ_PATCH_MAX_DEGREE);
    if ((st = check_out_w(p, out_pts, out_w, "elevated patch"))) return st;
    double a[CJ_PATCH_NET_MAX], b[CJ_PATCH_NET_MAX];
    const int hd = cj_patch_load_h(p, a);
    int m = p->deg_u, n = p->deg_v;
    for (int s = 0; s < ru; ++s) {
        for (int j = 0; j <= n; ++j)
            elevate_strided(a + (size_t)j * (size_t)(m + 1) * (size_t)hd, m, hd, (size_t)hd,
                            b + (size_t)j * (size_t)(m + 2) * (size_t)hd);
        ++m;
        memcpy(a, b, sizeof(double) * (size_t)(m + 1) * (size_t)(n + 1) * (size_t)hd);
    }
    for (int s = 0; s < rv; ++s) {
        const size_t row = (size_t)(m + 1) * (size_t)hd;
        for (int i = 0; i <= m; ++i)
            elevate_strided(a + (size_t)i * (size_t)hd, n, hd, row, b + (size_t)i * (size_t)hd);
        ++n;
        memcpy(a, b, sizeof(double) * (size_t)(m + 1) * (size_t)(n + 1) * (size_t)hd);
    }
    cj_patch_store_h(a, hd, (size_t)(m + 1) * (size_t)(n + 1), out_pts, out_w);
    return CJ_OK;
}

cj_status cj_patch_bbox(const cj_patch *p, double lo[3], double hi[3]) {
    assert(lo != NULL && hi != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    const size_t count = cj_patch_point_count(p);
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = p->pts[k];
    for (size_t q = 1; q < count; ++q)
        for (int k = 0; k < 3; ++k) {
            const double x = p->pts[3 * q + (size_t)k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    return CJ_OK;
}

cj_status cj_patch_size(const cj_patch *p, double *size) {
    assert(size != NULL);
    double lo[3], hi[3];
    cj_status st = cj_patch_bbox(p, lo, hi);
    if (st) return st;
    *size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return CJ_OK;
}

static cj_status iso(const cj_patch *p, int dir, double t, double *out_pts, double *out_w) {
    assert(out_pts != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "iso-parameter is not finite");
    if ((st = check_out_w(p, out_pts, out_w, "iso curve"))) return st;
    double h[CJ_PATCH_NET_MAX], c[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    const int hd = cj_patch_load_h(p, h);
    const int m = p->deg_u, n = p->deg_v;
    const size_t row = (size_t)(m + 1) * (size_t)hd;
    int cnt;
    if (dir == 0) { /* fixed u: evaluate each row at u -> n+1 points */
        for (int j = 0; j <= n; ++j) dc_strided(h + j * row, m, hd, (size_t)hd, t, c + j * hd);
        cnt = n + 1;
    } else { /* fixed v: evaluate each column at v -> m+1 points */
        for (int i = 0; i <= m; ++i)
            dc_strided(h + (size_t)i * (size_t)hd, n, hd, row, t, c + i * hd);
        cnt = m + 1;
    }
    cj_patch_store_h(c, hd, (size_t)cnt, out_pts, out_w);
    return CJ_OK;
}

cj_status cj_patch_iso_u(const cj_patch *p, double u, double *out_pts, double *out_w) {
    return iso(p, 0, u, out_pts, out_w);
}

cj_status cj_patch_iso_v(const cj_patch *p, double v, double *out_pts, double *out_w) {
    return iso(p, 1, v, out_pts, out_w);
}

void cj_patch_edge_indices(int m, int n, int edge, int *first, int *step, int *count) {
    switch (edge) {
    case CJ_PATCH_EDGE_V0:
        *first = 0, *step = 1, *count = m + 1;
        break;
    case CJ_PATCH_EDGE_V1:
        *first = n * (m + 1), *step = 1, *count = m + 1;
        break;
    case CJ_PATCH_EDGE_U0:
        *first = 0, *step = m + 1, *count = n + 1;
        break;
    default: /* U1 */
        *first = m, *step = m + 1, *count = n + 1;
        break;
    }
}

cj_status cj_patch_boundary(const cj_patch *p, cj_patch_edge edge, double *out_pts, double *out_w,
                            int *degree) {
    assert(out_pts != NULL);
    cj_status st = cj_patch_check(p);
    if (st) return st;
    if ((unsigned)edge > 3u) return cj_fail(CJ_ERR_ARGUMENT, "unknown patch edge %d", (int)edge);
    if ((st = check_out_w(p, out_pts, out_w, "boundary curve"))) return st;
    int first, step, count;
    cj_patch_edge_indices(p->deg_u, p->deg_v, (int)edge, &first, &step, &count);
    for (int a = 0; a < count; ++a) {
        const int q = first + a * step;
        memcpy(out_pts + 3 * a, p->pts + 3 * q, sizeof(double) * 3);
        if (p->weights) out_w[a] = p->weights[q];
    }
    if (degree) *degree = count - 1;
    return CJ_OK;
}
