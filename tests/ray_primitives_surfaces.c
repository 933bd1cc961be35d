/* Ray–primitive intersection, second part of test_ray_primitives: the torus (roots of the
 * quartic located in MPFR), Bézier patches directly, triangles against MPFR barycentrics,
 * polygons and planar/bilinear patches, and offsets of secondary origins (no acne at 1e6 scale,
 * no leaking at 1e-6). test_ray_primitives.c holds the quadrics and runs these. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/analytic.h"
#include "casteljau/bvh.h"
#include "casteljau/mesh.h"
#include "casteljau/quadric.h"
#include "casteljau/ray.h"
#include "casteljau/tessellate.h"
#include "ray_primitives_test.h"
#include "rng.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <stdlib.h>

#define PREC 320

/* ---- torus: MPFR g(s) along the ray, roots by sampling + bisection ----------------------- */

static int torus_sign(const cj_torus *to, cj_vec3 o, cj_vec3 d, double t, double *mag) {
    mpfr_t w[3], s, w2, h, tmp, G;
    mpfr_inits2(PREC, s, w2, h, tmp, G, (mpfr_ptr)0);
    const double oc[3] = {o.x - 0.0, o.y, o.z}, dc[3] = {d.x, d.y, d.z};
    const double cc[3] = {to->center.x, to->center.y, to->center.z};
    const double ac[3] = {to->a.x, to->a.y, to->a.z};
    mpfr_set_d(w2, 0, MPFR_RNDN);
    mpfr_set_d(h, 0, MPFR_RNDN);
    for (int k = 0; k < 3; k++) {
        mpfr_init2(w[k], PREC);
        mpfr_set_d(w[k], dc[k], MPFR_RNDN);
        mpfr_mul_d(w[k], w[k], t, MPFR_RNDN);
        mpfr_add_d(w[k], w[k], oc[k], MPFR_RNDN);
        mpfr_sub_d(w[k], w[k], cc[k], MPFR_RNDN);
        mpfr_fma(w2, w[k], w[k], w2, MPFR_RNDN);
        mpfr_mul_d(tmp, w[k], ac[k], MPFR_RNDN);
        mpfr_add(h, h, tmp, MPFR_RNDN);
    }
    mpfr_sqr(h, h, MPFR_RNDN);
    mpfr_sub(h, w2, h, MPFR_RNDN); /* |w|² - (w.a)² */
    mpfr_set_d(tmp, to->major, MPFR_RNDN);
    mpfr_sqr(tmp, tmp, MPFR_RNDN); /* R² */
    mpfr_set_d(s, to->minor, MPFR_RNDN);
    mpfr_sqr(s, s, MPFR_RNDN);
    mpfr_add(G, w2, tmp, MPFR_RNDN);
    mpfr_sub(G, G, s, MPFR_RNDN);
    mpfr_sqr(G, G, MPFR_RNDN);
    mpfr_mul(h, h, tmp, MPFR_RNDN);
    mpfr_mul_ui(h, h, 4, MPFR_RNDN);
    mpfr_sub(G, G, h, MPFR_RNDN);
    int sg = mpfr_sgn(G);
    if (mag) *mag = fabs(mpfr_get_d(G, MPFR_RNDN));
    mpfr_clears(s, w2, h, tmp, G, (mpfr_ptr)0);
    for (int k = 0; k < 3; k++) mpfr_clear(w[k]);
    return sg;
}

static double torus_first_root(const cj_torus *to, cj_vec3 o, cj_vec3 d, double t0, double t1) {
    const int N = 300;
    double prev_t = t0;
    int prev = torus_sign(to, o, d, t0, NULL);
    for (int i = 1; i <= N; i++) {
        double t = t0 + (t1 - t0) * i / N;
        int sg = torus_sign(to, o, d, t, NULL);
        if (sg != prev && sg != 0 && prev != 0) {
            double a = prev_t, b = t;
            for (int it = 0; it < 80; it++) {
                double m = 0.5 * (a + b);
                int sm = torus_sign(to, o, d, m, NULL);
                if (sm == prev)
                    a = m;
                else
                    b = m;
            }
            return 0.5 * (a + b);
        }
        if (sg == 0) return t;
        prev = sg;
        prev_t = t;
    }
    return NAN;
}

void test_torus(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 3);
    long n = 0, hits = 0, early = 0;
    double worst = 0;
    for (int i = 0; i < 400; i++) {
        cj_torus to;
        double R = cj_rng_range(&r, 0.5, 2), rho = R * cj_rng_range(&r, 0.1, 0.6);
        cj_vec3 c =
            cj_v3(cj_rng_range(&r, -2, 2), cj_rng_range(&r, -2, 2), cj_rng_range(&r, -2, 2));
        assert_int_equal(cj_torus_init(&to, c, rp_rand_unit(&r), R, rho), CJ_OK);
        double ang = cj_rng_range(&r, 0, 6.3), tube = cj_rng_range(&r, 0, 6.3);
        cj_vec3 er = cj_v3_add(cj_v3_scale(to.e1, cos(ang)), cj_v3_scale(to.e2, sin(ang)));
        cj_vec3 s = cj_v3_add(
            c, cj_v3_add(cj_v3_scale(er, R + rho * cos(tube)), cj_v3_scale(to.a, rho * sin(tube))));
        cj_vec3 o =
            cj_v3_add(c, cj_v3_scale(rp_rand_unit(&r), cj_rng_range(&r, 0.0, 3 * (R + rho))));
        cj_vec3 d = cj_v3_sub(cj_v3_add(s, cj_v3_scale(rp_rand_unit(&r), 0.2 * rho)), o);
        cj_ray ray = {o, d, 0.0, INFINITY};
        cj_hit h;
        int got = cj_ray_torus(&ray, &to, &h);
        /* Oracle interval: where the ray is within the bounding sphere. */
        double dd = cj_v3_dot(d, d), b = cj_v3_dot(cj_v3_sub(o, c), d) / dd;
        double cc =
            (cj_v3_dot(cj_v3_sub(o, c), cj_v3_sub(o, c)) - (R + rho) * (R + rho) * 1.0001) / dd;
        double disc = b * b - cc;
        double texp = NAN;
        if (disc > 0) {
            double t0 = fmax(0.0, -b - sqrt(disc)), t1 = -b + sqrt(disc);
            if (t1 > 0) texp = torus_first_root(&to, o, d, t0, t1);
        }
        n++;
        if (got) {
            /* Ours must be a genuine root: a sign change of g within 1e-9 (MPFR). */
            double dt = 1e-9 * fmax(1.0, h.t);
            int sa = torus_sign(&to, o, d, h.t - dt, NULL),
                sb = torus_sign(&to, o, d, h.t + dt, NULL);
            if (sa == sb) {
                double mag;
                torus_sign(&to, o, d, h.t, &mag);
                fprintf(stderr, "torus ray %d: t = %.17g is no sign change (|g| = %g)\n", i, h.t,
                        mag);
            }
            assert_true(sa != sb || sa == 0);
            hits++;
        }
        if (!isnan(texp)) {
            if (!got) fprintf(stderr, "torus ray %d: missed, oracle root %.17g\n", i, texp);
            assert_true(got);
            double e = fabs(h.t - texp) / fmax(1.0, texp);
            if (h.t < texp - 1e-9)
                early++; /* a root pair closer than the oracle's sampling */
            else {
                if (e > worst) worst = e;
                assert_true(e <= 1e-9);
            }
        }
    }
    /* Tangent rays: along the outer equator (double root) and through the inner one. */
    cj_torus to;
    assert_int_equal(cj_torus_init(&to, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 1.0, 0.25), CJ_OK);
    cj_hit h;
    cj_ray in = {cj_v3(-5, 1.25 - 1e-7, 0), cj_v3(1, 0, 0), 0, INFINITY};
    cj_ray out = {cj_v3(-5, 1.25 + 1e-7, 0), cj_v3(1, 0, 0), 0, INFINITY};
    cj_ray top = {cj_v3(0, -5, 0.25 - 1e-7), cj_v3(0, 1, 0), 0, INFINITY};
    assert_true(cj_ray_torus(&in, &to, &h));
    assert_true(fabs(h.t - 5.0) < 1e-3); /* the chord is 2 sqrt(2 · 1.25 · 1e-7) ≈ 1e-3 long */
    assert_false(cj_ray_torus(&out, &to, &h));
    assert_true(cj_ray_torus(&top, &to, &h));
    assert_true(h.t > 3.9 && h.t < 4.1 && fabs(h.n.z - 1.0) < 1e-3);
    printf("  torus: %ld rays, %ld hits (each a sign change of g in MPFR within 1e-9), worst "
           "|t - t_MPFR| = %.2e, %ld earlier grazing roots the 300-sample oracle skipped; tangent "
           "rays 1e-7 inside hit, 1e-7 outside miss\n",
           n, hits, worst, early);
}

/* ---- Bézier patches directly ---------------------------------------------------------------- */

static long double bern_ld(int n, int i, long double t) {
    long double c = 1;
    for (int k = 1; k <= i; k++) c = c * (n - i + k) / k;
    return c * powl(t, i) * powl(1 - t, n - i);
}

void test_patches(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 4);
    long n = 0, hits = 0, mesh_only = 0, direct_only = 0;
    double worst_err = 0, worst_dt = 0;
    const double tol = 1e-9;
    cj_ray_patch_stats stats = {0};
    for (int pi = 0; pi < 24; pi++) {
        int rational = pi % 3 == 2;
        double pts[48], w[16];
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++) {
                double *p = pts + 3 * (j * 4 + i);
                p[0] = i / 3.0 + cj_rng_range(&r, -0.1, 0.1);
                p[1] = j / 3.0 + cj_rng_range(&r, -0.1, 0.1);
                p[2] = cj_rng_range(&r, -0.6, 0.6);
                w[j * 4 + i] = cj_rng_range(&r, 0.5, 2.0);
            }
        cj_patch P = cj_patch_view(3, 3, pts, rational ? w : NULL);
        assert_int_equal(cj_ray_patch_check(&P, tol), CJ_OK);
        cj_mesh *m;
        assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
        cj_tess_options opt = {0};
        opt.tol = 1e-3;
        cj_tess_report rep;
        assert_int_equal(cj_tessellate_patches(&P, 1, &opt, m, &rep), CJ_OK);
        cj_bvh *bvh;
        assert_int_equal(cj_bvh_mesh_build(m->positions, m->vertex_count, m->triangles,
                                           m->triangle_count, NULL, &bvh),
                         CJ_OK);
        for (int k = 0; k < 100; k++) {
            cj_vec3 tg = cj_v3(cj_rng_range(&r, -0.1, 1.1), cj_rng_range(&r, -0.1, 1.1), 0);
            cj_vec3 o = cj_v3(cj_rng_range(&r, -1, 2), cj_rng_range(&r, -1, 2), k % 2 ? 3 : -3);
            cj_ray ray = {o, cj_v3_sub(tg, o), 0.0, INFINITY};
            cj_hit h, hm = {0}, tmp;
            int got = cj_ray_patch(&ray, &P, tol, &h, &stats);
            (void)tmp;
            int gm = cj_bvh_mesh_closest(bvh, &ray, &hm, NULL);
            n++;
            double len = cj_v3_norm(ray.dir);
            if (got) {
                hits++;
                /* Independent check in long double: S(u, v) lies within tol of the ray. */
                long double S[3] = {0, 0, 0}, W = 0;
                for (int j = 0; j < 4; j++)
                    for (int i = 0; i < 4; i++) {
                        long double bb = bern_ld(3, i, h.u) * bern_ld(3, j, h.v) *
                                         (rational ? w[j * 4 + i] : 1.0);
                        for (int q = 0; q < 3; q++) S[q] += bb * pts[3 * (j * 4 + i) + q];
                        W += bb;
                    }
                long double dx[3] = {S[0] / W - o.x, S[1] / W - o.y, S[2] / W - o.z};
                long double dn[3] = {ray.dir.x / len, ray.dir.y / len, ray.dir.z / len};
                long double along = dx[0] * dn[0] + dx[1] * dn[1] + dx[2] * dn[2], perp = 0;
                for (int q = 0; q < 3; q++)
                    perp += (dx[q] - along * dn[q]) * (dx[q] - along * dn[q]);
                double dist = (double)sqrtl(perp);
                if (dist > worst_err) worst_err = dist;
                assert_true(dist <= tol * 1.01 + 1e-15);
            }
            /* Against the mesh (bound rep.bound): hits agree away from the patch border and
             * grazing; the direct hit is never farther than the mesh's by more than the bound. */
            double cosang = got ? fabs(cj_v3_dot(h.n, ray.dir)) / len : 1;
            double slack = 4 * rep.bound / fmax(cosang, 0.05) / len;
            if (got && gm) {
                double dt = (h.t - hm.t) * len;
                if (fabs(dt) > worst_dt) worst_dt = fabs(dt);
                assert_true(h.t <= hm.t + slack);
            } else if (gm && !got) {
                mesh_only++;
            } else if (got && !gm) {
                direct_only++;
            }
        }
        cj_bvh_destroy(bvh);
        cj_mesh_destroy(m);
    }
    /* Disagreements are rays through the thin band between the patch border and the mesh. */
    assert_true(mesh_only + direct_only <= n / 100);
    printf("  bicubic patches (1/3 rational), tol %.0e: %ld rays, %ld hits; worst distance of "
           "S(u,v) (long double) to the ray %.2e; vs a 1e-3 tessellation (BVH): worst |t - t_mesh| "
           "%.2e, %ld/%ld hit only by mesh/direct (border band); %llu boxes, %llu Newton solves "
           "(%llu converged)\n",
           tol, n, hits, worst_err, worst_dt, mesh_only, direct_only,
           (unsigned long long)stats.boxes, (unsigned long long)stats.newton,
           (unsigned long long)stats.newton_ok);
}

/* ---- triangles against MPFR barycentrics ---------------------------------------------------- */

void test_triangles(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 5);
    long n = 0, hits = 0, near = 0;
    double worst = 0, worst_pe = 0;
    for (int i = 0; i < 10000; i++) {
        cj_vec3 v[3];
        for (int k = 0; k < 3; k++) v[k] = cj_v3_scale(rp_rand_unit(&r), cj_rng_range(&r, 0.1, 3));
        cj_vec3 o = cj_v3_scale(rp_rand_unit(&r), 6);
        cj_vec3 tg = cj_v3_add(cj_v3_scale(cj_v3_add(cj_v3_add(v[0], v[1]), v[2]), 1.0 / 3),
                               cj_v3_scale(rp_rand_unit(&r), 1.5));
        cj_ray ray = {o, cj_v3_sub(tg, o), 0.0, INFINITY};
        /* Solve o + t d = b0 v0 + b1 v1 + b2 v2 with b0 = 1 - b1 - b2 by Cramer in MPFR:
         * [v1-v0, v2-v0, -d] (b1, b2, t) = o - v0. */
        mpfr_t M[3][3], rhs[3], det, tmp, sol[3];
        cj_vec3 c0 = cj_v3_sub(v[1], v[0]), c1 = cj_v3_sub(v[2], v[0]);
        (void)c0;
        (void)c1;
        const double cols[3][3] = {{v[1].x, v[1].y, v[1].z},
                                   {v[2].x, v[2].y, v[2].z},
                                   {-ray.dir.x, -ray.dir.y, -ray.dir.z}};
        const double v0c[3] = {v[0].x, v[0].y, v[0].z}, oc[3] = {o.x, o.y, o.z};
        mpfr_inits2(PREC, det, tmp, (mpfr_ptr)0);
        for (int a = 0; a < 3; a++) {
            mpfr_init2(rhs[a], PREC);
            mpfr_set_d(rhs[a], oc[a], MPFR_RNDN);
            mpfr_sub_d(rhs[a], rhs[a], v0c[a], MPFR_RNDN);
            mpfr_init2(sol[a], PREC);
            for (int b = 0; b < 3; b++) {
                mpfr_init2(M[a][b], PREC);
                mpfr_set_d(M[a][b], cols[b][a], MPFR_RNDN);
                if (b < 2) mpfr_sub_d(M[a][b], M[a][b], v0c[a], MPFR_RNDN);
            }
        }
        /* det of 3x3 and Cramer */
#define DET3(X)                                                                                    \
    do {                                                                                           \
        mpfr_set_d(X, 0, MPFR_RNDN);                                                               \
        for (int p = 0; p < 3; p++) {                                                              \
            mpfr_t cf;                                                                             \
            mpfr_init2(cf, PREC);                                                                  \
            mpfr_mul(cf, C[1][(p + 1) % 3], C[2][(p + 2) % 3], MPFR_RNDN);                         \
            mpfr_mul(tmp, C[1][(p + 2) % 3], C[2][(p + 1) % 3], MPFR_RNDN);                        \
            mpfr_sub(cf, cf, tmp, MPFR_RNDN);                                                      \
            mpfr_fma(X, C[0][p], cf, X, MPFR_RNDN);                                                \
            mpfr_clear(cf);                                                                        \
        }                                                                                          \
    } while (0)
        mpfr_ptr C[3][3];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) C[a][b] = M[a][b];
        DET3(det);
        for (int col = 0; col < 3; col++) {
            for (int a = 0; a < 3; a++) C[a][col] = rhs[a];
            DET3(sol[col]);
            mpfr_div(sol[col], sol[col], det, MPFR_RNDN);
            for (int a = 0; a < 3; a++) C[a][col] = M[a][col];
        }
        double b1 = mpfr_get_d(sol[0], MPFR_RNDN), b2 = mpfr_get_d(sol[1], MPFR_RNDN);
        double t = mpfr_get_d(sol[2], MPFR_RNDN), b0 = 1 - b1 - b2;
        for (int a = 0; a < 3; a++) {
            mpfr_clear(rhs[a]);
            mpfr_clear(sol[a]);
            for (int b = 0; b < 3; b++) mpfr_clear(M[a][b]);
        }
        mpfr_clears(det, tmp, (mpfr_ptr)0);
        cj_hit h;
        int got = cj_ray_triangle(&ray, v[0], v[1], v[2], &h);
        n++;
        double mn = fmin(b0, fmin(b1, b2));
        if (fabs(mn) < 1e-12 || fabs(t) < 1e-12) {
            near++;
            continue;
        }
        int exp_hit = mn > 0 && t > 0;
        assert_int_equal(got, exp_hit);
        if (got) {
            hits++;
            double e = fabs(h.t - t) / fmax(1, t);
            if (e > worst) worst = e;
            assert_true(e < 1e-12);
            assert_true(fabs(h.u - b1) < 1e-12 && fabs(h.v - b2) < 1e-12);
            /* The point is on the triangle's plane within p_err (what offsetting needs):
             * its distance to the plane in long double. */
            long double e1[3] = {(long double)v[1].x - v[0].x, (long double)v[1].y - v[0].y,
                                 (long double)v[1].z - v[0].z};
            long double e2[3] = {(long double)v[2].x - v[0].x, (long double)v[2].y - v[0].y,
                                 (long double)v[2].z - v[0].z};
            long double nl[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                 e1[0] * e2[1] - e1[1] * e2[0]};
            long double nn = sqrtl(nl[0] * nl[0] + nl[1] * nl[1] + nl[2] * nl[2]);
            long double dist = fabsl(nl[0] * (h.p.x - (long double)v[0].x) +
                                     nl[1] * (h.p.y - (long double)v[0].y) +
                                     nl[2] * (h.p.z - (long double)v[0].z)) /
                               nn;
            double allowed =
                (fabsl(nl[0]) * h.p_err.x + fabsl(nl[1]) * h.p_err.y + fabsl(nl[2]) * h.p_err.z) /
                nn;
            if ((double)dist / allowed > worst_pe) worst_pe = (double)dist / allowed;
            assert_true((double)dist <= allowed);
        }
    }
    printf("  triangles: %ld random rays, %ld hits; hit/miss equals MPFR barycentrics wherever "
           "they are 1e-12 clear of an edge (%ld within, skipped); worst relative t error %.2e; "
           "distance of p to the plane (long double) / p_err bound <= %.3f\n",
           n, hits, near, worst, worst_pe);
}

/* ---- polygons, planar and bilinear patches ----------------------------------------------------
 */

void test_polygons_and_planar(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 6);
    long n = 0, agree = 0, near = 0;
    for (int i = 0; i < 3000; i++) {
        /* A star-shaped non-convex polygon about c in a random plane, and its fan. */
        int k = cj_rng_int(&r, 3, 10);
        cj_vec3 c =
            cj_v3(cj_rng_range(&r, -3, 3), cj_rng_range(&r, -3, 3), cj_rng_range(&r, -3, 3));
        cj_vec3 nn = rp_rand_unit(&r), e1, e2;
        cj_frame_from_axis(nn, &e1, &e2);
        double pts[30];
        cj_vec3 vv[10];
        for (int j = 0; j < k; j++) {
            double a = 6.283185307179586 * (j + cj_rng_range(&r, 0.1, 0.9)) / k,
                   rad = cj_rng_range(&r, 0.3, 2);
            vv[j] = cj_v3_add(
                c, cj_v3_add(cj_v3_scale(e1, rad * cos(a)), cj_v3_scale(e2, rad * sin(a))));
            pts[3 * j] = vv[j].x;
            pts[3 * j + 1] = vv[j].y;
            pts[3 * j + 2] = vv[j].z;
        }
        cj_vec3 o = cj_v3_add(c, cj_v3_scale(rp_rand_unit(&r), 5));
        cj_vec3 tg = cj_v3_add(c, cj_v3_scale(rp_rand_unit(&r), 1.5));
        cj_ray ray = {o, cj_v3_sub(tg, o), 0.0, INFINITY};
        cj_hit hp, ht;
        int gp = cj_ray_polygon(&ray, pts, (size_t)k, &hp);
        int gt = 0;
        double bmin = INFINITY;
        for (int j = 0; j < k; j++)
            if (cj_ray_triangle(&ray, c, vv[j], vv[(j + 1) % k], &ht)) {
                gt = 1;
                bmin = fmin(ht.u, ht.v);
            }
        n++;
        /* The fan's inner spokes are not polygon edges: only rays near the rim are uncertain. */
        if (gp != gt) {
            near++;
            continue;
        }
        if (gp) assert_true(fabs(hp.t - ht.t) <= 1e-12 * fmax(1, ht.t));
        (void)bmin;
        agree++;
    }
    assert_true(near <= n / 500);
    /* Planar patch and bilinear patch: exact (u, v) back to the point. */
    cj_planar_patch pp;
    assert_int_equal(cj_planar_patch_init(&pp, cj_v3(1, 0, 0), cj_v3(2, 0.5, 0), cj_v3(0.1, 1, 1)),
                     CJ_OK);
    cj_bilinear bl;
    assert_int_equal(cj_bilinear_init(&bl, cj_v3(0, 0, 0), cj_v3(1, 0, 0.5), cj_v3(0, 1, 0.2),
                                      cj_v3(1, 1, -0.4)),
                     CJ_OK);
    long pl = 0, bi = 0;
    for (int i = 0; i < 2000; i++) {
        double u = cj_rng_range(&r, -0.2, 1.2), v = cj_rng_range(&r, -0.2, 1.2);
        cj_vec3 s = cj_v3_add(pp.p, cj_v3_add(cj_v3_scale(pp.eu, u), cj_v3_scale(pp.ev, v)));
        cj_vec3 o = cj_v3_add(s, cj_v3_scale(rp_rand_unit(&r), 4));
        cj_ray ray = {o, cj_v3_sub(s, o), 0.0, INFINITY};
        cj_hit h;
        int got = cj_ray_planar(&ray, &pp, &h);
        int inside = u >= 0 && u <= 1 && v >= 0 && v <= 1;
        if (fmin(fmin(fabs(u), fabs(u - 1)), fmin(fabs(v), fabs(v - 1))) > 1e-9) {
            assert_int_equal(got, inside);
            if (got)
                assert_true(fabs(h.u - u) < 1e-12 && fabs(h.v - v) < 1e-12 &&
                            fabs(h.t - 1) < 1e-12);
            pl++;
        }
        cj_vec3 sb = cj_v3_add(
            cj_v3_add(cj_v3_scale(bl.p00, (1 - u) * (1 - v)), cj_v3_scale(bl.p10, u * (1 - v))),
            cj_v3_add(cj_v3_scale(bl.p01, (1 - u) * v), cj_v3_scale(bl.p11, u * v)));
        cj_vec3 nb = cj_v3(0, 0, 1);
        cj_ray rb = {cj_v3_add(sb, cj_v3_scale(nb, 3)), cj_v3_scale(nb, -1), 0.0, INFINITY};
        got = cj_ray_bilinear(&rb, &bl, 1e-12, &h);
        if (fmin(fmin(fabs(u), fabs(u - 1)), fmin(fabs(v), fabs(v - 1))) > 1e-6) {
            assert_int_equal(got, inside);
            if (got)
                assert_true(fabs(h.u - u) < 1e-9 && fabs(h.v - v) < 1e-9 && fabs(h.t - 3) < 1e-9);
            bi++;
        }
    }
    printf("  polygons (non-convex, random planes): %ld rays, %ld agree with the fan, %ld differ "
           "within the rounding band at an edge; planar patch %ld and bilinear patch %ld rays: "
           "(u, v) and t exact to 1e-12 / 1e-9\n",
           n, agree, near, pl, bi);
}

/* ---- offsetting secondary origins --------------------------------------------------------------
 */

void test_offsets(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 7);
    long self_hits = 0, n = 0;
    double worst_rel = 0;
    const double scales[2] = {1e6, 1e-6};
    for (int si = 0; si < 2; si++) {
        double L = scales[si];
        cj_vec3 far = cj_v3(3 * L, -2 * L, 5 * L); /* far from the origin: large coordinates */
        cj_torus to;
        assert_int_equal(cj_torus_init(&to, far, rp_rand_unit(&r), L, 0.3 * L), CJ_OK);
        cj_quadric q;
        assert_int_equal(cj_quadric_ellipsoid(&q, L, 0.7 * L, 0.4 * L), CJ_OK);
        cj_xform3 T = cj_xform3_translate(far.x, far.y, far.z);
        cj_ray_xform x;
        assert_int_equal(cj_ray_xform_init(&x, &T), CJ_OK);
        /* a wavy bicubic patch of size 2L */
        double bp[48];
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++) {
                bp[3 * (4 * j + k)] = far.x + L * (2.0 * k / 3 - 1);
                bp[3 * (4 * j + k) + 1] = far.y + L * (2.0 * j / 3 - 1);
                bp[3 * (4 * j + k) + 2] = far.z + L * (((j + k) % 2) ? 0.7 : -0.4);
            }
        cj_patch P = cj_patch_view(3, 3, bp, NULL);
        for (int i = 0; i < 7500; i++) {
            int kind = i % 5;
            cj_vec3 o = cj_v3_add(far, cj_v3_scale(rp_rand_unit(&r), 4 * L));
            cj_vec3 tg = cj_v3_add(far, cj_v3_scale(rp_rand_unit(&r), 0.5 * L));
            cj_ray ray = {o, cj_v3_sub(tg, o), 0.0, INFINITY};
            cj_hit h;
            int got = 0;
            cj_vec3 tv[3] = {cj_v3_add(far, cj_v3(L, 0, 0)), cj_v3_add(far, cj_v3(-L, L, 0.3 * L)),
                             cj_v3_add(far, cj_v3(0, -L, -0.2 * L))};
            if (kind == 0)
                got = cj_ray_sphere(&ray, far, L, &h);
            else if (kind == 1)
                got = cj_ray_torus(&ray, &to, &h);
            else if (kind == 2)
                got = cj_ray_triangle(&ray, tv[0], tv[1], tv[2], &h);
            else if (kind == 4)
                got = cj_ray_patch(&ray, &P, 1e-7 * L, &h, NULL);
            else {
                cj_ray ro;
                cj_ray_to_object(&x, &ray, &ro);
                got = cj_ray_quadric(&ro, &q, &h);
                if (got) cj_hit_to_world(&x, &h);
            }
            if (!got) continue;
            /* Leave to both sides: reflection-like (same side as the ray came from) and
             * refraction-like (through the surface). */
            for (int side = 0; side < 2; side++) {
                cj_vec3 nf = cj_v3_dot(h.ng, ray.dir) < 0 ? h.ng : cj_v3_scale(h.ng, -1);
                if (side) nf = cj_v3_scale(nf, -1);
                cj_vec3 w = cj_v3_normalize(cj_v3_add(nf, cj_v3_scale(rp_rand_unit(&r), 0.9)));
                if (cj_v3_dot(w, nf) <= 0.05) continue;
                cj_vec3 po = cj_ray_offset_origin(&h, w);
                double rel = cj_v3_norm(cj_v3_sub(po, h.p)) / L;
                if (rel > worst_rel) worst_rel = rel;
                assert_true(rel < 1e-6); /* no leaking: the offset is tiny against the geometry */
                cj_ray sr = {po, w, 0.0, INFINITY};
                cj_hit h2;
                int again = 0;
                if (kind == 0)
                    again = cj_ray_sphere(&sr, far, L, &h2);
                else if (kind == 1)
                    again = cj_ray_torus(&sr, &to, &h2);
                else if (kind == 2)
                    again = cj_ray_triangle(&sr, tv[0], tv[1], tv[2], &h2);
                else if (kind == 4)
                    again = cj_ray_patch(&sr, &P, 1e-7 * L, &h2, NULL);
                else {
                    cj_ray ro;
                    cj_ray_to_object(&x, &sr, &ro);
                    again = cj_ray_quadric(&ro, &q, &h2);
                    if (again) cj_hit_to_world(&x, &h2);
                }
                n++;
                /* A self-hit is a hit at a distance comparable to the offset (acne). */
                if (again && h2.t * cj_v3_norm(w) < 1e-4 * L) {
                    self_hits++;
                    fprintf(stderr, "offset: scale %g kind %d side %d: re-hit at t = %g\n", L, kind,
                            side, h2.t);
                }
            }
        }
    }
    printf("  offsets (sphere, torus, triangle, placed ellipsoid, bicubic patch at 1e6 and 1e-6 "
           "scale, far from "
           "the origin): %ld secondary rays to both sides, %ld self-hits; largest offset %.2e of "
           "the object's size\n",
           n, self_hits, worst_rel);
    assert_int_equal(self_hits, 0);
}
