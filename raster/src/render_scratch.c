/* The recycling allocator of a renderer's per-frame arrays (render_scratch.h). */
#include "render_scratch.h"

#include "error_internal.h"
#include "render_internal.h"

#include <assert.h>
#include <pthread.h>
#include <string.h>

#define HDR 16 /* header bytes: keeps the base allocator's 16-byte alignment */

typedef struct kept {
    void *base; /* the block as the base allocator returned it */
    size_t cap; /* usable bytes after the header */
} kept;

struct cj_rscratch {
    cj_allocator base;
    pthread_mutex_t mu;
    int n;
    kept k[CJ_SCRATCH_HELD];
};

static void *scratch_alloc(void *user, size_t bytes) {
    cj_rscratch *s = user;
    if (bytes >= CJ_SCRATCH_MIN) {
        pthread_mutex_lock(&s->mu);
        int best = -1;
        for (int i = 0; i < s->n; ++i)
            if (s->k[i].cap >= bytes && (best < 0 || s->k[i].cap < s->k[best].cap)) best = i;
        if (best >= 0 && (s->k[best].cap <= 2 * bytes || s->k[best].cap - bytes <= 65536)) {
            char *b = s->k[best].base;
            s->k[best] = s->k[--s->n];
            pthread_mutex_unlock(&s->mu);
            return b + HDR;
        }
        pthread_mutex_unlock(&s->mu);
    }
    if (bytes > (size_t)-1 - HDR) return NULL;
    char *b = cj_ralloc(&s->base, bytes + HDR);
    if (!b) return NULL;
    memcpy(b, &bytes, sizeof bytes);
    return b + HDR;
}

static void scratch_free(void *user, void *p) {
    cj_rscratch *s = user;
    if (!p) return; /* as free(NULL): some callers free unconditionally */
    char *b = (char *)p - HDR;
    size_t cap;
    memcpy(&cap, b, sizeof cap);
    if (cap < CJ_SCRATCH_MIN) {
        cj_rfree(&s->base, b);
        return;
    }
    pthread_mutex_lock(&s->mu);
    if (s->n == CJ_SCRATCH_HELD) { /* full: the smallest kept block makes room, or this goes */
        int small = 0;
        for (int i = 1; i < s->n; ++i)
            if (s->k[i].cap < s->k[small].cap) small = i;
        if (s->k[small].cap >= cap) {
            pthread_mutex_unlock(&s->mu);
            cj_rfree(&s->base, b);
            return;
        }
        void *out = s->k[small].base;
        s->k[small] = s->k[--s->n];
        cj_rfree(&s->base, out);
    }
    s->k[s->n].base = b;
    s->k[s->n].cap = cap;
    ++s->n;
    pthread_mutex_unlock(&s->mu);
}

cj_status cj_rscratch_create(const cj_allocator *base, cj_rscratch **out) {
    assert(out);
    cj_allocator a = cj_render_alloc(base);
    cj_rscratch *s = cj_ralloc(&a, sizeof *s);
    if (!s) return cj_fail(CJ_ERR_NOMEM, "scratch allocator");
    memset(s, 0, sizeof *s);
    s->base = a;
    if (pthread_mutex_init(&s->mu, NULL)) {
        cj_rfree(&a, s);
        return cj_fail(CJ_ERR_NOMEM, "scratch allocator's mutex");
    }
    *out = s;
    return CJ_OK;
}

void cj_rscratch_destroy(cj_rscratch *s) {
    if (!s) return;
    for (int i = 0; i < s->n; ++i) cj_rfree(&s->base, s->k[i].base);
    pthread_mutex_destroy(&s->mu);
    cj_allocator a = s->base;
    cj_rfree(&a, s);
}

cj_allocator cj_rscratch_allocator(cj_rscratch *s) {
    cj_allocator a = {scratch_alloc, scratch_free, s};
    return a;
}

size_t cj_rscratch_held(const cj_rscratch *s, size_t *bytes) {
    pthread_mutex_lock((pthread_mutex_t *)&s->mu);
    size_t total = 0;
    for (int i = 0; i < s->n; ++i) total += s->k[i].cap;
    const size_t n = (size_t)s->n;
    pthread_mutex_unlock((pthread_mutex_t *)&s->mu);
    if (bytes) *bytes = total;
    return n;
}
