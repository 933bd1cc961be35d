/* Forward kinematics of joint trees and inverse kinematics by damped least squares (with the
 * damping adapted Levenberg–Marquardt style so that every accepted step lowers the residual)
 * or the Jacobian transpose. */
#include "casteljau/kinematics.h"
#include "casteljau/vec.h"

#include "error_internal.h"

#include <assert.h>
#include <lapacke.h>
#include <math.h>
#include <string.h>

#define MAXR (3 * CJ_IK_MAX_EFFECTORS)

cj_ik_options cj_ik_defaults(cj_ik_method method) {
    cj_ik_options o;
    o.method = method;
    o.damping = 0.05;
    o.tol = 1e-10;
    o.max_step = 0.5;
    o.max_iterations = method == CJ_IK_DLS ? 1000 : 100000;
    o.stall_window = 20;
    return o;
}

static int finite3(const double *v) {
    return cj_v3_finite(cj_v3(v[0], v[1], v[2]));
}

cj_status cj_chain_check(const cj_chain *c, const double *q) {
    assert(c);
    if (c->count < 0 || c->count > CJ_CHAIN_MAX_JOINTS)
        return cj_fail(CJ_ERR_ARGUMENT, "chain has %d joints (0..%d)", c->count,
                       CJ_CHAIN_MAX_JOINTS);
    if (!finite3(c->base)) return cj_fail(CJ_ERR_NONFINITE, "chain base not finite");
    for (int j = 0; j < c->count; ++j) {
        const cj_joint *J = &c->joints[j];
        if (J->parent < -1 || J->parent >= j)
            return cj_fail(CJ_ERR_ARGUMENT, "joint %d: parent %d is not an earlier joint", j,
                           J->parent);
        if ((int)J->kind < 0 || J->kind > CJ_JOINT_PRISMATIC)
            return cj_fail(CJ_ERR_ARGUMENT, "joint %d: unknown kind %d", j, (int)J->kind);
        if (!finite3(J->offset) || !finite3(J->axis))
            return cj_fail(CJ_ERR_NONFINITE, "joint %d: offset or axis not finite", j);
        if (!(J->axis[0] * J->axis[0] + J->axis[1] * J->axis[1] + J->axis[2] * J->axis[2] > 0.0))
            return cj_fail(CJ_ERR_DEGENERATE, "joint %d: zero axis", j);
        if (J->lo != J->lo || J->hi != J->hi || J->lo > J->hi)
            return cj_fail(CJ_ERR_ARGUMENT, "joint %d: limits [%g, %g]", j, J->lo, J->hi);
        if (q) {
            if (!isfinite(q[j])) return cj_fail(CJ_ERR_NONFINITE, "joint %d: value %g", j, q[j]);
            if (q[j] < J->lo || q[j] > J->hi)
                return cj_fail(CJ_ERR_ARGUMENT, "joint %d: value %g outside its limits [%g, %g]", j,
                               q[j], J->lo, J->hi);
        }
    }
    return CJ_OK;
}

static void unit_axis(const double *a, double *u) {
    const double n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; ++k) u[k] = a[k] / n;
}

static void matvec(const double *R, const double *v, double *out) {
    for (int r = 0; r < 3; ++r)
        out[r] = R[3 * r] * v[0] + R[3 * r + 1] * v[1] + R[3 * r + 2] * v[2];
}

static void fk_raw(const cj_chain *c, const double *q, cj_chain_pose *pose) {
    static const double ident[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int j = 0; j < c->count; ++j) {
        const cj_joint *J = &c->joints[j];
        const double *RP = J->parent < 0 ? ident : pose->R[J->parent];
        const double *pP = J->parent < 0 ? c->base : pose->p[J->parent];
        double u[3], off[3], w[3];
        unit_axis(J->axis, u);
        memcpy(off, J->offset, sizeof off);
        if (J->kind == CJ_JOINT_PRISMATIC)
            for (int k = 0; k < 3; ++k) off[k] += q[j] * u[k];
        matvec(RP, off, w);
        for (int k = 0; k < 3; ++k) pose->p[j][k] = pP[k] + w[k];
        if (J->kind == CJ_JOINT_PRISMATIC) {
            memcpy(pose->R[j], RP, sizeof(double) * 9);
            continue;
        }
        /* Rodrigues: Rot = cI + s[u]x + (1−c) u uᵀ */
        const double cs = cos(q[j]), sn = sin(q[j]), t = 1.0 - cs;
        const double Rot[9] = {
            cs + t * u[0] * u[0],        t * u[0] * u[1] - sn * u[2], t * u[0] * u[2] + sn * u[1],
            t * u[0] * u[1] + sn * u[2], cs + t * u[1] * u[1],        t * u[1] * u[2] - sn * u[0],
            t * u[0] * u[2] - sn * u[1], t * u[1] * u[2] + sn * u[0], cs + t * u[2] * u[2]};
        for (int r = 0; r < 3; ++r)
            for (int cc = 0; cc < 3; ++cc)
                pose->R[j][3 * r + cc] =
                    RP[3 * r] * Rot[cc] + RP[3 * r + 1] * Rot[3 + cc] + RP[3 * r + 2] * Rot[6 + cc];
    }
}

cj_status cj_chain_fk(const cj_chain *c, const double *q, cj_chain_pose *pose) {
    assert(c && q && pose);
    cj_status st = cj_chain_check(c, q);
    if (st != CJ_OK) return st;
    fk_raw(c, q, pose);
    return CJ_OK;
}

void cj_chain_point(const cj_chain_pose *pose, int joint, const double local[3], double out[3]) {
    double w[3];
    matvec(pose->R[joint], local, w);
    for (int k = 0; k < 3; ++k) out[k] = pose->p[joint][k] + w[k];
}

/* Stacked error e = g − x and its norm. */
static double error_at(const cj_chain *c, const double *q, const cj_ik_effector *eff, size_t m,
                       cj_chain_pose *pose, double *e) {
    fk_raw(c, q, pose);
    double s = 0.0;
    for (size_t i = 0; i < m; ++i) {
        double x[3];
        cj_chain_point(pose, eff[i].joint, eff[i].local, x);
        for (int k = 0; k < 3; ++k) {
            e[3 * i + (size_t)k] = eff[i].target[k] - x[k];
            s += e[3 * i + (size_t)k] * e[3 * i + (size_t)k];
        }
    }
    return sqrt(s);
}

/* J (rows 3m, columns n, row-major) at the pose. */
static void jacobian(const cj_chain *c, const cj_chain_pose *pose, const cj_ik_effector *eff,
                     size_t m, const double *e, double *Jm) {
    static const double ident[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int n = c->count;
    memset(Jm, 0, sizeof(double) * 3 * m * (size_t)n);
    for (size_t i = 0; i < m; ++i) {
        double x[3];
        for (int k = 0; k < 3; ++k) x[k] = eff[i].target[k] - e[3 * i + (size_t)k];
        for (int j = eff[i].joint; j >= 0; j = c->joints[j].parent) {
            const cj_joint *J = &c->joints[j];
            const double *RP = J->parent < 0 ? ident : pose->R[J->parent];
            double u[3], a[3], col[3];
            unit_axis(J->axis, u);
            matvec(RP, u, a);
            if (J->kind == CJ_JOINT_PRISMATIC) {
                memcpy(col, a, sizeof col);
            } else {
                const double d[3] = {x[0] - pose->p[j][0], x[1] - pose->p[j][1],
                                     x[2] - pose->p[j][2]};
                col[0] = a[1] * d[2] - a[2] * d[1];
                col[1] = a[2] * d[0] - a[0] * d[2];
                col[2] = a[0] * d[1] - a[1] * d[0];
            }
            for (int k = 0; k < 3; ++k) Jm[(3 * i + (size_t)k) * (size_t)n + (size_t)j] = col[k];
        }
    }
}

cj_status cj_ik_solve(const cj_chain *c, double *q, const cj_ik_effector *eff, size_t m,
                      const cj_ik_options *opt_in, cj_ik_result *result) {
    assert(c && q && (eff || m == 0));
    cj_ik_options opt = opt_in ? *opt_in : cj_ik_defaults(CJ_IK_DLS);
    cj_status st = cj_chain_check(c, q);
    if (st != CJ_OK) return st;
    if (m == 0 || m > CJ_IK_MAX_EFFECTORS)
        return cj_fail(CJ_ERR_ARGUMENT, "%zu effectors (1..%d)", m, CJ_IK_MAX_EFFECTORS);
    for (size_t i = 0; i < m; ++i) {
        if (eff[i].joint < 0 || eff[i].joint >= c->count)
            return cj_fail(CJ_ERR_ARGUMENT, "effector %zu on joint %d of %d", i, eff[i].joint,
                           c->count);
        if (!finite3(eff[i].target) || !finite3(eff[i].local))
            return cj_fail(CJ_ERR_NONFINITE, "effector %zu: target or point not finite", i);
    }
    if (!(opt.tol > 0.0) || !(opt.max_step > 0.0) || !(opt.damping >= 0.0) ||
        !isfinite(opt.damping) || opt.max_iterations < 1 || opt.stall_window < 1)
        return cj_fail(CJ_ERR_ARGUMENT, "IK options: tol, max_step > 0, damping >= 0, "
                                        "iterations and stall window >= 1");
    const int n = c->count;
    const size_t rows = 3 * m;
    cj_chain_pose pose;
    double e[MAXR], enew[MAXR], Jm[MAXR * CJ_CHAIN_MAX_JOINTS], A[MAXR * MAXR], y[MAXR];
    double dq[CJ_CHAIN_MAX_JOINTS], qn[CJ_CHAIN_MAX_JOINTS];
    double r = error_at(c, q, eff, m, &pose, e);
    double lambda2 = opt.damping * opt.damping, mu = 1.0;
    double best = r;
    int since = 0, it = 0;
    cj_ik_outcome outcome = CJ_IK_MAX_ITERATIONS;
    if (r <= opt.tol) outcome = CJ_IK_REACHED;
    while (outcome != CJ_IK_REACHED && it < opt.max_iterations) {
        ++it;
        jacobian(c, &pose, eff, m, e, Jm);
        if (opt.method == CJ_IK_DLS) {
            for (size_t a = 0; a < rows; ++a)
                for (size_t b = 0; b < rows; ++b) {
                    double s = 0.0;
                    for (int k = 0; k < n; ++k)
                        s += Jm[a * (size_t)n + (size_t)k] * Jm[b * (size_t)n + (size_t)k];
                    A[a * rows + b] = s + (a == b ? lambda2 : 0.0);
                }
            memcpy(y, e, sizeof(double) * rows);
            const lapack_int info = LAPACKE_dposv(LAPACK_ROW_MAJOR, 'U', (lapack_int)rows, 1, A,
                                                  (lapack_int)rows, y, 1);
            if (info != 0) {
                if (opt.damping > 0.0 && lambda2 < 1e30) {
                    lambda2 = lambda2 > 0.0 ? 4.0 * lambda2 : 1e-12;
                    continue;
                }
                return cj_fail(CJ_ERR_SINGULAR, "IK: J Jᵀ + λ²I singular at iteration %d", it);
            }
        } else {
            /* y = α e with Buss's α = (e·JJᵀe)/|JJᵀe|², times the backtracking factor μ */
            double jte[CJ_CHAIN_MAX_JOINTS], jjte[MAXR], num = 0.0, den = 0.0;
            for (int k = 0; k < n; ++k) {
                jte[k] = 0.0;
                for (size_t a = 0; a < rows; ++a) jte[k] += Jm[a * (size_t)n + (size_t)k] * e[a];
            }
            for (size_t a = 0; a < rows; ++a) {
                jjte[a] = 0.0;
                for (int k = 0; k < n; ++k) jjte[a] += Jm[a * (size_t)n + (size_t)k] * jte[k];
                num += e[a] * jjte[a];
                den += jjte[a] * jjte[a];
            }
            const double alpha = den > 0.0 ? mu * num / den : 0.0;
            for (size_t a = 0; a < rows; ++a) y[a] = alpha * e[a];
        }
        double big = 0.0;
        for (int k = 0; k < n; ++k) {
            dq[k] = 0.0;
            for (size_t a = 0; a < rows; ++a) dq[k] += Jm[a * (size_t)n + (size_t)k] * y[a];
            big = fmax(big, fabs(dq[k]));
        }
        const double sc = big > opt.max_step ? opt.max_step / big : 1.0;
        for (int k = 0; k < n; ++k)
            qn[k] = fmin(fmax(q[k] + sc * dq[k], c->joints[k].lo), c->joints[k].hi);
        cj_chain_pose pn;
        const double rn = error_at(c, qn, eff, m, &pn, enew);
        if (rn < r) { /* accept: relax the damping / grow the transpose step again */
            memcpy(q, qn, sizeof(double) * (size_t)n);
            memcpy(e, enew, sizeof(double) * rows);
            pose = pn;
            r = rn;
            lambda2 = fmax(lambda2 / 9.0, 1e-12 * opt.damping * opt.damping);
            mu = fmin(1.0, 2.0 * mu);
        } else { /* reject: more damping / a shorter transpose step */
            lambda2 = lambda2 > 0.0 ? 16.0 * lambda2 : 1e-12;
            mu *= 0.5;
        }
        if (r <= opt.tol) {
            outcome = CJ_IK_REACHED;
        } else if (r < best * (1.0 - 1e-12)) {
            best = r;
            since = 0;
        } else if (++since >= opt.stall_window || lambda2 > 1e30 || mu < 1e-30) {
            outcome = CJ_IK_STALLED;
            break;
        }
    }
    if (result) {
        result->outcome = outcome;
        result->iterations = it;
        result->residual = r;
    }
    if (outcome == CJ_IK_REACHED) return CJ_OK;
    return cj_fail(CJ_ERR_CAP, "IK %s after %d iterations with residual %.3g (closest pose kept)",
                   outcome == CJ_IK_STALLED ? "stalled (target unreachable or a local minimum)"
                                            : "ran out of iterations",
                   it, r);
}
