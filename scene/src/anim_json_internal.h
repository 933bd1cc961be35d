/* Private: the animation document reader's context and the accessors of its own kinds of value
 * (bounded numbers and vectors, key lists), built on the shared checked-JSON kit
 * (json_read_internal.h, called with &c->json): every failure is reported as
 * "<file>:<line>: <path> <message>" through cj_fail. */
#ifndef CASTELJAU_ANIM_JSON_INTERNAL_H
#define CASTELJAU_ANIM_JSON_INTERNAL_H

#include "casteljau/anim_json.h"
#include "error_internal.h"
#include "json_read_internal.h"

#include <cjson/cJSON.h>
#include <stddef.h>

typedef struct actx {
    cj_json_doc json; /* the document: name and lines (json_read_internal.h) */
    cj_json_lines lines;
    const char *name, *base_dir;
    cj_anim_doc *doc; /* the document being read (channel lines are recorded in it) */
} actx;

/* Records the line of the channel just added (for binding errors, which come later). */
cj_status aj_channel_line(actx *c, const cJSON *n);

/* An optional finite number in [lo, hi], an integer when `integer` (missing: unchanged). Every
 * simulation parameter is read through it, so that no value implies unbounded work or a
 * float-to-int conversion out of range. */
cj_status aj_num_in(const actx *c, const cJSON *obj, const char *path, const char *key, double lo,
                    double hi, int integer, double *out);
/* An optional vector of 3 finite numbers whose length is at most bound. */
cj_status aj_vec3_in(const actx *c, const cJSON *obj, const char *path, const char *key,
                     double bound, double *out);
/* An array of exactly len numbers (len 0: up to cap) into v; *count (may be NULL) its length. */
cj_status aj_nums(const actx *c, const cJSON *n, const char *path, int len, double *v, size_t cap,
                  size_t *count);
cj_status aj_vec3(const actx *c, const cJSON *obj, const char *path, const char *key, double *out);
/* A string among `names`; *out its index (missing: unchanged). */
cj_status aj_pick(const actx *c, const cJSON *obj, const char *path, const char *key,
                  const char *const *names, int *out);
/* One number (dim 1) or array of dim numbers per key, malloc'ed key-major; *dim 0 = any. */
cj_status aj_key_values(const actx *c, const cJSON *arr, const char *path, int *dim, size_t want,
                        double **out);

#endif
