/* Arc-length reparameterisation: a Gauss–Kronrod table per segment, inverted by safeguarded
 * Newton. */
#include "casteljau/motion.h"

#include "casteljau/bezier.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CJ_PI 3.14159265358979323846

struct cj_path {
    cj_allocator alloc;
    int has_alloc;
    int dim;
    size_t nsegs;
    double length;
    double piece_tol; /* absolute tolerance of each arc-length call */
    double *segs;     /* nsegs × 4 × dim */
    double *cum;      /* nsegs × CJ_PATH_TABLE + 1 cumulative lengths */
};

static cj_bezier seg_of(const cj_path *p, size_t j) {
    return cj_bezier_view(3, p->dim, p->segs + j * 4 * (size_t)p->dim);
}

cj_status cj_path_create(const double *segs, size_t nsegs, int dim, double rel_tol,
                         const cj_allocator *alloc, cj_path **out) {
    assert(out && (segs || nsegs == 0));
    if (nsegs == 0) return cj_fail(CJ_ERR_EMPTY, "path has no segments");
    if (dim < 1 || dim > CJ_MAX_DIM) return cj_fail(CJ_ERR_DIMENSION, "path dimension %d", dim);
    if (!(rel_tol >= 1e-14 && rel_tol <= 0.1))
        return cj_fail(CJ_ERR_RANGE, "path relative tolerance %g outside [1e-14, 0.1]", rel_tol);
    for (size_t j = 0; j < nsegs * 4 * (size_t)dim; ++j)
        if (!isfinite(segs[j]))
            return cj_fail(CJ_ERR_NONFINITE, "path segment %zu, control point %zu is not finite",
                           j / (4 * (size_t)dim), (j / (size_t)dim) % 4);
    const size_t ntab = nsegs * CJ_PATH_TABLE + 1;
    const size_t bytes = sizeof(cj_path) + sizeof(double) * (nsegs * 4 * (size_t)dim + ntab);
    cj_path *p = alloc ? alloc->alloc(alloc->user, bytes) : malloc(bytes);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "path: no memory for %zu segments", nsegs);
    memset(p, 0, sizeof *p);
    if (alloc) {
        p->alloc = *alloc;
        p->has_alloc = 1;
    }
    p->dim = dim;
    p->nsegs = nsegs;
    p->segs = (double *)(p + 1);
    p->cum = p->segs + nsegs * 4 * (size_t)dim;
    memcpy(p->segs, segs, sizeof(double) * nsegs * 4 * (size_t)dim);
    /* The control polygon bounds the length from above: the tolerance is set from it, so the
     * summed piece errors stay below rel_tol·L/2 whatever the true L (>= chord). */
    double poly = 0.0;
    for (size_t j = 0; j < nsegs; ++j)
        for (int i = 0; i < 3; ++i) {
            double d2 = 0.0;
            for (int k = 0; k < dim; ++k) {
                const double d =
                    segs[(j * 4 + (size_t)i + 1) * dim + k] - segs[(j * 4 + (size_t)i) * dim + k];
                d2 += d * d;
            }
            poly += sqrt(d2);
        }
    cj_status st = CJ_OK;
    if (!(poly > 0.0)) {
        cj_path_destroy(p);
        return cj_fail(CJ_ERR_DEGENERATE, "path has zero length (all control points coincide)");
    }
    p->cum[0] = 0.0;
    double est_sum = 0.0;
    /* First pass with a provisional tolerance from the polygon, then the real length decides. */
    p->piece_tol = 0.25 * rel_tol * poly / (double)(ntab - 1);
    for (size_t j = 0; j < nsegs && st == CJ_OK; ++j) {
        const cj_bezier c = seg_of(p, j);
        for (int i = 0; i < CJ_PATH_TABLE; ++i) {
            double len, est;
            const double a = (double)i / CJ_PATH_TABLE, b = (double)(i + 1) / CJ_PATH_TABLE;
            st = cj_bezier_arclength(&c, a, b, p->piece_tol, &len, &est);
            if (st != CJ_OK) break;
            est_sum += est;
            const size_t k = j * CJ_PATH_TABLE + (size_t)i;
            p->cum[k + 1] = p->cum[k] + len;
        }
    }
    p->length = p->cum[ntab - 1];
    if (st == CJ_OK && !(p->length > 0.0)) st = cj_fail(CJ_ERR_DEGENERATE, "path has zero length");
    if (st == CJ_OK && est_sum > 0.5 * rel_tol * p->length)
        st = cj_fail(CJ_ERR_CAP, "path length error estimate %g exceeds %g of the length %g",
                     est_sum, rel_tol, p->length);
    if (st != CJ_OK) {
        cj_path_destroy(p);
        return st;
    }
    *out = p;
    return CJ_OK;
}

void cj_path_destroy(cj_path *p) {
    if (!p) return;
    if (p->has_alloc)
        p->alloc.free(p->alloc.user, p);
    else
        free(p);
}

double cj_path_length(const cj_path *p) {
    return p->length;
}
int cj_path_dim(const cj_path *p) {
    return p->dim;
}

static double speed_at(const cj_bezier *c, double u, double *deriv) {
    double d[2 * CJ_MAX_DIM];
    if (cj_bezier_eval_derivs(c, u, 1, d) != CJ_OK) return 0.0;
    double s2 = 0.0;
    for (int k = 0; k < c->dim; ++k) {
        deriv[k] = d[c->dim + k];
        s2 += deriv[k] * deriv[k];
    }
    return sqrt(s2);
}

cj_status cj_path_at_length(const cj_path *p, double s, double *point, double *tangent,
                            size_t *segment, double *u_out) {
    assert(p);
    if (!isfinite(s)) return cj_fail(CJ_ERR_NONFINITE, "path position %g", s);
    s = fmin(fmax(s, 0.0), p->length);
    const size_t ntab = p->nsegs * CJ_PATH_TABLE;
    size_t lo = 0, hi = ntab; /* cum[lo] <= s <= cum[hi] */
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (p->cum[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    const size_t j = lo / CJ_PATH_TABLE;
    const cj_bezier c = seg_of(p, j);
    const double ua = (double)(lo % CJ_PATH_TABLE) / CJ_PATH_TABLE;
    const double ub = (double)(lo % CJ_PATH_TABLE + 1) / CJ_PATH_TABLE;
    const double r = s - p->cum[lo], piece = p->cum[lo + 1] - p->cum[lo];
    double a = ua, b = ub;
    double u = piece > 0.0 ? ua + (ub - ua) * fmin(1.0, r / piece) : ua;
    double deriv[CJ_MAX_DIM];
    cj_status st = CJ_OK;
    for (int it = 0; it < 60; ++it) {
        double len = 0.0;
        st = u > ua ? cj_bezier_arclength(&c, ua, u, p->piece_tol, &len, NULL) : CJ_OK;
        if (st != CJ_OK && st != CJ_ERR_CAP) return st;
        st = CJ_OK;
        const double f = len - r;
        if (fabs(f) <= p->piece_tol) break;
        if (f > 0.0)
            b = u;
        else
            a = u;
        const double sp = speed_at(&c, u, deriv);
        double un = sp > 0.0 ? u - f / sp : 0.5 * (a + b);
        if (!(un > a && un < b)) un = 0.5 * (a + b);
        if (un == u || b - a <= 4 * CJ_UNIT_ROUNDOFF) break;
        u = un;
    }
    if (point) {
        st = cj_bezier_eval_decasteljau(&c, u, point);
        if (st != CJ_OK) return st;
    }
    if (tangent) {
        const double sp = speed_at(&c, u, deriv);
        for (int k = 0; k < p->dim; ++k) tangent[k] = sp > 0.0 ? deriv[k] / sp : 0.0;
    }
    if (segment) *segment = j;
    if (u_out) *u_out = u;
    return CJ_OK;
}

cj_status cj_ease_eval(cj_ease ease, double param, double x, double *sigma) {
    if (!isfinite(x)) return cj_fail(CJ_ERR_NONFINITE, "ease position %g", x);
    x = fmin(fmax(x, 0.0), 1.0);
    switch (ease) {
    case CJ_EASE_LINEAR:
        *sigma = x;
        return CJ_OK;
    case CJ_EASE_SMOOTHSTEP:
        *sigma = x * x * (3.0 - 2.0 * x);
        return CJ_OK;
    case CJ_EASE_SINE:
        *sigma = 0.5 * (1.0 - cos(CJ_PI * x));
        return CJ_OK;
    case CJ_EASE_TRAPEZOID: {
        if (!(param > 0.0 && param <= 0.5))
            return cj_fail(CJ_ERR_RANGE, "trapezoid acceleration fraction %g outside (0, 1/2]",
                           param);
        const double v = 1.0 / (1.0 - param);
        if (x < param)
            *sigma = v * x * x / (2.0 * param);
        else if (x <= 1.0 - param)
            *sigma = v * (x - 0.5 * param);
        else
            *sigma = 1.0 - v * (1.0 - x) * (1.0 - x) / (2.0 * param);
        return CJ_OK;
    }
    }
    return cj_fail(CJ_ERR_ARGUMENT, "unknown ease profile %d", (int)ease);
}

cj_status cj_path_motion(const cj_path *p, cj_ease ease, double param, double x, double *point,
                         double *tangent) {
    double sigma;
    cj_status st = cj_ease_eval(ease, param, x, &sigma);
    if (st != CJ_OK) return st;
    return cj_path_at_length(p, sigma * p->length, point, tangent, NULL, NULL);
}
