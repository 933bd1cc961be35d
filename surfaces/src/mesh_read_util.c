/* What the OBJ and PLY readers share (mesh_read_internal.h): the whole-file read and the
 * normals of vertices the file gave none. The readers call these; these call no reader. */
#include "casteljau/mesh_read.h"

#include "error_internal.h"
#include "file_internal.h"
#include "mesh_read_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_mesh_slurp_(const char *path, char **text, size_t *len) {
    return cj_file_read_all(path, CJ_FILE_MAX_BYTES, "mesh", text, len);
}

void cj_mesh_compute_normals(cj_mesh *m) {
    assert(m != NULL);
    memset(m->normals, 0, 3 * m->vertex_count * sizeof(double));
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const uint32_t *v = m->triangles + 3 * t;
        const double *a = m->positions + 3 * (size_t)v[0], *b = m->positions + 3 * (size_t)v[1],
                     *c = m->positions + 3 * (size_t)v[2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) m->normals[3 * (size_t)v[k] + (size_t)j] += n[j];
    }
    for (size_t i = 0; i < m->vertex_count; ++i) {
        double *n = m->normals + 3 * i;
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (l > 0 && isfinite(l))
            for (int j = 0; j < 3; ++j) n[j] /= l;
        else
            n[0] = n[1] = n[2] = 0;
    }
}

/* Fills the normals of the vertices with have[i] == 0 from the triangles around them. */
cj_status cj_mesh_fill_missing_normals_(cj_mesh *m, const unsigned char *have) {
    size_t n = m->vertex_count, missing = 0;
    for (size_t i = 0; i < n; ++i) missing += !have[i];
    if (!missing) return CJ_OK;
    double *keep = malloc(3 * n * sizeof *keep + 1);
    if (!keep) return cj_fail(CJ_ERR_NOMEM, "out of memory computing normals");
    memcpy(keep, m->normals, 3 * n * sizeof *keep);
    cj_mesh_compute_normals(m);
    for (size_t i = 0; i < n; ++i)
        if (have[i]) memcpy(m->normals + 3 * i, keep + 3 * i, 3 * sizeof *keep);
    free(keep);
    return CJ_OK;
}
