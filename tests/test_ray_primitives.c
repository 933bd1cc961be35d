/* Ray–primitive intersection (surfaces/: ray.h) against high-precision oracles:
 *  - triangles: hit/miss and t against barycentrics solved in MPFR (320 bits);
 *  - sphere, the six quadrics (domain limits), cylinder, and an ellipsoid placed by a sheared,
 *    rotated, scaled transform: the quadratic along the ray solved in MPFR from the exact
 *    double inputs; the hit point's distance to the surface (MPFR, first order) <= p_err;
 *  - grazing and tangent rays (1e-7 inside: hit; 1e-7 outside: miss), inside-out rays;
 *  - the torus: roots of the quartic located in MPFR by sampling and bisection; tangent rays;
 *  - Bézier patches directly: distance of S(u,v) (long double) to the ray <= tol, and no
 *    closer hit than the watertight hit of a fine tessellation (beyond its proven bound);
 *  - planar polygons (non-convex) against their triangle fans, planar and bilinear patches;
 *  - offsets of secondary origins: no self-hit (acne) at 1e6 scale, origin within 1e-6 of the
 *    geometry's scale at 1e-6 scale (no leaking).
 * Random rays are seeded (CJ_SEED replays). */
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
#include "rng.h"
#include "ray_primitives_test.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <stdlib.h>

#define PREC 320
uint64_t rp_seed;

cj_vec3 rp_rand_unit(cj_rng *r) {
    for (;;) {
        cj_vec3 p = cj_v3(cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1));
        double n = cj_v3_norm(p);
        if (n > 0.1 && n <= 1.0) return cj_v3_scale(p, 1.0 / n);
    }
}

/* ---- MPFR quadratic oracle for f = al x² + be y² + ga z² + la z + ka along o + t d --------- */

typedef struct mq {
    mpfr_t al, be, ga, la, ka;
} mq;

static void mq_init(mq *q) {
    mpfr_inits2(PREC, q->al, q->be, q->ga, q->la, q->ka, (mpfr_ptr)0);
}
static void mq_clear(mq *q) {
    mpfr_clears(q->al, q->be, q->ga, q->la, q->ka, (mpfr_ptr)0);
}

/* 1/(s*s) with sign. */
static void inv_sq(mpfr_t out, double s, int sign) {
    mpfr_set_d(out, s, MPFR_RNDN);
    mpfr_sqr(out, out, MPFR_RNDN);
    mpfr_ui_div(out, 1, out, MPFR_RNDN);
    if (sign < 0) mpfr_neg(out, out, MPFR_RNDN);
}

static void mq_from_quadric(mq *m, const cj_quadric *q) {
    inv_sq(m->al, q->a, 1);
    inv_sq(m->be, q->b, 1);
    inv_sq(m->ga, q->c, -1);
    mpfr_set_d(m->la, 0, MPFR_RNDN);
    mpfr_set_si(m->ka, -1, MPFR_RNDN);
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        mpfr_neg(m->ga, m->ga, MPFR_RNDN);
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
        break;
    case CJ_QUADRIC_HYPERBOLOID2:
        mpfr_set_si(m->ka, 1, MPFR_RNDN);
        break;
    case CJ_QUADRIC_CONE:
        mpfr_set_si(m->ka, 0, MPFR_RNDN);
        break;
    case CJ_QUADRIC_PARABOLOID:
        mpfr_set_si(m->ga, 0, MPFR_RNDN);
        mpfr_set_si(m->la, -1, MPFR_RNDN);
        mpfr_set_si(m->ka, 0, MPFR_RNDN);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        mpfr_neg(m->al, m->al, MPFR_RNDN);
        mpfr_set_si(m->ga, 0, MPFR_RNDN);
        mpfr_set_si(m->la, 1, MPFR_RNDN);
        mpfr_set_si(m->ka, 0, MPFR_RNDN);
        break;
    }
}

/* f and |grad f| at a double point, in MPFR: returns |f| / |grad f| (first-order distance). */
static double mq_dist(const mq *m, cj_vec3 p) {
    mpfr_t x[3], f, g, s, tmp;
    const double pc[3] = {p.x, p.y, p.z};
    mpfr_inits2(PREC, f, g, s, tmp, (mpfr_ptr)0);
    for (int k = 0; k < 3; k++) {
        mpfr_init2(x[k], PREC);
        mpfr_set_d(x[k], pc[k], MPFR_RNDN);
    }
    mpfr_srcptr co[3] = {m->al, m->be, m->ga};
    mpfr_set(f, m->ka, MPFR_RNDN);
    mpfr_fma(f, m->la, x[2], f, MPFR_RNDN);
    mpfr_set_d(g, 0, MPFR_RNDN);
    for (int k = 0; k < 3; k++) {
        mpfr_sqr(tmp, x[k], MPFR_RNDN);
        mpfr_fma(f, co[k], tmp, f, MPFR_RNDN);
        mpfr_mul(s, co[k], x[k], MPFR_RNDN);
        mpfr_mul_2ui(s, s, 1, MPFR_RNDN);
        if (k == 2) mpfr_add(s, s, m->la, MPFR_RNDN);
        mpfr_sqr(s, s, MPFR_RNDN);
        mpfr_add(g, g, s, MPFR_RNDN);
    }
    mpfr_sqrt(g, g, MPFR_RNDN);
    mpfr_abs(f, f, MPFR_RNDN);
    mpfr_div(f, f, g, MPFR_RNDN);
    double r = mpfr_get_d(f, MPFR_RNDU);
    mpfr_clears(f, g, s, tmp, (mpfr_ptr)0);
    for (int k = 0; k < 3; k++) mpfr_clear(x[k]);
    return r;
}

/* Real roots (ascending) of f(o + t d) = 0; returns their count (0..2); *disc_rel receives
 * disc / b'² (how far from tangent the ray is). */
static int mq_roots(const mq *m, mpfr_t o[3], mpfr_t d[3], double t[2], double *disc_rel) {
    mpfr_t A, B, C, tmp, disc, r0, r1;
    mpfr_inits2(PREC, A, B, C, tmp, disc, r0, r1, (mpfr_ptr)0);
    mpfr_srcptr co[3] = {m->al, m->be, m->ga};
    mpfr_set_d(A, 0, MPFR_RNDN);
    mpfr_mul(B, m->la, d[2], MPFR_RNDN);
    mpfr_div_2ui(B, B, 1, MPFR_RNDN);
    mpfr_set(C, m->ka, MPFR_RNDN);
    mpfr_fma(C, m->la, o[2], C, MPFR_RNDN);
    for (int k = 0; k < 3; k++) {
        mpfr_sqr(tmp, d[k], MPFR_RNDN);
        mpfr_fma(A, co[k], tmp, A, MPFR_RNDN);
        mpfr_mul(tmp, o[k], d[k], MPFR_RNDN);
        mpfr_fma(B, co[k], tmp, B, MPFR_RNDN);
        mpfr_sqr(tmp, o[k], MPFR_RNDN);
        mpfr_fma(C, co[k], tmp, C, MPFR_RNDN);
    }
    mpfr_sqr(disc, B, MPFR_RNDN);
    mpfr_mul(tmp, A, C, MPFR_RNDN);
    mpfr_sub(disc, disc, tmp, MPFR_RNDN);
    int n = 0;
    mpfr_sqr(tmp, B, MPFR_RNDN);
    *disc_rel =
        mpfr_zero_p(tmp) ? INFINITY : mpfr_get_d(disc, MPFR_RNDN) / mpfr_get_d(tmp, MPFR_RNDN);
    if (mpfr_zero_p(A)) {
        if (!mpfr_zero_p(B)) {
            mpfr_div(r0, C, B, MPFR_RNDN);
            mpfr_div_2ui(r0, r0, 1, MPFR_RNDN);
            t[n++] = -mpfr_get_d(r0, MPFR_RNDN);
        }
    } else if (mpfr_sgn(disc) >= 0) {
        mpfr_sqrt(disc, disc, MPFR_RNDN);
        mpfr_neg(tmp, B, MPFR_RNDN);
        mpfr_sub(r0, tmp, disc, MPFR_RNDN);
        mpfr_add(r1, tmp, disc, MPFR_RNDN);
        mpfr_div(r0, r0, A, MPFR_RNDN);
        mpfr_div(r1, r1, A, MPFR_RNDN);
        double a0 = mpfr_get_d(r0, MPFR_RNDN), a1 = mpfr_get_d(r1, MPFR_RNDN);
        t[n++] = fmin(a0, a1);
        t[n++] = fmax(a0, a1);
    }
    mpfr_clears(A, B, C, tmp, disc, r0, r1, (mpfr_ptr)0);
    return n;
}

static void set3(mpfr_t v[3], cj_vec3 a) {
    for (int k = 0; k < 3; k++) mpfr_init2(v[k], PREC);
    mpfr_set_d(v[0], a.x, MPFR_RNDN);
    mpfr_set_d(v[1], a.y, MPFR_RNDN);
    mpfr_set_d(v[2], a.z, MPFR_RNDN);
}
static void clear3(mpfr_t v[3]) {
    for (int k = 0; k < 3; k++) mpfr_clear(v[k]);
}

static int quadric_in_domain(const cj_quadric *q, cj_vec3 p, double slack) {
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        return 1;
    case CJ_QUADRIC_HYPERBOLOID1:
        return p.z >= q->c * sinh(q->v0) - slack && p.z <= q->c * sinh(q->v1) + slack;
    case CJ_QUADRIC_HYPERBOLOID2:
        return q->lower ? (p.z < 0 && -p.z <= q->c * cosh(q->v1) + slack)
                        : (p.z > 0 && p.z <= q->c * cosh(q->v1) + slack);
    case CJ_QUADRIC_CONE:
        return p.z >= q->c * q->v0 - slack && p.z <= q->c * q->v1 + slack;
    case CJ_QUADRIC_PARABOLOID:
        return p.z <= q->v1 * q->v1 + slack;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        return p.x >= q->a * q->u0 - slack && p.x <= q->a * q->u1 + slack &&
               p.y >= q->b * q->v0 - slack && p.y <= q->b * q->v1 + slack;
    }
    return 0;
}

/* Domain test with a margin: 1 inside by more than the margin, 0 outside by more, -1 near. */
static int domain_clear(const cj_quadric *q, cj_vec3 p) {
    int in_lo = quadric_in_domain(q, p, -1e-7), in_hi = quadric_in_domain(q, p, 1e-7);
    if (in_lo) return 1;
    if (!in_hi) return 0;
    return -1;
}

static void test_quadrics(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed);
    long n = 0, hits = 0, skipped = 0;
    double worst_t = 0, worst_perr = 0;
    mq m;
    mq_init(&m);
    for (int kind = 0; kind < 6; kind++) {
        for (int shape = 0; shape < 10; shape++) {
            double a = cj_rng_range(&r, 0.5, 2), b = cj_rng_range(&r, 0.5, 2),
                   c = cj_rng_range(&r, 0.5, 2);
            cj_quadric q;
            cj_status st = CJ_OK;
            switch (kind) {
            case 0:
                st = cj_quadric_ellipsoid(&q, a, b, c);
                break;
            case 1:
                st = cj_quadric_hyperboloid1(&q, a, b, c, -1.0, 0.8);
                break;
            case 2:
                st = cj_quadric_hyperboloid2(&q, a, b, c, shape % 2, 1.2);
                break;
            case 3:
                st = cj_quadric_cone(&q, a, b, c, -0.7, 1.1);
                break;
            case 4:
                st = cj_quadric_paraboloid(&q, a, b, 1.3);
                break;
            case 5:
                st = cj_quadric_hyperbolic_paraboloid(&q, a, b, -1.0, 0.7, -0.6, 1.0);
                break;
            }
            assert_int_equal(st, CJ_OK);
            mq_from_quadric(&m, &q);
            cj_param_surface surf;
            cj_quadric_surface(&q, &surf);
            for (int i = 0; i < 200; i++) {
                /* Aim at a random surface point, from a random origin (some inside). */
                double u = cj_rng_range(&r, surf.u0, surf.u1),
                       v = cj_rng_range(&r, surf.v0, surf.v1);
                cj_vec3 s;
                assert_int_equal(cj_surface_eval(&surf, u, v, &s, NULL, NULL), CJ_OK);
                cj_vec3 o = cj_v3(cj_rng_range(&r, -5, 5), cj_rng_range(&r, -5, 5),
                                  cj_rng_range(&r, -5, 5));
                if (i % 5 == 0) o = cj_v3_scale(s, cj_rng_range(&r, 0.0, 0.9)); /* inside-out */
                cj_vec3 d = cj_v3_sub(cj_v3_add(s, cj_v3_scale(rp_rand_unit(&r), 0.05)), o);
                if (i % 7 == 0) d = cj_v3_scale(d, 1e-3); /* unnormalised directions */
                cj_ray ray = {o, d, 0.0, INFINITY};
                mpfr_t mo[3], md[3];
                set3(mo, o);
                set3(md, d);
                double tr[2], drel;
                int nr = mq_roots(&m, mo, md, tr, &drel);
                clear3(mo);
                clear3(md);
                double texp = NAN;
                int uncertain = drel < 1e-8;
                for (int k = 0; k < nr; k++) {
                    if (fabs(tr[k]) < 1e-9) uncertain = 1;
                    if (tr[k] < 0.0) {
                        continue;
                    }
                    cj_vec3 p = cj_v3_add(o, cj_v3_scale(d, tr[k]));
                    int dc = domain_clear(&q, p);
                    if (dc < 0) uncertain = 1;
                    if (dc == 1) {
                        texp = tr[k];
                        break;
                    }
                    if (dc < 0) break;
                }
                cj_hit h;
                int got = cj_ray_quadric(&ray, &q, &h);
                n++;
                if (uncertain) {
                    skipped++;
                    continue;
                }
                if (isnan(texp)) {
                    if (got)
                        fprintf(stderr, "quadric %d shape %d ray %d: hit at %.17g, oracle: miss\n",
                                kind, shape, i, h.t);
                    assert_false(got);
                    continue;
                }
                if (!got)
                    fprintf(stderr, "quadric %d shape %d ray %d: miss, oracle t = %.17g\n", kind,
                            shape, i, texp);
                assert_true(got);
                hits++;
                double et = fabs(h.t - texp) / fmax(1.0, fabs(texp));
                if (et > worst_t) worst_t = et;
                assert_true(et <= 1e-9);
                double dist = mq_dist(&m, h.p);
                double pe = fmax(h.p_err.x, fmax(h.p_err.y, h.p_err.z));
                if (dist / pe > worst_perr) worst_perr = dist / pe;
                assert_true(dist <= pe);
                assert_true(fabs(cj_v3_norm(h.n) - 1.0) < 1e-12);
            }
        }
    }
    mq_clear(&m);
    printf(
        "  6 quadric kinds x 10 shapes: %ld rays, %ld hits; worst |t - t_exact|/max(1,|t|) = %.2e; "
        "worst distance-to-surface / p_err = %.3f; %ld near tangent/domain edge/origin (skipped)\n",
        n, hits, worst_t, worst_perr, skipped);
}

static void test_sphere_grazing_and_placed(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 1);
    mq m;
    mq_init(&m);
    long graze_in = 0, graze_out = 0;
    for (int i = 0; i < 2000; i++) {
        double rad = exp(cj_rng_range(&r, -3, 3));
        cj_vec3 c =
            cj_v3(cj_rng_range(&r, -10, 10), cj_rng_range(&r, -10, 10), cj_rng_range(&r, -10, 10));
        cj_vec3 d = rp_rand_unit(&r), perp = cj_v3_normalize(cj_v3_cross(d, rp_rand_unit(&r)));
        double off = (i % 2) ? 1.0 - 1e-7 : 1.0 + 1e-7;
        cj_vec3 o = cj_v3_add(cj_v3_sub(c, cj_v3_scale(d, 5 * rad)), cj_v3_scale(perp, off * rad));
        cj_ray ray = {o, d, 0.0, INFINITY};
        cj_hit h;
        int got = cj_ray_sphere(&ray, c, rad, &h);
        if (i % 2) {
            assert_true(got);
            /* Exact: t = 5 rad - sqrt(rad² - (off rad)²) (d ⟂ perp up to rounding). */
            double texp = 5 * rad - rad * sqrt(1 - off * off);
            assert_true(fabs(h.t - texp) <= 1e-6 * rad);
            graze_in++;
        } else {
            assert_false(got);
            graze_out++;
        }
    }
    /* Placed: a unit sphere under shear x rotation x non-uniform scale x translation. */
    inv_sq(m.al, 1, 1);
    inv_sq(m.be, 1, 1);
    inv_sq(m.ga, 1, 1);
    mpfr_set_si(m.la, 0, MPFR_RNDN);
    mpfr_set_si(m.ka, -1, MPFR_RNDN);
    long placed = 0;
    double worst_n = 0;
    for (int i = 0; i < 300; i++) {
        cj_xform3 S = cj_xform3_scale(cj_rng_range(&r, 0.2, 3), cj_rng_range(&r, 0.2, 3),
                                      cj_rng_range(&r, 0.2, 3));
        cj_xform3 H =
            cj_xform3_shear(cj_rng_range(&r, -1, 1), 0.3, 0.0, cj_rng_range(&r, -1, 1), 0.1, 0.0);
        cj_xform3 R;
        assert_int_equal(cj_xform3_rotate_axis(rp_rand_unit(&r), cj_rng_range(&r, 0, 6), &R),
                         CJ_OK);
        cj_xform3 T = cj_xform3_translate(cj_rng_range(&r, -5, 5), 2, 1);
        cj_xform3 M = cj_xform3_compose(&H, &S);
        M = cj_xform3_compose(&R, &M);
        M = cj_xform3_compose(&T, &M);
        cj_ray_xform x;
        assert_int_equal(cj_ray_xform_init(&x, &M), CJ_OK);
        for (int j = 0; j < 20; j++) {
            cj_vec3 target;
            assert_int_equal(cj_xform3_apply_point(&M, cj_v3_scale(rp_rand_unit(&r), 0.7), &target),
                             CJ_OK);
            cj_vec3 o = cj_v3(cj_rng_range(&r, -20, 20), cj_rng_range(&r, -20, 20),
                              cj_rng_range(&r, -20, 20));
            cj_ray ray = {o, cj_v3_sub(target, o), 0.0, INFINITY}, ro;
            cj_ray_to_object(&x, &ray, &ro);
            cj_hit h;
            assert_true(cj_ray_sphere(&ro, cj_v3(0, 0, 0), 1.0, &h));
            cj_hit_to_world(&x, &h);
            /* Oracle: the object-space ray of the double inverse, in MPFR. */
            mpfr_t mo[3], md[3];
            set3(mo, ro.org);
            set3(md, ro.dir);
            double tr[2], drel;
            assert_int_equal(mq_roots(&m, mo, md, tr, &drel), 2);
            clear3(mo);
            clear3(md);
            double texp = tr[0] >= 0 ? tr[0] : tr[1];
            assert_true(fabs(h.t - texp) <= 1e-10 * fmax(1.0, texp));
            /* World normal: M^-T times the object normal, compared with the gradient of the
             * world implicit |M^-1 x|² - 1 at the world point. */
            cj_vec3 ob;
            assert_int_equal(cj_xform3_apply_point(&x.minv, h.p, &ob), CJ_OK);
            cj_vec3 gw =
                cj_v3(x.minv.m[0][0] * ob.x + x.minv.m[1][0] * ob.y + x.minv.m[2][0] * ob.z,
                      x.minv.m[0][1] * ob.x + x.minv.m[1][1] * ob.y + x.minv.m[2][1] * ob.z,
                      x.minv.m[0][2] * ob.x + x.minv.m[1][2] * ob.y + x.minv.m[2][2] * ob.z);
            double ang = cj_v3_norm(cj_v3_cross(cj_v3_normalize(gw), h.n));
            if (ang > worst_n) worst_n = ang;
            assert_true(ang < 1e-9 && cj_v3_dot(gw, h.n) > 0);
            /* entering from outside, or leaving when the origin is inside */
            assert_true((cj_v3_dot(h.n, ray.dir) < 0) == (tr[0] >= 0));
            placed++;
        }
    }
    mq_clear(&m);
    printf("  sphere: %ld rays 1e-7 inside the silhouette hit (t within 1e-6 r of exact), %ld rays "
           "1e-7 outside miss; %ld rays on sheared/rotated/scaled spheres: t within 1e-10 of "
           "MPFR, normals within %.1e rad of M^-T grad\n",
           graze_in, graze_out, placed, worst_n);
}

static void test_cylinder(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, rp_seed + 2);
    long n = 0, hits = 0;
    for (int i = 0; i < 3000; i++) {
        cj_cylinder cy;
        cj_vec3 ax = rp_rand_unit(&r);
        assert_int_equal(cj_cylinder_init(&cy, cj_v3(1, 2, 3), ax, 0.7, -1.0, 2.0), CJ_OK);
        cj_vec3 o =
            cj_v3(cj_rng_range(&r, -4, 6), cj_rng_range(&r, -3, 7), cj_rng_range(&r, -2, 8));
        cj_vec3 tgt =
            cj_v3_add(cj_v3(1, 2, 3), cj_v3_add(cj_v3_scale(ax, cj_rng_range(&r, -1.5, 2.5)),
                                                cj_v3_scale(rp_rand_unit(&r), 0.8)));
        cj_ray ray = {o, cj_v3_sub(tgt, o), 0.0, INFINITY};
        /* Oracle in the cylinder's frame: x² + y² - r² along the transformed ray, in MPFR. */
        cj_vec3 w = cj_v3_sub(o, cy.base);
        cj_vec3 ol = cj_v3(cj_v3_dot(w, cy.e1), cj_v3_dot(w, cy.e2), cj_v3_dot(w, cy.a));
        cj_vec3 dl =
            cj_v3(cj_v3_dot(ray.dir, cy.e1), cj_v3_dot(ray.dir, cy.e2), cj_v3_dot(ray.dir, cy.a));
        mq m;
        mq_init(&m);
        mpfr_set_si(m.al, 1, MPFR_RNDN);
        mpfr_set_si(m.be, 1, MPFR_RNDN);
        mpfr_set_si(m.ga, 0, MPFR_RNDN);
        mpfr_set_si(m.la, 0, MPFR_RNDN);
        mpfr_set_d(m.ka, -0.49, MPFR_RNDN);
        mpfr_set_d(m.ka, 0.7, MPFR_RNDN);
        mpfr_sqr(m.ka, m.ka, MPFR_RNDN);
        mpfr_neg(m.ka, m.ka, MPFR_RNDN);
        mpfr_t mo[3], md[3];
        set3(mo, ol);
        set3(md, dl);
        double tr[2], drel;
        int nr = mq_roots(&m, mo, md, tr, &drel);
        clear3(mo);
        clear3(md);
        mq_clear(&m);
        double texp = NAN;
        int unc = drel < 1e-8;
        for (int k = 0; k < nr; k++) {
            if (tr[k] < 0) continue;
            double h = ol.z + tr[k] * dl.z;
            if (fabs(h + 1.0) < 1e-7 || fabs(h - 2.0) < 1e-7) unc = 1;
            if (h >= -1.0 && h <= 2.0) {
                texp = tr[k];
                break;
            }
        }
        cj_hit hit;
        int got = cj_ray_cylinder(&ray, &cy, &hit);
        n++;
        if (unc) continue;
        assert_int_equal(got, !isnan(texp));
        if (got) {
            hits++;
            assert_true(fabs(hit.t - texp) <= 1e-9 * fmax(1, texp));
            /* The normal is the unit radial direction at the hit. */
            cj_vec3 wp = cj_v3_sub(hit.p, cy.base);
            cj_vec3 rad = cj_v3_sub(wp, cj_v3_scale(cy.a, cj_v3_dot(wp, cy.a)));
            assert_true(fabs(cj_v3_norm(rad) - 0.7) <= fmax(hit.p_err.x, 1e-15));
            assert_true(cj_v3_norm(cj_v3_sub(cj_v3_normalize(rad), hit.n)) < 1e-9);
        }
    }
    printf("  cylinder (random axes): %ld rays, %ld hits, t within 1e-9 of MPFR, radius within "
           "p_err\n",
           n, hits);
}

static int setup(void **state) {
    (void)state;
    rp_seed = cj_test_seed("test_ray_primitives", 9001);
    return 0;
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_triangles),
        cmocka_unit_test(test_quadrics),
        cmocka_unit_test(test_sphere_grazing_and_placed),
        cmocka_unit_test(test_cylinder),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_patches),
        cmocka_unit_test(test_polygons_and_planar),
        cmocka_unit_test(test_offsets),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
