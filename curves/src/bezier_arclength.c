/* Arc length by globally adaptive Gauss–Kronrod 7/15 quadrature of the speed |c'(t)|.
 *
 * The hodograph is formed once; each rule evaluates it by de Casteljau at 15 nodes. The
 * intervals live in a max-heap keyed by their error estimate; while the total estimate exceeds
 * tol, the worst interval is bisected (QUADPACK QAG style). An interval's estimate is
 * |K15 - G7| plus a rounding floor, raised to a rigorous bound where the nodes are too sparse
 * to see a dip of the speed (see gk15); the total is their sum, pessimistic for smooth
 * integrands (K15 is exact for polynomials of degree 22, G7 for degree 13). Cusps, where |c'|
 * has a kink, are handled by the bisection concentrating there.
 *
 * Caps: CJ_ARCLEN_MAX_INTERVALS intervals, or a worst interval too narrow to bisect. Then the
 * value and the estimate reached are written and CJ_ERR_CAP is returned. No allocation: the
 * heap is a fixed array on the stack (64 KiB). */
#include "bezier_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#define CJ_ARCLEN_MAX_INTERVALS 2000
/* Initial uniform pieces for degree n. */
#define CJ_ARCLEN_INITIAL(n) (2 + (n) / 8)

/* Kronrod nodes (positive half, decreasing; the odd ones are the Gauss nodes) and weights. */
static const double xgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
static const double wgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
/* Gauss weights for xgk[1], xgk[3], xgk[5], xgk[7]. */
static const double wg[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

typedef struct speed_fn {
    const double *h;  /* hodograph control points */
    int m, d;         /* its degree and dimension */
    double d2;        /* upper bound of |c''| on [0,1] */
    const double *h2; /* second hodograph control points (degree m-1), NULL if m == 0 */
    double h2_noise;  /* rounding allowance for its control points on a subinterval */
} speed_fn;

/* Upper bound of |c''| on [x0,x1]: the largest control point of the second hodograph
 * restricted to [x0,x1] (convex hull property), plus the rounding of that subdivision. Much
 * tighter than the global bound once intervals are short. */
static double local_d2(const speed_fn *f, double x0, double x1) {
    if (!f->h2) return 0.0;
    double q[CJ_BEZIER_WORK];
    const cj_bezier c2 = cj_bezier_view(f->m - 1, f->d, f->h2);
    if (cj_bezier_subcurve(&c2, x0, x1, q) != CJ_OK) return f->d2;
    double best = 0.0;
    for (int i = 0; i < f->m; ++i) {
        double s = 0.0;
        for (int k = 0; k < f->d; ++k) s += q[i * f->d + k] * q[i * f->d + k];
        best = fmax(best, sqrt(s));
    }
    return fmin(f->d2, best * (1.0 + cj_gamma(f->d + 4)) + f->h2_noise);
}

static double speed(const speed_fn *f, double t) {
    double w[CJ_BEZIER_WORK];
    const int d = f->d;
    memcpy(w, f->h, sizeof(double) * (size_t)(f->m + 1) * (size_t)d);
    const double s = 1.0 - t;
    for (int r = f->m; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    double big = 0.0;
    for (int k = 0; k < d; ++k) big = fmax(big, fabs(w[k]));
    if (big == 0.0) return 0.0;
    double sum = 0.0;
    for (int k = 0; k < d; ++k) sum += (w[k] / big) * (w[k] / big);
    return big * sqrt(sum);
}

typedef struct arc_iv {
    double x0, x1, val, err;
} arc_iv;

/* Max-heap on err over heap[0..count-1]. */
static void sift_down(arc_iv *h, int count, int i) {
    for (;;) {
        int l = 2 * i + 1, r = l + 1, m = i;
        if (l < count && h[l].err > h[m].err) m = l;
        if (r < count && h[r].err > h[m].err) m = r;
        if (m == i) return;
        const arc_iv t = h[i];
        h[i] = h[m];
        h[m] = t;
        i = m;
    }
}

static void sift_up(arc_iv *h, int i) {
    while (i > 0) {
        const int p = (i - 1) / 2;
        if (!(h[i].err > h[p].err)) return;
        const arc_iv t = h[i];
        h[i] = h[p];
        h[p] = t;
        i = p;
    }
}

/* GK15 on [x0,x1]: returns K15 and writes the interval's error estimate to *err.
 *
 * Estimate: |K15 - G7| plus a rounding floor gamma(3m + 2d + 20) |K15| (speed evaluations by
 * de Casteljau on the hodograph and the norm, and the 15-term sum), so that tolerances below
 * what double precision can deliver are reported as a cap, not claimed as met.
 *
 * Resolution guard: K15 and G7 can agree by accident when |c'| has a narrow valley (a near
 * cusp) between the nodes. No point of [x0,x1] is farther than 0.052 (x1-x0) from a node, and
 * |c''| <= D2 (the hull bound of the second hodograph, globally and, if that is not enough,
 * restricted to the interval), so the speed between nodes is at least
 * s_min - 0.052 h D2. Unless 0.25 h D2 <= s_min (the speed cannot dip below ~0.8 s_min unseen),
 * the estimate is raised to the rigorous bound max(K15, max ∫|c'|) <= h (s_max + 0.052 h D2):
 * both the integral and K15 lie in [0, that], so it bounds their difference. Near a true cusp
 * this bound shrinks like h^2 and bisection still converges. */
static double gk15(const speed_fn *f, double x0, double x1, double *err) {
    const double c = 0.5 * (x0 + x1), hw = 0.5 * (x1 - x0), h = x1 - x0;
    const double fc = speed(f, c);
    double k = wgk[7] * fc, g = wg[3] * fc, smin = fc, smax = fc;
    for (int j = 0; j < 7; ++j) {
        const double dx = hw * xgk[j];
        const double s1 = speed(f, c - dx), s2 = speed(f, c + dx);
        const double s = s1 + s2;
        smin = fmin(smin, fmin(s1, s2));
        smax = fmax(smax, fmax(s1, s2));
        k += wgk[j] * s;
        if (j & 1) g += wg[j / 2] * s;
    }
    double e = fabs((k - g) * hw) + cj_gamma(3 * f->m + 2 * f->d + 20) * fabs(k * hw);
    if (!(0.25 * h * f->d2 <= smin)) {
        const double d2 = local_d2(f, x0, x1);
        if (!(0.25 * h * d2 <= smin)) e = fmax(e, h * (smax + 0.052 * h * d2));
    }
    *err = e;
    return k * hw;
}

cj_status cj_bezier_arclength(const cj_bezier *c, double a, double b, double tol, double *length,
                              double *error_estimate) {
    assert(length != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(a, "arc length start a"))) return st;
    if ((st = cj_check_param(b, "arc length end b"))) return st;
    if ((st = cj_check_param(tol, "arc length tolerance"))) return st;
    if (a < 0.0 || a > 1.0)
        return cj_fail(CJ_ERR_RANGE, "arc length start a = %.17g is outside [0,1]", a);
    if (b < 0.0 || b > 1.0)
        return cj_fail(CJ_ERR_RANGE, "arc length end b = %.17g is outside [0,1]", b);
    if (a > b)
        return cj_fail(CJ_ERR_RANGE, "arc length interval is reversed (a = %.17g > b = %.17g)", a,
                       b);
    if (!(tol > 0.0))
        return cj_fail(CJ_ERR_ARGUMENT, "arc length tolerance %.17g is not positive", tol);
    const int n = c->degree, d = c->dim;
    if (n == 0 || a == b) {
        *length = 0.0;
        if (error_estimate) *error_estimate = 0.0;
        return CJ_OK;
    }
    double h[CJ_BEZIER_WORK];
    (void)cj_bezier_hodograph(c, 1, h);
    /* |c''(t)| <= max_i |h2_i| (convex hull property), h2_i = (n-1) (h_{i+1} - h_i). */
    double h2[CJ_BEZIER_WORK];
    double d2 = 0.0, h2max = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        double q = 0.0;
        for (int k = 0; k < d; ++k) {
            const double v = (double)(n - 1) * (h[(i + 1) * d + k] - h[i * d + k]);
            h2[i * d + k] = v;
            q += v * v;
            h2max = fmax(h2max, fabs(v));
        }
        d2 = fmax(d2, sqrt(q));
    }
    d2 *= 1.0 + cj_gamma(d + 4); /* the bound itself is rounded */
    const speed_fn f = {
        h, n - 1, d, d2, n >= 2 ? h2 : NULL, cj_gamma(6 * n + 8) * h2max * sqrt((double)d)};

    arc_iv heap[CJ_ARCLEN_MAX_INTERVALS];
    const double span = b - a;
    /* Start from a uniform partition that grows with the degree: a single 15-point rule over
     * a long, wiggly piece can have K15 and G7 agree by accident (both wrong), which would
     * end the refinement with an optimistic estimate. */
    int count = CJ_ARCLEN_INITIAL(n), capped = 0;
    double total_err = 0.0;
    heap[0].x0 = a; /* (count >= 2; this only tells the compiler heap[0] is set) */
    heap[0].x1 = b;
    for (int i = 0; i < count; ++i) {
        heap[i].x0 = i == 0 ? a : a + span * ((double)i / count);
        heap[i].x1 = i == count - 1 ? b : a + span * ((double)(i + 1) / count);
        heap[i].val = gk15(&f, heap[i].x0, heap[i].x1, &heap[i].err);
        total_err += heap[i].err;
        sift_up(heap, i);
    }
    while (total_err > tol) {
        const arc_iv worst = heap[0];
        const double mid = 0.5 * (worst.x0 + worst.x1);
        if (count >= CJ_ARCLEN_MAX_INTERVALS || !(mid > worst.x0 && mid < worst.x1)) {
            capped = 1;
            break;
        }
        arc_iv l = {worst.x0, mid, 0.0, 0.0}, r = {mid, worst.x1, 0.0, 0.0};
        l.val = gk15(&f, l.x0, l.x1, &l.err);
        r.val = gk15(&f, r.x0, r.x1, &r.err);
        heap[0] = l;
        sift_down(heap, count, 0);
        heap[count] = r;
        sift_up(heap, count);
        ++count;
        /* Re-summed each time (O(count), cheap next to 30 speed evaluations): a running
         * total would drift and could keep the loop going after the goal is met. */
        total_err = 0.0;
        for (int i = 0; i < count; ++i) total_err += heap[i].err;
    }
    /* Final sums recomputed from scratch (the running total only steers the loop). */
    double total = 0.0, comp = 0.0;
    total_err = 0.0;
    for (int i = 0; i < count; ++i) {
        const double y = heap[i].val - comp, s = total + y;
        comp = (s - total) - y;
        total = s;
        total_err += heap[i].err;
    }
    *length = total;
    if (error_estimate) *error_estimate = total_err;
    if (capped && total_err > tol)
        return cj_fail(CJ_ERR_CAP,
                       "arc length: cap of %d intervals hit before tolerance %.3g was met "
                       "(estimate %.3g)",
                       CJ_ARCLEN_MAX_INTERVALS, tol, total_err);
    return CJ_OK;
}
