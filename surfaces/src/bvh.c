/* Bounding volume hierarchy: closest/any-hit traversal and the mesh BVH (see bvh.h); the
 * builder is bvh_build.c. */
#include "casteljau/bvh.h"
#include "bvh_internal.h"
#include "bvh_leaf_internal.h"
#include "ray_triangle_internal.h"
#include "alloc_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

void cj_bvh_destroy(cj_bvh *bvh) {
    if (!bvh) return;
    cj_bvhw_destroy(bvh);
    cj_allocator a = bvh->alloc_;
    cj_allocator_free(&a, bvh->nodes);
    cj_allocator_free(&a, bvh->prims);
    cj_allocator_free(&a, bvh->tri);
    cj_allocator_free(&a, bvh);
}

/* ---- traversal ------------------------------------------------------------------------- */

/* each wide level on the path pushes at most CJ_BVHW_W - 1 entries, and cj_bvhw_build bounds
 * the depth (one more entry is the child being pushed) */
#define WIDE_STACK ((CJ_BVHW_W - 1) * CJ_BVHW_MAX_DEPTH + 1)

typedef struct wentry {
    int32_t ref; /* >= 0: wide node; < 0: leaf ~ref, with n primitives */
    uint32_t n;
    float t0; /* lower bound of the entry parameter */
} wentry;

/* Inserts c into the stack segment st[base..*sp) kept sorted farthest first (nearest on top);
 * a tie goes below the entries already there, so the later child is popped first. */
static inline void push_sorted(wentry *st, int *sp, int base, wentry c) {
    int j = (*sp)++;
    while (j > base && st[j - 1].t0 < c.t0) {
        st[j] = st[j - 1];
        j--;
    }
    st[j] = c;
}

/* Traversal of the wide tree with a callback per primitive; `any` stops at the first hit. The walk
 * descends straight into the nearest met child and pushes the others farthest first; leaves are
 * tested where they are met. */
static int traverse(const cj_bvh *bvh, const cj_ray *ray0, cj_bvh_prim_fn fn, void *user,
                    cj_hit *hit, int any, cj_bvh_trav_stats *stats) {
    cj_ray ray = *ray0;
    const cj_bvhw *w = bvh->wide_;
    assert(w->nodes && "a mesh BVH is walked by cj_bvh_mesh_closest / cj_bvh_mesh_any");
    cj_bvhw_ray rw;
    cj_bvhw_ray_setup(&ray, &rw);
    const float tmin_f = cj_f32_down(ray.tmin);
    float tmax_f = cj_f32_up(ray.tmax);
    wentry st[WIDE_STACK];
    int sp = 0, found = 0;
    uint64_t nodes = 0, prims = 0;
    wentry cur = {0, 0, tmin_f};
    cj_hit h;
    for (;;) {
        if (cur.ref >= 0) {
            const cj_bvhw_node *wn = &w->nodes[cur.ref];
            float t0[CJ_BVHW_W];
            int mask = cj_bvhw_slab(wn, &rw, tmin_f, tmax_f, t0);
            nodes += (uint64_t)wn->count;
            if (mask) {
                int i = __builtin_ctz((unsigned)mask);
                mask &= mask - 1;
                cur = (wentry){wn->child[i], wn->nprim[i], t0[i]};
                if (!mask) continue; /* one child met: descend */
                /* several: the nearest becomes cur, the others go on the stack farthest first */
                const int base = sp;
                st[sp++] = cur;
                for (; mask; mask &= mask - 1) {
                    i = __builtin_ctz((unsigned)mask);
                    push_sorted(st, &sp, base, (wentry){wn->child[i], wn->nprim[i], t0[i]});
                }
                cur = st[--sp];
                continue;
            }
        } else {
            const uint32_t first = ~(uint32_t)cur.ref;
            for (uint32_t i = first; i < first + cur.n; i++) {
                prims++;
                const uint32_t prim = bvh->prims[i];
                if (fn(user, prim, &ray, &h) && h.t >= ray.tmin && h.t <= ray.tmax) {
                    found = 1;
                    if (any) goto done;
                    h.prim = prim;
                    *hit = h;
                    ray.tmax = h.t;
                    tmax_f = cj_f32_up(h.t);
                }
            }
        }
        /* next: the nearest pending entry that can still hold a closer hit */
        do {
            if (sp == 0) goto done;
            cur = st[--sp];
        } while (cur.t0 > tmax_f);
    }
done:
    if (stats) {
        stats->nodes += nodes;
        stats->prims += prims;
    }
    return found;
}

/* The closest hit so far among the built-in triangles: where it is, its t, edge values and
 * their sum (the hit record is filled once, at the end). */
typedef struct mesh_best {
    const cj_bvhw_tris *pk; /* its packet and lane: the record is filled from memory just read */
    int lane;
    double t, e[3], det;
} mesh_best;

/* Tests the packets of one leaf; returns 1 when one hits (for `any`, as soon as one does), with
 * ray->tmax and *best moved to the closest. Within a packet the last lane at the smallest t wins,
 * as a scalar loop's "t <= tmax" replaces ties in order. Inlined since the packet constants are
 * set up once per ray (cj_bvhw_tri_ray): a call cost more than the registers it saved. */
static inline __attribute__((always_inline)) int mesh_leaf(const cj_bvhw_tris *pk, uint32_t n,
                                                           cj_ray *ray, cj_bvhw_tri_ray *tr,
                                                           int any, mesh_best *best) {
    int found = 0;
    for (uint32_t j = 0; j < n; j += 4, ++pk) {
        cj_bvhw_tri_hits th;
        cj_bvhw_tris_test_r(pk, tr, &th);
        if (!th.mask) continue;
        found = 1;
        if (any) return 1;
        int bl = -1;
        for (int m = th.mask; m; m &= m - 1) {
            const int l = __builtin_ctz((unsigned)m);
            if (bl < 0 || th.t[l] <= th.t[bl]) bl = l;
        }
        best->pk = pk, best->lane = bl, best->t = th.t[bl], best->det = th.det[bl];
        best->e[0] = th.e0[bl], best->e[1] = th.e1[bl], best->e[2] = th.e2[bl];
        ray->tmax = best->t;
#if defined(__AVX__) && defined(__FMA__)
        tr->tmax = _mm256_set1_pd(best->t);
#endif
    }
    return found;
}

/* Starts loading what a met child will read: a wide node's four cache lines, or a leaf's first
 * packet (five). The walk is bound by the latency of these loads, and the children that are
 * pushed are popped later, by which time the lines have arrived. */
static inline void prefetch_entry(const cj_bvhw *w, wentry c) {
    const char *p =
        (const char *)w->lines + 64 * (size_t)(c.ref >= 0 ? (uint32_t)c.ref : ~(uint32_t)c.ref);
    __builtin_prefetch(p);
    __builtin_prefetch(p + 64);
    __builtin_prefetch(p + 128);
    __builtin_prefetch(p + 192);
    if (c.ref < 0) __builtin_prefetch(p + 256);
}

/* The walk over the built-in triangles (packets of 4 per leaf). */
static inline __attribute__((always_inline)) int walk_mesh(const cj_bvh *bvh, const cj_ray *ray0,
                                                           cj_hit *hit, const int any,
                                                           cj_bvh_trav_stats *stats) {
    cj_ray ray = *ray0;
    const cj_bvhw *w = bvh->wide_;
    cj_bvhw_ray rw;
    cj_bvhw_ray_setup(&ray, &rw);
    const float tmin_f = cj_f32_down(ray.tmin);
    float tmax_f = cj_f32_up(ray.tmax);
    cj_ray_tri_pre pre;
    cj_tri_prepare(&ray, &pre);
    cj_bvhw_tri_ray tr;
    cj_bvhw_tri_ray_setup(&ray, &pre, &tr);
    wentry st[WIDE_STACK];
    int sp = 0, found = 0;
    mesh_best best = {NULL, 0, 0.0, {0.0, 0.0, 0.0}, 1.0};
    uint64_t nodes = 0, prims = 0;
    wentry cur = {0, 0, tmin_f};
    for (;;) {
        if (cur.ref >= 0) {
            const cj_bvhw_node *wn =
                (const cj_bvhw_node *)(const void *)(w->lines + 64 * (size_t)cur.ref);
            float t0[CJ_BVHW_W];
            int mask = cj_bvhw_slab(wn, &rw, tmin_f, tmax_f, t0);
            nodes += (uint64_t)wn->count;
            if (mask) {
                int i = __builtin_ctz((unsigned)mask);
                mask &= mask - 1;
                cur = (wentry){wn->child[i], wn->nprim[i], t0[i]};
                if (!mask) continue; /* one child met: descend */
                i = __builtin_ctz((unsigned)mask);
                mask &= mask - 1;
                const wentry c2 = {wn->child[i], wn->nprim[i], t0[i]};
                prefetch_entry(w, cur);
                prefetch_entry(w, c2);
                if (!mask) {               /* two: push the farther, descend into the nearer */
                    if (c2.t0 <= cur.t0) { /* ties: the later child first, as below */
                        st[sp++] = cur;
                        cur = c2;
                    } else {
                        st[sp++] = c2;
                    }
                    continue;
                }
                /* more: the nearest becomes cur, the others go on the stack farthest first */
                const int base = sp;
                st[sp++] = cur;
                push_sorted(st, &sp, base, c2);
                for (; mask; mask &= mask - 1) {
                    i = __builtin_ctz((unsigned)mask);
                    const wentry c = {wn->child[i], wn->nprim[i], t0[i]};
                    prefetch_entry(w, c);
                    push_sorted(st, &sp, base, c);
                }
                cur = st[--sp];
                continue;
            }
        } else {
            prims += cur.n;
            const cj_bvhw_tris *pk =
                (const cj_bvhw_tris *)(const void *)(w->lines + 64 * (size_t) ~(uint32_t)cur.ref);
            if (mesh_leaf(pk, cur.n, &ray, &tr, any, &best)) {
                found = 1;
                if (any) break;
                tmax_f = cj_f32_up(ray.tmax);
            }
        }
        /* next: the nearest pending entry that can still hold a closer hit */
        do {
            if (sp == 0) goto done;
            cur = st[--sp];
        } while (cur.t0 > tmax_f);
    }
done:
    if (stats) {
        stats->nodes += nodes;
        stats->prims += prims;
    }
    if (found && !any) {
        double v[9];
        cj_bvhw_tris_lane(best.pk, best.lane, v);
        cj_tri_fill(cj_v3(v[0], v[1], v[2]), cj_v3(v[3], v[4], v[5]), cj_v3(v[6], v[7], v[8]),
                    best.t, best.e, best.det, hit);
        hit->prim = best.pk->idx[best.lane];
    }
    return found;
}

int cj_bvh_closest(const cj_bvh *bvh, const cj_ray *ray, cj_bvh_prim_fn fn, void *user, cj_hit *hit,
                   cj_bvh_trav_stats *stats) {
    return traverse(bvh, ray, fn, user, hit, 0, stats);
}

int cj_bvh_any(const cj_bvh *bvh, const cj_ray *ray, cj_bvh_prim_fn fn, void *user,
               cj_bvh_trav_stats *stats) {
    cj_hit h;
    return traverse(bvh, ray, fn, user, &h, 1, stats);
}

cj_status cj_bvh_mesh_build(const double *positions, size_t vertex_count, const uint32_t *tris,
                            size_t tri_count, const cj_allocator *alloc, cj_bvh **out) {
    if (tri_count == 0) return cj_fail(CJ_ERR_EMPTY, "BVH over a mesh without triangles");
    for (size_t t = 0; t < 3 * tri_count; t++)
        if (tris[t] >= vertex_count)
            return cj_fail(CJ_ERR_RANGE, "triangle %zu: vertex index %u >= %zu", t / 3, tris[t],
                           vertex_count);
    cj_allocator a = cj_allocator_resolve(alloc);
    cj_aabb *boxes = cj_allocator_alloc(&a, tri_count * sizeof *boxes);
    if (!boxes) return cj_fail(CJ_ERR_NOMEM, "BVH: out of memory");
    for (size_t t = 0; t < tri_count; t++) {
        const double *p0 = positions + 3 * (size_t)tris[3 * t];
        const double *p1 = positions + 3 * (size_t)tris[3 * t + 1];
        const double *p2 = positions + 3 * (size_t)tris[3 * t + 2];
        boxes[t] = cj_aabb_triangle(cj_v3(p0[0], p0[1], p0[2]), cj_v3(p1[0], p1[1], p1[2]),
                                    cj_v3(p2[0], p2[1], p2[2]));
    }
    cj_bvh *b;
    cj_status st = cj_bvh_build_blocks(boxes, tri_count, &a, 4, &b);
    cj_allocator_free(&a, boxes);
    if (st != CJ_OK) return st;
    b->tri = cj_allocator_alloc(&a, 9 * tri_count * sizeof *b->tri);
    if (!b->tri) {
        cj_bvh_destroy(b);
        return cj_fail(CJ_ERR_NOMEM, "BVH: out of memory for %zu triangles", tri_count);
    }
    for (size_t i = 0; i < tri_count; i++) {
        uint32_t t = b->prims[i];
        for (int c = 0; c < 3; c++)
            memcpy(b->tri + 9 * i + 3 * c, positions + 3 * (size_t)tris[3 * (size_t)t + c],
                   3 * sizeof(double));
    }
    st = cj_bvhw_pack_triangles(b);
    if (st != CJ_OK) {
        cj_bvh_destroy(b);
        return st;
    }
    *out = b;
    return CJ_OK;
}

int cj_bvh_mesh_closest(const cj_bvh *bvh, const cj_ray *ray, cj_hit *hit,
                        cj_bvh_trav_stats *stats) {
    return walk_mesh(bvh, ray, hit, 0, stats);
}

int cj_bvh_mesh_any(const cj_bvh *bvh, const cj_ray *ray, cj_bvh_trav_stats *stats) {
    cj_hit h;
    return walk_mesh(bvh, ray, &h, 1, stats);
}
