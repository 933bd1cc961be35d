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

typedef struct edge_info {
    int degree, collapsed, reversed;
    double pts[(CJ_PATCH_MAX_DEGREE + 1) * 3]; /* canonical order */
    double w[CJ_PATCH_MAX_DEGREE + 1];
} edge_info;

typedef struct ptess {
    const cj_patch *p;
    int32_t id;
    double h[CJ_PATCH_NET_MAX];
    int hd, m, n;
    int rational;
    double evalerr;
    /* rational patches (see cj_tess_rational_tri_bound) */
    double suberr_x, suberr_w; /* rounding of a sub-net coefficient */
    double verterr;            /* rounding of a vertex (3D norm) */
    double cellbox[4];         /* the grid cell whose sub-net is in cellnet */
    double cellq[4];           /* cj_tess_homog_bounds of that cell */
    double cellnet[CJ_PATCH_NET_MAX], trinet[CJ_PATCH_NET_MAX];
    double fnet[(CJ_PATCH_MAX_DEGREE + 2) * (CJ_PATCH_MAX_DEGREE + 2) * 3]; /* F's net */
    edge_info e[4];
    cj_mesh *mesh;
    int measure;
    int planning;      /* builds only for their bound and size: no normals */
    double abort_over; /* > 0: stop a build as soon as its bound exceeds this (it fails) */
    int aborted;       /* the last build stopped early */
    /* results of one build */
    double bound, measured;
    double worst_terms[3]; /* uu, uv, vv contributions of the worst triangle */
    size_t dropped;
} ptess;

/* A candidate grid: nu x nv cells, lines equidistributing the slab densities or (uni)
 * uniform. */
typedef struct grid {
    int nu, nv, uni;
} grid;

static inline int same_pos(const double *a, const double *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* ---- tessellate_bounds.c -------------------------------------------------------------- */

/* Sub-net bounds over [u0,u1]x[v0,v1], rescaled to the patch's parameters (polynomial
 * patches; rational ones: cj_tess_rational_tri_bound). */
dbounds cj_tess_strip_bounds(const ptess *P, double u0, double u1, double v0, double v1);
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
/* Adaptive choice of the grid of one patch (see tessellate_adaptive.c). */
cj_status cj_tess_adaptive_patch(ptess *P, double tol, int cap, size_t q, const int *kfix,
                                 const grid *hint, int kout[4], grid *out);

#endif
