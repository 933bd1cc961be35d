#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_fail(const char *cmd, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "casteljau %s: ", cmd);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return CLI_EXIT_USAGE;
}

int cli_parse_double(const char *s, double *out) {
    while (*s == ' ' || *s == '\t') ++s;
    if (*s == '\0') return -1;
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    while (*end == ' ' || *end == '\t') ++end;
    if (end == s || *end != '\0' || !isfinite(v)) return -1;
    *out = v;
    return 0;
}

/* Splits `text` on `sep` into a malloc'd copy with separators replaced by NUL; returns the
 * number of fields (an empty string has one empty field). */
static char *split_fields(const char *text, char sep, size_t *nfields) {
    size_t len = strlen(text);
    char *copy = malloc(len + 1);
    if (!copy) return NULL;
    memcpy(copy, text, len + 1);
    size_t n = 1;
    for (size_t i = 0; i < len; ++i)
        if (copy[i] == sep) {
            copy[i] = '\0';
            ++n;
        }
    *nfields = n;
    return copy;
}

int cli_parse_points(const char *text, double **pts, size_t *count, int *dim, char *why,
                     size_t why_size) {
    size_t npoints = 0;
    char *copy = split_fields(text, ';', &npoints);
    if (!copy) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    /* A trailing ';' is tolerated: "1,2;3,4;" has two points. */
    size_t len = strlen(text);
    if (len > 0 && text[len - 1] == ';') --npoints;
    if (len == 0 || npoints == 0) {
        free(copy);
        snprintf(why, why_size, "no control points given");
        return -1;
    }
    double *out = NULL;
    int d = -1;
    const char *field = copy;
    for (size_t i = 0; i < npoints; ++i) {
        size_t ncoord = 0;
        char *coords = split_fields(field, ',', &ncoord);
        if (!coords) {
            snprintf(why, why_size, "out of memory");
            goto fail;
        }
        if (d < 0) {
            d = (int)ncoord;
            out = malloc(sizeof(double) * npoints * (size_t)d);
            if (!out) {
                free(coords);
                snprintf(why, why_size, "out of memory");
                goto fail;
            }
        } else if ((int)ncoord != d) {
            snprintf(why, why_size, "point %zu has %zu coordinates but point 0 has %d", i, ncoord,
                     d);
            free(coords);
            goto fail;
        }
        const char *c = coords;
        for (int k = 0; k < d; ++k) {
            if (cli_parse_double(c, &out[i * (size_t)d + (size_t)k]) != 0) {
                snprintf(why, why_size, "point %zu, coordinate %d: '%s' is not a finite number", i,
                         k, c);
                free(coords);
                goto fail;
            }
            c += strlen(c) + 1;
        }
        free(coords);
        field += strlen(field) + 1;
    }
    free(copy);
    *pts = out;
    *count = npoints;
    *dim = d;
    return 0;
fail:
    free(out);
    free(copy);
    return -1;
}

int cli_parse_list(const char *text, double **values, size_t *count, char *why, size_t why_size) {
    size_t n = 0;
    char sep = strchr(text, ';') ? ';' : ',';
    char *copy = split_fields(text, sep, &n);
    if (!copy) {
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    double *out = malloc(sizeof(double) * n);
    if (!out) {
        free(copy);
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    const char *f = copy;
    for (size_t i = 0; i < n; ++i) {
        if (cli_parse_double(f, &out[i]) != 0) {
            snprintf(why, why_size, "value %zu: '%s' is not a finite number", i, f);
            free(out);
            free(copy);
            return -1;
        }
        f += strlen(f) + 1;
    }
    free(copy);
    *values = out;
    *count = n;
    return 0;
}

void cli_print_double(double v) {
    printf("%.17g", v);
}
