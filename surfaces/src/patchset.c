/* .bpt patch sets: parsing with line-numbered messages, loading, bounding box. */
#include "casteljau/patchset.h"
#include "alloc_internal.h"
#include "error_internal.h"
#include "file_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct lexer {
    const char *s;
    int line;
    const char *name;
    char tok[64];
    int tok_line;
} lexer;

/* Next token into lx->tok; returns 0 at end of input, -1 for an over-long token. */
static int next_token(lexer *lx) {
    for (;;) {
        while (*lx->s == ' ' || *lx->s == '\t' || *lx->s == '\r' || *lx->s == '\n') {
            if (*lx->s == '\n') ++lx->line;
            ++lx->s;
        }
        if (*lx->s == '#') {
            while (*lx->s && *lx->s != '\n') ++lx->s;
            continue;
        }
        break;
    }
    if (!*lx->s) return 0;
    size_t n = 0;
    lx->tok_line = lx->line;
    while (*lx->s && *lx->s != ' ' && *lx->s != '\t' && *lx->s != '\r' && *lx->s != '\n' &&
           *lx->s != '#') {
        if (n + 1 >= sizeof lx->tok) return -1;
        lx->tok[n++] = *lx->s++;
    }
    lx->tok[n] = '\0';
    return 1;
}

static cj_status read_int(lexer *lx, long lo, long hi, const char *what, long *out) {
    int r = next_token(lx);
    if (r == 0)
        return cj_fail(CJ_ERR_PARSE, "%s:%d: unexpected end of file, expected %s", lx->name,
                       lx->line, what);
    if (r < 0)
        return cj_fail(CJ_ERR_PARSE, "%s:%d: token too long where %s was expected", lx->name,
                       lx->line, what);
    char *end;
    errno = 0;
    long v = strtol(lx->tok, &end, 10);
    if (*end || end == lx->tok || errno)
        return cj_fail(CJ_ERR_PARSE, "%s:%d: %s: '%s' is not an integer", lx->name, lx->tok_line,
                       what, lx->tok);
    if (v < lo || v > hi)
        return cj_fail(lo == 0 && hi <= CJ_PATCH_MAX_DEGREE ? CJ_ERR_DEGREE : CJ_ERR_PARSE,
                       "%s:%d: %s = %ld is outside %ld..%ld", lx->name, lx->tok_line, what, v, lo,
                       hi);
    *out = v;
    return CJ_OK;
}

static cj_status read_double(lexer *lx, const char *what, long patch, long point, double *out) {
    int r = next_token(lx);
    if (r == 0)
        return cj_fail(CJ_ERR_PARSE,
                       "%s:%d: unexpected end of file in control point %ld of patch %ld (%s)",
                       lx->name, lx->line, point, patch, what);
    if (r < 0)
        return cj_fail(CJ_ERR_PARSE, "%s:%d: token too long in control point %ld of patch %ld",
                       lx->name, lx->line, point, patch);
    char *end;
    double v = strtod(lx->tok, &end);
    if (*end || end == lx->tok || !isfinite(v))
        return cj_fail(CJ_ERR_PARSE,
                       "%s:%d: control point %ld of patch %ld, %s: '%s' is not a finite number",
                       lx->name, lx->tok_line, point, patch, what, lx->tok);
    *out = v;
    return CJ_OK;
}

cj_status cj_patchset_parse_bpt(const char *text, const char *name, const cj_allocator *alloc,
                                cj_patchset **out) {
    assert(text != NULL && out != NULL);
    const cj_allocator a = cj_allocator_resolve(alloc);
    lexer lx = {text, 1, name ? name : "<bpt>", {0}, 1};
    long count;
    cj_status st = read_int(&lx, 1, 1000000, "patch count", &count);
    if (st) return st;
    int *degs = malloc(sizeof(int) * 2 * (size_t)count);
    size_t cap = 1024, used = 0;
    double *pts = malloc(sizeof(double) * cap);
    if (!degs || !pts) {
        free(degs);
        free(pts);
        return cj_fail(CJ_ERR_NOMEM, "out of memory reading %s", lx.name);
    }
    static const char *coord[3] = {"x", "y", "z"};
    for (long q = 0; q < count && !st; ++q) {
        long m, n;
        char what[64];
        snprintf(what, sizeof what, "degree in u of patch %ld", q);
        if ((st = read_int(&lx, 0, CJ_PATCH_MAX_DEGREE, what, &m))) break;
        snprintf(what, sizeof what, "degree in v of patch %ld", q);
        if ((st = read_int(&lx, 0, CJ_PATCH_MAX_DEGREE, what, &n))) break;
        degs[2 * q] = (int)m;
        degs[2 * q + 1] = (int)n;
        const size_t need = used + 3 * (size_t)(m + 1) * (size_t)(n + 1);
        if (need > cap) {
            while (cap < need) cap *= 2;
            double *np = realloc(pts, sizeof(double) * cap);
            if (!np) {
                st = cj_fail(CJ_ERR_NOMEM, "out of memory reading %s", lx.name);
                break;
            }
            pts = np;
        }
        for (long pnt = 0; pnt < (m + 1) * (n + 1) && !st; ++pnt)
            for (int k = 0; k < 3 && !st; ++k)
                st = read_double(&lx, coord[k], q, pnt, &pts[used++]);
    }
    if (!st) {
        int r = next_token(&lx);
        if (r != 0)
            st = cj_fail(CJ_ERR_PARSE, "%s:%d: unexpected '%s' after the last of %ld patches",
                         lx.name, lx.tok_line, r > 0 ? lx.tok : "...", count);
    }
    if (st) {
        free(degs);
        free(pts);
        return st;
    }
    cj_patchset *set = cj_allocator_alloc(&a, sizeof *set);
    double *own = cj_allocator_alloc(&a, sizeof(double) * used);
    cj_patch *patches = cj_allocator_alloc(&a, sizeof(cj_patch) * (size_t)count);
    if (!set || !own || !patches) {
        cj_allocator_free(&a, set);
        cj_allocator_free(&a, own);
        cj_allocator_free(&a, patches);
        free(degs);
        free(pts);
        return cj_fail(CJ_ERR_NOMEM, "out of memory reading %s", lx.name);
    }
    memcpy(own, pts, sizeof(double) * used);
    size_t off = 0;
    for (long q = 0; q < count; ++q) {
        patches[q] = cj_patch_view(degs[2 * q], degs[2 * q + 1], own + off, NULL);
        off += 3 * (size_t)(degs[2 * q] + 1) * (size_t)(degs[2 * q + 1] + 1);
    }
    set->count = (size_t)count;
    set->patches = patches;
    set->points = own;
    set->alloc_ = a;
    free(degs);
    free(pts);
    *out = set;
    return CJ_OK;
}

cj_status cj_patchset_load_bpt(const char *path, const cj_allocator *alloc, cj_patchset **out) {
    assert(path != NULL && out != NULL);
    char *buf = NULL;
    size_t len = 0;
    cj_status rs = cj_file_read_all(path, CJ_FILE_MAX_BYTES, "patch file", &buf, &len);
    if (rs) return rs;
    if (strlen(buf) != len) {
        free(buf);
        return cj_fail(CJ_ERR_PARSE, "'%s' contains a NUL byte (not a text file)", path);
    }
    cj_status st = cj_patchset_parse_bpt(buf, path, alloc, out);
    free(buf);
    return st;
}

void cj_patchset_destroy(cj_patchset *set) {
    if (!set) return;
    const cj_allocator a = set->alloc_;
    cj_allocator_free(&a, set->patches);
    cj_allocator_free(&a, set->points);
    cj_allocator_free(&a, set);
}

cj_status cj_patchset_bbox(const cj_patchset *set, double lo[3], double hi[3], double *diagonal) {
    assert(set != NULL && lo != NULL && hi != NULL);
    if (set->count == 0) return cj_fail(CJ_ERR_EMPTY, "the patch set is empty");
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = set->patches[0].pts[k];
    for (size_t q = 0; q < set->count; ++q) {
        const cj_patch *p = &set->patches[q];
        const size_t n = cj_patch_point_count(p);
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) {
                const double x = p->pts[3 * i + (size_t)k];
                if (x < lo[k]) lo[k] = x;
                if (x > hi[k]) hi[k] = x;
            }
    }
    if (diagonal)
        *diagonal = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return CJ_OK;
}
