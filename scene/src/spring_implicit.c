/* The spring system's backward Euler (Baraff–Witkin, matrix-free PCG), colliders and cloth. */
#include "casteljau/springs.h"

#include "error_internal.h"
#include "particle_internal.h"
#include "spring_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_seconds(void) {
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

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
    const double t0 = now_seconds();
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
    const double t1 = now_seconds();
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
    stats->seconds_solve = now_seconds() - t1;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(s->x[i]) || !isfinite(s->v[i]))
            return cj_fail(CJ_ERR_NONFINITE, "particle %zu: implicit step not finite", i / dim);
    return st;
}

/* Moves x to the surface point along the unit normal nrm, removes the inward normal velocity,
 * scales the tangential one. */
static void resolve(double *x, double *v, size_t dim, const double *nrm, double depth,
                    double friction) {
    double vn = 0.0;
    for (size_t k = 0; k < dim; ++k) {
        x[k] += depth * nrm[k];
        vn += v[k] * nrm[k];
    }
    for (size_t k = 0; k < dim; ++k) {
        const double vnk = vn * nrm[k];
        double vt = v[k] - vnk;
        vt *= 1.0 - friction;
        v[k] = (vn < 0.0 ? 0.0 : vnk) + vt;
    }
}

size_t cj_springs_collide(cj_springs *s) {
    const size_t dim = (size_t)s->dim;
    size_t hits = 0;
    if (s->npatch && dim == 3)
        for (size_t i = 0; i < s->count; ++i)
            if (!s->fixed[i])
                for (size_t j = 0; j < s->npatch; ++j)
                    hits += (size_t)cj_patch_collider_resolve_(
                        s->patch_colliders[j], s->xold + 3 * i, s->x + 3 * i, s->v + 3 * i, 0.0);
    if (s->nspheres == 0 && s->nplanes == 0) return hits;
    for (size_t i = 0; i < s->count; ++i) {
        if (s->fixed[i]) continue;
        double *x = s->x + i * dim, *v = s->v + i * dim;
        int hit = 0;
        for (size_t j = 0; j < s->nspheres; ++j) {
            const cj_sphere_collider *c = &s->spheres[j];
            double d[3] = {0, 0, 0}, l2 = 0.0;
            for (size_t k = 0; k < dim; ++k) {
                d[k] = x[k] - c->center[k];
                l2 += d[k] * d[k];
            }
            const double l = sqrt(l2);
            if (l >= c->radius) continue;
            double nrm[3] = {0, 0, 0};
            if (l > 0.0)
                for (size_t k = 0; k < dim; ++k) nrm[k] = d[k] / l;
            else
                nrm[dim - 1] = 1.0; /* at the centre: push out along the last axis */
            /* land exactly on the sphere: recompute the point rather than add a depth */
            for (size_t k = 0; k < dim; ++k) x[k] = c->center[k] + c->radius * nrm[k];
            resolve(x, v, dim, nrm, 0.0, c->friction);
            hit = 1;
        }
        for (size_t j = 0; j < s->nplanes; ++j) {
            const cj_plane_collider *c = &s->planes[j];
            double nl = 0.0, nrm[3] = {0, 0, 0}, side = 0.0;
            for (size_t k = 0; k < dim; ++k) nl += c->normal[k] * c->normal[k];
            nl = sqrt(nl);
            if (!(nl > 0.0)) continue;
            for (size_t k = 0; k < dim; ++k) {
                nrm[k] = c->normal[k] / nl;
                side += nrm[k] * x[k];
            }
            if (side >= c->offset) continue;
            resolve(x, v, dim, nrm, c->offset - side, c->friction);
            hit = 1;
        }
        hits += (size_t)hit;
    }
    return hits;
}

cj_status cj_springs_create_cloth(int nu, int nv, const double corner[3], const double eu[3],
                                  const double ev[3], double mass, double k_struct, double k_shear,
                                  double k_bend, double c, const int *pinned, size_t pinned_count,
                                  const cj_springs_desc *extra, const cj_allocator *alloc,
                                  cj_springs **out) {
    if (nu < 2 || nv < 2 || nu > 4096 || nv > 4096)
        return cj_fail(CJ_ERR_RANGE, "cloth grid %d x %d: each side must be in 2..4096", nu, nv);
    if (extra && extra->dim != 3)
        return cj_fail(CJ_ERR_DIMENSION, "cloth: extra description must be 3D");
    if (!(mass > 0.0) || !isfinite(mass))
        return cj_fail(CJ_ERR_RANGE, "cloth mass %g must be finite and > 0", mass);
    const size_t np = (size_t)nu * (size_t)nv;
    const size_t maxspr = 8 * np;
    double *x = malloc(sizeof(double) * 3 * np), *m = malloc(sizeof(double) * np);
    unsigned char *fixed = calloc(np, 1);
    cj_spring *spr = malloc(sizeof(cj_spring) * maxspr);
    cj_status st = CJ_OK;
    if (!x || !m || !fixed || !spr) {
        st = cj_fail(CJ_ERR_NOMEM, "cloth: no memory for %zu particles", np);
        goto done;
    }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const size_t id = (size_t)j * (size_t)nu + (size_t)i;
            const double a = (double)i / (nu - 1), b = (double)j / (nv - 1);
            for (int k = 0; k < 3; ++k) x[3 * id + k] = corner[k] + a * eu[k] + b * ev[k];
            m[id] = mass / (double)np;
        }
    for (size_t q = 0; q < pinned_count; ++q) {
        if (pinned[q] < 0 || (size_t)pinned[q] >= np) {
            st = cj_fail(CJ_ERR_ARGUMENT, "cloth: pinned particle %d of %zu", pinned[q], np);
            goto done;
        }
        fixed[pinned[q]] = 1;
    }
    size_t ns = 0;
    static const int offs[6][3] = {{1, 0, 0},  {0, 1, 0}, {1, 1, 1},
                                   {-1, 1, 1}, {2, 0, 2}, {0, 2, 2}};
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            for (int o = 0; o < 6; ++o) {
                const int i2 = i + offs[o][0], j2 = j + offs[o][1], kind = offs[o][2];
                const double k = kind == 0 ? k_struct : kind == 1 ? k_shear : k_bend;
                if (i2 < 0 || i2 >= nu || j2 >= nv || k == 0.0) continue;
                cj_spring *sp = &spr[ns++];
                sp->a = j * nu + i;
                sp->b = j2 * nu + i2;
                double l2 = 0.0;
                for (int kk = 0; kk < 3; ++kk) {
                    const double d = x[3 * (size_t)sp->a + kk] - x[3 * (size_t)sp->b + kk];
                    l2 += d * d;
                }
                sp->rest = sqrt(l2);
                sp->stiffness = k;
                sp->damping = c;
            }
    cj_springs_desc d;
    memset(&d, 0, sizeof d);
    if (extra) d = *extra;
    d.dim = 3;
    d.count = np;
    d.x = x;
    d.v = NULL;
    d.mass = m;
    d.fixed = fixed;
    d.spring_count = ns;
    d.springs = spr;
    st = cj_springs_create(&d, alloc, out);
done:
    free(x);
    free(m);
    free(fixed);
    free(spr);
    return st;
}
