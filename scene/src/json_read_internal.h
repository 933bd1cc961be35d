/* Private: the one checked-JSON reading kit, shared by the readers of the scene layer (the scene
 * reader, scene_json*.c, and the animation reader, anim_json*.c) and by the layers above (the
 * plot reader of formats/, which the viewer's documents go through; scene/ is the lowest layer
 * that links cJSON). A document is its name, its text and its cJSON
 * tree; every accessor reports a failure as "<name>:<line>: <path> <message>" through cj_fail and
 * returns its status, and leaves *out untouched when an optional key is missing. */
#ifndef CASTELJAU_JSON_READ_INTERNAL_H
#define CASTELJAU_JSON_READ_INTERNAL_H

#include "casteljau/scene.h"
#include "error_internal.h"

#include <cjson/cJSON.h>
#include <stddef.h>

/* Room for a JSON path in messages ("objects[3].children[0].transform.translate"). */
#define CJ_JSON_PATH 256

/* Returns the status of an accessor from the calling function when it is not CJ_OK. */
#define CJ_JSON_TRY(expr)                                                                          \
    do {                                                                                           \
        cj_status try_st_ = (expr);                                                                \
        if (try_st_) return try_st_;                                                               \
    } while (0)

/* Lines of the document's values, found only when a message needs one (json_read.c). */
typedef struct cj_json_lines {
    const char *text;
    const cJSON *root;
    void *table; /* the nodes with their lines, sorted by address */
    size_t n;
    int scanned; /* 0: not yet, 1: done, -1: out of memory (lines read as 0) */
} cj_json_lines;

typedef struct cj_json_doc {
    const char *name;     /* the document's name in messages */
    cj_json_lines *lines; /* filled on the first request; NULL: every line reads 0 */
} cj_json_doc;

/* Parses text (the document `name`) into *root (free with cJSON_Delete). A refusal names the
 * place: "<name>:<line>:<col>: JSON syntax error (line L, column C)", or "... JSON nested deeper
 * than N levels" at cJSON's nesting limit (CJ_ERR_PARSE); CJ_ERR_NOMEM when cJSON ran out. */
cj_status cj_json_parse(const char *name, const char *text, cJSON **root);

/* A document read from text (parsed into root); lines is the caller's storage. Free the line
 * table with cj_json_doc_free. */
void cj_json_doc_init(cj_json_doc *d, cj_json_lines *lines, const char *name, const char *text,
                      const cJSON *root);
void cj_json_doc_free(cj_json_doc *d);

/* The line of node's value, and of its key (= the value's line in arrays); 0 when unknown. */
int cj_json_line(const cj_json_doc *c, const cJSON *node);
int cj_json_key_line(const cj_json_doc *c, const cJSON *node);
/* Reports `st` at node's line (key line if `at_key`). */
cj_status cj_json_fail(const cj_json_doc *c, const cJSON *node, int at_key, cj_status st,
                       const char *fmt, ...) CJ_PRINTF(5, 6);
/* Re-labels the current cj_last_error() message with the document and node's line. */
cj_status cj_json_relabel(const cj_json_doc *c, const cJSON *node, cj_status st);

/* "an object", "an array", "a string", "a number", "a boolean" or "null", for messages. */
const char *cj_json_type_name(const cJSON *n);

/* path + "." + key (key alone when path is ""), or path + "[i]", into dst (CJ_JSON_PATH). */
void cj_json_join(char *dst, const char *path, const char *key);
void cj_json_index(char *dst, const char *path, size_t i);

/* obj must be an object whose keys are all in `allowed` (NULL-terminated), none repeated. */
cj_status cj_json_object(const cj_json_doc *c, const cJSON *obj, const char *path,
                         const char *const *allowed);
/* A required key; missing: error at obj naming the key. */
cj_status cj_json_require(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                          const cJSON **out);
/* arr must be an array. */
cj_status cj_json_list(const cj_json_doc *c, const cJSON *arr, const char *p);

/* Range kinds of numbers: any, >= lo, > lo, < hi, in [lo, hi], in (lo, hi). */
typedef enum cj_json_range {
    CJ_JSON_ANY = 0,
    CJ_JSON_GE,
    CJ_JSON_GT,
    CJ_JSON_LT,
    CJ_JSON_IN,
    CJ_JSON_OPEN
} cj_json_range;

/* Checks of a node in hand (an array entry, a value found by the caller), named `path` in
 * messages: a finite number in range (the range message ends with the value given: "width must
 * be in [64, 8192], not 10"), a whole number in [lo, hi], a boolean, a string, an array of
 * exactly `len` numbers. */
cj_status cj_json_number_at(const cj_json_doc *c, const cJSON *n, const char *path, cj_json_range r,
                            double lo, double hi, double *out);
cj_status cj_json_int_at(const cj_json_doc *c, const cJSON *n, const char *path, double lo,
                         double hi, int *out);
cj_status cj_json_bool_at(const cj_json_doc *c, const cJSON *n, const char *path, int *out);
cj_status cj_json_string_at(const cj_json_doc *c, const cJSON *n, const char *path,
                            const char **out);
cj_status cj_json_array_at(const cj_json_doc *c, const cJSON *n, const char *path, int len,
                           double *out);

/* Optional keys of obj, checked as the *_at accessors above: finite (CJ_ERR_NONFINITE otherwise),
 * in range (CJ_ERR_RANGE). */
cj_status cj_json_num(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                      cj_json_range r, double lo, double hi, double *out);
/* An optional whole number in [lo, hi]. */
cj_status cj_json_int(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                      double lo, double hi, int *out);
cj_status cj_json_bool(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                       int *out);
cj_status cj_json_vec3(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                       cj_vec3 *out);
/* Colour components in [0, max] (max < 0: >= 0 only). */
cj_status cj_json_rgb(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                      double max, cj_rgb *out);
cj_status cj_json_string(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                         const char **out);
/* A string among `names` (NULL-terminated); *out = its index. */
cj_status cj_json_enum(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                       const char *const *names, int *out);
/* Numbers of the array node `arr` (any length unless want > 0), each in range: `count` and a
 * malloc'ed array (free with free()). dim > 0: an array of arrays of `dim` numbers, flattened. */
cj_status cj_json_numbers(const cj_json_doc *c, const cJSON *arr, const char *path, int dim,
                          cj_json_range r, double lo, size_t want, double **out, size_t *count);
/* As cj_json_numbers with no fixed count but at least `min` entries ("points has 2 points, at
 * least 3 needed"). */
cj_status cj_json_numbers_at_least(const cj_json_doc *c, const cJSON *arr, const char *path,
                                   int dim, cj_json_range r, double lo, size_t min, double **out,
                                   size_t *count);
/* An angle given as key_deg or key_rad (not both), range in radians, into *out (radians). */
cj_status cj_json_angle(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                        cj_json_range r, double lo_rad, double hi_rad, double *out);

/* A file named in the document (rel) resolved against the document's folder base_dir ("" or
 * NULL: the current folder; an absolute rel stays as it is) into dst (cap bytes). CJ_ERR_RANGE
 * at node, naming path, when it does not fit. */
cj_status cj_json_resolve(const cj_json_doc *c, const char *base_dir, const cJSON *node,
                          const char *path, const char *rel, char *dst, size_t cap);

#endif
