/* Exact joints, overlaps of coincident pieces, and the merged, sorted output of the
 * intersection search. */
#include "intersect_internal.h"

#include "casteljau/bezier.h"
#include "casteljau/nearest.h"
#include "error_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* ---- joints, overlaps, output ------------------------------------------------------------ */

/* End points that are bitwise equal: an exact intersection at the corner (s0, t0). */
void cj_isect_joints(run *R, const cj_bezier2 *a, const cj_bezier2 *b) {
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
                if (cj_isect_krawczyk(R->qa, R->qb, U, K) == 1) {
                    cj_ivl X[2] = {cj_iv(s0), cj_iv(t0)};
                    cj_isect_record(R, X, U);
                    certified = 1;
                }
            }
            if (!certified) cj_isect_add_leaf(R, cj_iv(s0), cj_iv(t0), 0.0, 1);
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
        dev = cj_fmax(dev, hypot(ea[2 * i] - eb[2 * i], ea[2 * i + 1] - eb[2 * i + 1]));
        scale = cj_fmax(scale, cj_fmax(fabs(ea[2 * i]), fabs(ea[2 * i + 1])));
    }
    return dev + 16.0 * (n + 2) * 0x1p-53 * scale;
}

void cj_isect_overlaps(run *R, const cj_bezier2 *a, const cj_bezier2 *b) {
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
            cj_ivl box[2] = {cj_iv2(s1, s2), cj_iv2(cj_fmin(t1, t2), cj_fmax(t1, t2))};
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
cj_status cj_isect_finish(run *R, double line_scale, cj_isect *out, int cap, int *count) {
    /* connected components of touching leaf boxes: repeated pairwise merging */
    int n = R->nleaves;
    for (int changed = 1; changed;) {
        changed = 0;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (meets(R->leaves[i].B, R->leaves[j].B)) {
                    for (int k = 0; k < 2; ++k)
                        R->leaves[i].B[k] = cj_ihull(R->leaves[i].B[k], R->leaves[j].B[k]);
                    R->leaves[i].size = cj_fmax(R->leaves[i].size, R->leaves[j].size);
                    R->leaves[i].exact |= R->leaves[j].exact;
                    R->leaves[j] = R->leaves[--n];
                    changed = 1;
                    --j;
                }
    }
    R->nleaves = n;
    /* the usual handful of results on the stack; the heap only for many */
    cj_isect few[32], *tmp = few;
    int most = R->noverlaps + R->nroots + R->nleaves;
    if (most > 32 && !(tmp = malloc(sizeof(cj_isect) * (size_t)most)))
        return cj_fail(CJ_ERR_NOMEM, "intersection results");
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
    /* leaves inside a crossing's uniqueness box are that crossing (dropped); a crossing whose
     * enclosure lies inside a remaining contact is held by it (a flat contact made by one pair
     * can hold a root certified by a neighbouring pair): dropped, so it is not reported twice */
    for (int i = 0; i < R->nleaves; ++i) {
        leaf *l = &R->leaves[i];
        l->dropped = 0;
        for (int k = 0; k < R->noverlaps; ++k) l->dropped |= meets(l->B, R->overlap[k]);
        for (int k = 0; k < R->nroots && !l->exact; ++k) l->dropped |= inside(l->B, R->roots[k].U);
    }
    for (int i = 0; i < R->nroots; ++i) {
        root *r = &R->roots[i];
        int absorbed = 0;
        for (int k = 0; k < R->noverlaps; ++k) absorbed |= meets(r->K, R->overlap[k]);
        for (int k = 0; k < R->nleaves; ++k)
            absorbed |= !R->leaves[k].dropped && inside(r->K, R->leaves[k].B);
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
        if (l->dropped) continue;
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
        } else if (cj_qctx_point(R->qa, o->s, p)) {
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
            o->t = cj_fmin(cj_fmax(o->t, o->t_lo), o->t_hi);
        }
    }
    if (total > 1) qsort(tmp, (size_t)total, sizeof tmp[0], cmp_isect);
    *count = total;
    for (int i = 0; i < total && i < cap; ++i) out[i] = tmp[i];
    if (tmp != few) free(tmp);
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

cj_status cj_isect_check_tol(double tol, double scale) {
    if (!isfinite(tol)) return cj_fail(CJ_ERR_NONFINITE, "tol is %s", isnan(tol) ? "NaN" : "inf");
    if (!(tol > 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "tol %g must be > 0", tol);
    if (tol < scale * 0x1p-40)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "tol %g is below what doubles resolve at the curves' scale %g (the "
                       "smallest is %g = 2^-40 times the scale)",
                       tol, scale, scale * 0x1p-40);
    return CJ_OK;
}
