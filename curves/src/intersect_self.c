/* Self-intersections: pieces proven simple by their derivative directions, the others split
 * and their non-adjacent pairs searched (intersect.h). */
#include "intersect_internal.h"

#include "casteljau/bezier.h"
#include "casteljau/nearest.h"
#include "error_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

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

void cj_isect_self_piece(run *R, const cj_qpiece *p) {
    if (R->capped) return;
    const cj_qpiece *ps[1] = {p};
    if (simple_dirs(ps, 1)) return;
    double e = cj_isect_extent(p);
    if (e <= R->tol || p->b - p->a <= MIN_WIDTH) {
        cj_isect_add_leaf(R, cj_iv2(p->a, p->b), cj_iv2(p->a, p->b), e, 0);
        return;
    }
    cj_qpiece h[2];
    cj_qpiece_halve(p, R->qa->hmag, &h[0], &h[1]);
    cj_isect_self_piece(R, &h[0]);
    cj_isect_self_piece(R, &h[1]);
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
    double el = cj_isect_extent(l), er = cj_isect_extent(r);
    if ((el <= R->tol && er <= R->tol) || l->b - l->a <= MIN_WIDTH || r->b - r->a <= MIN_WIDTH) {
        cj_isect_add_leaf(R, cj_iv2(l->a, l->b), cj_iv2(r->a, r->b), cj_fmax(el, er), 0);
        return;
    }
    cj_qpiece lh[2], rh[2];
    cj_qpiece_halve(l, R->qa->hmag, &lh[0], &lh[1]);
    cj_qpiece_halve(r, R->qa->hmag, &rh[0], &rh[1]);
    self_adjacent(R, &lh[1], &rh[0]);
    cj_isect_pair(R, &lh[0], &rh[0]);
    cj_isect_pair(R, &lh[0], &rh[1]);
    cj_isect_pair(R, &lh[1], &rh[1]);
}
