/* Implicit plane curves: built-ins, gradients, projection, and marching-squares contouring with
 * crossing and chord refinement. See casteljau/implicit.h. */
#include "casteljau/implicit.h"
#include "alloc_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { SHAPE_LINE = 1, SHAPE_CIRCLE, SHAPE_ELLIPSE, SHAPE_POLY };

#define POLY_MAX_DEGREE 32
#define CHORD_DEPTH     24
#define EDGE_ITERS      200

/* ---- built-ins --------------------------------------------------------------------------- */

static double line_f(const void *u, double x, double y) {
    const cj_implicit_shape *s = u;
    return s->c[0] * x + s->c[1] * y + s->c[2];
}
static void line_g(const void *u, double x, double y, double g[2]) {
    const cj_implicit_shape *s = u;
    (void)x;
    (void)y;
    g[0] = s->c[0];
    g[1] = s->c[1];
}
static double circle_f(const void *u, double x, double y) {
    const cj_implicit_shape *s = u;
    const double dx = x - s->c[0], dy = y - s->c[1];
    return dx * dx + dy * dy - s->c[2] * s->c[2];
}
static void circle_g(const void *u, double x, double y, double g[2]) {
    const cj_implicit_shape *s = u;
    g[0] = 2.0 * (x - s->c[0]);
    g[1] = 2.0 * (y - s->c[1]);
}
/* Ellipse data: c = {cx, cy, rx, ry, cos rot, sin rot}. */
static void ellipse_local(const cj_implicit_shape *s, double x, double y, double *u, double *v) {
    const double dx = x - s->c[0], dy = y - s->c[1];
    *u = s->c[4] * dx + s->c[5] * dy;
    *v = -s->c[5] * dx + s->c[4] * dy;
}
static double ellipse_f(const void *p, double x, double y) {
    const cj_implicit_shape *s = p;
    double u, v;
    ellipse_local(s, x, y, &u, &v);
    const double a = u / s->c[2], b = v / s->c[3];
    return a * a + b * b - 1.0;
}
static void ellipse_g(const void *p, double x, double y, double g[2]) {
    const cj_implicit_shape *s = p;
    double u, v;
    ellipse_local(s, x, y, &u, &v);
    const double gu = 2.0 * u / (s->c[2] * s->c[2]), gv = 2.0 * v / (s->c[3] * s->c[3]);
    /* (u, v) = R(−rot)(x − c): ∇_x f = R(rot) ∇_(u,v) f. */
    g[0] = s->c[4] * gu - s->c[5] * gv;
    g[1] = s->c[5] * gu + s->c[4] * gv;
}

static size_t poly_index(int i, int j) { /* coefficient of x^i y^j */
    const int s = i + j;
    return (size_t)s * (size_t)(s + 1) / 2 + (size_t)j;
}
/* value, ∂x, ∂y by nested Horner (x outer, y inner). */
static void poly_eval(const cj_implicit_shape *s, double x, double y, double *f, double *fx,
                      double *fy) {
    const int n = s->degree;
    double acc = 0.0, dx = 0.0, dy = 0.0;
    for (int i = n; i >= 0; --i) {
        double q = 0.0, dq = 0.0;
        for (int j = n - i; j >= 0; --j) {
            dq = dq * y + q;
            q = q * y + s->coef[poly_index(i, j)];
        }
        dx = dx * x + acc;
        acc = acc * x + q;
        dy = dy * x + dq;
    }
    *f = acc;
    if (fx) *fx = dx;
    if (fy) *fy = dy;
}
static double poly_f(const void *u, double x, double y) {
    double f;
    poly_eval(u, x, y, &f, NULL, NULL);
    return f;
}
static void poly_g(const void *u, double x, double y, double g[2]) {
    double f;
    poly_eval(u, x, y, &f, &g[0], &g[1]);
}

size_t cj_implicit_poly_ncoef(int degree) {
    if (degree < 0) return 0;
    return (size_t)(degree + 1) * (size_t)(degree + 2) / 2;
}

static void set_out(cj_implicit_shape *s, int kind, cj_implicit_curve_fn f,
                    cj_implicit_curve_grad_fn g, cj_implicit *out) {
    s->kind = kind;
    out->f = f;
    out->grad = g;
    out->user = s;
}

cj_status cj_implicit_line(double a, double b, double c, cj_implicit_shape *shape,
                           cj_implicit *out) {
    assert(shape && out);
    const double v[3] = {a, b, c};
    cj_status st = cj_check_finite(v, 3, "line coefficient");
    if (st) return st;
    if (a == 0.0 && b == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "line a x + b y + c = 0 has a = b = 0");
    memset(shape, 0, sizeof *shape);
    shape->c[0] = a;
    shape->c[1] = b;
    shape->c[2] = c;
    set_out(shape, SHAPE_LINE, line_f, line_g, out);
    return CJ_OK;
}

cj_status cj_implicit_circle(double cx, double cy, double r, cj_implicit_shape *shape,
                             cj_implicit *out) {
    assert(shape && out);
    const double v[3] = {cx, cy, r};
    cj_status st = cj_check_finite(v, 3, "circle parameter (cx, cy, r)");
    if (st) return st;
    if (!(r > 0.0)) return cj_fail(CJ_ERR_DEGENERATE, "circle radius %g is not positive", r);
    memset(shape, 0, sizeof *shape);
    shape->c[0] = cx;
    shape->c[1] = cy;
    shape->c[2] = r;
    set_out(shape, SHAPE_CIRCLE, circle_f, circle_g, out);
    return CJ_OK;
}

cj_status cj_implicit_ellipse(double cx, double cy, double rx, double ry, double rot,
                              cj_implicit_shape *shape, cj_implicit *out) {
    assert(shape && out);
    const double v[5] = {cx, cy, rx, ry, rot};
    cj_status st = cj_check_finite(v, 5, "ellipse parameter (cx, cy, rx, ry, rot)");
    if (st) return st;
    if (!(rx > 0.0) || !(ry > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "ellipse radii must be positive (rx = %g, ry = %g)", rx,
                       ry);
    memset(shape, 0, sizeof *shape);
    shape->c[0] = cx;
    shape->c[1] = cy;
    shape->c[2] = rx;
    shape->c[3] = ry;
    shape->c[4] = cos(rot);
    shape->c[5] = sin(rot);
    set_out(shape, SHAPE_ELLIPSE, ellipse_f, ellipse_g, out);
    return CJ_OK;
}

cj_status cj_implicit_poly(int degree, const double *coef, cj_implicit_shape *shape,
                           cj_implicit *out) {
    assert(shape && out);
    if (degree < 0 || degree > POLY_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "polynomial degree %d is outside 0..%d", degree,
                       POLY_MAX_DEGREE);
    assert(coef != NULL);
    cj_status st = cj_check_finite(coef, cj_implicit_poly_ncoef(degree), "polynomial coefficient");
    if (st) return st;
    memset(shape, 0, sizeof *shape);
    shape->degree = degree;
    shape->coef = coef;
    set_out(shape, SHAPE_POLY, poly_f, poly_g, out);
    return CJ_OK;
}

/* ---- evaluation -------------------------------------------------------------------------- */

static void grad_raw(const cj_implicit *f, double x, double y, double g[2]) {
    if (f->grad) {
        f->grad(f->user, x, y, g);
        return;
    }
    const double hx = 0x1p-17 * fmax(1.0, fabs(x)), hy = 0x1p-17 * fmax(1.0, fabs(y));
    /* Make the steps exactly representable differences. */
    volatile double xp = x + hx, xm = x - hx, yp = y + hy, ym = y - hy;
    g[0] = (f->f(f->user, xp, y) - f->f(f->user, xm, y)) / (xp - xm);
    g[1] = (f->f(f->user, x, yp) - f->f(f->user, x, ym)) / (yp - ym);
}

cj_status cj_implicit_curve_eval(const cj_implicit *f, double x, double y, double *value,
                                 double g[2]) {
    assert(f != NULL && f->f != NULL);
    if (!isfinite(x) || !isfinite(y))
        return cj_fail(CJ_ERR_NONFINITE, "implicit curve evaluated at a non-finite point");
    if (value) {
        double v = f->f(f->user, x, y);
        if (!isfinite(v)) return cj_fail(CJ_ERR_NONFINITE, "f(%.17g, %.17g) is not finite", x, y);
        *value = v;
    }
    if (g) {
        double gg[2];
        grad_raw(f, x, y, gg);
        if (!isfinite(gg[0]) || !isfinite(gg[1]))
            return cj_fail(CJ_ERR_NONFINITE, "gradient of f at (%.17g, %.17g) is not finite", x, y);
        g[0] = gg[0];
        g[1] = gg[1];
    }
    return CJ_OK;
}

cj_status cj_implicit_curve_normal(const cj_implicit *f, double x, double y, double n[2]) {
    assert(n != NULL);
    double g[2];
    cj_status st = cj_implicit_curve_eval(f, x, y, NULL, g);
    if (st) return st;
    const double len = hypot(g[0], g[1]);
    if (!(len > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "gradient of f vanishes at (%.17g, %.17g)", x, y);
    n[0] = g[0] / len;
    n[1] = g[1] / len;
    return CJ_OK;
}

/* |f|/|∇f| at a point (f and gradient already known). */
static double residual_of(double v, const double g[2]) {
    const double len = hypot(g[0], g[1]);
    if (v == 0.0) return 0.0;
    return len > 0.0 ? fabs(v) / len : INFINITY;
}

cj_status cj_implicit_curve_project(const cj_implicit *f, double xy[2], double tol,
                                    double *residual) {
    assert(xy != NULL);
    if (!(tol > 0.0) || !isfinite(tol))
        return cj_fail(CJ_ERR_ARGUMENT, "projection tolerance %g must be positive and finite", tol);
    double p[2] = {xy[0], xy[1]}, res = INFINITY;
    for (int it = 0; it <= 50; ++it) {
        double v, g[2];
        cj_status st = cj_implicit_curve_eval(f, p[0], p[1], &v, g);
        if (st) return st;
        res = residual_of(v, g);
        if (res <= tol) {
            xy[0] = p[0];
            xy[1] = p[1];
            if (residual) *residual = res;
            return CJ_OK;
        }
        const double g2 = g[0] * g[0] + g[1] * g[1];
        if (!(g2 > 0.0)) break;
        if (it == 50) break;
        p[0] -= v * g[0] / g2;
        p[1] -= v * g[1] / g2;
    }
    xy[0] = p[0];
    xy[1] = p[1];
    if (residual) *residual = res;
    return cj_fail(CJ_ERR_CAP, "projection onto f = 0 stopped at residual %g > tol %g", res, tol);
}

/* ---- contouring -------------------------------------------------------------------------- */

typedef struct contour_ctx {
    const cj_implicit *f;
    double tol;
    int nx, ny;
    double x0, y0, x1, y1;
    double *val;        /* (nx+1)(ny+1) corner values */
    double *exy;        /* 2 per edge: crossing point */
    double *eres;       /* residual per edge */
    int *link;          /* 2 per edge: linked edges, -1 none */
    char *visited;      /* per edge */
    cj_allocator alloc; /* every work array comes from here */
    size_t nh, ne;      /* horizontal edges, all edges */
    /* polyline buffer */
    double *buf;
    size_t len, cap;
    size_t emitted; /* vertices in polylines already emitted */
    double poly_res;
    int capped;
    cj_status err;
} contour_ctx;

static double gx(const contour_ctx *c, int i) {
    return i == c->nx ? c->x1 : c->x0 + (c->x1 - c->x0) * (double)i / (double)c->nx;
}
static double gy(const contour_ctx *c, int j) {
    return j == c->ny ? c->y1 : c->y0 + (c->y1 - c->y0) * (double)j / (double)c->ny;
}
static double corner(const contour_ctx *c, int i, int j) {
    return c->val[(size_t)j * (size_t)(c->nx + 1) + (size_t)i];
}
static size_t hedge(const contour_ctx *c, int i, int j) { /* (i,j)-(i+1,j) */
    return (size_t)j * (size_t)c->nx + (size_t)i;
}
static size_t vedge(const contour_ctx *c, int i, int j) { /* (i,j)-(i,j+1) */
    return c->nh + (size_t)j * (size_t)(c->nx + 1) + (size_t)i;
}

/* Finds the crossing on the segment a→b (values fa, fb of opposite inside-ness) by Illinois
 * regula falsi, stopping at |f|/|∇f| <= tol/4 or a bracket narrower than tol/8. */
static cj_status refine_edge(contour_ctx *c, const double a[2], const double b[2], double fa,
                             double fb, double *out, double *res) {
    const double len = hypot(b[0] - a[0], b[1] - a[1]);
    double s0 = 0.0, s1 = 1.0, f0 = fa, f1 = fb;
    int side = 0;
    double best[2] = {a[0], a[1]}, bres = INFINITY;
    for (int it = 0; it < EDGE_ITERS; ++it) {
        double s = (f1 - f0) != 0.0 ? s0 - f0 * (s1 - s0) / (f1 - f0) : 0.5 * (s0 + s1);
        if (!(s > s0 && s < s1)) s = 0.5 * (s0 + s1);
        const double p[2] = {a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])};
        double v, g[2];
        cj_status st = cj_implicit_curve_eval(c->f, p[0], p[1], &v, g);
        if (st) return st;
        const double r = residual_of(v, g);
        best[0] = p[0];
        best[1] = p[1];
        bres = r;
        if (r <= 0.25 * c->tol || v == 0.0) break;
        if ((v < 0.0) == (f0 < 0.0)) {
            s0 = s;
            f0 = v;
            if (side == -1) f1 *= 0.5;
            side = -1;
        } else {
            s1 = s;
            f1 = v;
            if (side == 1) f0 *= 0.5;
            side = 1;
        }
        if ((s1 - s0) * len < 0.125 * c->tol) {
            /* The root is bracketed within tol/8: the vertex is that close to the curve. */
            break;
        }
        if (it + 1 == EDGE_ITERS) c->capped = 1;
    }
    out[0] = best[0];
    out[1] = best[1];
    *res = bres;
    return CJ_OK;
}

static int push_point(contour_ctx *c, const double p[2], double res) {
    if (c->emitted + c->len >= CJ_CONTOUR_MAX_POINTS) {
        c->err = cj_fail(CJ_ERR_CAP,
                         "contour: stopped at %zu vertices (the cap): tolerance %g is too fine "
                         "for this curve and box",
                         CJ_CONTOUR_MAX_POINTS, c->tol);
        return -1;
    }
    if (c->len + 1 > c->cap) {
        size_t nc = c->cap ? 2 * c->cap : 256;
        double *nb = cj_allocator_alloc(&c->alloc, nc * 2 * sizeof(double));
        if (!nb) {
            c->err = cj_fail(CJ_ERR_NOMEM, "out of memory while contouring");
            return -1;
        }
        if (c->len) memcpy(nb, c->buf, c->len * 2 * sizeof(double));
        cj_allocator_free(&c->alloc, c->buf);
        c->buf = nb;
        c->cap = nc;
    }
    c->buf[2 * c->len] = p[0];
    c->buf[2 * c->len + 1] = p[1];
    c->len++;
    if (res > c->poly_res) c->poly_res = res;
    return 0;
}

/* Appends the points strictly between a and b needed for the chord to stay within tol. */
static int refine_chord(contour_ctx *c, const double a[2], const double b[2], int depth) {
    const double chord = hypot(b[0] - a[0], b[1] - a[1]);
    if (chord <= c->tol) return 0;
    double m[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
    const double m0[2] = {m[0], m[1]};
    double res;
    cj_status st = cj_implicit_curve_project(c->f, m, 0.0625 * c->tol, &res);
    if (st == CJ_ERR_NONFINITE) {
        c->err = st;
        return -1;
    }
    const double moved = hypot(m[0] - m0[0], m[1] - m0[1]);
    if (st != CJ_OK || moved > chord) {
        /* Could not project (singular point, far jump): keep the chord, report the cap. */
        c->capped = 1;
        return 0;
    }
    if (moved <= 0.5 * c->tol) return 0;
    if (depth >= CHORD_DEPTH) {
        c->capped = 1;
        return 0;
    }
    if (refine_chord(c, a, m, depth + 1)) return -1;
    if (push_point(c, m, res)) return -1;
    return refine_chord(c, m, b, depth + 1);
}

static int append_edge(contour_ctx *c, size_t e, int first) {
    const double *p = c->exy + 2 * e;
    if (!first) {
        const double *prev = c->buf + 2 * (c->len - 1);
        double a[2] = {prev[0], prev[1]};
        if (refine_chord(c, a, p, 0)) return -1;
    }
    return push_point(c, p, c->eres[e]);
}

static cj_status emit_chain(contour_ctx *c, size_t start, cj_polyline_fn emit, void *user,
                            cj_contour_stats *stats) {
    c->len = 0;
    c->poly_res = 0.0;
    size_t cur = start;
    if (append_edge(c, cur, 1)) return c->err;
    c->visited[cur] = 1;
    int closed = 0;
    for (;;) {
        const int *l = c->link + 2 * cur;
        long next = -1;
        for (int k = 0; k < 2; ++k)
            if (l[k] >= 0 && !c->visited[l[k]]) {
                next = l[k];
                break;
            }
        if (next < 0) {
            const int *ls = c->link + 2 * start;
            if (ls[1] >= 0 && cur != start && (l[0] == (int)start || l[1] == (int)start))
                closed = 1;
            break;
        }
        cur = (size_t)next;
        if (append_edge(c, cur, 0)) return c->err;
        c->visited[cur] = 1;
    }
    if (closed) {
        if (append_edge(c, start, 0)) return c->err; /* bit-identical copy of the first */
    }
    if (c->len < 2) return CJ_OK; /* a lone crossing (touching the box corner): nothing to draw */
    stats->polylines++;
    stats->closed += (size_t)closed;
    stats->points += c->len;
    c->emitted += c->len;
    if (c->poly_res > stats->max_residual) stats->max_residual = c->poly_res;
    return emit(user, c->buf, c->len, closed, c->poly_res);
}

static void add_link(contour_ctx *c, size_t a, size_t b) {
    int *la = c->link + 2 * a, *lb = c->link + 2 * b;
    if (la[0] < 0)
        la[0] = (int)b;
    else
        la[1] = (int)b;
    if (lb[0] < 0)
        lb[0] = (int)a;
    else
        lb[1] = (int)a;
}

cj_status cj_implicit_contour(const cj_implicit *f, const double box[4],
                              const cj_contour_options *opts, cj_polyline_fn emit, void *user,
                              cj_contour_stats *stats) {
    assert(f != NULL && f->f != NULL && box != NULL && opts != NULL && emit != NULL);
    cj_status st = cj_check_finite(box, 4, "box coordinate");
    if (st) return st;
    if (!(box[0] < box[2]) || !(box[1] < box[3]))
        return cj_fail(CJ_ERR_DEGENERATE,
                       "box [%g, %g] x [%g, %g] is empty: need x0 < x1 and y0 < y1", box[0], box[2],
                       box[1], box[3]);
    if (!isfinite(opts->tol)) return cj_fail(CJ_ERR_NONFINITE, "contour tolerance is not finite");
    if (!(opts->tol > 0.0))
        return cj_fail(CJ_ERR_ARGUMENT, "contour tolerance %g must be positive", opts->tol);
    const int nx = opts->nx ? opts->nx : 64, ny = opts->ny ? opts->ny : 64;
    if (nx < 1 || nx > 4096 || ny < 1 || ny > 4096)
        return cj_fail(CJ_ERR_ARGUMENT, "contour grid %d x %d is outside 1..4096 cells", nx, ny);
    if (!isfinite(box[2] - box[0]) || !isfinite(box[3] - box[1]))
        return cj_fail(CJ_ERR_RANGE,
                       "box [%g, %g] x [%g, %g] is wider than the double range (its sides "
                       "overflow)",
                       box[0], box[2], box[1], box[3]);
    /* Below this, vertices cannot be placed within tol in doubles, and chord refinement would
     * only multiply points: refuse before any work (tessellation does the same). */
    double scale = fmax(fmax(fabs(box[0]), fabs(box[1])), fmax(fabs(box[2]), fabs(box[3])));
    scale = fmax(scale, fmax(box[2] - box[0], box[3] - box[1]));
    const double min_tol = CJ_CONTOUR_MIN_REL_TOL * scale;
    if (opts->tol < min_tol)
        return cj_fail(CJ_ERR_RANGE,
                       "contour tolerance %g is finer than doubles resolve in a box of scale %g "
                       "(the smallest accepted is %.3g)",
                       opts->tol, scale, min_tol);

    contour_ctx c;
    memset(&c, 0, sizeof c);
    c.f = f;
    c.tol = opts->tol;
    c.nx = nx;
    c.ny = ny;
    c.x0 = box[0];
    c.y0 = box[1];
    c.x1 = box[2];
    c.y1 = box[3];
    const size_t ncorner = (size_t)(nx + 1) * (size_t)(ny + 1);
    c.nh = (size_t)nx * (size_t)(ny + 1);
    c.ne = c.nh + (size_t)(nx + 1) * (size_t)ny;
    c.alloc = cj_allocator_resolve(opts->alloc);
    c.val = cj_allocator_alloc(&c.alloc, ncorner * sizeof(double));
    c.exy = cj_allocator_alloc(&c.alloc, c.ne * 2 * sizeof(double));
    c.eres = cj_allocator_alloc(&c.alloc, c.ne * sizeof(double));
    c.link = cj_allocator_alloc(&c.alloc, c.ne * 2 * sizeof(int));
    c.visited = cj_allocator_alloc(&c.alloc, c.ne);
    cj_contour_stats local = {0, 0, 0, 0.0};
    if (!c.val || !c.exy || !c.eres || !c.link || !c.visited) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory for a %d x %d contour grid", nx, ny);
        goto done;
    }
    for (size_t e = 0; e < 2 * c.ne; ++e) c.link[e] = -1;
    memset(c.visited, 0, c.ne);

    /* 1. grid values */
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            double v;
            if ((st = cj_implicit_curve_eval(f, gx(&c, i), gy(&c, j), &v, NULL))) goto done;
            c.val[(size_t)j * (size_t)(nx + 1) + (size_t)i] = v;
        }
    /* 2. crossings on sign-changing edges, each computed once */
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const double a[2] = {gx(&c, i), gy(&c, j)};
            const double fa = corner(&c, i, j);
            if (i < nx && (fa < 0.0) != (corner(&c, i + 1, j) < 0.0)) {
                const double b[2] = {gx(&c, i + 1), a[1]};
                size_t e = hedge(&c, i, j);
                if ((st = refine_edge(&c, a, b, fa, corner(&c, i + 1, j), c.exy + 2 * e,
                                      c.eres + e)))
                    goto done;
            }
            if (j < ny && (fa < 0.0) != (corner(&c, i, j + 1) < 0.0)) {
                const double b[2] = {a[0], gy(&c, j + 1)};
                size_t e = vedge(&c, i, j);
                if ((st = refine_edge(&c, a, b, fa, corner(&c, i, j + 1), c.exy + 2 * e,
                                      c.eres + e)))
                    goto done;
            }
        }
    /* 3. marching squares: link the crossings of each cell */
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int bl = corner(&c, i, j) < 0.0, br = corner(&c, i + 1, j) < 0.0;
            const int tr = corner(&c, i + 1, j + 1) < 0.0, tl = corner(&c, i, j + 1) < 0.0;
            const size_t eb = hedge(&c, i, j), er = vedge(&c, i + 1, j);
            const size_t et = hedge(&c, i, j + 1), el = vedge(&c, i, j);
            size_t cross[4];
            int n = 0;
            if (bl != br) cross[n++] = eb;
            if (br != tr) cross[n++] = er;
            if (tr != tl) cross[n++] = et;
            if (tl != bl) cross[n++] = el;
            if (n == 2) {
                add_link(&c, cross[0], cross[1]);
            } else if (n == 4) {
                /* Saddle: the corners sharing the centre's state are joined through the
                 * centre; the curve cuts off the other two corners. */
                double fc;
                if ((st = cj_implicit_curve_eval(f, 0.5 * (gx(&c, i) + gx(&c, i + 1)),
                                                 0.5 * (gy(&c, j) + gy(&c, j + 1)), &fc, NULL)))
                    goto done;
                const int centre = fc < 0.0;
                if (centre == bl) { /* bl–tr joined: cut br (bottom,right) and tl (top,left) */
                    add_link(&c, eb, er);
                    add_link(&c, et, el);
                } else { /* br–tl joined: cut bl (bottom,left) and tr (right,top) */
                    add_link(&c, eb, el);
                    add_link(&c, er, et);
                }
            }
        }
    /* 4. chains: open ones start at an edge with a single link (on the box boundary) */
    for (int pass = 0; pass < 2; ++pass)
        for (size_t e = 0; e < c.ne; ++e) {
            if (c.visited[e] || c.link[2 * e] < 0) continue;
            const int single = c.link[2 * e + 1] < 0;
            if (pass == 0 && !single) continue;
            if ((st = emit_chain(&c, e, emit, user, &local))) goto done;
        }
    if (c.capped)
        st = cj_fail(CJ_ERR_CAP,
                     "contour: some vertices or chords could not be refined to tol %g "
                     "(largest residual %g)",
                     c.tol, local.max_residual);
done:
    if (stats && (st == CJ_OK || st == CJ_ERR_CAP)) *stats = local;
    cj_allocator_free(&c.alloc, c.val);
    cj_allocator_free(&c.alloc, c.exy);
    cj_allocator_free(&c.alloc, c.eres);
    cj_allocator_free(&c.alloc, c.link);
    cj_allocator_free(&c.alloc, c.visited);
    cj_allocator_free(&c.alloc, c.buf);
    return st;
}
