/* The adaptive grid search for one patch: slab densities, equidistributed grid lines, and the
 * search over grid scales (then uniform grids) for the build with the fewest triangles whose
 * proven bound meets the tolerance. */
#include "casteljau/tessellate.h"
#include "error_internal.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <math.h>
#include <string.h>

/* Breakpoints 0 = b[0] < ... < b[cnt] = 1 equidistributing the piecewise constant density
 * rho[0..S-1] on S equal slabs (uniform where the density vanishes everywhere). */
static void equidistribute(const double *rho, int S, int cnt, double *b) {
    double total = 0.0;
    for (int a = 0; a < S; ++a) total += rho[a] / S;
    b[0] = 0.0;
    b[cnt] = 1.0;
    if (!(total > 0.0)) {
        for (int i = 1; i < cnt; ++i) b[i] = (double)i / cnt;
        return;
    }
    int a = 0;
    double acc = 0.0;
    for (int i = 1; i < cnt; ++i) {
        const double target = total * i / cnt;
        while (a < S - 1 && acc + rho[a] / S < target) {
            acc += rho[a] / S;
            ++a;
        }
        double x = rho[a] > 0.0 ? (double)a / S + (target - acc) / rho[a] : (double)(a + 1) / S;
        if (x > (double)(a + 1) / S) x = (double)(a + 1) / S;
        b[i] = x;
    }
    for (int i = 1; i < cnt; ++i) /* strictly increasing */
        if (!(b[i] > b[i - 1]) || !(b[i] < 1.0)) b[i] = b[i - 1] + (1.0 - b[i - 1]) / (cnt - i + 1);
}

/* Side counts of one build: a collapsed side follows the grid of its direction; otherwise the
 * fixed count kfix[e] or, when planning (kfix NULL), the larger of the edge-flatness count
 * ke[e] and the grid count along that side, so that the zipper triangles next to the side are
 * no wider than the grid cells there (a straight edge across which the patch twists needs as
 * many segments as the interior, or its slivers force the whole interior finer). */
static void side_counts(const ptess *P, const int ke[4], const int *kfix, int nu, int nv,
                        int k[4]) {
    for (int e = 0; e < 4; ++e) {
        const int ng = (e & 1) ? nv : nu;
        if (P->e[e].collapsed)
            k[e] = ng;
        else if (kfix)
            k[e] = kfix[e];
        else
            k[e] = ke[e] > ng ? ke[e] : ng;
    }
}

/* Tries grid g with side counts k; *pass receives whether the proven bound is <= tol and
 * P->tris its triangle count. A polynomial patch's trial is bounds-only (nothing evaluated or
 * added to the mesh) unless `real`; a rational patch's bound needs its vertices, so its trials
 * are builds. A build stays in the mesh (replacing whatever was there after vs, ts). */
static cj_status try_grid(ptess *P, const double *rho_u, const double *rho_v, grid g,
                          const int k[4], double tol, size_t q, size_t vs, size_t ts, int real,
                          const double *known, int *pass) {
    static const double flat[CJ_TESS_SLABS]; /* zero density: uniform lines */
    const int nu = g.nu, nv = g.nv;
    double *ub = t_alloc(P->mesh, sizeof(double) * (size_t)(nu + 1));
    double *vb = t_alloc(P->mesh, sizeof(double) * (size_t)(nv + 1));
    cj_status st = CJ_OK;
    if (!ub || !vb) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory tessellating patch %zu", q);
    } else {
        equidistribute(g.uni ? flat : rho_u, CJ_TESS_SLABS, nu, ub);
        equidistribute(g.uni ? flat : rho_v, CJ_TESS_SLABS, nv, vb);
        /* planning a rational patch: the bound is predicted, not proven (its build proves it) */
        P->predict = !real && P->planning && P->pm != NULL;
        P->bounds_only = !real && (!P->rational || P->predict);
        /* the build of a grid whose bounds-only trial passed: the same triangles, hence the
         * same bound (known[0], worst terms known[1..3]); not recomputed */
        P->bound_known = known != NULL && !P->rational;
        if (!P->bounds_only) cj_mesh_truncate(P->mesh, vs, ts);
        P->abort_over = tol; /* a failing build is never kept: stop it early */
        if (!real && !P->rational && P->pm)
            st = cj_tess_slab_trial(P, nu, ub, nv, vb, k); /* the same bound, without triangles */
        else
            st = cj_tess_build_patch(P, nu, ub, nv, vb, k);
        P->abort_over = 0.0;
        P->bounds_only = 0;
        P->predict = 0;
        if (P->bound_known) {
            P->bound = known[0];
            memcpy(P->worst_terms, known + 1, 3 * sizeof(double));
            P->bound_known = 0;
        }
        *pass = !st && !P->aborted && P->bound <= tol;
    }
    t_free(P->mesh, ub);
    t_free(P->mesh, vb);
    return st;
}

/* The bound of the last (bounds-only, passing) trial, for building the same grid later. */
static void keep_known(const ptess *P, double known[4]) {
    known[0] = P->bound;
    memcpy(known + 1, P->worst_terms, 3 * sizeof(double));
}

/* The polynomial patch's proven bounds per slab cell (P->pm, for planning's trials): the 16
 * strips restricted and walked once. */
static void slab_table(ptess *P) {
    const int S = CJ_TESS_SLABS, S2 = CJ_TESS_SLABS * CJ_TESS_SLABS;
    const int walk = cj_tess_walkable(P);
    for (int b = 0; b < S; ++b) {
        cj_tess_strip_restrict(P, (double)b / S, (double)(b + 1) / S, &P->strip);
        if (walk) cj_tess_line(P, &P->strip, 0.0, &P->lines[0]);
        for (int a = 0; a < S; ++a) {
            dbounds cb;
            if (walk) {
                tess_line *A = &P->lines[a & 1], *B = &P->lines[(a + 1) & 1];
                cj_tess_line(P, &P->strip, (double)(a + 1) / S, B);
                cb = cj_tess_cell_walk(P, A, B);
            } else {
                cb = cj_tess_cell_bounds(P, &P->strip, (double)a / S, (double)(a + 1) / S);
            }
            P->pm[b * S + a] = cb.uu;
            P->pm[S2 + b * S + a] = cb.uv;
            P->pm[2 * S2 + b * S + a] = cb.vv;
        }
    }
    P->bands_valid = 0;
}

/* Grid densities of the set-up patch: sqrt of the second-derivative bound on CJ_TESS_SLABS slabs
 * per direction (the mixed term counts in both, so a straight direction is still refined where it
 * twists), and the cell counts of the search's starting grid for tol (base_u, base_v). */
void cj_tess_patch_densities(ptess *P, double tol, double *rho_u, double *rho_v, double *base_u,
                             double *base_v) {
    {
        double su = 0.0, sv = 0.0;
        if (P->rational) {
            /* densities only shape the grid (the bound is checked per triangle): per cell of
             * CJ_TESS_SLABS x CJ_TESS_SLABS, the smaller of the largest |S_uu|, |S_uv|, |S_vv|
             * sampled at its corners and centre and of the homogeneous bound's M's */
            enum { S = CJ_TESS_SLABS, S1 = CJ_TESS_SLABS + 1 };
            for (int a = 0; a < S; ++a) rho_u[a] = rho_v[a] = 0.0;
            /* |S_uu|, |S_uv|, |S_vv| at the slab corners (each shared by up to four cells) */
            double corner[S1 * S1][3];
            for (int b = 0; b <= S; ++b)
                for (int a = 0; a <= S; ++a) {
                    double d[27];
                    cj_patch_derivs_unchecked(P->p, P->h, 4, (double)a / S, (double)b / S, 2, 2, d);
                    double *c = corner[b * S1 + a];
                    c[0] = sqrt(d[18] * d[18] + d[19] * d[19] + d[20] * d[20]);
                    c[1] = sqrt(d[12] * d[12] + d[13] * d[13] + d[14] * d[14]);
                    c[2] = sqrt(d[6] * d[6] + d[7] * d[7] + d[8] * d[8]);
                }
            for (int a = 0; a < CJ_TESS_SLABS; ++a)
                for (int b = 0; b < CJ_TESS_SLABS; ++b) {
                    double fu = 0.0, fv = 0.0, qb[4], muu = 0.0, muv = 0.0, mvv = 0.0;
                    cj_patch_sub_h(P->h, 4, P->m, P->n, (double)a / CJ_TESS_SLABS,
                                   (double)(a + 1) / CJ_TESS_SLABS, (double)b / CJ_TESS_SLABS,
                                   (double)(b + 1) / CJ_TESS_SLABS, P->trinet);
                    cj_tess_homog_bounds(P, P->trinet, qb);
                    double centre[27];
                    cj_patch_derivs_unchecked(P->p, P->h, 4, (a + 0.5) / S, (b + 0.5) / S, 2, 2,
                                              centre);
                    for (int o = 0; o < 5; ++o) { /* its four corners and its centre */
                        /* o = 4 is the centre: no corner row exists for it (b + 2) */
                        const double *c = o < 4 ? corner[(b + (o >> 1)) * S1 + a + (o & 1)] : NULL;
                        const double *d = centre;
                        const double suu =
                            o < 4 ? c[0] : sqrt(d[18] * d[18] + d[19] * d[19] + d[20] * d[20]);
                        const double suv =
                            o < 4 ? c[1] : sqrt(d[12] * d[12] + d[13] * d[13] + d[14] * d[14]);
                        const double svv =
                            o < 4 ? c[2] : sqrt(d[6] * d[6] + d[7] * d[7] + d[8] * d[8]);
                        fu = fmax(fu, sqrt(fmax(suu, suv)));
                        fv = fmax(fv, sqrt(fmax(svv, suv)));
                        muu = fmax(muu, suu);
                        muv = fmax(muv, suv);
                        mvv = fmax(mvv, svv);
                    }
                    if (P->pm) {
                        const int cell = b * CJ_TESS_SLABS + a, S2 = CJ_TESS_SLABS * CJ_TESS_SLABS;
                        const double s2 = (double)CJ_TESS_SLABS * CJ_TESS_SLABS;
                        P->pm[cell] = muu;
                        P->pm[S2 + cell] = muv;
                        P->pm[2 * S2 + cell] = mvv;
                        P->pm[3 * S2 + cell] = qb[0] * s2; /* local to patch parameters */
                        P->pm[4 * S2 + cell] = qb[1] * s2;
                        P->pm[5 * S2 + cell] = qb[2] * s2;
                        if (a == 0 && b == 0) P->pm[6 * S2] = 0.0;
                        P->pm[6 * S2] = fmax(P->pm[6 * S2], qb[3]);
                    }
                    /* the bound kept is the smaller of the two (cj_tess_rational_tri_bound) */
                    rho_u[a] = fmax(rho_u[a], fmin(fu, CJ_TESS_SLABS * sqrt(fmax(qb[0], qb[1]))));
                    rho_v[b] = fmax(rho_v[b], fmin(fv, CJ_TESS_SLABS * sqrt(fmax(qb[2], qb[1]))));
                }
        } else {
            if (P->pm) slab_table(P);
            for (int a = 0; a < CJ_TESS_SLABS; ++a) {
                const dbounds bu = cj_tess_strip_bounds(P, (double)a / CJ_TESS_SLABS,
                                                        (double)(a + 1) / CJ_TESS_SLABS, 0.0, 1.0);
                const dbounds bv = cj_tess_strip_bounds(P, 0.0, 1.0, (double)a / CJ_TESS_SLABS,
                                                        (double)(a + 1) / CJ_TESS_SLABS);
                rho_u[a] = sqrt(fmax(bu.uu, bu.uv));
                rho_v[a] = sqrt(fmax(bv.vv, bv.uv));
            }
        }
        for (int a = 0; a < CJ_TESS_SLABS; ++a) {
            su += rho_u[a] / CJ_TESS_SLABS;
            sv += rho_v[a] / CJ_TESS_SLABS;
        }
        *base_u = su / sqrt(4.0 * tol);
        *base_v = sv / sqrt(4.0 * tol);
    }
}

/* Adaptive choice for one patch. Interior: a grid of nu x nv cells whose lines equidistribute
 * the slab densities, nu = ceil(s base_u), nv = ceil(s base_v), with the scale s the smallest
 * (found by growing, then bisection) for which the per-triangle bound is <= tol; then uniform
 * K x K grids with fewer triangles than that build are tried (smallest passing K by
 * bisection), so a patch never gets more triangles than the uniform grid its sides allow.
 * Sides: when planning (kfix NULL) each build uses side_counts() and kout receives the counts
 * of the kept build; otherwise the counts kfix are imposed and the grid *hint (nu >= 2) is
 * tried first. The mesh then holds the passing build with the fewest triangles (when planning:
 * some build, to be truncated); *out is that grid. */
cj_status cj_tess_adaptive_patch(ptess *P, double tol, int cap, size_t q, const int *kfix,
                                 const grid *hint, tess_density *dens, int kout[4], grid *out) {
    int ke[4];
    for (int s = 0; s < 4; ++s) {
        ke[s] = P->e[s].collapsed
                    ? 0
                    : cj_tess_edge_segments(P->e[s].pts, P->e[s].degree, 0.25 * tol, cap);
        if (ke[s] > cap)
            return cj_fail(CJ_ERR_CAP,
                           "patch %zu, edge %d needs more than %d segments for tolerance %.3g", q,
                           s, cap, tol);
    }
    /* grid densities: see cj_tess_patch_densities */
    if (!kfix) dens->known_valid = 0;
    /* the prediction tables are needed by planning's trials only: filled with the densities
     * (planning always computes them) in the patch's scratch, not kept in the plan */
    P->pm = !dens->valid ? P->pmbuf : NULL;
    if (!dens->valid) {
        cj_tess_patch_densities(P, tol, dens->rho_u, dens->rho_v, &dens->base_u, &dens->base_v);
        dens->valid = 1;
    }
    const double base_u = dens->base_u, base_v = dens->base_v;
    const double *rho_u = dens->rho_u, *rho_v = dens->rho_v;
    const size_t vs = P->mesh->vertex_count, ts = P->mesh->triangle_count;
    cj_status st = CJ_OK;
    int k[4];
    if (kfix && hint && hint->nu >= 2 && hint->nv >= 2) {
        int pass = 0;
        side_counts(P, ke, kfix, hint->nu, hint->nv, k);
        if (dens->known_valid && memcmp(k, dens->known_k, sizeof k) == 0) {
            /* the planned grid with the planned counts (no neighbour raised one): planning's
             * passing trial computed this build's bound */
            st = try_grid(P, rho_u, rho_v, *hint, k, tol, q, vs, ts, 1, dens->known, &pass);
        } else {
            if (!P->rational) {
                /* a neighbour raised a side count: the slab table's trial first (proven, and
                 * about 1/5 of the cost of the walked cells' trial); if it misses tol, the
                 * walked cells' exact trial decides, so the table alone never refines a patch */
                P->pm = P->pmbuf;
                slab_table(P);
                if ((st = try_grid(P, rho_u, rho_v, *hint, k, tol, q, vs, ts, 0, NULL, &pass)))
                    return st;
                P->pm = NULL;
            }
            if (!pass && (st = try_grid(P, rho_u, rho_v, *hint, k, tol, q, vs, ts, 0, NULL, &pass)))
                return st;
            if (pass && !P->rational) { /* the bounds-only trial passed: build it once */
                const double known[4] = {P->bound, P->worst_terms[0], P->worst_terms[1],
                                         P->worst_terms[2]};
                st = try_grid(P, rho_u, rho_v, *hint, k, tol, q, vs, ts, 1, known, &pass);
            }
        }
        if (st) return st;
        grid g = *hint;
        /* a rational patch's plan was predicted (not proven): when its build misses tol, grow
         * the grid by the bound's 1/s^2 law (at least 10%) a few times before searching */
        for (int retry = 0; !pass && P->rational && retry < 3; ++retry) {
            const double excess = P->bound - P->verterr, room = tol - P->verterr;
            double f = room > 0.0 && excess > 0.0 ? 1.02 * sqrt(excess / room) : 2.0;
            if (!(f >= 1.1)) f = 1.1;
            if (f > 4.0) f = 4.0;
            g.nu = (int)ceil(f * g.nu);
            g.nv = (int)ceil(f * g.nv);
            if (g.nu > cap || g.nv > cap) break;
            side_counts(P, ke, kfix, g.nu, g.nv, k);
            if ((st = try_grid(P, rho_u, rho_v, g, k, tol, q, vs, ts, 1, NULL, &pass))) return st;
        }
        if (pass) {
            *out = g;
            memcpy(kout, k, sizeof k);
            return CJ_OK;
        }
    }
    double lo = 0.0, hi = 0.0, s = 1.0;
    grid best = {0, 0, 0}, last = {-1, -1, 0};
    size_t best_tris = (size_t)-1;
    double best_known[4] = {0.0, 0.0, 0.0, 0.0};
    int last_pass = 0;
    double last_bound = 0.0;
    for (int iter = 0; iter < 60; ++iter) {
        int nu = (int)fmin(ceil(s * base_u), (double)cap + 1.0);
        int nv = (int)fmin(ceil(s * base_v), (double)cap + 1.0);
        if (nu < 2) nu = 2;
        if (nv < 2) nv = 2;
        if (nu > cap || nv > cap) {
            if (best.nu) break; /* a finer passing build exists */
            st = cj_fail(CJ_ERR_CAP,
                         "patch %zu needs more than %d segments per direction for tolerance %.3g",
                         q, cap, tol);
            break;
        }
        int pass;
        if (nu == last.nu && nv == last.nv) {
            pass = last_pass;
            if (lo > 0.0 && hi > 0.0) break; /* the bracket no longer changes the grid */
        } else {
            const grid g = {nu, nv, 0};
            side_counts(P, ke, kfix, nu, nv, k);
            if ((st = try_grid(P, rho_u, rho_v, g, k, tol, q, vs, ts, 0, NULL, &pass))) break;
            const size_t tris = P->tris;
            if (pass && tris < best_tris) {
                best_tris = tris;
                best = g;
                keep_known(P, best_known);
            }
            last = g;
            last_pass = pass;
            last_bound = P->bound;
        }
        if (pass)
            hi = s;
        else
            lo = s;
        /* the bound is about evalerr + C / s^2: the scale where it would meet tol (a failing
         * trial stops at its first triangle over tol, so its bound only says "at least") */
        const double excess = last_bound - P->evalerr, room = tol - P->evalerr;
        const double pred = room > 0.0 && excess > 0.0 ? s * sqrt(excess / room) : 2.0 * s;
        if (hi == 0.0) /* no passing scale yet: grow to the prediction, at least 5% */
            s = fmax(1.05 * s, 1.02 * pred);
        else if (lo == 0.0 && iter < 8 && pred < 0.97 * hi) /* passing: shrink towards it */
            s = fmax(1.01 * pred, 0.6 * hi);
        else if (lo > 0.0 && hi - lo > 0.03 * hi)
            s = 0.5 * (lo + hi);
        else
            break; /* within 3% of the predicted or bracketed smallest passing scale */
    }
    if (!st && best.nu == 0)
        st = cj_fail(CJ_ERR_CAP, "patch %zu: no grid met tolerance %.3g", q, tol);
    if (!st && best_tris == 0) /* every triangle collapsed: nothing to search for */
        st = cj_fail(CJ_ERR_DEGENERATE,
                     "patch %zu is degenerate: its surface has no area (every triangle "
                     "collapses to a point or a curve)",
                     q);
    if (!st) {
        /* uniform K x K grids with fewer than best_tris triangles: the largest such K first;
         * if it passes, bisect for the smallest passing K (the bound decreases with K) */
        int khi = (int)floor(sqrt((double)(best_tris - 1) / 2.0));
        if (khi > cap) khi = cap;
        int klo = 1; /* klo fails (or is below the minimum 2), khi passes */
        int probe = khi;
        while (probe >= 2 && probe > klo) {
            const grid g = {probe, probe, 1};
            int pass;
            side_counts(P, ke, kfix, probe, probe, k);
            if ((st = try_grid(P, rho_u, rho_v, g, k, tol, q, vs, ts, 0, NULL, &pass))) break;
            const size_t tris = P->tris;
            last = g;
            if (pass && tris < best_tris) {
                best_tris = tris;
                best = g;
                keep_known(P, best_known);
            }
            if (!pass) {
                if (probe == khi) break; /* no uniform grid that small passes */
                klo = probe;
            } else {
                khi = probe;
            }
            probe = (klo + khi) / 2;
            if (probe == klo) break;
        }
    }
    side_counts(P, ke, kfix, best.nu, best.nv, k);
    /* build the best grid unless only planning (kfix NULL) or (a rational patch) it is the
     * last build; deterministic: it passes again */
    if (!st && kfix &&
        (!P->rational || best.nu != last.nu || best.nv != last.nv || best.uni != last.uni)) {
        int pass;
        st = try_grid(P, rho_u, rho_v, best, k, tol, q, vs, ts, 1, P->rational ? NULL : best_known,
                      &pass);
    }
    if (!st && !kfix && !P->rational && best.nu) { /* for the build of this plan */
        memcpy(dens->known, best_known, sizeof best_known);
        memcpy(dens->known_k, k, sizeof k);
        dens->known_valid = 1;
    }
    *out = best;
    memcpy(kout, k, sizeof k);
    return st;
}
