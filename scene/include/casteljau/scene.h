/* casteljau: the scene model shared by the rasterizer, the ray tracer, the animation and the
 * viewer (DESIGN.md, "Rendering, scenes and animation").
 *
 * A scene holds a camera, lights, materials, textures, geometries and a hierarchy of nodes.
 * A scene built from code needs no file: create one, add what it holds, render it. A JSON file
 * (casteljau/scene_json.h) is only one way to build it.
 *
 * OWNERSHIP: cj_scene_create() makes an empty scene that owns everything added to it (every
 * add function COPIES its input, including the arrays a geometry points to); destroy releases
 * it all through the allocator it was created with. Indices returned by the add functions are
 * stable for the life of the scene. Pointers returned by cj_scene_geometry() etc. stay valid
 * until the next add of the same kind.
 *
 * UNITS AND CONVENTIONS (seed notation):
 *   - geometry in double, right-handed world space;
 *   - colours are LINEAR RGB (not sRGB), radiance and reflectance alike; conversion to 8-bit
 *     sRGB happens once, when an image is written;
 *   - the camera: eye ē, gaze g⃗, up t⃗, near f and far F both negative with F < f < 0 (the
 *     camera looks down its −w axis), pseudodepth in [−1, 1], −1 at the near plane and +1 at
 *     the far plane (the framebuffer clears depth to +1);
 *   - triangles are counter-clockwise seen from outside; a back face is culled when
 *     (p̄ − ē)·n⃗ > 0 unless its material is two-sided.
 *
 * Status codes of the add/set functions: CJ_ERR_NONFINITE (a NaN/Inf field, named),
 * CJ_ERR_RANGE (a value out of its documented range, named), CJ_ERR_ARGUMENT (an index that
 * names nothing, a parent that is not a group or comes later), CJ_ERR_DEGENERATE (a zero gaze,
 * up parallel to gaze, a zero-size primitive), CJ_ERR_NOMEM. Nothing is added on failure.
 */
#ifndef CASTELJAU_SCENE_H
#define CASTELJAU_SCENE_H

#include "casteljau/alloc.h"
#include "casteljau/analytic.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/mesh.h"
#include "casteljau/patch.h"
#include "casteljau/quadric.h"
#include "casteljau/status.h"
#include "casteljau/transform.h"
#include "casteljau/vec.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Linear RGB. */
typedef struct cj_rgb {
    double r, g, b;
} cj_rgb;

static inline cj_rgb cj_rgb_make(double r, double g, double b) {
    cj_rgb c;
    c.r = r;
    c.g = g;
    c.b = b;
    return c;
}

/* ---- camera (seed 6) ------------------------------------------------------------------- */

typedef enum cj_projection { CJ_PROJ_PERSPECTIVE = 0, CJ_PROJ_ORTHOGRAPHIC } cj_projection;

typedef struct cj_camera {
    cj_vec3 eye;  /* ē */
    cj_vec3 gaze; /* g⃗, any non-zero length */
    cj_vec3 up;   /* t⃗, not parallel to g⃗ */
    double near;  /* f < 0: the near plane z = f in camera coordinates */
    double far;   /* F < f: the far plane */
    cj_projection projection;
    double fov_y;        /* perspective: full vertical field of view, radians, in (0, pi) */
    double ortho_height; /* orthographic: height of the view volume in world units, > 0 */
    /* Thin lens (seed 6.1; the ray tracer only, the rasterizer is a pinhole): the lens
     * diameter A in world units (0, the default: a pinhole) and the distance F from the eye to
     * the plane in focus, along the gaze (> 0 when A > 0; perspective cameras only). A point
     * at distance d along the gaze is blurred into a disk of diameter A |d − F| / d on the
     * plane in focus (the circle of confusion). */
    double aperture;
    double focus_distance;
} cj_camera;

/* A camera at (0, 0, 5) looking at the origin, up +y, 45° vertical field of view,
 * f = −0.1, F = −100, perspective. */
cj_camera cj_camera_defaults(void);

/* Validates a camera (finite fields, F < f < 0, non-degenerate basis, fov in (0, pi)). */
cj_status cj_camera_check(const cj_camera *cam);

/* The camera frame (seed 6.1): w = −g⃗/|g⃗|, u = t⃗×w/|t⃗×w|, v = w×u. */
cj_status cj_camera_basis(const cj_camera *cam, cj_vec3 *u, cj_vec3 *v, cj_vec3 *w);

/* World -> camera coordinates (M_cam): the eye to the origin, u, v, w to x, y, z. */
cj_status cj_camera_view(const cj_camera *cam, cj_xform3 *out);

/* Camera -> clip coordinates for an image of aspect = width/height: perspective
 *   x_c = x cot(fov/2)/aspect,  y_c = y cot(fov/2),  z_c = A z + B,  w_c = −z
 * with z_ndc = z_c/w_c = −1 at z = f and +1 at z = F (pseudodepth, seed 6.3 with the sign
 * chosen so that smaller is nearer); orthographic maps the box [−h·aspect/2, h·aspect/2] ×
 * [−h/2, h/2] × [F, f] to [−1, 1]³ with w_c = 1. */
cj_status cj_camera_projection(const cj_camera *cam, double aspect, cj_xform3 *out);

/* Projection × view: world -> clip. */
cj_status cj_camera_world_to_clip(const cj_camera *cam, double aspect, cj_xform3 *out);

/* The primary ray through the image point (px, py) in pixel units of a width × height image
 * (origin at the lower-left corner, pixel centres at half-integers): origin and UNIT direction
 * in world space. Perspective rays start at the eye, orthographic ones on the plane of the
 * eye. The ray through a pixel centre hits exactly the points the rasterizer projects to that
 * centre (same camera model). */
cj_status cj_camera_ray(const cj_camera *cam, int width, int height, double px, double py,
                        cj_vec3 *origin, cj_vec3 *dir);

/* The thin-lens ray through image point (px, py) and lens point (lu, lv) in [0, 1)²: the
 * lens point e + r (cos φ u + sin φ v) with r = (A/2) √lu, φ = 2π lv (uniform on the lens
 * disk), aimed at where the pinhole ray through (px, py) meets the plane in focus (distance F
 * along the gaze). A pinhole camera (aperture 0) gives cj_camera_ray's ray. Same status codes. */
cj_status cj_camera_lens_ray(const cj_camera *cam, int width, int height, double px, double py,
                             double lu, double lv, cj_vec3 *origin, cj_vec3 *dir);

/* ---- lights (seed 8) -------------------------------------------------------------------- */

typedef enum cj_light_kind {
    CJ_LIGHT_AMBIENT = 0, /* I_a: only colour × intensity is used */
    CJ_LIGHT_POINT,       /* at `position` */
    CJ_LIGHT_DIRECTIONAL, /* light travelling along `direction` (from the light) */
    CJ_LIGHT_SPOT,        /* at `position`, along `direction`, cone `spot_angle`, falloff */
    CJ_LIGHT_AREA,        /* parallelogram position + s·edge_u + t·edge_v, s,t in [0,1] */
    CJ_LIGHT_DISC,        /* disc of `radius` centred at `position`, emitting along `direction`
                             (the side its normal `direction` points to) */
    CJ_LIGHT_SPHERE       /* sphere of `radius` centred at `position`, emitting outwards */
} cj_light_kind;

typedef struct cj_light {
    cj_light_kind kind;
    cj_rgb color;     /* linear */
    double intensity; /* >= 0; colour × intensity is the light's I */
    cj_vec3 position;
    cj_vec3 direction;
    double spot_angle;    /* half-angle of the cone, radians, (0, pi/2] */
    double spot_exponent; /* >= 0 */
    cj_vec3 edge_u, edge_v;
    double radius;     /* disc and sphere: > 0 */
    int casts_shadows; /* ray tracer: 1 = shadow rays are cast for this light (default 1) */
} cj_light;

/* WHAT A LIGHT'S colour × intensity MEANS depends on the scene's light model
 * (cj_scene_settings.light_model; docs/light.md):
 *   CJ_LIGHT_LEGACY (the default, every scene written before the choice existed): I is a
 *     non-physical strength; no light falls off with distance; an area light is seen by the
 *     rasterizer as a point light at its centre and by the tracer as the mean of point lights
 *     over its surface; materials reflect with the Phong model of cj_material.
 *   CJ_LIGHT_RADIOMETRIC (seed 12): lights have units and materials are BRDFs.
 *     ambient      I_a is a radiance [W m⁻² sr⁻¹] arriving from every direction; a surface
 *                  reflects r_a c_r I_a (its ambient albedo times it);
 *     point        I is a radiant intensity [W sr⁻¹]: irradiance I cos θ / r² at distance r;
 *     spot         the same, times the cone's falloff (cos ψ)^spot_exponent inside spot_angle;
 *     directional  I is the irradiance [W m⁻²] on a surface facing the light: E = I cos θ;
 *     area         I is the radiance L_e of a Lambertian emitter [W m⁻² sr⁻¹] on the side its
 *                  normal edge_u × edge_v points to (none on the other side): irradiance
 *                  ∫ L_e cos θ cos θ′ / r² dA over the parallelogram. The tracer samples it by
 *                  area (pdf 1/A, stratified); the rasterizer takes the exact irradiance of the
 *                  polygon for the diffuse term (Lambert's formula) and its centre as a point of
 *                  intensity L_e A cos θ′ for the specular one.
 *     disc, sphere I is the radiance L_e of a Lambertian emitter: a disc emits on the side its
 *                  normal `direction` points to, a sphere outwards. The tracer samples a disc by
 *                  area (pdf 1/(π R²)) and a sphere by the solid angle of its cone from the point
 *                  (pdf 1/(2π (1 − cos θ_max)), sin θ_max = R/d). The rasterizer takes a
 *                  disc's diffuse term as that of the regular 32-gon of its area (Lambert's
 *                  formula, clipped to the horizon: within 2·10⁻⁵ of the on-axis irradiance
 *                  wherever the receiver is at least R/4 from the disc's plane) and its specular
 *                  one from its centre as a point of intensity π R² L_e cos θ′; a sphere as its
 *                  centre of intensity π R² L_e (exact wherever all of it is above the
 *                  horizon), and where the horizon cuts it by the clipped polygon of the disc
 *                  filling the same cone (docs/light.md).
 *   The reflected radiance is then Σ f_r E with the material's BRDF
 *     f_r = r_d c_r / π + r_s c_p f_s
 *   (f_s the energy-conserving form of the specular lobe of cj_specular_model:
 *   (α+2)/(2π) max(0, m·v)^α for Phong, (α+1)/(8π) max(0, n·h)^α / ((l·h) max(n·l, n·v)) for
 *   Blinn; raster/src/reflect_model.h, docs/light.md).
 * Emissive materials (cj_material.emission, a radiance) are seen by camera and secondary rays
 * in both models. */
typedef enum cj_light_model { CJ_LIGHT_LEGACY = 0, CJ_LIGHT_RADIOMETRIC } cj_light_model;

/* A white point light of intensity 1 at (5, 5, 5), casting shadows. */
cj_light cj_light_defaults(cj_light_kind kind);

/* ---- textures (seed 10) ------------------------------------------------------------------ */

typedef enum cj_texture_kind { CJ_TEX_IMAGE = 0, CJ_TEX_CHECKER } cj_texture_kind;
typedef enum cj_tex_filter {
    CJ_TEX_NEAREST = 0,
    CJ_TEX_BILINEAR,
    CJ_TEX_TRILINEAR /* mip-mapped */
} cj_tex_filter;
typedef enum cj_tex_wrap { CJ_TEX_REPEAT = 0, CJ_TEX_CLAMP } cj_tex_wrap;

typedef struct cj_texture {
    cj_texture_kind kind;
    cj_tex_filter filter;
    cj_tex_wrap wrap;
    double scale_u, scale_v; /* (u, v) -> (u·scale_u + offset_u, v·scale_v + offset_v) */
    double offset_u, offset_v;
    /* CJ_TEX_IMAGE: the file (as given; resolved against the scene file's folder when read)
     * and, once loaded (cj_scene_set_texture_pixels), width × height LINEAR RGBA float texels,
     * bottom row first. A scene whose image textures have no pixels cannot be rendered
     * (CJ_ERR_ARGUMENT naming the texture). */
    const char *path;
    int width, height;
    const float *texels;
    /* CJ_TEX_CHECKER: squares of 1/checks_u × 1/checks_v in (u, v), colours a and b. */
    int checks_u, checks_v;
    cj_rgb checker_a, checker_b;
} cj_texture;

cj_texture cj_texture_defaults(cj_texture_kind kind);

/* ---- materials (seed 8-13) -------------------------------------------------------------- */

typedef enum cj_shading { CJ_SHADE_FLAT = 0, CJ_SHADE_GOURAUD, CJ_SHADE_PHONG } cj_shading;

/* The specular lobe of the local reflection model (docs/light.md; both renderers evaluate it
 * through one definition, raster/src/reflect_model.h). With n the unit normal, l the unit
 * direction to the light, v the unit direction to the viewer, and only where n·l > 0 (a light
 * behind the surface gives no highlight):
 *   CJ_SPEC_BLINN  s = max(0, n·h)^α, h = (l + v)/|l + v|   (Blinn's half vector; the default,
 *                  the model every scene written before the choice existed was drawn with)
 *   CJ_SPEC_PHONG  s = max(0, m·v)^α, m = 2(n·l)n − l       (the seed's mirror form) */
typedef enum cj_specular_model { CJ_SPEC_BLINN = 0, CJ_SPEC_PHONG } cj_specular_model;

typedef struct cj_material {
    /* Phong (seed 8): L = c_r (r_a I_a + r_d Σ I max(0, n·l)) + c_p r_s Σ_{n·l>0} I s
     * where c_r is the diffuse colour (times the texture when there is one), c_p the specular
     * colour and s the specular lobe named by specular_model (Blinn by default); the ray
     * tracer reads the same fields and evaluates the same formula. */
    cj_rgb color;    /* c_r, linear, each in [0, 1] */
    cj_rgb specular; /* c_p, linear, each in [0, 1] */
    double ka;       /* r_a >= 0 */
    double kd;       /* r_d >= 0 */
    double ks;       /* r_s >= 0 */
    double alpha;    /* α >= 0, the Phong exponent */
    cj_shading shading;
    int two_sided;  /* 1: no backface culling, the normal is flipped to face the viewer */
    int texture;    /* index of a scene texture modulating c_r, or −1 */
    double opacity; /* in [0, 1]; < 1 makes the material transparent (drawn back to front) */
    /* Ray tracer (seed 11-13): read by the tracer only, kept in the format from the start. */
    double mirror;        /* r_m in [0, 1]: weight of the mirror reflection ray */
    double transmission;  /* r_t in [0, 1]: weight of the refracted ray */
    double ior;           /* index of refraction >= 1 (inside the object) */
    double glossiness;    /* Phong-lobe exponent of glossy reflection; 0 = perfect mirror */
    cj_rgb emission;      /* emitted radiance (area lights drawn as objects), linear */
    int receives_shadows; /* 1 (default): shadow rays are cast from this material's hits */
    cj_specular_model specular_model; /* the specular lobe s (default CJ_SPEC_BLINN) */
} cj_material;

/* Grey plastic: colour 0.8, specular 1, r_a 0.1, r_d 0.7, r_s 0.3, α 32, Phong shading,
 * one-sided, no texture, opaque, no mirror/transmission, ior 1.5, receives shadows. */
cj_material cj_material_defaults(void);

/* ---- geometry ---------------------------------------------------------------------------- */

typedef enum cj_geometry_kind {
    CJ_GEOM_PATCHES = 0, /* Bézier patches (polynomial or rational), e.g. the teapot */
    CJ_GEOM_QUADRIC,     /* any of the six quadrics of casteljau/quadric.h */
    CJ_GEOM_SPHERE,      /* centre + radius (an ellipsoid a = b = c the ray tracer knows) */
    CJ_GEOM_TORUS,
    CJ_GEOM_CYLINDER,
    CJ_GEOM_PLANAR,       /* planar patch p + s eu + t ev, s,t in [0,1] (floors, walls) */
    CJ_GEOM_BILINEAR,     /* bilinear patch */
    CJ_GEOM_REVOLUTION,   /* profile (r(t), z(t)) as a Bézier curve, revolved about an axis */
    CJ_GEOM_GEN_CYLINDER, /* planar Bézier profile swept along a direction */
    CJ_GEOM_MESH,         /* triangle mesh (OBJ, PLY, or from code) */
    CJ_GEOM_CURVE,        /* 3D curve drawn as a line: Bézier, rational Bézier, Catmull-Rom */
    CJ_GEOM_KIND_COUNT_
} cj_geometry_kind;

typedef enum cj_curve_kind {
    CJ_CURVE_BEZIER = 0,
    CJ_CURVE_RATIONAL,
    CJ_CURVE_SPLINE /* interpolating spline through the points (casteljau/catmull_rom.h) */
} cj_curve_kind;

typedef struct cj_geometry {
    cj_geometry_kind kind;
    union {
        struct {
            size_t count;      /* patches */
            cj_patch *patches; /* owned views into owned point/weight arrays */
        } patches;
        cj_quadric quadric;
        struct {
            cj_vec3 center;
            double radius;
        } sphere;
        cj_torus torus;
        cj_cylinder cylinder;
        cj_planar_patch planar;
        cj_bilinear bilinear;
        struct {
            int degree;            /* profile degree >= 1 */
            const double *pts;     /* (degree+1) × 2: (r, z) per control point, owned */
            const double *weights; /* NULL or degree+1 weights > 0, owned */
            cj_vec3 origin, axis;
        } revolution;
        struct {
            int degree;
            const double *pts; /* (degree+1) × 2 in the (e1, e2) plane, owned */
            const double *weights;
            cj_vec3 origin, e1, e2, dir;
            double v0, v1;
        } gen_cylinder;
        cj_mesh *mesh; /* owned */
        struct {
            cj_curve_kind kind;
            int degree;            /* BEZIER/RATIONAL: degree; SPLINE: unused */
            size_t count;          /* control points (spline: points interpolated) */
            const double *pts;     /* count × 3, owned */
            const double *weights; /* RATIONAL: count weights > 0, owned; else NULL */
            cj_spline_kind spline;
            double tension, continuity, bias; /* spline parameters (κ or T, C, B) */
            int closed;
            double width_px; /* line width in pixels (>= 1; 1 draws exact Bresenham lines) */
            cj_rgb color;
        } curve;
    } u;
} cj_geometry;

/* ---- nodes: objects and groups in a hierarchy (seed 3, 5) --------------------------------- */

/* Overlays drawn over a node's surface as depth-tested lines. */
enum {
    CJ_OVERLAY_CONTROL_NET = 1u, /* patches: the control net; curves: the control polygon */
    CJ_OVERLAY_WIREFRAME = 2u,   /* the triangles the renderer drew */
    CJ_OVERLAY_ISO_LINES = 4u,   /* iso-parameter lines, iso_count per direction */
    CJ_OVERLAY_NORMALS = 8u      /* vertex normals, normal_length long (world units) */
};

typedef struct cj_overlay_style {
    unsigned flags;       /* CJ_OVERLAY_* */
    cj_rgb color;         /* line colour, linear */
    int iso_count;        /* >= 1 */
    double normal_length; /* > 0 */
} cj_overlay_style;

/* The local transform of a node, applied to column vectors as
 *   M = T(translate) · R(rotation) · S(scale) · matrix
 * (matrix first). Keeping T, R, S apart lets animation channels act on each (rotation as a
 * unit quaternion w + xi + yj + zk). The world transform of a node is its parent's world
 * transform times its local one. */
typedef struct cj_transform {
    cj_vec3 translate;
    double rotation[4]; /* unit quaternion (w, x, y, z) */
    cj_vec3 scale;      /* non-zero components */
    cj_xform3 matrix;   /* any invertible affine matrix (shear, mirror, ...) */
} cj_transform;

cj_transform cj_transform_identity(void);
/* M as a 4×4 matrix. */
cj_xform3 cj_transform_matrix(const cj_transform *t);

typedef struct cj_node {
    const char *name;   /* owned copy, may be NULL */
    int parent;         /* index of a group node added earlier, or −1 for the root */
    cj_transform local; /* relative to the parent */
    int geometry;       /* index of a geometry, or −1 for a group */
    int material;       /* index of a material (objects); groups: −1 */
    cj_overlay_style overlay;
    int visible; /* 0: skipped by every renderer */
    uint32_t id; /* object id (signature image, id buffer): 1 + index among objects */
} cj_node;

/* A node with the defaults every builder wants: no parent, identity transform, visible, no
 * overlay (white lines, 1 iso line, normals 0.1 long when switched on). */
cj_node cj_node_defaults(int geometry, int material);

/* ---- render settings stored with the scene (CLI flags override them) ---------------------- */

/* The ray tracer's pixel reconstruction filter (docs/light.md), separable f(dx) f(dy) over
 * |dx|, |dy| < r pixels from the pixel centre, the pixel the weighted mean Σ f L / Σ f of its
 * samples (spread over the filter's support). r = filter_radius, or when 0 the default below.
 *   BOX       f = 1                                   (default r 0.5: the pixel itself)
 *   TENT      f = 1 − |x|/r                           (default r 1)
 *   GAUSSIAN  f = exp(−x²/2σ²) − exp(−r²/2σ²), σ = r/3 (default r 1.5)
 *   MITCHELL  Mitchell–Netravali, B = C = 1/3, of t = 2|x|/r (default r 2; negative lobes)
 * The rasterizer always box-filters its samples. */
typedef enum cj_pixel_filter {
    CJ_FILTER_BOX = 0,
    CJ_FILTER_TENT,
    CJ_FILTER_GAUSSIAN,
    CJ_FILTER_MITCHELL
} cj_pixel_filter;

typedef struct cj_scene_settings {
    int width, height;          /* image size, 1..CJ_FRAMEBUFFER_MAX_SIDE (default 640 × 480) */
    int spp;                    /* samples per pixel: rasterizer 1, 4 or 16; ray tracer any >= 1 */
    double tol_px;              /* screen-space tessellation tolerance in pixels (default 0.25) */
    cj_rgb background;          /* linear (default black) */
    int max_depth;              /* ray tracer recursion depth (default 5) */
    uint64_t seed;              /* random sampling seed (default 1) */
    cj_light_model light_model; /* what light intensities mean (default CJ_LIGHT_LEGACY) */
    cj_pixel_filter filter;     /* ray tracer, spp > 1 (default CJ_FILTER_BOX) */
    double filter_radius;       /* pixels, >= 0; 0: the filter's default */
} cj_scene_settings;

cj_scene_settings cj_scene_settings_defaults(void);

/* ---- the scene ------------------------------------------------------------------------------ */

typedef struct cj_scene cj_scene;

cj_status cj_scene_create(const cj_allocator *alloc, cj_scene **out);
void cj_scene_destroy(cj_scene *scene);

cj_status cj_scene_set_camera(cj_scene *scene, const cj_camera *cam);
const cj_camera *cj_scene_get_camera(const cj_scene *scene);
cj_status cj_scene_set_settings(cj_scene *scene, const cj_scene_settings *s);
const cj_scene_settings *cj_scene_get_settings(const cj_scene *scene);

cj_status cj_scene_add_light(cj_scene *scene, const cj_light *light, int *index);
cj_status cj_scene_add_texture(cj_scene *scene, const cj_texture *tex, int *index);
/* Copies width × height × 4 linear float texels into texture `index` (image textures). */
cj_status cj_scene_set_texture_pixels(cj_scene *scene, int index, int width, int height,
                                      const float *rgba);
cj_status cj_scene_add_material(cj_scene *scene, const cj_material *mat, int *index);
/* Deep-copies the geometry (the arrays it points to, the mesh). */
cj_status cj_scene_add_geometry(cj_scene *scene, const cj_geometry *geom, int *index);
/* Adds a node; `node->id` is assigned by the scene (ignored on input). */
cj_status cj_scene_add_node(cj_scene *scene, const cj_node *node, int *index);

size_t cj_scene_light_count(const cj_scene *scene);
size_t cj_scene_texture_count(const cj_scene *scene);
size_t cj_scene_material_count(const cj_scene *scene);
size_t cj_scene_geometry_count(const cj_scene *scene);
size_t cj_scene_node_count(const cj_scene *scene);
const cj_light *cj_scene_light(const cj_scene *scene, int index);
const cj_texture *cj_scene_texture(const cj_scene *scene, int index);
const cj_material *cj_scene_material(const cj_scene *scene, int index);
const cj_geometry *cj_scene_geometry(const cj_scene *scene, int index);
const cj_node *cj_scene_node(const cj_scene *scene, int index);

/* Mutable access for editors and animation (the viewer, keyframe channels). The caller keeps
 * the values valid; cj_scene_check() re-validates. */
cj_light *cj_scene_light_mut(cj_scene *scene, int index);
cj_material *cj_scene_material_mut(cj_scene *scene, int index);
cj_node *cj_scene_node_mut(cj_scene *scene, int index);
cj_geometry *cj_scene_geometry_mut(cj_scene *scene, int index);

/* Optional names of materials and textures (the JSON format refers to them by name; an editor
 * shows them), copied; NULL = unnamed. CJ_ERR_ARGUMENT for an index that names nothing,
 * CJ_ERR_NOMEM. Names are not checked for uniqueness here (cj_scene_save_json refuses repeats). */
cj_status cj_scene_set_material_name(cj_scene *scene, int index, const char *name);
const char *cj_scene_material_name(const cj_scene *scene, int index);
cj_status cj_scene_set_texture_name(cj_scene *scene, int index, const char *name);
const char *cj_scene_texture_name(const cj_scene *scene, int index);
/* Where texture `index` was defined, for the messages of later stages (the texture loader of
 * casteljau/scene_textures.h), e.g. "scenes/teapot.json:12: textures[0]"; copied; NULL when
 * unknown (a scene built from code). */
cj_status cj_scene_set_texture_source(cj_scene *scene, int index, const char *where);
const char *cj_scene_texture_source(const cj_scene *scene, int index);

/* World transform of node `index` (parents composed). */
cj_status cj_scene_node_world(const cj_scene *scene, int index, cj_xform3 *out);

/* Whether node `index` is shown: its own `visible` and that of every group above it (a hidden
 * group hides its whole subtree). The one walk up the parent chain that every renderer, the
 * viewer and the exports use. 0 for an index that names no node. */
int cj_scene_node_shown(const cj_scene *scene, int index);

/* cj_scene_node_shown of every node at once, in one pass (parents come before their children):
 * shown[i] for i < cj_scene_node_count(scene). */
void cj_scene_nodes_shown(const cj_scene *scene, unsigned char *shown);

/* Validates the whole scene (every field of every part); the message names the part
 * ("materials[2].alpha must be >= 0"). Renderers call it first: the rasterizer and the ray
 * tracer accept exactly the same scenes. Beyond finiteness it bounds what would overflow
 * later: every coordinate, length, direction and scale within +-CJ_SCENE_MAX_COORD (an eye,
 * a radius or an OBJ vertex at 1e308 is refused by name, not found as an inf clip coordinate
 * or a "parallel up vector"), light intensity times colour and material emission at most
 * CJ_SCENE_MAX_RADIANCE (radiance is float), and Bezier patches whose control points all lie
 * on one line (no area: CJ_ERR_DEGENERATE). */
#define CJ_SCENE_MAX_COORD    1e9
#define CJ_SCENE_MAX_RADIANCE 1e9
cj_status cj_scene_check(const cj_scene *scene);

#ifdef __cplusplus
}
#endif
#endif
