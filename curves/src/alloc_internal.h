/* Private: the one implementation of "optional allocator, default malloc/free" shared by every
 * module's objects. */
#ifndef CASTELJAU_ALLOC_INTERNAL_H
#define CASTELJAU_ALLOC_INTERNAL_H

#include "casteljau/alloc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The allocator an object should keep: *a if given (both functions asserted), else malloc/free. */
cj_allocator cj_allocator_resolve(const cj_allocator *a);

/* a->alloc for `bytes` (0 is treated as 1, so a successful call never returns NULL). */
void *cj_allocator_alloc(const cj_allocator *a, size_t bytes);

/* a->free(ptr); ptr may be NULL. */
void cj_allocator_free(const cj_allocator *a, void *ptr);

#ifdef __cplusplus
}
#endif
#endif
