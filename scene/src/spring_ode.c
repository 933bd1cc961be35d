/* Time integrators for x'' = a(t, x, v): explicit, symplectic, RK4, and backward Euler by
 * Newton's method with dense LAPACKE solves. */
#include "casteljau/springs.h"

#include "error_internal.h"

#include <assert.h>
#include <lapacke.h>
#include <math.h>
#include <string.h>

const char *cj_integrator_name(cj_integrator m) {
    switch (m) {
    case CJ_INTEGRATE_EXPLICIT_EULER:
        return "explicit_euler";
    case CJ_INTEGRATE_SYMPLECTIC_EULER:
        return "symplectic_euler";
    case CJ_INTEGRATE_RK4:
        return "rk4";
    case CJ_INTEGRATE_IMPLICIT_EULER:
        return "implicit_euler";
    default:
        return "unknown";
    }
}

size_t cj_ode2_work_size(size_t n, cj_integrator m) {
    switch (m) {
    case CJ_INTEGRATE_EXPLICIT_EULER:
    case CJ_INTEGRATE_SYMPLECTIC_EULER:
        return n;
    case CJ_INTEGRATE_RK4:
        return 7 * n;
    case CJ_INTEGRATE_IMPLICIT_EULER:
        return 2 * n * n + 4 * n;
    default:
        return 0;
    }
}

static cj_status check_finite_state(const double *x, const double *v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(x[i]) || !isfinite(v[i]))
            return cj_fail(CJ_ERR_NONFINITE, "state component %zu became non-finite", i);
    return CJ_OK;
}

static void rk4_step(const cj_ode2 *s, double t, double h, double *x, double *v, double *w) {
    const size_t n = s->n;
    double *x0 = w, *v0 = w + n, *sx = w + 2 * n, *sv = w + 3 * n, *xt = w + 4 * n, *vt = w + 5 * n,
           *a = w + 6 * n;
    memcpy(x0, x, sizeof(double) * n);
    memcpy(v0, v, sizeof(double) * n);
    /* k1 */
    s->accel(s->user, t, x0, v0, a);
    for (size_t i = 0; i < n; ++i) {
        sx[i] = v0[i];
        sv[i] = a[i];
        xt[i] = x0[i] + 0.5 * h * v0[i];
        vt[i] = v0[i] + 0.5 * h * a[i];
    }
    /* k2 at the midpoint */
    s->accel(s->user, t + 0.5 * h, xt, vt, a);
    for (size_t i = 0; i < n; ++i) {
        const double kx = vt[i], kv = a[i];
        sx[i] += 2.0 * kx;
        sv[i] += 2.0 * kv;
        xt[i] = x0[i] + 0.5 * h * kx;
        vt[i] = v0[i] + 0.5 * h * kv;
    }
    /* k3 at the midpoint again */
    s->accel(s->user, t + 0.5 * h, xt, vt, a);
    for (size_t i = 0; i < n; ++i) {
        const double kx = vt[i], kv = a[i];
        sx[i] += 2.0 * kx;
        sv[i] += 2.0 * kv;
        xt[i] = x0[i] + h * kx;
        vt[i] = v0[i] + h * kv;
    }
    /* k4 at the end */
    s->accel(s->user, t + h, xt, vt, a);
    for (size_t i = 0; i < n; ++i) {
        x[i] = x0[i] + h / 6.0 * (sx[i] + vt[i]);
        v[i] = v0[i] + h / 6.0 * (sv[i] + a[i]);
    }
}

static cj_status implicit_step(const cj_ode2 *s, double t, double h, double *x, double *v,
                               double *w, int *ipiv, int *iters) {
    const size_t n = s->n;
    if (!s->jacobian) return cj_fail(CJ_ERR_ARGUMENT, "implicit Euler needs the Jacobians");
    if (n > CJ_ODE2_DENSE_MAX)
        return cj_fail(CJ_ERR_ARGUMENT, "implicit Euler: %zu unknowns exceed the dense limit %d", n,
                       CJ_ODE2_DENSE_MAX);
    double *J = w, *Av = w + n * n, *vn = w + 2 * n * n, *xn = vn + n, *a = xn + n, *r = a + n;
    memcpy(vn, v, sizeof(double) * n);
    double scale = 0.0;
    for (size_t i = 0; i < n; ++i) scale = fmax(scale, fmax(fabs(v[i]), fabs(x[i]) / h));
    cj_status st = CJ_ERR_CAP;
    int it = 0;
    while (it < 20) {
        ++it;
        for (size_t i = 0; i < n; ++i) xn[i] = x[i] + h * vn[i];
        s->accel(s->user, t + h, xn, vn, a);
        s->jacobian(s->user, t + h, xn, vn, J, Av);
        for (size_t i = 0; i < n; ++i) {
            r[i] = -(vn[i] - v[i] - h * a[i]);
            for (size_t j = 0; j < n; ++j)
                J[i * n + j] = (i == j ? 1.0 : 0.0) - h * h * J[i * n + j] - h * Av[i * n + j];
        }
        const lapack_int info =
            LAPACKE_dgesv(LAPACK_ROW_MAJOR, (lapack_int)n, 1, J, (lapack_int)n, ipiv, r, 1);
        if (info > 0)
            return cj_fail(CJ_ERR_SINGULAR, "implicit Euler: Newton matrix singular at pivot %d",
                           (int)info);
        if (info < 0) return cj_fail(CJ_ERR_ARGUMENT, "LAPACK dgesv argument %d", (int)-info);
        double dmax = 0.0;
        for (size_t i = 0; i < n; ++i) {
            vn[i] += r[i];
            dmax = fmax(dmax, fabs(r[i]));
            scale = fmax(scale, fabs(vn[i]));
        }
        if (!(dmax == dmax)) return cj_fail(CJ_ERR_NONFINITE, "implicit Euler: Newton diverged");
        if (dmax <= 1e-14 * scale || dmax == 0.0) {
            st = CJ_OK;
            break;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        v[i] = vn[i];
        x[i] = x[i] + h * vn[i];
    }
    if (iters) *iters = it;
    if (st == CJ_ERR_CAP)
        return cj_fail(CJ_ERR_CAP, "implicit Euler: Newton did not converge in 20 iterations");
    return CJ_OK;
}

cj_status cj_ode2_step(const cj_ode2 *s, cj_integrator m, double t, double h, double *x, double *v,
                       double *work, int *ipiv, int *newton_iters) {
    assert(s && s->accel && x && v && work);
    if (!(h > 0.0) || !isfinite(h)) return cj_fail(CJ_ERR_RANGE, "time step %g must be > 0", h);
    if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "time %g", t);
    const size_t n = s->n;
    if (newton_iters) *newton_iters = 0;
    switch (m) {
    case CJ_INTEGRATE_EXPLICIT_EULER:
        s->accel(s->user, t, x, v, work);
        for (size_t i = 0; i < n; ++i) {
            x[i] += h * v[i];
            v[i] += h * work[i];
        }
        break;
    case CJ_INTEGRATE_SYMPLECTIC_EULER:
        s->accel(s->user, t, x, v, work);
        for (size_t i = 0; i < n; ++i) {
            v[i] += h * work[i];
            x[i] += h * v[i];
        }
        break;
    case CJ_INTEGRATE_RK4:
        rk4_step(s, t, h, x, v, work);
        break;
    case CJ_INTEGRATE_IMPLICIT_EULER: {
        assert(ipiv);
        cj_status st = implicit_step(s, t, h, x, v, work, ipiv, newton_iters);
        if (st != CJ_OK) return st;
        break;
    }
    default:
        return cj_fail(CJ_ERR_ARGUMENT, "unknown integrator %d", (int)m);
    }
    return check_finite_state(x, v, n);
}
