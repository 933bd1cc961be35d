/* Private to the casteljau tool: the surface document (formats/include/surface_json.h, read by
 * its one reader) loaded from a file as Bézier patches, for `tessellate --surface`, `section
 * --surface` and `nearest --surface`. */
#ifndef CASTELJAU_APP_SURFACE_LOAD_H
#define CASTELJAU_APP_SURFACE_LOAD_H

#include "casteljau/bspline_surface.h"

#include <stddef.h>

typedef struct surface_patches {
    size_t count;
    cj_patch *patches;     /* views into pts / weights */
    double *pts, *weights; /* owned */
} surface_patches;

/* Reads the file (or standard input for "-") and converts. 0, or -1 with a one-line reason
 * naming the JSON field in why; *nomem is set when the failure was an allocation. */
int surface_load(const char *path, surface_patches *out, char *why, size_t why_size, int *nomem);
void surface_patches_free(surface_patches *s);

#endif
