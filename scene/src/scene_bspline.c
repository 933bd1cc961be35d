/* B-spline / NURBS surfaces kept in the scene model next to the Bézier patches the renderers
 * draw (casteljau/scene_bspline.h): one owned block per geometry holding the net, weights,
 * knots and the span breaks that map a control point to the patches it moves. */
#include "casteljau/scene_bspline.h"

#include "error_internal.h"
#include "scene_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct cj_scene_bspline_ {
    cj_bspline_surface surf; /* views into data[] */
    int nspans_u, nspans_v;
    const double *ub, *vb; /* the breaks: nspans_u + 1 and nspans_v + 1 values */
    double data[];         /* pts, weights, knots_u, knots_v, ub, vb */
};

/* The surface's patches in freshly allocated buffers (pts, weights for a NURBS, breaks). */
typedef struct converted {
    int count, nsu, nsv;
    double *pts, *w, *ub, *vb;
} converted;

static void converted_free(converted *c) {
    free(c->pts);
    free(c->w);
    free(c->ub);
    free(c->vb);
}

/* The non-empty knot spans of the domain [knots[deg], knots[n]]. */
static int nonempty_spans(const double *knots, int deg, int n) {
    int spans = 0;
    for (int a = deg; a < n; ++a) spans += knots[a + 1] > knots[a];
    return spans;
}

static cj_status convert(const cj_bspline_surface *s, converted *c) {
    memset(c, 0, sizeof *c);
    cj_status st = cj_bspline_surface_patch_count(s, &c->count);
    if (st) return st;
    const size_t per = (size_t)(s->deg_u + 1) * (size_t)(s->deg_v + 1);
    c->pts = malloc(sizeof(double) * 3 * per * (size_t)c->count);
    c->w = s->weights ? malloc(sizeof(double) * per * (size_t)c->count) : NULL;
    c->ub = malloc(sizeof(double) * (size_t)(s->npts_u + 1));
    c->vb = malloc(sizeof(double) * (size_t)(s->npts_v + 1));
    if (!c->pts || (s->weights && !c->w) || !c->ub || !c->vb) {
        converted_free(c);
        return cj_fail(CJ_ERR_NOMEM, "out of memory converting a B-spline surface to patches");
    }
    st = cj_bspline_surface_to_patches(s, c->pts, c->w, c->ub, c->vb, c->count, NULL);
    if (st) {
        converted_free(c);
        return st;
    }
    c->nsu = nonempty_spans(s->knots_u, s->deg_u, s->npts_u);
    c->nsv = nonempty_spans(s->knots_v, s->deg_v, s->npts_v);
    assert(c->nsu * c->nsv == c->count);
    return CJ_OK;
}

cj_status cj_scene_add_bspline_surface_at_(cj_scene *scene, const cj_bspline_surface *s,
                                           const char *path, int *index) {
    assert(scene && s && path);
    cj_status st = cj_bspline_surface_check(s);
    if (st) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_fail(st, "%s: %s", path, msg);
    }
    converted c;
    if ((st = convert(s, &c))) return st;
    const size_t n = (size_t)s->npts_u * (size_t)s->npts_v;
    const size_t nku = (size_t)(s->npts_u + s->deg_u + 1), nkv = (size_t)(s->npts_v + s->deg_v + 1);
    const size_t nd =
        3 * n + (s->weights ? n : 0) + nku + nkv + (size_t)(c.nsu + 1) + (size_t)(c.nsv + 1);
    struct cj_scene_bspline_ *b = cj_scene_alloc_(scene, sizeof *b + nd * sizeof(double));
    cj_patch *patches = calloc((size_t)c.count, sizeof *patches);
    if (!b || !patches) {
        cj_scene_free_(scene, b);
        free(patches);
        converted_free(&c);
        return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", path);
    }
    double *d = b->data;
    b->surf = *s;
    memcpy(d, s->pts, 3 * n * sizeof(double));
    b->surf.pts = d;
    d += 3 * n;
    if (s->weights) {
        memcpy(d, s->weights, n * sizeof(double));
        b->surf.weights = d;
        d += n;
    }
    memcpy(d, s->knots_u, nku * sizeof(double));
    b->surf.knots_u = d;
    d += nku;
    memcpy(d, s->knots_v, nkv * sizeof(double));
    b->surf.knots_v = d;
    d += nkv;
    memcpy(d, c.ub, (size_t)(c.nsu + 1) * sizeof(double));
    b->ub = d;
    d += c.nsu + 1;
    memcpy(d, c.vb, (size_t)(c.nsv + 1) * sizeof(double));
    b->vb = d;
    b->nspans_u = c.nsu;
    b->nspans_v = c.nsv;
    const size_t per = (size_t)(s->deg_u + 1) * (size_t)(s->deg_v + 1);
    for (int k = 0; k < c.count; ++k)
        patches[k] = cj_patch_view(s->deg_u, s->deg_v, c.pts + 3 * per * (size_t)k,
                                   c.w ? c.w + per * (size_t)k : NULL);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = (size_t)c.count;
    g.u.patches.patches = patches;
    int at = -1;
    st = cj_scene_check_geometry_(&g, path);
    if (!st) st = cj_scene_add_geometry(scene, &g, &at);
    free(patches);
    converted_free(&c);
    if (st) {
        cj_scene_free_(scene, b);
        return st;
    }
    scene->gstore[at].bspline = b;
    if (index) *index = at;
    return CJ_OK;
}

cj_status cj_scene_add_bspline_surface(cj_scene *scene, const cj_bspline_surface *s, int *index) {
    assert(scene && s);
    char path[48];
    snprintf(path, sizeof path, "geometries[%zu]", scene->ngeoms);
    return cj_scene_add_bspline_surface_at_(scene, s, path, index);
}

static struct cj_scene_bspline_ *kept(const cj_scene *scene, int index) {
    assert(scene);
    if (index < 0 || (size_t)index >= scene->ngeoms) return NULL;
    return scene->gstore[index].bspline;
}

const cj_bspline_surface *cj_scene_geometry_bspline(const cj_scene *scene, int index) {
    const struct cj_scene_bspline_ *b = kept(scene, index);
    return b ? &b->surf : NULL;
}

/* The spans [first, last] of breaks br[0..nspans] that meet the open box (lo, hi). */
static void span_range(const double *br, int nspans, double lo, double hi, int *first, int *last) {
    *first = nspans;
    *last = -1;
    for (int a = 0; a < nspans; ++a)
        if (br[a] < hi && br[a + 1] > lo) {
            if (a < *first) *first = a;
            *last = a;
        }
}

int cj_scene_bspline_support(const cj_scene *scene, int index, int i, int j, int *patches,
                             int cap) {
    const struct cj_scene_bspline_ *b = kept(scene, index);
    if (!b || i < 0 || j < 0 || i >= b->surf.npts_u || j >= b->surf.npts_v) return -1;
    const cj_bspline_surface *s = &b->surf;
    int a0, a1, b0, b1;
    span_range(b->ub, b->nspans_u, s->knots_u[i], s->knots_u[i + s->deg_u + 1], &a0, &a1);
    span_range(b->vb, b->nspans_v, s->knots_v[j], s->knots_v[j + s->deg_v + 1], &b0, &b1);
    int n = 0;
    for (int bv = b0; bv <= b1; ++bv)
        for (int au = a0; au <= a1; ++au, ++n)
            if (patches && n < cap) patches[n] = bv * b->nspans_u + au;
    return n;
}

int cj_scene_bspline_in_sync_(const cj_scene *scene, int index) {
    const struct cj_scene_bspline_ *b = kept(scene, index);
    if (!b) return 0;
    const cj_geometry *g = &scene->geoms[index];
    converted c;
    if (g->kind != CJ_GEOM_PATCHES || convert(&b->surf, &c)) return 0;
    int same = (size_t)c.count == g->u.patches.count;
    const size_t per = (size_t)(b->surf.deg_u + 1) * (size_t)(b->surf.deg_v + 1);
    for (int k = 0; same && k < c.count; ++k) {
        const cj_patch *p = &g->u.patches.patches[k];
        same = p->deg_u == b->surf.deg_u && p->deg_v == b->surf.deg_v && !p->weights == !c.w &&
               !memcmp(p->pts, c.pts + 3 * per * (size_t)k, 3 * per * sizeof(double)) &&
               (!c.w || !memcmp(p->weights, c.w + per * (size_t)k, per * sizeof(double)));
    }
    converted_free(&c);
    return same;
}

/* Copies the patches of `c` listed in which[0..n) (all when which is NULL) that differ from the
 * geometry's into it; the differing ones go to changed[0..cap); returns how many differed. */
static int rewrite(cj_geometry *g, const converted *c, size_t per, const int *which, int n,
                   int *changed, int cap) {
    int nc = 0;
    for (int m = 0; m < n; ++m) {
        const int k = which ? which[m] : m;
        const cj_patch *p = &g->u.patches.patches[k];
        const double *np = c->pts + 3 * per * (size_t)k;
        const double *nw = c->w ? c->w + per * (size_t)k : NULL;
        if (!memcmp(p->pts, np, 3 * per * sizeof(double)) &&
            (!nw || !memcmp(p->weights, nw, per * sizeof(double))))
            continue;
        memcpy((double *)p->pts, np, 3 * per * sizeof(double));
        if (nw) memcpy((double *)p->weights, nw, per * sizeof(double));
        if (changed && nc < cap) changed[nc] = k;
        ++nc;
    }
    return nc;
}

cj_status cj_scene_bspline_set_point(cj_scene *scene, int index, int i, int j, const double xyz[3],
                                     double weight, int *changed, int cap, int *nchanged) {
    assert(scene && xyz);
    struct cj_scene_bspline_ *b = kept(scene, index);
    if (!b) return cj_fail(CJ_ERR_ARGUMENT, "geometry %d has no B-spline form", index);
    cj_bspline_surface *s = &b->surf;
    if (i < 0 || j < 0 || i >= s->npts_u || j >= s->npts_v)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "geometries[%d]: control point (%d, %d) outside the %d x %d net", index, i,
                       j, s->npts_u, s->npts_v);
    for (int k = 0; k < 3; ++k) {
        if (!isfinite(xyz[k]))
            return cj_fail(CJ_ERR_NONFINITE, "geometries[%d]: point (%d, %d) coordinate %d is %g",
                           index, i, j, k, xyz[k]);
        if (fabs(xyz[k]) > CJ_SCENE_MAX_COORD)
            return cj_fail(CJ_ERR_RANGE,
                           "geometries[%d]: point (%d, %d) coordinate %d = %g beyond %g", index, i,
                           j, k, xyz[k], CJ_SCENE_MAX_COORD);
    }
    if (!isfinite(weight))
        return cj_fail(CJ_ERR_NONFINITE, "geometries[%d]: weight of point (%d, %d) is %g", index, i,
                       j, weight);
    if (s->weights ? !(weight > 0.0) : weight != 1.0)
        return cj_fail(CJ_ERR_ARGUMENT, "geometries[%d]: weight of point (%d, %d) is %g (%s)",
                       index, i, j, weight,
                       s->weights ? "must be > 0" : "a polynomial surface has weights 1");
    const size_t at = (size_t)j * (size_t)s->npts_u + (size_t)i;
    double *pts = (double *)s->pts, *w = (double *)s->weights;
    double old[4] = {pts[3 * at], pts[3 * at + 1], pts[3 * at + 2], w ? w[at] : 1.0};
    memcpy(pts + 3 * at, xyz, 3 * sizeof(double));
    if (w) w[at] = weight;
    converted c;
    cj_status st = convert(s, &c);
    if (st) {
        memcpy(pts + 3 * at, old, 3 * sizeof(double));
        if (w) w[at] = old[3];
        return st;
    }
    int support[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1)];
    const int ns = cj_scene_bspline_support(scene, index, i, j, support,
                                            (int)(sizeof support / sizeof *support));
    const size_t per = (size_t)(s->deg_u + 1) * (size_t)(s->deg_v + 1);
    const int nc = rewrite(&scene->geoms[index], &c, per, support, ns, changed, cap);
    converted_free(&c);
    if (nchanged) *nchanged = nc;
    return CJ_OK;
}

cj_status cj_scene_bspline_refresh(cj_scene *scene, int index, int *changed, int cap,
                                   int *nchanged) {
    struct cj_scene_bspline_ *b = kept(scene, index);
    if (!b) return cj_fail(CJ_ERR_ARGUMENT, "geometry %d has no B-spline form", index);
    cj_status st = cj_bspline_surface_check(&b->surf);
    if (st) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_fail(st, "geometries[%d]: %s", index, msg);
    }
    converted c;
    if ((st = convert(&b->surf, &c))) return st;
    cj_geometry *g = &scene->geoms[index];
    const size_t per = (size_t)(b->surf.deg_u + 1) * (size_t)(b->surf.deg_v + 1);
    const int nc = rewrite(g, &c, per, NULL, c.count, changed, cap);
    converted_free(&c);
    if (nchanged) *nchanged = nc;
    return CJ_OK;
}
