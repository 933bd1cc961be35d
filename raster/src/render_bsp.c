/* Back-to-front order of the transparent triangles: a BSP tree (seed 7.5) whose leaves are
 * lists for which the painter's algorithm (seed 7.4) is PROVEN exact.
 *
 * At every node the list is first sorted far to near by centroid depth and checked: every pair
 * of triangles whose screen boxes overlap must pass one of Newell's plane tests (the earlier one
 * lies wholly beyond the later one's plane seen from the eye, or the later one wholly on the
 * eye's side of the earlier one's plane). If all pass, no ray meets the triangles out of order
 * and the list is a leaf drawn in that order (a convex object seen from outside, separated
 * objects: no cut at all). Otherwise the plane of a triangle of a failing pair splits the list:
 * triangles in the plane stay at the node, the others go to the front or back list by the signed
 * distances of their vertices (within a relative epsilon of the plane counts as on it), and a
 * triangle crossing the plane is cut into pieces (a triangle and a quad, the quad as two
 * triangles) whose new vertices interpolate position, normal and (u, v) linearly along the cut
 * edges (exact for attributes affine over the triangle). Traversal emits, at every node, the
 * subtree on the far side from the eye first, then the node's triangles, then the near side.
 * Interpenetrating surfaces are cut along their intersection, so the order is exact for any
 * input (tests/test_render_stages.c: two crossing quads, a lone sphere with 0 cuts). Build and
 * traversal use explicit stacks. If cutting would more than quadruple the triangles, the
 * remaining lists are drawn in painter's order without the proof (reported as
 * painter_fallback; never reached by the shipped scenes). */
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
    size_t splits, limit, leaves;
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

/* Screen box of triangle id in pixels; 0 when a vertex is not in front of the eye (the box is
 * then the whole image: it may overlap anything). */
static int screen_box(const bsp *s, const cj_rview *v, uint32_t id, double box[4]) {
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (int k = 0; k < 3; ++k) {
        const double *p = s->b->pos + 3 * (size_t)s->tris[3 * id + k];
        const double(*M)[4] = (const double(*)[4])v->world_to_clip.m;
        double c[4];
        for (int r = 0; r < 4; ++r)
            c[r] = M[r][0] * p[0] + M[r][1] * p[1] + M[r][2] * p[2] + M[r][3];
        if (!(c[3] > 0.0)) return 0;
        double x = (c[0] / c[3] + 1.0) * 0.5 * v->width, y = (c[1] / c[3] + 1.0) * 0.5 * v->height;
        box[0] = fmin(box[0], x);
        box[1] = fmin(box[1], y);
        box[2] = fmax(box[2], x);
        box[3] = fmax(box[3], y);
    }
    return 1;
}

/* Side of the eye w.r.t. the plane of triangle id: +1 or -1 (0: the eye lies in it). */
static int eye_side(const bsp *s, const cj_rview *v, uint32_t id, double n[3], double *d) {
    const double *p0 = s->b->pos + 3 * (size_t)s->tris[3 * id],
                 *p1 = s->b->pos + 3 * (size_t)s->tris[3 * id + 1],
                 *p2 = s->b->pos + 3 * (size_t)s->tris[3 * id + 2];
    double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0)
        for (int k = 0; k < 3; ++k) n[k] /= len;
    *d = n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2];
    double e = v->cam.projection == CJ_PROJ_PERSPECTIVE
                   ? n[0] * v->eye.x + n[1] * v->eye.y + n[2] * v->eye.z - *d
                   : -(n[0] * v->gaze_unit.x + n[1] * v->gaze_unit.y + n[2] * v->gaze_unit.z);
    return e > 0.0 ? 1 : e < 0.0 ? -1 : 0;
}

/* Whether all of triangle id lies on side `side` of plane (n, d), points within eps counting
 * as on it. */
static int all_on_side(const bsp *s, uint32_t id, const double n[3], double d, int side) {
    for (int k = 0; k < 3; ++k) {
        const double *p = s->b->pos + 3 * (size_t)s->tris[3 * id + k];
        double v = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - d;
        if (side * v < -s->eps) return 0;
    }
    return 1;
}

/* Drawing a before b is right when no ray meets a before b: a lies wholly beyond b's plane
 * (seen from the eye), or b wholly on the eye's side of a's plane (Newell's tests). pa, pb:
 * the planes (n, d, eye side) of a and b. */
static int order_ok(const bsp *s, uint32_t a, uint32_t b, const double *pa, const double *pb) {
    int sa = (int)pa[4], sb = (int)pb[4];
    if (sb != 0 && all_on_side(s, a, pb, pb[3], -sb)) return 1;
    if (sa != 0 && all_on_side(s, b, pa, pa[3], sa)) return 1;
    return 0;
}

#define PGRID 64

/* THE PAINTER'S TEST (seed 7.4): sorts ids far to near by centroid depth, then checks every
 * pair whose screen boxes overlap (found through a PGRID x PGRID grid of the image) with
 * order_ok. *exact = 1 when every pair passes: the painter's order is then exact and the list
 * needs no BSP node; else *conflict is the position of a triangle of a failing pair (its plane
 * is the next BSP splitter, which cuts where the order is ambiguous). */
static cj_status painter_test(const bsp *s, const cj_rview *v, uint32_t *ids, size_t n, int *exact,
                              size_t *conflict) {
    *exact = 0;
    *conflict = 0;
    cj_status st = painter(s, v, ids, n);
    if (st) return st;
    double *box = cj_ralloc(s->a, sizeof(double) * 4 * n);
    double *pl = cj_ralloc(s->a, sizeof(double) * 5 * n);
    int *head = cj_ralloc(s->a, sizeof(int) * PGRID * PGRID);
    size_t *stamp = cj_ralloc(s->a, sizeof(size_t) * n), ecap = 4 * n + 64, ne = 0;
    int *enext = cj_ralloc(s->a, sizeof(int) * ecap), *eitem = cj_ralloc(s->a, sizeof(int) * ecap);
    if (!box || !pl || !head || !stamp || !enext || !eitem) {
        st = cj_fail(CJ_ERR_NOMEM, "painter's test of %zu triangles", n);
        goto done;
    }
    for (int c = 0; c < PGRID * PGRID; ++c) head[c] = -1;
    double cw = (double)v->width / PGRID, ch = (double)v->height / PGRID;
    int ok = 1;
    for (size_t i = 0; i < n && ok; ++i) {
        double *b = box + 4 * i;
        pl[5 * i + 4] = eye_side(s, v, ids[i], pl + 5 * i, pl + 5 * i + 3);
        int x0 = 0, y0 = 0, x1 = PGRID - 1, y1 = PGRID - 1;
        if (screen_box(s, v, ids[i], b)) {
            if (b[2] < 0 || b[3] < 0 || b[0] >= v->width || b[1] >= v->height) continue;
            x0 = b[0] <= 0 ? 0 : (int)(b[0] / cw), y0 = b[1] <= 0 ? 0 : (int)(b[1] / ch);
            x1 = b[2] >= v->width ? PGRID - 1 : (int)(b[2] / cw);
            y1 = b[3] >= v->height ? PGRID - 1 : (int)(b[3] / ch);
            x1 = x1 > PGRID - 1 ? PGRID - 1 : x1;
            y1 = y1 > PGRID - 1 ? PGRID - 1 : y1;
        } else {
            b[0] = b[1] = -INFINITY;
            b[2] = b[3] = INFINITY;
        }
        stamp[i] = (size_t)-1;
        for (int y = y0; y <= y1 && ok; ++y)
            for (int x = x0; x <= x1 && ok; ++x) {
                int c = y * PGRID + x;
                for (int e = head[c]; e >= 0 && ok; e = enext[e]) {
                    size_t j = (size_t)eitem[e];
                    if (stamp[j] == i) continue;
                    stamp[j] = i;
                    const double *bj = box + 4 * j;
                    if (bj[0] > b[2] || b[0] > bj[2] || bj[1] > b[3] || b[1] > bj[3]) continue;
                    if (!order_ok(s, ids[j], ids[i], pl + 5 * j, pl + 5 * i)) {
                        ok = 0;
                        *conflict = i;
                    }
                }
                if (ne == ecap) {
                    size_t nc = 2 * ecap;
                    int *a1 = cj_ralloc(s->a, sizeof(int) * nc),
                        *a2 = cj_ralloc(s->a, sizeof(int) * nc);
                    if (!a1 || !a2) {
                        cj_rfree(s->a, a1);
                        cj_rfree(s->a, a2);
                        st = cj_fail(CJ_ERR_NOMEM, "painter's test grid");
                        goto done;
                    }
                    memcpy(a1, enext, sizeof(int) * ecap);
                    memcpy(a2, eitem, sizeof(int) * ecap);
                    cj_rfree(s->a, enext);
                    cj_rfree(s->a, eitem);
                    enext = a1;
                    eitem = a2;
                    ecap = nc;
                }
                enext[ne] = head[c];
                eitem[ne] = (int)i;
                head[c] = (int)ne++;
            }
    }
    *exact = ok;
done:
    cj_rfree(s->a, box);
    cj_rfree(s->a, pl);
    cj_rfree(s->a, head);
    cj_rfree(s->a, stamp);
    cj_rfree(s->a, enext);
    cj_rfree(s->a, eitem);
    return st;
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
        int exact = 0;
        size_t conflict = 0;
        bnode nd;
        memset(&nd, 0, sizeof nd);
        nd.front = nd.back = -1;
        uint32_t *front = cj_ralloc(s->a, sizeof(uint32_t) * (2 * j.count + 1));
        uint32_t *back = cj_ralloc(s->a, sizeof(uint32_t) * (2 * j.count + 1));
        size_t nf = 0, nb = 0;
        if (!front || !back) {
            st = cj_fail(CJ_ERR_NOMEM, "BSP lists");
        } else if (s->count > s->limit || j.count == 1 ||
                   (!(st = painter_test(s, view, j.ids, j.count, &exact, &conflict)) && exact)) {
            /* the painter's order is exact here (or too many cuts: painter's order for what
             * is left, reported as a fallback) */
            if (s->count > s->limit) {
                s->fallback = 1;
                st = painter(s, view, j.ids, j.count);
            } else {
                ++s->leaves;
            }
            if (!st)
                st =
                    push(s->a, (void **)&s->store, &s->scap, s->nstore + j.count, sizeof(uint32_t));
            if (!st) {
                nd.t0 = s->nstore;
                memcpy(s->store + s->nstore, j.ids, j.count * sizeof(uint32_t));
                s->nstore += j.count;
                nd.t1 = s->nstore;
            }
        } else if (!st) {
            uint32_t t0 = j.ids[conflict];
            j.ids[conflict] = j.ids[0];
            j.ids[0] = t0;
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
