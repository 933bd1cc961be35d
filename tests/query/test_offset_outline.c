/* Outlines of strokes (cj_offset_outline: end caps, closed curves) and offsets of curves with a
 * cusp (cj_offset_curve completing the cusp by an arc), against a long-double oracle independent
 * of the library: the exact offsets c(t) +- w N(t) (distance to them refined by golden section on
 * t), the exact caps (segment, half circle, half square) and the exact arcs about the cusp or the
 * seam. Checked both ways: every sample of every piece within the proven deviation of the exact
 * outline, every sample of the exact outline within it of the pieces. Structure: each loop closes
 * bit for bit, consecutive pieces share their end points, newline marks the loops. Bad input
 * refused. */
#include "casteljau/offset.h"
#include "check.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef long double ld;
#define PI 3.14159265358979323846L

typedef struct curve {
    int n;
    const double *P;
} curve;

/* c, c' in long double (de Casteljau on the points and on the hodograph). */
static void ceval(const curve *c, ld t, ld p[2], ld d[2]) {
    ld w[16][2] = {{0}};
    d[0] = d[1] = 0;
    for (int i = 0; i <= c->n; ++i) w[i][0] = c->P[2 * i], w[i][1] = c->P[2 * i + 1];
    for (int r = c->n; r > 0; --r) {
        if (r == 1)
            for (int k = 0; k < 2; ++k) d[k] = c->n * (w[1][k] - w[0][k]);
        for (int i = 0; i < r; ++i)
            for (int k = 0; k < 2; ++k) w[i][k] = (1 - t) * w[i][k] + t * w[i + 1][k];
    }
    p[0] = w[0][0], p[1] = w[0][1];
}

static void oeval(const curve *c, ld s, ld t, ld o[2]) {
    ld p[2] = {0, 0}, d[2] = {0, 0};
    ceval(c, t, p, d);
    ld l = sqrtl(d[0] * d[0] + d[1] * d[1]);
    if (!(l > 0)) l = 1e-300L;
    o[0] = p[0] - s * d[1] / l;
    o[1] = p[1] + s * d[0] / l;
}

/* Distance from x to the exact offset at s (t in [0,1]): 4000 samples, golden section around the
 * best. */
static double dist_offset(const curve *c, double s, const double x[2]) {
    int best = 0;
    ld bd = INFINITY, o[2];
    for (int i = 0; i <= 4000; ++i) {
        oeval(c, s, i / 4000.0L, o);
        ld dd = hypotl(o[0] - x[0], o[1] - x[1]);
        if (dd < bd) bd = dd, best = i;
    }
    ld a = fmaxl(0, (best - 1) / 4000.0L), b = fminl(1, (best + 1) / 4000.0L);
    for (int it = 0; it < 80; ++it) {
        ld m1 = a + (b - a) * 0.381966L, m2 = b - (b - a) * 0.381966L, o1[2], o2[2];
        oeval(c, s, m1, o1);
        oeval(c, s, m2, o2);
        ld d1 = hypotl(o1[0] - x[0], o1[1] - x[1]), d2 = hypotl(o2[0] - x[0], o2[1] - x[1]);
        bd = fminl(bd, fminl(d1, d2));
        if (d1 < d2)
            b = m2;
        else
            a = m1;
    }
    return (double)bd;
}

static double dist_seg(const double a[2], const double b[2], const double x[2]) {
    double ab[2] = {b[0] - a[0], b[1] - a[1]}, l2 = ab[0] * ab[0] + ab[1] * ab[1];
    double t = l2 > 0 ? ((x[0] - a[0]) * ab[0] + (x[1] - a[1]) * ab[1]) / l2 : 0;
    t = fmin(1, fmax(0, t));
    return hypot(a[0] + t * ab[0] - x[0], a[1] + t * ab[1] - x[1]);
}

/* Distance to the arc of radius r about C between angles a0 and a0 + sweep. */
static double dist_arc(const double C[2], double r, double a0, double sweep, const double x[2]) {
    double ang = atan2(x[1] - C[1], x[0] - C[0]), rel = ang - a0;
    while (sweep >= 0 ? rel < 0 : rel > 0) rel += sweep >= 0 ? 2 * PI : -2 * PI;
    while (sweep >= 0 ? rel > 2 * PI : rel < -2 * PI) rel -= sweep >= 0 ? 2 * PI : -2 * PI;
    if (sweep >= 0 ? rel <= sweep : rel >= sweep) return fabs(hypot(x[0] - C[0], x[1] - C[1]) - r);
    double e0[2] = {C[0] + r * cos(a0), C[1] + r * sin(a0)},
           e1[2] = {C[0] + r * cos(a0 + sweep), C[1] + r * sin(a0 + sweep)};
    return fmin(hypot(x[0] - e0[0], x[1] - e0[1]), hypot(x[0] - e1[0], x[1] - e1[1]));
}

static void bez(const double *q, double t, double x[2]) {
    double s = 1 - t;
    for (int k = 0; k < 2; ++k)
        x[k] = s * s * s * q[k] + 3 * s * s * t * q[2 + k] + 3 * s * t * t * q[4 + k] +
               t * t * t * q[6 + k];
}

static double dist_pieces(const double *pts, int np, const double x[2]) {
    double best = INFINITY;
    for (int k = 0; k < np; ++k) {
        const double *q = pts + 8 * k;
        int bs = 0;
        double bd = INFINITY, p[2];
        for (int i = 0; i <= 512; ++i) {
            bez(q, i / 512.0, p);
            double dd = hypot(p[0] - x[0], p[1] - x[1]);
            if (dd < bd) bd = dd, bs = i;
        }
        double a = fmax(0, (bs - 1) / 512.0), b = fmin(1, (bs + 1) / 512.0);
        for (int it = 0; it < 60; ++it) {
            double m1 = a + (b - a) * 0.381966, m2 = b - (b - a) * 0.381966, p1[2], p2[2];
            bez(q, m1, p1);
            bez(q, m2, p2);
            double d1 = hypot(p1[0] - x[0], p1[1] - x[1]), d2 = hypot(p2[0] - x[0], p2[1] - x[1]);
            bd = fmin(bd, fmin(d1, d2));
            if (d1 < d2)
                b = m2;
            else
                a = m1;
        }
        best = fmin(best, bd);
    }
    return best;
}

/* The exact outline as a set: the two offsets and up to 4 extra parts (segments or arcs). */
typedef struct part {
    int arc; /* 0: segment a-b; 1: arc about C */
    double a[2], b[2], C[2], r, a0, sweep;
} part;

static double dist_exact(const curve *c, double w, const part *parts, int nparts, int offsets,
                         const double x[2]) {
    double d = INFINITY;
    if (offsets & 1) d = fmin(d, dist_offset(c, w, x));
    if (offsets & 2) d = fmin(d, dist_offset(c, -w, x));
    for (int i = 0; i < nparts; ++i)
        d = fmin(d, parts[i].arc ? dist_arc(parts[i].C, parts[i].r, parts[i].a0, parts[i].sweep, x)
                                 : dist_seg(parts[i].a, parts[i].b, x));
    return d;
}

static long samples = 0;

static void check_structure(const char *what, const double *pts, const int *nl, int np, int loops) {
    int seen = 0, start = 0;
    for (int k = 0; k < np; ++k) {
        if (nl[k]) {
            ++seen;
            start = k;
        } else if (k > 0) {
            CHECK(!memcmp(pts + 8 * (k - 1) + 6, pts + 8 * k, 2 * sizeof(double)),
                  "%s: pieces %d and %d do not join", what, k - 1, k);
        }
        if (k + 1 == np || nl[k + 1])
            CHECK(!memcmp(pts + 8 * k + 6, pts + 8 * start, 2 * sizeof(double)),
                  "%s: the loop from piece %d does not close", what, start);
    }
    CHECK(nl[0] == 1 && seen == loops, "%s: %d loops, want %d", what, seen, loops);
}

/* Both directions against the exact set; pieces that pass through `skip` (the pivot of a
 * concave seam, inside the stroke) are not part of the outline. */
static void check_both(const char *what, const curve *c, double w, const double *pts, int np,
                       double dev, const part *parts, int nparts, int offsets, const double *skip) {
    double worst_out = 0, worst_in = 0;
    for (int k = 0; k < np; ++k) {
        const double *q = pts + 8 * k;
        if (skip && ((q[0] == skip[0] && q[1] == skip[1]) || (q[6] == skip[0] && q[7] == skip[1])))
            continue;
        for (int i = 0; i <= 6; ++i) {
            double x[2];
            bez(q, i / 6.0, x);
            worst_out = fmax(worst_out, dist_exact(c, w, parts, nparts, offsets, x));
            ++samples;
        }
    }
    for (int side = 0; side < 2; ++side) {
        if (!(offsets & (1 << side))) continue;
        for (int i = 0; i <= 400; ++i) {
            ld o[2], p[2], dd[2];
            ceval(c, i / 400.0L, p, dd);
            if (hypotl(dd[0], dd[1]) < 1e-9L) continue; /* the cusp itself: N undefined */
            oeval(c, side ? -w : w, i / 400.0L, o);
            double x[2] = {(double)o[0], (double)o[1]};
            double di = dist_pieces(pts, np, x);
            worst_in = fmax(worst_in, di);
            ++samples;
        }
    }
    CHECK(worst_out <= dev && worst_in <= dev,
          "%s: pieces -> exact %g, exact -> pieces %g, proven deviation %g", what, worst_out,
          worst_in, dev);
    printf("%s: %d pieces, deviation %.3g; measured pieces -> exact %.3g, exact -> pieces %.3g\n",
           what, np, dev, worst_out, worst_in);
}

enum { CAP = 4096 };
static double buf[8 * CAP];
static int nl[CAP];

static void check_open(void) {
    static const double P[] = {0, 0, 1, 2, 2, -1, 3, 1};
    curve c = {3, P};
    cj_bezier2 b = cj_bezier2_view(3, P, NULL);
    const double w = 0.3, tol = 1e-4;
    const char *names[3] = {"butt", "round", "square"};
    for (int cap = 0; cap < 3; ++cap) {
        int np = 0, cusps = 0;
        double dev = 0;
        cj_status st =
            cj_offset_outline(&b, w, tol, (cj_offset_cap)cap, buf, nl, CAP, &np, &dev, &cusps);
        CHECK(st == CJ_OK, "open %s: %s", names[cap], cj_last_error());
        if (st) continue;
        char what[64];
        snprintf(what, sizeof what, "open cubic, w 0.3, %s caps", names[cap]);
        check_structure(what, buf, nl, np, 1);
        CHECK(dev <= tol, "%s: deviation %g", what, dev);
        /* the exact caps: ends E, normals N = (-T_y, T_x) */
        double T1[2] = {3 - 2, 1 + 1}, T0[2] = {1, 2}, l1 = hypot(T1[0], T1[1]),
               l0 = hypot(T0[0], T0[1]);
        T1[0] /= l1, T1[1] /= l1, T0[0] /= l0, T0[1] /= l0;
        double E[2] = {3, 1}, S[2] = {0, 0};
        part parts[8];
        int n = 0;
        for (int end = 0; end < 2; ++end) {
            const double *X = end ? E : S;
            double T[2] = {end ? T1[0] : -T0[0], end ? T1[1] : -T0[1]};
            double N[2] = {-T[1], T[0]};
            double A[2] = {X[0] + w * N[0], X[1] + w * N[1]},
                   B[2] = {X[0] - w * N[0], X[1] - w * N[1]};
            if (cap == 0) {
                parts[n++] = (part){0, {A[0], A[1]}, {B[0], B[1]}, {0, 0}, 0, 0, 0};
            } else if (cap == 1) {
                parts[n++] = (part){1, {0, 0}, {0, 0}, {X[0], X[1]}, w, atan2(N[1], N[0]), -PI};
            } else {
                double A2[2] = {A[0] + w * T[0], A[1] + w * T[1]},
                       B2[2] = {B[0] + w * T[0], B[1] + w * T[1]};
                parts[n++] = (part){0, {A[0], A[1]}, {A2[0], A2[1]}, {0, 0}, 0, 0, 0};
                parts[n++] = (part){0, {A2[0], A2[1]}, {B2[0], B2[1]}, {0, 0}, 0, 0, 0};
                parts[n++] = (part){0, {B2[0], B2[1]}, {B[0], B[1]}, {0, 0}, 0, 0, 0};
            }
        }
        check_both(what, &c, w, buf, np, dev, parts, n, 3, NULL);
    }
}

static void check_closed(void) {
    /* a teardrop: c(0) = c(1) = (0,0) with a corner there (the curve turns left) */
    static const double P[] = {0, 0, 3, 3, -3, 3, 0, 0};
    curve c = {3, P};
    cj_bezier2 b = cj_bezier2_view(3, P, NULL);
    const double w = 0.2, tol = 1e-4;
    int np = 0, cusps = 0;
    double dev = 0;
    cj_status st =
        cj_offset_outline(&b, w, tol, CJ_OFFSET_CAP_ROUND, buf, nl, CAP, &np, &dev, &cusps);
    CHECK(st == CJ_OK, "teardrop: %s", cj_last_error());
    if (st) return;
    check_structure("teardrop", buf, nl, np, 2);
    /* the right side (-w) is convex at the seam: the arc about (0,0) from the end normal's
     * opposite to the start normal's opposite */
    double T1[2] = {3 / sqrt(18.0), -3 / sqrt(18.0)}, T0[2] = {3 / sqrt(18.0), 3 / sqrt(18.0)};
    double a0 = atan2(-T1[0], T1[1]); /* -N(1) = (T1_y, -T1_x) */
    double a1 = atan2(-T0[0], T0[1]);
    double sweep = a1 - a0;
    while (sweep > PI) sweep -= 2 * PI;
    while (sweep < -PI) sweep += 2 * PI;
    part arc = {1, {0, 0}, {0, 0}, {0, 0}, w, a0, sweep};
    double pivot[2] = {0, 0};
    check_both("teardrop, w 0.2 (round join on the convex side, pivot on the concave)", &c, w, buf,
               np, dev, &arc, 1, 3, pivot);
}

static void check_cusp(void) {
    /* c'(1/2) = 0: a cusp at (1, 1.5) pointing up */
    static const double P[] = {0, 0, 2, 2, 0, 2, 2, 0};
    curve c = {3, P};
    cj_bezier2 b = cj_bezier2_view(3, P, NULL);
    const double tol = 1e-4;
    int through_tip = 0, through_inside = 0;
    for (int s = 0; s < 2; ++s) {
        double d = s ? -0.3 : 0.3, dev = 0;
        int np = 0, cusps = 0;
        cj_status st = cj_offset_curve(&b, d, tol, buf, NULL, CAP, &np, &dev, &cusps);
        CHECK(st == CJ_OK, "cusp, d %g: %s", d, cj_last_error());
        if (st) continue;
        for (int k = 1; k < np; ++k)
            CHECK(!memcmp(buf + 8 * (k - 1) + 6, buf + 8 * k, 2 * sizeof(double)),
                  "cusp d %g: pieces %d, %d do not join", d, k - 1, k);
        /* the completed offset: the offset and the circle of radius 0.3 about the cusp */
        part circle = {1, {0, 0}, {0, 0}, {1, 1.5}, 0.3, 0, 2 * PI};
        char what[64];
        snprintf(what, sizeof what, "cusp of a cubic, d %g (completed by an arc)", d);
        check_both(what, &c, d, buf, np, dev, &circle, 1, 1, NULL);
        double tip[2] = {1, 1.8}, inside[2] = {1, 1.2};
        through_tip += dist_pieces(buf, np, tip) <= dev;
        through_inside += dist_pieces(buf, np, inside) <= dev;
    }
    CHECK(through_tip == 1 && through_inside == 1,
          "cusp: one offset round the tip (%d), one through the inside (%d)", through_tip,
          through_inside);
}

static void check_bad(void) {
    static const double P[] = {0, 0, 1, 2, 2, -1, 3, 1};
    cj_bezier2 b = cj_bezier2_view(3, P, NULL);
    int np;
    double dev;
    CHECK(cj_offset_outline(&b, -1, 1e-4, CJ_OFFSET_CAP_BUTT, buf, nl, CAP, &np, &dev, NULL) ==
                  CJ_ERR_ARGUMENT &&
              strstr(cj_last_error(), "half-width"),
          "negative w: %s", cj_last_error());
    CHECK(cj_offset_outline(&b, 0.3, 1e-4, (cj_offset_cap)7, buf, nl, CAP, &np, &dev, NULL) ==
                  CJ_ERR_ARGUMENT &&
              strstr(cj_last_error(), "cap 7"),
          "cap 7: %s", cj_last_error());
    CHECK(cj_offset_outline(&b, 0.3, 1e-4, CJ_OFFSET_CAP_ROUND, buf, nl, 3, &np, &dev, NULL) ==
                  CJ_ERR_BUFFER &&
              np > 3,
          "small buffer: %s", cj_last_error());
    static const double Q[] = {0, 0, 0, 0, 1, 1, 2, 0}; /* c'(0) = 0 */
    cj_bezier2 e = cj_bezier2_view(3, Q, NULL);
    CHECK(cj_offset_outline(&e, 0.3, 1e-4, CJ_OFFSET_CAP_BUTT, buf, nl, CAP, &np, &dev, NULL) ==
              CJ_ERR_DEGENERATE,
          "vanishing end derivative: %s", cj_last_error());
}

int main(void) {
    check_open();
    check_closed();
    check_cusp();
    check_bad();
    printf("test_offset_outline: %ld samples checked against the exact outline (long double): %s\n",
           samples, cj_check_failures ? "FAILED" : "passed");
    return cj_check_exit();
}
