/* Differential geometry at a parameter: unit tangent, unit normal, curvature, with the
 * zero-speed rule (first non-vanishing derivative).
 *
 * Work is done on the difference polynomials D_j(t) = Σ Δ^j b_i B_i^{n-j}(t), so that
 * c^(j)(t) = n!/(n-j)! D_j(t) without ever forming the factorial (which overflows for large n).
 *
 * "Vanishing": D_j(t) counts as zero when ||D_j(t)||_inf <= tau_j = 8 n u 2^j S, where
 * S = max |b_i,k| over all control points and u = 2^-53. Forming Δ^j costs at most about
 * j 2^j S u of rounding and the de Casteljau evaluation gamma(3(n-j)) 2^j S, so tau_j is a
 * small multiple of the noise floor of D_j: below it the computed direction is rounding noise.
 * The test scales with the curve (uniform scaling leaves it invariant). */
#include "bezier_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

typedef struct frame_ctx {
    int n, d;
    double scale;                /* S */
    double diff[CJ_BEZIER_WORK]; /* Δ^j b, n-j+1 points; j = `order` */
    int order;
} frame_ctx;

static void ctx_init(frame_ctx *f, const cj_bezier *c) {
    f->n = c->degree;
    f->d = c->dim;
    const size_t count = (size_t)(f->n + 1) * (size_t)f->d;
    memcpy(f->diff, c->pts, sizeof(double) * count);
    double s = 0.0;
    for (size_t i = 0; i < count; ++i) s = fmax(s, fabs(c->pts[i]));
    f->scale = s;
    f->order = 0;
}

/* Advances to the next order and evaluates D_order(t) into v; returns 0 past order n. */
static int ctx_next(frame_ctx *f, double t, double *v) {
    if (f->order >= f->n) return 0;
    const int m = f->n - f->order; /* points before differencing: m+1 */
    for (int i = 0; i < m * f->d; ++i) f->diff[i] = f->diff[i + f->d] - f->diff[i];
    f->order++;
    double w[CJ_BEZIER_WORK];
    const int deg = f->n - f->order;
    memcpy(w, f->diff, sizeof(double) * (size_t)(deg + 1) * (size_t)f->d);
    const double s = 1.0 - t;
    for (int r = deg; r > 0; --r)
        for (int i = 0; i < r * f->d; ++i) w[i] = s * w[i] + t * w[i + f->d];
    memcpy(v, w, sizeof(double) * (size_t)f->d);
    return 1;
}

static double tau(const frame_ctx *f, int j) {
    return 8.0 * (double)f->n * CJ_UNIT_ROUNDOFF * ldexp(f->scale, j);
}

static double norm_inf(const double *v, int d) {
    double m = 0.0;
    for (int k = 0; k < d; ++k) m = fmax(m, fabs(v[k]));
    return m;
}

static double norm2(const double *v, int d) {
    double big = norm_inf(v, d);
    if (big == 0.0) return 0.0;
    double s = 0.0;
    for (int k = 0; k < d; ++k) s += (v[k] / big) * (v[k] / big);
    return big * sqrt(s);
}

/* First non-vanishing D_j(t): writes it to v and returns j, or 0 if all vanish. */
static int first_nonvanishing(frame_ctx *f, double t, double *v) {
    while (ctx_next(f, t, v))
        if (norm_inf(v, f->d) > tau(f, f->order)) return f->order;
    return 0;
}

/* After the tangent order j: the next D_m(t) whose component orthogonal to the unit tangent
 * `tan` does not vanish. Writes that component (unnormalised) to perp, D_m to raw; returns m or
 * 0 (a straight piece). */
static int next_transverse(frame_ctx *f, double t, const double *tan, double *perp, double *raw) {
    while (ctx_next(f, t, raw)) {
        double dot = 0.0;
        for (int k = 0; k < f->d; ++k) dot += raw[k] * tan[k];
        for (int k = 0; k < f->d; ++k) perp[k] = raw[k] - dot * tan[k];
        if (norm_inf(perp, f->d) > tau(f, f->order)) return f->order;
    }
    return 0;
}

static cj_status check_frame_input(const cj_bezier *c, double t) {
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    return cj_check_param(t, "parameter t");
}

/* Shared by tangent/normal/curvature: validated input, unit tangent into tan, its order. */
static cj_status unit_tangent(frame_ctx *f, const cj_bezier *c, double t, double *tan, int *j) {
    ctx_init(f, c);
    double v[CJ_MAX_DIM];
    *j = first_nonvanishing(f, t, v);
    if (*j == 0)
        return cj_fail(CJ_ERR_DEGENERATE,
                       "curve is a single point at t = %.17g: every derivative vanishes", t);
    const double len = norm2(v, f->d);
    for (int k = 0; k < f->d; ++k) tan[k] = v[k] / len;
    return CJ_OK;
}

cj_status cj_bezier_tangent(const cj_bezier *c, double t, double *tangent, int *order) {
    assert(tangent != NULL);
    cj_status st = check_frame_input(c, t);
    if (st) return st;
    frame_ctx f;
    double tan[CJ_MAX_DIM];
    int j;
    if ((st = unit_tangent(&f, c, t, tan, &j))) return st;
    memcpy(tangent, tan, sizeof(double) * (size_t)c->dim);
    if (order) *order = j;
    return CJ_OK;
}

cj_status cj_bezier_normal(const cj_bezier *c, double t, double *normal) {
    assert(normal != NULL);
    cj_status st = check_frame_input(c, t);
    if (st) return st;
    if (c->dim != 2 && c->dim != 3)
        return cj_fail(CJ_ERR_DIMENSION, "normal needs a 2D or 3D curve, got dimension %d", c->dim);
    frame_ctx f;
    double tan[CJ_MAX_DIM];
    int j;
    if ((st = unit_tangent(&f, c, t, tan, &j))) return st;
    if (c->dim == 2) {
        normal[0] = -tan[1];
        normal[1] = tan[0];
        return CJ_OK;
    }
    double perp[CJ_MAX_DIM], raw[CJ_MAX_DIM];
    if (!next_transverse(&f, t, tan, perp, raw))
        return cj_fail(CJ_ERR_DEGENERATE, "3D curve is straight at t = %.17g: no principal normal",
                       t);
    const double len = norm2(perp, 3);
    for (int k = 0; k < 3; ++k) normal[k] = perp[k] / len;
    return CJ_OK;
}

/* With A = c^(j)(t) (first non-vanishing) and B = c^(m)(t) (first one not parallel to A), the
 * curvature as s -> t+ behaves like |A x B| (m-j) ((j-1)!)^2 / ((m-1)! |A|^3) h^(m-2j): finite
 * and non-zero iff m = 2j, zero if m > 2j (or no such m), infinite if m < 2j. In terms of the
 * difference polynomials (A = F_j D_j, F_j = n!/(n-j)!), for m = 2j:
 *     kappa = |D_j x D_m| / |D_j|^3 * Π_{q<j} (n-j-q)/(n-q) / C(2j-1, j-1). */
cj_status cj_bezier_curvature(const cj_bezier *c, double t, double *kappa) {
    assert(kappa != NULL);
    cj_status st = check_frame_input(c, t);
    if (st) return st;
    if (c->dim != 2 && c->dim != 3)
        return cj_fail(CJ_ERR_DIMENSION, "curvature needs a 2D or 3D curve, got dimension %d",
                       c->dim);
    frame_ctx f;
    ctx_init(&f, c);
    double a[CJ_MAX_DIM], tan[CJ_MAX_DIM], perp[CJ_MAX_DIM], b[CJ_MAX_DIM];
    const int j = first_nonvanishing(&f, t, a);
    if (j == 0)
        return cj_fail(CJ_ERR_DEGENERATE,
                       "curve is a single point at t = %.17g: curvature undefined", t);
    const double alen = norm2(a, f.d);
    for (int k = 0; k < f.d; ++k) tan[k] = a[k] / alen;
    const int m = next_transverse(&f, t, tan, perp, b);
    if (m == 0 || m > 2 * j) {
        *kappa = 0.0;
        return CJ_OK;
    }
    if (m < 2 * j)
        return cj_fail(CJ_ERR_DEGENERATE,
                       "curvature is unbounded at the cusp t = %.17g (derivative orders %d, %d)", t,
                       j, m);
    /* |a x b| / |a|^3 = |u x (b/|a|)| / |a| with u = a/|a|: no overflow at extreme scales. */
    for (int k = 0; k < f.d; ++k) {
        a[k] = tan[k];
        b[k] /= alen;
    }
    double cross;
    if (f.d == 2) {
        cross = a[0] * b[1] - a[1] * b[0];
    } else {
        const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
                     cz = a[0] * b[1] - a[1] * b[0];
        const double v[3] = {cx, cy, cz};
        cross = norm2(v, 3);
    }
    double factor = 1.0, binom = 1.0; /* binom = C(2j-1, j-1) built as Π (j+q)/(q+1) */
    for (int q = 0; q < j; ++q) factor *= (double)(f.n - j - q) / (double)(f.n - q);
    for (int q = 0; q < j - 1; ++q) binom = binom * (double)(j + 1 + q) / (double)(q + 1);
    const double kap = cross / alen * factor / binom;
    if (!isfinite(kap))
        return cj_fail(CJ_ERR_DEGENERATE, "curvature at t = %.17g overflows (%g)", t, kap);
    *kappa = kap;
    return CJ_OK;
}
