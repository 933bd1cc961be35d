/* casteljau: sets of Bézier patches read from .bpt text files (the Utah teapot ships as
 * data/teapot.bpt, installed under share/casteljau/).
 *
 * .bpt FORMAT (whitespace-separated; '#' starts a comment to the end of the line):
 *     N                      number of patches (>= 1)
 *     then N times:
 *       m n                  the degrees in u and v (0..CJ_PATCH_MAX_DEGREE)
 *       (m+1)(n+1) lines     "x y z" control points, row by row with u fastest
 *                            (point j*(m+1)+i is b_ij, as in patch.h)
 * Patches are polynomial. Every value must be a finite number; anything else is
 * CJ_ERR_PARSE with a message naming the line ("teapot.bpt:17: control point 3 of patch 0:
 * 'x' is not a number").
 */
#ifndef CASTELJAU_PATCHSET_H
#define CASTELJAU_PATCHSET_H

#include "casteljau/mesh.h"
#include "casteljau/patch.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_patchset {
    size_t count;      /* number of patches */
    cj_patch *patches; /* views into `points`, owned by the set */
    double *points;    /* all control points */
    /* private */
    cj_allocator alloc_;
} cj_patchset;

/* Parses .bpt text (NUL-terminated). `name` is used in messages (e.g. the file name).
 * alloc may be NULL. Status: CJ_ERR_PARSE (with line number), CJ_ERR_DEGREE, CJ_ERR_NOMEM. */
cj_status cj_patchset_parse_bpt(const char *text, const char *name, const cj_allocator *alloc,
                                cj_patchset **out);

/* Reads and parses a .bpt file. CJ_ERR_IO if it cannot be read (the message names the path
 * and the system's reason). */
cj_status cj_patchset_load_bpt(const char *path, const cj_allocator *alloc, cj_patchset **out);

/* Frees the set; NULL is a no-op. */
void cj_patchset_destroy(cj_patchset *set);

/* Axis-aligned box of all control points and its diagonal (the "size" relative tolerances
 * refer to). CJ_ERR_EMPTY for an empty set. */
cj_status cj_patchset_bbox(const cj_patchset *set, double lo[3], double hi[3], double *diagonal);

#ifdef __cplusplus
}
#endif
#endif
