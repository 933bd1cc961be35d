/* Plane sections of Bézier patches (casteljau/patch_section.h) against exact cases and an
 * independent long-double oracle:
 *  - a rational sphere octant cut by z = h: one open polyline whose vertices lie on the circle
 *    of radius sqrt(1 - h^2) and whose segments stay within the proven deviation of it, from
 *    angle 0 to pi/2; a tilted plane: vertices on the exact circle of the plane and sphere;
 *  - the paraboloid z = x^2 + y^2 as a biquadratic: z = 1/4 is one CLOSED loop on the circle of
 *    radius 1/2 all the way round; x = 0.3 the parabola z = 0.09 + y^2; z = 0 (the tangent
 *    plane) is reported near the origin, never dropped; z = -0.01 is proven empty;
 *  - random bicubic patches and planes through a point of the patch (seeded): every crossing of
 *    the section with 120 lines v = const, found by long-double bisection on a dense grid, lies
 *    within the proven deviation of the polylines (or of an unresolved point): never missed;
 *  - bad input refused naming it. */
#include "casteljau/patch_section.h"
#include "check.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846

/* S(u,v) in long double: tensor de Casteljau on homogeneous points (independent of the
 * library). */
static void oracle_eval(const cj_patch *p, long double u, long double v, long double out[3]) {
    int m = p->deg_u, n = p->deg_v;
    long double w[16][4], col[16][4];
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= m; ++i) {
            int idx = j * (m + 1) + i;
            long double wt = p->weights ? p->weights[idx] : 1.0L;
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

static double seg_dist(const double *a, const double *b, const double *x) {
    double ab[3], ax[3], l2 = 0, t = 0;
    for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ax[k] = x[k] - a[k], l2 += ab[k] * ab[k];
    for (int k = 0; k < 3; ++k) t += ab[k] * ax[k];
    t = l2 > 0 ? fmin(1.0, fmax(0.0, t / l2)) : 0.0;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
        double e = a[k] + t * ab[k] - x[k];
        d2 += e * e;
    }
    return sqrt(d2);
}

/* Distance from x to the reported section: its segments (closing ones included), its
 * isolated points and its unresolved points. */
static double dist_to_section(const cj_patch_section *s, const double x[3]) {
    double best = INFINITY;
    for (int l = 0; l < s->nlines; ++l) {
        int a = s->starts[l], b = s->starts[l + 1];
        if (b - a == 1) best = fmin(best, seg_dist(s->pts + 3 * a, s->pts + 3 * a, x));
        for (int i = a; i + 1 < b; ++i)
            best = fmin(best, seg_dist(s->pts + 3 * i, s->pts + 3 * (i + 1), x));
        if (s->closed[l] && b - a > 1)
            best = fmin(best, seg_dist(s->pts + 3 * (b - 1), s->pts + 3 * a, x));
    }
    for (int i = 0; i < s->nunresolved; ++i)
        best = fmin(best, seg_dist(s->unresolved + 3 * i, s->unresolved + 3 * i, x));
    return best;
}

/* ---- exact cases ---------------------------------------------------------------------- */

static void sphere_octant(double pts[27], double w[9]) {
    /* revolution of the quarter meridian (r, z) = (1,0), (1,1), (0,1) about z by the quarter
     * circle (1,0), (1,1), (0,1); weights 1, sqrt(1/2), 1 in each direction */
    const double a[3][2] = {{1, 0}, {1, 1}, {0, 1}}, mer[3][2] = {{1, 0}, {1, 1}, {0, 1}};
    const double wa[3] = {1, sqrt(0.5), 1};
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            int idx = j * 3 + i;
            pts[3 * idx] = mer[j][0] * a[i][0];
            pts[3 * idx + 1] = mer[j][0] * a[i][1];
            pts[3 * idx + 2] = mer[j][1];
            w[idx] = wa[i] * wa[j];
        }
}

static void check_sphere(void) {
    double pts[27], w[9];
    sphere_octant(pts, w);
    cj_patch p = cj_patch_view(2, 2, pts, w);
    const double hs[3] = {0.1, 0.5, 0.9};
    for (int t = 0; t < 3; ++t) {
        double h = hs[t], rho = sqrt(1 - h * h), tol = 1e-3;
        const double n[3] = {0, 0, 1};
        cj_patch_section s;
        cj_status st = cj_patch_section_plane(&p, n, h, tol, &s);
        CHECK(st == CJ_OK, "sphere z = %g: status %d", h, (int)st);
        if (st != CJ_OK) continue;
        CHECK(s.nlines == 1 && !s.closed[0], "sphere z = %g: %d lines, closed %d", h, s.nlines,
              s.nlines ? s.closed[0] : -1);
        CHECK(s.deviation <= tol, "sphere z = %g: deviation %g > tol", h, s.deviation);
        CHECK(s.nunresolved == 0 && s.ambiguous == 0, "sphere z = %g: %d unresolved %d ambiguous",
              h, s.nunresolved, s.ambiguous);
        double worst_v = 0, worst_mid = 0, amin = 10, amax = -10;
        int monotone = 1;
        for (int i = 0; i < s.npts; ++i) {
            const double *x = s.pts + 3 * i;
            worst_v = fmax(worst_v, fmax(fabs(x[2] - h), fabs(hypot(x[0], x[1]) - rho)));
            double ang = atan2(x[1], x[0]);
            amin = fmin(amin, ang);
            amax = fmax(amax, ang);
            if (i > 0) {
                const double *y = x - 3;
                double prev = atan2(y[1], y[0]);
                if (i > 1) {
                    const double *z = y - 3;
                    double pp = atan2(z[1], z[0]);
                    if ((ang - prev) * (prev - pp) < 0) monotone = 0;
                }
                double mid[2] = {0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1])};
                worst_mid = fmax(worst_mid, fabs(hypot(mid[0], mid[1]) - rho));
            }
        }
        CHECK(worst_v <= 1e-13, "sphere z = %g: a vertex is %g off the circle", h, worst_v);
        CHECK(worst_mid <= s.deviation, "sphere z = %g: a chord midpoint is %g off the circle", h,
              worst_mid);
        CHECK(fabs(amin) <= 1e-9 && fabs(amax - PI / 2) <= 1e-9 && monotone,
              "sphere z = %g: angles %.17g .. %.17g (monotone %d)", h, amin, amax, monotone);
        printf("sphere octant z = %.1f: %d points, deviation %.3g (tol %g), vertices within "
               "%.2g of the circle, chords within %.2g, %ld cells\n",
               h, s.npts, s.deviation, tol, worst_v, worst_mid, s.cells);
        cj_patch_section_free(&s);
    }
    /* tilted plane x + 2y + 2z = 2: the circle of centre (2/9)(1,2,2), radius sqrt(1 - 4/9) */
    const double n[3] = {1, 2, 2};
    cj_patch_section s;
    cj_status st = cj_patch_section_plane(&p, n, 2.0, 1e-4, &s);
    CHECK(st == CJ_OK && s.npts > 10, "tilted sphere section: status %d, %d points", (int)st,
          s.npts);
    double c[3] = {2.0 / 9, 4.0 / 9, 4.0 / 9}, rho = sqrt(1 - 4.0 / 9), worst = 0;
    for (int i = 0; i < s.npts; ++i) {
        const double *x = s.pts + 3 * i;
        double r = sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
                        (x[2] - c[2]) * (x[2] - c[2]));
        worst = fmax(worst, fmax(fabs(r - rho), fabs(x[0] + 2 * x[1] + 2 * x[2] - 2) / 3));
    }
    CHECK(worst <= 1e-13, "tilted sphere section: a vertex %g off the circle", worst);
    printf("sphere octant x + 2y + 2z = 2: %d lines, %d points, deviation %.3g, vertices within "
           "%.2g of the exact circle\n",
           s.nlines, s.npts, s.deviation, worst);
    cj_patch_section_free(&s);
}

static void check_paraboloid(void) {
    /* z = x^2 + y^2 over [-1,1]^2: x^2 on [-1,1] has Bernstein coefficients 1, -1, 1 */
    double pts[27];
    const double a[3] = {1, -1, 1}, xs[3] = {-1, 0, 1};
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            int idx = j * 3 + i;
            pts[3 * idx] = xs[i];
            pts[3 * idx + 1] = xs[j];
            pts[3 * idx + 2] = a[i] + a[j];
        }
    cj_patch p = cj_patch_view(2, 2, pts, NULL);
    const double nz[3] = {0, 0, 1}, nx[3] = {1, 0, 0};
    cj_patch_section s;
    cj_status st = cj_patch_section_plane(&p, nz, 0.25, 1e-3, &s);
    CHECK(st == CJ_OK && s.nlines == 1 && s.closed[0], "paraboloid z = 1/4: status %d, %d lines",
          (int)st, s.nlines);
    double worst = 0, gap = 0;
    for (int i = 0; i < s.npts; ++i) {
        const double *x = s.pts + 3 * i, *y = s.pts + 3 * ((i + 1) % s.npts);
        worst = fmax(worst, fmax(fabs(hypot(x[0], x[1]) - 0.5), fabs(x[2] - 0.25)));
        double da = fabs(remainder(atan2(y[1], y[0]) - atan2(x[1], x[0]), 2 * PI));
        gap = fmax(gap, da);
    }
    CHECK(worst <= 1e-13 && gap < 0.1, "paraboloid loop: %g off the circle, angular gap %g", worst,
          gap);
    printf("paraboloid z = 1/4: one closed loop of %d points on the circle r = 1/2 (within %.2g, "
           "largest angular step %.3g), deviation %.3g\n",
           s.npts, worst, gap, s.deviation);
    cj_patch_section_free(&s);

    st = cj_patch_section_plane(&p, nx, 0.3, 1e-3, &s);
    worst = 0;
    for (int i = 0; i < s.npts; ++i) {
        const double *x = s.pts + 3 * i;
        worst = fmax(worst, fmax(fabs(x[2] - 0.09 - x[1] * x[1]), fabs(x[0] - 0.3)));
    }
    CHECK(st == CJ_OK && s.nlines == 1 && !s.closed[0] && worst <= 1e-13,
          "paraboloid x = 0.3: status %d, %d lines, %g off the parabola", (int)st, s.nlines, worst);
    printf("paraboloid x = 0.3: one open line of %d points on z = 0.09 + y^2 (within %.2g)\n",
           s.npts, worst);
    cj_patch_section_free(&s);

    st = cj_patch_section_plane(&p, nz, 0.0, 1e-3, &s);
    double far = 0;
    for (int i = 0; i < s.npts; ++i)
        far = fmax(far, sqrt(s.pts[3 * i] * s.pts[3 * i] + s.pts[3 * i + 1] * s.pts[3 * i + 1]));
    for (int i = 0; i < s.nunresolved; ++i)
        far = fmax(far, hypot(s.unresolved[3 * i], s.unresolved[3 * i + 1]));
    CHECK(st == CJ_OK && s.npts + s.nunresolved > 0 && far <= 2e-3,
          "tangent plane z = 0: %d points, %d unresolved, farthest %g from the origin", s.npts,
          s.nunresolved, far);
    printf("paraboloid z = 0 (tangent at the origin): %d points, %d unresolved, all within %.2g "
           "of the origin\n",
           s.npts, s.nunresolved, far);
    cj_patch_section_free(&s);

    st = cj_patch_section_plane(&p, nz, -0.01, 1e-3, &s);
    CHECK(st == CJ_OK && s.npts == 0 && s.nunresolved == 0,
          "z = -0.01: status %d, %d points, %d unresolved (should be proven empty)", (int)st,
          s.npts, s.nunresolved);
    printf("paraboloid z = -0.01: proven empty in %ld cells\n", s.cells);
    cj_patch_section_free(&s);
}

/* ---- random patches against the line oracle ------------------------------------------------ */

static double oracle_f(const cj_patch *p, const double n[3], double d, long double u,
                       long double v) {
    long double x[3];
    oracle_eval(p, u, v, x);
    return (double)(n[0] * x[0] + n[1] * x[1] + n[2] * x[2] - d);
}

static void check_random(void) {
    cj_rng rng;
    const uint64_t seed = 0x5ec7105eedULL;
    cj_rng_init(&rng, seed);
    long crossings = 0;
    int cases = 40, lines = 0;
    double worst_ratio = 0, worst_gap = 0;
    for (int c = 0; c < cases; ++c) {
        int rational = c % 4 == 3;
        double pts[48], w[16];
        for (int i = 0; i < 16; ++i) {
            pts[3 * i] = (i % 4) / 3.0 + cj_rng_range(&rng, -0.2, 0.2);
            pts[3 * i + 1] = (i / 4) / 3.0 + cj_rng_range(&rng, -0.2, 0.2);
            pts[3 * i + 2] = cj_rng_range(&rng, -0.5, 0.5);
            w[i] = cj_rng_range(&rng, 0.5, 2.0);
        }
        cj_patch p = cj_patch_view(3, 3, pts, rational ? w : NULL);
        double n[3] = {cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1),
                       cj_rng_range(&rng, -1, 1)};
        long double x0[3];
        oracle_eval(&p, cj_rng_unit(&rng), cj_rng_unit(&rng), x0);
        double d = (double)(n[0] * x0[0] + n[1] * x0[1] + n[2] * x0[2]);
        double tol = 2e-3;
        cj_patch_section s;
        cj_status st = cj_patch_section_plane(&p, n, d, tol, &s);
        CHECK(st == CJ_OK, "random %d: status %d", c, (int)st);
        if (st != CJ_OK) continue;
        CHECK(s.deviation <= tol, "random %d: deviation %g", c, s.deviation);
        worst_gap = fmax(worst_gap, s.plane_gap / sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
        for (int l = 0; l < 120; ++l) {
            long double v = (l + 0.5L) / 120;
            int N = 1500;
            double fprev = oracle_f(&p, n, d, 0, v);
            ++lines;
            for (int k = 1; k <= N; ++k) {
                long double u = (long double)k / N;
                double fk = oracle_f(&p, n, d, u, v);
                if ((fprev < 0) != (fk < 0)) {
                    long double a = (long double)(k - 1) / N, b = u;
                    int sa = fprev < 0;
                    for (int it = 0; it < 64; ++it) {
                        long double mid = 0.5L * (a + b);
                        if ((oracle_f(&p, n, d, mid, v) < 0) == sa)
                            a = mid;
                        else
                            b = mid;
                    }
                    long double xr[3];
                    oracle_eval(&p, 0.5L * (a + b), v, xr);
                    double x[3] = {(double)xr[0], (double)xr[1], (double)xr[2]};
                    double dist = dist_to_section(&s, x);
                    ++crossings;
                    worst_ratio = fmax(worst_ratio, dist / s.deviation);
                    CHECK(dist <= s.deviation + 1e-12,
                          "random %d (seed %#llx): crossing at v = %.6Lf is %g from the section, "
                          "deviation %g",
                          c, (unsigned long long)seed, v, dist, s.deviation);
                }
                fprev = fk;
            }
        }
        cj_patch_section_free(&s);
    }
    printf("random bicubic patches (seed %#llx, every fourth rational): %d cases, %d lines, %ld "
           "oracle crossings, none farther than the proven deviation (worst at %.2f of it); "
           "crossings at most %.2g off the plane\n",
           (unsigned long long)seed, cases, lines, crossings, worst_ratio, worst_gap);
    CHECK(worst_gap <= 1e-13, "a crossing %g off the plane", worst_gap);
}

static void check_bad_input(void) {
    double pts[27], w[9];
    sphere_octant(pts, w);
    cj_patch p = cj_patch_view(2, 2, pts, w);
    cj_patch_section s;
    const double zero[3] = {0, 0, 0}, nz[3] = {0, 0, 1}, nan3[3] = {NAN, 0, 1};
    CHECK(cj_patch_section_plane(&p, zero, 0.5, 1e-3, &s) == CJ_ERR_DEGENERATE, "zero normal");
    CHECK(strstr(cj_last_error(), "normal") != NULL, "message: %s", cj_last_error());
    CHECK(cj_patch_section_plane(&p, nan3, 0.5, 1e-3, &s) == CJ_ERR_NONFINITE, "NaN normal");
    CHECK(cj_patch_section_plane(&p, nz, NAN, 1e-3, &s) == CJ_ERR_NONFINITE, "NaN d");
    CHECK(cj_patch_section_plane(&p, nz, 0.5, 1e-20, &s) == CJ_ERR_ARGUMENT, "tol too small");
    CHECK(strstr(cj_last_error(), "tol") != NULL, "message: %s", cj_last_error());
    CHECK(cj_patch_section_plane(&p, nz, 0.5, NAN, &s) == CJ_ERR_ARGUMENT, "NaN tol");
    w[4] = -1;
    CHECK(cj_patch_section_plane(&p, nz, 0.5, 1e-3, &s) == CJ_ERR_ARGUMENT, "negative weight");
    static double big[3 * 17 * 17];
    cj_patch q = cj_patch_view(16, 16, big, NULL);
    CHECK(cj_patch_section_plane(&q, nz, 0.5, 1e-3, &s) == CJ_ERR_DEGREE, "degree 16");
    printf("bad input: zero and NaN normal, NaN d, tol too small and NaN, a negative weight, "
           "degree 16: refused\n");
}

int main(void) {
    check_sphere();
    check_paraboloid();
    check_random();
    check_bad_input();
    return cj_check_exit();
}
