/* Hermite–Birkhoff polynomial interpolation in the Bernstein basis, solved by LAPACK's
 * equilibrated, refined LU (dgesvx); clashes diagnosed by pivoted QR (dgeqp3).
 * See casteljau/interp.h. */
#include "casteljau/interp.h"
#include "casteljau/bezier.h"
#include "error_internal.h"

#include <assert.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAXM (CJ_INTERP_MAX_DEGREE + 1)

/* Row of the system for the r-th derivative at parameter u (local), degree n, interval h:
 * d^r/dt^r B_i^n(u(t)) = h^-r n!/(n-r)! Σ_k (-1)^(r-k) C(r,k) B_{i-k}^{n-r}(u). */
static void basis_row(int n, int r, double u, double h, double *row) {
    for (int i = 0; i <= n; ++i) row[i] = 0.0;
    if (r > n) return;
    const int m = n - r;
    double b[MAXM];
    b[0] = 1.0;
    for (int lev = 1; lev <= m; ++lev) { /* Bernstein basis of degree lev at u */
        b[lev] = u * b[lev - 1];
        for (int j = lev - 1; j >= 1; --j) b[j] = (1.0 - u) * b[j] + u * b[j - 1];
        b[0] = (1.0 - u) * b[0];
    }
    double f = 1.0;
    for (int q = 0; q < r; ++q) f *= (double)(n - q) / h;
    double crk = 1.0; /* C(r, k) */
    for (int k = 0; k <= r; ++k) {
        const double sgn = ((r - k) & 1) ? -1.0 : 1.0;
        for (int j = 0; j <= m; ++j) row[j + k] += sgn * crk * b[j];
        crk = crk * (double)(r - k) / (double)(k + 1);
    }
    for (int i = 0; i <= n; ++i) row[i] *= f;
}

static cj_status check_constraints(const cj_interp_constraint *cons, size_t m, int dim) {
    for (size_t j = 0; j < m; ++j) {
        if (!isfinite(cons[j].t))
            return cj_fail(CJ_ERR_NONFINITE, "constraint %zu: parameter t is not finite", j);
        if (cons[j].order < 0)
            return cj_fail(CJ_ERR_ARGUMENT, "constraint %zu: derivative order %d is negative", j,
                           cons[j].order);
        assert(cons[j].value != NULL);
        for (int k = 0; k < dim; ++k)
            if (!isfinite(cons[j].value[k]))
                return cj_fail(CJ_ERR_NONFINITE, "constraint %zu: value coordinate %d is %s", j, k,
                               isnan(cons[j].value[k]) ? "NaN" : "infinite");
    }
    const int n = (int)m - 1;
    for (size_t j = 0; j < m; ++j) {
        if (cons[j].order > n)
            return cj_fail(CJ_ERR_SINGULAR,
                           "constraint %zu: derivative order %d exceeds the degree %d that %zu "
                           "constraints determine (that derivative is identically zero)",
                           j, cons[j].order, n, m);
        for (size_t i = 0; i < j; ++i)
            if (cons[i].t == cons[j].t && cons[i].order == cons[j].order) {
                int same = 1;
                for (int k = 0; k < dim; ++k) same &= cons[i].value[k] == cons[j].value[k];
                if (cons[j].order == 0)
                    return cj_fail(CJ_ERR_SINGULAR,
                                   "constraints %zu and %zu both fix the value at t = %.17g%s", i,
                                   j, cons[j].t, same ? " (repeated)" : " to different points");
                return cj_fail(CJ_ERR_SINGULAR,
                               "constraints %zu and %zu both fix derivative %d at t = %.17g%s", i,
                               j, cons[j].order, cons[j].t,
                               same ? " (repeated)" : " to different vectors");
            }
    }
    return CJ_OK;
}

/* Names a constraint that depends on the others: QR with column pivoting of A^T (columns =
 * constraints, normalised), the last pivot column being the least independent. */
static cj_status diagnose_singular(const double *a, int m, const cj_interp_constraint *cons,
                                   double cond) {
    double at[MAXM * MAXM], tau[MAXM];
    lapack_int jpvt[MAXM];
    for (int j = 0; j < m; ++j) { /* column j of A^T = row j of A */
        double nrm = 0.0;
        for (int i = 0; i < m; ++i) nrm = fmax(nrm, fabs(a[j * m + i]));
        for (int i = 0; i < m; ++i) at[i * m + j] = nrm > 0.0 ? a[j * m + i] / nrm : 0.0;
        jpvt[j] = 0;
    }
    lapack_int info = LAPACKE_dgeqp3(LAPACK_ROW_MAJOR, m, m, at, m, jpvt, tau);
    if (info != 0 || m < 2)
        return cj_fail(CJ_ERR_SINGULAR,
                       "constraint set is singular (condition estimate %g): it does not "
                       "determine the polynomial",
                       cond);
    const int j = (int)jpvt[m - 1] - 1; /* 1-based */
    /* |R_mm| / |R_11| tells a numerically dependent constraint from a merely ill-conditioned
     * (but determined) set, e.g. equispaced parameters at high degree. */
    const double r11 = fabs(at[0]), rmm = fabs(at[(m - 1) * m + (m - 1)]);
    if (rmm <= 1e3 * (double)m * CJ_UNIT_ROUNDOFF * r11)
        return cj_fail(CJ_ERR_SINGULAR,
                       "constraints do not determine the polynomial (condition estimate %g): "
                       "constraint %d (order %d at t = %.17g) depends linearly on the others",
                       cond, j, cons[j].order, cons[j].t);
    return cj_fail(CJ_ERR_SINGULAR,
                   "constraint set too ill-conditioned for double precision (condition estimate "
                   "%g > %g); closest to dependent: constraint %d (order %d at t = %.17g); "
                   "use fewer constraints or Chebyshev-like parameters",
                   cond, 1.0 / (64.0 * CJ_UNIT_ROUNDOFF), j, cons[j].order, cons[j].t);
}

cj_status cj_interp_solve(const cj_interp_constraint *cons, size_t m, int dim, double a, double b,
                          double *bez, double *power, double *cond) {
    assert(bez != NULL);
    if (m == 0) return cj_fail(CJ_ERR_EMPTY, "no interpolation constraints");
    if (m > MAXM)
        return cj_fail(CJ_ERR_DEGREE, "%zu constraints ask for degree %zu, above the limit %d", m,
                       m - 1, CJ_INTERP_MAX_DEGREE);
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    if (!isfinite(a) || !isfinite(b))
        return cj_fail(CJ_ERR_NONFINITE, "interval [a, b] bound is not finite");
    if (!(a < b))
        return cj_fail(CJ_ERR_ARGUMENT, "interval [%.17g, %.17g] is empty: need a < b", a, b);
    assert(cons != NULL);
    cj_status st = check_constraints(cons, m, dim);
    if (st) return st;

    const int n = (int)m - 1, M = (int)m;
    const double h = b - a;
    if (!isfinite(h))
        return cj_fail(CJ_ERR_RANGE,
                       "parameter interval [%.17g, %.17g] is wider than the double range", a, b);
    double *work = malloc(sizeof(double) * (size_t)(3 * M * M + 2 * M * dim + 6 * M));
    lapack_int *ipiv = malloc(sizeof(lapack_int) * (size_t)M);
    if (!work || !ipiv) {
        free(work);
        free(ipiv);
        return cj_fail(CJ_ERR_NOMEM, "out of memory for a %d x %d interpolation system", M, M);
    }
    double *A = work, *A0 = A + M * M, *AF = A0 + M * M, *B = AF + M * M, *X = B + M * dim;
    double *R = X + M * dim, *C = R + M, *ferr = C + M, *berr = ferr + M;
    for (int j = 0; j < M; ++j) {
        basis_row(n, cons[j].order, (cons[j].t - a) / h, h, A + j * M);
        for (int k = 0; k < dim; ++k) B[j * dim + k] = cons[j].value[k];
    }
    memcpy(A0, A, sizeof(double) * (size_t)(M * M));
    char equed = 'N';
    double rcond = 0.0, rpivot = 0.0;
    lapack_int info = LAPACKE_dgesvx(LAPACK_ROW_MAJOR, 'E', 'N', M, dim, A, M, AF, M, ipiv, &equed,
                                     R, C, B, dim, X, dim, &rcond, ferr, berr, &rpivot);
    const double cnd = rcond > 0.0 ? 1.0 / rcond : INFINITY;
    if (info < 0) {
        st = cj_fail(CJ_ERR_ARGUMENT, "LAPACK dgesvx rejected argument %d", (int)-info);
    } else if (info > 0 || !(cnd <= 1.0 / (64.0 * CJ_UNIT_ROUNDOFF))) {
        st = diagnose_singular(A0, M, cons, cnd);
    } else {
        for (int i = 0; i < M * dim; ++i)
            if (!isfinite(X[i])) {
                st = cj_fail(CJ_ERR_SINGULAR, "interpolation solution is not finite");
                break;
            }
    }
    if (!st && power) {
        /* Taylor expansion at t = 0: power_k = c^(k)(0)/k!, c^(k) = h^-k d^k/du^k. */
        double *D = A0; /* reuse: (n+1)*dim doubles */
        cj_bezier bc = cj_bezier_view(n, dim, X);
        if ((st = cj_bezier_eval_derivs(&bc, (0.0 - a) / h, n, D)) == CJ_OK) {
            double f = 1.0;
            for (int k = 0; k <= n; ++k) {
                if (k > 0) f *= h * (double)k;
                for (int q = 0; q < dim; ++q) power[k * dim + q] = D[k * dim + q] / f;
            }
        }
    }
    if (!st) {
        memcpy(bez, X, sizeof(double) * (size_t)(M * dim));
        if (cond) *cond = cnd;
    }
    free(work);
    free(ipiv);
    return st;
}

cj_status cj_interp_points(const double *ts, const double *pts, size_t npts, int dim, double a,
                           double b, double *bez, double *power, double *cond) {
    if (npts == 0) return cj_fail(CJ_ERR_EMPTY, "no points to interpolate");
    if (npts > MAXM)
        return cj_fail(CJ_ERR_DEGREE, "%zu points ask for degree %zu, above the limit %d", npts,
                       npts - 1, CJ_INTERP_MAX_DEGREE);
    assert(ts != NULL && pts != NULL);
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    cj_interp_constraint cons[MAXM];
    for (size_t j = 0; j < npts; ++j) {
        cons[j].t = ts[j];
        cons[j].order = 0;
        cons[j].value = pts + j * (size_t)dim;
    }
    return cj_interp_solve(cons, npts, dim, a, b, bez, power, cond);
}

static cj_status check_nodes(int n, double a, double b) {
    if (!isfinite(a) || !isfinite(b))
        return cj_fail(CJ_ERR_NONFINITE, "parameter interval bound is not finite");
    if (n < 1) return cj_fail(CJ_ERR_ARGUMENT, "need n >= 1 (n + 1 parameters), got %d", n);
    if (!(a < b))
        return cj_fail(CJ_ERR_ARGUMENT, "interval [%.17g, %.17g] is empty: need a < b", a, b);
    return CJ_OK;
}

cj_status cj_interp_equispaced(int n, double a, double b, double *out) {
    assert(out != NULL);
    cj_status st = check_nodes(n, a, b);
    if (st) return st;
    for (int k = 0; k <= n; ++k) out[k] = a + (b - a) * ((double)k / (double)n);
    out[0] = a;
    out[n] = b;
    return CJ_OK;
}

cj_status cj_interp_chebyshev(int n, double a, double b, double *out) {
    assert(out != NULL);
    cj_status st = check_nodes(n, a, b);
    if (st) return st;
    const double pi = 3.14159265358979323846;
    for (int k = 0; k <= n; ++k) {
        /* (1 − cos θ)/2 = sin²(θ/2): no cancellation near the left end. */
        const double s = sin((2.0 * k + 1.0) * pi / (4.0 * n + 4.0));
        out[k] = a + (b - a) * (s * s);
    }
    return CJ_OK;
}
