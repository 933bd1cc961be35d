/* Shared helpers of the JSON readers of `casteljau plot` (plot_json.c, chart_json.c): error
 * text with JSON paths, typed field readers. */
#include "plot_json_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
int
pj_fail(pj_ctx *c, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->why, c->why_size, fmt, ap);
    va_end(ap);
    return -1;
}

/* snprintf for JSON paths (truncation of an absurdly deep path is harmless). */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void
pj_pathf(char *buf, size_t size, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, size, fmt, ap);
    va_end(ap);
}

int pj_check_keys(pj_ctx *c, const cJSON *obj, const char *path, const char *const *allowed) {
    for (const cJSON *f = obj->child; f; f = f->next) {
        int ok = 0;
        for (const char *const *a = allowed; *a && !ok; ++a) ok = !strcmp(f->string, *a);
        if (!ok) {
            char list[512] = "";
            for (const char *const *a = allowed; *a; ++a) {
                strncat(list, *a, sizeof list - strlen(list) - 1);
                if (a[1]) strncat(list, ", ", sizeof list - strlen(list) - 1);
            }
            return pj_fail(c, "%s: unknown field '%s' (known: %s)", path, f->string, list);
        }
    }
    return 0;
}

static int hexval(char ch) {
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return -1;
}

/* The CSS basic colour names (and a few common extended ones), for plots written by hand. */
static const struct {
    const char *name;
    uint32_t rgba;
} named_colours[] = {{"black", 0x000000ff},   {"white", 0xffffffff},      {"red", 0xff0000ff},
                     {"green", 0x008000ff},   {"blue", 0x0000ffff},       {"yellow", 0xffff00ff},
                     {"cyan", 0x00ffffff},    {"aqua", 0x00ffffff},       {"magenta", 0xff00ffff},
                     {"fuchsia", 0xff00ffff}, {"gray", 0x808080ff},       {"grey", 0x808080ff},
                     {"silver", 0xc0c0c0ff},  {"maroon", 0x800000ff},     {"olive", 0x808000ff},
                     {"lime", 0x00ff00ff},    {"teal", 0x008080ff},       {"navy", 0x000080ff},
                     {"purple", 0x800080ff},  {"orange", 0xffa500ff},     {"brown", 0xa52a2aff},
                     {"pink", 0xffc0cbff},    {"transparent", 0x00000000}};

static int same_name(const char *a, const char *b) { /* ASCII, ignoring case */
    for (; *a && *b; ++a, ++b) {
        char x = *a >= 'A' && *a <= 'Z' ? (char)(*a - 'A' + 'a') : *a;
        if (x != *b) return 0;
    }
    return *a == *b;
}

int pj_parse_color(pj_ctx *c, const cJSON *v, const char *path, cj_rgba *out) {
    const char *s = cJSON_IsString(v) ? v->valuestring : NULL;
    for (size_t k = 0; s && k < sizeof named_colours / sizeof named_colours[0]; ++k)
        if (same_name(s, named_colours[k].name)) {
            const uint32_t x = named_colours[k].rgba;
            *out =
                cj_rgba_make((uint8_t)(x >> 24), (uint8_t)(x >> 16), (uint8_t)(x >> 8), (uint8_t)x);
            return 0;
        }
    size_t n = s ? strlen(s) : 0;
    int digits[8];
    int ok = s && s[0] == '#' && (n == 4 || n == 7 || n == 9);
    for (size_t i = 1; ok && i < n; ++i) ok = (digits[i - 1] = hexval(s[i])) >= 0;
    if (!ok)
        return pj_fail(c,
                       "%s is not a colour \"#rgb\", \"#rrggbb\", \"#rrggbbaa\" or a name (black, "
                       "white, red, green, blue, yellow, cyan, magenta, gray, orange, ...)",
                       path);
    if (n == 4) {
        *out = cj_rgba_make((uint8_t)(17 * digits[0]), (uint8_t)(17 * digits[1]),
                            (uint8_t)(17 * digits[2]), 255);
    } else {
        uint8_t ch[4] = {0, 0, 0, 255};
        for (size_t k = 0; k < (n - 1) / 2; ++k)
            ch[k] = (uint8_t)(16 * digits[2 * k] + digits[2 * k + 1]);
        *out = cj_rgba_make(ch[0], ch[1], ch[2], ch[3]);
    }
    return 0;
}

int pj_parse_number(pj_ctx *c, const cJSON *v, const char *path, double lo, double hi,
                    double *out) {
    if (!cJSON_IsNumber(v)) return pj_fail(c, "%s is not a number", path);
    double d = v->valuedouble;
    if (!isfinite(d)) return pj_fail(c, "%s is not a finite number", path);
    if (d < lo || d > hi) return pj_fail(c, "%s = %g is outside [%g, %g]", path, d, lo, hi);
    *out = d;
    return 0;
}

int pj_parse_int(pj_ctx *c, const cJSON *v, const char *path, int lo, int hi, int *out) {
    double d = 0.0; /* set by parse_number on success */
    if (pj_parse_number(c, v, path, lo, hi, &d)) return -1;
    if (d != floor(d)) return pj_fail(c, "%s = %g is not an integer", path, d);
    *out = (int)d;
    return 0;
}

int pj_parse_bool(pj_ctx *c, const cJSON *v, const char *path, int *out) {
    if (!cJSON_IsBool(v)) return pj_fail(c, "%s is not true or false", path);
    *out = cJSON_IsTrue(v);
    return 0;
}

/* A fixed-size array of numbers ([cx, cy, r] ...). */
int pj_parse_numbers(pj_ctx *c, const cJSON *v, const char *path, int count, double *out) {
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != count)
        return pj_fail(c, "%s is not an array of %d numbers", path, count);
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, ++i) {
        char p[300];
        pj_pathf(p, sizeof p, "%s[%d]", path, i);
        if (pj_parse_number(c, e, p, -INFINITY, INFINITY, &out[i])) return -1;
    }
    return 0;
}

/* [[x, y], ...] with at least min_count points into a new array (caller frees). */
int pj_parse_points(pj_ctx *c, const cJSON *v, const char *path, size_t min_count, double **out,
                    size_t *count) {
    if (!cJSON_IsArray(v)) return pj_fail(c, "%s is not an array of [x, y] pairs", path);
    size_t n = (size_t)cJSON_GetArraySize(v);
    if (n < min_count)
        return pj_fail(c, "%s has %zu point%s, at least %zu needed", path, n, n == 1 ? "" : "s",
                       min_count);
    if (n > PLOT_JSON_MAX_POINTS - c->points)
        return pj_fail(c, "%s: the document has more than %d points in all", path,
                       PLOT_JSON_MAX_POINTS);
    c->points += n;
    double *pts = malloc((n ? n : 1) * 2 * sizeof *pts);
    if (!pts) return pj_fail(c, "%s: out of memory", path);
    size_t i = 0;
    for (const cJSON *e = v->child; e; e = e->next, ++i) {
        if (!cJSON_IsArray(e) || cJSON_GetArraySize(e) != 2 || !cJSON_IsNumber(e->child) ||
            !cJSON_IsNumber(e->child->next)) {
            free(pts);
            return pj_fail(c, "%s[%zu] is not a pair of numbers", path, i);
        }
        pts[2 * i] = e->child->valuedouble;
        pts[2 * i + 1] = e->child->next->valuedouble;
        if (!isfinite(pts[2 * i]) || !isfinite(pts[2 * i + 1])) {
            free(pts);
            return pj_fail(c, "%s[%zu] has a coordinate that is not finite", path, i);
        }
    }
    *out = pts;
    *count = n;
    return 0;
}

int pj_lib_fail(pj_ctx *c, const char *path) {
    return pj_fail(c, "%s: %s", path, cj_last_error());
}

const cJSON *pj_field(const cJSON *obj, const char *key) {
    return cJSON_GetObjectItemCaseSensitive(obj, key);
}

static const cj_rgba palette[] = {{0x1f, 0x77, 0xb4, 255}, {0xff, 0x7f, 0x0e, 255},
                                  {0x2c, 0xa0, 0x2c, 255}, {0xd6, 0x27, 0x28, 255},
                                  {0x94, 0x67, 0xbd, 255}, {0x8c, 0x56, 0x4b, 255},
                                  {0xe3, 0x77, 0xc2, 255}, {0x17, 0xbe, 0xcf, 255}};

cj_rgba pj_palette(size_t i) {
    return palette[i % (sizeof palette / sizeof palette[0])];
}

void pj_syntax_error(pj_ctx *c, const char *text, const char *at) {
    int line = 1, col = 1;
    for (const char *s = text; at && s < at && *s; ++s) {
        if (*s == '\n')
            line++, col = 1;
        else
            col++;
    }
    pj_fail(c, "JSON syntax error at line %d, column %d", line, col);
}
