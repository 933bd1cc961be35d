/* Certified nearest point on a Bézier patch: branch and bound (patch_nearest.h). */
#include "casteljau/patch_nearest.h"
#include "binomial_internal.h"
#include "error_internal.h"
#include "query_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#define MAXP      (CJ_PATCH_NEAREST_MAX_DEGREE + 1)
#define MIN_WIDTH 0x1p-40
#define MAX_LEVEL 96

typedef struct spatch {
    double u0, u1, v0, v1;
    double err[4];
    double h[MAXP * MAXP][4]; /* homogeneous (w x, w y, w z, w), u fastest */
} spatch;

typedef struct prun {
    const cj_patch *p;
    int m, n, rational;
    double q[3], tol, hmag[4];
    cj_ivl H[MAXP * MAXP][4]; /* enclosed homogeneous net of the whole patch */
    double best, bu, bv, lower;
    long pieces;
    spatch *pool; /* two children per level */
} prun;

/* Enclosure of S(u,v) at a point, by interval de Casteljau along u then v. */
static int ieval(const prun *R, double u, double v, cj_ivl out[3]) {
    int m = R->m, n = R->n;
    cj_ivl U = cj_iv(u), V = cj_iv(v), Su = cj_isub(cj_iv(1.0), U), Sv = cj_isub(cj_iv(1.0), V);
    cj_ivl col[MAXP][4], w[MAXP][4];
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= m; ++i)
            for (int k = 0; k < 4; ++k) w[i][k] = R->H[j * (m + 1) + i][k];
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < 4; ++k)
                    w[i][k] = cj_iadd(cj_imul(Su, w[i][k]), cj_imul(U, w[i + 1][k]));
        for (int k = 0; k < 4; ++k) col[j][k] = w[0][k];
    }
    for (int r = n; r > 0; --r)
        for (int j = 0; j < r; ++j)
            for (int k = 0; k < 4; ++k)
                col[j][k] = cj_iadd(cj_imul(Sv, col[j][k]), cj_imul(V, col[j + 1][k]));
    if (!(col[0][3].lo > 0.0)) return 0;
    for (int k = 0; k < 3; ++k) {
        out[k] = R->rational ? cj_idiv(col[0][k], col[0][3]) : col[0][k];
        if (!cj_ifinite(out[k])) return 0;
    }
    return 1;
}

static double upper_at(const prun *R, double u, double v, double pt[3]) {
    cj_ivl s[3];
    if (!ieval(R, u, v, s)) return INFINITY;
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        double e = cj_imag(cj_isub(s[k], cj_iv(R->q[k])));
        d2 = cj_up(d2 + cj_up(e * e));
        if (pt) pt[k] = cj_imid(s[k]);
    }
    return cj_up(sqrt(d2));
}

/* Gauss-Newton on |S - q|^2 from (u,v), clamped to the unit square. */
static void polish(prun *R, double u, double v) {
    for (int it = 0; it < 8; ++it) {
        double d[12]; /* S, S_v, S_u, S_uv: cj_patch_eval_derivs with ku = kv = 1 */
        if (cj_patch_eval_derivs(R->p, u, v, 1, 1, d) != CJ_OK) return;
        /* out[(a*(kv+1) + b)*3 + k]: a = u order, b = v order */
        const double *S = d, *Sv = d + 3, *Su = d + 6;
        double e[3] = {S[0] - R->q[0], S[1] - R->q[1], S[2] - R->q[2]};
        double a = Su[0] * Su[0] + Su[1] * Su[1] + Su[2] * Su[2];
        double b = Su[0] * Sv[0] + Su[1] * Sv[1] + Su[2] * Sv[2];
        double c = Sv[0] * Sv[0] + Sv[1] * Sv[1] + Sv[2] * Sv[2];
        double gu = Su[0] * e[0] + Su[1] * e[1] + Su[2] * e[2];
        double gv = Sv[0] * e[0] + Sv[1] * e[1] + Sv[2] * e[2];
        double det = a * c - b * b;
        if (!(det > 0.0) || !isfinite(det)) return;
        double du = (c * gu - b * gv) / det, dv = (a * gv - b * gu) / det;
        double nu = fmin(1.0, fmax(0.0, u - du)), nv = fmin(1.0, fmax(0.0, v - dv));
        if (!isfinite(nu) || !isfinite(nv) || (nu == u && nv == v)) break;
        u = nu;
        v = nv;
    }
    double ub = upper_at(R, u, v, NULL);
    if (ub < R->best) R->best = ub, R->bu = u, R->bv = v;
}

/* Proven lower bound of the distance from q to the hull of the sub-patch's control points. */
static double piece_lower(const prun *R, const spatch *s) {
    int np = (R->m + 1) * (R->n + 1);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double c[3] = {0, 0, 0};
    static const int corners[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    for (int i = 0; i < np; ++i) {
        cj_ivl W = cj_iv2(cj_down(s->h[i][3] - s->err[3]), cj_up(s->h[i][3] + s->err[3]));
        for (int k = 0; k < 3; ++k) {
            cj_ivl X = cj_iv2(cj_down(s->h[i][k] - s->err[k]), cj_up(s->h[i][k] + s->err[k]));
            cj_ivl x = R->rational ? (W.lo > 0 ? cj_idiv(X, W) : cj_iv2(-INFINITY, INFINITY)) : X;
            lo[k] = fmin(lo[k], x.lo);
            hi[k] = fmax(hi[k], x.hi);
        }
    }
    for (int k = 0; k < 4; ++k) {
        int i = corners[k][0] * R->m, j = corners[k][1] * R->n, idx = j * (R->m + 1) + i;
        for (int d = 0; d < 3; ++d) c[d] += 0.25 * s->h[idx][d] / s->h[idx][3];
    }
    double g2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        double gap = fmax(0.0, fmax(cj_down(lo[k] - R->q[k]), cj_down(R->q[k] - hi[k])));
        g2 = cj_down(g2 + cj_down(gap * gap));
    }
    double box = fmax(0.0, cj_down(sqrt(fmax(0.0, g2))));
    double v[3] = {c[0] - R->q[0], c[1] - R->q[1], c[2] - R->q[2]};
    double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!(vv > 0.0) || !isfinite(vv)) return box;
    double mn = INFINITY;
    for (int i = 0; i < np && mn > 0.0; ++i) {
        cj_ivl W = cj_iv2(cj_down(s->h[i][3] - s->err[3]), cj_up(s->h[i][3] + s->err[3]));
        cj_ivl dot = cj_iv(0.0);
        for (int k = 0; k < 3; ++k) {
            cj_ivl X = cj_iv2(cj_down(s->h[i][k] - s->err[k]), cj_up(s->h[i][k] + s->err[k]));
            cj_ivl x = R->rational ? (W.lo > 0 ? cj_idiv(X, W) : cj_iv2(-INFINITY, INFINITY)) : X;
            dot = cj_iadd(dot, cj_imul(cj_iv(v[k]), cj_isub(x, cj_iv(R->q[k]))));
        }
        mn = fmin(mn, dot.lo);
    }
    if (!(mn > 0.0)) return box;
    double vn = cj_up(sqrt(cj_up(cj_up(v[0] * v[0]) + cj_up(v[1] * v[1]) + cj_up(v[2] * v[2]))));
    return fmax(box, cj_down(mn / vn));
}

/* Proven lower bound of min |S - q| over the sub-patch from the Bernstein form of the squared
 * distance: |S - q|^2 = N / D with N = sum_k (P_k - q_k W)^2 and D = W^2, both of degree
 * (2m, 2n). Their coefficients N_IJ, D_IJ are sums over i + i' = I, j + j' = J of
 * C(m,i) C(m,i') C(n,j) C(n,j') times the products of the net's entries, all divided by the same
 * C(2m,I) C(2n,J), which cancels in N_IJ / D_IJ and is left out. With every D_IJ > 0, N / D is
 * a convex combination of the N_IJ / D_IJ, so it is at least their minimum. Unlike the box of the
 * control points this bound is exact for a patch whose every point is equally far from q (the
 * coefficients of N - r^2 D all vanish): a sphere patch seen from its centre is settled at once
 * instead of being halved until its pieces are flatter than tol. */
static double bern_lower(const prun *R, const spatch *s) {
    int m = R->m, n = R->n, mm = 2 * m + 1, nn = 2 * n + 1;
    const double *bm = cj_binomial_row(m), *bn = cj_binomial_row(n);
    cj_ivl E[MAXP * MAXP][3], W[MAXP * MAXP];
    static const cj_ivl zero = {0.0, 0.0};
    for (int i = 0; i < (m + 1) * (n + 1); ++i) {
        W[i] = cj_iv2(cj_down(s->h[i][3] - s->err[3]), cj_up(s->h[i][3] + s->err[3]));
        for (int k = 0; k < 3; ++k) {
            cj_ivl X = cj_iv2(cj_down(s->h[i][k] - s->err[k]), cj_up(s->h[i][k] + s->err[k]));
            E[i][k] = cj_isub(X, R->rational ? cj_imul(cj_iv(R->q[k]), W[i]) : cj_iv(R->q[k]));
        }
    }
    cj_ivl N[(2 * MAXP - 1) * (2 * MAXP - 1)], D[(2 * MAXP - 1) * (2 * MAXP - 1)];
    for (int i = 0; i < mm * nn; ++i) N[i] = D[i] = zero;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            int a = j * (m + 1) + i;
            for (int j2 = j; j2 <= n; ++j2)
                for (int i2 = j2 == j ? i : 0; i2 <= m; ++i2) {
                    int b = j2 * (m + 1) + i2, I = i + i2, J = j + j2;
                    double c = bm[i] * bm[i2] * bn[j] * bn[j2] * (a == b ? 1.0 : 2.0);
                    cj_ivl e =
                        a == b
                            ? cj_iadd(cj_iadd(cj_isqr(E[a][0]), cj_isqr(E[a][1])), cj_isqr(E[a][2]))
                            : cj_iadd(cj_iadd(cj_imul(E[a][0], E[b][0]), cj_imul(E[a][1], E[b][1])),
                                      cj_imul(E[a][2], E[b][2]));
                    N[J * mm + I] = cj_iadd(N[J * mm + I], cj_imul(cj_iv(c), e));
                    if (R->rational)
                        D[J * mm + I] =
                            cj_iadd(D[J * mm + I], cj_imul(cj_iv(c), cj_imul(W[a], W[b])));
                    else /* exact: integers below 2^53 */
                        D[J * mm + I].lo += c, D[J * mm + I].hi += c;
                }
        }
    double lo2 = INFINITY;
    for (int i = 0; i < mm * nn; ++i) {
        if (!(D[i].lo > 0.0) || !cj_ifinite(N[i]) || !cj_ifinite(D[i])) return 0.0;
        lo2 = fmin(lo2, N[i].lo > 0.0 ? cj_down(N[i].lo / D[i].hi) : 0.0);
    }
    return lo2 > 0.0 ? cj_down(sqrt(lo2)) : 0.0;
}

/* Halves s along u (dir 0) or v (dir 1) into a and b, tracking the rounding as in curves. */
static void halve(const prun *R, const spatch *s, int dir, spatch *a, spatch *b) {
    int m = R->m, n = R->n;
    int len = dir == 0 ? m : n, lines = dir == 0 ? n + 1 : m + 1;
    double w[MAXP][4];
    for (int l = 0; l < lines; ++l) {
        int stride = dir == 0 ? 1 : m + 1, base = dir == 0 ? l * (m + 1) : l;
        for (int i = 0; i <= len; ++i)
            for (int k = 0; k < 4; ++k) w[i][k] = s->h[base + i * stride][k];
        for (int k = 0; k < 4; ++k) {
            a->h[base][k] = w[0][k];
            b->h[base + len * stride][k] = w[len][k];
        }
        for (int r = len; r > 0; --r) {
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < 4; ++k) w[i][k] = 0.5 * (w[i][k] + w[i + 1][k]);
            for (int k = 0; k < 4; ++k) {
                a->h[base + (len - r + 1) * stride][k] = w[0][k];
                b->h[base + (r - 1) * stride][k] = w[r - 1][k];
            }
        }
    }
    for (int k = 0; k < 4; ++k) {
        double e = s->err[k] + (double)len * ((R->hmag[k] + s->err[k]) * 0x1p-53 + 0x1p-1074);
        a->err[k] = b->err[k] = (k == 3 && !R->rational) ? 0.0 : e * (1.0 + 0x1p-40);
    }
    a->u0 = s->u0, a->u1 = s->u1, a->v0 = s->v0, a->v1 = s->v1;
    b->u0 = s->u0, b->u1 = s->u1, b->v0 = s->v0, b->v1 = s->v1;
    if (dir == 0) {
        double mid = 0.5 * (s->u0 + s->u1);
        a->u1 = b->u0 = mid;
    } else {
        double mid = 0.5 * (s->v0 + s->v1);
        a->v1 = b->v0 = mid;
    }
}

static void search(prun *R, const spatch *s, double lb, int level) {
    if (!(lb >= 0.0)) lb = 0.0; /* a NaN bound proves nothing */
    /* the Bernstein bound costs (m+1)^2 (n+1)^2 / 2 interval products: used where the box bound
     * has not pruned after a few levels (nearly equidistant pieces), and at the root */
    if (level % 4 == 0 && lb < R->best - R->tol) lb = fmax(lb, bern_lower(R, s));
    double wu = s->u1 - s->u0, wv = s->v1 - s->v0;
    if (++R->pieces > CJ_PATCH_NEAREST_MAX_PIECES || lb >= R->best - R->tol || level >= MAX_LEVEL ||
        (wu <= MIN_WIDTH && wv <= MIN_WIDTH)) {
        R->lower = fmin(R->lower, lb);
        return;
    }
    double um = 0.5 * (s->u0 + s->u1), vm = 0.5 * (s->v0 + s->v1);
    double ub = upper_at(R, um, vm, NULL);
    if (ub < R->best) {
        R->best = ub, R->bu = um, R->bv = vm;
        polish(R, um, vm);
    }
    if (lb >= R->best - R->tol) {
        R->lower = fmin(R->lower, lb);
        return;
    }
    int dir = (wu >= wv && wu > MIN_WIDTH) || wv <= MIN_WIDTH ? 0 : 1;
    spatch *a = &R->pool[2 * level], *b = &R->pool[2 * level + 1];
    halve(R, s, dir, a, b);
    double la = piece_lower(R, a), lbb = piece_lower(R, b);
    if (la <= lbb) {
        search(R, a, la, level + 1);
        search(R, b, lbb, level + 1);
    } else {
        search(R, b, lbb, level + 1);
        search(R, a, la, level + 1);
    }
}

cj_status cj_patch_nearest(const cj_patch *p, const double q[3], double tol,
                           cj_patch_nearest_result *out) {
    assert(p && q && out);
    cj_status st = cj_patch_check(p);
    if (st != CJ_OK) return st;
    if (p->deg_u > CJ_PATCH_NEAREST_MAX_DEGREE || p->deg_v > CJ_PATCH_NEAREST_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "patch degree (%d, %d) above %d for the nearest point",
                       p->deg_u, p->deg_v, CJ_PATCH_NEAREST_MAX_DEGREE);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(q[k]))
            return cj_fail(CJ_ERR_NONFINITE, "query point coordinate %d is %g", k, q[k]);
    int m = p->deg_u, n = p->deg_v, np = (m + 1) * (n + 1);
    double scale = fmax(fabs(q[0]), fmax(fabs(q[1]), fabs(q[2])));
    int distinct = 0;
    for (int i = 0; i < np; ++i)
        for (int k = 0; k < 3; ++k) {
            scale = fmax(scale, fabs(p->pts[3 * i + k]));
            distinct |= p->pts[3 * i + k] != p->pts[k];
        }
    if (!distinct) return cj_fail(CJ_ERR_DEGENERATE, "patch: all %d control points coincide", np);
    if (!isfinite(tol)) return cj_fail(CJ_ERR_NONFINITE, "tol is %g", tol);
    if (!(tol > 0.0) || tol < scale * 0x1p-36 || scale > 0x1p500 || scale < 0x1p-200)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "tol %g must be > 0 and at least %g (2^-36 times the scale %g of the "
                       "patch and the point, itself within 2^-200..2^500)",
                       tol, scale * 0x1p-36, scale);
    prun *R = malloc(sizeof *R);
    spatch *root = malloc(sizeof *root);
    spatch *pool = malloc(sizeof(spatch) * 2 * MAX_LEVEL);
    if (!R || !root || !pool) {
        free(R), free(root), free(pool);
        return cj_fail(CJ_ERR_NOMEM, "patch nearest point work space");
    }
    memset(R, 0, sizeof *R);
    R->p = p;
    R->m = m;
    R->n = n;
    R->rational = p->weights != NULL;
    memcpy(R->q, q, sizeof R->q);
    R->tol = tol;
    R->best = INFINITY;
    R->lower = INFINITY;
    R->pool = pool;
    for (int i = 0; i < np; ++i) {
        cj_ivl w = cj_iv(p->weights ? p->weights[i] : 1.0);
        for (int k = 0; k < 3; ++k)
            R->H[i][k] =
                p->weights ? cj_imul(cj_iv(p->pts[3 * i + k]), w) : cj_iv(p->pts[3 * i + k]);
        R->H[i][3] = w;
    }
    root->u0 = root->v0 = 0.0;
    root->u1 = root->v1 = 1.0;
    for (int k = 0; k < 4; ++k) {
        double e = 0.0;
        R->hmag[k] = 0.0;
        for (int i = 0; i < np; ++i) {
            double mid = cj_imid(R->H[i][k]);
            root->h[i][k] = mid;
            e = fmax(e, fmax(mid - R->H[i][k].lo, R->H[i][k].hi - mid));
            R->hmag[k] = fmax(R->hmag[k], cj_imag(R->H[i][k]));
        }
        root->err[k] = e > 0 ? cj_up(e) : 0.0;
    }
    /* a first upper bound: a grid of samples, the best polished */
    int g = 2 * (m > n ? m : n) + 2;
    for (int i = 0; i <= g; ++i)
        for (int j = 0; j <= g; ++j) {
            double ub = upper_at(R, (double)i / g, (double)j / g, NULL);
            if (ub < R->best) R->best = ub, R->bu = (double)i / g, R->bv = (double)j / g;
        }
    polish(R, R->bu, R->bv);
    search(R, root, piece_lower(R, root), 0);
    out->u = R->bu;
    out->v = R->bv;
    out->distance = upper_at(R, R->bu, R->bv, out->point);
    out->distance = fmax(out->distance, R->best);
    out->lower = fmin(R->lower, R->best);
    out->pieces = R->pieces;
    st = CJ_OK;
    if (!isfinite(out->distance))
        st = cj_fail(CJ_ERR_RANGE, "the patch's distance to the point overflows");
    else if (R->pieces > CJ_PATCH_NEAREST_MAX_PIECES)
        st = cj_fail(CJ_ERR_CAP,
                     "patch nearest point hit its cap of %ld sub-patches; the bounds "
                     "written are %g apart",
                     CJ_PATCH_NEAREST_MAX_PIECES, out->distance - out->lower);
    free(R), free(root), free(pool);
    return st;
}
