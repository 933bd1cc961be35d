/* Vertices of a patch's grid, column by column: the u stage of the tensor de Casteljau once per
 * grid column, then each vertex's v stage, and (polynomial patches) S_u, S_v and the normal
 * from the same levels, also for the normals of the side points. Split from tessellate_build.c,
 * which uses them. */
#include "casteljau/tessellate.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <math.h>
#include <string.h>

/* The u stage of the tensor de Casteljau (each row of the net at u): one per grid column, shared
 * by the column's vertices (the same operations as cj_patch_eval_h, in the same order). A
 * polynomial patch's column also gets the u-derivative of each row, m (w1 - w0) from the last
 * level (dcol, n+1 points): S_u along the column. */
void cj_tess_eval_column(const ptess *P, double u, double *col, double *dcol) {
    const int m = P->m, n = P->n, hd = P->hd;
    const double s = 1.0 - u;
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    for (int j = 0; j <= n; ++j) {
        memcpy(w, P->h + (size_t)j * (size_t)(m + 1) * (size_t)hd,
               sizeof(double) * (size_t)((m + 1) * hd));
        for (int r = m; r > 0; --r) {
            if (r == 1 && hd == 3)
                for (int c = 0; c < 3; ++c) dcol[3 * j + c] = (double)m * (w[3 + c] - w[c]);
            for (int i = 0; i < r * hd; ++i) w[i] = s * w[i] + u * w[i + hd];
        }
        if (m == 0 && hd == 3)
            for (int c = 0; c < 3; ++c) dcol[3 * j + c] = 0.0;
        memcpy(col + j * hd, w, sizeof(double) * (size_t)hd);
    }
}

/* The v stage: the point of a column at v; for a polynomial patch also S_v (n (w1 - w0) from
 * the last level) into dv. */
void cj_tess_eval_in_column(const ptess *P, const double *col, double v, double out[3],
                            double dv[3]) {
    const int n = P->n, hd = P->hd;
    const double s = 1.0 - v;
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    memcpy(w, col, sizeof(double) * (size_t)((n + 1) * hd));
    if (n == 0 && hd == 3) dv[0] = dv[1] = dv[2] = 0.0;
    for (int r = n; r > 0; --r) {
        if (r == 1 && hd == 3)
            for (int c = 0; c < 3; ++c) dv[c] = (double)n * (w[3 + c] - w[c]);
        for (int i = 0; i < r * hd; ++i) w[i] = s * w[i] + v * w[i + hd];
    }
    if (hd == 4)
        for (int c = 0; c < 3; ++c) out[c] = w[c] / w[3];
    else
        memcpy(out, w, 3 * sizeof(double));
}

/* S_u of a polynomial patch at v along a column (its dcol). */
void cj_tess_eval_du(const ptess *P, const double *dcol, double v, double du[3]) {
    const int n = P->n;
    const double s = 1.0 - v;
    double w[(CJ_PATCH_MAX_DEGREE + 1) * 3];
    memcpy(w, dcol, sizeof(double) * (size_t)((n + 1) * 3));
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * 3; ++i) w[i] = s * w[i] + v * w[i + 3];
    memcpy(du, w, 3 * sizeof(double));
}

/* The unit normal at a grid vertex: S_u x S_v normalised where it is well conditioned (the
 * regular case of cj_patch_normal_unchecked, same test), else cj_patch_normal_unchecked. */
void cj_tess_grid_normal(const ptess *P, const double su[3], const double sv[3], double u, double v,
                         double nrm[3]) {
    if (P->hd == 3) {
        const double c[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2],
                             su[0] * sv[1] - su[1] * sv[0]};
        const double cn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        const double nu = sqrt(su[0] * su[0] + su[1] * su[1] + su[2] * su[2]);
        const double nv = sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
        if (cn > 64.0 * U_ROUND * nu * nv && cn > 0.0 && isfinite(cn)) {
            for (int k = 0; k < 3; ++k) nrm[k] = c[k] / cn;
            return;
        }
    }
    if (cj_patch_normal_unchecked(P->p, P->h, P->hd, u, v, nrm, NULL) != CJ_OK)
        nrm[0] = nrm[1] = nrm[2] = 0.0; /* a patch collapsed to a curve: no normal */
}

/* The normals of a polynomial patch's side points o[s][1..k[s]-1] (side parameters tout) as a
 * grid vertex's (cj_tess_grid_normal: S_u x S_v from the grid columns, the regular-case test of
 * cj_patch_normal_unchecked, which stays the fallback). Sides u = 0 and u = 1 are one column
 * each; a point of the sides v = 0 and v = 1 is its own column. */
void cj_tess_side_normals(ptess *P, uint32_t *const o[4], double *const tout[4], const int k[4],
                          double *col, double *dcol) {
    for (int s = 0; s < 4; ++s) {
        const int along_u = !(s & 1);
        const double fixed = s == 1 || s == 2 ? 1.0 : 0.0;
        if (!along_u) cj_tess_eval_column(P, fixed, col, dcol);
        for (int a = 1; a < k[s]; ++a) {
            const double t = tout[s][a], u = along_u ? t : fixed, v = along_u ? fixed : t;
            if (along_u) cj_tess_eval_column(P, u, col, dcol);
            double pt[3], su[3], sv[3];
            cj_tess_eval_in_column(P, col, v, pt, sv);
            cj_tess_eval_du(P, dcol, v, su);
            cj_tess_grid_normal(P, su, sv, u, v, P->mesh->normals + 3 * (size_t)o[s][a]);
        }
    }
}
