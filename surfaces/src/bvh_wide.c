/* The 8-wide BVH that traversal walks: collapsed from the binary SAH tree, and
 * its 8-box slab test (bvh_internal.h), boxes rounded outward to float. */
#include "bvh_internal.h"
#include "bvh_leaf_internal.h"
#include "alloc_internal.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>

/* p rounded up to a multiple of a (a power of two; NULL stays NULL). */
static void *align_up(void *p, uintptr_t a) {
    return p ? (void *)(((uintptr_t)p + a - 1u) & ~(a - 1u)) : NULL;
}

static double box_area(const cj_aabb *b) {
    const double dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    return dx >= 0.0 && dy >= 0.0 && dz >= 0.0 ? dx * dy + dy * dz + dz * dx : 0.0;
}

cj_status cj_bvhw_build(cj_bvh *bvh) {
    cj_allocator *a = &bvh->alloc_;
    /* the walks' stacks hold at most CJ_BVHW_W - 1 entries per level of a path, and a wide path
     * is never longer than a binary one (the builder keeps that below DEEP_SPLIT + 33) */
    if (bvh->depth > CJ_BVHW_MAX_DEPTH)
        return cj_fail(CJ_ERR_CAP, "BVH: depth %d exceeds %d", bvh->depth, CJ_BVHW_MAX_DEPTH);
    const size_t cap = bvh->node_count; /* each wide node consumes >= 1 binary inner node */
    cj_bvhw *w = cj_allocator_alloc(a, sizeof *w);
    if (!w) return cj_fail(CJ_ERR_NOMEM, "BVH: out of memory for the wide nodes");
    /* 64-byte aligned: a node is four whole cache lines */
    w->nodes_mem_ = cj_allocator_alloc(a, cap * sizeof *w->nodes + 63);
    w->nodes = align_up(w->nodes_mem_, 64);
    w->lines_mem_ = NULL;
    uint32_t *todo = cj_allocator_alloc(a, 2 * cap * sizeof *todo);
    if (!w->nodes_mem_ || !todo) {
        cj_allocator_free(a, w->nodes_mem_);
        cj_allocator_free(a, todo);
        cj_allocator_free(a, w);
        return cj_fail(CJ_ERR_NOMEM, "BVH: out of memory for %zu wide nodes", cap);
    }
    /* todo holds pairs (wide node, binary node whose subtree it stands for) */
    size_t nw = 1, ntodo = 0;
    todo[ntodo++] = 0;
    todo[ntodo++] = 0;
    while (ntodo > 0) {
        const uint32_t b = todo[--ntodo], wi = todo[--ntodo];
        uint32_t kids[CJ_BVHW_W];
        int nk = 0;
        const cj_bvh_node *bn = &bvh->nodes[b];
        if (bn->count) {
            kids[nk++] = b;
        } else {
            kids[nk++] = bn->first;
            kids[nk++] = bn->first + 1;
        }
        while (nk < CJ_BVHW_W) { /* open the inner child with the largest area */
            int best = -1;
            double best_area = -1.0;
            for (int i = 0; i < nk; ++i) {
                const cj_bvh_node *c = &bvh->nodes[kids[i]];
                const double ar = box_area(&c->box);
                if (!c->count && ar > best_area) best = i, best_area = ar;
            }
            if (best < 0) break;
            const uint32_t open = kids[best];
            kids[best] = bvh->nodes[open].first;
            kids[nk++] = bvh->nodes[open].first + 1;
        }
        cj_bvhw_node *wn = &w->nodes[wi];
        memset(wn, 0, sizeof *wn);
        wn->count = nk;
        wn->valid = (1 << nk) - 1;
        for (int i = 0; i < CJ_BVHW_W; ++i) {
            for (int k = 0; k < 3; ++k) {
                wn->b[2 * k][i] = INFINITY;
                wn->b[2 * k + 1][i] = -INFINITY;
            }
            if (i >= nk) continue;
            const cj_bvh_node *c = &bvh->nodes[kids[i]];
            for (int k = 0; k < 3; ++k) { /* outward: the float box contains the double box */
                wn->b[2 * k][i] = cj_f32_down(c->box.lo[k]);
                wn->b[2 * k + 1][i] = cj_f32_up(c->box.hi[k]);
            }
            if (c->count) {
                wn->child[i] = ~(int32_t)c->first;
                wn->nprim[i] = (uint8_t)c->count;
            } else {
                wn->child[i] = (int32_t)nw;
                todo[ntodo++] = (uint32_t)nw++;
                todo[ntodo++] = kids[i];
            }
        }
    }
    w->count = nw;
    w->lines = NULL;
    w->line_count = w->tris_count = 0;
    cj_allocator_free(a, todo);
    bvh->wide_ = w;
    return CJ_OK;
}

/* Two equal vertices: the watertight test never hits such a triangle (one edge value is exactly
 * zero and the other two are exact opposites, so they are of opposite signs or both zero), so its
 * lane is left empty rather than sent through the scalar tie-break on every ray that reaches it. */
static int degenerate(const double *v) {
    const int e01 = v[0] == v[3] && v[1] == v[4] && v[2] == v[5];
    const int e12 = v[3] == v[6] && v[4] == v[7] && v[5] == v[8];
    const int e20 = v[6] == v[0] && v[7] == v[1] && v[8] == v[2];
    return e01 || e12 || e20;
}

/* One leaf: its n triangles from position `first` of the tree order, into packets p[0..]. */
static void pack_leaf(const cj_bvh *bvh, uint32_t first, uint32_t n, cj_bvhw_tris *p) {
    for (uint32_t j = 0; j < n; j += 4, ++p) {
        memset(p->pad_, 0, sizeof p->pad_);
        for (int l = 0; l < 4; ++l) {
            const size_t at_i = first + j + (uint32_t)l;
            int used = j + (uint32_t)l < n;
            if (used && degenerate(bvh->tri + 9 * at_i)) used = 0;
            p->idx[l] = used ? bvh->prims[at_i] : UINT32_MAX;
            for (int r = 0; r < 9; ++r) p->v[r][l] = used ? bvh->tri[9 * at_i + (size_t)r] : NAN;
        }
    }
}

#define NODE_LINES   (sizeof(cj_bvhw_node) / 64)
#define PACKET_LINES (sizeof(cj_bvhw_tris) / 64)
_Static_assert(sizeof(cj_bvhw_tris) % 64 == 0, "a packet is whole cache lines");

cj_status cj_bvhw_pack_triangles(cj_bvh *bvh) {
    cj_bvhw *w = bvh->wide_;
    size_t np = 0;
    for (size_t n = 0; n < w->count; ++n)
        for (int i = 0; i < w->nodes[n].count; ++i)
            if (w->nodes[n].child[i] < 0) np += (w->nodes[n].nprim[i] + 3u) / 4u;
    const size_t lines = w->count * NODE_LINES + np * PACKET_LINES;
    if (lines > (size_t)INT32_MAX)
        return cj_fail(CJ_ERR_CAP, "BVH: %zu wide nodes and %zu packets exceed 2^31 lines",
                       w->count, np);
    /* pending nodes: (wide node, line of its parent, slot in the parent) */
    uint32_t *todo = cj_allocator_alloc(&bvh->alloc_, 3 * w->count * sizeof *todo);
    w->lines_mem_ = cj_allocator_alloc(&bvh->alloc_, lines * 64 + 63);
    w->lines = align_up(w->lines_mem_, 64);
    if (!w->lines_mem_ || !todo) {
        cj_allocator_free(&bvh->alloc_, todo);
        return cj_fail(CJ_ERR_NOMEM, "BVH: out of memory for %zu triangle packets", np);
    }
    w->line_count = lines;
    w->tris_count = np;
    size_t at = 0, ntodo = 0;
    todo[ntodo++] = 0, todo[ntodo++] = UINT32_MAX, todo[ntodo++] = 0;
    while (ntodo > 0) { /* depth first: a node, its leaves, then its inner children in order */
        const uint32_t slot = todo[--ntodo], parent = todo[--ntodo], n = todo[--ntodo];
        cj_bvhw_node *wn = (cj_bvhw_node *)(void *)(w->lines + 64 * at);
        *wn = w->nodes[n];
        const uint32_t line = (uint32_t)at;
        if (parent != UINT32_MAX)
            ((cj_bvhw_node *)(void *)(w->lines + 64 * (size_t)parent))->child[slot] = (int32_t)line;
        at += NODE_LINES;
        for (int i = 0; i < wn->count; ++i) {
            if (wn->child[i] >= 0) continue;
            const uint32_t first = ~(uint32_t)wn->child[i];
            wn->child[i] = ~(int32_t)at;
            pack_leaf(bvh, first, wn->nprim[i], (cj_bvhw_tris *)(void *)(w->lines + 64 * at));
            at += PACKET_LINES * ((wn->nprim[i] + 3u) / 4u);
        }
        for (int i = wn->count - 1; i >= 0; --i) /* reversed: the first child comes out first */
            if (wn->child[i] >= 0) {
                todo[ntodo++] = (uint32_t)wn->child[i];
                todo[ntodo++] = line;
                todo[ntodo++] = (uint32_t)i;
            }
    }
    cj_allocator_free(&bvh->alloc_, todo);
    cj_allocator_free(&bvh->alloc_, w->nodes_mem_);
    w->nodes_mem_ = NULL;
    w->nodes = NULL;
    return CJ_OK;
}

void cj_bvhw_destroy(cj_bvh *bvh) {
    cj_bvhw *w = bvh->wide_;
    if (!w) return;
    cj_allocator_free(&bvh->alloc_, w->lines_mem_);
    cj_allocator_free(&bvh->alloc_, w->nodes_mem_);
    cj_allocator_free(&bvh->alloc_, w);
    bvh->wide_ = NULL;
}
