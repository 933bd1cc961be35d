/* Private: the one reader and writer of the B-spline / NURBS surface object, shared by the scene
 * reader (a "bspline_surface" or "nurbs_surface" geometry, scene_json_geom.c) and by the surface
 * document of formats/ (surface_json.c: `tessellate --surface`, `section --surface`, `nearest
 * --surface`), which is that geometry alone. scene/ is the lowest layer that links cJSON, so it
 * lives here beside the kit it reads with (json_read_internal.h).
 *
 * The object: {"type": "bspline_surface" | "nurbs_surface", "degree": [p, q] (integers in
 * [1, CJ_PATCH_MAX_DEGREE]), "size": [nu, nv] (integers >= 2, at most 1e6 points in all),
 * "points": [[x, y, z] x nu nv] (u fastest), "knots_u": [nu + p + 1 numbers], "knots_v":
 * [nv + q + 1 numbers] (each optional: clamped uniform on [0, 1]), "weights": [nu nv numbers
 * > 0] (required for nurbs_surface, refused for bspline_surface)}, and "name" when `named`. */
#ifndef CASTELJAU_BSPLINE_SURFACE_JSON_INTERNAL_H
#define CASTELJAU_BSPLINE_SURFACE_JSON_INTERNAL_H

#include "casteljau/bspline_surface.h"
#include "json_read_internal.h"

/* Reads obj (at path, "" for a document's root) into *out, whose arrays are malloc'd (free with
 * cj_json_bspline_surface_free; *out is zeroed first, and holds nothing on failure). The knots
 * are checked by cj_bspline_surface_patch_count, so the surface converts to patches.
 * Errors, each "<name>:<line>: <path> ..." through cj_fail: CJ_ERR_PARSE (a missing or
 * unknown key, a wrong type, weights on a bspline_surface), CJ_ERR_RANGE (a value out of its
 * range), the status of cj_bspline_surface_patch_count for knots it refuses, CJ_ERR_NOMEM. */
cj_status cj_json_read_bspline_surface(const cj_json_doc *d, const cJSON *obj, const char *path,
                                       int named, cj_bspline_surface *out);
void cj_json_bspline_surface_free(cj_bspline_surface *s);

/* The one writer of that object: adds its members to obj (a cJSON object) in the order above,
 * knots always explicit, numbers through the writing kit (json_write_internal.h), so that the
 * reader rebuilds the same surface bit for bit. Used by the scene writer and the surface
 * document. CJ_OK, or CJ_ERR_NOMEM (obj then holds some members: drop it). */
cj_status cj_json_add_bspline_surface(cJSON *obj, const cj_bspline_surface *s);

#endif
