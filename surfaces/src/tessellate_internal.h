/* What the tessellation sources share: the per-patch state of a build, the bound types, and the
 * functions each file offers the others (bounds: tessellate_bounds.c; one build:
 * tessellate_build.c; the adaptive search: tessellate_adaptive.c; the entry points:
 * tessellate.c). */
#ifndef CASTELJAU_TESSELLATE_INTERNAL_H
#define CASTELJAU_TESSELLATE_INTERNAL_H

#include "casteljau/bezier.h"
#include "casteljau/mesh.h"
#include "casteljau/patch.h"
#include "alloc_internal.h"
#include "patch_internal.h"

#include <stddef.h>
#include <stdint.h>

#define U_ROUND CJ_UNIT_ROUNDOFF

/* Slabs per direction on which the grid densities are sampled. */
#define CJ_TESS_SLABS 16
/* Planning a rational patch predicts a grid's bound from sampled second derivatives, times this
 * margin (the build then proves the bound; see tessellate_adaptive.c). */
#define CJ_TESS_PREDICT_MARGIN 1.0

/* Bounds on |S_uu|, |S_uv|, |S_vv| over a region, in the patch's own parameters. */
typedef struct dbounds {
    double uu, uv, vv;
} dbounds;

/* Temporaries go through the mesh's allocator (a mesh always has one). */
static inline void *t_alloc(const cj_mesh *mesh, size_t bytes) {
    return cj_allocator_alloc(&mesh->alloc_, bytes);
}
static inline void t_free(const cj_mesh *mesh, void *ptr) {
    cj_allocator_free(&mesh->alloc_, ptr);
}

/* Difference nets of a polynomial patch restricted in v to a strip [v0,v1] (tess_bounds_poly.c):
 * a cell of the strip restricts them in u only. */
#define CJ_TESS_DNET_MAX ((CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1) * 3)
typedef struct tess_strip {
    double v0, v1;
    double uu[CJ_TESS_DNET_MAX], uv[CJ_TESS_DNET_MAX], vv[CJ_TESS_DNET_MAX];
} tess_strip;

/* One grid line of a strip (u degree <= 3, v degree <= 3): per difference net and row, the row's
 * value at t and its last de Casteljau level (tess_bounds_poly.c, walking a strip). */
typedef struct tess_line {
    double t;
    double pt[3][4][3][3]; /* [net uu, uv, vv][row][value, Q0, Q1][xyz] */
    double nrm[3];         /* per net: the largest value norm over the rows */
    int deg[3], count[3];  /* per net: degree and number of the curves walked (deg -1: none) */
} tess_line;

typedef struct edge_info {
    int degree, collapsed, reversed;
    double pts[(CJ_PATCH_MAX_DEGREE + 1) * 3]; /* canonical order */
    double w[CJ_PATCH_MAX_DEGREE + 1];
} edge_info;

typedef struct ptess {
    const cj_patch *p;
    int32_t id;
    int hd, m, n;
    int rational;
    double evalerr;
    double err_uu, err_uv, err_vv; /* polynomial: rounding of a restricted difference norm */
    /* rational patches (see cj_tess_rational_tri_bound) */
    double suberr_x, suberr_w; /* rounding of a sub-net coefficient */
    double verterr;            /* rounding of a vertex (3D norm) */
    double cellbox[4];         /* the grid cell whose sub-net is in cellnet */
    double cellq[4];           /* cj_tess_homog_bounds of that cell */
    cj_mesh *mesh;
    int measure;
    int planning;    /* builds only for their bound and size: no normals */
    int bounds_only; /* polynomial: a trial that computes the bound and triangle count only:
                      * no positions, nothing added to the mesh (uvs in scr_uv) */
    int bound_known; /* a build whose bound a bounds-only trial computed: add_tri skips it */
    double *scr_uv;  /* bounds_only: the (u,v) of the trial's vertices */
    uint32_t scr_count;
    size_t tris;   /* triangles of the last build (bounds_only: including those a real
                    * build would drop) */
    size_t builds; /* mesh builds of this patch (bounds-only trials not counted) */
    size_t trials; /* bounds-only trials of this patch */
    /* polynomial zippers: the strip all triangles of the current zipper span (zip_dir 0: its v
     * range, 1: its u range; -1: none) with its inner end zip_t (a grid line), restricted once
     * into zip; the walk of its breakpoints (outer and inner parameters merged, zip_n of them)
     * and the bounds of the intervals between them */
    int zip_dir;
    double zip_t;
    int zip_n;
    const double *zip_bp;
    const dbounds *zip_iv;
    dbounds whole; /* polynomial: bounds over the whole patch */
    /* rational patches: the tables of the densities on S x S slab cells (S = CJ_TESS_SLABS):
     * pm[0..3 S^2) the sampled |S_uu|, |S_uv|, |S_vv|, pm[3 S^2..6 S^2) the homogeneous (Q)
     * bound's M's in the patch's parameters, pm[6 S^2] the largest constant term of (Q); NULL:
     * not kept (filled with the densities while planning, in pmbuf). predict: the current trial
     * predicts its bound from them (planning only, see tessellate_adaptive.c) */
    double *pm;
    int predict;
    int bands_valid;   /* slab_bands holds the bands of the current pm (tess_trial.c) */
    double abort_over; /* > 0: stop a build as soon as its bound exceeds this (it fails) */
    int aborted;       /* the last build stopped early */
    /* results of one build */
    double bound, measured;
    double worst_terms[3]; /* uu, uv, vv contributions of the worst triangle */
    size_t dropped;
    /* ---- large arrays, written before they are read (cj_tess_setup does not clear them) */
    double h[CJ_PATCH_NET_MAX];
    double pmbuf[6 * CJ_TESS_SLABS * CJ_TESS_SLABS + 1]; /* rational planning: pm points here */
    edge_info e[4];
    /* polynomial planning (tess_trial.c): per slab row b and slab column a, the largest Muu,
     * Muv, Mvv of pm over rows [b, b] ([0]) and [b, b+1] ([1]) */
    double slab_bands[2][CJ_TESS_SLABS][CJ_TESS_SLABS][3];
    /* polynomial patches: difference nets (tess_bounds_poly.c) */
    double duu[CJ_TESS_DNET_MAX], duv[CJ_TESS_DNET_MAX], dvv[CJ_TESS_DNET_MAX];
    double cellnet[CJ_PATCH_NET_MAX], trinet[CJ_PATCH_NET_MAX];
    double fnet[(CJ_PATCH_MAX_DEGREE + 2) * (CJ_PATCH_MAX_DEGREE + 2) * 3]; /* F's net */
    tess_strip strip;   /* scratch of the cell loop */
    tess_line lines[2]; /* walking the current strip */
    tess_strip zip;
} ptess;

/* A candidate grid: nu x nv cells, lines equidistributing the slab densities or (uni)
 * uniform. */
typedef struct grid {
    int nu, nv, uni;
} grid;

/* The zipper's next step between a side's outer parameters tout[0..k] and the inner row's
 * tin[0..L], at outer index a and inner index b: 1 to advance along the outer side (triangle
 * o[a], o[a+1], in[b]), 0 along the inner row. The build and the planning trial both take it from
 * here, so the trial bounds exactly the triangles the build makes. */
static inline int cj_tess_zip_outer(const double *tout, int a, int k, const double *tin, int b,
                                    int L) {
    if (a == k) return 0;
    if (b == L) return 1;
    return tout[a] + tout[a + 1] < tin[b] + tin[b + 1];
}

static inline int same_pos(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* ---- tess_bounds_poly.c --------------------------------------------------------------- */

/* Forms the difference nets of the set-up polynomial patch (once per patch). */
void cj_tess_diff_setup(ptess *P);
/* Bounds over [u0,u1]x[v0,v1] in the patch's parameters (polynomial patches; rational ones:
 * cj_tess_rational_tri_bound). */
dbounds cj_tess_strip_bounds(const ptess *P, double u0, double u1, double v0, double v1);
/* The same in two steps: restrict to the strip [v0,v1] once, then to each cell [u0,u1] of it. */
void cj_tess_strip_restrict(const ptess *P, double v0, double v1, tess_strip *s);
dbounds cj_tess_cell_bounds(const ptess *P, const tess_strip *s, double u0, double u1);
/* Walking a strip (polynomial, degrees <= 3): the line data at t, then a cell's bounds from its
 * two lines. */
int cj_tess_walkable(const ptess *P);
void cj_tess_line(const ptess *P, const tess_strip *s, double t, tess_line *L);
/* The same for a u-strip (cj_tess_ustrip_restrict) walked in v. */
void cj_tess_uline(const ptess *P, const tess_strip *s, double t, tess_line *L);
dbounds cj_tess_cell_walk(const ptess *P, const tess_line *A, const tess_line *B);
/* The same with the roles swapped: a strip [u0,u1] in u (s->v0, s->v1 hold u0, u1), then the
 * cells [v0,v1] of it (the zippers of the sides u = 0 and u = 1). */
void cj_tess_ustrip_restrict(const ptess *P, double u0, double u1, tess_strip *s);
dbounds cj_tess_ucell_bounds(const ptess *P, const tess_strip *s, double v0, double v1);

/* ---- tess_trial.c ---------------------------------------------------------------------- */

/* Planning's bounds-only trial of a polynomial patch on its slab table (P->pm): the bound and
 * triangle count of the build on lines ub[0..nu] x vb[0..nv] with side counts k, bit for bit
 * those of the triangle-by-triangle trial (P->predict in cj_tess_build_patch), without
 * enumerating the interior cells. */
cj_status cj_tess_slab_trial(ptess *P, int nu, const double *ub, int nv, const double *vb,
                             const int k[4]);

/* ---- tess_grid_eval.c ------------------------------------------------------------------ */

/* The u stage at u (col: n+1 points of dimension hd) and, polynomial patches, the rows'
 * u-derivatives (dcol: n+1 3D points). */
void cj_tess_eval_column(const ptess *P, double u, double *col, double *dcol);
/* The point of a column at v (out) and, polynomial patches, S_v (dv). */
void cj_tess_eval_in_column(const ptess *P, const double *col, double v, double out[3],
                            double dv[3]);
/* S_u at v along a column (polynomial patches). */
void cj_tess_eval_du(const ptess *P, const double *dcol, double v, double du[3]);
/* The unit normal at a grid vertex from S_u, S_v (polynomial), else cj_patch_normal_unchecked. */
void cj_tess_grid_normal(const ptess *P, const double su[3], const double sv[3], double u, double v,
                         double nrm[3]);
/* The normals of a polynomial patch's side points o[s][1..k[s]-1] (side parameters tout) from
 * grid columns, into the mesh; col, dcol: scratch of one column. */
void cj_tess_side_normals(ptess *P, uint32_t *const o[4], double *const tout[4], const int k[4],
                          double *col, double *dcol);

/* ---- tessellate_bounds.c -------------------------------------------------------------- */
/* Homogeneous rational bound of a box from its homogeneous sub-net (see the RATIONAL BOUND
 * in tessellate_bounds.c). */
void cj_tess_homog_bounds(const ptess *P, const double *sub, double out[4]);
/* Bound on the distance between the rational patch and the mesh triangle (a,b,c) (see the
 * RATIONAL BOUND in tessellate_bounds.c). */
double cj_tess_rational_tri_bound(ptess *P, const double *ua, const double *ub, const double *uc,
                                  const double *pa, const double *pb, const double *pc, int in_cell,
                                  double floor);
/* Loads the homogeneous sub-net of the grid cell [u0,u1]x[v0,v1] for
 * cj_tess_rational_tri_bound. */
void cj_tess_load_cell(ptess *P, double u0, double u1, double v0, double v1);

/* ---- tessellate_build.c --------------------------------------------------------------- */

/* Lexicographic order of (x, y, z, w): the canonical order of a side's control points. */
int cj_tess_cmp_point(const double *a, double wa, const double *b, double wb);
/* A side of the patch in canonical order (so that two patches sharing it evaluate the same
 * points). */
void cj_tess_edge_setup(const cj_patch *p, int side, edge_info *e);
/* Per-patch state for one patch (everything but the results of a build). */
void cj_tess_setup(ptess *P, const cj_patch *p, size_t q, cj_mesh *mesh, int measure);
/* One build of a patch on the grid lines ub[0..nu] x vb[0..nv] with k[s] segments on side s. */
cj_status cj_tess_build_patch(ptess *P, int nu, const double *ub, int nv, const double *vb,
                              const int k[4]);

/* ---- tessellate_adaptive.c ------------------------------------------------------------ */

/* Grid densities of the set-up patch on CJ_TESS_SLABS slabs per direction, and the cell counts
 * of the search's starting grid for tol. */
void cj_tess_patch_densities(ptess *P, double tol, double *rho_u, double *rho_v, double *base_u,
                             double *base_v);
/* A patch's grid densities and starting counts for one tol (cj_tess_patch_densities), kept
 * from its planning to its build (valid != 0). */
typedef struct tess_density {
    double rho_u[CJ_TESS_SLABS], rho_v[CJ_TESS_SLABS], base_u, base_v;
    int valid;
    /* polynomial patches: the bound (and worst terms) of the planned grid with the planned
     * side counts known_k, from planning's passing trial */
    int known_valid;
    int known_k[4];
    double known[4];
} tess_density;

/* Adaptive choice of the grid of one patch (see tessellate_adaptive.c). dens: computed when
 * not valid, reused when valid (the same patch and tol). */
cj_status cj_tess_adaptive_patch(ptess *P, double tol, int cap, size_t q, const int *kfix,
                                 const grid *hint, tess_density *dens, int kout[4], grid *out);

/* ---- tessellate.c: the steps of adaptive tessellation (shared with tess_cache.c) ---- */

/* What planning decides for one patch at one tol: a function of the patch and tol alone. */
typedef struct tess_plan {
    int k[4]; /* requested side counts */
    grid g;   /* planned grid */
    tess_density dens;
} tess_plan;

/* Plans patch p (index q for messages); mesh is scratch (left as it was). Adds the builds and
 * bounds-only trials made to *builds, *trials. */
cj_status cj_tess_plan_patch(ptess *P, const cj_patch *p, size_t q, double tol, int cap,
                             cj_mesh *mesh, tess_plan *plan, size_t *builds, size_t *trials);
/* k[4 q + s] (requested counts in, shared counts out): every side shared by several patches
 * (identical canonical control points) gets the largest count requested for it. */
cj_status cj_tess_share_counts(const cj_patch *patches, size_t count, int *k,
                               const cj_allocator *alloc);
/* Builds planned patch p with side counts k, appending its mesh piece (triangle_patch q) to
 * mesh; on failure the mesh is as before. *used receives the grid; P holds bound, dropped. */
cj_status cj_tess_build_planned(ptess *P, const cj_patch *p, size_t q, double tol, int cap,
                                int measure, const int k[4], tess_plan *plan, cj_mesh *mesh,
                                grid *used, size_t *builds, size_t *trials);

#endif
