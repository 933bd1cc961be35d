/* What is the plot format's own (plot_json_internal.h): colours by hex or CSS name, the default
 * palette, points counted against the document's budget. Everything else is checked with the
 * JSON kit (json_read_internal.h). */
#include "plot_json_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
        return pj_fail(c, v,
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

int pj_parse_points(pj_ctx *c, const cJSON *v, const char *path, size_t min_count, double **out,
                    size_t *count) {
    const size_t n = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
    if (n > PLOT_JSON_MAX_POINTS - c->points)
        return pj_fail(c, v, "%s: the document has more than %d points in all", path,
                       PLOT_JSON_MAX_POINTS);
    CJ_JSON_TRY(
        cj_json_numbers_at_least(&c->doc, v, path, 2, CJ_JSON_ANY, 0.0, min_count, out, count));
    c->points += n;
    return 0;
}

cj_status pj_open(pj_ctx *c, const char *name, const char *text, cJSON **root) {
    memset(c, 0, sizeof *c);
    if (!name) name = "<plot>";
    CJ_JSON_TRY(cj_json_parse(name, text, root));
    cj_json_doc_init(&c->doc, &c->lines, name, text, *root);
    return CJ_OK;
}

cj_status pj_close(pj_ctx *c, cJSON *root, int rc) {
    cj_json_doc_free(&c->doc);
    cJSON_Delete(root);
    return pj_status(rc);
}

cj_status pj_status(int rc) {
    return rc > 0 ? (cj_status)rc : rc ? CJ_ERR_PARSE : CJ_OK;
}

int pj_lib_fail(pj_ctx *c, const cJSON *node, const char *path) {
    return pj_fail(c, node, "%s: %s", path, cj_last_error());
}

static const cj_rgba palette[] = {{0x1f, 0x77, 0xb4, 255}, {0xff, 0x7f, 0x0e, 255},
                                  {0x2c, 0xa0, 0x2c, 255}, {0xd6, 0x27, 0x28, 255},
                                  {0x94, 0x67, 0xbd, 255}, {0x8c, 0x56, 0x4b, 255},
                                  {0xe3, 0x77, 0xc2, 255}, {0x17, 0xbe, 0xcf, 255}};

cj_rgba pj_palette(size_t i) {
    return palette[i % (sizeof palette / sizeof palette[0])];
}
