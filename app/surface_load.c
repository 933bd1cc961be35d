/* The surface document as Bézier patches. See surface_load.h. */
#include "surface_load.h"

#include "error_internal.h"
#include "file_internal.h"
#include "surface_json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SURFACE_MAX_BYTES ((size_t)256 << 20)

/* The surface's patches into out (arrays malloc'd). */
static cj_status to_patches(const cj_bspline_surface *s, surface_patches *out) {
    const int p = s->deg_u, q = s->deg_v;
    int np = 0;
    cj_status st = cj_bspline_surface_patch_count(s, &np);
    if (st) return st;
    const size_t per = (size_t)(p + 1) * (size_t)(q + 1);
    out->pts = malloc(sizeof(double) * 3 * per * (size_t)np);
    out->weights = s->weights ? malloc(sizeof(double) * per * (size_t)np) : NULL;
    out->patches = calloc((size_t)np, sizeof *out->patches);
    if (!out->pts || !out->patches || (s->weights && !out->weights))
        return cj_fail(CJ_ERR_NOMEM, "out of memory for %d patches", np);
    st = cj_bspline_surface_to_patches(s, out->pts, out->weights, NULL, NULL, np, NULL);
    if (st) return st;
    for (int i = 0; i < np; ++i)
        out->patches[i] = cj_patch_view(p, q, out->pts + 3 * per * (size_t)i,
                                        out->weights ? out->weights + per * (size_t)i : NULL);
    out->count = (size_t)np;
    return CJ_OK;
}

int surface_load(const char *path, surface_patches *out, char *why, size_t n, int *nomem) {
    memset(out, 0, sizeof *out);
    char *text = NULL;
    size_t size = 0;
    cj_status st = cj_file_read_input(path, SURFACE_MAX_BYTES, "surface document", &text, &size);
    if (!st) {
        cj_bspline_surface s; /* zeroed by the parse, whole when it succeeds */
        st = cj_surface_json_parse(path, text, &s);
        if (!st) st = to_patches(&s, out);
        cj_surface_json_free(&s);
    }
    free(text);
    if (!st) return 0;
    *nomem = st == CJ_ERR_NOMEM;
    snprintf(why, n, "%s", cj_last_error());
    surface_patches_free(out);
    return -1;
}

void surface_patches_free(surface_patches *s) {
    free(s->patches);
    free(s->pts);
    free(s->weights);
    memset(s, 0, sizeof *s);
}
