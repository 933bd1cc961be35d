/* casteljau: the JSON scene format (read through cJSON), one way to build a cj_scene.
 *
 * EVERY KEY IS CHECKED: an unknown key, a duplicate key, a wrong type, a value out of range, a
 * name that refers to nothing or a missing file is an error whose message (cj_last_error())
 * names the file, the line and the JSON path:
 *
 *     scene.json:14: objects[2].material.alpha must be >= 0
 *     scene.json:9: lights[0].colour is not a known key (expected one of: type, color, ...)
 *     scene.json:3:17: JSON syntax error (line 3, column 17)
 *
 * Nothing half-built is returned: on error *out is untouched and everything read is freed.
 *
 * THE DOCUMENT: one object with the keys below, all optional except "objects". Numbers are JSON
 * numbers; vectors are arrays of 3 numbers; colours are LINEAR RGB arrays of 3 numbers
 * (reflectances in [0, 1], radiances >= 0); booleans are true/false; angles are in degrees
 * ("..._deg") or radians ("..._rad"). Every default is the C default (cj_camera_defaults,
 * cj_light_defaults, cj_material_defaults, ...). Paths are relative to the scene file's folder.
 *
 * {
 *   "camera": {
 *     "eye": [0, 2, 8],            ē
 *     "look_at": [0, 0.5, 0],      or "gaze": [0, -0.2, -1]  (g⃗; one of the two)
 *     "up": [0, 1, 0],             t⃗, not parallel to the gaze
 *     "near": -0.1, "far": -100,   f and F, F < f < 0
 *     "projection": "perspective", or "orthographic"
 *     "fov_deg": 40,               full vertical field of view (or "fov_rad"), or
 *                                  "focal_length_mm": 50 with "sensor_height_mm" (24)
 *     "ortho_height": 4            orthographic: height of the view volume
 *     "aperture": 0.1,             thin lens (ray tracer): lens diameter (0: pinhole) and
 *     "focus_distance": 8          the distance of the plane in focus along the gaze
 *   },
 *   "settings": {"width": 640, "height": 480, "spp": 4, "tol_px": 0.25,
 *                "background": [0, 0, 0], "max_depth": 5, "seed": 1,
 *                "light_model": "legacy",    or "radiometric": what intensities mean
 *                "filter": "box", "filter_radius": 0},  ray tracer: box | tent | gaussian |
 *                                  mitchell, radius in pixels (0: the filter's default)
 *                                  (cj_light_model in casteljau/scene.h, docs/light.md)
 *   "lights": [
 *     {"type": "ambient", "color": [1, 1, 1], "intensity": 0.2},
 *     {"type": "point", "position": [5, 5, 5], "intensity": 1, "casts_shadows": true},
 *     {"type": "directional", "direction": [-1, -1, -1]},
 *     {"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "angle_deg": 30,
 *      "exponent": 2},
 *     {"type": "area", "position": [-1, 4, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2]},
 *     {"type": "disc", "position": [0, 4, 0], "direction": [0, -1, 0], "radius": 0.5},
 *     {"type": "sphere", "position": [2, 3, 0], "radius": 0.25}
 *   ],
 *   "textures": [
 *     {"name": "wood", "type": "image", "path": "textures/wood.png", "filter": "trilinear",
 *      "wrap": "repeat", "scale": [1, 1], "offset": [0, 0]},
 *     {"name": "tiles", "type": "checker", "checks": [8, 8],
 *      "colors": [[0.9, 0.9, 0.9], [0.1, 0.1, 0.1]]}
 *   ],                             filter: nearest | bilinear | trilinear; wrap: repeat | clamp
 *   "materials": [
 *     {"name": "red", "color": [0.8, 0.1, 0.1], "specular": [1, 1, 1], "ka": 0.1, "kd": 0.7,
 *      "ks": 0.3, "alpha": 32, "shading": "phong", "two_sided": false, "texture": "wood",
 *      "opacity": 1, "mirror": 0, "transmission": 0, "ior": 1.5, "glossiness": 0,
 *      "emission": [0, 0, 0], "receives_shadows": true, "specular_model": "blinn"}
 *   ],                             shading: flat | gouraud | phong; texture: a texture's name;
 *                                  specular_model: blinn (default) | phong (the mirror form)
 *   "geometries": [ {"name": "ball", "type": "sphere", "radius": 1} ],
 *                                  optional: geometries shared by name between objects
 *   "objects": [
 *     {"name": "pot", "material": "red", "visible": true,
 *      "transform": {"translate": [0, 0, 0], "rotate": {"axis": [1, 0, 0], "angle_deg": -90},
 *                    "scale": 0.5},
 *      "geometry": {"type": "teapot"},
 *      "overlay": {"control_net": true, "wireframe": false, "iso_lines": 0, "normals": 0,
 *                  "color": [1, 1, 0]}},
 *     {"name": "table", "transform": {"translate": [0, -1, 0]}, "material": "red",
 *      "children": [ {...}, {...} ]}
 *   ]
 * }
 *
 * OBJECTS (nodes): each has either "geometry" (an object as below, or the name of an entry of
 * "geometries") or "children" (a group: a list of objects under the group's transform).
 * "material" is a material's name or an inline material object (the keys of "materials" but
 * "name"); a group's material is the default of the objects under it; an object without one
 * gets the grey default material. "visible" (true). "overlay": control_net, wireframe
 * (booleans), iso_lines (count per direction, 0 = none), normals (length in world units,
 * 0 = none), color.
 *
 * TRANSFORM: M = T(translate) · R · S(scale) · matrix. "translate" [3]; the rotation is ONE of
 * "rotate": {"axis": [3], "angle_deg"}, "quaternion": [w, x, y, z] (normalised when read),
 * "euler_deg": [ax, ay, az] (angles about x, y, z) with "euler_order" (the sequence about the
 * fixed axes, "xyz" by default: x first, then y, then z: R = Rz Ry Rx); "scale" a number or
 * [3] (non-zero); "matrix" four rows of four numbers, last row [0, 0, 0, 1], invertible.
 *
 * GEOMETRY ("type" and the keys of that type):
 *   teapot        the Utah teapot (data/teapot.bpt, found as cj_scene_json_options says)
 *   bpt           "path": a .bpt patch file
 *   patches       "patches": [{"degree": [m, n], "points": [[x, y, z] × (m+1)(n+1)],
 *                 "weights": [(m+1)(n+1) numbers > 0] (optional: rational)}]; point j(m+1)+i
 *                 is b_ij (i along u runs fastest)
 *   bspline_surface  "degree": [p, q], "size": [nu, nv], "points": [[x, y, z] × nu nv] (point
 *                 j nu + i is d_ij, i along u fastest), "knots_u" (nu + p + 1 numbers),
 *                 "knots_v" (nv + q + 1) (both optional: clamped uniform on [0, 1]); converted
 *                 to its Bézier patches at load (casteljau/bspline_surface.h), so the geometry is
 *                 "patches" from then on (and is written back as such)
 *   nurbs_surface the same with "weights" [nu nv numbers > 0] (required): rational patches
 *   sphere        "center" ([0, 0, 0]), "radius"
 *   quadric       "kind": ellipsoid (a, b, c) | hyperboloid1 (a, b, c, v0, v1) | hyperboloid2
 *                 (a, b, c, v1, "lower": bool) | cone (a, b, c, v0, v1) | paraboloid (a, b, v1)
 *                 | hyperbolic_paraboloid (a, b, u0, u1, v0, v1), as casteljau/quadric.h
 *   torus         "center", "axis", "major", "minor"
 *   cylinder      "base", "axis", "radius", "h0", "h1"
 *   planar        (or "plane") "origin", "edge_u", "edge_v": origin + s edge_u + t edge_v
 *   bilinear      "p00", "p10", "p01", "p11"
 *   revolution    "points": [[r, z], ...] (a Bézier profile of degree count-1), "weights"
 *                 (optional), "origin" ([0, 0, 0]), "axis" ([0, 0, 1])
 *   gen_cylinder  "points": [[x, y], ...] in the (e1, e2) plane, "weights", "origin", "e1",
 *                 "e2", "dir", "v0", "v1"
 *   mesh          "path": an OBJ or PLY file (casteljau/mesh_read.h), or inline "positions"
 *                 [[x, y, z], ...], "triangles" [[a, b, c], ...] (0-based), "normals",
 *                 "uvs", "patch_ids" (one per triangle) optional; missing normals are computed
 *   curve         "kind": bezier | rational | catmull-rom | centripetal | chordal |
 *                 kochanek-bartels; "points" [[x, y, z], ...]; "weights" (rational);
 *                 "tension" (0.5; T for kochanek-bartels: 0), "continuity", "bias",
 *                 "closed" (splines), "width_px" (1), "color" ([1, 1, 1])
 *
 * Textures are read by cj_scene_load_textures (casteljau/scene_textures.h, viz/): this reader
 * keeps each image texture's path as written and records where it was defined
 * (cj_scene_texture_source) so a missing image is reported with the scene file and line.
 */
#ifndef CASTELJAU_SCENE_JSON_H
#define CASTELJAU_SCENE_JSON_H

#include "casteljau/alloc.h"
#include "casteljau/scene.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_scene_json_options {
    /* The Utah teapot's .bpt file for geometry "teapot" (the library has no fixed install
     * path; the command-line tool passes its own). NULL: "teapot" is CJ_ERR_UNSUPPORTED. */
    const char *teapot_path;
} cj_scene_json_options;

/* Parses `text` (NUL-terminated). `name` names the document in messages (usually the file
 * name); `base_dir` is the folder paths are relative to (NULL or "" = the current one);
 * options may be NULL (no teapot path). alloc (may be NULL) becomes the scene's allocator.
 * Status: CJ_ERR_PARSE (syntax, unknown or duplicate key, wrong type, a name that refers to
 * nothing), CJ_ERR_RANGE / CJ_ERR_NONFINITE / CJ_ERR_DEGENERATE (a value out of range),
 * CJ_ERR_IO (a referenced file cannot be read), CJ_ERR_UNSUPPORTED (teapot without a path),
 * CJ_ERR_NOMEM; the message is "name:line: path message". */
cj_status cj_scene_parse_json_with_options(const char *text, const char *name, const char *base_dir,
                                           const cj_scene_json_options *options,
                                           const cj_allocator *alloc, cj_scene **out);
/* cj_scene_parse_json_with_options without options. */
cj_status cj_scene_parse_json(const char *text, const char *name, const char *base_dir,
                              const cj_allocator *alloc, cj_scene **out);

/* Reads the file at `path` and parses it with base_dir = the file's folder and name = path.
 * CJ_ERR_IO if the file cannot be read. */
cj_status cj_scene_load_json_with_options(const char *path, const cj_scene_json_options *options,
                                          const cj_allocator *alloc, cj_scene **out);
/* cj_scene_load_json_with_options without options. */
cj_status cj_scene_load_json(const char *path, const cj_allocator *alloc, cj_scene **out);

/* Writes the scene as JSON that cj_scene_load_json reads back to an equal scene: every
 * material and texture (unnamed ones are named "material<i>" / "texture<i>", with "_" appended
 * while that clashes with another name) and every geometry
 * (inline data, in "geometries", named "geometry<i>") in index order, objects nested under their
 * groups in pre-order (a scene whose nodes are in pre-order, as every loaded scene is, comes
 * back with the same indices). Image texture paths are written as stored; texels are not
 * written. Atomic: a temporary file in the destination's folder is written, flushed, synced
 * and renamed onto `path`; on any failure it is removed and an old file at `path` is kept.
 * Status: CJ_ERR_IO (naming the path and the reason), CJ_ERR_NOMEM, CJ_ERR_ARGUMENT (two
 * materials or two textures with the same name, an empty name), CJ_ERR_RANGE (settings.seed
 * above 2^53, not exact in JSON), or what cj_scene_check reports (a scene that does not check is
 * not written). Shared geometries stay shared (objects refer to "geometries" by name). */
cj_status cj_scene_save_json(const cj_scene *scene, const char *path);

#ifdef __cplusplus
}
#endif
#endif
