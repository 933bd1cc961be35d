/* B-spline interpolation and least-squares approximation (banded LAPACK solves). See
 * casteljau/bspline_fit.h. */
#include "casteljau/bspline_fit.h"
#include "bspline_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static double distance(const double *a, const double *b, int dim) {
    double s = 0.0;
    for (int k = 0; k < dim; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
    return sqrt(s);
}

static cj_status check_data(const double *pts, int npts, int dim) {
    if (npts < 2) return cj_fail(CJ_ERR_EMPTY, "%d data points are too few to fit a curve", npts);
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    return cj_check_points(pts, (size_t)npts, dim, "data point");
}

cj_status cj_fit_params(const double *pts, int npts, int dim, cj_fit_param kind, double *ts) {
    assert(pts != NULL && ts != NULL);
    cj_status st = check_data(pts, npts, dim);
    if (st) return st;
    if (kind != CJ_FIT_UNIFORM && kind != CJ_FIT_CHORD && kind != CJ_FIT_CENTRIPETAL)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown parametrisation %d", (int)kind);
    ts[0] = 0.0;
    for (int k = 1; k < npts; ++k) {
        double step = 1.0;
        if (kind != CJ_FIT_UNIFORM) {
            step =
                distance(pts + (size_t)k * (size_t)dim, pts + (size_t)(k - 1) * (size_t)dim, dim);
            if (!(step > 0.0))
                return cj_fail(CJ_ERR_DEGENERATE,
                               "data points %d and %d coincide (chord-length and centripetal "
                               "parameters need distinct neighbours)",
                               k - 1, k);
            if (kind == CJ_FIT_CENTRIPETAL) step = sqrt(step);
        }
        ts[k] = ts[k - 1] + step;
        if (!isfinite(ts[k]))
            return cj_fail(CJ_ERR_RANGE, "total chord length overflows at data point %d", k);
    }
    const double total = ts[npts - 1];
    for (int k = 1; k < npts - 1; ++k) ts[k] /= total;
    ts[npts - 1] = 1.0;
    return CJ_OK;
}

/* Largest s in [p, m-1] with U[s] <= u (u in [0, 1], clamped knots). */
static int span_of(const double *U, int p, int m, double u) {
    int lo = p, hi = m - 1;
    while (lo < hi) {
        const int mid = lo + (hi - lo + 1) / 2;
        if (U[mid] <= u)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* The p+1 basis functions N_{s-p..s, p}(u) of span s into N[p+1]: the triangle of
 * Cox–de Boor ratios, built one degree at a time. */
static void basis(const double *U, int p, int s, double u, double *N) {
    double left[CJ_BSPLINE_MAX_DEGREE + 1], right[CJ_BSPLINE_MAX_DEGREE + 1];
    N[0] = 1.0;
    for (int j = 1; j <= p; ++j) {
        left[j] = u - U[s + 1 - j];
        right[j] = U[s + j] - u;
        double carry = 0.0;
        for (int r = 0; r < j; ++r) {
            const double q = N[r] / (right[r + 1] + left[j - r]);
            N[r] = carry + right[r + 1] * q;
            carry = left[j - r] * q;
        }
        N[j] = carry;
    }
}

/* Largest Euclidean deviation of the curve from the data at its parameters. */
static double deviation(const cj_bspline *c, const double *pts, const double *ts, int npts) {
    double worst = 0.0, v[CJ_MAX_DIM];
    for (int k = 0; k < npts; ++k) {
        cj_bspline_eval_unchecked(c, ts[k], v); /* validated by construction, ts in [0, 1] */
        worst = fmax(worst, distance(v, pts + (size_t)k * (size_t)c->dim, c->dim));
    }
    return worst;
}

static void clamp_ends(double *U, int p, int m) {
    for (int i = 0; i <= p; ++i) {
        U[i] = 0.0;
        U[m + i] = 1.0;
    }
}

cj_status cj_bsp_interp_solve(const double *pts, int npts, int dim, int p, const double *ts,
                              const double *d_start, const double *d_end, double *out_pts,
                              double *out_knots) {
    const int s0 = d_start != NULL, s1 = d_end != NULL, m = npts + s0 + s1;
    cj_status st = CJ_OK;
    double *ext = malloc(sizeof(double) * (size_t)m);
    int *spans = malloc(sizeof(int) * (size_t)m);
    double *U = malloc(sizeof(double) * (size_t)(m + p + 1));
    double *ab = NULL, *rhs = malloc(sizeof(double) * (size_t)m * (size_t)dim);
    lapack_int *ipiv = malloc(sizeof(lapack_int) * (size_t)m);
    if (!ext || !spans || !U || !rhs || !ipiv) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory to interpolate %d points", npts);
        goto done;
    }
    /* Knots by averaging the parameters (an end with a derivative repeats its parameter). */
    int e = 0;
    if (s0) ext[e++] = 0.0;
    for (int k = 0; k < npts; ++k) ext[e++] = ts[k];
    if (s1) ext[e++] = 1.0;
    clamp_ends(U, p, m);
    for (int j = 1; j <= m - p - 1; ++j) {
        double sum = 0.0;
        for (int i = j; i < j + p; ++i) sum += ext[i];
        U[j + p] = sum / p;
    }
    /* Row layout: Q_0, [c'(0)], Q_1..Q_{N-2}, [c'(1)], Q_{N-1}; band widths from the spans. */
    int kl = 1, ku = 1, walk = p;
    for (int k = 1; k < npts - 1; ++k) {
        /* the parameters increase: the span walks forward (the search only if they do not) */
        if (ts[k] < ts[k - 1])
            walk = span_of(U, p, m, ts[k]);
        else
            while (walk < m - 1 && U[walk + 1] <= ts[k]) ++walk;
        const int row = k + s0, s = walk;
        spans[row] = s;
        if (row - (s - p) > kl) kl = row - (s - p);
        if (s - row > ku) ku = s - row;
    }
    const int ldab = 2 * kl + ku + 1;
    ab = calloc((size_t)ldab * (size_t)m, sizeof(double));
    if (!ab) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory to interpolate %d points", npts);
        goto done;
    }
#define AB(i, j) ab[(size_t)(kl + ku + (i) - (j)) + (size_t)(j) * (size_t)ldab]
    AB(0, 0) = 1.0;
    AB(m - 1, m - 1) = 1.0;
    for (int k = 0; k < dim; ++k) {
        rhs[(size_t)k * (size_t)m] = pts[k];
        rhs[(size_t)(m - 1) + (size_t)k * (size_t)m] = pts[(size_t)(npts - 1) * (size_t)dim + k];
    }
    if (s0) {
        const double f = p / U[p + 1];
        AB(1, 0) = -f;
        AB(1, 1) = f;
        for (int k = 0; k < dim; ++k) rhs[1 + (size_t)k * (size_t)m] = d_start[k];
    }
    if (s1) {
        const double f = p / (1.0 - U[m - 1]);
        AB(m - 2, m - 2) = -f;
        AB(m - 2, m - 1) = f;
        for (int k = 0; k < dim; ++k) rhs[(size_t)(m - 2) + (size_t)k * (size_t)m] = d_end[k];
    }
    for (int k = 1; k < npts - 1; ++k) {
        const int row = k + s0, s = spans[row];
        double N[CJ_BSPLINE_MAX_DEGREE + 1];
        basis(U, p, s, ts[k], N);
        for (int i = 0; i <= p; ++i) AB(row, s - p + i) = N[i];
        for (int c = 0; c < dim; ++c)
            rhs[(size_t)row + (size_t)c * (size_t)m] = pts[(size_t)k * (size_t)dim + c];
    }
    /* Without end derivatives the matrix is a B-spline collocation matrix at increasing
     * parameters: totally nonnegative, so Gaussian elimination without pivoting is stable (de
     * Boor and Pinkus) and needs no fill beyond the band; it is solved here in place, several
     * times faster than the general banded LU with pivoting (dgbsv), which the rows of end
     * derivatives (negative entries) still use. */
    lapack_int info = 0;
    if (!s0 && !s1) {
        for (int j = 0; j < m && info == 0; ++j) {
            const double piv = AB(j, j);
            if (!(fabs(piv) > 0.0) || !isfinite(piv)) {
                info = j + 1;
                break;
            }
            const int imax = j + kl < m - 1 ? j + kl : m - 1,
                      cmax = j + ku < m - 1 ? j + ku : m - 1;
            for (int i = j + 1; i <= imax; ++i) {
                const double f = AB(i, j) / piv;
                if (f == 0.0) continue;
                for (int c = j + 1; c <= cmax; ++c) AB(i, c) -= f * AB(j, c);
                for (int k = 0; k < dim; ++k)
                    rhs[(size_t)i + (size_t)k * (size_t)m] -=
                        f * rhs[(size_t)j + (size_t)k * (size_t)m];
            }
        }
        for (int j = m - 1; j >= 0 && info == 0; --j) {
            const int cmax = j + ku < m - 1 ? j + ku : m - 1;
            for (int k = 0; k < dim; ++k) {
                double v = rhs[(size_t)j + (size_t)k * (size_t)m];
                for (int c = j + 1; c <= cmax; ++c)
                    v -= AB(j, c) * rhs[(size_t)c + (size_t)k * (size_t)m];
                rhs[(size_t)j + (size_t)k * (size_t)m] = v / AB(j, j);
            }
        }
    } else {
        info = LAPACKE_dgbsv(LAPACK_COL_MAJOR, m, kl, ku, dim, ab, ldab, ipiv, rhs, m);
    }
#undef AB
    if (info != 0) {
        st = cj_fail(CJ_ERR_SINGULAR, "interpolation system is singular (LAPACK dgbsv info %d)",
                     (int)info);
        goto done;
    }
    for (int i = 0; i < m; ++i)
        for (int c = 0; c < dim; ++c) {
            const double v = rhs[(size_t)i + (size_t)c * (size_t)m];
            if (!isfinite(v)) {
                st = cj_fail(CJ_ERR_RANGE, "control point %d of the interpolant overflows", i);
                goto done;
            }
            out_pts[(size_t)i * (size_t)dim + c] = v;
        }
    memcpy(out_knots, U, sizeof(double) * (size_t)(m + p + 1));
done:
    free(ext);
    free(spans);
    free(U);
    free(ab);
    free(rhs);
    free(ipiv);
    return st;
}

cj_status cj_bspline_interpolate(const double *pts, int npts, int dim, int degree,
                                 cj_fit_param kind, const double *d_start, const double *d_end,
                                 double *out_pts, double *out_knots, int *npts_out,
                                 double *residual) {
    assert(pts != NULL && out_pts != NULL && out_knots != NULL && npts_out != NULL);
    cj_status st = check_data(pts, npts, dim);
    if (st) return st;
    const int p = degree;
    if (p < 1 || p > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "fitting degree %d is outside 1..%d", p,
                       CJ_BSPLINE_MAX_DEGREE);
    if (d_start && (st = cj_check_finite(d_start, (size_t)dim, "start derivative"))) return st;
    if (d_end && (st = cj_check_finite(d_end, (size_t)dim, "end derivative"))) return st;
    const int s0 = d_start != NULL, s1 = d_end != NULL, m = npts + s0 + s1;
    if ((s0 || s1) && p < 2)
        return cj_fail(CJ_ERR_DEGREE,
                       "end derivatives need degree >= 2 (a polyline's end slopes are its "
                       "chords)");
    if (m < p + 1)
        return cj_fail(CJ_ERR_EMPTY, "%d data points%s are too few for degree %d", npts,
                       s0 || s1 ? " and end derivatives" : "", p);
    double *ts = malloc(sizeof(double) * (size_t)npts);
    if (!ts) return cj_fail(CJ_ERR_NOMEM, "no memory for %d parameters", npts);
    if (!(st = cj_fit_params(pts, npts, dim, kind, ts)) &&
        !(st = cj_bsp_interp_solve(pts, npts, dim, p, ts, d_start, d_end, out_pts, out_knots))) {
        *npts_out = m;
        if (residual) {
            const cj_bspline c = cj_bspline_view(p, dim, m, out_pts, NULL, out_knots);
            *residual = deviation(&c, pts, ts, npts);
        }
    }
    free(ts);
    return st;
}

/* Least squares with m control points given the parameters ts; writes P[m*dim], U[m+p+1]. */
static cj_status lsq_fixed(const double *pts, const double *ts, int npts, int dim, int p, int m,
                           double *P, double *U) {
    clamp_ends(U, p, m);
    const double dd = (double)npts / (m - p);
    for (int j = 1; j <= m - p - 1; ++j) {
        const int i = (int)(j * dd);
        const double a = j * dd - i;
        U[p + j] = (1.0 - a) * ts[i - 1] + a * ts[i];
    }
    for (int c = 0; c < dim; ++c) {
        P[c] = pts[c];
        P[(size_t)(m - 1) * (size_t)dim + c] = pts[(size_t)(npts - 1) * (size_t)dim + c];
    }
    const int nu = m - 2; /* unknowns d_1..d_{m-2} */
    if (nu <= 0) return CJ_OK;
    const int kd = p, ldab = kd + 1;
    double *ab = calloc((size_t)ldab * (size_t)nu, sizeof(double));
    double *rhs = calloc((size_t)nu * (size_t)dim, sizeof(double));
    if (!ab || !rhs) {
        free(ab);
        free(rhs);
        return cj_fail(CJ_ERR_NOMEM, "no memory for a least-squares fit of %d points", npts);
    }
    for (int k = 1; k < npts - 1; ++k) {
        const int s = span_of(U, p, m, ts[k]);
        double N[CJ_BSPLINE_MAX_DEGREE + 1], R[CJ_MAX_DIM];
        basis(U, p, s, ts[k], N);
        for (int c = 0; c < dim; ++c) R[c] = pts[(size_t)k * (size_t)dim + c];
        for (int i = 0; i <= p; ++i) {
            const int col = s - p + i;
            if (col == 0)
                for (int c = 0; c < dim; ++c) R[c] -= N[i] * P[c];
            if (col == m - 1)
                for (int c = 0; c < dim; ++c) R[c] -= N[i] * P[(size_t)(m - 1) * (size_t)dim + c];
        }
        for (int i = 0; i <= p; ++i) {
            const int a = s - p + i - 1;
            if (a < 0 || a >= nu) continue;
            for (int c = 0; c < dim; ++c) rhs[(size_t)a + (size_t)c * (size_t)nu] += N[i] * R[c];
            for (int j = i; j <= p; ++j) {
                const int b = s - p + j - 1;
                if (b < 0 || b >= nu) continue;
                ab[(size_t)(kd + a - b) + (size_t)b * (size_t)ldab] += N[i] * N[j];
            }
        }
    }
    lapack_int info = LAPACKE_dpbsv(LAPACK_COL_MAJOR, 'U', nu, kd, dim, ab, ldab, rhs, nu);
    cj_status st = CJ_OK;
    if (info != 0)
        st = cj_fail(CJ_ERR_SINGULAR,
                     "least-squares normal equations with %d control points are singular "
                     "(LAPACK dpbsv info %d)",
                     m, (int)info);
    else
        for (int i = 0; i < nu; ++i)
            for (int c = 0; c < dim; ++c)
                P[(size_t)(i + 1) * (size_t)dim + c] = rhs[(size_t)i + (size_t)c * (size_t)nu];
    free(ab);
    free(rhs);
    return st;
}

static cj_status check_fit_args(const double *pts, int npts, int dim, int p) {
    cj_status st = check_data(pts, npts, dim);
    if (st) return st;
    if (p < 1 || p > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "fitting degree %d is outside 1..%d", p,
                       CJ_BSPLINE_MAX_DEGREE);
    if (npts < p + 1)
        return cj_fail(CJ_ERR_EMPTY, "%d data points are too few for degree %d", npts, p);
    return CJ_OK;
}

cj_status cj_bspline_lsq(const double *pts, int npts, int dim, int degree, cj_fit_param kind, int m,
                         double *out_pts, double *out_knots, double *max_dev) {
    assert(pts != NULL && out_pts != NULL && out_knots != NULL);
    cj_status st = check_fit_args(pts, npts, dim, degree);
    if (st) return st;
    if (m < degree + 1 || m > npts)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "%d control points: need %d..%d for degree %d and %d points", m, degree + 1,
                       npts, degree, npts);
    double *ts = malloc(sizeof(double) * (size_t)npts);
    if (!ts) return cj_fail(CJ_ERR_NOMEM, "no memory for %d parameters", npts);
    if (!(st = cj_fit_params(pts, npts, dim, kind, ts)) &&
        !(st = lsq_fixed(pts, ts, npts, dim, degree, m, out_pts, out_knots)) && max_dev) {
        const cj_bspline c = cj_bspline_view(degree, dim, m, out_pts, NULL, out_knots);
        *max_dev = deviation(&c, pts, ts, npts);
    }
    free(ts);
    return st;
}

cj_status cj_bspline_approximate(const double *pts, int npts, int dim, int degree,
                                 cj_fit_param kind, double tol, int max_pts, double *out_pts,
                                 double *out_knots, int *npts_out, double *max_dev) {
    assert(pts != NULL && out_pts != NULL && out_knots != NULL && npts_out != NULL);
    cj_status st = check_fit_args(pts, npts, dim, degree);
    if (st) return st;
    const int p = degree;
    if (isnan(tol)) return cj_fail(CJ_ERR_NONFINITE, "fitting tolerance is NaN");
    if (!(tol >= 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "fitting tolerance %g is negative", tol);
    if (max_pts < p + 1)
        return cj_fail(CJ_ERR_ARGUMENT, "a cap of %d control points is below degree + 1 = %d",
                       max_pts, p + 1);
    const int cap = max_pts < npts ? max_pts : npts;
    double *ts = malloc(sizeof(double) * (size_t)npts);
    double *P = malloc(sizeof(double) * (size_t)cap * (size_t)dim);
    double *U = malloc(sizeof(double) * (size_t)(cap + p + 1));
    if (!ts || !P || !U) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory to approximate %d points", npts);
        goto done;
    }
    if ((st = cj_fit_params(pts, npts, dim, kind, ts))) goto done;
    int best = 0, fail = p; /* best: smallest M found within tol; fail: largest M known to fail */
    double best_dev = INFINITY;
    int m = p + 1;
    for (;;) {
        if ((st = lsq_fixed(pts, ts, npts, dim, p, m, P, U))) goto done;
        const cj_bspline c = cj_bspline_view(p, dim, m, P, NULL, U);
        const double dev = deviation(&c, pts, ts, npts);
        if (dev <= tol) {
            best = m;
            best_dev = dev;
            memcpy(out_pts, P, sizeof(double) * (size_t)m * (size_t)dim);
            memcpy(out_knots, U, sizeof(double) * (size_t)(m + p + 1));
        } else {
            fail = m;
            if (m == cap) { /* nothing within tol up to the cap: report the largest */
                if (!best) {
                    memcpy(out_pts, P, sizeof(double) * (size_t)m * (size_t)dim);
                    memcpy(out_knots, U, sizeof(double) * (size_t)(m + p + 1));
                    *npts_out = m;
                    if (max_dev) *max_dev = dev;
                    st = cj_fail(CJ_ERR_CAP,
                                 "no fit within %g with up to %d control points (deviation %g)",
                                 tol, cap, dev);
                    goto done;
                }
            }
        }
        if (best && best - fail <= 1) break;
        if (best)
            m = fail + (best - fail) / 2;
        else {
            const int grow = m + (m + 1) / 2;
            m = grow > cap ? cap : grow;
        }
    }
    *npts_out = best;
    if (max_dev) *max_dev = best_dev;
done:
    free(ts);
    free(P);
    free(U);
    return st;
}
