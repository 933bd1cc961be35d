/* Plane primitives of seed chapter 2. See casteljau/primitives.h. */
#include "casteljau/primitives.h"
#include "error_internal.h"
#include "eft_internal.h"

#include <assert.h>
#include <math.h>

#define CJ_PI 3.14159265358979323846
#define U     0x1p-53

static cj_status finite_vec(cj_vec2 v, const char *what) {
    if (!isfinite(v.x) || !isfinite(v.y))
        return cj_fail(CJ_ERR_NONFINITE, "%s is not finite", what);
    return CJ_OK;
}

/* ---- exact orientation ------------------------------------------------------------------- */

/* Sign of (b − a) × (c − a): floating-point filter, then the exact sum of the six products
 * bx cy − bx ay − ax cy − by cx + by ax + ay cx as a nonoverlapping expansion. */
static int orient(cj_vec2 a, cj_vec2 b, cj_vec2 c) {
    const double l = (b.x - a.x) * (c.y - a.y), r = (b.y - a.y) * (c.x - a.x);
    const double det = l - r, bound = 3.3306690738754716e-16 * (fabs(l) + fabs(r));
    if (det > bound) return 1;
    if (-det > bound) return -1;
    const double f[6][2] = {{b.x, c.y},  {-b.x, a.y}, {-a.x, c.y},
                            {-b.y, c.x}, {b.y, a.x},  {a.y, c.x}};
    double e[32];
    int ne = 0;
    for (int k = 0; k < 6; ++k) {
        const double p = f[k][0] * f[k][1], q = fma(f[k][0], f[k][1], -p);
        const double terms[2] = {q, p};
        for (int t = 0; t < 2; ++t) {
            double Q = terms[t];
            int m = 0;
            for (int i = 0; i < ne; ++i) {
                double s, err;
                cj_two_sum(Q, e[i], &s, &err);
                Q = s;
                if (err != 0.0) e[m++] = err;
            }
            if (Q != 0.0) e[m++] = Q;
            ne = m;
        }
    }
    /* Components grow in magnitude: the last nonzero one carries the sign. */
    for (int i = ne - 1; i >= 0; --i)
        if (e[i] != 0.0) return e[i] > 0.0 ? 1 : -1;
    return 0;
}

static int on_segment_collinear(cj_vec2 p, cj_vec2 q, cj_vec2 r) { /* r on pq, all collinear */
    return fmin(p.x, q.x) <= r.x && r.x <= fmax(p.x, q.x) && fmin(p.y, q.y) <= r.y &&
           r.y <= fmax(p.y, q.y);
}

static int segments_touch(cj_vec2 p1, cj_vec2 p2, cj_vec2 p3, cj_vec2 p4) {
    const int o1 = orient(p1, p2, p3), o2 = orient(p1, p2, p4);
    const int o3 = orient(p3, p4, p1), o4 = orient(p3, p4, p2);
    if (o1 * o2 < 0 && o3 * o4 < 0) return 1;
    if (o1 == 0 && on_segment_collinear(p1, p2, p3)) return 1;
    if (o2 == 0 && on_segment_collinear(p1, p2, p4)) return 1;
    if (o3 == 0 && on_segment_collinear(p3, p4, p1)) return 1;
    if (o4 == 0 && on_segment_collinear(p3, p4, p2)) return 1;
    return 0;
}

/* ---- lines ------------------------------------------------------------------------------- */

cj_status cj_line2_from_points(cj_vec2 p, cj_vec2 q, cj_line2 *out) {
    assert(out != NULL);
    cj_status st;
    if ((st = finite_vec(p, "line point p")) || (st = finite_vec(q, "line point q"))) return st;
    if (p.x == q.x && p.y == q.y)
        return cj_fail(CJ_ERR_DEGENERATE, "line through two coincident points (%g, %g)", p.x, p.y);
    out->p = p;
    out->d = cj_v2_sub(q, p);
    return CJ_OK;
}

cj_vec2 cj_line2_point(const cj_line2 *l, double s) {
    return cj_v2(l->p.x + s * l->d.x, l->p.y + s * l->d.y);
}

static cj_status check_line(const cj_line2 *l) {
    cj_status st;
    if ((st = finite_vec(l->p, "line point")) || (st = finite_vec(l->d, "line direction")))
        return st;
    if (l->d.x == 0.0 && l->d.y == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "line direction is the zero vector");
    return CJ_OK;
}

static cj_status check_iline(const cj_iline2 *m) {
    if (!isfinite(m->a) || !isfinite(m->b) || !isfinite(m->c))
        return cj_fail(CJ_ERR_NONFINITE, "implicit line coefficient is not finite");
    if (m->a == 0.0 && m->b == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "implicit line has a = b = 0");
    return CJ_OK;
}

cj_status cj_line2_to_implicit(const cj_line2 *l, cj_iline2 *out) {
    assert(l && out);
    cj_status st = check_line(l);
    if (st) return st;
    const double len = cj_v2_norm(l->d);
    const cj_vec2 n = cj_v2(-l->d.y / len, l->d.x / len);
    out->a = n.x;
    out->b = n.y;
    out->c = -(n.x * l->p.x + n.y * l->p.y);
    return CJ_OK;
}

cj_status cj_iline2_to_param(const cj_iline2 *m, cj_line2 *out) {
    assert(m && out);
    cj_status st = check_iline(m);
    if (st) return st;
    const double nn = m->a * m->a + m->b * m->b;
    out->p = cj_v2(-m->c * m->a / nn, -m->c * m->b / nn);
    out->d = cj_v2(m->b, -m->a);
    return CJ_OK;
}

cj_status cj_iline2_distance(const cj_iline2 *m, cj_vec2 q, double *dist) {
    assert(m && dist);
    cj_status st = check_iline(m);
    if (st || (st = finite_vec(q, "query point"))) return st;
    *dist = (m->a * q.x + m->b * q.y + m->c) / hypot(m->a, m->b);
    return CJ_OK;
}

cj_status cj_line2_intersect_implicit(const cj_line2 *l, cj_line_extent extent, const cj_iline2 *m,
                                      cj_intersection *kind, double *s, cj_vec2 *point) {
    assert(l && m && kind);
    cj_status st = check_line(l);
    if (st || (st = check_iline(m))) return st;
    if ((unsigned)extent > (unsigned)CJ_EXTENT_SEGMENT)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown line extent %d", (int)extent);
    const double nab = hypot(m->a, m->b);
    const double den = m->a * l->d.x + m->b * l->d.y;
    const double num = -(m->a * l->p.x + m->b * l->p.y + m->c);
    if (fabs(den) <= 8.0 * U * nab * cj_v2_norm(l->d)) {
        const double scale = fabs(m->a * l->p.x) + fabs(m->b * l->p.y) + fabs(m->c);
        *kind = fabs(num) <= 8.0 * U * scale ? CJ_ISECT_COINCIDENT : CJ_ISECT_NONE;
        return CJ_OK;
    }
    const double sv = num / den;
    if (s) *s = sv;
    int inside = 1;
    if (extent == CJ_EXTENT_RAY) inside = sv >= 0.0;
    if (extent == CJ_EXTENT_SEGMENT) inside = sv >= 0.0 && sv <= 1.0;
    *kind = inside ? CJ_ISECT_POINT : CJ_ISECT_NONE;
    if (inside && point) *point = cj_line2_point(l, sv);
    return CJ_OK;
}

cj_status cj_perpendicular_bisector(cj_vec2 p, cj_vec2 q, cj_line2 *out, cj_iline2 *implicit) {
    assert(out != NULL);
    cj_status st;
    if ((st = finite_vec(p, "point p")) || (st = finite_vec(q, "point q"))) return st;
    if (p.x == q.x && p.y == q.y)
        return cj_fail(CJ_ERR_DEGENERATE, "perpendicular bisector of coincident points (%g, %g)",
                       p.x, p.y);
    const cj_vec2 d = cj_v2_sub(q, p);
    out->p = cj_v2(0.5 * (p.x + q.x), 0.5 * (p.y + q.y));
    out->d = cj_v2_perp(d);
    if (implicit) {
        implicit->a = d.x;
        implicit->b = d.y;
        implicit->c = -0.5 * ((q.x * q.x + q.y * q.y) - (p.x * p.x + p.y * p.y));
    }
    return CJ_OK;
}

/* ---- circles and ellipses ---------------------------------------------------------------- */

cj_status cj_circle_check(const cj_circle *c) {
    assert(c != NULL);
    cj_status st = finite_vec(c->center, "circle centre");
    if (st) return st;
    if (!isfinite(c->r)) return cj_fail(CJ_ERR_NONFINITE, "circle radius is not finite");
    if (!(c->r > 0.0)) return cj_fail(CJ_ERR_DEGENERATE, "circle radius %g is not positive", c->r);
    return CJ_OK;
}

cj_status cj_ellipse_check(const cj_ellipse *e) {
    assert(e != NULL);
    cj_status st = finite_vec(e->center, "ellipse centre");
    if (st) return st;
    if (!isfinite(e->rx) || !isfinite(e->ry) || !isfinite(e->rot))
        return cj_fail(CJ_ERR_NONFINITE, "ellipse radius or rotation is not finite");
    if (!(e->rx > 0.0) || !(e->ry > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "ellipse radii must be positive (rx = %g, ry = %g)",
                       e->rx, e->ry);
    return CJ_OK;
}

cj_status cj_circle_eval(const cj_circle *c, double theta, cj_vec2 *point, cj_vec2 *deriv) {
    cj_status st = cj_circle_check(c);
    if (st) return st;
    if (!isfinite(theta)) return cj_fail(CJ_ERR_NONFINITE, "angle theta is not finite");
    const double co = cos(theta), si = sin(theta);
    if (point) *point = cj_v2(c->center.x + c->r * co, c->center.y + c->r * si);
    if (deriv) *deriv = cj_v2(-c->r * si, c->r * co);
    return CJ_OK;
}

cj_status cj_ellipse_eval(const cj_ellipse *e, double theta, cj_vec2 *point, cj_vec2 *deriv) {
    cj_status st = cj_ellipse_check(e);
    if (st) return st;
    if (!isfinite(theta)) return cj_fail(CJ_ERR_NONFINITE, "angle theta is not finite");
    const double co = cos(theta), si = sin(theta), cr = cos(e->rot), sr = sin(e->rot);
    if (point) {
        const double u = e->rx * co, v = e->ry * si;
        *point = cj_v2(e->center.x + cr * u - sr * v, e->center.y + sr * u + cr * v);
    }
    if (deriv) {
        const double u = -e->rx * si, v = e->ry * co;
        *deriv = cj_v2(cr * u - sr * v, sr * u + cr * v);
    }
    return CJ_OK;
}

cj_status cj_circle_implicit(const cj_circle *c, cj_vec2 q, double *f, cj_vec2 *grad) {
    cj_status st = cj_circle_check(c);
    if (st || (st = finite_vec(q, "query point"))) return st;
    const double dx = q.x - c->center.x, dy = q.y - c->center.y;
    if (f) *f = dx * dx + dy * dy - c->r * c->r;
    if (grad) *grad = cj_v2(2.0 * dx, 2.0 * dy);
    return CJ_OK;
}

cj_status cj_ellipse_implicit(const cj_ellipse *e, cj_vec2 q, double *f, cj_vec2 *grad) {
    cj_status st = cj_ellipse_check(e);
    if (st || (st = finite_vec(q, "query point"))) return st;
    const double cr = cos(e->rot), sr = sin(e->rot);
    const double dx = q.x - e->center.x, dy = q.y - e->center.y;
    const double u = cr * dx + sr * dy, v = -sr * dx + cr * dy;
    const double a = u / e->rx, b = v / e->ry;
    if (f) *f = a * a + b * b - 1.0;
    if (grad) {
        const double gu = 2.0 * u / (e->rx * e->rx), gv = 2.0 * v / (e->ry * e->ry);
        *grad = cj_v2(cr * gu - sr * gv, sr * gu + cr * gv);
    }
    return CJ_OK;
}

cj_status cj_ellipse_frame(const cj_ellipse *e, double theta, cj_vec2 *tangent, cj_vec2 *normal) {
    cj_vec2 p, d, g;
    cj_status st = cj_ellipse_eval(e, theta, &p, &d);
    if (st || (st = cj_ellipse_implicit(e, p, NULL, &g))) return st;
    if (tangent) *tangent = cj_v2_scale(d, 1.0 / cj_v2_norm(d));
    if (normal) *normal = cj_v2_scale(g, 1.0 / cj_v2_norm(g));
    return CJ_OK;
}

/* ---- polygons ---------------------------------------------------------------------------- */

cj_status cj_regular_ngon(cj_vec2 center, double radius, int n, double phase, cj_vec2 *out) {
    assert(out != NULL);
    cj_status st = finite_vec(center, "n-gon centre");
    if (st) return st;
    if (!isfinite(radius) || !isfinite(phase))
        return cj_fail(CJ_ERR_NONFINITE, "n-gon radius or phase is not finite");
    if (n < 3) return cj_fail(CJ_ERR_DEGENERATE, "a regular n-gon needs n >= 3, got %d", n);
    if (!(radius > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "n-gon radius %g is not positive", radius);
    for (int k = 0; k < n; ++k) {
        const double a = phase + 2.0 * CJ_PI * (double)k / (double)n;
        out[k] = cj_v2(center.x + radius * cos(a), center.y + radius * sin(a));
    }
    return CJ_OK;
}

static cj_status check_polygon(const cj_vec2 *v, size_t n) {
    if (n < 3) return cj_fail(CJ_ERR_EMPTY, "a polygon needs at least 3 vertices, got %zu", n);
    assert(v != NULL);
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i].x) || !isfinite(v[i].y))
            return cj_fail(CJ_ERR_NONFINITE, "polygon vertex %zu is not finite", i);
    return CJ_OK;
}

cj_status cj_polygon_area(const cj_vec2 *v, size_t n, double *area) {
    assert(area != NULL);
    cj_status st = check_polygon(v, n);
    if (st) return st;
    /* Relative to v[0] to limit cancellation. */
    double s = 0.0;
    for (size_t i = 1; i + 1 < n; ++i)
        s += cj_v2_cross(cj_v2_sub(v[i], v[0]), cj_v2_sub(v[i + 1], v[0]));
    *area = 0.5 * s;
    return CJ_OK;
}

static int simple_polygon(const cj_vec2 *v, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        const cj_vec2 a = v[i], b = v[(i + 1) % n], c = v[(i + 2) % n];
        if (a.x == b.x && a.y == b.y) return 0; /* zero-length edge */
        /* adjacent edges ab, bc: a fold back along the same line overlaps */
        if (orient(a, b, c) == 0 && cj_v2_dot(cj_v2_sub(b, a), cj_v2_sub(c, b)) < 0.0) return 0;
    }
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue; /* adjacent through the closing edge */
            if (segments_touch(v[i], v[i + 1], v[j], v[(j + 1) % n])) return 0;
        }
    return 1;
}

cj_status cj_polygon_is_simple(const cj_vec2 *v, size_t n, int *simple) {
    assert(simple != NULL);
    cj_status st = check_polygon(v, n);
    if (st) return st;
    *simple = simple_polygon(v, n);
    return CJ_OK;
}

cj_status cj_polygon_is_convex(const cj_vec2 *v, size_t n, int *convex, int *orientation) {
    assert(convex != NULL);
    cj_status st = check_polygon(v, n);
    if (st) return st;
    int sign = 0, ok = 1;
    for (size_t i = 0; i < n && ok; ++i) {
        const int o = orient(v[i], v[(i + 1) % n], v[(i + 2) % n]);
        if (o == 0) continue;
        if (sign == 0)
            sign = o;
        else if (o != sign)
            ok = 0;
    }
    if (sign == 0) ok = 0; /* all collinear */
    if (ok) ok = simple_polygon(v, n);
    *convex = ok;
    if (orientation) *orientation = ok ? sign : 0;
    return CJ_OK;
}

cj_status cj_polygon_contains(const cj_vec2 *v, size_t n, cj_vec2 q, int *inside) {
    assert(inside != NULL);
    cj_status st = check_polygon(v, n);
    if (st || (st = finite_vec(q, "query point"))) return st;
    int in = 0;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        const cj_vec2 a = v[j], b = v[i];
        if (orient(a, b, q) == 0 && on_segment_collinear(a, b, q)) {
            *inside = 1;
            return CJ_OK;
        }
        /* Half-open rule on y; the side test is exact. */
        if ((a.y > q.y) != (b.y > q.y)) {
            const int o = orient(a, b, q);
            if ((b.y > a.y) ? o > 0 : o < 0) in = !in;
        }
    }
    *inside = in;
    return CJ_OK;
}
