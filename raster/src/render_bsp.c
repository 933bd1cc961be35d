/* Back-to-front order of the transparent triangles by a BSP tree (seed 7.5).
 *
 * Each node takes the plane of its first triangle; the other triangles go to the front or back
 * list by the signed distances of their vertices (within a relative epsilon of the plane counts
 * as on it), triangles in the plane stay at the node, and a triangle crossing the plane is cut
 * into pieces (a triangle and a quad, the quad as two triangles) whose new vertices interpolate
 * position, normal and (u, v) linearly along the cut edges (exact for attributes that are
 * affine over the triangle). Traversal emits, at every node, the subtree on the far side from
 * the eye first, then the node's triangles, then the near side: painter's order that is exact
 * for any set of non-intersecting pieces, which the cuts guarantee (interpenetrating
 * surfaces included). Build and traversal use explicit stacks (a convex object's tree is a
 * chain as deep as its triangle count). If cutting would more than quadruple the triangles, the
 * remaining lists are drawn in painter's order by centroid depth instead (counted as a
 * fallback in the stage report; never reached by the shipped scenes). */
#include "render_pipe.h"

#include "error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct bnode {
    double n[3], d;
    int front, back;
    size_t t0, t1; /* triangles at the node: out[t0..t1) of the node triangle store */
} bnode;

typedef struct bjob {
    int node;
    size_t count;
    uint32_t *ids; /* triangle ids into the work arrays */
} bjob;

typedef struct bsp {
    cj_rbuild *b;
    const cj_allocator *a;
    uint32_t *tris, *obj; /* growing work triangle arrays */
    size_t count, cap;
    bnode *nodes;
    size_t nnodes, ncap;
    uint32_t *store; /* node triangles */
    size_t nstore, scap;
    size_t splits, limit;
    int fallback;
    double eps;
} bsp;

static cj_status push(const cj_allocator *a, void **arr, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return CJ_OK;
    size_t nc = *cap ? *cap * 2 : 256;
    while (nc < need) nc *= 2;
    void *p = cj_ralloc(a, nc * elem);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "BSP tree of %zu elements", nc);
    if (*arr) memcpy(p, *arr, *cap * elem);
    cj_rfree(a, *arr);
    *arr = p;
    *cap = nc;
    return CJ_OK;
}

static cj_status add_tri(bsp *s, uint32_t a, uint32_t b, uint32_t c, uint32_t obj, uint32_t *id) {
    if (s->count == s->cap) {
        size_t cap = s->cap;
        cj_status st = push(s->a, (void **)&s->tris, &cap, s->count + 1, 3 * sizeof(uint32_t));
        if (!st) st = push(s->a, (void **)&s->obj, &s->cap, s->count + 1, sizeof(uint32_t));
        if (st) return st;
    }
    s->tris[3 * s->count] = a;
    s->tris[3 * s->count + 1] = b;
    s->tris[3 * s->count + 2] = c;
    s->obj[s->count] = obj;
    *id = (uint32_t)s->count++;
    return CJ_OK;
}

/* The vertex where edge (i, j) meets the plane: attributes lerped from i towards j. */
static cj_status cut_vertex(bsp *s, uint32_t i, uint32_t j, double di, double dj, uint32_t *out) {
    cj_rbuild *b = s->b;
    double t = di / (di - dj), p[3];
    float n[3], uv[2];
    for (int k = 0; k < 3; ++k)
        p[k] =
            b->pos[3 * (size_t)i + k] + t * (b->pos[3 * (size_t)j + k] - b->pos[3 * (size_t)i + k]);
    if (b->nrm)
        for (int k = 0; k < 3; ++k)
            n[k] = (float)(b->nrm[3 * (size_t)i + k] +
                           t * (b->nrm[3 * (size_t)j + k] - b->nrm[3 * (size_t)i + k]));
    if (b->uv)
        for (int k = 0; k < 2; ++k)
            uv[k] = (float)(b->uv[2 * (size_t)i + k] +
                            t * (b->uv[2 * (size_t)j + k] - b->uv[2 * (size_t)i + k]));
    return cj_rbuild_add_vertex(b, p, b->nrm ? n : NULL, b->uv ? uv : NULL, out);
}

static double dist(const bsp *s, const bnode *nd, uint32_t v) {
    const double *p = s->b->pos + 3 * (size_t)v;
    return nd->n[0] * p[0] + nd->n[1] * p[1] + nd->n[2] * p[2] - nd->d;
}

/* Splits triangle id by the node's plane into front / back pieces appended to the lists. */
static cj_status split(bsp *s, const bnode *nd, uint32_t id, const double d[3], uint32_t *front,
                       size_t *nf, uint32_t *back, size_t *nb) {
    uint32_t v[3] = {s->tris[3 * id], s->tris[3 * id + 1], s->tris[3 * id + 2]}, obj = s->obj[id];
    uint32_t fp[4], bp[4];
    int nfp = 0, nbp = 0;
    for (int k = 0; k < 3; ++k) {
        int k2 = (k + 1) % 3;
        double da = d[k], db = d[k2];
        if (da >= 0.0) fp[nfp++] = v[k];
        if (da <= 0.0) bp[nbp++] = v[k];
        if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) {
            uint32_t cv;
            /* cut from the lower index so both triangles sharing the edge cut it alike */
            cj_status st = v[k] < v[k2] ? cut_vertex(s, v[k], v[k2], da, db, &cv)
                                        : cut_vertex(s, v[k2], v[k], db, da, &cv);
            if (st) return st;
            fp[nfp++] = cv;
            bp[nbp++] = cv;
        }
    }
    (void)nd;
    ++s->splits;
    for (int k = 1; k + 1 < nfp; ++k) {
        uint32_t nid;
        cj_status st = add_tri(s, fp[0], fp[k], fp[k + 1], obj, &nid);
        if (st) return st;
        front[(*nf)++] = nid;
    }
    for (int k = 1; k + 1 < nbp; ++k) {
        uint32_t nid;
        cj_status st = add_tri(s, bp[0], bp[k], bp[k + 1], obj, &nid);
        if (st) return st;
        back[(*nb)++] = nid;
    }
    return CJ_OK;
}

static double centroid_depth(const bsp *s, const cj_rview *view, uint32_t id) {
    double z = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double *p = s->b->pos + 3 * (size_t)s->tris[3 * id + k];
        z += view->world_to_cam.m[2][0] * p[0] + view->world_to_cam.m[2][1] * p[1] +
             view->world_to_cam.m[2][2] * p[2];
    }
    return z; /* camera z: more negative is farther */
}

typedef struct depth_key {
    double z;
    uint32_t id;
} depth_key;

static int by_depth(const void *x, const void *y) {
    const depth_key *a = x, *b = y;
    if (a->z != b->z) return a->z < b->z ? -1 : 1;
    return a->id < b->id ? -1 : a->id > b->id;
}

/* Painter's order (farthest centroid first) of ids[0..n). */
static cj_status painter(const bsp *s, const cj_rview *view, uint32_t *ids, size_t n) {
    depth_key *k = cj_ralloc(s->a, sizeof *k * (n ? n : 1));
    if (!k) return cj_fail(CJ_ERR_NOMEM, "painter's order of %zu triangles", n);
    for (size_t i = 0; i < n; ++i) {
        k[i].z = centroid_depth(s, view, ids[i]);
        k[i].id = ids[i];
    }
    qsort(k, n, sizeof *k, by_depth);
    for (size_t i = 0; i < n; ++i) ids[i] = k[i].id;
    cj_rfree(s->a, k);
    return CJ_OK;
}

static cj_status build(bsp *s, const cj_rview *view, size_t n) {
    bjob *stack = NULL;
    size_t sn = 0, scap = 0;
    cj_status st = push(s->a, (void **)&stack, &scap, 1, sizeof(bjob));
    if (st) return st;
    uint32_t *ids = cj_ralloc(s->a, sizeof(uint32_t) * (n ? n : 1));
    if (!ids) {
        cj_rfree(s->a, stack);
        return cj_fail(CJ_ERR_NOMEM, "BSP list");
    }
    for (size_t i = 0; i < n; ++i) ids[i] = (uint32_t)i;
    st = push(s->a, (void **)&s->nodes, &s->ncap, 1, sizeof(bnode));
    if (st) goto done;
    s->nnodes = 1;
    stack[sn++] = (bjob){0, n, ids};
    while (sn && !st) {
        bjob j = stack[--sn];
        bnode nd;
        memset(&nd, 0, sizeof nd);
        nd.front = nd.back = -1;
        uint32_t *front = cj_ralloc(s->a, sizeof(uint32_t) * (2 * j.count + 1));
        uint32_t *back = cj_ralloc(s->a, sizeof(uint32_t) * (2 * j.count + 1));
        size_t nf = 0, nb = 0;
        if (!front || !back) {
            st = cj_fail(CJ_ERR_NOMEM, "BSP lists");
        } else if (s->count > s->limit) {
            /* too many cuts: painter's order for what is left */
            s->fallback = 1;
            st = painter(s, view, j.ids, j.count);
            if (!st)
                st =
                    push(s->a, (void **)&s->store, &s->scap, s->nstore + j.count, sizeof(uint32_t));
            if (!st) {
                nd.t0 = s->nstore;
                memcpy(s->store + s->nstore, j.ids, j.count * sizeof(uint32_t));
                s->nstore += j.count;
                nd.t1 = s->nstore;
            }
        } else {
            uint32_t t0 = j.ids[0];
            const double *p0 = s->b->pos + 3 * (size_t)s->tris[3 * t0],
                         *p1 = s->b->pos + 3 * (size_t)s->tris[3 * t0 + 1],
                         *p2 = s->b->pos + 3 * (size_t)s->tris[3 * t0 + 2];
            cj_vec3 pn = cj_v3_cross(cj_v3(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]),
                                     cj_v3(p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]));
            pn = cj_v3_normalize(pn);
            nd.n[0] = pn.x, nd.n[1] = pn.y, nd.n[2] = pn.z;
            nd.d = pn.x * p0[0] + pn.y * p0[1] + pn.z * p0[2];
            st = push(s->a, (void **)&s->store, &s->scap, s->nstore + j.count, sizeof(uint32_t));
            nd.t0 = s->nstore;
            for (size_t i = 0; i < j.count && !st; ++i) {
                uint32_t id = j.ids[i];
                double d[3];
                int pos = 0, neg = 0;
                for (int k = 0; k < 3; ++k) {
                    d[k] = dist(s, &nd, s->tris[3 * id + k]);
                    if (fabs(d[k]) <= s->eps) d[k] = 0.0;
                    pos += d[k] > 0.0;
                    neg += d[k] < 0.0;
                }
                if (i == 0 || (!pos && !neg))
                    s->store[s->nstore++] = id;
                else if (!neg)
                    front[nf++] = id;
                else if (!pos)
                    back[nb++] = id;
                else
                    st = split(s, &nd, id, d, front, &nf, back, &nb);
            }
            nd.t1 = s->nstore;
        }
        cj_rfree(s->a, j.ids);
        if (!st && (nf || nb)) st = push(s->a, (void **)&stack, &scap, sn + 2, sizeof(bjob));
        if (!st && nf) st = push(s->a, (void **)&s->nodes, &s->ncap, s->nnodes + 1, sizeof(bnode));
        if (!st && nf) {
            nd.front = (int)s->nnodes++;
            stack[sn++] = (bjob){nd.front, nf, front};
            front = NULL;
        }
        if (!st && nb) st = push(s->a, (void **)&s->nodes, &s->ncap, s->nnodes + 1, sizeof(bnode));
        if (!st && nb) {
            nd.back = (int)s->nnodes++;
            stack[sn++] = (bjob){nd.back, nb, back};
            back = NULL;
        }
        cj_rfree(s->a, front);
        cj_rfree(s->a, back);
        if (!st) s->nodes[j.node] = nd;
    }
    while (sn) cj_rfree(s->a, stack[--sn].ids);
done:
    cj_rfree(s->a, stack);
    return st;
}

cj_status cj_rbsp_order(cj_rbuild *b, const cj_rview *view, uint32_t **tris, uint32_t **obj,
                        size_t *count, size_t *splits, int *fallback, const cj_allocator *a) {
    *splits = 0;
    *fallback = 0;
    size_t n = *count;
    if (n == 0) return CJ_OK;
    bsp s;
    memset(&s, 0, sizeof s);
    s.b = b;
    s.a = a;
    s.tris = *tris;
    s.obj = *obj;
    s.count = s.cap = n;
    s.limit = 4 * n + 1024;
    double scale = 0.0;
    for (size_t i = 0; i < 3 * n; ++i) {
        const double *p = b->pos + 3 * (size_t)s.tris[i];
        for (int k = 0; k < 3; ++k)
            if (fabs(p[k]) > scale) scale = fabs(p[k]);
    }
    s.eps = 1e-9 * (scale > 0.0 ? scale : 1.0);
    cj_status st = build(&s, view, n);
    uint32_t *ot = NULL, *oo = NULL;
    size_t on = 0;
    if (!st) {
        ot = cj_ralloc(a, sizeof(uint32_t) * 3 * (s.nstore ? s.nstore : 1));
        oo = cj_ralloc(a, sizeof(uint32_t) * (s.nstore ? s.nstore : 1));
        int *stk = cj_ralloc(a, sizeof(int) * 2 * (s.nnodes * 3 + 1));
        if (!ot || !oo || !stk) {
            st = cj_fail(CJ_ERR_NOMEM, "BSP order");
        } else {
            /* entries: node >= 0 visits it; -(node+1) emits its triangles */
            size_t sp = 0;
            stk[sp++] = 0;
            int persp = view->cam.projection == CJ_PROJ_PERSPECTIVE;
            while (sp) {
                int e = stk[--sp];
                if (e < 0) {
                    const bnode *nd = &s.nodes[-e - 1];
                    for (size_t k = nd->t0; k < nd->t1; ++k) {
                        uint32_t id = s.store[k];
                        memcpy(ot + 3 * on, s.tris + 3 * id, 3 * sizeof(uint32_t));
                        oo[on++] = s.obj[id];
                    }
                    continue;
                }
                const bnode *nd = &s.nodes[e];
                double side = persp
                                  ? nd->n[0] * view->eye.x + nd->n[1] * view->eye.y +
                                        nd->n[2] * view->eye.z - nd->d
                                  : -(nd->n[0] * view->gaze_unit.x + nd->n[1] * view->gaze_unit.y +
                                      nd->n[2] * view->gaze_unit.z);
                int nearc = side >= 0.0 ? nd->front : nd->back;
                int farc = side >= 0.0 ? nd->back : nd->front;
                /* pushed in reverse: far subtree, this node, near subtree */
                if (nearc >= 0) stk[sp++] = nearc;
                stk[sp++] = -e - 1;
                if (farc >= 0) stk[sp++] = farc;
            }
        }
        cj_rfree(a, stk);
    }
    cj_rfree(a, s.tris);
    cj_rfree(a, s.obj);
    cj_rfree(a, s.nodes);
    cj_rfree(a, s.store);
    if (st) {
        cj_rfree(a, ot);
        cj_rfree(a, oo);
        *tris = NULL;
        *obj = NULL;
        *count = 0;
        return st;
    }
    *tris = ot;
    *obj = oo;
    *count = on;
    *splits = s.splits;
    *fallback = s.fallback;
    return CJ_OK;
}
