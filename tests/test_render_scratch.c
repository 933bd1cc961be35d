/* test_render_scratch: the recycling allocator of a renderer's per-frame arrays
 * (raster/src/render_scratch.h), over a counting base allocator:
 *   - a large block freed is handed out again for a request it holds (no base call), with
 *     its bytes intact up to the new size and 16-byte alignment;
 *   - a request larger than every kept block, and one far smaller than the only kept block
 *     (more than twice and 64 KiB over), go to the base allocator;
 *   - blocks under CJ_SCRATCH_MIN pass straight through (freed to the base at once);
 *   - at most CJ_SCRATCH_HELD blocks are kept, the smallest leaving first;
 *   - freeing NULL is a no-op; destroy returns every kept block (0 live base blocks);
 *   - a frame-like pattern (the same 40 sizes allocated and freed 50 times) calls the base
 *     allocator only in the first round. */
#include "render_scratch.h"

#include "support/check.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct counting {
    long allocs, frees, live;
} counting;

static void *c_alloc(void *user, size_t bytes) {
    counting *c = user;
    ++c->allocs;
    ++c->live;
    return malloc(bytes);
}

static void c_free(void *user, void *p) {
    counting *c = user;
    if (!p) return;
    ++c->frees;
    --c->live;
    free(p);
}

int main(void) {
    counting cnt = {0, 0, 0};
    cj_allocator base = {c_alloc, c_free, &cnt};
    cj_rscratch *s = NULL;
    CHECK(!cj_rscratch_create(&base, &s), "create");
    cj_allocator a = cj_rscratch_allocator(s);
    const long after_create = cnt.allocs;

    /* reuse */
    unsigned char *p = a.alloc(a.user, 100000);
    CHECK(p && ((uintptr_t)p & 15) == 0, "16-byte alignment");
    for (int i = 0; i < 100000; ++i) p[i] = (unsigned char)(i * 7);
    a.free(a.user, p);
    long before = cnt.allocs;
    unsigned char *q = a.alloc(a.user, 90000);
    CHECK(q == p && cnt.allocs == before, "a kept block is reused (%p, %p)", (void *)p, (void *)q);
    int intact = 1;
    for (int i = 0; i < 90000; ++i) intact &= q[i] == (unsigned char)(i * 7);
    CHECK(intact, "the reused block's bytes are untouched by the allocator");
    size_t bytes = 0;
    CHECK(cj_rscratch_held(s, &bytes) == 0, "a block handed out is not kept");

    /* too large, and far too small, for the kept block */
    a.free(a.user, q);
    before = cnt.allocs;
    void *big = a.alloc(a.user, 200000);
    CHECK(big && big != q && cnt.allocs == before + 1, "a larger request goes to the base");
    void *tiny = a.alloc(a.user, 20000); /* 100000 > 2 * 20000 and > 20000 + 65536 */
    CHECK(tiny && tiny != q && cnt.allocs == before + 2, "a far smaller request is not given "
                                                         "the kept block");
    a.free(a.user, big);
    a.free(a.user, tiny);
    CHECK(cj_rscratch_held(s, &bytes) == 3 && bytes == 100000 + 200000 + 20000,
          "three large blocks kept (%zu bytes)", bytes);

    /* small blocks pass through */
    long frees = cnt.frees;
    void *small = a.alloc(a.user, CJ_SCRATCH_MIN - 1);
    CHECK(small != NULL, "small block");
    a.free(a.user, small);
    CHECK(cnt.frees == frees + 1 && cj_rscratch_held(s, NULL) == 3,
          "a small block goes back to the base at once");
    a.free(a.user, NULL);

    /* the cap: the smallest kept blocks leave first */
    void *many[CJ_SCRATCH_HELD + 6];
    for (int i = 0; i < CJ_SCRATCH_HELD + 6; ++i)
        many[i] = a.alloc(a.user, 300000 + 1000 * (size_t)i); /* each larger than any kept */
    for (int i = 0; i < CJ_SCRATCH_HELD + 6; ++i) a.free(a.user, many[i]);
    CHECK(cj_rscratch_held(s, &bytes) == CJ_SCRATCH_HELD, "at most %d blocks kept",
          CJ_SCRATCH_HELD);
    size_t want = 0;
    for (int i = 6; i < CJ_SCRATCH_HELD + 6; ++i) want += 300000 + 1000 * (size_t)i;
    CHECK(bytes == want, "the largest %d are kept: %zu bytes, expected %zu", CJ_SCRATCH_HELD, bytes,
          want);
    CHECK(cnt.live == after_create + CJ_SCRATCH_HELD, "live base blocks %ld", cnt.live);
    cj_rscratch_destroy(s);
    CHECK(cnt.live == 0, "destroy returns everything (%ld live)", cnt.live);

    /* frames: the same sizes every frame, so only the first frame calls the base */
    counting fc = {0, 0, 0};
    cj_allocator fb = {c_alloc, c_free, &fc};
    CHECK(!cj_rscratch_create(&fb, &s), "create");
    a = cj_rscratch_allocator(s);
    long first = 0;
    for (int frame = 0; frame < 50; ++frame) {
        void *blk[40];
        for (int i = 0; i < 40; ++i) blk[i] = a.alloc(a.user, 20000 + 37000 * (size_t)i);
        for (int i = 0; i < 40; ++i) {
            CHECK(blk[i] != NULL, "frame block");
            memset(blk[i], frame, 20000 + 37000 * (size_t)i);
        }
        for (int i = 39; i >= 0; --i) a.free(a.user, blk[i]);
        if (frame == 0) first = fc.allocs;
    }
    CHECK(fc.allocs == first,
          "frames after the first reuse every block (%ld base calls, %ld "
          "after the first frame)",
          fc.allocs, first);
    cj_rscratch_destroy(s);
    CHECK(fc.live == 0, "destroy returns everything (%ld live)", fc.live);
    printf("test_render_scratch: reuse, pass-through, the %d-block cap, frames reusing every "
           "block (%ld base allocations in 50 frames of 40 blocks)\n",
           CJ_SCRATCH_HELD, first);
    return cj_check_exit();
}
