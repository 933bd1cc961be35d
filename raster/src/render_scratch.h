/* Private to raster/: the allocator of a renderer's per-frame arrays (render_main.c).
 *
 * A frame allocates its set-up arrays (triangle lists, clip coordinates, shading records,
 * texture planes, the rasterizer's set-up and bins) and frees them at its end; the next frame
 * asks for about the same sizes. Through malloc every frame paid for fresh pages: the heap's
 * top was trimmed at the free and grown again (page faults, zeroed pages: about a tenth of a
 * warm 1024² frame's CPU time). The scratch allocator keeps the large blocks a frame frees and
 * hands them out again, so a warm frame touches memory it already owns.
 *
 * Blocks of at least CJ_SCRATCH_MIN bytes are kept when freed (at most CJ_SCRATCH_HELD of
 * them; when full, the smallest goes back to the base allocator), and a request takes the
 * smallest kept block that holds it, unless that block is more than twice the request and
 * 64 KiB over it. Smaller blocks pass straight through. Every block carries a 16-byte header
 * (its capacity), so pointers keep the base allocator's 16-byte alignment. Thread-safe (a
 * mutex); held memory is returned by cj_rscratch_destroy. */
#ifndef CJ_RENDER_SCRATCH_H
#define CJ_RENDER_SCRATCH_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"

#include <stddef.h>

#define CJ_SCRATCH_MIN  ((size_t)16384)
#define CJ_SCRATCH_HELD 64

typedef struct cj_rscratch cj_rscratch;

/* A scratch allocator over base (NULL: malloc). CJ_ERR_NOMEM. */
cj_status cj_rscratch_create(const cj_allocator *base, cj_rscratch **out);
/* Frees the kept blocks and the allocator. Every block it handed out must have been freed
 * (through it) before. NULL is ignored. */
void cj_rscratch_destroy(cj_rscratch *s);
/* The allocator interface of s (valid until cj_rscratch_destroy). */
cj_allocator cj_rscratch_allocator(cj_rscratch *s);
/* Blocks kept and their bytes (for tests and the stage report). */
size_t cj_rscratch_held(const cj_rscratch *s, size_t *bytes);

#endif
