#include "alloc_internal.h"

#include <assert.h>
#include <stdlib.h>

static void *default_alloc(void *user, size_t bytes) {
    (void)user;
    return malloc(bytes);
}

static void default_free(void *user, void *ptr) {
    (void)user;
    free(ptr);
}

cj_allocator cj_allocator_resolve(const cj_allocator *a) {
    if (a) {
        assert(a->alloc != NULL && a->free != NULL);
        return *a;
    }
    cj_allocator d = {default_alloc, default_free, NULL};
    return d;
}

void *cj_allocator_alloc(const cj_allocator *a, size_t bytes) {
    return a->alloc(a->user, bytes ? bytes : 1);
}

void cj_allocator_free(const cj_allocator *a, void *ptr) {
    if (ptr) a->free(a->user, ptr);
}
