/* Private to the casteljau tool: a B-spline / NURBS surface from JSON, as Bézier patches.
 * The object is the scene's geometry (scene_json.h): {"type": "bspline_surface" |
 * "nurbs_surface", "degree": [p, q], "size": [nu, nv], "points": [[x, y, z] × nu nv] (u fastest),
 * "knots_u", "knots_v" (optional: clamped uniform on [0, 1]), "weights" (nurbs_surface only,
 * required)}. `casteljau fit --grid` writes it; `casteljau tessellate --surface` reads it. */
#ifndef CASTELJAU_APP_SURFACE_JSON_H
#define CASTELJAU_APP_SURFACE_JSON_H

#include "casteljau/bspline_surface.h"

#include <stddef.h>
#include <stdio.h>

typedef struct surface_patches {
    size_t count;
    cj_patch *patches;     /* views into pts / weights */
    double *pts, *weights; /* owned */
} surface_patches;

/* Reads the file (or standard input for "-") and converts. 0, or -1 with a one-line reason
 * naming the JSON field in why; *nomem is set when the failure was an allocation. */
int surface_json_load(const char *path, surface_patches *out, char *why, size_t why_size,
                      int *nomem);
void surface_json_free(surface_patches *s);

/* Prints the surface object with cJSON's printer (a newline after it), numbers in their
 * shortest exact form. 0, or -1 with cj_last_error() explaining (out of memory, a write error). */
int surface_json_write(FILE *f, const cj_bspline_surface *s);

#endif
