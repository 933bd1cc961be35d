/* Private, shared by every writer of JSON in the library and the tool (the scene writer, the
 * stage report, the plot document writer of formats/, the viewer's save): documents are built
 * as cJSON trees and printed with cJSON's printer, numbers in their shortest exact form, files
 * written through the atomic writer (file_internal.h). scene/ is the lowest layer that links
 * cJSON, so the kit lives here and every layer above reaches it without climbing. */
#ifndef CASTELJAU_JSON_WRITE_INTERNAL_H
#define CASTELJAU_JSON_WRITE_INTERNAL_H

#include "casteljau/status.h"

#include <cJSON.h>
#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Room for any double in its shortest form ("-2.2250738585072014e-308" and the NUL). */
#define CJ_JSON_NUMBER_MAX 32

/* The shortest decimal text that reads back (strtod) to exactly v: "%.15g" when it round-trips,
 * else "%.16g", else "%.17g" (a double never needs more). "%.Ng" rounds to nearest and drops
 * trailing zeros, and a normal double's shortest form of up to 15 digits is within half a unit
 * of its 15th digit, so the first precision that round-trips gives the fewest digits: 5.6 is
 * written "5.6", not "5.5999999999999996". Subnormals (fewer significant bits) are searched from
 * one digit: 4.9406564584124654e-324 is "5e-324". NaN and infinity, which JSON has not, give
 * "null". */
void cj_json_number_text(double v, char buf[CJ_JSON_NUMBER_MAX]);

/* A cJSON node that cJSON's printer writes as cj_json_number_text(v) (a raw node: cJSON's own
 * number printing keeps 17 digits where 16 suffice). NULL when out of memory. */
cJSON *cj_json_number(double v);

/* Turns every number of the tree from node on (its siblings and their children: pass a document's
 * root) into cj_json_number's form, for a document read with cJSON, edited and printed again
 * (the query commands): a number read as 0.1 prints "0.1", not cJSON's own 17 digits when it
 * needs 16. Numbers can no longer be read as numbers afterwards. Returns 0, or -1 when out of
 * memory (the tree stays whole, some numbers changed). */
int cj_json_shortest_numbers(cJSON *node);

/* Adds cj_json_number(v) to obj under key (obj an object) or at the end (obj an array, key
 * NULL). Returns 0, or -1 when out of memory (obj unchanged). */
int cj_json_add_number(cJSON *obj, const char *key, double v);

/* An array of n numbers, each as cj_json_number. NULL when out of memory. */
cJSON *cj_json_number_array(const double *v, size_t n);

/* An array of n points of dim coordinates each ([[x, y], ...]), numbers as cj_json_number. NULL
 * when out of memory. */
cJSON *cj_json_point_array(const double *p, size_t n, int dim);

/* Prints root with cJSON's printer (indented when `pretty`) followed by a newline onto f.
 * Errors: CJ_ERR_NOMEM, CJ_ERR_IO (the stream's error flag), each naming `what`. */
cj_status cj_json_print(const cJSON *root, int pretty, FILE *f, const char *what);

/* Prints root (indented) and writes it atomically to path: the old file stays whole on any
 * error. Errors: those of cj_json_print and of cj_atomic_open / cj_atomic_commit. */
cj_status cj_json_write_file(const cJSON *root, const char *path, const char *what);

#ifdef __cplusplus
}
#endif
#endif
