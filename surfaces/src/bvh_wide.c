/* The 4-wide BVH that traversal walks: collapsed from the binary SAH tree, boxes unchanged, and
 * its 4-box slab test (AVX when the compiler targets it, else a plain loop over the lanes). */
#include "bvh_internal.h"
#include "alloc_internal.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>
#ifdef __AVX__
#include <immintrin.h>
#endif

static double box_area(const cj_aabb *b) {
    const double dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    return dx >= 0.0 && dy >= 0.0 && dz >= 0.0 ? dx * dy + dy * dz + dz * dx : 0.0;
}

cj_status cj_bvh4_build(cj_bvh *bvh) {
    cj_allocator *a = &bvh->alloc_;
    const size_t cap = bvh->node_count; /* each wide node consumes >= 1 binary inner node */
    cj_bvh4 *w = cj_allocator_alloc(a, sizeof *w);
    if (!w) return cj_fail(CJ_ERR_NOMEM, "BVH: out of memory for the wide nodes");
    w->nodes = cj_allocator_alloc(a, cap * sizeof *w->nodes);
    uint32_t *todo = cj_allocator_alloc(a, 2 * cap * sizeof *todo);
    if (!w->nodes || !todo) {
        cj_allocator_free(a, w->nodes);
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
        uint32_t kids[4];
        int nk = 0;
        const cj_bvh_node *bn = &bvh->nodes[b];
        if (bn->count) {
            kids[nk++] = b;
        } else {
            kids[nk++] = bn->first;
            kids[nk++] = bn->first + 1;
        }
        while (nk < 4) { /* open the inner child with the largest area */
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
        cj_bvh4_node *wn = &w->nodes[wi];
        wn->count = nk;
        wn->pad_ = 0;
        for (int i = 0; i < 4; ++i) {
            for (int k = 0; k < 3; ++k) {
                wn->lo[k][i] = INFINITY;
                wn->hi[k][i] = -INFINITY;
            }
            wn->child[i] = 0;
            if (i >= nk) continue;
            const cj_bvh_node *c = &bvh->nodes[kids[i]];
            for (int k = 0; k < 3; ++k) {
                wn->lo[k][i] = c->box.lo[k];
                wn->hi[k][i] = c->box.hi[k];
            }
            if (c->count) {
                wn->child[i] = ~(int32_t)kids[i];
            } else {
                wn->child[i] = (int32_t)nw;
                todo[ntodo++] = (uint32_t)nw++;
                todo[ntodo++] = kids[i];
            }
        }
    }
    w->count = nw;
    cj_allocator_free(a, todo);
    bvh->wide_ = w;
    return CJ_OK;
}

void cj_bvh4_destroy(cj_bvh *bvh) {
    cj_bvh4 *w = bvh->wide_;
    if (!w) return;
    cj_allocator_free(&bvh->alloc_, w->nodes);
    cj_allocator_free(&bvh->alloc_, w);
    bvh->wide_ = NULL;
}

int cj_bvh4_slab(const cj_bvh4_node *n, const cj_bvh4_ray *r, double tmin, double tmax,
                 double t0[4]) {
    const double widen = 1.0 + 2.0 * 3.3306690738754716e-16; /* 1 + 2γ(3), as cj_aabb_slab */
#ifdef __AVX__
    __m256d vmin = _mm256_set1_pd(tmin), vmax = _mm256_set1_pd(tmax);
    const __m256d vw = _mm256_set1_pd(widen);
    for (int k = 0; k < 3; ++k) {
        const double *nearp = r->neg[k] ? n->hi[k] : n->lo[k];
        const double *farp = r->neg[k] ? n->lo[k] : n->hi[k];
        const __m256d o = _mm256_set1_pd(r->o[k]), id = _mm256_set1_pd(r->id[k]);
        const __m256d tn = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(nearp), o), id);
        const __m256d tf =
            _mm256_mul_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(farp), o), id), vw);
        /* max/min return their second operand when the first is NaN: NaN leaves the bound */
        vmin = _mm256_max_pd(tn, vmin);
        vmax = _mm256_min_pd(tf, vmax);
    }
    _mm256_storeu_pd(t0, vmin);
    return _mm256_movemask_pd(_mm256_cmp_pd(vmin, vmax, _CMP_LE_OQ));
#else
    int mask = 0;
    for (int i = 0; i < 4; ++i) {
        double lo = tmin, hi = tmax;
        for (int k = 0; k < 3; ++k) {
            const double tn = ((r->neg[k] ? n->hi[k][i] : n->lo[k][i]) - r->o[k]) * r->id[k];
            const double tf =
                ((r->neg[k] ? n->lo[k][i] : n->hi[k][i]) - r->o[k]) * r->id[k] * widen;
            if (tn > lo) lo = tn;
            if (tf < hi) hi = tf;
        }
        t0[i] = lo;
        if (lo <= hi) mask |= 1 << i;
    }
    return mask;
#endif
}
