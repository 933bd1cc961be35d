/* Where a JSON document's values stand (json_read_internal.h): the parse that names the line and
 * column of a syntax error, and the lines of values for the kit's messages. cJSON keeps no
 * positions, so when a message needs a line a scanner walks the raw text once (cJSON accepted it,
 * so it is valid JSON) and records the line of every value in document order; a node's position
 * in a pre-order walk of the cJSON tree is its index in that list, and a table sorted by node
 * address finds it. The success path pays nothing. */
#include "json_read_internal.h"

#include "json_depth_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct scanner {
    const char *s;
    int line;
    int *vals; /* pairs (line, key_line) in document order */
    size_t n, cap;
    int ok;
} scanner;

static void skip_ws(scanner *sc) {
    while (*sc->s && (unsigned char)*sc->s <= 32) {
        if (*sc->s == '\n') sc->line++;
        sc->s++;
    }
}

static void skip_string(scanner *sc) {
    sc->s++; /* opening quote */
    while (*sc->s && *sc->s != '"') {
        if (*sc->s == '\\' && sc->s[1]) sc->s++;
        if (*sc->s == '\n') sc->line++;
        sc->s++;
    }
    if (*sc->s) sc->s++;
}

static void record(scanner *sc, int line, int key_line) {
    if (sc->n + 2 > sc->cap) {
        size_t nc = sc->cap ? 2 * sc->cap : 256;
        int *d = realloc(sc->vals, nc * sizeof *d);
        if (!d) {
            sc->ok = 0;
            return;
        }
        sc->vals = d;
        sc->cap = nc;
    }
    sc->vals[sc->n++] = line;
    sc->vals[sc->n++] = key_line;
}

/* The text is valid JSON (cJSON parsed it), so the scanner only has to find token starts. */
static void scan_value(scanner *sc, int key_line, int depth) {
    skip_ws(sc);
    record(sc, sc->line, key_line ? key_line : sc->line);
    char ch = *sc->s;
    if (ch == '{' || ch == '[') {
        const char close = ch == '{' ? '}' : ']';
        sc->s++;
        skip_ws(sc);
        if (*sc->s == close) {
            sc->s++;
            return;
        }
        while (*sc->s && sc->ok && depth < 4096) {
            skip_ws(sc);
            int kl = 0;
            if (close == '}') {
                kl = sc->line;
                skip_string(sc);
                skip_ws(sc);
                if (*sc->s == ':') sc->s++;
            }
            scan_value(sc, kl, depth + 1);
            skip_ws(sc);
            if (*sc->s == ',') {
                sc->s++;
                continue;
            }
            if (*sc->s == close) sc->s++;
            return;
        }
    } else if (ch == '"') {
        skip_string(sc);
    } else {
        while (*sc->s && *sc->s != ',' && *sc->s != ']' && *sc->s != '}' &&
               (unsigned char)*sc->s > 32)
            sc->s++;
    }
}

/* The sorted table: every node of the tree with its (line, key line), ordered by address, so a
 * lookup is a binary search (a reader that asks for many lines, such as the animation reader's
 * one line per channel, stays linear overall). */
typedef struct node_entry {
    const cJSON *node;
    int line, key_line;
} node_entry;

static void pair_nodes(const cJSON *n, const int *vals, size_t nvals, node_entry *t, size_t *k) {
    for (; n; n = n->next) {
        t[*k].node = n;
        t[*k].line = *k < nvals ? vals[2 * *k] : 0;
        t[*k].key_line = *k < nvals ? vals[2 * *k + 1] : 0;
        ++*k;
        if (n->child) pair_nodes(n->child, vals, nvals, t, k);
    }
}

static size_t count_nodes(const cJSON *n) {
    size_t k = 0;
    for (; n; n = n->next) k += 1 + (n->child ? count_nodes(n->child) : 0);
    return k;
}

static int by_node(const void *a, const void *b) {
    const uintptr_t x = (uintptr_t)((const node_entry *)a)->node,
                    y = (uintptr_t)((const node_entry *)b)->node;
    return x < y ? -1 : x > y;
}

static void build_table(cj_json_lines *l) {
    scanner sc = {l->text, 1, NULL, 0, 0, 1};
    if ((unsigned char)sc.s[0] == 0xEF && (unsigned char)sc.s[1] == 0xBB &&
        (unsigned char)sc.s[2] == 0xBF)
        sc.s += 3;
    scan_value(&sc, 0, 0);
    const size_t n = count_nodes(l->root);
    node_entry *t = sc.ok ? malloc((n ? n : 1) * sizeof *t) : NULL;
    if (t) {
        size_t k = 0;
        pair_nodes(l->root, sc.vals, sc.n / 2, t, &k);
        qsort(t, n, sizeof *t, by_node);
    }
    free(sc.vals);
    l->table = t;
    l->n = t ? n : 0;
    l->scanned = t ? 1 : -1;
}

/* The entry of node, scanning the text on the first request; NULL if unknown. */
static const node_entry *node_lines(const cj_json_doc *c, const cJSON *node) {
    cj_json_lines *l = c->lines;
    if (!l || !node || !l->text || !l->root) return NULL;
    if (!l->scanned) build_table(l);
    const node_entry *t = l->table;
    size_t lo = 0, hi = l->n;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if ((uintptr_t)t[mid].node < (uintptr_t)node)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < l->n && t[lo].node == node ? &t[lo] : NULL;
}

int cj_json_line(const cj_json_doc *c, const cJSON *node) {
    const node_entry *e = node_lines(c, node);
    return e ? e->line : 0;
}

int cj_json_key_line(const cj_json_doc *c, const cJSON *node) {
    const node_entry *e = node_lines(c, node);
    return e ? e->key_line : 0;
}

void cj_json_doc_init(cj_json_doc *d, cj_json_lines *lines, const char *name, const char *text,
                      const cJSON *root) {
    memset(lines, 0, sizeof *lines);
    lines->text = text;
    lines->root = root;
    d->name = name;
    d->lines = lines;
}

void cj_json_doc_free(cj_json_doc *d) {
    if (!d->lines) return;
    free(d->lines->table);
    d->lines->table = NULL;
    d->lines->n = 0;
    d->lines->scanned = 0;
}

cj_status cj_json_parse(const char *name, const char *text, cJSON **root) {
    const char *end = NULL;
    *root = cJSON_ParseWithOpts(text, &end, 1);
    if (*root) return CJ_OK;
    if (!end) end = cJSON_GetErrorPtr();
    if (!end) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory parsing JSON", name);
    int line = 1, col = 1;
    for (const char *p = text; p < end && *p; ++p) {
        if (*p == '\n')
            line++, col = 1;
        else
            col++;
    }
    if (cj_json_depth_at_(text, end) >= CJSON_NESTING_LIMIT)
        return cj_fail(CJ_ERR_PARSE,
                       "%s:%d:%d: JSON nested deeper than %d levels (the reader's limit)", name,
                       line, col, CJSON_NESTING_LIMIT);
    return cj_fail(CJ_ERR_PARSE, "%s:%d:%d: JSON syntax error (line %d, column %d)", name, line,
                   col, line, col);
}
