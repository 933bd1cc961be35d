/* The surface document: a B-spline / NURBS surface alone, the object of the scene's
 * "bspline_surface" / "nurbs_surface" geometry (scene_json.h): {"type": "bspline_surface" |
 * "nurbs_surface", "degree": [p, q], "size": [nu, nv], "points": [[x, y, z] x nu nv] (u
 * fastest), "knots_u", "knots_v" (optional: clamped uniform on [0, 1]), "weights" (nurbs_surface
 * only, required)}. `casteljau fit --grid` writes it; `tessellate --surface`, `section
 * --surface` and `nearest --surface` read it. One reader: the scene layer's reader of that
 * geometry (scene/src/bspline_surface_json.c), so a surface reads the same alone or in a scene. */
#ifndef CASTELJAU_FORMATS_SURFACE_JSON_H
#define CASTELJAU_FORMATS_SURFACE_JSON_H

#include "casteljau/bspline_surface.h"

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Parses text, the document `name` (in messages), into *out, whose arrays are malloc'd (free with
 * cj_surface_json_free; on failure *out holds nothing). Errors, each "<name>:<line>: <path> ..."
 * (cj_last_error): CJ_ERR_PARSE (syntax, a missing or unknown key, a wrong type), CJ_ERR_RANGE (a
 * value out of range), the library's status for knots it refuses, CJ_ERR_NOMEM. */
cj_status cj_surface_json_parse(const char *name, const char *text, cj_bspline_surface *out);
void cj_surface_json_free(cj_bspline_surface *s);

/* Prints the surface object with the writing kit (cJSON's printer, numbers in their shortest
 * exact form, a newline after it) onto f. Errors: CJ_ERR_NOMEM, CJ_ERR_IO, naming `what`. */
cj_status cj_surface_json_print(FILE *f, const cj_bspline_surface *s, const char *what);

#ifdef __cplusplus
}
#endif
#endif
