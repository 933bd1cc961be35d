/* The JSON writing kit (json_write_internal.h): shortest exact numbers, cJSON's printer, the
 * atomic writer. */
#include "json_write_internal.h"

#include "error_internal.h"
#include "file_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void cj_json_number_text(double v, char buf[CJ_JSON_NUMBER_MAX]) {
    if (!isfinite(v)) {
        memcpy(buf, "null", 5);
        return;
    }
    /* Subnormals carry fewer than 15 significant digits: search them from one digit up. */
    const int from = fabs(v) < DBL_MIN && v != 0.0 ? 1 : 15;
    for (int digits = from; digits <= 17; ++digits) {
        snprintf(buf, CJ_JSON_NUMBER_MAX, "%.*g", digits, v);
        if (digits == 17 || strtod(buf, NULL) == v) return;
    }
}

cJSON *cj_json_number(double v) {
    char buf[CJ_JSON_NUMBER_MAX];
    cj_json_number_text(v, buf);
    return cJSON_CreateRaw(buf);
}

int cj_json_shortest_numbers(cJSON *node) {
    for (; node; node = node->next) {
        if (cJSON_IsNumber(node)) {
            char buf[CJ_JSON_NUMBER_MAX];
            cj_json_number_text(node->valuedouble, buf);
            const size_t len = strlen(buf) + 1;
            char *text = cJSON_malloc(len); /* freed by cJSON_Delete, as a raw node's text */
            if (!text) return -1;
            memcpy(text, buf, len);
            node->type = cJSON_Raw | (node->type & ~0xFF);
            node->valuestring = text;
        } else if (node->child && cj_json_shortest_numbers(node->child)) {
            return -1;
        }
    }
    return 0;
}

int cj_json_add_number(cJSON *obj, const char *key, double v) {
    cJSON *n = cj_json_number(v);
    if (!n) return -1;
    if (key ? !cJSON_AddItemToObject(obj, key, n) : !cJSON_AddItemToArray(obj, n)) {
        cJSON_Delete(n);
        return -1;
    }
    return 0;
}

cJSON *cj_json_number_array(const double *v, size_t n) {
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; a && i < n; ++i)
        if (cj_json_add_number(a, NULL, v[i])) {
            cJSON_Delete(a);
            a = NULL;
        }
    return a;
}

cJSON *cj_json_point_array(const double *p, size_t n, int dim) {
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; a && i < n; ++i) {
        cJSON *pt = cj_json_number_array(p + i * (size_t)dim, (size_t)dim);
        if (!pt || !cJSON_AddItemToArray(a, pt)) {
            cJSON_Delete(pt);
            cJSON_Delete(a);
            a = NULL;
        }
    }
    return a;
}

cj_status cj_json_print(const cJSON *root, int pretty, FILE *f, const char *what) {
    char *text = pretty ? cJSON_Print(root) : cJSON_PrintUnformatted(root);
    if (!text) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory while printing the JSON", what);
    fputs(text, f);
    fputc('\n', f);
    cJSON_free(text);
    return ferror(f) ? cj_fail(CJ_ERR_IO, "%s: writing the JSON failed", what) : CJ_OK;
}

cj_status cj_json_write_file(const cJSON *root, const char *path, const char *what) {
    cj_atomic_file f;
    cj_status st = cj_atomic_open(&f, path);
    if (st) return st;
    st = cj_json_print(root, 1, f.fp, what);
    if (st) {
        cj_atomic_abandon(&f);
        return st;
    }
    return cj_atomic_commit(&f);
}
