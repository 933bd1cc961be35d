/* Private to raster/: the rasterizer pipeline's stages (render_*.c) and what other renderers
 * reuse of it (the ray tracer may take the scene -> world triangles step; the VTK cross-check
 * takes the mesh the pipeline drew through cj_render_scene_mesh).
 *
 * SCENE -> TRIANGLES (render_build.c, render_geom.c): every visible object node becomes world-
 * space triangles with (when asked for) world unit normals and (u, v):
 *   - Bézier patch sets, surfaces of revolution and general cylinders (converted exactly to
 *     rational Bézier patches) are tessellated FOR THE VIEW: the screen tolerance tol_px becomes
 *     a world tolerance at the nearest depth of each patch inside the view volume and an object
 *     tolerance through the largest singular value of the world transform's linear part; a set
 *     is tessellated in ONE cj_tessellate_patches call at the smallest tolerance its visible
 *     patches need (so shared edges stay bit-identical: watertight). Patches entirely outside
 *     the view volume are left out.
 *   - quadrics, spheres, tori, cylinders, planar and bilinear patches: a uniform grid through
 *     cj_tessellate_surface whose cell sizes (hu, hv) satisfy the tessellator's second-order
 *     bound (Muu hu² + 2 Muv hu hv + Mvv hv²)/8 <= tol with Muu >= |S_uu|, Muv >= |S_uv|,
 *     Mvv >= |S_vv| bounded analytically per kind over the domain (render_geom.c).
 *   - meshes are taken as they are (missing normals are area-weighted face normals).
 * Back faces ((p̄ − ē)·n⃗ > 0, n⃗ from the world positions; orthographic: g⃗·n⃗ > 0) of one-sided
 * materials are dropped. A mirroring transform (det < 0) has its triangles' winding reversed so
 * that they stay counter-clockwise seen from outside.
 */
#ifndef CASTELJAU_RENDER_INTERNAL_H
#define CASTELJAU_RENDER_INTERNAL_H

#include "casteljau/alloc.h"
#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/stage_report.h"
#include "casteljau/status.h"
#include "casteljau/tess_cache.h"
#include <stddef.h>
#include <stdint.h>

/* One drawn object (a visible node with geometry). */
typedef struct cj_robject {
    int node;
    int material;
    uint32_t id;
    int geometry;
    cj_xform3 world;      /* object -> world */
    cj_xform3 normal;     /* object -> world for normals: L^-T (upper 3x3 used) */
    double det;           /* det of the linear part (< 0: mirroring) */
    double sigma;         /* largest singular value of the linear part (upper bound) */
    size_t v0, v1;        /* its vertices [v0, v1) */
    size_t t0, t1;        /* its triangles [t0, t1) of the (uncompacted) build */
    int grid_nu, grid_nv; /* analytic surfaces: the grid used (iso lines follow it) */
    double tol_obj;       /* object-space tolerance used (patches, surfaces, curves) */
} cj_robject;

/* What to compute per vertex. */
enum { CJ_RB_NORMALS = 1u, CJ_RB_UVS = 2u };

/* The camera as the pipeline uses it. */
typedef struct cj_rview {
    cj_camera cam;
    int width, height;
    cj_xform3 world_to_clip;
    cj_xform3 world_to_cam;
    double f_px;     /* perspective: pixels per unit of x/depth (height / (2 tan(fov/2))) */
    double k;        /* perspective: secant of the view volume's corner ray (>= 1) */
    double px_ortho; /* orthographic: world size of a pixel */
    cj_vec3 eye, gaze_unit;
} cj_rview;

cj_status cj_rview_init(const cj_camera *cam, int width, int height, cj_rview *out);
/* World size of one pixel at depth d (> 0) in front of the camera. */
double cj_rview_pixel_size(const cj_rview *v, double depth);
/* The world tolerance that projects to at most tol_px pixels for geometry at depth >= depth. */
double cj_rview_world_tol(const cj_rview *v, double depth, double tol_px);
/* The pixels a world distance dist at depth >= depth can project to. */
double cj_rview_pixels(const cj_rview *v, double depth, double dist);
/* Nearest depth of the box [lo, hi] (object space, mapped by world) inside the view volume:
 * returns 0 when the box is entirely outside the view volume, else 1 with *depth >= -near. */
int cj_rview_box_depth(const cj_rview *v, const cj_xform3 *world, const double lo[3],
                       const double hi[3], double *depth);

/* The world-space triangles of a scene. */
typedef struct cj_rbuild {
    size_t vertex_count, vertex_cap;
    double *pos; /* 3 per vertex, world */
    float *nrm;  /* 3 per vertex (CJ_RB_NORMALS), world, unit; else NULL */
    float *uv;   /* 2 per vertex (CJ_RB_UVS), the geometry's (u, v); else NULL */
    size_t tri_count, tri_cap;
    uint32_t *tris; /* 3 per triangle, CCW from outside, after culling */
    uint32_t *tobj; /* object per triangle */
    size_t object_count;
    cj_robject *objects;
    unsigned flags;
    /* figures for the stage report */
    size_t patches_in, patches_culled, patch_tris, surface_tris, mesh_tris, culled_back;
    size_t cache_hits;   /* patch objects whose tessellation came from the cache */
    size_t cache_misses; /* patch objects tessellated (in view, not found in the cache) */
    /* patches (through the cache) planned, built, and whose mesh piece was reused */
    size_t patches_planned, patches_built, patches_reused;
    double patch_bound_px, surface_bound_px; /* proven bounds in pixels (0 when none) */
    double tol_px;
    double sec_patches, sec_surfaces, sec_meshes, sec_transform, sec_cull;
    cj_allocator alloc;
} cj_rbuild;

/* Builds the world triangles of every drawn object of the scene pass `rs` (render_scene.h:
 * which nodes are drawn, their world transforms) for the view. flags: which
 * vertex attributes to compute; `need` (may be NULL) says per material whether normals / uvs
 * are needed (bit CJ_RB_*), letting objects whose material needs nothing skip them.
 * Back faces of one-sided materials are dropped when cull != 0. */
struct cj_rscene;
cj_status cj_rbuild_scene(const struct cj_rscene *rs, const cj_rview *view, double tol_px,
                          unsigned flags, const unsigned *need, int cull, cj_render_cache *cache,
                          const cj_allocator *alloc, cj_rbuild *out);
void cj_rbuild_free(cj_rbuild *b);
/* Appends a vertex / triangle (growing the arrays). */
cj_status cj_rbuild_add_vertex(cj_rbuild *b, const double p[3], const float n[3], const float uv[2],
                               uint32_t *index);
cj_status cj_rbuild_add_tri(cj_rbuild *b, uint32_t a, uint32_t c, uint32_t d, uint32_t obj);

/* Tessellation of one object's geometry in OBJECT space into mesh (render_geom.c); tol_obj is
 * set to the tolerance used, *bound to the proven bound (object units), *skip to 1 when the
 * geometry lies entirely outside the view (nothing added). Curves add nothing. */
cj_status cj_render_geometry_mesh(const cj_geometry *g, const cj_robject *o, const cj_rview *view,
                                  double tol_px, cj_render_cache *cache, cj_mesh *mesh,
                                  double *tol_obj, double *bound, int *nu, int *nv, size_t *patches,
                                  size_t *culled, int *skip, int *cache_hit,
                                  cj_tess_cache_stats *cache_work);

/* render_cache.c: tessellates `count` patches of node `node` through its incremental cache
 * (appending to mesh), at opt->tol or, when that lies within [cached tol, 2 cached tol], at the
 * cached tol (opt->tol is set to the tolerance used). stats: the update's plans and pieces
 * reused / redone. Status: those of cj_tess_cache_update (CJ_ERR_CANCELLED when the progress
 * callback set by cj_rcache_set_progress asks to stop), CJ_ERR_NOMEM. */
cj_status cj_rcache_tessellate(cj_render_cache *c, int node, const cj_patch *patches, size_t count,
                               cj_tess_options *opt, cj_mesh *mesh, cj_tess_report *rep,
                               cj_tess_cache_stats *stats);

/* render_cache.c: the frame's progress callback, called with done = total = 0 before each patch
 * the cache plans or builds (a nonzero answer cancels the tessellation); NULL: none. */
void cj_rcache_set_progress(cj_render_cache *c, cj_render_progress_fn fn, void *user);

/* A geometry of kind REVOLUTION or GEN_CYLINDER as exact rational Bézier patches (render_geom.c).
 * pts/w receive the control points and weights (caller frees with alloc), patches the views. */
cj_status cj_render_geometry_patches(const cj_geometry *g, const cj_allocator *alloc,
                                     cj_patch **patches, size_t *count, double **pts, double **w);

/* An analytic surface (quadric, sphere, torus, cylinder, planar, bilinear) as the pipeline
 * tessellates it: its parametric view (points S + offset), proven bounds on |S_uu|, |S_uv|,
 * |S_vv| over the domain, and an object-space bounding box (render_geom.c). */
typedef struct cj_rsurf {
    cj_param_surface s;
    cj_quadric q;   /* storage for the sphere's ellipsoid */
    cj_vec3 offset; /* added to S (the sphere's centre), else 0 */
    double muu, muv, mvv;
    double lo[3], hi[3];
} cj_rsurf;
cj_status cj_rsurf_init(const cj_geometry *g, cj_rsurf *out);

/* Resolved allocator (NULL -> malloc/free). */
cj_allocator cj_render_alloc(const cj_allocator *alloc);
void *cj_ralloc(const cj_allocator *a, size_t bytes);
void cj_rfree(const cj_allocator *a, void *p);

/* cj_render_image_create, with the planes cleared only when `clear` (else their values are
 * undefined until written: for a caller that writes all of them). */
cj_status cj_render_image_alloc(int width, int height, unsigned flags, const cj_allocator *alloc,
                                int clear, cj_render_image **out);
double cj_render_now(void);
/* CPU time of the calling thread, seconds. */
double cj_render_thread_cpu(void);

#endif
