/* casteljau: the optional allocator every object that owns memory accepts (framebuffers, plots,
 * meshes, patch sets). Pass NULL for malloc/free. */
#ifndef CASTELJAU_ALLOC_H
#define CASTELJAU_ALLOC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* alloc(user, bytes) returns memory aligned for any type, or NULL on failure (reported by the
 * caller as CJ_ERR_NOMEM); free(user, ptr) releases it and accepts NULL. Both are required when
 * an allocator is given. An object keeps a copy of the allocator it was created with and
 * releases everything through it on destroy. */
typedef struct cj_allocator {
    void *(*alloc)(void *user, size_t bytes);
    void (*free)(void *user, void *ptr);
    void *user;
} cj_allocator;

#ifdef __cplusplus
}
#endif
#endif
