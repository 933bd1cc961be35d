/* The spring system's backward Euler (Baraff–Witkin, matrix-free PCG). */
#include "casteljau/springs.h"

#include "error_internal.h"
#include "particle_internal.h"
#include "spring_internal.h"
#include "clock_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Per spring: S = beta I + (alpha − beta) n nᵀ is the spring's block of h C + h² K (with the
 * compressive part clamped), and the rhs uses gamma n nᵀ + beta (I − n nᵀ) = h² K. */
static void fill_cache(cj_springs *s, double h) {
    const size_t dim = (size_t)s->dim;
    for (size_t j = 0; j < s->nsprings; ++j) {
        const cj_spring *sp = &s->springs[j];
        double *c = s->cache + 6 * j, d[3] = {0, 0, 0}, l2 = 0.0;
        for (size_t k = 0; k < dim; ++k) {
            d[k] = s->x[(size_t)sp->a * dim + k] - s->x[(size_t)sp->b * dim + k];
            l2 += d[k] * d[k];
        }
        const double l = sqrt(l2);
        if (!(l > 0.0)) {
            memset(c, 0, sizeof(double) * 6);
            continue;
        }
        for (size_t k = 0; k < 3; ++k) c[k] = d[k] / l;
        const double lat = fmax(0.0, 1.0 - sp->rest / l);
        c[3] = h * sp->damping + h * h * sp->stiffness; /* alpha: along n */
        c[4] = h * h * sp->stiffness * lat;             /* beta: across n */
        c[5] = h * h * sp->stiffness;                   /* gamma: rhs along n */
        if (dim == 1) c[4] = 0.0;                       /* no transverse direction in 1D */
    }
}

/* y = A x with A = M (1 + h drag) + Σ springs S, fixed rows and columns removed. */
static void apply_A(const cj_springs *s, double h, const double *x, double *y) {
    const size_t dim = (size_t)s->dim;
    for (size_t i = 0; i < s->count; ++i)
        for (size_t k = 0; k < dim; ++k)
            y[i * dim + k] = s->fixed[i] ? 0.0 : s->mass[i] * (1.0 + h * s->drag) * x[i * dim + k];
    for (size_t j = 0; j < s->nsprings; ++j) {
        const cj_spring *sp = &s->springs[j];
        const double *c = s->cache + 6 * j;
        const size_t a = (size_t)sp->a * dim, b = (size_t)sp->b * dim;
        double dx[3], nd = 0.0;
        for (size_t k = 0; k < dim; ++k) {
            const double xa = s->fixed[sp->a] ? 0.0 : x[a + k];
            const double xb = s->fixed[sp->b] ? 0.0 : x[b + k];
            dx[k] = xa - xb;
            nd += c[k] * dx[k];
        }
        for (size_t k = 0; k < dim; ++k) {
            const double yk = c[4] * dx[k] + (c[3] - c[4]) * c[k] * nd;
            if (!s->fixed[sp->a]) y[a + k] += yk;
            if (!s->fixed[sp->b]) y[b + k] -= yk;
        }
    }
}

cj_status cj_springs_implicit_step(cj_springs *s, double h, cj_springs_stats *stats) {
    const size_t dim = (size_t)s->dim, n = s->count * dim;
    double *dv = s->cg, *r = dv + n, *p = r + n, *q = p + n, *z = q + n, *diag = z + n,
           *rhs = diag + n;
    const double t0 = cj_clock_seconds();
    fill_cache(s, h);
    cj_springs_forces_at(s, s->x, s->v, rhs);
    for (size_t i = 0; i < n; ++i) rhs[i] *= h;
    for (size_t i = 0; i < s->count; ++i)
        for (size_t k = 0; k < dim; ++k) diag[i * dim + k] = s->mass[i] * (1.0 + h * s->drag);
    for (size_t j = 0; j < s->nsprings; ++j) {
        const cj_spring *sp = &s->springs[j];
        const double *c = s->cache + 6 * j;
        const size_t a = (size_t)sp->a * dim, b = (size_t)sp->b * dim;
        double dvel[3], nd = 0.0;
        for (size_t k = 0; k < dim; ++k) {
            dvel[k] = s->v[a + k] - s->v[b + k];
            nd += c[k] * dvel[k];
        }
        for (size_t k = 0; k < dim; ++k) {
            const double t = c[5] * c[k] * nd + c[4] * (dvel[k] - c[k] * nd);
            rhs[a + k] -= t;
            rhs[b + k] += t;
            const double dk = c[4] + (c[3] - c[4]) * c[k] * c[k];
            diag[a + k] += dk;
            diag[b + k] += dk;
        }
    }
    for (size_t i = 0; i < s->count; ++i)
        if (s->fixed[i])
            for (size_t k = 0; k < dim; ++k) {
                rhs[i * dim + k] = 0.0;
                diag[i * dim + k] = 1.0;
            }
    const double t1 = cj_clock_seconds();
    /* Preconditioned CG from Δv = 0. */
    double bnorm = 0.0, rz = 0.0;
    for (size_t i = 0; i < n; ++i) {
        dv[i] = 0.0;
        r[i] = rhs[i];
        z[i] = r[i] / diag[i];
        p[i] = z[i];
        bnorm += rhs[i] * rhs[i];
        rz += r[i] * z[i];
    }
    bnorm = sqrt(bnorm);
    int it = 0;
    double rn = bnorm;
    cj_status st = CJ_OK;
    while (rn > 1e-9 * bnorm && rn > 0.0) {
        if (it >= CJ_SPRING_CG_MAX) {
            st = CJ_ERR_CAP;
            break;
        }
        ++it;
        apply_A(s, h, p, q);
        double pq = 0.0;
        for (size_t i = 0; i < n; ++i) pq += p[i] * q[i];
        if (!(pq > 0.0)) break; /* exact solution reached (or breakdown) */
        const double alpha = rz / pq;
        double rz_new = 0.0, r2 = 0.0;
        for (size_t i = 0; i < n; ++i) {
            dv[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            z[i] = r[i] / diag[i];
            rz_new += r[i] * z[i];
            r2 += r[i] * r[i];
        }
        rn = sqrt(r2);
        const double beta = rz_new / rz;
        rz = rz_new;
        for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    }
    for (size_t i = 0; i < n; ++i) {
        s->v[i] += dv[i];
        s->x[i] += h * s->v[i];
    }
    stats->cg_iterations = it;
    stats->cg_residual = bnorm > 0.0 ? rn / bnorm : 0.0;
    stats->seconds_forces = t1 - t0;
    stats->seconds_solve = cj_clock_seconds() - t1;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(s->x[i]) || !isfinite(s->v[i]))
            return cj_fail(CJ_ERR_NONFINITE, "particle %zu: implicit step not finite", i / dim);
    return st;
}
