/* One build of one patch: its per-patch state, the vertices (corners, canonical side points,
 * grid), the triangles with their bound and measured deviation, and the zippers between a
 * side and the grid. The adaptive search (tessellate_adaptive.c) and the uniform path
 * (tessellate.c) both build through here. */
#include "casteljau/tessellate.h"
#include "error_internal.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

int cj_tess_cmp_point(const double *a, double wa, const double *b, double wb) {
    for (int k = 0; k < 3; ++k)
        if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
    if (wa != wb) return wa < wb ? -1 : 1;
    return 0;
}

void cj_tess_edge_setup(const cj_patch *p, int side, edge_info *e) {
    int first, step, count;
    cj_patch_edge_indices(p->deg_u, p->deg_v, side, &first, &step, &count);
    double g[(CJ_PATCH_MAX_DEGREE + 1) * 3], gw[CJ_PATCH_MAX_DEGREE + 1];
    for (int a = 0; a < count; ++a) {
        memcpy(g + 3 * a, p->pts + 3 * (first + a * step), 3 * sizeof(double));
        gw[a] = p->weights ? p->weights[first + a * step] : 1.0;
    }
    e->degree = count - 1;
    e->collapsed = 1;
    for (int a = 1; a < count && e->collapsed; ++a)
        if (cj_tess_cmp_point(g + 3 * a, gw[a], g, gw[0]) != 0) e->collapsed = 0;
    e->reversed = 0;
    for (int a = 0; a < count; ++a) {
        const int c =
            cj_tess_cmp_point(g + 3 * a, gw[a], g + 3 * (count - 1 - a), gw[count - 1 - a]);
        if (c != 0) {
            e->reversed = c > 0;
            break;
        }
    }
    for (int a = 0; a < count; ++a) {
        const int src = e->reversed ? count - 1 - a : a;
        memcpy(e->pts + 3 * a, g + 3 * src, 3 * sizeof(double));
        e->w[a] = gw[src];
    }
}

/* Point a of k along the patch side (side parameter a/k), evaluated canonically. */
static void edge_point(const edge_info *e, int rational, int a, int k, double out[3]) {
    const int ac = e->reversed ? k - a : a;
    const int d = e->degree;
    if (e->collapsed || ac == 0) {
        memcpy(out, e->pts, 3 * sizeof(double));
        return;
    }
    if (ac == k) {
        memcpy(out, e->pts + 3 * d, 3 * sizeof(double));
        return;
    }
    const double t = (double)ac / (double)k, s = 1.0 - t;
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    const int hd = rational ? 4 : 3;
    for (int i = 0; i <= d; ++i) {
        const double wi = rational ? e->w[i] : 1.0;
        for (int c = 0; c < 3; ++c)
            w[i * hd + c] = rational ? wi * e->pts[3 * i + c] : e->pts[3 * i + c];
        if (rational) w[i * hd + 3] = wi;
    }
    for (int r = d; r > 0; --r)
        for (int i = 0; i < r * hd; ++i) w[i] = s * w[i] + t * w[i + hd];
    for (int c = 0; c < 3; ++c) out[c] = rational ? w[c] / w[3] : w[c];
}

static void eval_point(const ptess *P, double u, double v, double out[3]) {
    double r[4];
    cj_patch_eval_h(P->h, P->hd, P->m, P->n, u, v, r);
    if (P->hd == 4)
        for (int c = 0; c < 3; ++c) out[c] = r[c] / r[3];
    else
        memcpy(out, r, 3 * sizeof(double));
}

/* Adds a vertex; its normal is computed unless planning or `later` (grid vertices: computed
 * with their position). */
static cj_status add_vertex(ptess *P, const double pos[3], double u, double v, int later,
                            uint32_t *idx) {
    if (P->bounds_only) {
        P->scr_uv[2 * (size_t)P->scr_count] = u;
        P->scr_uv[2 * (size_t)P->scr_count + 1] = v;
        *idx = P->scr_count++;
        return CJ_OK;
    }
    double nrm[3] = {0.0, 0.0, 0.0};
    const double uv[2] = {u, v};
    if (!P->planning && !later &&
        cj_patch_normal_unchecked(P->p, P->h, P->hd, u, v, nrm, NULL) != CJ_OK)
        nrm[0] = nrm[1] = nrm[2] = 0.0; /* a patch collapsed to a curve: no normal */
    return cj_mesh_add_vertex(P->mesh, pos, nrm, uv, idx);
}

/* Index of t among the zipper walk's breakpoints, or -1. */
static int zip_find(const ptess *P, double t) {
    int lo = 0, hi = P->zip_n - 1;
    while (lo <= hi) {
        const int mid = (lo + hi) / 2;
        if (P->zip_bp[mid] == t) return mid;
        if (P->zip_bp[mid] < t)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

/* Bounds over a zipper triangle's box from the walk of its ring: the largest interval bounds
 * over the intervals the box covers (each bounds its derivative on its piece; the pieces cover
 * the box). 0 when the box does not span the ring's strip (then computed directly). */
static int zip_walk_bounds(const ptess *P, double u0, double u1, double v0, double v1,
                           dbounds *out) {
    double a = u0, b = u1;
    if (P->zip_dir == 0) {
        if (!(v0 == P->zip.v0 && v1 == P->zip.v1)) return 0;
    } else {
        if (!(u0 == P->zip.v0 && u1 == P->zip.v1)) return 0;
        a = v0;
        b = v1;
    }
    const int i = zip_find(P, a), j = zip_find(P, b);
    if (i < 0 || j <= i) return 0;
    dbounds r = P->zip_iv[i];
    for (int x = i + 1; x < j; ++x) {
        r.uu = fmax(r.uu, P->zip_iv[x].uu);
        r.uv = fmax(r.uv, P->zip_iv[x].uv);
        r.vv = fmax(r.vv, P->zip_iv[x].vv);
    }
    *out = r;
    return 1;
}

/* Adds triangle (a,b,c) (reordered CCW in (u,v)), accounting its bound with strip bounds
 * `db` and its measured deviation; degenerate triangles are counted and not added. */
/* The smallest and largest of three (no NaN here: parameters in [0,1]). */
static inline double min3(double a, double b, double c) {
    const double m = a < b ? a : b;
    return m < c ? m : c;
}
static inline double max3(double a, double b, double c) {
    const double m = a > b ? a : b;
    return m > c ? m : c;
}

static cj_status add_tri(ptess *P, uint32_t a, uint32_t b, uint32_t c, const dbounds *db) {
    cj_mesh *M = P->mesh;
    const double *uvs = P->bounds_only ? P->scr_uv : M->uvs;
    const double *ua = uvs + 2 * (size_t)a, *ub = uvs + 2 * (size_t)b, *uc = uvs + 2 * (size_t)c;
    const double area = (ub[0] - ua[0]) * (uc[1] - ua[1]) - (ub[1] - ua[1]) * (uc[0] - ua[0]);
    if (area < 0.0) {
        uint32_t t = b;
        b = c;
        c = t;
        const double *tu = ub;
        ub = uc;
        uc = tu;
    }
    if (P->bound_known) {
        /* the bound of these triangles is known (tessellate_adaptive.c, try_grid) */
    } else if (P->predict) {
        /* a predicted (not proven) bound for planning a rational patch: the interpolation error
         * with the sampled second derivatives of the slab cells the triangle's box meets */
        const double u0 = min3(ua[0], ub[0], uc[0]), u1 = max3(ua[0], ub[0], uc[0]);
        const double v0 = min3(ua[1], ub[1], uc[1]), v1 = max3(ua[1], ub[1], uc[1]);
        const int S = CJ_TESS_SLABS;
        int a0 = (int)(u0 * S), a1 = (int)ceil(u1 * S) - 1, b0 = (int)(v0 * S),
            b1 = (int)ceil(v1 * S) - 1;
        a0 = a0 < 0 ? 0 : a0 > S - 1 ? S - 1 : a0;
        b0 = b0 < 0 ? 0 : b0 > S - 1 ? S - 1 : b0;
        a1 = a1 < a0 ? a0 : a1 > S - 1 ? S - 1 : a1;
        b1 = b1 < b0 ? b0 : b1 > S - 1 ? S - 1 : b1;
        const int tables = P->rational ? 6 : 3;
        double m[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        for (int bb = b0; bb <= b1; ++bb)
            for (int aa = a0; aa <= a1; ++aa)
                for (int t = 0; t < tables; ++t) {
                    const double x = P->pm[t * S * S + bb * S + aa];
                    m[t] = x > m[t] ? x : m[t];
                }
        const double du = u1 - u0, dv = v1 - v0;
        if (!P->rational) {
            /* polynomial: the slab cells' bounds are proven bounds over the cells the box
             * meets (a sub-box's restricted net is a convex combination of the cell's), so
             * this is the proven polynomial bound, only coarser than the cell's own */
            const double t0 = m[0] * du * du, t1 = 2.0 * m[1] * du * dv, t2 = m[2] * dv * dv;
            const double bnd = (t0 + t1 + t2) * 0.125 * (1.0 + 8.0 * U_ROUND) + P->evalerr;
            if (bnd > P->bound) {
                P->bound = bnd;
                P->worst_terms[0] = t0;
                P->worst_terms[1] = t1;
                P->worst_terms[2] = t2;
            }
            if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
            ++P->tris;
            return CJ_OK;
        }
        /* min(bF, bQ) as the build's bound: bF from the sampled derivatives (its M's tend to
         * them as the triangle shrinks), bQ from the slab cells' (Q) bounds (an over-estimate
         * of a smaller box's) */
        const double bf = CJ_TESS_PREDICT_MARGIN *
                          (m[0] * du * du + 2.0 * m[1] * du * dv + m[2] * dv * dv) * 0.125;
        const double bq =
            (m[3] * du * du + 2.0 * m[4] * du * dv + m[5] * dv * dv) * 0.125 + P->pm[6 * S * S];
        const double bnd = fmin(bf, bq) + P->verterr;
        if (bnd > P->bound) P->bound = bnd;
        if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
    } else if (P->rational) {
        double bnd = cj_tess_rational_tri_bound(P, ua, ub, uc, M->positions + 3 * (size_t)a,
                                                M->positions + 3 * (size_t)b,
                                                M->positions + 3 * (size_t)c, db != NULL, P->bound);
        if (!(bnd >= 0.0)) bnd = INFINITY;
        if (bnd > P->bound) P->bound = bnd;
        if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
    } else {
        const double u0 = fmin(fmin(ua[0], ub[0]), uc[0]), u1 = fmax(fmax(ua[0], ub[0]), uc[0]);
        const double v0 = fmin(fmin(ua[1], ub[1]), uc[1]), v1 = fmax(fmax(ua[1], ub[1]), uc[1]);
        const double du = u1 - u0, dv = v1 - v0;
        dbounds local;
        if (!db) { /* bounds over the triangle's own (u,v) box */
            if (!(du > 0.0 && dv > 0.0))
                local = P->whole;
            else if (P->zip_n > 0 && zip_walk_bounds(P, u0, u1, v0, v1, &local))
                ; /* the intervals of the ring's walk that the box covers */
            else if (P->zip_dir == 0 && v0 == P->zip.v0 && v1 == P->zip.v1)
                local = cj_tess_cell_bounds(P, &P->zip, u0, u1); /* the box spans the strip */
            else if (P->zip_dir == 1 && u0 == P->zip.v0 && u1 == P->zip.v1)
                local = cj_tess_ucell_bounds(P, &P->zip, v0, v1);
            else
                local = cj_tess_strip_bounds(P, u0, u1, v0, v1);
            db = &local;
        }
        const double t0 = db->uu * du * du, t1 = 2.0 * db->uv * du * dv, t2 = db->vv * dv * dv;
        const double bnd = (t0 + t1 + t2) * 0.125 * (1.0 + 8.0 * U_ROUND) + P->evalerr;
        if (bnd > P->bound) {
            P->bound = bnd;
            P->worst_terms[0] = t0;
            P->worst_terms[1] = t1;
            P->worst_terms[2] = t2;
        }
        if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
    }
    if (P->bounds_only) {
        ++P->tris;
        return CJ_OK;
    }
    const double *pa = M->positions + 3 * (size_t)a, *pb = M->positions + 3 * (size_t)b,
                 *pc = M->positions + 3 * (size_t)c;
    if (P->measure > 0) {
        const int L = P->measure;
        /* rational: min(|S - L|, |S - Q|), Q(x) = Σ λ_i w_i V_i / Σ λ_i w_i (both points of
         * the triangle; the bound is the smaller of one for each: cj_tess_rational_tri_bound) */
        double wa = 1.0, wb = 1.0, wc = 1.0;
        if (P->rational) {
            double r[4];
            cj_patch_eval_h(P->h, 4, P->m, P->n, ua[0], ua[1], r);
            wa = r[3];
            cj_patch_eval_h(P->h, 4, P->m, P->n, ub[0], ub[1], r);
            wb = r[3];
            cj_patch_eval_h(P->h, 4, P->m, P->n, uc[0], uc[1], r);
            wc = r[3];
        }
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const double la = (double)i / L, lb = (double)j / L, lc = 1.0 - la - lb;
                const double u = la * ua[0] + lb * ub[0] + lc * uc[0];
                const double v = la * ua[1] + lb * ub[1] + lc * uc[1];
                double s[3], d2 = 0.0;
                eval_point(P, u, v, s);
                for (int k = 0; k < 3; ++k) {
                    const double x = s[k] - (la * pa[k] + lb * pb[k] + lc * pc[k]);
                    d2 += x * x;
                }
                double dev = sqrt(d2);
                if (P->rational) {
                    const double sw = la * wa + lb * wb + lc * wc;
                    double q2 = 0.0;
                    for (int k = 0; k < 3; ++k) {
                        const double x =
                            s[k] - (la * wa * pa[k] + lb * wb * pb[k] + lc * wc * pc[k]) / sw;
                        q2 += x * x;
                    }
                    dev = fmin(dev, sqrt(q2));
                }
                if (dev > P->measured) P->measured = dev;
            }
    }
    if (same_pos(pa, pb) || same_pos(pb, pc) || same_pos(pa, pc)) {
        ++P->dropped;
        return CJ_OK;
    }
    ++P->tris;
    return cj_mesh_add_triangle(M, a, b, c, P->id);
}

/* Zipper between outer points o[0..k] with side parameters tout[0..k] and inner points
 * in[0..L] with side parameters tin[0..L]: advances the row whose next segment's midpoint
 * comes first. */
static cj_status zipper(ptess *P, const uint32_t *o, const double *tout, int k, const uint32_t *in,
                        const double *tin, int L, const dbounds *db) {
    int a = 0, b = 0;
    double *bp = NULL;
    dbounds *iv = NULL;
    P->zip_n = 0;
    if (!P->rational && !P->bound_known &&
        !P->predict) {            /* every triangle spans the ring's strip */
        const int s = P->zip_dir; /* set by the caller: the side */
        if (s == 0)
            cj_tess_strip_restrict(P, 0.0, P->zip_t, &P->zip);
        else if (s == 2)
            cj_tess_strip_restrict(P, P->zip_t, 1.0, &P->zip);
        else if (s == 3)
            cj_tess_ustrip_restrict(P, 0.0, P->zip_t, &P->zip);
        else
            cj_tess_ustrip_restrict(P, P->zip_t, 1.0, &P->zip);
        P->zip_dir = (s & 1) ? 1 : 0;
        if (cj_tess_walkable(P)) { /* walk the merged breakpoints of the ring once */
            const size_t cap = (size_t)k + (size_t)L + 2;
            bp = t_alloc(P->mesh, sizeof(double) * cap);
            iv = t_alloc(P->mesh, sizeof(dbounds) * cap);
            if (!bp || !iv) {
                t_free(P->mesh, bp);
                t_free(P->mesh, iv);
                return cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %d", (int)P->id);
            }
            int nb = 0, x = 0, y = 0;
            while (x <= k || y <= L) { /* merge, dropping repeats */
                const double t = y > L || (x <= k && tout[x] <= tin[y]) ? tout[x++] : tin[y++];
                if (nb == 0 || t > bp[nb - 1]) bp[nb++] = t;
            }
            for (int c = 0; c < nb; ++c) {
                tess_line *A = &P->lines[c & 1];
                if (P->zip_dir == 0)
                    cj_tess_line(P, &P->zip, bp[c], A);
                else
                    cj_tess_uline(P, &P->zip, bp[c], A);
                if (c > 0) iv[c - 1] = cj_tess_cell_walk(P, &P->lines[(c - 1) & 1], A);
            }
            P->zip_n = nb;
            P->zip_bp = bp;
            P->zip_iv = iv;
        }
    } else {
        P->zip_dir = -1;
    }
    cj_status st = CJ_OK;
    while (a < k || b < L) {
        const int adv_outer = cj_tess_zip_outer(tout, a, k, tin, b, L);
        if (adv_outer) {
            st = add_tri(P, o[a], o[a + 1], in[b], db);
            ++a;
        } else {
            st = add_tri(P, o[a], in[b + 1], in[b], db);
            ++b;
        }
        if (st || P->aborted) break;
    }
    P->zip_dir = -1;
    P->zip_n = 0;
    t_free(P->mesh, bp);
    t_free(P->mesh, iv);
    return st;
}

/* One build of a patch: interior breakpoints ub[0..nu] (ub[0] = 0, ub[nu] = 1) and
 * vb[0..nv]; k[s] segments on side s (a collapsed side uses the interior breakpoints of its
 * direction, k[s] = nu or nv). */
cj_status cj_tess_build_patch(ptess *P, int nu, const double *ub, int nv, const double *vb,
                              const int k[4]) {
    const int m = P->m, n = P->n;
    cj_status st = CJ_OK;
    P->bound = 0.0;
    P->measured = 0.0;
    P->dropped = 0;
    P->aborted = 0;
    P->tris = 0;
    P->worst_terms[0] = P->worst_terms[1] = P->worst_terms[2] = 0.0;
    assert(!P->bounds_only || !P->rational || P->predict);
    if (P->bounds_only)
        ++P->trials;
    else
        ++P->builds;
    const size_t nouter = (size_t)(k[0] + k[1] + k[2] + k[3] + 4);
    const size_t ngrid = (size_t)(nu + 1) * (size_t)(nv + 1);
    const size_t nmax = (size_t)(nu > nv ? nu : nv) + 1;
    const size_t ncol = P->bounds_only ? 0 : (size_t)(P->n + 1) * (size_t)(P->hd + 3);
    uint32_t *buf = t_alloc(P->mesh, sizeof(uint32_t) * (nouter + ngrid + nmax));
    /* doubles: side parameters, inner parameters, then (bounds_only) the vertices' (u,v) or
     * (a build) one column of the grid evaluation */
    double *tbuf = t_alloc(
        P->mesh, sizeof(double) * (nouter + nmax + (P->bounds_only ? 2 * (nouter + ngrid) : ncol)));
    P->scr_uv = tbuf ? tbuf + nouter + nmax : NULL;
    P->scr_count = 0;
    if (!buf || !tbuf) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %d", (int)P->id);
        goto done;
    }
    uint32_t *o[4];
    double *tout[4];
    o[0] = buf;
    tout[0] = tbuf;
    for (int s = 1; s < 4; ++s) {
        o[s] = o[s - 1] + k[s - 1] + 1;
        tout[s] = tout[s - 1] + k[s - 1] + 1;
    }
    uint32_t *g = buf + nouter; /* grid indices, (j*(nu+1)+i) */
    uint32_t *inner = g + ngrid;
    double *tin = tbuf + nouter;
    int regular = 1;
    for (int s = 0; s < 4; ++s) {
        const int along_u = !(s & 1);
        const double *br = along_u ? ub : vb;
        const int nb = along_u ? nu : nv;
        for (int a = 0; a <= k[s]; ++a)
            tout[s][a] = P->e[s].collapsed ? br[a] : (double)a / (double)k[s];
        if (k[s] != nb)
            regular = 0;
        else
            for (int a = 0; a <= k[s] && regular; ++a)
                if (tout[s][a] != br[a]) regular = 0;
    }
    /* the normals of a polynomial patch's side points: from grid columns, after the sides */
    const int side_later = !P->bounds_only && !P->planning && P->hd == 3;
    double *col = tbuf + nouter + nmax, *dcol = col + (size_t)(P->n + 1) * (size_t)P->hd;
    /* corners: the control points themselves */
    const int m1 = m + 1;
    uint32_t c00, c10, c11, c01;
    if ((st = add_vertex(P, P->p->pts, 0.0, 0.0, 0, &c00))) goto done;
    if ((st = add_vertex(P, P->p->pts + 3 * m, 1.0, 0.0, 0, &c10))) goto done;
    if ((st = add_vertex(P, P->p->pts + 3 * (n * m1 + m), 1.0, 1.0, 0, &c11))) goto done;
    if ((st = add_vertex(P, P->p->pts + 3 * (n * m1), 0.0, 1.0, 0, &c01))) goto done;
    const uint32_t first[4] = {c00, c10, c01, c00}, last[4] = {c10, c11, c11, c01};
    for (int s = 0; s < 4; ++s) {
        o[s][0] = first[s];
        o[s][k[s]] = last[s];
        for (int a = 1; a < k[s]; ++a) {
            double pos[3] = {0.0, 0.0, 0.0};
            if (!P->bounds_only) edge_point(&P->e[s], P->rational, a, k[s], pos);
            const double t = tout[s][a];
            double u, v;
            switch (s) {
            case 0:
                u = t, v = 0.0;
                break;
            case 1:
                u = 1.0, v = t;
                break;
            case 2:
                u = t, v = 1.0;
                break;
            default:
                u = 0.0, v = t;
                break;
            }
            if ((st = add_vertex(P, pos, u, v, side_later, &o[s][a]))) goto done;
        }
    }
    if (side_later) cj_tess_side_normals(P, o, tout, k, col, dcol);
    /* grid vertices column by column (the u stage shared), stored row by row as before */
    for (int j = 1; j < nv; ++j)
        for (int i = 1; i < nu; ++i) {
            const double pos[3] = {0.0, 0.0, 0.0};
            if ((st = add_vertex(P, pos, ub[i], vb[j], 1, &g[j * (nu + 1) + i]))) goto done;
        }
    if (!P->bounds_only)
        for (int i = 1; i < nu; ++i) {
            cj_tess_eval_column(P, ub[i], col, dcol);
            for (int j = 1; j < nv; ++j) {
                const size_t vi = (size_t)g[j * (nu + 1) + i];
                double *pos = P->mesh->positions + 3 * vi, su[3], sv[3];
                cj_tess_eval_in_column(P, col, vb[j], pos, sv);
                if (!P->planning) {
                    if (P->hd == 3) cj_tess_eval_du(P, dcol, vb[j], su);
                    cj_tess_grid_normal(P, su, sv, ub[i], vb[j], P->mesh->normals + 3 * vi);
                }
                if (!isfinite(pos[0]) || !isfinite(pos[1]) || !isfinite(pos[2])) {
                    st = cj_fail(CJ_ERR_NONFINITE,
                                 "patch %d: vertex at (%.17g, %.17g) is not finite", (int)P->id,
                                 ub[i], vb[j]);
                    goto done;
                }
            }
        }
    int j0 = 0, j1 = nv, i0 = 0, i1 = nu; /* the block of regular cells */
    if (regular) {
        for (int i = 0; i <= nu; ++i) {
            g[i] = o[0][i];
            g[nv * (nu + 1) + i] = o[2][i];
        }
        for (int j = 0; j <= nv; ++j) {
            g[j * (nu + 1)] = o[3][j];
            g[j * (nu + 1) + nu] = o[1][j];
        }
    } else {
        assert(nu >= 2 && nv >= 2);
        int L = nu - 2;
        for (int i = 1; i < nu; ++i) {
            inner[i - 1] = g[1 * (nu + 1) + i];
            tin[i - 1] = ub[i];
        }
        P->zip_dir = 0, P->zip_t = vb[1];
        if ((st = zipper(P, o[0], tout[0], k[0], inner, tin, L, NULL)) || P->aborted) goto done;
        for (int i = 1; i < nu; ++i) inner[i - 1] = g[(nv - 1) * (nu + 1) + i];
        P->zip_dir = 2, P->zip_t = vb[nv - 1];
        if ((st = zipper(P, o[2], tout[2], k[2], inner, tin, L, NULL)) || P->aborted) goto done;
        L = nv - 2;
        for (int j = 1; j < nv; ++j) {
            inner[j - 1] = g[j * (nu + 1) + 1];
            tin[j - 1] = vb[j];
        }
        P->zip_dir = 3, P->zip_t = ub[1];
        if ((st = zipper(P, o[3], tout[3], k[3], inner, tin, L, NULL)) || P->aborted) goto done;
        for (int j = 1; j < nv; ++j) inner[j - 1] = g[j * (nu + 1) + nu - 1];
        P->zip_dir = 1, P->zip_t = ub[nu - 1];
        if ((st = zipper(P, o[1], tout[1], k[1], inner, tin, L, NULL)) || P->aborted) goto done;
        j0 = i0 = 1;
        j1 = nv - 1;
        i1 = nu - 1;
    }
    for (int j = j0; j < j1; ++j) {
        const int cells = !P->bound_known && !P->predict; /* cell bounds needed */
        const int walk = cells && cj_tess_walkable(P);
        if (cells && !P->rational) cj_tess_strip_restrict(P, vb[j], vb[j + 1], &P->strip);
        if (walk) cj_tess_line(P, &P->strip, ub[i0], &P->lines[0]);
        for (int i = i0; i < i1; ++i) {
            dbounds cb = {0.0, 0.0, 0.0};
            if (cells && P->rational) {
                cj_tess_load_cell(P, ub[i], ub[i + 1], vb[j], vb[j + 1]);
            } else if (walk) { /* the line at ub[i] was computed for the previous cell */
                tess_line *A = &P->lines[(i - i0) & 1], *B = &P->lines[(i - i0 + 1) & 1];
                cj_tess_line(P, &P->strip, ub[i + 1], B);
                cb = cj_tess_cell_walk(P, A, B);
            } else if (cells) {
                cb = cj_tess_cell_bounds(P, &P->strip, ub[i], ub[i + 1]);
            }
            const uint32_t A = g[j * (nu + 1) + i], B = g[j * (nu + 1) + i + 1],
                           C = g[(j + 1) * (nu + 1) + i + 1], D = g[(j + 1) * (nu + 1) + i];
            if ((st = add_tri(P, A, B, C, &cb))) goto done;
            if ((st = add_tri(P, A, C, D, &cb)) || P->aborted) goto done;
        }
    }
done:
    t_free(P->mesh, buf);
    t_free(P->mesh, tbuf);
    return st;
}

/* Per-patch state for one patch (everything but the results of a build). */
void cj_tess_setup(ptess *P, const cj_patch *p, size_t q, cj_mesh *mesh, int measure) {
    memset(P, 0, offsetof(ptess, h)); /* the large arrays are written before they are read */
    P->p = p;
    P->id = (int32_t)q;
    P->m = p->deg_u;
    P->n = p->deg_v;
    P->hd = cj_patch_load_h(p, P->h);
    P->rational = p->weights != NULL;
    P->mesh = mesh;
    P->measure = measure;
    double mx = 0.0;
    for (size_t i = 0; i < 3 * cj_patch_point_count(p); ++i) mx = fmax(mx, fabs(p->pts[i]));
    /* vertex rounding (de Casteljau) plus the sample's own rounding, in 3D norm */
    P->evalerr = 2.0 * cj_gamma(3 * (P->m + P->n) + 4) * mx * sqrt(3.0);
    if (P->rational) {
        /* homogeneous de Casteljau: numerator off by <= g w max|b|, weight by <= g w (weights
         * > 0), g = gamma(3(m+n)+4); the quotient by <= (2g + u) max|b| / (1 - g) per
         * coordinate */
        const double g0 = cj_gamma(3 * (P->m + P->n) + 4);
        P->verterr = (2.0 * g0 + U_ROUND) / (1.0 - g0) * mx * sqrt(3.0) * (1.0 + 8.0 * U_ROUND);
        /* sub-net coefficients (cj_tess_rational_tri_bound): <= 2(m+n) levels of s a + t b (and the
         * rounding of s = 1 - t), relative to the largest coefficient */
        double hx = 0.0, hw = 0.0;
        for (size_t i = 0; i < cj_patch_point_count(p); ++i) {
            for (int k = 0; k < 3; ++k) hx = fmax(hx, fabs(P->h[4 * i + (size_t)k]));
            hw = fmax(hw, P->h[4 * i + 3]);
        }
        const double g = cj_gamma(6 * (P->m + P->n) + 8);
        P->suberr_x = g * hx;
        P->suberr_w = g * hw;
    }
    for (int s = 0; s < 4; ++s) cj_tess_edge_setup(p, s, &P->e[s]);
    P->zip_dir = -1;
    if (!P->rational) {
        cj_tess_diff_setup(P);
        P->whole = cj_tess_strip_bounds(P, 0.0, 1.0, 0.0, 1.0);
    }
}
