/* Certified curve–curve, curve–line and self-intersections (see intersect.h for the guarantee).
 *
 * The search walks pairs of pieces (parameter boxes S x T). A box is dropped only on proof that
 * it holds no intersection: the control point hulls are separated along an axis (x, y, or the
 * normal of either chord), with every control point enclosed in a box that covers the rounding
 * of subdivision; or Krawczyk's operator K(X) misses X. When K(X+) lies inside the slightly
 * enlarged box X+, the box holds exactly one intersection, which is refined and recorded with
 * X+ as its uniqueness box. Boxes whose pieces shrank below tol without either proof become
 * contact leaves, merged afterwards into connected clusters. */
#include "intersect_internal.h"

#include "casteljau/bezier.h"
#include "casteljau/nearest.h"
#include "error_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

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

/* Points R at the full-size tables in *store (allocated). */
static cj_status big_tables(run *R, run_tables **store) {
    if (!(*store = malloc(sizeof **store))) return cj_fail(CJ_ERR_NOMEM, "intersection work space");
    R->roots = (*store)->roots;
    R->max_roots = MAX_ROOTS;
    R->leaves = (*store)->leaves;
    R->max_leaves = MAX_LEAVES;
    return CJ_OK;
}

static cj_status curves_impl(const cj_bezier2 *a, const cj_bezier2 *b, double tol, cj_isect *out,
                             int cap, int *count) {
    assert(a && b && count && (out || cap == 0));
    /* small tables on the stack (a few roots and contacts is the usual answer); the full ones
     * (~250 KiB) on the heap only if those fill, the pass then run again */
    root few_roots[16];
    leaf few_leaves[64];
    run_tables *store = NULL;
    run Rs, *R = &Rs;
    R->roots = few_roots;
    R->max_roots = 16;
    R->leaves = few_leaves;
    R->max_leaves = 64;
    cj_qctx ctx[2], *qa = &ctx[0], *qb = &ctx[1]; /* 22 KiB */
    cj_status st = CJ_OK;
    if ((st = cj_qctx_init_first(qa, a, "curve a")) != CJ_OK) return st;
    if ((st = cj_qctx_init_first(qb, b, "curve b")) != CJ_OK) return st;
    if ((st = cj_isect_check_tol(tol, cj_fmax(qa->scale, qb->scale))) != CJ_OK) return st;
    /* Overlaps are looked for only when a first search, capped low, leaves something
     * unresolved: coincident pieces can neither be excluded nor certified, so they always do. */
    for (int pass = 0; pass < 2;) {
        cj_isect_run_reset(R);
        R->qa = qa;
        R->qb = qb;
        R->tol = tol;
        R->max_boxes = pass == 0 ? 20000 : CJ_ISECT_MAX_BOXES;
        R->ca = a;
        cj_isect_joints(R, a, b);
        if (pass == 1) cj_isect_overlaps(R, a, b);
        cj_qpiece pa, pb;
        cj_qpiece_root(qa, &pa);
        cj_qpiece_root(qb, &pb);
        R->ext_a = cj_isect_extent(&pa);
        R->ext_b = cj_isect_extent(&pb);
        cj_isect_pair(R, &pa, &pb);
        if (R->table_full && !store) {
            if ((st = big_tables(R, &store)) != CJ_OK) return st;
            continue; /* the same pass with room */
        }
        if (!R->capped && R->nleaves == 0) break;
        ++pass;
    }
    st = cj_isect_finish(R, 0.0, out, cap, count);
    free(store);
    return st;
}

static cj_status self_impl(const cj_bezier2 *a, double tol, cj_isect *out, int cap, int *count) {
    assert(a && count && (out || cap == 0));
    run Rs, *R = &Rs;
    run_tables *store = NULL;
    cj_qctx *qa = malloc(sizeof *qa);
    cj_status st = CJ_OK;
    if (!qa) {
        st = cj_fail(CJ_ERR_NOMEM, "intersection work space");
        goto done;
    }
    if ((st = cj_qctx_init_first(qa, a, "curve")) != CJ_OK) goto done;
    if ((st = cj_isect_check_tol(tol, qa->scale)) != CJ_OK) goto done;
    if ((st = big_tables(R, &store)) != CJ_OK) goto done;
    cj_isect_run_reset(R);
    R->qa = R->qb = qa;
    R->tol = tol;
    R->self = 1;
    R->max_boxes = CJ_ISECT_MAX_BOXES;
    R->ca = a;
    cj_isect_joints(R, a, a);
    {
        cj_qpiece p;
        cj_qpiece_root(qa, &p);
        R->ext_a = R->ext_b = cj_isect_extent(&p);
        cj_isect_self_piece(R, &p);
    }
    st = cj_isect_finish(R, 0.0, out, cap, count);
done:
    free(store);
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
    run Rs, *R = &Rs;
    run_tables *store = NULL;
    cj_qctx *qa = malloc(sizeof *qa), *qb = malloc(sizeof *qb);
    cj_status st = CJ_OK;
    if (!qa || !qb) {
        st = cj_fail(CJ_ERR_NOMEM, "intersection work space");
        goto done;
    }
    if ((st = cj_qctx_init_first(qa, a, "curve")) != CJ_OK) goto done;
    if ((st = cj_isect_check_tol(tol, qa->scale)) != CJ_OK) goto done;
    if ((st = big_tables(R, &store)) != CJ_OK) goto done;
    {
        /* λ span: the control points project within |c_i - p| / |d| of λ = 0; a power of two
         * at least twice that keeps L exact and the curve strictly inside the segment. */
        double reach = 0.0, dn = cj_fmax(fabs(d[0]), fabs(d[1]));
        for (int i = 0; i <= a->degree; ++i)
            reach = cj_fmax(reach, fabs(a->pts[2 * i] - p[0]) + fabs(a->pts[2 * i + 1] - p[1]));
        double L = ldexp(1.0, ilogb(cj_fmax(reach / dn, 0x1p-1000)) + 2);
        if (!isfinite(L) || !isfinite(L * dn)) {
            st = cj_fail(CJ_ERR_RANGE, "line point and direction are out of scale with the curve");
            goto done;
        }
        cj_qctx_line(qb, p, d, L);
        cj_isect_run_reset(R);
        R->qa = qa;
        R->qb = qb;
        R->tol = tol;
        R->line = 1;
        R->max_boxes = CJ_ISECT_MAX_BOXES;
        cj_qpiece pa, pb;
        cj_qpiece_root(qa, &pa);
        cj_qpiece_root(qb, &pb);
        R->ext_a = cj_isect_extent(&pa);
        R->ext_b = cj_isect_extent(&pb);
        cj_isect_pair(R, &pa, &pb);
        st = cj_isect_finish(R, L, out, cap, count);
    }
done:
    free(store);
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
    int k = cj_query_scale_exp(cj_fmax(cj_query_scale(a), cj_query_scale(b)));
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
    double sc = cj_fmax(cj_query_scale(a), cj_fmax(fabs(p[0]), fabs(p[1])));
    int k = cj_query_scale_exp(sc);
    if (k == 0) return line_impl(a, p, d, tol, out, cap, count);
    double pa[2 * (CJ_QUERY_MAX_DEGREE + 1)], ps[2] = {ldexp(p[0], k), ldexp(p[1], k)};
    cj_bezier2 A = cj_query_scaled(a, k, pa);
    cj_status st = line_impl(&A, ps, d, ldexp(tol, k), out, cap, count);
    unscale(out, *count < cap ? *count : cap, k, 1);
    return st;
}
