/* Patch colliders for particles: world-space copies of Bézier patches in a BVH, hit along each
 * particle's step segment by the ray tracer's patch intersection. */
#include "casteljau/particles.h"

#include "casteljau/bvh.h"
#include "casteljau/patch_nearest.h"
#include "casteljau/ray.h"
#include "error_internal.h"
#include "particle_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct cj_patch_collider {
    cj_allocator alloc;
    int has_alloc;
    size_t count;
    cj_patch *patches; /* views into `pts` / `w` below */
    double *pts, *w;
    cj_bvh *bvh;
    cj_aabb *boxes; /* per patch, world space (after the patches' points) */
    cj_aabb all;    /* of every patch */
    double tol, friction, offset;
    int solid;    /* cj_patch_collider_set_solid */
    double up[3]; /* unit: the direction the solid is closed against */
    /* solid: ruled patches sealing narrow gaps between open sides (separately allocated) */
    size_t nseal;
    cj_patch *seal;
    double *seal_data;
};

static void *pc_alloc(const cj_allocator *a, size_t n) {
    return a ? a->alloc(a->user, n) : malloc(n);
}
static void pc_free(const cj_allocator *a, void *p) {
    if (a)
        a->free(a->user, p);
    else
        free(p);
}

cj_status cj_patch_collider_create(const cj_patch *patches, size_t count, const cj_xform3 *to_world,
                                   double tol, double friction, const cj_allocator *alloc,
                                   cj_patch_collider **out) {
    assert(out && (patches || count == 0));
    if (count == 0) return cj_fail(CJ_ERR_EMPTY, "patch collider without patches");
    if (!(tol > 0.0) || !isfinite(tol))
        return cj_fail(CJ_ERR_ARGUMENT, "patch collider tol %g", tol);
    if (!(friction >= 0.0 && friction <= 1.0))
        return cj_fail(CJ_ERR_RANGE, "patch collider friction %g outside [0, 1]", friction);
    size_t npts = 0, nw = 0;
    for (size_t i = 0; i < count; ++i) {
        cj_status st = cj_ray_patch_check(&patches[i], tol);
        if (st != CJ_OK) {
            char msg[200];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            return cj_fail(st, "patch collider, patch %zu: %s", i, msg);
        }
        const size_t n = (size_t)(patches[i].deg_u + 1) * (size_t)(patches[i].deg_v + 1);
        npts += 3 * n;
        if (patches[i].weights) nw += n;
    }
    const size_t bytes = sizeof(cj_patch_collider) + sizeof(cj_patch) * count +
                         sizeof(double) * (npts + nw) + sizeof(cj_aabb) * count;
    cj_patch_collider *c = pc_alloc(alloc, bytes);
    if (!c) return cj_fail(CJ_ERR_NOMEM, "patch collider: no memory for %zu patches", count);
    memset(c, 0, sizeof *c);
    if (alloc) {
        c->alloc = *alloc;
        c->has_alloc = 1;
    }
    c->count = count;
    c->patches = (cj_patch *)(c + 1);
    c->pts = (double *)(c->patches + count);
    c->w = c->pts + npts;
    c->boxes = (cj_aabb *)(c->w + nw);
    cj_aabb *boxes = c->boxes;
    c->all = cj_aabb_empty();
    c->tol = tol;
    c->friction = friction;
    double *p = c->pts, *w = c->w, size = 0.0;
    cj_status st = CJ_OK;
    for (size_t i = 0; i < count && st == CJ_OK; ++i) {
        const cj_patch *src = &patches[i];
        const size_t n = (size_t)(src->deg_u + 1) * (size_t)(src->deg_v + 1);
        if (to_world)
            st = cj_xform3_apply_points(to_world, src->pts, n, p);
        else
            memcpy(p, src->pts, sizeof(double) * 3 * n);
        const double *wi = NULL;
        if (src->weights) {
            memcpy(w, src->weights, sizeof(double) * n);
            wi = w;
            w += n;
        }
        c->patches[i] = cj_patch_view(src->deg_u, src->deg_v, p, wi);
        boxes[i] = cj_aabb_empty();
        for (size_t k = 0; k < n; ++k)
            cj_aabb_grow(&boxes[i], cj_v3(p[3 * k], p[3 * k + 1], p[3 * k + 2]));
        for (int k = 0; k < 3; ++k) size = fmax(size, boxes[i].hi[k] - boxes[i].lo[k]);
        cj_aabb_grow(&c->all, cj_v3(boxes[i].lo[0], boxes[i].lo[1], boxes[i].lo[2]));
        cj_aabb_grow(&c->all, cj_v3(boxes[i].hi[0], boxes[i].hi[1], boxes[i].hi[2]));
        p += 3 * n;
    }
    if (st == CJ_OK) st = cj_bvh_build(boxes, count, alloc, &c->bvh);
    if (st != CJ_OK) {
        pc_free(alloc, c);
        return st;
    }
    c->offset = 1e-6 * size + 100.0 * tol; /* well clear of cj_ray_patch's own-surface rejection */
    *out = c;
    return CJ_OK;
}

void cj_patch_collider_destroy(cj_patch_collider *c) {
    if (!c) return;
    free(c->seal);
    free(c->seal_data);
    cj_bvh_destroy(c->bvh);
    pc_free(c->has_alloc ? &c->alloc : NULL, c);
}

static int hit_patch(void *user, uint32_t prim, const cj_ray *ray, cj_hit *hit) {
    const cj_patch_collider *c = user;
    return cj_ray_patch(ray, &c->patches[prim], c->tol, hit, NULL);
}

int cj_patch_collider_segment(const cj_patch_collider *c, const double a[3], const double b[3],
                              double *t, double point[3], double normal[3]) {
    cj_ray ray;
    ray.org = cj_v3(a[0], a[1], a[2]);
    const cj_vec3 d = cj_v3(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    const double len = cj_v3_norm(d);
    if (!(len > 0.0)) return 0;
    /* a unit direction: cj_ray_patch missed short grazing segments given as b − a (a step of a
     * few millimetres along a surface) and finds them with the same line at unit speed */
    ray.dir = cj_v3_scale(d, 1.0 / len);
    ray.tmin = 0.0;
    ray.tmax = len;
    cj_hit h;
    int found = cj_bvh_closest(c->bvh, &ray, hit_patch, (void *)c, &h, NULL);
    for (size_t i = 0; i < c->nseal; ++i) { /* a solid's seals (few): tested directly */
        cj_hit hs;
        if (cj_ray_patch(&ray, &c->seal[i], c->tol, &hs, NULL) && (!found || hs.t < h.t)) {
            h = hs;
            found = 1;
        }
    }
    if (!found) return 0;
    cj_vec3 n = h.n;
    if (cj_v3_dot(n, ray.dir) > 0.0) n = cj_v3_scale(n, -1.0);
    *t = h.t / len;
    point[0] = h.p.x;
    point[1] = h.p.y;
    point[2] = h.p.z;
    normal[0] = n.x;
    normal[1] = n.y;
    normal[2] = n.z;
    return 1;
}

int cj_patch_collider_resolve_(const cj_patch_collider *c, const double a[3], double x[3],
                               double v[3], double restitution) {
    double t, p[3], n[3];
    if (!cj_patch_collider_segment(c, a, x, &t, p, n)) return 0;
    double vn = 0.0;
    for (int k = 0; k < 3; ++k) {
        x[k] = p[k] + c->offset * n[k];
        vn += v[k] * n[k];
    }
    if (vn < 0.0)
        for (int k = 0; k < 3; ++k) {
            const double vt = v[k] - vn * n[k];
            v[k] = -restitution * vn * n[k] + (1.0 - c->friction) * vt;
        }
    return 1;
}

/* Control point a of side s of patch p (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0). */
static int side_point(const cj_patch *p, int s, int a) {
    const int m = p->deg_u;
    switch (s) {
    case 0:
        return a;
    case 1:
        return a * (m + 1) + m;
    case 2:
        return p->deg_v * (m + 1) + a;
    default:
        return a * (m + 1);
    }
}

static int side_count(const cj_patch *p, int s) {
    return (s & 1 ? p->deg_v : p->deg_u) + 1;
}

static int same_point(const cj_patch *p, int i, const cj_patch *r, int j) {
    const double *x = p->pts + 3 * i, *y = r->pts + 3 * j;
    const double wi = p->weights ? p->weights[i] : 1.0, wj = r->weights ? r->weights[j] : 1.0;
    return x[0] == y[0] && x[1] == y[1] && x[2] == y[2] && wi == wj;
}

/* Whether side s of patch q is open: no other side has the same control points (either
 * direction) and its points do not all coincide. */
static int side_open(const cj_patch_collider *c, size_t q, int s) {
    const cj_patch *p = &c->patches[q];
    const int n = side_count(p, s);
    int collapsed = 1;
    for (int a = 1; a < n && collapsed; ++a)
        collapsed = same_point(p, side_point(p, s, a), p, side_point(p, s, 0));
    if (collapsed) return 0;
    for (size_t r = 0; r < c->count; ++r)
        for (int t = 0; t < 4; ++t) {
            const cj_patch *o = &c->patches[r];
            if ((r == q && t == s) || side_count(o, t) != n) continue;
            int fwd = 1, rev = 1;
            for (int a = 0; a < n && (fwd || rev); ++a) {
                fwd = fwd && same_point(p, side_point(p, s, a), o, side_point(o, t, a));
                rev = rev && same_point(p, side_point(p, s, a), o, side_point(o, t, n - 1 - a));
            }
            if (fwd || rev) return 0;
        }
    return 1;
}

/* The largest distance between corresponding control points of two sides of equal count
 * (b's in reverse when rev). */
static double side_gap(const cj_patch *p, int s, const cj_patch *o, int t, int rev) {
    const int n = side_count(p, s);
    double g = 0.0;
    for (int a = 0; a < n; ++a) {
        const double *x = p->pts + 3 * side_point(p, s, a),
                     *y = o->pts + 3 * side_point(o, t, rev ? n - 1 - a : a);
        const double d = sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                              (x[2] - y[2]) * (x[2] - y[2]));
        g = fmax(g, d);
    }
    return g;
}

/* Seals: every open side whose nearest open side of another patch (same count, either
 * direction) lies within CJ_SEAL_GAP of the collider's size gets a ruled patch to it (each
 * pair once). The teapot's lid rests 0.1 inside its rim (1.6% of its size): four seals. */
#define CJ_SEAL_GAP 0.02
static void seal_gaps(cj_patch_collider *c) {
    double size = 0.0;
    for (int k = 0; k < 3; ++k) size = fmax(size, c->all.hi[k] - c->all.lo[k]);
    const size_t nside = 4 * c->count;
    unsigned char *open = malloc(nside);
    int *pair = malloc(sizeof(int) * nside);
    cj_patch *seal = malloc(sizeof(cj_patch) * nside);
    double *data = malloc(sizeof(double) * nside * 2 * (CJ_PATCH_MAX_DEGREE + 1) * 4);
    if (!open || !pair || !seal || !data) {
        free(open), free(pair), free(seal), free(data);
        return; /* no seals: the solid keeps its gaps */
    }
    for (size_t i = 0; i < nside; ++i) {
        open[i] = (unsigned char)side_open(c, i / 4, (int)(i % 4));
        pair[i] = -1;
    }
    size_t ns = 0;
    double *d = data;
    for (size_t i = 0; i < nside; ++i) {
        if (!open[i] || pair[i] >= 0) continue;
        const cj_patch *p = &c->patches[i / 4];
        const int s = (int)(i % 4), n = side_count(p, s);
        double best = CJ_SEAL_GAP * size;
        size_t bj = 0;
        int brev = 0, found = 0;
        for (size_t j = 0; j < nside; ++j) {
            if (!open[j] || j / 4 == i / 4 || side_count(&c->patches[j / 4], (int)(j % 4)) != n)
                continue;
            for (int rev = 0; rev < 2; ++rev) {
                const double g = side_gap(p, s, &c->patches[j / 4], (int)(j % 4), rev);
                if (g < best) {
                    best = g;
                    bj = j;
                    brev = rev;
                    found = 1;
                }
            }
        }
        if (!found || pair[bj] >= 0) continue;
        pair[i] = (int)bj;
        pair[bj] = (int)i;
        /* degree (n - 1, 1): row 0 this side, row 1 the other (reversed to match) */
        const cj_patch *o = &c->patches[bj / 4];
        const int t = (int)(bj % 4);
        const int rational = p->weights || o->weights;
        double *pts = d, *w = rational ? d + 6 * n : NULL;
        for (int a = 0; a < n; ++a) {
            const int ip = side_point(p, s, a), io = side_point(o, t, brev ? n - 1 - a : a);
            memcpy(pts + 3 * a, p->pts + 3 * ip, 3 * sizeof(double));
            memcpy(pts + 3 * (n + a), o->pts + 3 * io, 3 * sizeof(double));
            if (w) {
                w[a] = p->weights ? p->weights[ip] : 1.0;
                w[n + a] = o->weights ? o->weights[io] : 1.0;
            }
        }
        seal[ns++] = cj_patch_view(n - 1, 1, pts, w);
        d += 8 * n;
    }
    free(open);
    free(pair);
    c->seal = seal;
    c->seal_data = data;
    c->nseal = ns;
}

void cj_patch_collider_set_solid(cj_patch_collider *c, const double up[3]) {
    assert(c != NULL);
    const double l = up ? sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]) : 0.0;
    c->solid = l > 0.0 && isfinite(l);
    for (int k = 0; k < 3; ++k) c->up[k] = c->solid ? up[k] / l : 0.0;
    free(c->seal);
    free(c->seal_data);
    c->seal = NULL;
    c->seal_data = NULL;
    c->nseal = 0;
    if (c->solid) seal_gaps(c);
}

size_t cj_patch_collider_seals(const cj_patch_collider *c) {
    assert(c != NULL);
    return c->nseal;
}

/* The crossings of one ray with the patches, gathered by the BVH walk (the primitive callback
 * records every hit and reports none, so that every patch whose box the ray meets is seen). */
typedef struct crossing_walk {
    const cj_patch_collider *c;
    double t[64];
    int n;
} crossing_walk;

static int record_crossings(void *user, uint32_t prim, const cj_ray *ray, cj_hit *hit) {
    crossing_walk *w = user;
    cj_ray r = *ray;
    (void)hit;
    cj_hit h;
    for (int k = 0; k < 8 && w->n < 64; ++k) {
        if (!cj_ray_patch(&r, &w->c->patches[prim], w->c->tol, &h, NULL)) break;
        w->t[w->n++] = h.t;
        r.tmin = h.t + 1e3 * w->c->tol;
    }
    return 0;
}

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int cj_patch_collider_inside(const cj_patch_collider *c, const double x[3]) {
    assert(c != NULL && x != NULL);
    if (!c->solid) return 0;
    for (int k = 0; k < 3; ++k)
        if (!(x[k] >= c->all.lo[k] && x[k] <= c->all.hi[k])) return 0;
    double reach = 0.0;
    for (int k = 0; k < 3; ++k) reach += c->all.hi[k] - c->all.lo[k];
    cj_ray ray;
    ray.org = cj_v3(x[0], x[1], x[2]);
    ray.dir = cj_v3(c->up[0], c->up[1], c->up[2]);
    ray.tmin = 0.0;
    ray.tmax = reach;
    crossing_walk w;
    w.c = c;
    w.n = 0;
    cj_hit unused;
    (void)cj_bvh_closest(c->bvh, &ray, record_crossings, &w, &unused, NULL);
    for (size_t i = 0; i < c->nseal; ++i) {
        cj_ray r = ray;
        for (int k = 0; k < 8 && w.n < 64; ++k) {
            if (!cj_ray_patch(&r, &c->seal[i], c->tol, &unused, NULL)) break;
            w.t[w.n++] = unused.t;
            r.tmin = unused.t + 1e3 * c->tol;
        }
    }
    /* a crossing on a seam is found on both patches: count crossings, not hits */
    qsort(w.t, (size_t)w.n, sizeof(double), cmp_double);
    int crossings = 0;
    for (int i = 0; i < w.n; ++i)
        if (i == 0 || w.t[i] - w.t[i - 1] > 1e3 * c->tol) ++crossings;
    return crossings & 1;
}

int cj_patch_collider_push_out_(const cj_patch_collider *c, double x[3], double v[3]) {
    if (!cj_patch_collider_inside(c, x)) return 0;
    double best = INFINITY, p[3] = {0.0, 0.0, 0.0};
    for (size_t q = 0; q < c->count; ++q) {
        double gap2 = 0.0; /* the distance to the patch's box bounds the distance to it */
        for (int k = 0; k < 3; ++k) {
            const double g = fmax(0.0, fmax(c->boxes[q].lo[k] - x[k], x[k] - c->boxes[q].hi[k]));
            gap2 += g * g;
        }
        if (!(sqrt(gap2) < best)) continue;
        cj_patch_nearest_result r;
        if (cj_patch_nearest(&c->patches[q], x, c->tol, &r) != CJ_OK) continue;
        if (r.distance < best) {
            best = r.distance;
            memcpy(p, r.point, sizeof p);
        }
    }
    for (size_t i = 0; i < c->nseal; ++i) {
        cj_patch_nearest_result r;
        if (cj_patch_nearest(&c->seal[i], x, c->tol, &r) == CJ_OK && r.distance < best) {
            best = r.distance;
            memcpy(p, r.point, sizeof p);
        }
    }
    if (!(best < INFINITY) || !(best > 0.0)) return 0;
    /* out through the nearest surface point: from x towards it, and past it by the offset */
    double n[3], vn = 0.0;
    for (int k = 0; k < 3; ++k) n[k] = (p[k] - x[k]) / best;
    for (int k = 0; k < 3; ++k) {
        x[k] = p[k] + c->offset * n[k];
        vn += v[k] * n[k];
    }
    if (vn < 0.0)
        for (int k = 0; k < 3; ++k) {
            const double vt = v[k] - vn * n[k];
            v[k] = (1.0 - c->friction) * vt;
        }
    return 1;
}
