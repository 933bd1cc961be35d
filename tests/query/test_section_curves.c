/* Plane sections of MODELS as joined chains of cubic Bézier pieces (cj_patches_section_curves),
 * checked against a long-double oracle independent of the library:
 *  - section -> pieces: the crossings of the true section with dense lines u = const and
 *    v = const of every patch (long-double bisection of n . S - d) all lie within the proven
 *    deviation of the pieces (distance measured at evaluated points of the pieces: an upper
 *    bound);
 *  - pieces -> section: every sample of every piece lies within the deviation of a true section
 *    point, found by long-double Newton along the section (f = 0 to 1e-17) from the nearest
 *    oracle crossing;
 *  - structure: consecutive pieces share end points bit for bit, closed chains close bit for
 *    bit; the teapot cut by y = 0, a plane holding patch edges, comes out as 6 curves with nothing
 *    unresolved; the sphere made of 8 rational octants cut by z = 1/2 and x = 0.3 gives ONE closed
 * chain (joined over 4 patches) on the exact circle; the teapot cut by z = 1.5 and y = 0.2 and a
 *    random bicubic B-spline surface (9 patches) give joined chains, not one per patch; bad
 *    input refused. */
#include "casteljau/bspline_surface.h"
#include "casteljau/patch_section.h"
#include "casteljau/patchset.h"
#include "check.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

typedef long double ld;

static void oracle_eval(const cj_patch *p, ld u, ld v, ld out[3]) {
    int m = p->deg_u, n = p->deg_v;
    ld w[16][4], col[16][4];
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= m; ++i) {
            int idx = j * (m + 1) + i;
            ld wt = p->weights ? p->weights[idx] : 1.0L;
            for (int k = 0; k < 3; ++k) w[i][k] = wt * p->pts[3 * idx + k];
            w[i][3] = wt;
        }
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < 4; ++k) w[i][k] = (1 - u) * w[i][k] + u * w[i + 1][k];
        for (int k = 0; k < 4; ++k) col[j][k] = w[0][k];
    }
    for (int r = n; r > 0; --r)
        for (int j = 0; j < r; ++j)
            for (int k = 0; k < 4; ++k) col[j][k] = (1 - v) * col[j][k] + v * col[j + 1][k];
    for (int k = 0; k < 3; ++k) out[k] = col[0][k] / col[0][3];
}

typedef struct crossing {
    double x[3];
    int patch;
    ld u, v;
} crossing;

typedef struct oracle {
    crossing *c;
    int n, cap;
} oracle;

static ld fval(const cj_patch *p, const double nrm[3], double d, ld u, ld v) {
    ld s[3];
    oracle_eval(p, u, v, s);
    return nrm[0] * s[0] + nrm[1] * s[1] + nrm[2] * s[2] - d;
}

/* Crossings of the section with G lines u = const and G lines v = const of each patch, each
 * line sampled at G points and every sign change bisected in long double. */
static void build_oracle(const cj_patch *ps, size_t count, const double nrm[3], double d, int G,
                         oracle *o) {
    for (size_t p = 0; p < count; ++p)
        for (int dir = 0; dir < 2; ++dir)
            for (int l = 0; l <= G; ++l) {
                ld fixed = (ld)l / G;
                ld prev_t = 0, prev_f = 0;
                for (int s = 0; s <= G; ++s) {
                    ld t = (ld)s / G;
                    ld f = dir ? fval(&ps[p], nrm, d, fixed, t) : fval(&ps[p], nrm, d, t, fixed);
                    if (s > 0 && (f < 0) != (prev_f < 0)) {
                        ld a = prev_t, b = t, fa = prev_f;
                        for (int it = 0; it < 70; ++it) {
                            ld mid = (a + b) / 2;
                            ld fm = dir ? fval(&ps[p], nrm, d, fixed, mid)
                                        : fval(&ps[p], nrm, d, mid, fixed);
                            if ((fm < 0) == (fa < 0))
                                a = mid, fa = fm;
                            else
                                b = mid;
                        }
                        if (o->n == o->cap) {
                            o->cap = o->cap ? 2 * o->cap : 1024;
                            o->c = realloc(o->c, (size_t)o->cap * sizeof *o->c);
                        }
                        crossing *c = &o->c[o->n++];
                        ld r = (a + b) / 2, pt[3];
                        c->u = dir ? fixed : r;
                        c->v = dir ? r : fixed;
                        c->patch = (int)p;
                        oracle_eval(&ps[p], c->u, c->v, pt);
                        for (int k = 0; k < 3; ++k) c->x[k] = (double)pt[k];
                    }
                    prev_t = t, prev_f = f;
                }
            }
}

static void bez(const double *B, double t, double out[3]) {
    double s = 1 - t;
    for (int k = 0; k < 3; ++k)
        out[k] = s * s * s * B[k] + 3 * s * s * t * B[3 + k] + 3 * s * t * t * B[6 + k] +
                 t * t * t * B[9 + k];
}

static double dist3(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* Upper bound of the distance from x to the pieces: 64 samples per piece near x, then golden
 * section search around the best (every value is the distance to an evaluated point). */
static double dist_to_pieces(const cj_section_curves *s, const double x[3]) {
    double best = INFINITY;
    for (int k = 0; k < s->npieces; ++k) {
        const double *B = s->ctrl + 12 * k;
        double lo[3], hi[3];
        for (int q = 0; q < 3; ++q) {
            lo[q] = fmin(fmin(B[q], B[3 + q]), fmin(B[6 + q], B[9 + q]));
            hi[q] = fmax(fmax(B[q], B[3 + q]), fmax(B[6 + q], B[9 + q]));
        }
        double g = 0;
        for (int q = 0; q < 3; ++q) g += pow(fmax(0, fmax(lo[q] - x[q], x[q] - hi[q])), 2);
        if (sqrt(g) >= best) continue; /* the hull is farther than what we have */
        int bs = 0;
        double bd = INFINITY, pt[3];
        for (int i = 0; i <= 64; ++i) {
            bez(B, i / 64.0, pt);
            double dd = dist3(pt, x);
            if (dd < bd) bd = dd, bs = i;
        }
        double a = fmax(0, (bs - 1) / 64.0), b = fmin(1, (bs + 1) / 64.0);
        for (int it = 0; it < 60; ++it) {
            double m1 = a + (b - a) * 0.381966, m2 = b - (b - a) * 0.381966, p1[3], p2[3];
            bez(B, m1, p1);
            bez(B, m2, p2);
            double d1 = dist3(p1, x), d2 = dist3(p2, x);
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

/* A true section point near x on patch p: Newton along the section from (u,v) (a tangential step
 * plus a step back onto f = 0, in long double), accepted only where |f| / |n| ends below 1e-15;
 * returns its distance to x, or +inf. */
static double project(const cj_patch *p, const double nrm[3], double d, ld u, ld v,
                      const double x[3]) {
    ld h = 1e-7L;
    for (int it = 0; it < 40; ++it) {
        ld S[3], a[3], b[3], c[3], e[3], Su[3], Sv[3];
        oracle_eval(p, u, v, S);
        oracle_eval(p, fminl(1, u + h), v, a);
        oracle_eval(p, fmaxl(0, u - h), v, b);
        ld hu = fminl(1, u + h) - fmaxl(0, u - h);
        for (int k = 0; k < 3; ++k) Su[k] = (a[k] - b[k]) / hu;
        oracle_eval(p, u, fminl(1, v + h), a);
        oracle_eval(p, u, fmaxl(0, v - h), c);
        ld hv = fminl(1, v + h) - fmaxl(0, v - h);
        for (int k = 0; k < 3; ++k) Sv[k] = (a[k] - c[k]) / hv;
        ld f = nrm[0] * S[0] + nrm[1] * S[1] + nrm[2] * S[2] - d;
        ld fu = nrm[0] * Su[0] + nrm[1] * Su[1] + nrm[2] * Su[2];
        ld fv = nrm[0] * Sv[0] + nrm[1] * Sv[1] + nrm[2] * Sv[2];
        ld g2 = fu * fu + fv * fv;
        if (!(g2 > 0)) break;
        ld du = -f * fu / g2, dv = -f * fv / g2;
        ld D[3], DD = 0, t = 0;
        for (int k = 0; k < 3; ++k) {
            D[k] = -fv * Su[k] + fu * Sv[k];
            DD += D[k] * D[k];
            e[k] = x[k] - S[k];
            t += e[k] * D[k];
        }
        if (DD > 0 && it < 30) du += -fv * t / DD, dv += fu * t / DD;
        u = fminl(1, fmaxl(0, u + du));
        v = fminl(1, fmaxl(0, v + dv));
    }
    ld S[3];
    oracle_eval(p, u, v, S);
    ld f = nrm[0] * S[0] + nrm[1] * S[1] + nrm[2] * S[2] - d;
    double nn = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(fabsl(f) / nn < 1e-15L)) return INFINITY;
    double y[3] = {(double)S[0], (double)S[1], (double)S[2]};
    return dist3(y, x) + (double)(fabsl(f) / nn);
}

/* Upper bound of the distance from x to the true section: the nearest oracle crossing, and the
 * Newton projections from the nearest crossing of each of the three nearest patches (the
 * nearest point may lie past the edge of the first one). */
static double dist_to_section(const cj_patch *ps, size_t count, const double nrm[3], double d,
                              const oracle *o, const double x[3]) {
    double bd = INFINITY, pd[3] = {INFINITY, INFINITY, INFINITY};
    int pi[3] = {-1, -1, -1};
    double *per = malloc(count * sizeof *per);
    int *at = malloc(count * sizeof *at);
    for (size_t p = 0; p < count; ++p) per[p] = INFINITY, at[p] = -1;
    for (int i = 0; i < o->n; ++i) {
        double dd = dist3(o->c[i].x, x);
        bd = fmin(bd, dd);
        if (dd < per[o->c[i].patch]) per[o->c[i].patch] = dd, at[o->c[i].patch] = i;
    }
    for (size_t p = 0; p < count; ++p)
        for (int r = 0; r < 3; ++r)
            if (per[p] < pd[r]) {
                for (int q = 2; q > r; --q) pd[q] = pd[q - 1], pi[q] = pi[q - 1];
                pd[r] = per[p], pi[r] = at[p];
                break;
            }
    for (int r = 0; r < 3; ++r)
        if (pi[r] >= 0)
            bd = fmin(bd, project(&ps[o->c[pi[r]].patch], nrm, d, o->c[pi[r]].u, o->c[pi[r]].v, x));
    free(per);
    free(at);
    return bd;
}

static long oracle_points = 0, piece_samples = 0;

/* Checks one model section; returns the result for the caller's own checks (freed by it). */
static void check_model(const char *what, const cj_patch *ps, size_t count, const double nrm[3],
                        double d, double tol, int G, cj_section_curves *out) {
    cj_status st = cj_patches_section_curves(ps, count, nrm, d, tol, out);
    CHECK(st == CJ_OK, "%s: %s", what, cj_last_error());
    if (st != CJ_OK) return;
    const cj_section_curves *s = out;
    CHECK(s->deviation <= tol, "%s: deviation %g > tol %g", what, s->deviation, tol);
    /* structure: shared end points, closed chains closed */
    for (int c = 0; c < s->nchains; ++c) {
        int a = s->piece_starts[c], b = s->piece_starts[c + 1];
        CHECK(b > a, "%s: chain %d has no piece", what, c);
        for (int k = a; k + 1 < b; ++k)
            CHECK(!memcmp(s->ctrl + 12 * k + 9, s->ctrl + 12 * (k + 1), 3 * sizeof(double)),
                  "%s: chain %d pieces %d, %d do not share their end point", what, c, k, k + 1);
        if (s->closed[c])
            CHECK(!memcmp(s->ctrl + 12 * (b - 1) + 9, s->ctrl + 12 * a, 3 * sizeof(double)),
                  "%s: closed chain %d does not close", what, c);
    }
    oracle o = {0};
    build_oracle(ps, count, nrm, d, G, &o);
    double worst_in = 0, worst_out = 0;
    for (int i = 0; i < o.n; ++i) {
        double dd = dist_to_pieces(s, o.c[i].x);
        for (int j = 0; j < s->nunresolved; ++j)
            dd = fmin(dd, dist3(s->unresolved + 3 * j, o.c[i].x));
        worst_in = fmax(worst_in, dd);
        ++oracle_points;
    }
    CHECK(worst_in <= s->deviation, "%s: a true crossing %g from the pieces (deviation %g)", what,
          worst_in, s->deviation);
    for (int k = 0; k < s->npieces; ++k)
        for (int i = 0; i <= 8; ++i) {
            double pt[3];
            bez(s->ctrl + 12 * k, i / 8.0, pt);
            double dd = dist_to_section(ps, count, nrm, d, &o, pt);
            if (getenv("SECT_DEBUG") && dd > s->deviation) {
                double dp = INFINITY;
                for (int q = 0; q < s->npts; ++q) dp = fmin(dp, dist3(s->pts + 3 * q, pt));
                fprintf(stderr, "piece %d t %g at (%g %g %g): oracle %g, polyline vertices %g\n", k,
                        i / 8.0, pt[0], pt[1], pt[2], dd, dp);
            }
            worst_out = fmax(worst_out, dd);
            ++piece_samples;
        }
    CHECK(worst_out <= s->deviation, "%s: a piece point %g from the section (deviation %g)", what,
          worst_out, s->deviation);
    int closed = 0;
    for (int c = 0; c < s->nchains; ++c) closed += s->closed[c];
    printf("%s: %d chains (%d closed), %d cubic pieces for %d polyline vertices, %d joins (gap "
           "%.2g), deviation %.3g (polylines %.3g) <= tol %g; measured: crossings -> pieces %.3g, "
           "pieces -> section %.3g (%d oracle crossings)\n",
           what, s->nchains, closed, s->npieces, s->npts, s->joins, s->join_gap, s->deviation,
           s->poly_deviation, tol, worst_in, worst_out, o.n);
    free(o.c);
}

/* The unit sphere as 8 rational biquadratic octants (mirror images of the first). */
static void sphere(double pts[8][27], double w[8][9], cj_patch ps[8]) {
    const double a[3][2] = {{1, 0}, {1, 1}, {0, 1}}, wa[3] = {1, sqrt(0.5), 1};
    for (int o = 0; o < 8; ++o) {
        double sx = o & 1 ? -1 : 1, sy = o & 2 ? -1 : 1, sz = o & 4 ? -1 : 1;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                int idx = j * 3 + i;
                pts[o][3 * idx] = sx * a[j][0] * a[i][0];
                pts[o][3 * idx + 1] = sy * a[j][0] * a[i][1];
                pts[o][3 * idx + 2] = sz * a[j][1];
                w[o][idx] = wa[i] * wa[j];
            }
        ps[o] = cj_patch_view(2, 2, pts[o], w[o]);
    }
}

static void check_sphere(void) {
    double pts[8][27], w[8][9];
    cj_patch ps[8];
    sphere(pts, w, ps);
    const double planes[2][4] = {{0, 0, 1, 0.5}, {1, 0, 0, 0.3}};
    for (int t = 0; t < 2; ++t) {
        cj_section_curves s;
        char what[96];
        snprintf(what, sizeof what, "sphere, plane %g,%g,%g,%g", planes[t][0], planes[t][1],
                 planes[t][2], planes[t][3]);
        check_model(what, ps, 8, planes[t], planes[t][3], 1e-3, 200, &s);
        CHECK(s.nchains == 1 && s.closed && s.closed[0] && s.joins == 4,
              "%s: %d chains, %d joins (want one closed chain over 4 patches)", what, s.nchains,
              s.joins);
        /* exact: the circle of radius sqrt(1 - h^2) in the plane */
        double h = planes[t][3], rho = sqrt(1 - h * h), worst = 0;
        for (int k = 0; k < s.npieces; ++k)
            for (int i = 0; i <= 32; ++i) {
                double p[3];
                bez(s.ctrl + 12 * k, i / 32.0, p);
                double r = t == 0 ? hypot(p[0], p[1]) : hypot(p[1], p[2]);
                double off = t == 0 ? p[2] - h : p[0] - h;
                worst = fmax(worst, hypot(r - rho, off));
            }
        CHECK(worst <= s.deviation, "%s: %g off the exact circle (deviation %g)", what, worst,
              s.deviation);
        printf("  exact circle: samples within %.3g of it\n", worst);
        cj_section_curves_free(&s);
    }
}

static void check_teapot(void) {
    cj_patchset *set = NULL;
    cj_status st = cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set);
    CHECK(st == CJ_OK, "teapot: %s", cj_last_error());
    if (st) return;
    const double planes[2][4] = {{0, 0, 1, 1.5}, {0, 1, 0, 0.2}};
    for (int t = 0; t < 2; ++t) {
        cj_section_curves s;
        char what[96];
        snprintf(what, sizeof what, "teapot, plane %g,%g,%g,%g", planes[t][0], planes[t][1],
                 planes[t][2], planes[t][3]);
        check_model(what, set->patches, set->count, planes[t], planes[t][3], 2e-3, 120, &s);
        int runs = 0, closed = 0;
        for (int c = 0; c < s.nchains; ++c) closed += s.closed[c];
        runs = s.nchains + s.joins; /* every join merges two runs */
        CHECK(s.joins > 0 && s.nchains < runs, "%s: %d chains, %d joins", what, s.nchains, s.joins);
        if (t == 0) /* body, spout and handle are tubes: every chain closes */
            CHECK(closed == s.nchains && s.nchains >= 3, "%s: %d of %d chains closed", what, closed,
                  s.nchains);
        cj_section_curves_free(&s);
    }
    /* y = 0 contains patch edges (the teapot is made of quarters): the patches on one side find
     * the edge as polylines, those on the other side only unresolved cells on it, which the
     * pieces cover (absorbed): the profile comes out as curves, nothing left unresolved */
    {
        cj_section_curves s;
        const double y0[3] = {0, 1, 0};
        check_model("teapot, plane y = 0 (along patch edges)", set->patches, set->count, y0, 0,
                    2e-3, 60, &s);
        CHECK(s.nunresolved == 0 && s.nchains == 6 && s.deviation <= 2e-3,
              "teapot y = 0: %d unresolved, %d chains, deviation %g", s.nunresolved, s.nchains,
              s.deviation);
        cj_section_curves_free(&s);
    }
    cj_patchset_destroy(set);
}

static void check_bspline(cj_rng *rng) {
    /* a random bicubic B-spline surface, 6 x 6 points over a wavy grid: 3 x 3 patches */
    double pts[6 * 6 * 3], ku[10] = {0, 0, 0, 0, 1, 2, 3, 3, 3, 3};
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) {
            double *p = pts + 3 * (j * 6 + i);
            p[0] = i + cj_rng_range(rng, -0.3, 0.3);
            p[1] = j + cj_rng_range(rng, -0.3, 0.3);
            p[2] = cj_rng_range(rng, -1, 1);
        }
    cj_bspline_surface S = {3, 3, 6, 6, pts, NULL, ku, ku};
    double bp[9 * 48];
    int count = 0;
    cj_status st = cj_bspline_surface_to_patches(&S, bp, NULL, NULL, NULL, 9, &count);
    CHECK(st == CJ_OK && count == 9, "B-spline patches: %d", count);
    if (st) return;
    cj_patch ps[9];
    for (int k = 0; k < 9; ++k) ps[k] = cj_patch_view(3, 3, bp + 48 * k, NULL);
    const double planes[2][4] = {{1, 0.3, 0, 2.6}, {0.2, 1, 0.1, 2.4}};
    for (int t = 0; t < 2; ++t) {
        cj_section_curves s;
        char what[80];
        snprintf(what, sizeof what, "B-spline 3x3 patches, plane %g,%g,%g,%g", planes[t][0],
                 planes[t][1], planes[t][2], planes[t][3]);
        check_model(what, ps, 9, planes[t], planes[t][3], 1e-3, 150, &s);
        CHECK(s.joins >= 2 && s.nchains >= 1, "%s: %d chains, %d joins", what, s.nchains, s.joins);
        cj_section_curves_free(&s);
    }
}

static void check_bad(void) {
    double pts[8][27], w[8][9];
    cj_patch ps[8];
    sphere(pts, w, ps);
    cj_section_curves s;
    CHECK(cj_patches_section_curves(ps, 0, (double[]){0, 0, 1}, 0, 1e-3, &s) == CJ_ERR_ARGUMENT,
          "0 patches");
    CHECK(cj_patches_section_curves(ps, 8, (double[]){0, 0, 0}, 0, 1e-3, &s) == CJ_ERR_DEGENERATE &&
              strstr(cj_last_error(), "patch 0"),
          "zero normal: %s", cj_last_error());
    w[3][4] = -1;
    CHECK(cj_patches_section_curves(ps, 8, (double[]){0, 0, 1}, 0.5, 1e-3, &s) != CJ_OK &&
              strstr(cj_last_error(), "patch 3"),
          "negative weight in patch 3: %s", cj_last_error());
    w[3][4] = 0.5;
    CHECK(cj_patches_section_curves(ps, 8, (double[]){0, 0, 1}, 0.5, NAN, &s) == CJ_ERR_ARGUMENT,
          "NaN tol: %s", cj_last_error());
}

int main(void) {
    uint64_t seed = cj_test_seed("test_section_curves", 2323);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    check_sphere();
    check_teapot();
    check_bspline(&rng);
    check_bad();
    printf("test_section_curves: %ld long-double oracle crossings all within the proven "
           "deviation of the pieces, %ld piece samples all within it of the true section: %s\n",
           oracle_points, piece_samples, cj_check_failures ? "FAILED" : "passed");
    return cj_check_exit();
}
