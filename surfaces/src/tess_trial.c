/* Planning's bounds-only trial of a polynomial patch on its slab table, without enumerating the
 * grid's interior triangles (issue 19, part 3).
 *
 * The trial's bound of a triangle is the proven bound with the largest slab-cell bounds
 * (P->pm: Muu, Muv, Mvv of the CJ_TESS_SLABS x CJ_TESS_SLABS slab cells) over the slab cells
 * its (u,v) box meets, taken per component (see add_tri in tessellate_build.c, P->predict):
 *
 *     bnd(M, du, dv) = (M_uu du^2 + 2 M_uv du dv + M_vv dv^2) / 8 (1 + 8u) + evalerr.
 *
 * Both triangles of an interior grid cell [u_i, u_i+1] x [v_j, v_j+1] have the cell as their
 * box. The slab columns a cell meets are a contiguous range R(i) that depends on the cell only
 * through its end points; since the lines increase, cells with the same range are consecutive.
 * So the interior cells fall into groups (range in u) x (range in v), in which M is the same
 * and only du, dv vary; bnd is non-decreasing in du and dv (also in floating point: every
 * operation is monotone and the inputs are non-negative), so the largest bnd of a group is bnd
 * with the group's widest du and dv. The trial's bound over the interior is therefore exactly
 * (bit for bit) the largest bnd over the groups, found in O(ranges^2) instead of O(nu nv)
 * (about 31 x 31 ranges at most: single slabs and the cells straddling two). The zipper
 * triangles along the sides (O(nu + nv)) are bounded one by one, as in a build. */
#include "error_internal.h"
#include "tessellate_internal.h"

#include <math.h>

enum { S = CJ_TESS_SLABS, S2 = CJ_TESS_SLABS * CJ_TESS_SLABS };

/* The slab columns [*lo, *hi] that the parameter interval [t0, t1] meets (as add_tri). */
static inline void slab_range(double t0, double t1, int *lo, int *hi) {
    int a0 = (int)(t0 * S), a1 = (int)ceil(t1 * S) - 1;
    a0 = a0 < 0 ? 0 : a0 > S - 1 ? S - 1 : a0;
    a1 = a1 < a0 ? a0 : a1 > S - 1 ? S - 1 : a1;
    *lo = a0;
    *hi = a1;
}

/* Per component, the largest slab-cell bound over the band of slab rows [b0,b1] (across_u: of
 * slab columns [b0,b1]), for each slab column (row) along the band: band[a][0..2]. */
static void band_max(const ptess *P, int b0, int b1, int across_u, double band[S][3]) {
    for (int a = 0; a < S; ++a)
        for (int t = 0; t < 3; ++t) {
            double x = 0.0;
            for (int bb = b0; bb <= b1; ++bb) {
                const double y = P->pm[t * S2 + (across_u ? a * S + bb : bb * S + a)];
                x = y > x ? y : x;
            }
            band[a][t] = x;
        }
}

/* The band of rows [b0,b1]: from the patch's table of one- and two-row bands (made at its
 * first trial), else into `own`. */
static double (*row_band(ptess *P, int b0, int b1, double own[S][3]))[3] {
    if (!P->bands_valid) {
        for (int b = 0; b < S; ++b) {
            band_max(P, b, b, 0, P->slab_bands[0][b]);
            band_max(P, b, b + 1 < S ? b + 1 : b, 0, P->slab_bands[1][b]);
        }
        P->bands_valid = 1;
    }
    if (b1 - b0 <= 1) return P->slab_bands[b1 - b0][b0];
    band_max(P, b0, b1, 0, own);
    return own;
}

/* Per component, the largest of band[a0..a1]. */
static inline void range_max(double band[S][3], int a0, int a1, double m[3]) {
    m[0] = band[a0][0];
    m[1] = band[a0][1];
    m[2] = band[a0][2];
    for (int a = a0 + 1; a <= a1; ++a)
        for (int t = 0; t < 3; ++t) m[t] = band[a][t] > m[t] ? band[a][t] : m[t];
}

/* Accounts one bound with the same operations, in the same order, as add_tri. */
static void account(ptess *P, const double m[3], double du, double dv) {
    const double t0 = m[0] * du * du, t1 = 2.0 * m[1] * du * dv, t2 = m[2] * dv * dv;
    const double bnd = (t0 + t1 + t2) * 0.125 * (1.0 + 8.0 * U_ROUND) + P->evalerr;
    if (bnd > P->bound) {
        P->bound = bnd;
        P->worst_terms[0] = t0;
        P->worst_terms[1] = t1;
        P->worst_terms[2] = t2;
    }
}

/* The zipper of one side, triangle by triangle in the order of zipper() (tessellate_build.c):
 * outer parameters tout[0..k], inner tin[0..L]; every triangle spans [c0, c1] across the side
 * (along_u: the side runs along u). Returns the number of triangles. */
static size_t zip_trial(ptess *P, const double *tout, int k, const double *tin, int L, int along_u,
                        double c0, double c1) {
    int r0, r1;
    slab_range(c0, c1, &r0, &r1);
    double own[S][3];
    double(*band)[3] = own;
    if (along_u)
        band = row_band(P, r0, r1, own);
    else
        band_max(P, r0, r1, 1, own);
    int a = 0, b = 0;
    while (a < k || b < L) {
        const int adv_outer = cj_tess_zip_outer(tout, a, k, tin, b, L);
        /* (o[a], o[a+1], in[b]) or (o[a], in[b+1], in[b]); parameters increase along a row */
        const double x0 = tout[a] < tin[b] ? tout[a] : tin[b];
        const double hi = adv_outer ? tout[a + 1] : tin[b + 1];
        const double lo = adv_outer ? tin[b] : tout[a];
        const double x1 = hi > lo ? hi : lo;
        int a0, a1;
        slab_range(x0, x1, &a0, &a1);
        double m[3];
        range_max(band, a0, a1, m);
        if (along_u)
            account(P, m, x1 - x0, c1 - c0);
        else
            account(P, m, c1 - c0, x1 - x0);
        if (adv_outer)
            ++a;
        else
            ++b;
    }
    return (size_t)k + (size_t)L;
}

/* Cells [i0, i1) of lines t grouped by the slab range they meet: *count groups with ranges
 * lo[g]..hi[g] and widest cell wide[g]. */
static void group_cells(const double *t, int i0, int i1, int *lo, int *hi, double *wide,
                        int *count) {
    int c = 0;
    for (int i = i0; i < i1; ++i) {
        int a0, a1;
        slab_range(t[i], t[i + 1], &a0, &a1);
        const double w = t[i + 1] - t[i];
        if (c > 0 && lo[c - 1] == a0 && hi[c - 1] == a1) {
            if (w > wide[c - 1]) wide[c - 1] = w;
        } else {
            lo[c] = a0;
            hi[c] = a1;
            wide[c] = w;
            ++c;
        }
    }
    *count = c;
}

cj_status cj_tess_slab_trial(ptess *P, int nu, const double *ub, int nv, const double *vb,
                             const int k[4]) {
    P->bound = 0.0;
    P->measured = 0.0;
    P->dropped = 0;
    P->aborted = 0;
    P->tris = 0;
    P->worst_terms[0] = P->worst_terms[1] = P->worst_terms[2] = 0.0;
    ++P->trials;
    /* the side parameters, as cj_tess_build_patch sets them */
    double *tbuf = t_alloc(P->mesh, sizeof(double) * (size_t)(k[0] + k[1] + k[2] + k[3] + 4));
    if (!tbuf) return cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %d", (int)P->id);
    double *tout[4];
    tout[0] = tbuf;
    for (int s = 1; s < 4; ++s) tout[s] = tout[s - 1] + k[s - 1] + 1;
    for (int s = 0; s < 4; ++s) {
        const double *br = (s & 1) ? vb : ub;
        for (int a = 0; a <= k[s]; ++a)
            tout[s][a] = P->e[s].collapsed ? br[a] : (double)a / (double)k[s];
    }
    int regular = 1;
    for (int s = 0; s < 4 && regular; ++s) {
        const double *br = (s & 1) ? vb : ub;
        const int nb = (s & 1) ? nv : nu;
        if (k[s] != nb) regular = 0;
        for (int a = 0; a <= k[s] && regular; ++a)
            if (tout[s][a] != br[a]) regular = 0;
    }
    int i0 = 0, i1 = nu, j0 = 0, j1 = nv;
    if (!regular) {
        /* inner rows and columns: the grid lines 1..n-1 (tin of zipper()) */
        P->tris += zip_trial(P, tout[0], k[0], ub + 1, nu - 2, 1, 0.0, vb[1]);
        P->tris += zip_trial(P, tout[2], k[2], ub + 1, nu - 2, 1, vb[nv - 1], 1.0);
        P->tris += zip_trial(P, tout[3], k[3], vb + 1, nv - 2, 0, 0.0, ub[1]);
        P->tris += zip_trial(P, tout[1], k[1], vb + 1, nv - 2, 0, ub[nu - 1], 1.0);
        i0 = j0 = 1;
        i1 = nu - 1;
        j1 = nv - 1;
    }
    if (i1 > i0 && j1 > j0) {
        /* lo and hi never decrease along the lines and one of them grows at each new group:
         * at most 2S - 1 groups */
        int ulo[2 * S + 2], uhi[2 * S + 2], vlo[2 * S + 2], vhi[2 * S + 2], nru, nrv;
        double uw[2 * S + 2], vw[2 * S + 2];
        group_cells(ub, i0, i1, ulo, uhi, uw, &nru);
        group_cells(vb, j0, j1, vlo, vhi, vw, &nrv);
        for (int gv = 0; gv < nrv; ++gv) {
            double own[S][3];
            double(*band)[3] = row_band(P, vlo[gv], vhi[gv], own);
            for (int gu = 0; gu < nru; ++gu) {
                double m[3];
                range_max(band, ulo[gu], uhi[gu], m);
                account(P, m, uw[gu], vw[gv]);
            }
        }
        P->tris += 2 * (size_t)(i1 - i0) * (size_t)(j1 - j0);
    }
    if (P->abort_over > 0.0 && P->bound > P->abort_over) P->aborted = 1;
    t_free(P->mesh, tbuf);
    return CJ_OK;
}
