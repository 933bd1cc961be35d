/* The tessellation entry points: argument checks, the loop over patches (uniform, or planned
 * then adaptive), the planning pass that gives every shared side one segment count (watertight),
 * the size prediction, and the grid of a parametric surface. See tessellate.h for the rules and
 * the proof of the bound; the pieces live in tessellate_bounds.c, tessellate_build.c and
 * tessellate_adaptive.c. */
#include "casteljau/tessellate.h"
#include "alloc_internal.h"
#include "error_internal.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A patch side for finding shared edges: its control points in canonical order. */
typedef struct side_ref {
    const cj_patch *p;
    int first, step, count, reversed;
    size_t slot; /* 4 * patch + side */
} side_ref;

static const double *side_point(const side_ref *r, int a, double *w) {
    const int i = r->first + r->step * (r->reversed ? r->count - 1 - a : a);
    *w = r->p->weights ? r->p->weights[i] : 1.0;
    return r->p->pts + 3 * i;
}

/* Same comparison as cj_tess_edge_setup's canonical order: equal iff the two sides would evaluate
 * their points from identical control sequences. */
static int cmp_side_points(const side_ref *a, const side_ref *b) {
    if (a->count != b->count) return a->count < b->count ? -1 : 1;
    for (int i = 0; i < a->count; ++i) {
        double wa, wb;
        const double *pa = side_point(a, i, &wa), *pb = side_point(b, i, &wb);
        const int c = cj_tess_cmp_point(pa, wa, pb, wb);
        if (c) return c;
    }
    return 0;
}

static int cmp_side_ref(const void *x, const void *y) {
    const side_ref *a = x, *b = y;
    const int c = cmp_side_points(a, b);
    if (c) return c;
    return a->slot < b->slot ? -1 : (a->slot > b->slot ? 1 : 0);
}

cj_status cj_tess_plan_patch(ptess *P, const cj_patch *p, size_t q, double tol, int cap,
                             cj_mesh *mesh, tess_plan *plan, size_t *builds, size_t *trials) {
    const size_t vs = mesh->vertex_count, ts = mesh->triangle_count;
    cj_tess_setup(P, p, q, mesh, 0);
    P->planning = 1;
    plan->dens.valid = 0;
    const cj_status st =
        cj_tess_adaptive_patch(P, tol, cap, q, NULL, NULL, &plan->dens, plan->k, &plan->g);
    *builds += P->builds;
    *trials += P->trials;
    cj_mesh_truncate(mesh, vs, ts);
    return st;
}

cj_status cj_tess_share_counts(const cj_patch *patches, size_t count, int *k,
                               const cj_allocator *alloc) {
    if (count == 0) return CJ_OK;
    if (count > SIZE_MAX / (4 * sizeof(side_ref))) return cj_fail(CJ_ERR_NOMEM, "out of memory");
    side_ref *refs = cj_allocator_alloc(alloc, sizeof *refs * 4 * count);
    if (!refs) return cj_fail(CJ_ERR_NOMEM, "out of memory sharing %zu patches' sides", count);
    size_t nr = 0;
    for (size_t i = 0; i < count; ++i)
        for (int s = 0; s < 4; ++s) {
            edge_info e;
            cj_tess_edge_setup(&patches[i], s, &e);
            if (e.collapsed) continue;
            side_ref *r = &refs[nr++];
            r->p = &patches[i];
            cj_patch_edge_indices(patches[i].deg_u, patches[i].deg_v, s, &r->first, &r->step,
                                  &r->count);
            r->reversed = e.reversed;
            r->slot = 4 * i + (size_t)s;
        }
    qsort(refs, nr, sizeof *refs, cmp_side_ref);
    for (size_t a = 0; a < nr;) {
        size_t b = a + 1;
        int kmax = k[refs[a].slot];
        while (b < nr && cmp_side_points(&refs[a], &refs[b]) == 0) {
            if (k[refs[b].slot] > kmax) kmax = k[refs[b].slot];
            ++b;
        }
        for (size_t c = a; c < b; ++c) k[refs[c].slot] = kmax;
        a = b;
    }
    cj_allocator_free(alloc, refs);
    return CJ_OK;
}

cj_status cj_tess_build_planned(ptess *P, const cj_patch *p, size_t q, double tol, int cap,
                                int measure, const int k[4], tess_plan *plan, cj_mesh *mesh,
                                grid *used, size_t *builds, size_t *trials) {
    cj_tess_setup(P, p, q, mesh, measure);
    const size_t vq = mesh->vertex_count, tq = mesh->triangle_count;
    int kused[4];
    *used = (grid){0, 0, 0};
    cj_status st = cj_tess_adaptive_patch(P, tol, cap, q, k, &plan->g, &plan->dens, kused, used);
    *builds += P->builds;
    *trials += P->trials;
    if (!st && mesh->triangle_count == tq)
        st = cj_fail(CJ_ERR_DEGENERATE,
                     "patch %zu is degenerate: its surface has no area (every triangle "
                     "collapses to a point or a curve)",
                     q);
    if (st) cj_mesh_truncate(mesh, vq, tq); /* no partial or failing build of this patch stays */
    return st;
}

cj_status cj_tessellate_patches(const cj_patch *patches, size_t count, const cj_tess_options *opt,
                                cj_mesh *mesh, cj_tess_report *report) {
    assert(opt != NULL && mesh != NULL);
    assert(patches != NULL || count == 0);
    cj_tess_report rep;
    memset(&rep, 0, sizeof rep);
    rep.measured = opt->measure > 0 ? 0.0 : -1.0;
    if (opt->uniform < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "uniform segment count %d is negative", opt->uniform);
    if (opt->measure < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "measure lattice %d is negative", opt->measure);
    if (opt->max_segments < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "max_segments %d is negative", opt->max_segments);
    const int cap = opt->max_segments ? opt->max_segments : CJ_TESS_DEFAULT_MAX_SEGMENTS;
    if (opt->uniform == 0) {
        if (!isfinite(opt->tol)) return cj_fail(CJ_ERR_NONFINITE, "tolerance is not finite");
        if (!(opt->tol > 0.0))
            return cj_fail(CJ_ERR_ARGUMENT, "tolerance %.17g must be > 0", opt->tol);
    } else if (opt->uniform > cap) {
        return cj_fail(CJ_ERR_CAP, "uniform count %d exceeds the cap of %d segments", opt->uniform,
                       cap);
    }
    for (size_t q = 0; q < count; ++q) {
        cj_status st = cj_patch_check(&patches[q]);
        if (st) return cj_fail(st, "patch %zu: %s", q, cj_last_error());
    }
    const int adaptive = opt->uniform == 0;
    ptess *P = t_alloc(mesh, sizeof *P);
    double *br = adaptive ? NULL : t_alloc(mesh, sizeof(double) * (size_t)(opt->uniform + 1));
    const int fits = count <= SIZE_MAX / (4 * sizeof(tess_plan)); /* sizes below cannot wrap */
    tess_plan *plan = adaptive && count && fits ? t_alloc(mesh, sizeof *plan * count) : NULL;
    int *kshared = adaptive && count && fits ? t_alloc(mesh, sizeof(int) * 4 * count) : NULL;
    if (!P || (!adaptive && !br) || (adaptive && count && (!plan || !kshared))) {
        t_free(mesh, P);
        t_free(mesh, br);
        t_free(mesh, plan);
        t_free(mesh, kshared);
        return cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    if (br)
        for (int i = 0; i <= opt->uniform; ++i) br[i] = (double)i / (double)opt->uniform;
    const size_t v_start = mesh->vertex_count, t_start = mesh->triangle_count;
    cj_status st = CJ_OK, plan_st = CJ_OK;
    size_t todo = count;
    if (adaptive) { /* patches after a planning failure are not built */
        size_t q = 0;
        for (; q < count; ++q) {
            plan_st = cj_tess_plan_patch(P, &patches[q], q, opt->tol, cap, mesh, &plan[q],
                                         &rep.builds, &rep.trials);
            if (plan_st) break;
            memcpy(kshared + 4 * q, plan[q].k, sizeof plan[q].k);
        }
        todo = q;
        if (plan_st == CJ_ERR_NOMEM) todo = 0;
        const cj_status sh = cj_tess_share_counts(patches, todo, kshared, &mesh->alloc_);
        if (sh) {
            plan_st = sh;
            todo = 0;
        }
    }
    for (size_t q = 0; q < todo && !st; ++q) {
        grid g = {0, 0, 0};
        if (!adaptive) {
            cj_tess_setup(P, &patches[q], q, mesh, opt->measure);
            const size_t vq = mesh->vertex_count, tq = mesh->triangle_count;
            const int k[4] = {opt->uniform, opt->uniform, opt->uniform, opt->uniform};
            g.nu = g.nv = opt->uniform;
            st = cj_tess_build_patch(P, g.nu, br, g.nv, br, k);
            rep.builds += P->builds;
            if (!st && mesh->triangle_count == tq)
                st = cj_fail(CJ_ERR_DEGENERATE,
                             "patch %zu is degenerate: its surface has no area (every triangle "
                             "collapses to a point or a curve)",
                             q);
            if (st) cj_mesh_truncate(mesh, vq, tq);
        } else {
            st = cj_tess_build_planned(P, &patches[q], q, opt->tol, cap, opt->measure,
                                       kshared + 4 * q, &plan[q], mesh, &g, &rep.builds,
                                       &rep.trials);
        }
        if (st) break;
        rep.bound = fmax(rep.bound, P->bound);
        if (opt->measure > 0 && P->measured > rep.measured) rep.measured = P->measured;
        rep.dropped += P->dropped;
        if (g.nu > rep.max_nu) rep.max_nu = g.nu;
        if (g.nv > rep.max_nv) rep.max_nv = g.nv;
    }
    if (!st) st = plan_st;
    t_free(mesh, P);
    t_free(mesh, br);
    t_free(mesh, plan);
    t_free(mesh, kshared);
    rep.vertices = mesh->vertex_count - v_start;
    rep.triangles = mesh->triangle_count - t_start;
    if (report) *report = rep;
    return st;
}

cj_status cj_tessellate_predict(const cj_patch *patches, size_t count, const cj_tess_options *opt,
                                double *triangles) {
    assert(opt != NULL && triangles != NULL);
    assert(patches != NULL || count == 0);
    if (opt->uniform < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "uniform segment count %d is negative", opt->uniform);
    for (size_t q = 0; q < count; ++q) {
        cj_status st = cj_patch_check(&patches[q]);
        if (st) return cj_fail(st, "patch %zu: %s", q, cj_last_error());
    }
    if (opt->uniform > 0) {
        *triangles = 2.0 * (double)opt->uniform * (double)opt->uniform * (double)count;
        return CJ_OK;
    }
    if (!isfinite(opt->tol)) return cj_fail(CJ_ERR_NONFINITE, "tolerance is not finite");
    if (!(opt->tol > 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "tolerance %.17g must be > 0", opt->tol);
    cj_mesh *scratch = NULL;
    cj_status st = cj_mesh_create(NULL, &scratch);
    ptess *P = st ? NULL : malloc(sizeof *P);
    if (!P) {
        cj_mesh_destroy(scratch);
        return cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    double total = 0.0;
    for (size_t q = 0; q < count; ++q) {
        double rho_u[CJ_TESS_SLABS], rho_v[CJ_TESS_SLABS], bu, bv;
        cj_tess_setup(P, &patches[q], q, scratch, 0);
        cj_tess_patch_densities(P, opt->tol, rho_u, rho_v, &bu, &bv);
        /* the search starts here; its minimum is 2 x 2 cells */
        total += 2.0 * fmax(2.0, ceil(bu)) * fmax(2.0, ceil(bv));
    }
    free(P);
    cj_mesh_destroy(scratch);
    *triangles = total;
    return CJ_OK;
}

/* ---- parametric surfaces ------------------------------------------------------------- */

cj_status cj_tessellate_surface(const cj_param_surface *s, int nu, int nv, int32_t id,
                                cj_mesh *mesh, size_t *dropped) {
    assert(s != NULL && mesh != NULL);
    cj_status st = cj_param_surface_check(s);
    if (st) return st;
    const int pu = (s->flags & CJ_SURF_PERIODIC_U) != 0, pv = (s->flags & CJ_SURF_PERIODIC_V) != 0;
    if (nu < (pu ? 3 : 1) || nv < (pv ? 3 : 1))
        return cj_fail(CJ_ERR_ARGUMENT, "grid %d x %d too small (need >= %d x %d)", nu, nv,
                       pu ? 3 : 1, pv ? 3 : 1);
    const size_t nvert = (size_t)(nu + 1) * (size_t)(nv + 1);
    uint32_t *idx = t_alloc(mesh, sizeof(uint32_t) * nvert);
    if (!idx) return cj_fail(CJ_ERR_NOMEM, "out of memory tessellating a surface");
    const size_t v_start = mesh->vertex_count, t_start = mesh->triangle_count;
    const unsigned f = s->flags;
    size_t drop = 0;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            int si = i, sj = j; /* the grid point whose vertex this one shares */
            if (pu && i == nu) si = 0;
            if (pv && j == nv) sj = 0;
            if ((f & CJ_SURF_COLLAPSED_V0) && sj == 0) si = 0;
            if ((f & CJ_SURF_COLLAPSED_V1) && sj == nv) si = 0;
            if ((f & CJ_SURF_COLLAPSED_U0) && si == 0) sj = 0;
            if ((f & CJ_SURF_COLLAPSED_U1) && si == nu) sj = 0;
            if (si != i || sj != j) {
                idx[j * (nu + 1) + i] = idx[sj * (nu + 1) + si];
                continue;
            }
            const double u = i == nu ? s->u1 : s->u0 + (s->u1 - s->u0) * ((double)i / nu);
            const double v = j == nv ? s->v1 : s->v0 + (s->v1 - s->v0) * ((double)j / nv);
            cj_vec3 p, n;
            if ((st = cj_surface_eval(s, u, v, &p, NULL, NULL))) goto fail;
            if ((st = cj_surface_normal(s, u, v, &n))) n = cj_v3(0.0, 0.0, 0.0);
            const double pos[3] = {p.x, p.y, p.z}, nrm[3] = {n.x, n.y, n.z}, uv[2] = {u, v};
            if ((st = cj_mesh_add_vertex(mesh, pos, nrm, uv, &idx[j * (nu + 1) + i]))) goto fail;
        }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const uint32_t A = idx[j * (nu + 1) + i], B = idx[j * (nu + 1) + i + 1],
                           C = idx[(j + 1) * (nu + 1) + i + 1], D = idx[(j + 1) * (nu + 1) + i];
            const uint32_t tri[2][3] = {{A, B, C}, {A, C, D}};
            for (int q = 0; q < 2; ++q) {
                const uint32_t a = tri[q][0], b = tri[q][1], c = tri[q][2];
                if (a == b || b == c || a == c ||
                    same_pos(mesh->positions + 3 * (size_t)a, mesh->positions + 3 * (size_t)b) ||
                    same_pos(mesh->positions + 3 * (size_t)b, mesh->positions + 3 * (size_t)c) ||
                    same_pos(mesh->positions + 3 * (size_t)a, mesh->positions + 3 * (size_t)c)) {
                    ++drop;
                    continue;
                }
                if ((st = cj_mesh_add_triangle(mesh, a, b, c, id))) goto fail;
            }
        }
    t_free(mesh, idx);
    if (dropped) *dropped = drop;
    return CJ_OK;
fail:
    t_free(mesh, idx);
    cj_mesh_truncate(mesh, v_start, t_start);
    return st;
}
