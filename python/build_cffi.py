"""Writes the C source of the cffi extension module casteljau._casteljau_cffi.

Run by CMake (python/CMakeLists.txt) as `python3 build_cffi.py OUT.c`; CMake then compiles
OUT.c against the library's public headers and links the static libraries into the module.
cffi's API mode is used on purpose: the declarations below are compiled against the real
headers, so a declaration that drifts from its header is an error (at build or first use), not a
wrong call.
Only what casteljau/__init__.py uses is declared; `...;` leaves the rest of a struct to the
compiler.
"""
import sys

import cffi

CDEF = r"""
typedef enum cj_status {
    CJ_OK = 0,
    CJ_ERR_NONFINITE, CJ_ERR_EMPTY, CJ_ERR_DIMENSION, CJ_ERR_DEGREE, CJ_ERR_RANGE,
    CJ_ERR_ARGUMENT, CJ_ERR_DEGENERATE, CJ_ERR_SINGULAR, CJ_ERR_CAP, CJ_ERR_BUFFER,
    CJ_ERR_NOMEM, CJ_ERR_IO, CJ_ERR_PARSE, CJ_ERR_UNSUPPORTED, CJ_ERR_CANCELLED,
    ...
} cj_status;
const char *cj_status_str(cj_status status);
const char *cj_last_error(void);

typedef struct cj_allocator cj_allocator;

/* curves: bezier.h */
#define CJ_MAX_DIM ...
#define CJ_BEZIER_MAX_DEGREE ...
typedef struct cj_bezier { int degree; int dim; const double *pts; } cj_bezier;
typedef enum cj_eval_method {
    CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER, CJ_EVAL_COMPENSATED
} cj_eval_method;
cj_status cj_bezier_eval(const cj_bezier *c, cj_eval_method method, double t, double *out);
cj_status cj_bezier_eval_batch(const cj_bezier *c, cj_eval_method method, const double *ts,
                               size_t nt, double *out);
cj_status cj_bezier_eval_compensated(const cj_bezier *c, double t, double *out, double *bound);
cj_status cj_bezier_error_bound(const cj_bezier *c, cj_eval_method method, double t,
                                double *bound);
cj_status cj_bezier_eval_derivs(const cj_bezier *c, double t, int kmax, double *out);
cj_status cj_bezier_hodograph(const cj_bezier *c, int k, double *out);
cj_status cj_bezier_split(const cj_bezier *c, double t, double *left, double *right);
cj_status cj_bezier_arclength(const cj_bezier *c, double a, double b, double tol,
                              double *length, double *error_estimate);
cj_status cj_bezier_bbox(const cj_bezier *c, double *lo, double *hi);
cj_status cj_bezier_curvature(const cj_bezier *c, double t, double *kappa);

/* curves: rational.h */
typedef struct cj_rbezier {
    int degree; int dim; const double *pts; const double *weights;
} cj_rbezier;
cj_status cj_rbezier_eval(const cj_rbezier *c, double t, double *out);
cj_status cj_rbezier_eval_derivs(const cj_rbezier *c, double t, int kmax, double *out);
int cj_rbezier_arc_pieces(double a0, double a1);
cj_status cj_rbezier_ellipse_arcs(double cx, double cy, double rx, double ry, double rot,
                                  double a0, double a1, double *pts, double *weights,
                                  int cap_pieces, int *npieces);

/* curves: flatten.h */
typedef enum cj_flatten_method {
    CJ_FLATTEN_UNIFORM, CJ_FLATTEN_SUBDIVIDE, CJ_FLATTEN_NEAR_OPTIMAL, ...
} cj_flatten_method;
typedef struct cj_flatten_opts {
    cj_flatten_method method; double tol; size_t max_segments;
    ...;
} cj_flatten_opts;
typedef struct cj_flatten_stats { size_t segments; double bound; ...; } cj_flatten_stats;
cj_status cj_flatten_bezier(const cj_bezier *c, const cj_flatten_opts *opts, double *out,
                            size_t cap_points, size_t *npoints, cj_flatten_stats *stats);
cj_status cj_flatten_rbezier(const cj_rbezier *c, const cj_flatten_opts *opts, double *out,
                             size_t cap_points, size_t *npoints, cj_flatten_stats *stats);

/* curves: bspline.h, bspline_fit.h */
#define CJ_BSPLINE_MAX_DEGREE ...
#define CJ_BSPLINE_MAX_DERIV ...
typedef struct cj_bspline {
    int degree; int dim; int npts; const double *pts; const double *weights;
    const double *knots;
} cj_bspline;
cj_status cj_bspline_check(const cj_bspline *c);
cj_status cj_bspline_domain(const cj_bspline *c, double *t0, double *t1);
cj_status cj_bspline_uniform_knots(int npts, int degree, double a, double b, int clamped,
                                   double *knots);
cj_status cj_bspline_eval_batch(const cj_bspline *c, const double *ts, size_t nt, double *out);
cj_status cj_bspline_eval_derivs(const cj_bspline *c, double t, int kmax, double *out);
cj_status cj_bspline_error_bound(const cj_bspline *c, double t, double *bound);
cj_status cj_bspline_derivs_error_bound(const cj_bspline *c, double t, int kmax, double *bound);
cj_status cj_bspline_insert_knot(const cj_bspline *c, double x, int r, double *out_pts,
                                 double *out_w, double *out_knots);
cj_status cj_bspline_bezier_count(const cj_bspline *c, int *npieces);
cj_status cj_bspline_to_bezier(const cj_bspline *c, double *pts, double *w, double *breaks,
                               int cap_pieces, int *npieces);
typedef enum cj_fit_param { CJ_FIT_UNIFORM, CJ_FIT_CHORD, CJ_FIT_CENTRIPETAL } cj_fit_param;
cj_status cj_bspline_interpolate(const double *pts, int npts, int dim, int degree,
                                 cj_fit_param kind, const double *d_start, const double *d_end,
                                 double *out_pts, double *out_knots, int *npts_out,
                                 double *residual);
cj_status cj_bspline_approximate(const double *pts, int npts, int dim, int degree,
                                 cj_fit_param kind, double tol, int max_pts, double *out_pts,
                                 double *out_knots, int *npts_out, double *max_dev);

/* curves: intersect.h, nearest.h, offset.h */
#define CJ_QUERY_MAX_DEGREE ...
typedef struct cj_bezier2 { int degree; const double *pts; const double *weights; } cj_bezier2;
typedef enum cj_isect_kind { CJ_ISECT_CROSSING, CJ_ISECT_CONTACT, CJ_ISECT_OVERLAP } cj_isect_kind;
typedef struct cj_isect {
    cj_isect_kind kind; double s, t; double s_lo, s_hi; double t_lo, t_hi; double point[2];
    double deviation; int at_end;
} cj_isect;
const char *cj_isect_kind_name(cj_isect_kind kind);
cj_status cj_intersect_curves(const cj_bezier2 *a, const cj_bezier2 *b, double tol, cj_isect *out,
                              int cap, int *count);
typedef struct cj_nearest {
    double t; double point[2]; double distance; double lower; long pieces;
} cj_nearest;
cj_status cj_nearest_curve(const cj_bezier2 *c, const double q[2], double tol, cj_nearest *out);
cj_status cj_offset_curve(const cj_bezier2 *c, double d, double tol, double *pts, double *breaks,
                          int cap_pieces, int *npieces, double *deviation, int *cusps);

/* surfaces: bspline_surface.h */
typedef struct cj_bspline_surface {
    int deg_u, deg_v; int npts_u, npts_v; const double *pts; const double *weights;
    const double *knots_u; const double *knots_v;
} cj_bspline_surface;
cj_status cj_bspline_surface_check(const cj_bspline_surface *s);
cj_status cj_bspline_surface_eval(const cj_bspline_surface *s, double u, double v, double *out);
cj_status cj_bspline_surface_error_bound(const cj_bspline_surface *s, double u, double v,
                                         double *bound);
cj_status cj_bspline_surface_patch_count(const cj_bspline_surface *s, int *count);
cj_status cj_bspline_surface_to_patches(const cj_bspline_surface *s, double *pts, double *weights,
                                        double *ub, double *vb, int cap, int *count);

/* surfaces: patch.h, mesh.h, tessellate.h, patchset.h */
typedef struct cj_patch {
    int deg_u; int deg_v; const double *pts; const double *weights;
} cj_patch;
cj_status cj_patch_eval(const cj_patch *p, cj_eval_method method, double u, double v,
                        double out[3]);
cj_status cj_patch_normal(const cj_patch *p, double u, double v, double n[3], int *order);
typedef struct cj_mesh {
    size_t vertex_count; size_t triangle_count;
    double *positions; double *normals; double *uvs;
    uint32_t *triangles; int32_t *triangle_patch;
    ...;
} cj_mesh;
cj_status cj_mesh_create(const cj_allocator *alloc, cj_mesh **out);
void cj_mesh_destroy(cj_mesh *mesh);
cj_status cj_mesh_weld(cj_mesh *mesh, size_t *dropped);
typedef struct cj_tess_options {
    double tol; int uniform; int measure; int max_segments;
    ...;
} cj_tess_options;
typedef struct cj_tess_report {
    size_t triangles; size_t vertices; size_t dropped; double bound; double measured;
    int max_nu; int max_nv;
    ...;
} cj_tess_report;
cj_status cj_tessellate_patches(const cj_patch *patches, size_t count,
                                const cj_tess_options *opt, cj_mesh *mesh,
                                cj_tess_report *report);
typedef struct cj_patchset { size_t count; cj_patch *patches; double *points; ...; } cj_patchset;
cj_status cj_patchset_load_bpt(const char *path, const cj_allocator *alloc, cj_patchset **out);
void cj_patchset_destroy(cj_patchset *set);

/* scene: scene.h, scene_json.h */
typedef struct cj_vec3 { double x, y, z; } cj_vec3;
typedef struct cj_rgb { double r, g, b; } cj_rgb;
typedef enum cj_projection { CJ_PROJ_PERSPECTIVE, CJ_PROJ_ORTHOGRAPHIC } cj_projection;
typedef struct cj_camera {
    cj_vec3 eye; cj_vec3 gaze; cj_vec3 up; double near; double far;
    cj_projection projection; double fov_y; double ortho_height;
    ...;
} cj_camera;
cj_camera cj_camera_defaults(void);
typedef enum cj_light_kind {
    CJ_LIGHT_AMBIENT, CJ_LIGHT_POINT, CJ_LIGHT_DIRECTIONAL, CJ_LIGHT_SPOT, CJ_LIGHT_AREA,
    CJ_LIGHT_DISC, CJ_LIGHT_SPHERE
} cj_light_kind;
typedef struct cj_light {
    cj_light_kind kind; cj_rgb color; double intensity; cj_vec3 position; cj_vec3 direction;
    ...;
} cj_light;
cj_light cj_light_defaults(cj_light_kind kind);
typedef struct cj_material {
    cj_rgb color; cj_rgb specular; double ka; double kd; double ks; double alpha;
    int two_sided; double opacity; double mirror; double transmission; double ior;
    ...;
} cj_material;
cj_material cj_material_defaults(void);
typedef enum cj_geometry_kind { CJ_GEOM_PATCHES, CJ_GEOM_SPHERE, ... } cj_geometry_kind;
typedef struct cj_geometry { cj_geometry_kind kind; ...; } cj_geometry;
typedef struct cj_transform { cj_vec3 translate; double rotation[4]; cj_vec3 scale; ...; }
    cj_transform;
typedef struct cj_node { cj_transform local; ...; } cj_node;
typedef struct cj_scene_settings {
    int width, height; int spp; double tol_px; cj_rgb background; int max_depth;
    uint64_t seed;
    ...;
} cj_scene_settings;
typedef struct cj_scene cj_scene;
cj_status cj_scene_create(const cj_allocator *alloc, cj_scene **out);
void cj_scene_destroy(cj_scene *scene);
cj_status cj_scene_set_camera(cj_scene *scene, const cj_camera *cam);
const cj_camera *cj_scene_get_camera(const cj_scene *scene);
cj_status cj_scene_set_settings(cj_scene *scene, const cj_scene_settings *s);
const cj_scene_settings *cj_scene_get_settings(const cj_scene *scene);
cj_status cj_scene_add_light(cj_scene *scene, const cj_light *light, int *index);
cj_status cj_scene_add_material(cj_scene *scene, const cj_material *mat, int *index);
cj_status cj_scene_add_geometry(cj_scene *scene, const cj_geometry *geom, int *index);
cj_status cj_scene_add_node(cj_scene *scene, const cj_node *node, int *index);
size_t cj_scene_node_count(const cj_scene *scene);
size_t cj_scene_light_count(const cj_scene *scene);
cj_status cj_scene_check(const cj_scene *scene);
typedef struct cj_scene_json_options { const char *teapot_path; } cj_scene_json_options;
cj_status cj_scene_parse_json_with_options(const char *text, const char *name, const char *base_dir,
                                 const cj_scene_json_options *options,
                                 const cj_allocator *alloc, cj_scene **out);
cj_status cj_scene_load_json_with_options(const char *path, const cj_scene_json_options *options,
                                const cj_allocator *alloc, cj_scene **out);
cj_status cj_scene_save_json(const cj_scene *scene, const char *path);

/* raster: render.h, trace.h */
#define CJ_IMAGE_IDS ...
#define CJ_IMAGE_DEPTH ...
typedef struct cj_render_image {
    int width, height; float *rgba; uint32_t *ids; float *depth; ...;
} cj_render_image;
void cj_render_image_destroy(cj_render_image *img);
cj_status cj_render_image_to_srgb8(const cj_render_image *img, uint8_t *rgba8, size_t stride);
typedef struct cj_render_options {
    int width, height; int spp; double tol_px; int threads; int tile_size; int max_depth;
    int use_seed; uint64_t seed; ...;
} cj_render_options;
cj_render_options cj_render_options_defaults(void);
typedef struct cj_stage_report cj_stage_report;
cj_status cj_render_raster(const cj_scene *scene, const cj_render_options *opt,
                           unsigned planes, const cj_allocator *alloc, cj_render_image **out,
                           cj_stage_report *report);
cj_status cj_render_trace(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                          const cj_allocator *alloc, cj_render_image **out,
                          cj_stage_report *report);
cj_node cj_node_defaults(int geometry, int material);
"""

# The sphere and patch geometries are filled in C: cffi cannot name members of the anonymous
# union inside cj_geometry, so two small helpers (static, in the module only) do it.
SOURCE = r"""
#include "casteljau/bezier.h"
#include "casteljau/bspline.h"
#include "casteljau/bspline_fit.h"
#include "casteljau/bspline_surface.h"
#include "casteljau/flatten.h"
#include "casteljau/intersect.h"
#include "casteljau/mesh.h"
#include "casteljau/nearest.h"
#include "casteljau/offset.h"
#include "casteljau/patch.h"
#include "casteljau/patchset.h"
#include "casteljau/rational.h"
#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/scene_json.h"
#include "casteljau/status.h"
#include "casteljau/tessellate.h"
#include "casteljau/trace.h"

static cj_geometry cjpy_sphere(double x, double y, double z, double radius) {
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.center.x = x;
    g.u.sphere.center.y = y;
    g.u.sphere.center.z = z;
    g.u.sphere.radius = radius;
    return g;
}

static cj_geometry cjpy_patches(cj_patch *patches, size_t count) {
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = count;
    g.u.patches.patches = patches;
    return g;
}
"""

HELPERS = r"""
cj_geometry cjpy_sphere(double x, double y, double z, double radius);
cj_geometry cjpy_patches(cj_patch *patches, size_t count);
"""


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: build_cffi.py OUT.c")
    ffi = cffi.FFI()
    ffi.cdef(CDEF + HELPERS)
    ffi.set_source("casteljau._casteljau_cffi", "#include <string.h>\n" + SOURCE)
    ffi.emit_c_code(sys.argv[1])


if __name__ == "__main__":
    main()
