/* Certified curve–curve, curve–line and self-intersections (see intersect.h for the guarantee).
 *
 * The search walks pairs of pieces (parameter boxes S x T). A box is dropped only on proof that
 * it holds no intersection: the control point hulls are separated along an axis (x, y, or the
 * normal of either chord), with every control point enclosed in a box that covers the rounding
 * of subdivision; or Krawczyk's operator K(X) misses X. When K(X+) lies inside the slightly
 * enlarged box X+, the box holds exactly one intersection, which is refined and recorded with
 * X+ as its uniqueness box. Boxes whose pieces shrank below tol without either proof become
 * contact leaves, merged afterwards into connected clusters. */
#include "query_internal.h"

#include "casteljau/bezier.h"
#include "casteljau/nearest.h"
#include "error_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROOTS    512
#define MAX_LEAVES   4096
#define MAX_OVERLAPS 4
#define MIN_WIDTH    0x1p-52
/* Krawczyk is tried once both pieces are this small against their curves */
#define KRAWCZYK_SIZE 0.0625

typedef struct root {
    cj_ivl K[2]; /* enclosure */
    cj_ivl U[2]; /* uniqueness box */
    int at_end;
} root;

typedef struct leaf {
    cj_ivl B[2];
    double size;
    int exact; /* a joint: bitwise equal end points */
} leaf;

typedef struct run {
    const cj_qctx *qa, *qb;
    double tol;
    double ext_a, ext_b; /* extents of the whole curves */
    long max_boxes;
    const cj_bezier2 *ca; /* the first curve, for exact end points */
    int self;             /* qa == qb, s < t */
    int line;             /* qb is a line: no domain clipping on t */
    long boxes;
    int capped;
    root roots[MAX_ROOTS];
    int nroots;
    leaf leaves[MAX_LEAVES];
    int nleaves;
    cj_ivl overlap[MAX_OVERLAPS][2];
    double overlap_dev[MAX_OVERLAPS];
    int noverlaps;
} run;

/* Empties the tables without touching their (large) storage. */
static void run_reset(run *R) {
    R->qa = R->qb = NULL;
    R->tol = R->ext_a = R->ext_b = 0.0;
    R->max_boxes = 0;
    R->ca = NULL;
    R->self = R->line = R->capped = 0;
    R->boxes = 0;
    R->nroots = R->nleaves = R->noverlaps = 0;
}

const char *cj_isect_kind_name(cj_isect_kind kind) {
    switch (kind) {
    case CJ_ISECT_CROSSING:
        return "crossing";
    case CJ_ISECT_CONTACT:
        return "contact";
    case CJ_ISECT_OVERLAP:
        return "overlap";
    }
    return "unknown";
}

/* ---- proofs ----------------------------------------------------------------------------- */

/* min and max of v . x over the boxes of a piece, outward rounded. */
static void project(const double lo[][2], const double hi[][2], int n, const double v[2],
                    double *pmin, double *pmax) {
    double mn = INFINITY, mx = -INFINITY;
    for (int i = 0; i <= n; ++i) {
        /* the smallest and largest of v . x over the box, each product and the sum widened */
        double a0 = v[0] >= 0 ? v[0] * lo[i][0] : v[0] * hi[i][0];
        double a1 = v[1] >= 0 ? v[1] * lo[i][1] : v[1] * hi[i][1];
        double b0 = v[0] >= 0 ? v[0] * hi[i][0] : v[0] * lo[i][0];
        double b1 = v[1] >= 0 ? v[1] * hi[i][1] : v[1] * lo[i][1];
        double l = cj_down(cj_down(a0) + cj_down(a1)), h = cj_up(cj_up(b0) + cj_up(b1));
        if (isnan(l) || isnan(h)) l = -INFINITY, h = INFINITY;
        mn = l < mn ? l : mn;
        mx = h > mx ? h : mx;
    }
    *pmin = mn;
    *pmax = mx;
}

/* 1 if the hulls of the two pieces are proven disjoint. */
static int separated(const cj_qpiece *pa, const cj_qpiece *pb) {
    double alo[CJ_QUERY_MAXN + 1][2], ahi[CJ_QUERY_MAXN + 1][2];
    double blo[CJ_QUERY_MAXN + 1][2], bhi[CJ_QUERY_MAXN + 1][2];
    cj_qpiece_boxes(pa, alo, ahi);
    cj_qpiece_boxes(pb, blo, bhi);
    double axes[4][2] = {{1, 0}, {0, 1}, {0, 0}, {0, 0}};
    int na = pa->n, nb = pb->n;
    axes[2][0] = -(alo[na][1] - alo[0][1]);
    axes[2][1] = alo[na][0] - alo[0][0];
    axes[3][0] = -(blo[nb][1] - blo[0][1]);
    axes[3][1] = blo[nb][0] - blo[0][0];
    for (int k = 0; k < 4; ++k) {
        if (!isfinite(axes[k][0]) || !isfinite(axes[k][1])) continue;
        if (axes[k][0] == 0.0 && axes[k][1] == 0.0) continue;
        double amin, amax, bmin, bmax;
        project((const double(*)[2])alo, (const double(*)[2])ahi, na, axes[k], &amin, &amax);
        project((const double(*)[2])blo, (const double(*)[2])bhi, nb, axes[k], &bmin, &bmax);
        if (amax < bmin || bmax < amin) return 1;
    }
    return 0;
}

/* Krawczyk's operator for F(s,t) = a(s) - b(t) over X: -1 if K misses X (no zero in X), 1 if K
 * lies in the interior of X (exactly one zero in X, and it lies in K), 0 otherwise. */
static int krawczyk(const cj_qctx *qa, const cj_qctx *qb, const cj_ivl X[2], cj_ivl K[2]) {
    double m[2] = {cj_imid(X[0]), cj_imid(X[1])};
    cj_ivl pa[2], pb[2], da[2], db[2], tmp[2];
    if (!cj_qctx_eval(qa, X[0], tmp, da) || !cj_qctx_eval(qb, X[1], tmp, db)) return 0;
    if (!cj_qctx_eval(qa, cj_iv(m[0]), pa, NULL) || !cj_qctx_eval(qb, cj_iv(m[1]), pb, NULL))
        return 0;
    cj_ivl F[2] = {cj_isub(pa[0], pb[0]), cj_isub(pa[1], pb[1])};
    cj_ivl J[2][2] = {{da[0], cj_ineg(db[0])}, {da[1], cj_ineg(db[1])}};
    double Jm[2][2];
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) Jm[r][c] = cj_imid(J[r][c]);
    double det = Jm[0][0] * Jm[1][1] - Jm[0][1] * Jm[1][0];
    if (!(fabs(det) > 0.0) || !isfinite(det)) return 0;
    double Y[2][2] = {{Jm[1][1] / det, -Jm[0][1] / det}, {-Jm[1][0] / det, Jm[0][0] / det}};
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c)
            if (!isfinite(Y[r][c])) return 0;
    for (int r = 0; r < 2; ++r) {
        cj_ivl acc = cj_isub(cj_iv(m[r]),
                             cj_iadd(cj_imul(cj_iv(Y[r][0]), F[0]), cj_imul(cj_iv(Y[r][1]), F[1])));
        for (int c = 0; c < 2; ++c) {
            cj_ivl yj = cj_iadd(cj_imul(cj_iv(Y[r][0]), J[0][c]), cj_imul(cj_iv(Y[r][1]), J[1][c]));
            cj_ivl M = cj_isub(cj_iv(r == c ? 1.0 : 0.0), yj);
            acc = cj_iadd(acc, cj_imul(M, cj_isub(X[c], cj_iv(m[c]))));
        }
        K[r] = acc;
    }
    for (int r = 0; r < 2; ++r) {
        if (!cj_ifinite(K[r])) return 0;
        if (K[r].hi < X[r].lo || K[r].lo > X[r].hi) return -1;
    }
    for (int r = 0; r < 2; ++r)
        if (!(K[r].lo > X[r].lo && K[r].hi < X[r].hi)) return 0;
    return 1;
}

/* Shrinks an enclosure of a zero already proven unique: K <- K(X) ∩ X while it narrows. */
static void refine(const cj_qctx *qa, const cj_qctx *qb, cj_ivl X[2]) {
    for (int it = 0; it < 12; ++it) {
        cj_ivl K[2];
        int r = krawczyk(qa, qb, X, K);
        if (r < 0) return; /* cannot happen for a box holding the zero; keep what we have */
        double before = cj_iwidth(X[0]) + cj_iwidth(X[1]);
        for (int k = 0; k < 2; ++k) {
            X[k].lo = fmax(X[k].lo, K[k].lo);
            X[k].hi = fmin(X[k].hi, K[k].hi);
        }
        if (cj_iwidth(X[0]) + cj_iwidth(X[1]) >= before) return;
    }
}

static int inside(const cj_ivl a[2], const cj_ivl b[2]) {
    return a[0].lo >= b[0].lo && a[0].hi <= b[0].hi && a[1].lo >= b[1].lo && a[1].hi <= b[1].hi;
}

static int meets(const cj_ivl a[2], const cj_ivl b[2]) {
    return a[0].lo <= b[0].hi && b[0].lo <= a[0].hi && a[1].lo <= b[1].hi && b[1].lo <= a[1].hi;
}

/* Records a zero proven unique in U with enclosure K, unless it is outside the domain or the
 * same zero as one recorded before (its enclosure inside the other's uniqueness box). Returns 0
 * if the zero lies outside the domain (so not in the box being examined either). */
static int record(run *R, cj_ivl K[2], const cj_ivl U[2]) {
    int at_end = 0;
    for (int k = 0; k < 2; ++k) {
        if (k == 1 && R->line) continue;
        if (K[k].hi < 0.0 || K[k].lo > 1.0) return 0;
        if (K[k].lo <= 0.0 || K[k].hi >= 1.0) {
            at_end = 1;
            K[k].lo = fmax(K[k].lo, 0.0);
            K[k].hi = fmin(K[k].hi, 1.0);
        }
    }
    if (R->self && K[0].hi >= K[1].lo) { /* must be s < t: the diagonal is no intersection */
        if (K[0].lo >= K[1].hi) return 0;
    }
    for (int i = 0; i < R->nroots; ++i) {
        root *o = &R->roots[i];
        if (inside(K, o->U) || inside(o->K, U)) {
            for (int k = 0; k < 2; ++k) {
                o->K[k].lo = fmax(o->K[k].lo, K[k].lo);
                o->K[k].hi = fmin(o->K[k].hi, K[k].hi);
            }
            o->at_end |= at_end;
            return 1;
        }
    }
    if (R->nroots == MAX_ROOTS) {
        R->capped = 1;
        return 1;
    }
    root *r = &R->roots[R->nroots++];
    r->K[0] = K[0];
    r->K[1] = K[1];
    r->U[0] = U[0];
    r->U[1] = U[1];
    r->at_end = at_end;
    return 1;
}

static void add_leaf(run *R, cj_ivl S, cj_ivl T, double size, int exact) {
    if (R->nleaves == MAX_LEAVES) {
        R->capped = 1;
        return;
    }
    leaf *l = &R->leaves[R->nleaves++];
    l->B[0] = S;
    l->B[1] = T;
    l->size = size;
    l->exact = exact;
}

static double extent(const cj_qpiece *p) {
    double lo[2], hi[2];
    cj_qpiece_bbox(p, lo, hi);
    return fmax(hi[0] - lo[0], hi[1] - lo[1]);
}

/* Tries to settle the box S x T by Krawczyk on the box enlarged by an eighth on each side:
 * -1 no zero in S x T, 1 its one zero recorded, 0 undecided. */
static int settle(run *R, cj_ivl S, cj_ivl T) {
    double ws = cj_iwidth(S) / 8, wt = cj_iwidth(T) / 8;
    cj_ivl U[2] = {cj_iv2(S.lo - ws, S.hi + ws), cj_iv2(T.lo - wt, T.hi + wt)};
    cj_ivl K[2];
    int r = krawczyk(R->qa, R->qb, U, K);
    if (r < 0) return -1;
    if (r == 0) return 0;
    cj_ivl X[2] = {K[0], K[1]};
    refine(R->qa, R->qb, X);
    cj_ivl box[2] = {S, T};
    if (!meets(X, box)) return -1; /* the one zero of U lies outside S x T */
    if (!record(R, X, U)) return -1;
    return 1;
}

static int in_overlap(const run *R, const cj_qpiece *pa, const cj_qpiece *pb) {
    cj_ivl B[2] = {cj_iv2(pa->a, pa->b), cj_iv2(pb->a, pb->b)};
    for (int i = 0; i < R->noverlaps; ++i)
        if (inside(B, R->overlap[i])) return 1;
    return 0;
}

static void pair(run *R, const cj_qpiece *pa, const cj_qpiece *pb) {
    if (R->capped) return;
    if (++R->boxes > R->max_boxes) {
        R->capped = 1;
        return;
    }
    if (in_overlap(R, pa, pb)) return;
    if (separated(pa, pb)) return;
    cj_ivl S = cj_iv2(pa->a, pa->b), T = cj_iv2(pb->a, pb->b);
    double ea = extent(pa), eb = extent(pb);
    /* Krawczyk needs the derivative enclosures to be narrow: try it once the pieces are small
     * against the curves (cheap exclusion does the coarse work). */
    if ((ea <= R->ext_a * KRAWCZYK_SIZE || pa->n <= 1) &&
        (eb <= R->ext_b * KRAWCZYK_SIZE || pb->n <= 1) && settle(R, S, T) != 0)
        return;
    int can_a = ea > R->tol && pa->b - pa->a > MIN_WIDTH;
    int can_b = eb > R->tol && pb->b - pb->a > MIN_WIDTH;
    if (!can_a && !can_b) {
        add_leaf(R, S, T, fmax(ea, eb), 0);
        return;
    }
    cj_qpiece h[2];
    if (can_a && (!can_b || ea >= eb)) {
        cj_qpiece_halve(pa, R->qa->hmag, &h[0], &h[1]);
        pair(R, &h[0], pb);
        pair(R, &h[1], pb);
    } else {
        cj_qpiece_halve(pb, R->qb->hmag, &h[0], &h[1]);
        pair(R, pa, &h[0]);
        pair(R, pa, &h[1]);
    }
}

/* ---- self-intersections ----------------------------------------------------------------- */

/* Vectors whose positive combinations give the derivative direction of the piece: the
 * differences of the control points (polynomial), or ΔP_i W_j - P_j ΔW_i over all i, j
 * (rational: P'W - PW' is Σ B_i^{n-1} B_j^n n (ΔP_i W_j - P_j ΔW_i)). 1 if all lie in one open
 * half-plane, proven with interval dot products against the sum of their midpoints. */
static int simple_dirs(const cj_qpiece *const *ps, int np) {
    double vsum[2] = {0, 0};
    for (int pass = 0; pass < 2; ++pass) {
        for (int q = 0; q < np; ++q) {
            const cj_qpiece *p = ps[q];
            int n = p->n;
            const double *e = p->err;
            for (int i = 0; i < n; ++i) {
                int jmax = p->rational ? n : 0;
                for (int j = 0; j <= jmax; ++j) {
                    cj_ivl v[2];
                    for (int k = 0; k < 2; ++k) {
                        cj_ivl a = cj_iv2(cj_down(p->h[i][k] - e[k]), cj_up(p->h[i][k] + e[k]));
                        cj_ivl b =
                            cj_iv2(cj_down(p->h[i + 1][k] - e[k]), cj_up(p->h[i + 1][k] + e[k]));
                        cj_ivl dP = cj_isub(b, a);
                        if (!p->rational) {
                            v[k] = dP;
                            continue;
                        }
                        cj_ivl wa = cj_iv2(cj_down(p->h[i][2] - e[2]), cj_up(p->h[i][2] + e[2]));
                        cj_ivl wb =
                            cj_iv2(cj_down(p->h[i + 1][2] - e[2]), cj_up(p->h[i + 1][2] + e[2]));
                        cj_ivl Wj = cj_iv2(cj_down(p->h[j][2] - e[2]), cj_up(p->h[j][2] + e[2]));
                        cj_ivl Pj = cj_iv2(cj_down(p->h[j][k] - e[k]), cj_up(p->h[j][k] + e[k]));
                        v[k] = cj_isub(cj_imul(dP, Wj), cj_imul(Pj, cj_isub(wb, wa)));
                    }
                    if (pass == 0) {
                        vsum[0] += cj_imid(v[0]);
                        vsum[1] += cj_imid(v[1]);
                    } else {
                        cj_ivl dot =
                            cj_iadd(cj_imul(cj_iv(vsum[0]), v[0]), cj_imul(cj_iv(vsum[1]), v[1]));
                        if (!(dot.lo > 0.0)) return 0;
                    }
                }
            }
        }
        if (pass == 0 && (!isfinite(vsum[0]) || !isfinite(vsum[1]))) return 0;
    }
    return 1;
}

static void self_adjacent(run *R, const cj_qpiece *l, const cj_qpiece *r);

static void self_piece(run *R, const cj_qpiece *p) {
    if (R->capped) return;
    const cj_qpiece *ps[1] = {p};
    if (simple_dirs(ps, 1)) return;
    double e = extent(p);
    if (e <= R->tol || p->b - p->a <= MIN_WIDTH) {
        add_leaf(R, cj_iv2(p->a, p->b), cj_iv2(p->a, p->b), e, 0);
        return;
    }
    cj_qpiece h[2];
    cj_qpiece_halve(p, R->qa->hmag, &h[0], &h[1]);
    self_piece(R, &h[0]);
    self_piece(R, &h[1]);
    self_adjacent(R, &h[0], &h[1]);
}

/* l = [a, m], r = [m, b]: intersections a(s) = a(t) with s in l, t in r, s != t. */
static void self_adjacent(run *R, const cj_qpiece *l, const cj_qpiece *r) {
    if (R->capped) return;
    if (++R->boxes > R->max_boxes) {
        R->capped = 1;
        return;
    }
    const cj_qpiece *ps[2] = {l, r};
    if (simple_dirs(ps, 2)) return;
    double el = extent(l), er = extent(r);
    if ((el <= R->tol && er <= R->tol) || l->b - l->a <= MIN_WIDTH || r->b - r->a <= MIN_WIDTH) {
        add_leaf(R, cj_iv2(l->a, l->b), cj_iv2(r->a, r->b), fmax(el, er), 0);
        return;
    }
    cj_qpiece lh[2], rh[2];
    cj_qpiece_halve(l, R->qa->hmag, &lh[0], &lh[1]);
    cj_qpiece_halve(r, R->qa->hmag, &rh[0], &rh[1]);
    self_adjacent(R, &lh[1], &rh[0]);
    pair(R, &lh[0], &rh[0]);
    pair(R, &lh[0], &rh[1]);
    pair(R, &lh[1], &rh[1]);
}

/* ---- joints, overlaps, output ------------------------------------------------------------ */

/* End points that are bitwise equal: an exact intersection at the corner (s0, t0). */
static void joints(run *R, const cj_bezier2 *a, const cj_bezier2 *b) {
    for (int ea = 0; ea < 2; ++ea)
        for (int eb = 0; eb < 2; ++eb) {
            if (R->self && (ea == eb || ea > eb)) continue;
            const double *pa = a->pts + 2 * (ea ? a->degree : 0);
            const double *pb = b->pts + 2 * (eb ? b->degree : 0);
            if (pa[0] != pb[0] || pa[1] != pb[1]) continue;
            double s0 = ea, t0 = eb;
            int certified = 0;
            for (double h = 0x1p-12; h >= 0x1p-44 && !certified; h *= 0x1p-8) {
                cj_ivl U[2] = {cj_iv2(s0 - h, s0 + h), cj_iv2(t0 - h, t0 + h)}, K[2];
                if (krawczyk(R->qa, R->qb, U, K) == 1) {
                    cj_ivl X[2] = {cj_iv(s0), cj_iv(t0)};
                    record(R, X, U);
                    certified = 1;
                }
            }
            if (!certified) add_leaf(R, cj_iv(s0), cj_iv(t0), 0.0, 1);
        }
}

/* Polynomial pieces a[s1,s2] and b[t1,t2] as the same curve: max control point distance after
 * elevating both to one degree, plus the rounding of the two subdivisions. */
static double coincidence(const cj_bezier2 *a, double s1, double s2, const cj_bezier2 *b, double t1,
                          double t2) {
    enum { M = CJ_QUERY_MAX_DEGREE + 1 };
    double pa[2 * M], pb[2 * M], ea[2 * M], eb[2 * M];
    cj_bezier A = cj_bezier_view(a->degree, 2, a->pts), B = cj_bezier_view(b->degree, 2, b->pts);
    if (s1 == s2 || t1 == t2) return INFINITY;
    if (cj_bezier_subcurve(&A, s1, s2, pa) != CJ_OK) return INFINITY;
    if (cj_bezier_subcurve(&B, t1, t2, pb) != CJ_OK) return INFINITY;
    int n = a->degree > b->degree ? a->degree : b->degree;
    cj_bezier SA = cj_bezier_view(a->degree, 2, pa), SB = cj_bezier_view(b->degree, 2, pb);
    if (cj_bezier_elevate(&SA, n - a->degree, ea) != CJ_OK) return INFINITY;
    if (cj_bezier_elevate(&SB, n - b->degree, eb) != CJ_OK) return INFINITY;
    double dev = 0.0, scale = 0.0;
    for (int i = 0; i <= n; ++i) {
        dev = fmax(dev, hypot(ea[2 * i] - eb[2 * i], ea[2 * i + 1] - eb[2 * i + 1]));
        scale = fmax(scale, fmax(fabs(ea[2 * i]), fabs(ea[2 * i + 1])));
    }
    return dev + 16.0 * (n + 2) * 0x1p-53 * scale;
}

static void overlaps(run *R, const cj_bezier2 *a, const cj_bezier2 *b) {
    if (a->weights || b->weights || R->self || R->line) return;
    double cand[4][2];
    int nc = 0;
    for (int e = 0; e < 2; ++e) {
        cj_nearest nb, na;
        const double *pa = a->pts + 2 * (e ? a->degree : 0);
        const double *pb = b->pts + 2 * (e ? b->degree : 0);
        if (cj_nearest_curve(b, pa, R->tol, &nb) == CJ_OK && nb.distance <= R->tol) {
            cand[nc][0] = e;
            cand[nc++][1] = nb.t;
        }
        if (cj_nearest_curve(a, pb, R->tol, &na) == CJ_OK && na.distance <= R->tol) {
            cand[nc][0] = na.t;
            cand[nc++][1] = e;
        }
    }
    for (int i = 0; i < nc; ++i)
        for (int j = 0; j < nc; ++j) {
            double s1 = cand[i][0], s2 = cand[j][0], t1 = cand[i][1], t2 = cand[j][1];
            if (!(s1 < s2) || t1 == t2) continue;
            double dev = coincidence(a, s1, s2, b, t1, t2);
            if (!(dev <= R->tol)) continue;
            cj_ivl box[2] = {cj_iv2(s1, s2), cj_iv2(fmin(t1, t2), fmax(t1, t2))};
            int dup = 0;
            for (int k = 0; k < R->noverlaps; ++k) {
                if (inside(box, R->overlap[k]))
                    dup = 1;
                else if (inside(R->overlap[k], box)) {
                    R->overlap[k][0] = box[0];
                    R->overlap[k][1] = box[1];
                    R->overlap_dev[k] = dev;
                    dup = 1;
                }
            }
            if (!dup && R->noverlaps < MAX_OVERLAPS) {
                R->overlap[R->noverlaps][0] = box[0];
                R->overlap[R->noverlaps][1] = box[1];
                R->overlap_dev[R->noverlaps++] = dev;
            }
        }
}

static int cmp_isect(const void *x, const void *y) {
    const cj_isect *a = x, *b = y;
    if (a->s != b->s) return a->s < b->s ? -1 : 1;
    if (a->t != b->t) return a->t < b->t ? -1 : 1;
    return 0;
}

/* Merges touching leaves into clusters (in place), drops those inside a crossing's uniqueness
 * box or meeting an overlap, and writes every result. */
static cj_status finish(run *R, double line_scale, cj_isect *out, int cap, int *count) {
    /* connected components of touching leaf boxes: repeated pairwise merging */
    int n = R->nleaves;
    for (int changed = 1; changed;) {
        changed = 0;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (meets(R->leaves[i].B, R->leaves[j].B)) {
                    for (int k = 0; k < 2; ++k)
                        R->leaves[i].B[k] = cj_ihull(R->leaves[i].B[k], R->leaves[j].B[k]);
                    R->leaves[i].size = fmax(R->leaves[i].size, R->leaves[j].size);
                    R->leaves[i].exact |= R->leaves[j].exact;
                    R->leaves[j] = R->leaves[--n];
                    changed = 1;
                    --j;
                }
    }
    R->nleaves = n;
    cj_isect *tmp = malloc(sizeof(cj_isect) * (MAX_ROOTS + MAX_LEAVES + MAX_OVERLAPS));
    if (!tmp) return cj_fail(CJ_ERR_NOMEM, "intersection results");
    int total = 0;
    for (int i = 0; i < R->noverlaps; ++i) {
        cj_isect *o = &tmp[total++];
        memset(o, 0, sizeof *o);
        o->kind = CJ_ISECT_OVERLAP;
        o->s_lo = R->overlap[i][0].lo;
        o->s_hi = R->overlap[i][0].hi;
        o->t_lo = R->overlap[i][1].lo;
        o->t_hi = R->overlap[i][1].hi;
        o->deviation = R->overlap_dev[i];
        o->at_end = 1;
    }
    for (int i = 0; i < R->nroots; ++i) {
        root *r = &R->roots[i];
        int absorbed = 0;
        for (int k = 0; k < R->noverlaps; ++k) absorbed |= meets(r->K, R->overlap[k]);
        if (absorbed) continue;
        cj_isect *o = &tmp[total++];
        memset(o, 0, sizeof *o);
        o->kind = CJ_ISECT_CROSSING;
        o->s_lo = r->K[0].lo;
        o->s_hi = r->K[0].hi;
        o->t_lo = r->K[1].lo;
        o->t_hi = r->K[1].hi;
        o->at_end = r->at_end;
    }
    for (int i = 0; i < R->nleaves; ++i) {
        leaf *l = &R->leaves[i];
        int absorbed = 0;
        for (int k = 0; k < R->noverlaps; ++k) absorbed |= meets(l->B, R->overlap[k]);
        for (int k = 0; k < R->nroots && !l->exact; ++k) absorbed |= inside(l->B, R->roots[k].U);
        if (absorbed) continue;
        cj_isect *o = &tmp[total++];
        memset(o, 0, sizeof *o);
        o->kind = CJ_ISECT_CONTACT;
        o->s_lo = l->B[0].lo;
        o->s_hi = l->B[0].hi;
        o->t_lo = l->B[1].lo;
        o->t_hi = l->B[1].hi;
        o->deviation = 2.8284271247461903 * l->size;
        o->at_end = l->B[0].lo <= 0.0 || l->B[0].hi >= 1.0 ||
                    (!R->line && (l->B[1].lo <= 0.0 || l->B[1].hi >= 1.0));
    }
    for (int i = 0; i < total; ++i) {
        cj_isect *o = &tmp[i];
        o->s = 0.5 * o->s_lo + 0.5 * o->s_hi;
        o->t = 0.5 * o->t_lo + 0.5 * o->t_hi;
        cj_ivl p[2];
        if (R->ca && o->s_lo == o->s_hi && (o->s == 0.0 || o->s == 1.0)) { /* an exact end */
            const double *e = R->ca->pts + (o->s == 0.0 ? 0 : 2 * R->ca->degree);
            o->point[0] = e[0];
            o->point[1] = e[1];
        } else if (cj_qctx_eval(R->qa, cj_iv(o->s), p, NULL)) {
            o->point[0] = cj_imid(p[0]);
            o->point[1] = cj_imid(p[1]);
        }
        if (R->line) { /* t in [0,1] on the enclosing segment -> λ = L (2t - 1), outward */
            cj_ivl L = cj_iv(line_scale);
            cj_ivl lo = cj_imul(L, cj_isub(cj_imul(cj_iv(2.0), cj_iv(o->t_lo)), cj_iv(1.0)));
            cj_ivl hi = cj_imul(L, cj_isub(cj_imul(cj_iv(2.0), cj_iv(o->t_hi)), cj_iv(1.0)));
            o->t_lo = lo.lo;
            o->t_hi = hi.hi;
            o->t = line_scale * (2.0 * o->t - 1.0);
            o->t = fmin(fmax(o->t, o->t_lo), o->t_hi);
        }
    }
    qsort(tmp, (size_t)total, sizeof tmp[0], cmp_isect);
    *count = total;
    for (int i = 0; i < total && i < cap; ++i) out[i] = tmp[i];
    free(tmp);
    if (R->capped)
        return cj_fail(CJ_ERR_CAP,
                       "intersection search hit its cap (%ld boxes, %d leaves): the "
                       "curves may overlap with different parametrisations; %d results are "
                       "partial",
                       R->boxes, R->nleaves, total);
    if (total > cap)
        return cj_fail(CJ_ERR_BUFFER, "%d intersections found, room for %d", total, cap);
    return CJ_OK;
}

static cj_status check_tol(double tol, double scale) {
    if (!isfinite(tol)) return cj_fail(CJ_ERR_NONFINITE, "tol is %s", isnan(tol) ? "NaN" : "inf");
    if (!(tol > 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "tol %g must be > 0", tol);
    if (tol < scale * 0x1p-40)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "tol %g is below what doubles resolve at the curves' scale %g (the "
                       "smallest is %g = 2^-40 times the scale)",
                       tol, scale, scale * 0x1p-40);
    return CJ_OK;
}

static cj_status curves_impl(const cj_bezier2 *a, const cj_bezier2 *b, double tol, cj_isect *out,
                             int cap, int *count) {
    assert(a && b && count && (out || cap == 0));
    run *R = malloc(sizeof *R); /* the bookkeeping tables (~250 KiB) do not belong on a stack */
    cj_qctx *qa = malloc(sizeof *qa), *qb = malloc(sizeof *qb);
    cj_status st = CJ_OK;
    if (!R || !qa || !qb) {
        st = cj_fail(CJ_ERR_NOMEM, "intersection work space");
        goto done;
    }
    if ((st = cj_qctx_init(qa, a, "curve a")) != CJ_OK) goto done;
    if ((st = cj_qctx_init(qb, b, "curve b")) != CJ_OK) goto done;
    if ((st = check_tol(tol, fmax(qa->scale, qb->scale))) != CJ_OK) goto done;
    /* Overlaps are looked for only when a first search, capped low, leaves something
     * unresolved: coincident pieces can neither be excluded nor certified, so they always do. */
    for (int pass = 0; pass < 2; ++pass) {
        run_reset(R);
        R->qa = qa;
        R->qb = qb;
        R->tol = tol;
        R->max_boxes = pass == 0 ? 20000 : CJ_ISECT_MAX_BOXES;
        R->ca = a;
        joints(R, a, b);
        if (pass == 1) overlaps(R, a, b);
        cj_qpiece pa, pb;
        cj_qpiece_root(qa, &pa);
        cj_qpiece_root(qb, &pb);
        R->ext_a = extent(&pa);
        R->ext_b = extent(&pb);
        pair(R, &pa, &pb);
        if (!R->capped && R->nleaves == 0) break;
    }
    st = finish(R, 0.0, out, cap, count);
done:
    free(R);
    free(qa);
    free(qb);
    return st;
}

static cj_status self_impl(const cj_bezier2 *a, double tol, cj_isect *out, int cap, int *count) {
    assert(a && count && (out || cap == 0));
    run *R = malloc(sizeof *R);
    cj_qctx *qa = malloc(sizeof *qa);
    cj_status st = CJ_OK;
    if (!R || !qa) {
        st = cj_fail(CJ_ERR_NOMEM, "intersection work space");
        goto done;
    }
    if ((st = cj_qctx_init(qa, a, "curve")) != CJ_OK) goto done;
    if ((st = check_tol(tol, qa->scale)) != CJ_OK) goto done;
    run_reset(R);
    R->qa = R->qb = qa;
    R->tol = tol;
    R->self = 1;
    R->max_boxes = CJ_ISECT_MAX_BOXES;
    R->ca = a;
    joints(R, a, a);
    {
        cj_qpiece p;
        cj_qpiece_root(qa, &p);
        R->ext_a = R->ext_b = extent(&p);
        self_piece(R, &p);
    }
    st = finish(R, 0.0, out, cap, count);
done:
    free(R);
    free(qa);
    return st;
}

static cj_status line_impl(const cj_bezier2 *a, const double p[2], const double d[2], double tol,
                           cj_isect *out, int cap, int *count) {
    assert(a && p && d && count && (out || cap == 0));
    if (!isfinite(p[0]) || !isfinite(p[1]))
        return cj_fail(CJ_ERR_NONFINITE, "line point (%g, %g) is not finite", p[0], p[1]);
    if (!isfinite(d[0]) || !isfinite(d[1]))
        return cj_fail(CJ_ERR_NONFINITE, "line direction (%g, %g) is not finite", d[0], d[1]);
    if (d[0] == 0.0 && d[1] == 0.0) return cj_fail(CJ_ERR_DEGENERATE, "line direction is (0, 0)");
    run *R = malloc(sizeof *R);
    cj_qctx *qa = malloc(sizeof *qa), *qb = malloc(sizeof *qb);
    cj_status st = CJ_OK;
    if (!R || !qa || !qb) {
        st = cj_fail(CJ_ERR_NOMEM, "intersection work space");
        goto done;
    }
    if ((st = cj_qctx_init(qa, a, "curve")) != CJ_OK) goto done;
    if ((st = check_tol(tol, qa->scale)) != CJ_OK) goto done;
    {
        /* λ span: the control points project within |c_i - p| / |d| of λ = 0; a power of two
         * at least twice that keeps L exact and the curve strictly inside the segment. */
        double reach = 0.0, dn = fmax(fabs(d[0]), fabs(d[1]));
        for (int i = 0; i <= a->degree; ++i)
            reach = fmax(reach, fabs(a->pts[2 * i] - p[0]) + fabs(a->pts[2 * i + 1] - p[1]));
        double L = ldexp(1.0, ilogb(fmax(reach / dn, 0x1p-1000)) + 2);
        if (!isfinite(L) || !isfinite(L * dn)) {
            st = cj_fail(CJ_ERR_RANGE, "line point and direction are out of scale with the curve");
            goto done;
        }
        cj_qctx_line(qb, p, d, L);
        run_reset(R);
        R->qa = qa;
        R->qb = qb;
        R->tol = tol;
        R->line = 1;
        R->max_boxes = CJ_ISECT_MAX_BOXES;
        cj_qpiece pa, pb;
        cj_qpiece_root(qa, &pa);
        cj_qpiece_root(qb, &pb);
        R->ext_a = extent(&pa);
        R->ext_b = extent(&pb);
        pair(R, &pa, &pb);
        st = finish(R, L, out, cap, count);
    }
done:
    free(R);
    free(qa);
    free(qb);
    return st;
}

/* ---- tiny scales -------------------------------------------------------------------------- */

/* Curves far below 1 in size are scaled up by a power of two (exact) before the search, so that
 * the squares and inverses in the proofs stay in the normal range; parameters are unchanged,
 * points and distances are scaled back. */
static void unscale(cj_isect *out, int n, int k, int line) {
    for (int i = 0; i < n; ++i) {
        out[i].point[0] = ldexp(out[i].point[0], -k);
        out[i].point[1] = ldexp(out[i].point[1], -k);
        out[i].deviation = ldexp(out[i].deviation, -k);
        if (line) {
            out[i].t = ldexp(out[i].t, -k);
            out[i].t_lo = ldexp(out[i].t_lo, -k);
            out[i].t_hi = ldexp(out[i].t_hi, -k);
        }
    }
}

cj_status cj_intersect_curves(const cj_bezier2 *a, const cj_bezier2 *b, double tol, cj_isect *out,
                              int cap, int *count) {
    assert(a && b && count && (out || cap == 0));
    int k = cj_query_scale_exp(fmax(cj_query_scale(a), cj_query_scale(b)));
    if (k == 0) return curves_impl(a, b, tol, out, cap, count);
    double pa[2 * (CJ_QUERY_MAX_DEGREE + 1)], pb[2 * (CJ_QUERY_MAX_DEGREE + 1)];
    cj_bezier2 A = cj_query_scaled(a, k, pa), B = cj_query_scaled(b, k, pb);
    cj_status st = curves_impl(&A, &B, ldexp(tol, k), out, cap, count);
    unscale(out, *count < cap ? *count : cap, k, 0);
    return st;
}

cj_status cj_intersect_self(const cj_bezier2 *a, double tol, cj_isect *out, int cap, int *count) {
    assert(a && count && (out || cap == 0));
    int k = cj_query_scale_exp(cj_query_scale(a));
    if (k == 0) return self_impl(a, tol, out, cap, count);
    double pa[2 * (CJ_QUERY_MAX_DEGREE + 1)];
    cj_bezier2 A = cj_query_scaled(a, k, pa);
    cj_status st = self_impl(&A, ldexp(tol, k), out, cap, count);
    unscale(out, *count < cap ? *count : cap, k, 0);
    return st;
}

cj_status cj_intersect_line(const cj_bezier2 *a, const double p[2], const double d[2], double tol,
                            cj_isect *out, int cap, int *count) {
    assert(a && p && d && count && (out || cap == 0));
    double sc = fmax(cj_query_scale(a), fmax(fabs(p[0]), fabs(p[1])));
    int k = cj_query_scale_exp(sc);
    if (k == 0) return line_impl(a, p, d, tol, out, cap, count);
    double pa[2 * (CJ_QUERY_MAX_DEGREE + 1)], ps[2] = {ldexp(p[0], k), ldexp(p[1], k)};
    cj_bezier2 A = cj_query_scaled(a, k, pa);
    cj_status st = line_impl(&A, ps, d, ldexp(tol, k), out, cap, count);
    unscale(out, *count < cap ? *count : cap, k, 1);
    return st;
}
