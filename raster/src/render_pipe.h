/* Private to the rasterizer pipeline (render_main.c, render_shade.c, render_lines.c,
 * render_bsp.c): the prepared frame every tile reads.
 *
 * SHADING KERNELS. Each material maps to one of 8 kernels, (model, textured) with model in
 * {unlit, flat, Gouraud, Phong}; the tile shader sorts its samples by kernel (a counting sort)
 * and runs one loop per kernel, each an instantiation of one always-inlined function with the
 * model and texture flags as compile-time constants: no feature branches per pixel.
 *   unlit    L = c_r·t·a            a = r_a I_a (ambient lights only) or 1 (no light at all)
 *   flat     L = c_r·t·A + S        A, S per triangle at its centroid (face normal)
 *   Gouraud  L = c_r·t·A + S        A, S per vertex, interpolated
 *   Phong    L = c_r·t·A + S        A, S per sample from the interpolated normal
 * with A = r_a I_a + r_d Σ I d, S = c_p r_s Σ I s (d, s: the one reflection model of
 * reflect_model.h, shared with the ray tracer: no highlight where n·l <= 0), t the texture's RGB (1
 * without texture). Two-sided materials light the side the viewer sees: where a triangle shows its
 * back ((p̄ − ē)·n⃗ > 0 for its face normal n⃗, seed 7.2) every normal it shades with is flipped. The
 * triangle decides, not the interpolated normal, which can point away from the viewer near a
 * silhouette and would light the wrong side. */
#ifndef CASTELJAU_RENDER_PIPE_H
#define CASTELJAU_RENDER_PIPE_H

#include "raster3d_internal.h"
#include "reflect_model.h"
#include "render_internal.h"
#include "texture_internal.h"

#include <stdatomic.h>

enum { CJ_RM_UNLIT = 0, CJ_RM_FLAT, CJ_RM_GOURAUD, CJ_RM_PHONG, CJ_RM_COUNT };
#define CJ_RK_COUNT (2 * CJ_RM_COUNT) /* kernel = 2·model + textured */

/* Per-tile stage counters, one set per thread (summed after the run). */
enum {
    CJ_RS_SHADE0 = 0, /* + kernel */
    CJ_RS_BACKGROUND = CJ_RK_COUNT,
    CJ_RS_LINES,
    CJ_RS_TRANSPARENT,
    CJ_RS_RESOLVE,
    CJ_RS_OUTPUT,
    CJ_RS_COUNT
};

typedef struct cj_rcount {
    double sec[CJ_RS_COUNT];
    double cpu[CJ_RS_COUNT]; /* the same in the worker's CPU time (robust on a busy machine) */
    uint64_t n[CJ_RS_COUNT];
    uint64_t textured;
    char pad[64];
} cj_rcount;

typedef struct cj_rlight {
    int directional; /* 1: l is constant */
    float I[3];
    double pos[3]; /* point and spot */
    float pe[3];   /* pos − eye in float (the shading kernels, render_light8.h) */
    float l[3];    /* directional: unit vector towards the light */
    int spot;
    float axis[3]; /* spot: unit direction the light travels */
    float cos_cut, spot_exp;
    int falloff; /* radiometric point and spot: I is an intensity, divided by r² */
    /* radiometric area light (I = L_e): the diffuse term takes the polygon's exact irradiance
     * (reflect_model.h), the specular one its centre pos as a point of intensity L_e A cos θ′.
     * A disc light is the polygon of cj_reflect_disc_polygon (its area, πR², in size). */
    /* radiometric sphere light (I = π R² L_e, a point at its centre): exact wherever the sphere
     * is wholly above the receiver's horizon; where it is partly below, the diffuse term takes
     * the polygon path with the disc that fills the same cone (cj_lanes_sphere_horizon) */
    int sphere;
    double radius;
    int area, ncorner;
    double corner[CJ_REFLECT_POLY_MAX][3], normal[3], size; /* size: the area A */
} cj_rlight;

typedef struct cj_rmat {
    float cr[3];   /* c_r */
    float amb[3];  /* r_a I_a (unlit without any light: 1) */
    float spec[3]; /* c_p r_s */
    float emit[3]; /* the material's emission (a radiance), added to every lit model */
    float kd, alpha, opacity;
    int model, two_sided, tex; /* tex: sampler index or −1 */
    int spec_model;            /* cj_specular_model */
    int used;
} cj_rmat;

/* A triangle list handed to the rasterizer. */
typedef struct cj_rlist {
    size_t count;
    uint32_t *tris;  /* 3 global vertex indices per triangle */
    uint32_t *obj;   /* object per triangle */
    uint8_t *kernel; /* kernel per triangle */
    float *flat;     /* 6 per triangle (A, S) where flat-lit, else unused; may be NULL */
    double *uvplane; /* 9 per triangle where textured with a footprint filter; may be NULL.
                        Built lazily, by the first sample that needs it (cj_rshade_plane) */
    _Atomic uint8_t *plane_state; /* per triangle: 0 no plane yet, 1 being built, 2 built; with
                                     uvplane */
    uint8_t *back; /* 1 per triangle: 1 where a two-sided triangle shows its back; NULL when the
                      list has no two-sided triangle */
    cj_raster_prep *prep;
} cj_rlist;

/* A screen-space overlay segment: pixel-space ends and pseudodepths. */
typedef struct cj_rseg {
    double x0, y0, x1, y1;
    float z0, z1;
    float rgb[3];
    int width; /* pixels across: parallel exact lines offset along the minor axis */
} cj_rseg;

typedef struct cj_rlines {
    size_t count, cap;
    cj_rseg *segs;
    size_t *bin_start; /* tiles + 1 */
    uint32_t *bin_items;
    size_t world_segments; /* 3D segments before clipping */
} cj_rlines;

typedef struct cj_rctx {
    const cj_rbuild *b;
    const cj_rview *view;
    int width, height, spp, tile_size, tiles_x, threads;
    const double (*pattern)[2];
    double *clip;   /* 4 per vertex */
    float *vrec;    /* 8 per vertex: the unit normal (0 without normals), position − eye, (u, v)
                       (0 without), in float: Phong shading (render_light8.h, render_shade8.c) */
    float *gouraud; /* gstride per vertex: (A, S) lit from the front, then (where two-sided
                       Gouraud materials exist, gstride 12) from the back; or NULL */
    int gstride;
    cj_rmat *mats; /* per scene material, plus the default material at index nmat */
    int nmat;
    int *obj_mat; /* object -> index into mats */
    cj_rlight *lights;
    int nlights;
    /* radiometric area, disc and sphere lights, drawn with their radiance where camera rays
     * meet them in front of the surfaces (render_emitters.c) */
    const cj_light **emitters;
    int nemitters;
    int radiometric; /* cj_light_model CJ_LIGHT_RADIOMETRIC (reflect_model.h) */
    cj_tex_sampler *samplers;
    int nsamplers;
    float bg[3];
    cj_rlist opaque, transp;
    cj_rlines lines;
    int has_lines, has_transp;
    cj_render_image *img;
    float **color;    /* per thread: 4 floats per sample of a tile */
    uint32_t **order; /* per thread: sample indices sorted by kernel */
    cj_rcount *count; /* per thread */
} cj_rctx;

/* render_shade.c */
/* flip: light the other side (n -> -n). */
void cj_rlight_eval(const cj_rctx *c, const cj_rmat *m, const double p[3], const float n_in[3],
                    int flip, float A[3], float S[3]);
/* Fills c->vrec and each light's pe (positions relative to the eye, float). */
cj_status cj_rshade_prepare_eye(cj_rctx *c, const cj_allocator *a);
/* render_shade8.c: the Phong kernels, CJ_LANES samples at a time (textured or not). */
void cj_rshade_phong8(const cj_rctx *c, const cj_tile *t, const uint32_t *idx, size_t n,
                      float *col);
void cj_rshade_phong8_tex(const cj_rctx *c, const cj_tile *t, const uint32_t *idx, size_t n,
                          float *col);
/* Shades the samples idx[0..n) of the tile with kernel k into col (4 floats per sample). */
void cj_rshade_kernel(const cj_rctx *c, int k, const cj_tile *t, const uint32_t *idx, size_t n,
                      float *col);
/* The texture's RGB at a sample (b1, b2) of triangle tri of list L, pixel point (sx, sy). */
void cj_rshade_tex(const cj_rctx *c, const cj_rlist *L, uint32_t tri, float b1, float b2, double sx,
                   double sy, float out[3]);
/* Shades one fragment of list L (transparent pass). */
void cj_rshade_one(const cj_rctx *c, const cj_rlist *L, uint32_t tri, float b1, float b2, double sx,
                   double sy, float out[4]);
/* Per-triangle / per-vertex preparation of a list: kernel, flat A/S, (u,v) planes. pool (may
 * be NULL) with workers > 1: the per-triangle part runs in ranges on it (the same values). */
struct cj_rpool;
cj_status cj_rshade_prepare_list(cj_rctx *c, cj_rlist *L, const cj_allocator *a,
                                 struct cj_rpool *pool, int workers);
/* The same in two steps: the kernel table and the arrays (begin), then the per-triangle values
 * of triangles [t0, t1) (range: facing, flat A/S, (u,v) planes), which depend on that triangle
 * alone, so ranges may run on any thread and in any order. */
cj_status cj_rshade_prepare_begin(cj_rctx *c, cj_rlist *L, const cj_allocator *a);
/* The (u,v) plane of triangle tri of L (L->uvplane non-NULL). A plane is built the first time a
 * sample of its triangle needs it, not for every triangle at set-up: most of a fine mesh's
 * triangles are hidden or win no sample. Race-free on any number of threads: the first caller
 * claims the triangle (0 -> 1), writes its plane, then publishes it (release store of 2); a
 * caller that finds it being built waits the few instructions that takes. The values do not
 * depend on which thread builds them (the same function of the clip coordinates and (u,v)). */
const double *cj_rshade_plane_build(const cj_rctx *c, const cj_rlist *L, uint32_t tri);
static inline const double *cj_rshade_plane(const cj_rctx *c, const cj_rlist *L, uint32_t tri) {
    if (atomic_load_explicit(&L->plane_state[tri], memory_order_acquire) == 2)
        return L->uvplane + 9 * (size_t)tri;
    return cj_rshade_plane_build(c, L, tri);
}
/* How many planes of L were built (after the tiles). */
size_t cj_rshade_planes_built(const cj_rlist *L);
void cj_rshade_prepare_range(const cj_rctx *c, cj_rlist *L, size_t t0, size_t t1);
cj_status cj_rshade_prepare_gouraud(cj_rctx *c, const cj_allocator *a, size_t *vertices);

/* render_emitters.c: the samples of the tile whose camera ray meets an emitter in front of
 * what was drawn take its radiance (alpha 1). */
void cj_remitters_tile(const cj_rctx *c, const cj_tile *t, float *col);

/* render_tile.c: the cj_tile_fn of the opaque run (user = the cj_rctx). */
void cj_rtile_run(void *user, const cj_tile *t);

/* render_lines.c */
cj_status cj_rlines_build(cj_rctx *c, const cj_scene *scene, const cj_allocator *a);
void cj_rlines_free(cj_rlines *l, const cj_allocator *a);
void cj_rlines_tile(const cj_rctx *c, const cj_tile *t, float *col, uint64_t *pixels);

/* render_bsp.c: orders the transparent triangles back to front (splitting where needed); may
 * append vertices to the build. tris/obj are replaced by the ordered (split) list. */
cj_status cj_rbsp_order(cj_rbuild *b, const cj_rview *view, uint32_t **tris, uint32_t **obj,
                        size_t *count, size_t *splits, int *fallback, const cj_allocator *a);

#endif
