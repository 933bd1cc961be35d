/* The 2D editor's B-splines and queries, without a window: plot JSON round trip of B-spline
 * and NURBS items (through the formats/ reader and writer), knot insertion leaves the curve
 * unchanged (MPFR oracle of both control nets), local control (a moved point changes the curve
 * on its basis function's support only, bit for bit elsewhere), certified snapping (never
 * beaten by dense sampling with the oracle; the snapped point lies on the curve), intersection
 * marks on both curves, and the edits a B-spline refuses. */
#define _POSIX_C_SOURCE 200809L
#include "casteljau/viewer_model.h"
#include "oracle_bspline.h"
#include "support/check.h"
#include "support/rng.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[] = "/tmp/cj_viewer_bspline_XXXXXX";

static void write_file(const char *name, const char *text, char *path, size_t size) {
    snprintf(path, size, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(1);
    }
    fputs(text, f);
    fclose(f);
}

static const char doc_text[] =
    "{\"width\": 400, \"height\": 300, \"axes\": false, \"margin\": 0, \"view\": [0, 0, 4, 3],\n"
    " \"items\": [\n"
    "  {\"type\": \"bspline\", \"degree\": 3, \"color\": \"#1f77b4\", \"knot_markers\": false,\n"
    "   \"points\": [[0.3,0.5],[0.8,2.5],[1.6,0.4],[2.4,2.6],[3.2,0.6],[3.7,2.2],[3.9,1.0]]},\n"
    "  {\"type\": \"bspline\", \"degree\": 2, \"weights\": [1, 3, 1, 0.5],\n"
    "   \"knots\": [0, 0, 0, 0.25, 1, 1, 1],\n"
    "   \"points\": [[0.5,2.8],[2.0,1.0],[3.5,2.8],[3.8,1.5]]},\n"
    "  {\"type\": \"bezier\", \"points\": [[0.2, 1.5], [2, 3.5], [3.8, 0.2]],"
    "   \"weights\": [1, 0.6, 1]},\n"
    "  {\"type\": \"bezier\", \"points\": [[0.1, 0.1], [3.9, 2.9]]}]}\n";

/* The curve as an oracle B-spline: a Bézier (rational) curve is one with knots 0^(p+1) 1^(p+1). */
typedef struct ocurve {
    cj_obsp o;
    double knots[2 * 64];
} ocurve;

static void as_oracle(const cj_vcurve *c, ocurve *out) {
    if (c->kind == CJ_VCURVE_BSPLINE) {
        out->o = (cj_obsp){c->degree, 2, (int)c->count, c->pts, c->weights, c->knot_vector};
        return;
    }
    const int p = (int)c->count - 1;
    for (int i = 0; i <= p; ++i) out->knots[i] = 0.0, out->knots[p + 1 + i] = 1.0;
    out->o = (cj_obsp){p, 2, (int)c->count, c->pts, c->weights, out->knots};
}

/* The curve at u in MPFR (x, y): the caller's initialised values. */
static void oracle_point(const cj_obsp *o, double u, mpfr_t x, mpfr_t y) {
    mpfr_t t;
    mpfr_init2(t, 64);
    mpfr_set_d(t, u, MPFR_RNDN);
    /* an mpfr_t parameter is a pointer to its one element: as an array of one value */
    cj_obsp_eval(o, 0, t, 0, (mpfr_t *)x, NULL);
    cj_obsp_eval(o, 1, t, 0, (mpfr_t *)y, NULL);
    mpfr_clear(t);
}

/* |q - c(u)| in MPFR, rounded up to a double. */
static double oracle_distance(const cj_obsp *o, double u, const double q[2]) {
    mpfr_t x, y;
    mpfr_inits2(CJ_ORACLE_BSP_PREC, x, y, (mpfr_ptr)0);
    oracle_point(o, u, x, y);
    mpfr_sub_d(x, x, q[0], MPFR_RNDN);
    mpfr_sub_d(y, y, q[1], MPFR_RNDN);
    mpfr_sqr(x, x, MPFR_RNDN);
    mpfr_sqr(y, y, MPFR_RNDN);
    mpfr_add(x, x, y, MPFR_RNDN);
    mpfr_sqrt(x, x, MPFR_RNDU);
    const double d = mpfr_get_d(x, MPFR_RNDU);
    mpfr_clears(x, y, (mpfr_ptr)0);
    return d;
}

static void domain(const cj_obsp *o, double *a, double *b) {
    *a = o->knots[o->p];
    *b = o->knots[o->n1];
}

static cj_vdoc *load(const char *path, cj_vview *v) {
    cj_vdoc *d = NULL;
    cj_vdoc_display disp;
    if (cj_vdoc_load_json(path, &d, v, &disp)) {
        fprintf(stderr, "cannot load %s: %s\n", path, cj_last_error());
        exit(1);
    }
    return d;
}

static int same_curve(const cj_vcurve *a, const cj_vcurve *b) {
    if (a->kind != b->kind || a->count != b->count || a->degree != b->degree ||
        !a->weights != !b->weights || !a->knot_vector != !b->knot_vector)
        return 0;
    if (memcmp(a->pts, b->pts, a->count * 2 * sizeof(double))) return 0;
    if (a->weights && memcmp(a->weights, b->weights, a->count * sizeof(double))) return 0;
    const size_t nk = a->count + (size_t)a->degree + 1;
    if (a->knot_vector && memcmp(a->knot_vector, b->knot_vector, nk * sizeof(double))) return 0;
    return a->color.r == b->color.r && a->color.g == b->color.g && a->color.b == b->color.b &&
           a->width == b->width && a->knots == b->knots &&
           a->control_polygon == b->control_polygon && a->control_points == b->control_points;
}

static void test_round_trip(const char *path) {
    cj_vview v;
    cj_vdoc *d = load(path, &v);
    CHECK(cj_vdoc_curve_count(d) == 4, "%zu curves", cj_vdoc_curve_count(d));
    CHECK(cj_vdoc_curve(d, 0)->kind == CJ_VCURVE_BSPLINE && !cj_vdoc_curve(d, 0)->weights,
          "item 0 is a B-spline");
    CHECK(cj_vdoc_curve(d, 1)->kind == CJ_VCURVE_BSPLINE && cj_vdoc_curve(d, 1)->weights,
          "item 1 is a NURBS");
    CHECK(cj_vdoc_curve(d, 0)->knot_vector[4] == 0.25, "default knots clamped uniform");
    CHECK(!cj_vdoc_curve(d, 0)->knots, "knot_markers false read");
    char out[600];
    snprintf(out, sizeof out, "%s/saved.json", dir);
    const cj_vdoc_display disp = {cj_rgba_make(255, 255, 255, 255), -1, 0.5, 0, 0};
    CHECK(cj_vdoc_save_json(d, &v, &disp, out) == CJ_OK, "save: %s", cj_last_error());
    cj_vview v2;
    cj_vdoc *e = load(out, &v2);
    int same = cj_vdoc_curve_count(e) == cj_vdoc_curve_count(d);
    for (size_t i = 0; same && i < cj_vdoc_curve_count(d); ++i)
        same = same_curve(cj_vdoc_curve(d, i), cj_vdoc_curve(e, i));
    CHECK(same, "save -> load is bit-identical");
    printf("round trip: a B-spline (default knots), a NURBS, a rational and a line saved with "
           "the formats/ writer and read back with its reader: bit-identical\n");
    cj_vdoc_destroy(d);
    cj_vdoc_destroy(e);
}

/* Knot insertion: the exact curves of the old and new control nets differ by at most what
 * rounding the new points can move them (convex combinations of old points, homogeneous for a
 * NURBS): a few units in the last place of the largest coordinate, times wmax/wmin. */
static void test_knot_insertion(cj_rng *rng) {
    double worst = 0;
    int cases = 0, samples = 0;
    mpfr_t xa, ya, xb, yb;
    mpfr_inits2(CJ_ORACLE_BSP_PREC, xa, ya, xb, yb, (mpfr_ptr)0);
    for (int k = 0; k < 60; ++k) {
        const int p = cj_rng_int(rng, 1, 5), n = p + 1 + cj_rng_int(rng, 0, 6);
        const int nurbs = k % 2;
        double pts[2 * 16], w[16], knots[32];
        const double scale = ldexp(1.0, cj_rng_int(rng, -20, 20));
        double wmin = INFINITY, wmax = 0, pmax = 0;
        for (int i = 0; i < n; ++i) {
            pts[2 * i] = scale * cj_rng_range(rng, -1, 1);
            pts[2 * i + 1] = scale * cj_rng_range(rng, -1, 1);
            pmax = fmax(pmax, fmax(fabs(pts[2 * i]), fabs(pts[2 * i + 1])));
            w[i] = nurbs ? cj_rng_range(rng, 0.2, 5) : 1.0;
            wmin = fmin(wmin, w[i]), wmax = fmax(wmax, w[i]);
        }
        /* clamped, random interior knots (sorted), some repeated */
        for (int i = 0; i <= p; ++i) knots[i] = 0.0, knots[n + i] = 1.0;
        for (int i = p + 1; i < n; ++i) knots[i] = cj_rng_unit(rng);
        for (int i = p + 1; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (knots[j] < knots[i]) {
                    const double t = knots[i];
                    knots[i] = knots[j], knots[j] = t;
                }
        if (n > p + 2 && k % 3 == 0) knots[p + 2] = knots[p + 1];
        cj_vcurve c = cj_vcurve_init(CJ_VCURVE_BSPLINE, (size_t)n, pts, nurbs ? w : NULL);
        c.degree = p;
        c.knot_vector = knots;
        cj_vdoc *d = NULL;
        cj_vdoc_create(&d);
        if (cj_vdoc_add_curve(d, &c)) {
            CHECK(0, "case %d: %s", k, cj_last_error());
            cj_vdoc_destroy(d);
            continue;
        }
        const double u = k % 5 == 0 ? knots[p + 1] : cj_rng_unit(rng); /* an existing knot too */
        const cj_status st = cj_vdoc_insert_knot(d, 0, u);
        if (st) { /* a multiplicity above p is refused: the curve is untouched */
            CHECK(cj_vdoc_curve(d, 0)->count == (size_t)n, "refused insertion left the curve");
            cj_vdoc_destroy(d);
            continue;
        }
        const cj_vcurve *e = cj_vdoc_curve(d, 0);
        CHECK(e->count == (size_t)n + 1, "one more point");
        const cj_obsp before = {p, 2, n, pts, nurbs ? w : NULL, knots};
        const cj_obsp after = {p, 2, n + 1, e->pts, e->weights, e->knot_vector};
        double err = 0;
        for (int s = 0; s <= 40; ++s) {
            const double t = s == 40 ? 1.0 : cj_rng_unit(rng);
            oracle_point(&before, t, xa, ya);
            oracle_point(&after, t, xb, yb);
            mpfr_sub(xa, xa, xb, MPFR_RNDN);
            mpfr_sub(ya, ya, yb, MPFR_RNDN);
            err = fmax(err, fmax(fabs(mpfr_get_d(xa, MPFR_RNDU)), fabs(mpfr_get_d(ya, MPFR_RNDU))));
            samples++;
        }
        const double rel = err / (DBL_EPSILON * pmax * (wmax / wmin));
        CHECK(rel <= 16.0,
              "case %d (degree %d, %d points, %s, u = %.17g): the curve moved by %g "
              "= %.2f eps x max|P| x wmax/wmin",
              k, p, n, nurbs ? "NURBS" : "B-spline", u, err, rel);
        worst = fmax(worst, rel);
        CHECK(cj_vdoc_undo(d) == CJ_OK && same_curve(cj_vdoc_curve(d, 0), &c),
              "undo restores the curve bit for bit");
        cases++;
        cj_vdoc_destroy(d);
    }
    mpfr_clears(xa, ya, xb, yb, (mpfr_ptr)0);
    printf("knot insertion: %d random B-splines and NURBS (degree 1-5, scales 2^-20..2^20, "
           "repeated knots), %d parameters each compared in MPFR: the old and new curves differ "
           "by at most %.2f eps x max|P| x wmax/wmin (limit 16); undo restores bit for bit\n",
           cases, samples / (cases ? cases : 1), worst);
}

/* Local control: moving point i changes the curve only on [u_i, u_{i+p+1}]. */
static void test_local_control(const char *path, cj_rng *rng) {
    cj_vview v;
    cj_vdoc *d = load(path, &v);
    int outside = 0, inside_changed = 0;
    for (size_t i = 0; i < cj_vdoc_curve(d, 0)->count; ++i) {
        cj_vcurve c0 = *cj_vdoc_curve(d, 0);
        double pts[32], kn[40];
        memcpy(pts, c0.pts, c0.count * 2 * sizeof(double));
        memcpy(kn, c0.knot_vector, (c0.count + (size_t)c0.degree + 1) * sizeof(double));
        const cj_bspline before = cj_bspline_view(c0.degree, 2, (int)c0.count, pts, NULL, kn);
        double u0, u1;
        CHECK(cj_vcurve_support(&c0, i, &u0, &u1) == CJ_OK, "support");
        CHECK(u0 == fmax(kn[i], kn[c0.degree]) &&
                  u1 == fmin(kn[i + (size_t)c0.degree + 1], kn[c0.count]),
              "support of point %zu is [u_i, u_{i+p+1}]", i);
        cj_vdoc_begin_drag(d);
        cj_vdoc_move_point(d, 0, i, pts[2 * i] + 0.3, pts[2 * i + 1] - 0.2);
        cj_vdoc_move_point(d, 0, i, pts[2 * i] + 0.5, pts[2 * i + 1] - 0.1);
        cj_vdoc_end_drag(d);
        const cj_bspline after = cj_vcurve_bspline(cj_vdoc_curve(d, 0));
        int changed = 0;
        for (int s = 0; s < 400; ++s) {
            const double t = s < 2 ? (double)s : cj_rng_unit(rng);
            double a[2], b[2];
            cj_bspline_eval(&before, t, a);
            cj_bspline_eval(&after, t, b);
            if (t < u0 || t > u1) {
                CHECK(!memcmp(a, b, sizeof a),
                      "point %zu: the curve changed at %g outside "
                      "[%g, %g]",
                      i, t, u0, u1);
                outside++;
            } else if (t > u0 && t < u1) {
                changed |= memcmp(a, b, sizeof a) != 0;
            }
        }
        CHECK(changed, "point %zu: the curve changed inside its support", i);
        inside_changed += changed;
        CHECK(cj_vdoc_undo_depth(d) == i + 1, "a drag is one command");
    }
    printf("local control: each of the 7 points of a cubic B-spline dragged: the curve is "
           "bit-identical at %d parameters outside the point's support [u_i, u_{i+p+1}] and "
           "changed inside it (%d of 7)\n",
           outside, inside_changed);
    cj_vdoc_destroy(d);
}

/* Snapping: never beaten by dense sampling with the oracle, and the point lies on the curve. */
static void test_snap(const char *path, cj_rng *rng) {
    cj_vview v;
    cj_vdoc *d = load(path, &v);
    const size_t nc = cj_vdoc_curve_count(d);
    ocurve oc[8];
    for (size_t i = 0; i < nc; ++i) as_oracle(cj_vdoc_curve(d, i), &oc[i]);
    const double tol = 1e-5;
    double worst_gap = 0, worst_on = 0, worst_ratio = 0;
    long pieces = 0;
    const int queries = 60, per_curve = 300;
    for (int k = 0; k < queries; ++k) {
        const double q[2] = {cj_rng_range(rng, -0.5, 4.5), cj_rng_range(rng, -0.5, 3.5)};
        cj_vsnap s;
        if (cj_vdoc_snap(d, q, -1, tol, &s)) {
            CHECK(0, "snap: %s", cj_last_error());
            continue;
        }
        pieces += s.pieces;
        CHECK(s.distance - s.lower <= tol * (1 + 1e-9), "distance - lower = %g > tol",
              s.distance - s.lower);
        double sampled = INFINITY;
        for (size_t i = 0; i < nc; ++i) {
            double a, b;
            domain(&oc[i].o, &a, &b);
            for (int j = 0; j <= per_curve; ++j)
                sampled = fmin(sampled, oracle_distance(&oc[i].o, a + (b - a) * j / per_curve, q));
        }
        /* sampled >= the true minimum >= lower: nothing beats the certified bound */
        CHECK(sampled >= s.lower, "query %d: a sample at %.17g beats the lower bound %.17g", k,
              sampled, s.lower);
        worst_gap = fmax(worst_gap, s.distance - sampled);
        /* the point itself: |point - c(u)| by the oracle, against the certified on_curve */
        const double on = oracle_distance(&oc[s.curve].o, s.u, s.point);
        const double ulp = DBL_EPSILON * fmax(fabs(s.point[0]), fabs(s.point[1]));
        CHECK(on <= fmax(s.on_curve, 2 * ulp),
              "query %d: the snapped point is %g from c(u), "
              "certified %g",
              k, on, s.on_curve);
        worst_on = fmax(worst_on, on);
        worst_ratio = fmax(worst_ratio, s.on_curve / ulp);
        /* nearest.h's proven upper bound carries the evaluation's rounding term, which scales
         * with the piece's control points rather than with the point itself: tight means within
         * a few hundred units of the point's size (measured: up to 112 since the Bernstein sign
         * test settles pieces without subdividing them to the point) */
        CHECK(s.on_curve <= 256 * ulp, "query %d: on-curve bound %g is not tight", k, s.on_curve);
    }
    printf("snap: %d random points, %zu curves (B-spline, NURBS, rational, line), tol %g: "
           "distance - lower <= tol; no oracle sample (%d per curve, MPFR) beats the certified "
           "lower bound (the best sample is within %.2e above the snapped distance); the "
           "snapped point lies %.2e at most from c(u) by the oracle, and its certified distance "
           "to the curve is at most %.1f ulps; %ld pieces examined\n",
           queries, nc, tol, per_curve, worst_gap, worst_on, worst_ratio, pieces);
    cj_vdoc_destroy(d);
}

/* Intersections: each mark lies on both curves (oracle at the reported parameters). */
static void test_intersections(const char *path) {
    cj_vview v;
    cj_vdoc *d = load(path, &v);
    ocurve oc[8];
    for (size_t i = 0; i < cj_vdoc_curve_count(d); ++i) as_oracle(cj_vdoc_curve(d, i), &oc[i]);
    cj_vmark *m = NULL;
    size_t n = 0, failed = 0;
    CHECK(cj_vdoc_intersections(d, 1e-9, &m, &n, &failed) == CJ_OK, "%s", cj_last_error());
    CHECK(failed == 0, "%zu pairs failed", failed);
    double worst = 0;
    size_t with_line = 0;
    for (size_t i = 0; i < n; ++i) {
        const double da = oracle_distance(&oc[m[i].a].o, m[i].ua, m[i].point);
        const double db = oracle_distance(&oc[m[i].b].o, m[i].ub, m[i].point);
        worst = fmax(worst, fmax(da, db));
        CHECK(da <= 1e-9 && db <= 1e-9, "mark %zu (curves %zu, %zu) is %g / %g off the curves", i,
              m[i].a, m[i].b, da, db);
        with_line += m[i].b == 3;
    }
    /* the line y = 0.1 + (x - 0.1) 2.8/3.8 crosses the cubic B-spline: sign changes of the
     * oracle's signed distance along it count the crossings */
    int changes = 0, prev = 0;
    for (int j = 0; j <= 4000; ++j) {
        mpfr_t x, y;
        mpfr_inits2(CJ_ORACLE_BSP_PREC, x, y, (mpfr_ptr)0);
        oracle_point(&oc[0].o, j / 4000.0, x, y);
        const double fx = mpfr_get_d(x, MPFR_RNDN), fy = mpfr_get_d(y, MPFR_RNDN);
        mpfr_clears(x, y, (mpfr_ptr)0);
        const double side = (fy - 0.1) * 3.8 - (fx - 0.1) * 2.8;
        const int sg = side > 0 ? 1 : -1;
        changes += j && sg != prev;
        prev = sg;
    }
    size_t bline = 0;
    for (size_t i = 0; i < n; ++i) bline += m[i].a == 0 && m[i].b == 3;
    CHECK(bline == (size_t)changes, "B-spline x line: %zu marks, %d sign changes", bline, changes);
    printf("intersections: %zu marks between the 4 curves (%zu with the line), each within "
           "%.2e of both curves at its parameters (MPFR); B-spline x line: %zu marks = %d sign "
           "changes of the oracle's side along the curve\n",
           n, with_line, worst, bline, changes);
    free(m);
    cj_vdoc_destroy(d);
}

static void test_refusals(const char *path) {
    cj_vview v;
    cj_vdoc *d = load(path, &v);
    const size_t depth = cj_vdoc_undo_depth(d);
    CHECK(cj_vdoc_insert_point(d, 0, 1, 1, 1) == CJ_ERR_ARGUMENT, "insert point refused");
    CHECK(cj_vdoc_delete_point(d, 0, 1) == CJ_ERR_ARGUMENT, "delete point refused");
    CHECK(cj_vdoc_elevate(d, 0) == CJ_ERR_ARGUMENT, "Bezier elevation refused");
    CHECK(cj_vdoc_split(d, 0, 0.5) == CJ_ERR_ARGUMENT, "split refused");
    CHECK(strstr(cj_last_error(), "B-spline") != NULL, "the message says why: %s", cj_last_error());
    CHECK(cj_vdoc_set_weight(d, 1, 0, 0.0) != CJ_OK, "weight 0 refused");
    CHECK(cj_vdoc_insert_knot(d, 2, 0.5) == CJ_ERR_ARGUMENT, "a Bezier has no knots");
    CHECK(cj_vdoc_insert_knot(d, 0, 2.0) != CJ_OK, "a knot outside the domain refused");
    CHECK(cj_vdoc_undo_depth(d) == depth, "nothing recorded");
    CHECK(cj_vdoc_set_weight(d, 0, 2, 2.0) == CJ_OK && cj_vdoc_curve(d, 0)->weights &&
              cj_vdoc_curve(d, 0)->weights[2] == 2.0 && cj_vdoc_curve(d, 0)->weights[0] == 1.0,
          "a weight makes the B-spline a NURBS");
    cj_vdoc_destroy(d);
    static const char *const bad[][2] = {
        {"{\"items\": [{\"type\": \"bspline\", \"degree\": 2, \"knots\": [0,0,0,1,0.5,1],"
         " \"points\": [[0,0],[1,1],[2,0]]}]}",
         "items[0]"},
        {"{\"items\": [{\"type\": \"bspline\", \"degree\": 1, \"points\": [[0,0,1],[1,1,1]]}]}",
         "2D"},
        {"{\"items\": [{\"type\": \"bspline\", \"degree\": 1, \"weights\": [1, -1],"
         " \"points\": [[0,0],[1,1]]}]}",
         "items[0]"},
        {"{\"items\": [{\"type\": \"bspline\", \"degree\": 1, \"width\": \"wide\","
         " \"points\": [[0,0],[1,1]]}]}",
         "items[0]"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char p[600];
        write_file("bad.json", bad[i][0], p, sizeof p);
        cj_vdoc *e = NULL;
        cj_vview w;
        cj_vdoc_display disp;
        const cj_status st = cj_vdoc_load_json(p, &e, &w, &disp);
        CHECK(st != CJ_OK && !e, "bad file %zu loaded", i);
        CHECK(strstr(cj_last_error(), bad[i][1]) != NULL, "bad file %zu: message '%s' lacks '%s'",
              i, cj_last_error(), bad[i][1]);
        printf("refused: %s\n", cj_last_error());
    }
    printf("refusals: a B-spline refuses point insertion/deletion, Bezier elevation and split "
           "(the message says why), weights <= 0, knots outside its domain; nothing recorded\n");
}

int main(void) {
    if (!mkdtemp(dir)) return 1;
    char path[600];
    write_file("doc.json", doc_text, path, sizeof path);
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_viewer_bspline", 22));
    test_round_trip(path);
    test_knot_insertion(&rng);
    test_local_control(path, &rng);
    test_snap(path, &rng);
    test_intersections(path);
    test_refusals(path);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) return 1;
    return cj_check_exit();
}
