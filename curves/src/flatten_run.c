/* Flattening: the three methods, the drivers and the public entry points. */
#include "flatten_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* ---- uniform (Wang) ----------------------------------------------------------------------- */

static cj_status run_uniform(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em,
                             double *bound) {
    const double K = cj_fl_wang_coefficient(fc);
    double pt[CJ_MAX_DIM];
    const double mf = K > 0.0 ? ceil(sqrt(K / tol_eff)) : 1.0;
    const size_t room = em->max_points - (em->count > 0 ? em->count - 1 : 0);
    /* room - 1 more segments fit (the first point of this curve may be shared). */
    if (!(mf <= (double)(room - 1))) return cj_fl_cap_fail(em, "uniform");
    const size_t m = (size_t)mf;
    cj_fl_end(fc, 0, pt);
    if (cj_fl_emit(em, pt, 0.0)) return cj_fl_cap_fail(em, "uniform");
    for (size_t j = 1; j < m; ++j) {
        const double t = (double)j / (double)m;
        cj_fl_eval(fc, t, pt);
        if (cj_fl_emit(em, pt, t)) return cj_fl_cap_fail(em, "uniform");
    }
    cj_fl_end(fc, fc->n, pt);
    if (cj_fl_emit(em, pt, 1.0)) return cj_fl_cap_fail(em, "uniform");
    *bound = K / (mf * mf) + fc->slack;
    return CJ_OK;
}

/* ---- recursive subdivision ---------------------------------------------------------------- */

#define SUBDIV_MAX_DEPTH 60
/* Subdivision refines a rejected piece's bound only when the cheap bound is at most this many
 * times tol (further above, the halves are needed anyway; refining them all would cost ~2x for
 * <1% fewer segments). */
#define SUBDIV_REFINE        1.5
#define SUBDIV_STACK_DOUBLES 4096

static cj_status subdiv_too_deep(double tol_eff, double a) {
    return cj_fail(CJ_ERR_RANGE,
                   "tolerance %.3g cannot be reached by subdivision near t = %.17g (parameter "
                   "resolution exhausted)",
                   tol_eff, a);
}

/* Pieces of small curves live on an explicit stack: halving a piece costs one de Casteljau
 * triangle. Curves too large for the stack take the stack-free walk below. */
static cj_status run_subdivide_stack(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em,
                                     double *bound) {
    const size_t S = (size_t)(fc->n + 1) * (size_t)fc->D;
    double stk[SUBDIV_STACK_DOUBLES], pa[SUBDIV_MAX_DEPTH + 2], pb[SUBDIV_MAX_DEPTH + 2];
    int lev[SUBDIV_MAX_DEPTH + 2];
    double pt[CJ_MAX_DIM], tmp[CJ_FL_WORK];
    double worst = 0.0;
    cj_fl_end(fc, 0, pt);
    if (cj_fl_emit(em, pt, 0.0)) return cj_fl_cap_fail(em, "subdivide");
    int top = 1;
    memcpy(stk, fc->hom, sizeof(double) * S);
    pa[0] = 0.0, pb[0] = 1.0, lev[0] = 0;
    while (top > 0) {
        double *cur = stk + (size_t)(top - 1) * S;
        const double D = cj_fl_piece_bound_refined(fc, cur, tol_eff, SUBDIV_REFINE * tol_eff,
                                                   CJ_FL_REFINE_GAIN, tol_eff);
        if (!isfinite(D))
            return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
        if (D <= tol_eff) {
            if (D > worst) worst = D;
            const double b = pb[top - 1];
            if (b == 1.0)
                cj_fl_end(fc, fc->n, pt);
            else
                cj_fl_point(fc, cur, fc->n, pt);
            if (cj_fl_emit(em, pt, b)) return cj_fl_cap_fail(em, "subdivide");
            --top;
            continue;
        }
        if (lev[top - 1] >= SUBDIV_MAX_DEPTH) return subdiv_too_deep(tol_eff, pa[top - 1]);
        /* right half replaces the piece, left half goes on top (processed first) */
        const double a = pa[top - 1], b = pb[top - 1], m = 0.5 * (a + b);
        cj_fl_split_half(cur, fc->n, fc->D, tmp, cur + S);
        memcpy(cur, cur + S, sizeof(double) * S);
        memcpy(cur + S, tmp, sizeof(double) * S);
        pa[top - 1] = m;
        pa[top] = a, pb[top] = m;
        lev[top] = ++lev[top - 1];
        ++top;
    }
    *bound = worst + fc->slack;
    return CJ_OK;
}

/* Stack-free walk over the dyadic pieces [k 2^-L, (k+1) 2^-L], each computed from the whole
 * curve; accepted pieces advance k, climbing while k is even. */
static cj_status run_subdivide(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em,
                               double *bound) {
    if ((size_t)(fc->n + 1) * (size_t)fc->D * (SUBDIV_MAX_DEPTH + 2) <= SUBDIV_STACK_DOUBLES)
        return run_subdivide_stack(fc, tol_eff, em, bound);
    double sub[CJ_FL_WORK], pt[CJ_MAX_DIM];
    double worst = 0.0;
    cj_fl_end(fc, 0, pt);
    if (cj_fl_emit(em, pt, 0.0)) return cj_fl_cap_fail(em, "subdivide");
    int L = 0;
    unsigned long long k = 0;
    for (;;) {
        const double a = ldexp((double)k, -L), b = ldexp((double)(k + 1), -L);
        cj_fl_subcurve(fc, a, b, sub);
        const double D = cj_fl_piece_bound_refined(fc, sub, tol_eff, SUBDIV_REFINE * tol_eff,
                                                   CJ_FL_REFINE_GAIN, tol_eff);
        if (!isfinite(D))
            return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
        if (D <= tol_eff) {
            if (D > worst) worst = D;
            if (b == 1.0)
                cj_fl_end(fc, fc->n, pt);
            else
                cj_fl_point(fc, sub, fc->n, pt);
            if (cj_fl_emit(em, pt, b)) return cj_fl_cap_fail(em, "subdivide");
            if (b == 1.0) break;
            ++k;
            while (L > 0 && (k & 1u) == 0) {
                k >>= 1;
                --L;
            }
        } else {
            if (L >= SUBDIV_MAX_DEPTH) return subdiv_too_deep(tol_eff, a);
            ++L;
            k <<= 1;
        }
    }
    *bound = worst + fc->slack;
    return CJ_OK;
}

/* ---- near-optimal (curvature-spaced, verified) -------------------------------------------- */

static cj_status run_near_optimal(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em,
                                  double *bound) {
    double sub[CJ_FL_WORK], sublo[CJ_FL_WORK], pt[CJ_MAX_DIM];
    const size_t nsub = (size_t)(fc->n + 1) * (size_t)fc->D;
    const double target = 0.975 * tol_eff, accept_lo = 0.95 * tol_eff;
    double worst = 0.0;
    cj_fl_end(fc, 0, pt);
    if (cj_fl_emit(em, pt, 0.0)) return cj_fl_cap_fail(em, "near-optimal");
    /* First step from Wang's count (its steps are safe everywhere, so a bit more is a good
     * first guess); afterwards the previous step predicts the next one. */
    const double K = cj_fl_wang_coefficient(fc);
    if (!isfinite(K))
        return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
    double h = K > 0.0 ? 1.5 / sqrt(K / tol_eff) : 1.0;
    if (h > 1.0) h = 1.0;
    double a = 0.0, hprev = 0.0;
    while (a < 1.0) {
        const double hmax = 1.0 - a;
        if (h > hmax) h = hmax;
        double lo = 0.0, Dlo = 0.0, hi = 0.0, Dhi = 0.0, blo = 0.0;
        int have_lo = 0, have_hi = 0;
        double hacc, Dacc, bacc;
        const double *acc = sub;
        for (int it = 0;; ++it) {
            const double b = h >= hmax ? 1.0 : a + h;
            if (!(b > a))
                return cj_fail(CJ_ERR_RANGE,
                               "tolerance %.3g cannot be reached in double precision near "
                               "t = %.17g",
                               tol_eff, a);
            cj_fl_subcurve(fc, a, b, sub);
            const double D =
                cj_fl_piece_bound_refined(fc, sub, accept_lo, INFINITY, CJ_FL_REFINE_GAIN, tol_eff);
            if (!isfinite(D))
                return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
            if (D <= tol_eff) {
                if (b == 1.0 || D >= accept_lo) {
                    hacc = h, Dacc = D, bacc = b;
                    acc = sub;
                    break;
                }
                lo = h, Dlo = D, blo = b, have_lo = 1;
                memcpy(sublo, sub, sizeof(double) * nsub);
            } else {
                hi = h, Dhi = D, have_hi = 1;
            }
            if (have_lo && (it >= 40 || (have_hi && hi - lo <= 1e-3 * lo))) {
                hacc = lo, Dacc = Dlo, bacc = blo;
                acc = sublo;
                break;
            }
            double hn;
            if (have_lo && have_hi) {
                /* log-log secant on the bound (~ h^2 on curved pieces, steeper near
                 * inflections), safeguarded to stay inside the bracket. */
                double p = 2.0;
                if (Dlo > 0.0 && Dhi > Dlo) p = log(Dhi / Dlo) / log(hi / lo);
                if (!(p >= 0.5)) p = 0.5;
                if (p > 8.0) p = 8.0;
                hn = Dlo > 0.0 ? lo * pow(target / Dlo, 1.0 / p) : 0.5 * (lo + hi);
                const double mar = 0.05 * (hi - lo);
                if (!(hn > lo + mar && hn < hi - mar)) hn = 0.5 * (lo + hi);
            } else if (have_lo) {
                hn = D > 0.0 ? h * sqrt(target / D) : 4.0 * h;
                if (hn < 1.02 * h) hn = 1.02 * h;
                if (hn > 4.0 * h) hn = 4.0 * h;
            } else {
                hn = h * sqrt(target / D);
                if (!(hn <= 0.9 * h)) hn = 0.9 * h;
                if (hn < 0.05 * h) hn = 0.05 * h;
            }
            h = hn < hmax ? hn : hmax;
        }
        if (Dacc > worst) worst = Dacc;
        if (bacc == 1.0)
            cj_fl_end(fc, fc->n, pt);
        else
            cj_fl_point(fc, acc, fc->n, pt);
        if (cj_fl_emit(em, pt, bacc)) return cj_fl_cap_fail(em, "near-optimal");
        a = bacc;
        /* Next guess: this step, corrected for the error it left unused and extrapolated by
         * the trend of the last two steps (curvature varies smoothly along most curves). */
        double hn = Dacc > 0.0 && bacc < 1.0 ? hacc * fmin(1.5, sqrt(target / Dacc)) : hacc;
        if (hprev > 0.0) hn *= fmax(0.7, fmin(1.4, hacc / hprev));
        hprev = hacc;
        h = hn;
    }
    *bound = worst + fc->slack;
    return CJ_OK;
}

/* ---- drivers ------------------------------------------------------------------------------ */

static cj_status check_opts(const cj_flatten_opts *opts) {
    assert(opts != NULL);
    if ((unsigned)opts->method >= CJ_FLATTEN_METHOD_COUNT_)
        return cj_fail(CJ_ERR_ARGUMENT, "flattening method %d is unknown", (int)opts->method);
    if (!isfinite(opts->tol))
        return cj_fail(CJ_ERR_NONFINITE, "tolerance is %s", isnan(opts->tol) ? "NaN" : "infinite");
    if (!(opts->tol > 0.0))
        return cj_fail(CJ_ERR_RANGE, "tolerance %.17g is not positive", opts->tol);
    return CJ_OK;
}

static cj_status flatten_one(const cj_fl_curve *fc, const cj_flatten_opts *opts, cj_fl_emitter *em,
                             double *bound) {
    if (opts->tol < 4.0 * fc->slack)
        return cj_fail(CJ_ERR_RANGE,
                       "tolerance %.3g is below what double rounding of coordinates this large "
                       "can guarantee (needs >= %.3g)",
                       opts->tol, 4.0 * fc->slack);
    const double tol_eff = opts->tol - fc->slack;
    if (fc->n == 0) { /* a single point: one zero-length segment */
        double pt[CJ_MAX_DIM];
        cj_fl_end(fc, 0, pt);
        if (cj_fl_emit(em, pt, 0.0) || cj_fl_emit(em, pt, 1.0)) return cj_fl_cap_fail(em, "any");
        *bound = 0.0;
        return CJ_OK;
    }
    switch (opts->method) {
    case CJ_FLATTEN_UNIFORM: {
        const double K = cj_fl_wang_coefficient(fc);
        if (!isfinite(K))
            return cj_fail(CJ_ERR_RANGE, "Wang's bound overflows: coordinates too large");
        return run_uniform(fc, tol_eff, em, bound);
    }
    case CJ_FLATTEN_SUBDIVIDE:
        return run_subdivide(fc, tol_eff, em, bound);
    default:
        if (cj_fl_fast_applies(fc)) return cj_fl_run_fast(fc, tol_eff, em, bound);
        return run_near_optimal(fc, tol_eff, em, bound);
    }
}

static void emitter_init(cj_fl_emitter *em, int d, const cj_flatten_opts *opts, double *out,
                         size_t cap_points, cj_flatten_sink sink, void *user) {
    memset(em, 0, sizeof *em);
    em->d = d;
    em->out = out;
    em->cap_points = cap_points;
    em->sink = sink;
    em->user = user;
    const size_t cap = opts->max_segments ? opts->max_segments : CJ_FLATTEN_DEFAULT_CAP;
    em->max_points = cap + 1;
}

static cj_status finish(const cj_fl_emitter *em, cj_status st, double bound, size_t *npoints,
                        cj_flatten_stats *stats) {
    if (npoints) *npoints = em->count;
    if (st) return st;
    if (stats) {
        stats->segments = em->count - 1;
        stats->bound = bound;
    }
    if (em->out && em->count > em->cap_points)
        return cj_fail(CJ_ERR_BUFFER, "output buffer holds %zu points, %zu are needed",
                       em->cap_points, em->count);
    return CJ_OK;
}

static cj_status flatten_single(const cj_bezier *c, const double *weights,
                                const cj_flatten_opts *opts, double *out, size_t cap_points,
                                cj_flatten_sink sink, void *user, size_t *npoints,
                                cj_flatten_stats *stats) {
    cj_status st = check_opts(opts);
    if (st) return st;
    cj_fl_curve fc;
    if ((st = cj_fl_init(&fc, c, weights))) return st;
    cj_fl_emitter em;
    emitter_init(&em, c->dim, opts, out, cap_points, sink, user);
    double bound = 0.0;
    st = flatten_one(&fc, opts, &em, &bound);
    return finish(&em, st, bound, npoints, stats);
}

cj_status cj_flatten_bezier(const cj_bezier *c, const cj_flatten_opts *opts, double *out,
                            size_t cap_points, size_t *npoints, cj_flatten_stats *stats) {
    assert(c != NULL && npoints != NULL);
    return flatten_single(c, NULL, opts, out, cap_points, NULL, NULL, npoints, stats);
}

cj_status cj_flatten_bezier_cb(const cj_bezier *c, const cj_flatten_opts *opts,
                               cj_flatten_sink sink, void *user, cj_flatten_stats *stats) {
    assert(c != NULL && sink != NULL);
    return flatten_single(c, NULL, opts, NULL, 0, sink, user, NULL, stats);
}

static cj_bezier rb_points(const cj_rbezier *c) {
    assert(c != NULL);
    assert(c->degree < 0 || c->weights != NULL);
    return cj_bezier_view(c->degree, c->dim, c->pts);
}

cj_status cj_flatten_rbezier(const cj_rbezier *c, const cj_flatten_opts *opts, double *out,
                             size_t cap_points, size_t *npoints, cj_flatten_stats *stats) {
    assert(npoints != NULL);
    const cj_bezier b = rb_points(c);
    return flatten_single(&b, c->weights, opts, out, cap_points, NULL, NULL, npoints, stats);
}

cj_status cj_flatten_rbezier_cb(const cj_rbezier *c, const cj_flatten_opts *opts,
                                cj_flatten_sink sink, void *user, cj_flatten_stats *stats) {
    assert(sink != NULL);
    const cj_bezier b = rb_points(c);
    return flatten_single(&b, c->weights, opts, NULL, 0, sink, user, NULL, stats);
}

static cj_status flatten_seq(const cj_flatten_piece *pieces, size_t count,
                             const cj_flatten_opts *opts, double *out, size_t cap_points,
                             cj_flatten_sink sink, void *user, size_t *npoints,
                             cj_flatten_stats *stats) {
    cj_status st = check_opts(opts);
    if (st) return st;
    if (count == 0) return cj_fail(CJ_ERR_EMPTY, "sequence has no pieces");
    assert(pieces != NULL);
    const int d = pieces[0].curve.dim;
    /* Validate every piece before emitting anything. */
    cj_fl_curve fc;
    for (size_t i = 0; i < count; ++i) {
        if (pieces[i].curve.dim != d)
            return cj_fail(CJ_ERR_DIMENSION, "piece %zu has dimension %d, piece 0 has %d", i,
                           pieces[i].curve.dim, d);
        if ((st = cj_fl_init(&fc, &pieces[i].curve, pieces[i].weights))) {
            char msg[512];
            strncpy(msg, cj_last_error(), sizeof msg - 1);
            msg[sizeof msg - 1] = '\0';
            return cj_fail(st, "piece %zu: %s", i, msg);
        }
    }
    cj_fl_emitter em;
    emitter_init(&em, d, opts, out, cap_points, sink, user);
    double worst = 0.0;
    for (size_t i = 0; i < count; ++i) {
        cj_fl_init(&fc, &pieces[i].curve, pieces[i].weights);
        em.piece = i;
        em.skip_equal = i > 0;
        double b = 0.0;
        st = flatten_one(&fc, opts, &em, &b);
        if (st) {
            char msg[512];
            strncpy(msg, cj_last_error(), sizeof msg - 1);
            msg[sizeof msg - 1] = '\0';
            cj_fail(st, "piece %zu: %s", i, msg);
            break;
        }
        if (b > worst) worst = b;
    }
    return finish(&em, st, worst, npoints, stats);
}

cj_status cj_flatten_sequence(const cj_flatten_piece *pieces, size_t count,
                              const cj_flatten_opts *opts, double *out, size_t cap_points,
                              size_t *npoints, cj_flatten_stats *stats) {
    assert(npoints != NULL);
    return flatten_seq(pieces, count, opts, out, cap_points, NULL, NULL, npoints, stats);
}

cj_status cj_flatten_sequence_cb(const cj_flatten_piece *pieces, size_t count,
                                 const cj_flatten_opts *opts, cj_flatten_sink sink, void *user,
                                 cj_flatten_stats *stats) {
    assert(sink != NULL);
    return flatten_seq(pieces, count, opts, NULL, 0, sink, user, NULL, stats);
}

cj_status cj_flatten_piece_bound(const cj_bezier *c, const double *weights, double *bound) {
    assert(bound != NULL);
    cj_fl_curve fc;
    cj_status st = cj_fl_init(&fc, c, weights);
    if (st) return st;
    const double D = cj_fl_piece_bound_refined(&fc, fc.hom, 0.0, INFINITY, 0.0, INFINITY);
    if (!isfinite(D))
        return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
    *bound = D + fc.slack;
    return CJ_OK;
}

cj_status cj_flatten_wang_count(const cj_bezier *c, const double *weights, double tol,
                                size_t *segments) {
    assert(segments != NULL);
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_UNIFORM, tol);
    cj_status st = check_opts(&o);
    if (st) return st;
    cj_fl_curve fc;
    if ((st = cj_fl_init(&fc, c, weights))) return st;
    if (tol < 4.0 * fc.slack)
        return cj_fail(CJ_ERR_RANGE, "tolerance %.3g is below the rounding floor %.3g", tol,
                       4.0 * fc.slack);
    const double K = cj_fl_wang_coefficient(&fc);
    if (!isfinite(K)) return cj_fail(CJ_ERR_RANGE, "Wang's bound overflows: coordinates too large");
    const double mf = K > 0.0 ? ceil(sqrt(K / (tol - fc.slack))) : 1.0;
    if (!(mf < 0x1p62)) return cj_fail(CJ_ERR_CAP, "Wang's count %.3g does not fit", mf);
    *segments = (size_t)mf;
    return CJ_OK;
}
