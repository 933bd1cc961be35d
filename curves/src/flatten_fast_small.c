/* The planar fast path's measured second placement for plans of few segments. */
#include "flatten_fast_internal.h"

/* ---- few segments: a measured second placement --------------------------------------------
 *
 * With few segments per curve the whole-number count and the model's spread cost most (a long
 * segment's deviation strays further from the parabola model's estimate: across an inflection it
 * is far below it), and the per-curve set-up dominates the time, so a second placement pays:
 * the planned points are certified first without emitting, and each bound D_k tells how many
 * segments of deviation FAST_SMALL_TARGET tol its piece needs, sqrt(D_k / (FAST_SMALL_TARGET
 * tol)) by the h^2 law. When their sum asks for fewer segments than planned, the points are
 * placed again at equal steps of that measure (linear in t within each planned piece) and
 * certified as usual; otherwise the planned points, already certified, are emitted. */

/* 0.97 rather than 0.99: the linear interpolation of the measure inside a planned piece misses
 * by a few percent, and each rejected point costs a repair (up to six trial pieces); at tol 1
 * this saves about a twentieth of the work for 0.1 % more segments. */
#define FAST_SMALL_TARGET 0.97

/* Walks the break points ts[1..M] (ts[M] = 1; points pts; d2s[k] the squared bound of
 * [ts[k-1], ts[k]] when already known, else negative): certified segments are emitted, rejected
 * ones repaired, the walk resuming at the next point at least half a step ahead. */
static cj_status walk_list(fast_run *fr, const double *ts, const fpt *pts, const double *d2s,
                           size_t M) {
    const fast_ctx *cx = &fr->cx;
    const double tol2 = cx->tol_s * cx->tol_s;
    double a = 0.0, prev = 0.0;
    fpt P = pts[0];
    size_t k = 1;
    while (a < 1.0) {
        const double b = ts[k];
        const double D2 =
            d2s[k] >= 0.0 && a == ts[k - 1] ? d2s[k] : piece_dev2(cx, a, b, &P, &pts[k]);
        if (D2 <= tol2) {
            if (D2 > fr->worst2) fr->worst2 = D2;
            const cj_status st = emit_break(fr, b, &pts[k]);
            if (st) return st;
            a = b;
            P = pts[k];
            prev = b;
            ++k;
            continue;
        }
        const cj_status st = cj_fl_fast_repair(fr, &a, &P, b, &pts[k], D2);
        if (st) return st;
        while (k < M && !(ts[k] - a >= 0.5 * (ts[k] - prev))) {
            prev = ts[k];
            ++k;
        }
    }
    return CJ_OK;
}

/* The plan pl of m (2 <= m <= FAST_SMALL_MAX) segments between the break points first (t = 0)
 * and last (t = 1), measured and placed again as above. */
cj_status cj_fl_fast_run_small(fast_run *fr, fast_plan *pl, const fpt *first, const fpt *last,
                               size_t m) {
    const fast_ctx *cx = &fr->cx;
    double ts[FAST_SMALL_MAX + 1], d2s[FAST_SMALL_MAX + 1], need[FAST_SMALL_MAX + 1];
    fpt pts[FAST_SMALL_MAX + 1];
    ts[0] = 0.0;
    pts[0] = *first;
    size_t M = m;
    for (size_t k = 1; k < m; ++k) {
        const double t = plan_next(pl, k);
        if (t >= 1.0) {
            M = k;
            break;
        }
        ts[k] = t;
        eval_pd(cx->p, cx->dq, cx->n, t, &pts[k]);
    }
    ts[M] = 1.0;
    pts[M] = *last;
    /* need[k]: segments of deviation FAST_SMALL_TARGET tol the pieces up to k ask for */
    const double inv_goal = 1.0 / sqrt(FAST_SMALL_TARGET * cx->tol_s);
    const double tol2 = cx->tol_s * cx->tol_s;
    int all_certified = 1;
    double worst2 = fr->worst2;
    need[0] = 0.0;
    d2s[0] = -1.0;
    for (size_t k = 1; k <= M; ++k) {
        const double D2 = piece_dev2(cx, ts[k - 1], ts[k], &pts[k - 1], &pts[k]);
        d2s[k] = D2;
        all_certified &= D2 <= tol2;
        worst2 = D2 > worst2 ? D2 : worst2;
        need[k] = need[k - 1] + sqrt(sqrt(D2)) * inv_goal;
    }
    const double total = need[M];
    const double m2f = ceil(total);
    if (!(m2f < (double)M) || !(m2f >= 1.0)) { /* no fewer: the planned points */
        if (!all_certified) return walk_list(fr, ts, pts, d2s, M);
        fr->worst2 = worst2;
        for (size_t k = 1; k <= M; ++k) {
            const cj_status st = emit_break(fr, ts[k], &pts[k]);
            if (st) return st;
        }
        return CJ_OK;
    }
    const size_t m2 = (size_t)m2f;
    double ts2[FAST_SMALL_MAX + 1], d2n[FAST_SMALL_MAX + 1];
    fpt pts2[FAST_SMALL_MAX + 1];
    ts2[0] = 0.0;
    pts2[0] = *first;
    d2n[0] = -1.0;
    size_t k = 1, M2 = m2;
    for (size_t i = 1; i < m2; ++i) {
        const double target = total * (double)i / (double)m2;
        while (k < M && need[k] <= target) ++k;
        const double span = need[k] - need[k - 1];
        double t =
            span > 0.0 ? ts[k - 1] + (target - need[k - 1]) / span * (ts[k] - ts[k - 1]) : ts[k];
        if (!(t > ts2[i - 1])) t = ts[k]; /* rounding: keep the parameters increasing */
        if (!(t > ts2[i - 1]) || t >= 1.0) {
            M2 = i;
            break;
        }
        ts2[i] = t;
        d2n[i] = -1.0;
        eval_pd(cx->p, cx->dq, cx->n, t, &pts2[i]);
    }
    ts2[M2] = 1.0;
    pts2[M2] = *last;
    d2n[M2] = -1.0;
    return walk_list(fr, ts2, pts2, d2n, M2);
}
