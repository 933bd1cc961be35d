/* Private: outward-rounded interval arithmetic and the curve contexts shared by the certified
 * queries (intersect.c, nearest.c, query_piece.c).
 *
 * Every interval operation rounds to nearest and then steps each bound at least one ulp outwards
 * (cj_up, cj_down), which encloses the exact result because a rounding to nearest is off by at most
 * half an ulp (also in the subnormal range, where the step is 2^-1074). Nothing here depends on
 * the rounding mode or on the compiler keeping extended precision: the library is built with
 * SSE2 doubles and without -ffast-math. */
#ifndef CASTELJAU_QUERY_INTERNAL_H
#define CASTELJAU_QUERY_INTERNAL_H

#include "casteljau/intersect.h"
#include <math.h>

typedef struct cj_ivl {
    double lo, hi;
} cj_ivl;

/* One step outwards: |x| 2^-52 is at least one ulp of x (2^-1074 covers zero and subnormals),
 * and rounding to nearest is monotone, so x + that is at least the next double above x. */
static inline double cj_up(double x) {
    return x + (fabs(x) * 0x1p-52 + 0x1p-1074);
}
static inline double cj_down(double x) {
    return x - (fabs(x) * 0x1p-52 + 0x1p-1074);
}

/* fmax and fmin with their NaN rule (a NaN argument is ignored), inlined: the libm calls are a
 * visible share of the queries' hot loops. */
static inline double cj_fmax(double a, double b) {
    return (a > b || b != b) ? a : b;
}
static inline double cj_fmin(double a, double b) {
    return (a < b || b != b) ? a : b;
}

static inline cj_ivl cj_iv(double x) {
    cj_ivl r = {x, x};
    return r;
}
static inline cj_ivl cj_iv2(double lo, double hi) {
    cj_ivl r = {lo, hi};
    return r;
}
static inline cj_ivl cj_iadd(cj_ivl a, cj_ivl b) {
    return cj_iv2(cj_down(a.lo + b.lo), cj_up(a.hi + b.hi));
}
static inline cj_ivl cj_isub(cj_ivl a, cj_ivl b) {
    return cj_iv2(cj_down(a.lo - b.hi), cj_up(a.hi - b.lo));
}
static inline cj_ivl cj_ineg(cj_ivl a) {
    return cj_iv2(-a.hi, -a.lo);
}
static inline double cj_min4(double a, double b, double c, double d) {
    double x = a < b ? a : b, y = c < d ? c : d;
    return x < y ? x : y;
}
static inline double cj_max4(double a, double b, double c, double d) {
    double x = a > b ? a : b, y = c > d ? c : d;
    return x > y ? x : y;
}
/* Products and quotients: a NaN among the four candidates (0 times infinity) makes the result
 * the whole line, so that a NaN never narrows an enclosure. */
static inline cj_ivl cj_ihull4(double p0, double p1, double p2, double p3) {
    if (isnan(p0 + p1 + p2 + p3)) return cj_iv2(-INFINITY, INFINITY);
    return cj_iv2(cj_down(cj_min4(p0, p1, p2, p3)), cj_up(cj_max4(p0, p1, p2, p3)));
}
static inline cj_ivl cj_imul(cj_ivl a, cj_ivl b) {
    return cj_ihull4(a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi);
}
/* a * b for a.lo >= 0 (then the bounds come from two products); NaN widens to the line. */
static inline cj_ivl cj_imul_nonneg(cj_ivl a, cj_ivl b) {
    double lo = (b.lo >= 0.0 ? a.lo : a.hi) * b.lo, hi = (b.hi >= 0.0 ? a.hi : a.lo) * b.hi;
    if (isnan(lo + hi)) return cj_iv2(-INFINITY, INFINITY);
    return cj_iv2(cj_down(lo), cj_up(hi));
}
/* Division by an interval that does not contain zero (the caller checks b.lo > 0 or b.hi < 0). */
static inline cj_ivl cj_idiv(cj_ivl a, cj_ivl b) {
    return cj_ihull4(a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi);
}
static inline cj_ivl cj_ihull(cj_ivl a, cj_ivl b) {
    return cj_iv2(cj_fmin(a.lo, b.lo), cj_fmax(a.hi, b.hi));
}
static inline double cj_imid(cj_ivl a) {
    return 0.5 * a.lo + 0.5 * a.hi;
}
static inline double cj_iwidth(cj_ivl a) {
    return a.hi - a.lo;
}
static inline double cj_imag(cj_ivl a) {
    return cj_fmax(fabs(a.lo), fabs(a.hi));
}
static inline int cj_ifinite(cj_ivl a) {
    return isfinite(a.lo) && isfinite(a.hi);
}

/* Largest degree of the queries (stack work space: a few KiB per curve and recursion level). */
#define CJ_QUERY_MAXN CJ_QUERY_MAX_DEGREE

/* A validated plane curve prepared for interval evaluation: homogeneous control points
 * (w x, w y, w) and their first hodograph, as intervals that contain the exact products. */
typedef struct cj_qctx {
    int n;
    int rational;                     /* 0: all weights 1 (then w = 1 and w' = 0 exactly) */
    cj_ivl h[CJ_QUERY_MAXN + 1][3];   /* homogeneous control points */
    cj_ivl dh[CJ_QUERY_MAXN + 1][3];  /* n (h_{i+1} - h_i), i < n */
    cj_ivl ddh[CJ_QUERY_MAXN + 1][3]; /* (n-1) (dh_{i+1} - dh_i), i < n-1 */
    cj_ivl d3h[CJ_QUERY_MAXN + 1][3]; /* (n-2) (ddh_{i+1} - ddh_i), i < n-2 */
    double d2mag[2]; /* a polynomial's max |c''_k| over [0,1] (upper bound), else INFINITY */
    double scale;    /* max |coordinate| of the control points */
    double hmag[3];  /* max |homogeneous coordinate| k (bounds every piece) */
    /* A polynomial curve's plain evaluations (cj_qctx_point, cj_qctx_deriv_near) and its root
     * piece start from these, set once by cj_qctx_init_first (plain = 1, the curve's own exact
     * control points in h; 0 for other contexts): points hm and dm within hrad and drad of
     * the exact control points of c and c', and the largest magnitudes hmax and dmax of hm,
     * dm. */
    int plain;
    double hm[CJ_QUERY_MAXN + 1][2], dm[CJ_QUERY_MAXN + 1][2];
    double hrad, hmax, drad, dmax;
} cj_qctx;

/* Validates the curve (degree 0..CJ_QUERY_MAX_DEGREE, finite points, finite positive weights)
 * naming `what` in the message, and fills the context. */
cj_status cj_qctx_init(cj_qctx *q, const cj_bezier2 *c, const char *what);
/* The same without ddh and d3h (then cj_qctx_eval2 and cj_qctx_eval3 must not be used): what the
 * intersections and nearest points need, at about half the cost. */
cj_status cj_qctx_init_first(cj_qctx *q, const cj_bezier2 *c, const char *what);

/* Encloses the point c(t) and the derivative c'(t) for every t in the interval T (T may extend
 * a little beyond [0,1]); d may be NULL, and so may p (then only d is enclosed). Returns 0 if the
 * weight enclosure reaches zero or a bound overflows (nothing certified then). */
int cj_qctx_eval(const cj_qctx *q, cj_ivl T, cj_ivl p[2], cj_ivl d[2]);

/* Encloses the point c(t) at the double t: the same as cj_qctx_eval on [t, t], by plain de
 * Casteljau with a rounding bound for a polynomial curve and t in [0,1] (several times cheaper
 * than interval arithmetic). */
int cj_qctx_point(const cj_qctx *q, double t, cj_ivl p[2]);

/* Encloses c'(t) for every t in T, for a polynomial curve and a narrow T inside [0,1]: c' at
 * T's midpoint by plain de Casteljau with a rounding bound, widened by max |c''| times T's
 * radius. Returns 0 where it does not apply (then use cj_qctx_eval). */
int cj_qctx_deriv_near(const cj_qctx *q, cj_ivl T, cj_ivl d[2]);

/* Encloses c(t), c'(t) and c''(t) for every t in T. Returns 0 as cj_qctx_eval does. */
int cj_qctx_eval2(const cj_qctx *q, cj_ivl T, cj_ivl p[2], cj_ivl d[2], cj_ivl dd[2]);
/* The same with c'''(t) too. */
int cj_qctx_eval3(const cj_qctx *q, cj_ivl T, cj_ivl p[2], cj_ivl d[2], cj_ivl dd[2], cj_ivl d3[2]);

static inline cj_ivl cj_isqr(cj_ivl a) {
    if (a.lo >= 0) return cj_iv2(cj_down(a.lo * a.lo), cj_up(a.hi * a.hi));
    if (a.hi <= 0) return cj_iv2(cj_down(a.hi * a.hi), cj_up(a.lo * a.lo));
    double m = cj_fmax(-a.lo, a.hi);
    return cj_iv2(0.0, cj_up(m * m));
}
static inline cj_ivl cj_isqrt(cj_ivl a) {
    return cj_iv2(a.lo > 0 ? cj_fmax(0.0, cj_down(sqrt(a.lo))) : 0.0,
                  cj_up(sqrt(cj_fmax(a.hi, 0.0))));
}

/* A piece of a curve on the parameter interval [a, b]: k 2^-d and (k+1) 2^-d from halvings of
 * [0,1]; the callers stop halving at width 2^-52, so every midpoint (2k+1) 2^-(d+1) is exact:
 * homogeneous control points computed by halving, within err[k] (absolute, coordinate k) of the
 * exact ones. */
typedef struct cj_qpiece {
    int n;
    int rational;
    double a, b;
    double perr;           /* the exact parameter ends are within perr of a and b: 0 for pieces
                              made by halving alone (dyadic, exact), > 0 after a clip */
    double err[3];         /* per homogeneous coordinate (the weight's is 0 for a polynomial) */
    double blo[2], bhi[2]; /* enclosure of the whole piece (cj_qpiece_bbox), set on creation */
    double h[CJ_QUERY_MAXN + 1][3];
} cj_qpiece;

void cj_qpiece_root(const cj_qctx *q, cj_qpiece *p);
/* Halves p into left and right (neither may alias p or the other; p is not modified). Only the
 * n+1 points in use are written, so the cost follows the degree, not CJ_QUERY_MAXN. */
void cj_qpiece_halve(const cj_qpiece *p, const double hmag[3], cj_qpiece *left, cj_qpiece *right);
/* The sub-piece of a polynomial piece p over its own parameters [u0, u1] (doubles in [0,1],
 * u0 < u1), or a superset of it: de Casteljau at u0 and then at the rounded-up relative
 * parameter, with the error of both splits tracked; out's a, b and perr enclose the exact
 * parameter interval its control points describe. out may be p. */
void cj_qpiece_sub(const cj_qpiece *p, const double hmag[3], double u0, double u1, cj_qpiece *out);
/* The parameter interval of a piece, widened by its perr (outward rounded; every piece lies
 * within [0,1]). */
static inline cj_ivl cj_qpiece_span(const cj_qpiece *p) {
    if (p->perr == 0.0) return cj_iv2(p->a, p->b);
    double lo = cj_down(p->a - p->perr), hi = cj_up(p->b + p->perr);
    return cj_iv2(lo > 0.0 ? lo : 0.0, hi < 1.0 ? hi : 1.0);
}
/* A context for the straight line p + λ d over λ in [-L, L], as a degree-1 curve whose two
 * control points are enclosed exactly (t in [0,1] maps to λ = L (2 t - 1)). */
void cj_qctx_line(cj_qctx *q, const double p[2], const double d[2], double L);
/* Boxes of the exact projected control points: lo/hi per point and coordinate. */
void cj_qpiece_boxes(const cj_qpiece *p, double lo[][2], double hi[][2]);
/* Enclosure of the whole piece: the box of its control point boxes (cached in blo, bhi). */
void cj_qpiece_bbox(const cj_qpiece *p, double lo[2], double hi[2]);

/* The fast path of cj_nearest_curve for polynomial curves up to this degree (nearest_roots.c):
 * isolates the roots of (c - q) . c' on its Bernstein coefficients. Returns 1 with *out filled
 * and certified (lower <= min distance <= distance, distance - lower <= tol), or 0 when some step
 * could not be proven (a double root, a flat g, a cap), and for any input the caller would
 * refuse (it validates nothing itself): the caller then validates and runs its branch and bound. */
#define CJ_NEAREST_ROOTS_MAXN 12
struct cj_nearest;
int cj_nearest_by_roots(const cj_bezier2 *c, const double qp[2], double tol,
                        struct cj_nearest *out);

/* Max |coordinate| of the control points (finite ones; validation catches the others), the
 * exponent k that brings a scale below 2^-200 up to about 1 (0 otherwise), and a copy of the
 * curve with its points scaled by 2^k into buf (2 (degree+1) doubles; exact for k >= 0). */
double cj_query_scale(const cj_bezier2 *c);
int cj_query_scale_exp(double scale);
cj_bezier2 cj_query_scaled(const cj_bezier2 *c, int k, double *buf);

#endif
