/* Taper and twist deformations (surfaces/include/casteljau/deform.h):
 *  - Jacobian against central finite differences of the point map,
 *  - normals against an independently computed inverse transpose, and perpendicular to every
 *    deformed tangent,
 *  - deformed parametric surfaces: partials vs finite differences, normals perpendicular to
 *    the deformed partials (also at poles), orientation kept,
 *  - exact geometric identities: a cylinder twisted about its axis is the same cylinder; a
 *    cylinder tapered by r(s) = k s is an elliptic cone (normals vs the cone's gradient),
 *  - vertex arrays: same results as the point/normal functions, all-or-nothing on failure,
 *  - meshes: deforming a tessellation = tessellating the deformed surface; still manifold,
 *  - bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/analytic.h"
#include "casteljau/bezier.h"
#include "casteljau/deform.h"
#include "casteljau/mesh.h"
#include "casteljau/quadric.h"
#include "casteljau/tessellate.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double PI = 3.14159265358979323846;
static uint64_t seed;

static int setup(void **state) {
    (void)state;
    seed = cj_test_seed("test_deform", 5700);
    return 0;
}

static cj_vec3 rvec(cj_rng *r, double lo, double hi) {
    return cj_v3(cj_rng_range(r, lo, hi), cj_rng_range(r, lo, hi), cj_rng_range(r, lo, hi));
}

/* A random deformation: taper (linear or quadratic) or twist about a random axis. The taper
 * profile keeps r(s) >= 0.4 on the test box (|s| <= 2*sqrt(3)): k0 in [1.5,2], |k1| <= 0.2,
 * |k2| <= 0.05. */
static void random_deform(cj_rng *r, cj_deform *d, int kind) {
    cj_vec3 o = rvec(r, -1, 1), a;
    do a = rvec(r, -1, 1);
    while (cj_v3_norm(a) < 0.1);
    if (kind == 0)
        assert_int_equal(
            cj_deform_taper(d, o, a, cj_rng_range(r, 1.5, 2.0), cj_rng_range(r, -0.2, 0.2), 0.0),
            CJ_OK);
    else if (kind == 1)
        assert_int_equal(cj_deform_taper(d, o, a, cj_rng_range(r, 1.5, 2.0),
                                         cj_rng_range(r, -0.2, 0.2), cj_rng_range(r, -0.05, 0.05)),
                         CJ_OK);
    else
        assert_int_equal(cj_deform_twist(d, o, a, cj_rng_range(r, -2.0, 2.0)), CJ_OK);
}

static const char *const kind_names[3] = {"linear taper", "quadratic taper", "twist"};

/* Central differences with h = 1e-5: truncation h^2/6 |D'''| (|D'''| <= ~30 for these rates
 * and points) plus rounding ~eps |D| / h, about 1e-10 together; observed worst ~4e-11;
 * tolerance 1e-9 (1 + |J|). */
static void test_jacobian_vs_finite_differences(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    double worst = 0.0;
    int checked = 0;
    for (int trial = 0; trial < 300; ++trial) {
        int kind = trial % 3;
        cj_deform d;
        random_deform(&r, &d, kind);
        cj_vec3 p = rvec(&r, -2, 2);
        double J[3][3], h = 1e-5;
        assert_int_equal(cj_deform_jacobian(&d, p, J), CJ_OK);
        double jn = 0.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) jn += J[i][j] * J[i][j];
        jn = sqrt(jn);
        for (int j = 0; j < 3; ++j) {
            cj_vec3 e = cj_v3(j == 0, j == 1, j == 2), a, b, t;
            assert_int_equal(cj_deform_point(&d, cj_v3_add(p, cj_v3_scale(e, h)), &a), CJ_OK);
            assert_int_equal(cj_deform_point(&d, cj_v3_sub(p, cj_v3_scale(e, h)), &b), CJ_OK);
            cj_vec3 fd = cj_v3_scale(cj_v3_sub(a, b), 0.5 / h);
            cj_vec3 col = cj_v3(J[0][j], J[1][j], J[2][j]);
            double err = cj_v3_norm(cj_v3_sub(fd, col)) / (1.0 + jn);
            if (err > worst) worst = err;
            if (err > 1e-9)
                fail_msg("%s trial %d: Jacobian column %d off by %g; seed %llu", kind_names[kind],
                         trial, j, err, (unsigned long long)seed);
            /* The tangent map is the same matrix. */
            assert_int_equal(cj_deform_tangent(&d, p, e, &t), CJ_OK);
            assert_true(cj_v3_norm(cj_v3_sub(t, col)) <= 1e-14 * (1.0 + jn));
        }
        ++checked;
    }
    printf("Jacobian vs central differences: %d random taper/twist cases, worst rel. error "
           "%.2e (tol 1e-9)\n",
           checked, worst);
}

/* det(J) J^{-T} n computed in the test by the explicit adjugate, independently of the library's
 * analytic formulas. */
static cj_vec3 cofactor_times(double J[3][3], cj_vec3 n) {
    double C[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            C[i][j] = J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1];
        }
    return cj_v3(C[0][0] * n.x + C[0][1] * n.y + C[0][2] * n.z,
                 C[1][0] * n.x + C[1][1] * n.y + C[1][2] * n.z,
                 C[2][0] * n.x + C[2][1] * n.y + C[2][2] * n.z);
}

static void test_normals_inverse_transpose(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 1);
    double worst_dir = 0.0, worst_perp = 0.0;
    for (int trial = 0; trial < 600; ++trial) {
        int kind = trial % 3;
        cj_deform d;
        random_deform(&r, &d, kind);
        cj_vec3 p = rvec(&r, -2, 2), n;
        do n = rvec(&r, -1, 1);
        while (cj_v3_norm(n) < 0.1);
        double J[3][3];
        cj_vec3 m;
        assert_int_equal(cj_deform_jacobian(&d, p, J), CJ_OK);
        assert_int_equal(cj_deform_normal(&d, p, n, &m), CJ_OK);
        assert_true(fabs(cj_v3_norm(m) - 1.0) < 1e-14);
        cj_vec3 want = cj_v3_normalize(cofactor_times(J, n));
        double e = 1.0 - cj_v3_dot(m, want);
        if (e > worst_dir) worst_dir = e;
        if (e > 1e-13)
            fail_msg("%s trial %d: normal differs from cof(J) n: 1-cos = %g; seed %llu",
                     kind_names[kind], trial, e, (unsigned long long)seed);
        /* Perpendicular to the image of every tangent of the plane n.t = 0. */
        cj_vec3 t1, t2;
        cj_frame_from_axis(cj_v3_normalize(n), &t1, &t2);
        for (int k = 0; k < 2; ++k) {
            cj_vec3 jt;
            assert_int_equal(cj_deform_tangent(&d, p, k ? t2 : t1, &jt), CJ_OK);
            double perp = fabs(cj_v3_dot(m, jt)) / cj_v3_norm(jt);
            if (perp > worst_perp) worst_perp = perp;
            if (perp > 1e-13)
                fail_msg("%s trial %d: deformed normal not perpendicular to J t (%g); seed %llu",
                         kind_names[kind], trial, perp, (unsigned long long)seed);
        }
    }
    printf("normals: 600 cases agree with the adjugate det(J) J^-T n (worst 1-cos %.2e) and are "
           "perpendicular to deformed tangents (worst |n.Jt|/|Jt| %.2e)\n",
           worst_dir, worst_perp);
}

static void test_closed_forms(void **state) {
    (void)state;
    cj_deform d;
    cj_vec3 o = cj_v3(0, 0, 0), z = cj_v3(0, 0, 1), q;
    /* Twist about z: (1, 0, s) -> (cos ks, sin ks, s). */
    assert_int_equal(cj_deform_twist(&d, o, cj_v3(0, 0, 3), 0.7), CJ_OK);
    for (int i = -5; i <= 5; ++i) {
        double s = 0.4 * i;
        assert_int_equal(cj_deform_point(&d, cj_v3(1, 0, s), &q), CJ_OK);
        assert_true(fabs(q.x - cos(0.7 * s)) < 1e-15 && fabs(q.y - sin(0.7 * s)) < 1e-15 &&
                    q.z == s);
    }
    /* Linear taper about z: (x, y, s) -> ((1 + k s) x, (1 + k s) y, s). */
    assert_int_equal(cj_deform_taper(&d, o, z, 1.0, 0.25, 0.0), CJ_OK);
    assert_int_equal(cj_deform_point(&d, cj_v3(2, -1, 2), &q), CJ_OK);
    assert_true(fabs(q.x - 3.0) < 1e-15 && fabs(q.y + 1.5) < 1e-15 && q.z == 2.0);
    /* Quadratic taper. */
    assert_int_equal(cj_deform_taper(&d, o, z, 1.0, 0.0, 0.5), CJ_OK);
    assert_int_equal(cj_deform_point(&d, cj_v3(1, 1, 2), &q), CJ_OK);
    assert_true(fabs(q.x - 3.0) < 1e-15 && fabs(q.y - 3.0) < 1e-15);
    /* Points on a tilted axis are fixed by a twist. */
    cj_vec3 ax = cj_v3(1, 2, -2), org = cj_v3(0.5, -1, 2);
    assert_int_equal(cj_deform_twist(&d, org, ax, 1.3), CJ_OK);
    cj_vec3 on = cj_v3_add(org, cj_v3_scale(ax, 0.8));
    assert_int_equal(cj_deform_point(&d, on, &q), CJ_OK);
    assert_true(cj_v3_norm(cj_v3_sub(q, on)) < 1e-14);
    /* Rate 0 and r == 1 are the identity (to rounding of the frame change). */
    assert_int_equal(cj_deform_twist(&d, org, ax, 0.0), CJ_OK);
    assert_int_equal(cj_deform_point(&d, cj_v3(3, -4, 5), &q), CJ_OK);
    assert_true(cj_v3_norm(cj_v3_sub(q, cj_v3(3, -4, 5))) < 1e-14);
    printf("closed forms: twist of (1,0,s), linear and quadratic taper values, fixed axis, "
           "identity\n");
}

/* A cylinder twisted about its own axis is the same cylinder, with the same normals; a
 * cylinder of radius rho tapered by r(s) = k s is the cone x^2 + y^2 = (rho k)^2 z^2. These
 * compare the deformed surface with implicit forms that do not involve the deformation. */
static void test_geometric_identities(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 2);
    cj_cylinder cy;
    cj_vec3 base = cj_v3(1, -1, 0.5), ax = cj_v3(0.2, 0.3, 1);
    assert_int_equal(cj_cylinder_init(&cy, base, ax, 0.6, -1, 2), CJ_OK);
    cj_param_surface cs, tw;
    cj_cylinder_surface(&cy, &cs);
    cj_implicit_surface ci;
    cj_cylinder_implicit(&cy, &ci);
    cj_deform d;
    assert_int_equal(cj_deform_twist(&d, base, ax, 1.7), CJ_OK);
    cj_deformed_surface store;
    assert_int_equal(cj_deform_surface(&d, &cs, &store, &tw), CJ_OK);
    for (int k = 0; k < 500; ++k) {
        double u = cj_rng_range(&r, tw.u0, tw.u1), v = cj_rng_range(&r, tw.v0, tw.v1), f;
        cj_vec3 p, n, g;
        assert_int_equal(cj_surface_eval(&tw, u, v, &p, NULL, NULL), CJ_OK);
        assert_int_equal(cj_surface_normal(&tw, u, v, &n), CJ_OK);
        assert_int_equal(cj_implicit_eval(&ci, p, &f, NULL), CJ_OK);
        assert_int_equal(cj_implicit_normal(&ci, p, &g), CJ_OK);
        if (fabs(f) > 1e-14 || 1.0 - cj_v3_dot(n, g) > 1e-13)
            fail_msg("twisted cylinder at (%.17g,%.17g): f = %g, 1-cos = %g; seed %llu", u, v, f,
                     1.0 - cj_v3_dot(n, g), (unsigned long long)seed);
    }
    /* Cylinder about z, radius 0.5, heights [0.5, 3]; taper r(s) = 1.5 s -> cone a = b = 0.75. */
    cj_cylinder cz;
    assert_int_equal(cj_cylinder_init(&cz, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 0.5, 0.5, 3), CJ_OK);
    cj_cylinder_surface(&cz, &cs);
    assert_int_equal(cj_deform_taper(&d, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 0.0, 1.5, 0.0), CJ_OK);
    assert_int_equal(cj_deform_surface(&d, &cs, &store, &tw), CJ_OK);
    cj_quadric cone;
    assert_int_equal(cj_quadric_cone(&cone, 0.75, 0.75, 1.0, 0.5, 3), CJ_OK);
    cj_implicit_surface coni;
    cj_quadric_implicit(&cone, &coni);
    for (int k = 0; k < 500; ++k) {
        double u = cj_rng_range(&r, tw.u0, tw.u1), v = cj_rng_range(&r, tw.v0, tw.v1), f;
        cj_vec3 p, n, g;
        assert_int_equal(cj_surface_eval(&tw, u, v, &p, NULL, NULL), CJ_OK);
        assert_int_equal(cj_surface_normal(&tw, u, v, &n), CJ_OK);
        assert_int_equal(cj_implicit_eval(&coni, p, &f, NULL), CJ_OK);
        assert_int_equal(cj_implicit_normal(&coni, p, &g), CJ_OK);
        if (fabs(f) > 1e-14 * (1 + cj_v3_dot(p, p)) || 1.0 - cj_v3_dot(n, g) > 1e-13)
            fail_msg("tapered cylinder at (%.17g,%.17g): f = %g, 1-cos = %g; seed %llu", u, v, f,
                     1.0 - cj_v3_dot(n, g), (unsigned long long)seed);
    }
    printf("identities: twisted cylinder = cylinder, tapered cylinder = cone (points and "
           "normals, 500 samples each)\n");
}

/* Deformed parametric surfaces. Central differences with h = 2e-6 of the domain width
 * (about 1.3e-5 on [0, 2pi]): the deformed surfaces have third derivatives up to ~100 (twist
 * rates up to 2 on a torus), so truncation ~3e-9 at h = 1e-5 would be too close to the
 * tolerance 1e-8; at h = 2e-6 truncation is ~1e-10 and rounding ~1e-11. */
static void test_deformed_surfaces(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 3);
    cj_quadric ell, hp, cone;
    cj_torus tor;
    cj_revolution rev;
    static const double prof[] = {0, -1, 1.3, -1, 1.3, 1, 0, 1};
    cj_bezier pb = cj_bezier_view(3, 2, prof);
    cj_curve2 pc;
    assert_int_equal(cj_quadric_ellipsoid(&ell, 1.0, 0.7, 1.2), CJ_OK);
    assert_int_equal(cj_quadric_hyperbolic_paraboloid(&hp, 1, 1, -1, 1, -1, 1), CJ_OK);
    assert_int_equal(cj_quadric_cone(&cone, 1, 1, 1, 0, 1.5), CJ_OK);
    assert_int_equal(cj_torus_init(&tor, cj_v3(0, 0, 0), cj_v3(1, 0, 1), 1.5, 0.5), CJ_OK);
    assert_int_equal(cj_curve2_from_bezier(&pb, &pc), CJ_OK);
    assert_int_equal(cj_revolution_init(&rev, &pc, cj_v3(0, 0, 0), cj_v3(0, 1, 0)), CJ_OK);
    cj_param_surface bases[5];
    const char *names[5] = {"ellipsoid", "hyperbolic paraboloid", "cone", "torus",
                            "Bezier revolution"};
    cj_quadric_surface(&ell, &bases[0]);
    cj_quadric_surface(&hp, &bases[1]);
    cj_quadric_surface(&cone, &bases[2]);
    cj_torus_surface(&tor, &bases[3]);
    cj_revolution_surface(&rev, &bases[4]);
    int checked = 0, singular = 0;
    double worst_fd = 0.0, worst_perp = 0.0;
    for (int b = 0; b < 5; ++b)
        for (int kind = 0; kind < 3; ++kind) {
            cj_deform d;
            random_deform(&r, &d, kind);
            cj_deformed_surface store;
            cj_param_surface s;
            assert_int_equal(cj_deform_surface(&d, &bases[b], &store, &s), CJ_OK);
            assert_true(s.flags == bases[b].flags && s.u0 == bases[b].u0 && s.v1 == bases[b].v1);
            double hu = 2e-6 * (s.u1 - s.u0), hv = 2e-6 * (s.v1 - s.v0);
            for (int k = 0; k < 200; ++k) {
                double u = cj_rng_range(&r, s.u0 + 2 * hu, s.u1 - 2 * hu);
                double v = cj_rng_range(&r, s.v0 + 2 * hv, s.v1 - 2 * hv);
                int edge = k % 5 == 0;
                if (edge) v = k % 10 == 0 ? s.v0 : s.v1; /* poles, apex, boundary */
                cj_vec3 p, su, sv, n, a, c;
                assert_int_equal(cj_surface_eval(&s, u, v, &p, &su, &sv), CJ_OK);
                assert_int_equal(cj_surface_normal(&s, u, v, &n), CJ_OK);
                if (!edge) {
                    cj_surface_eval(&s, u + hu, v, &a, NULL, NULL);
                    cj_surface_eval(&s, u - hu, v, &c, NULL, NULL);
                    cj_vec3 fu = cj_v3_scale(cj_v3_sub(a, c), 0.5 / hu);
                    cj_surface_eval(&s, u, v + hv, &a, NULL, NULL);
                    cj_surface_eval(&s, u, v - hv, &c, NULL, NULL);
                    cj_vec3 fv = cj_v3_scale(cj_v3_sub(a, c), 0.5 / hv);
                    double sc = cj_v3_norm(p) + cj_v3_norm(su) + cj_v3_norm(sv) + 1.0;
                    double e =
                        fmax(cj_v3_norm(cj_v3_sub(fu, su)), cj_v3_norm(cj_v3_sub(fv, sv))) / sc;
                    if (e > worst_fd) worst_fd = e;
                    if (e > 1e-8)
                        fail_msg("%s %s: partials vs FD at (%.17g,%.17g): %g; seed %llu",
                                 kind_names[kind], names[b], u, v, e, (unsigned long long)seed);
                }
                for (int t = 0; t < 2; ++t) {
                    cj_vec3 tv = t ? sv : su;
                    double len = cj_v3_norm(tv);
                    if (len < 1e-12) continue; /* a partial vanishes on a collapsed edge */
                    double perp = fabs(cj_v3_dot(n, tv)) / len;
                    if (perp > worst_perp) worst_perp = perp;
                    if (perp > 1e-12)
                        fail_msg("%s %s: normal not perpendicular to S_%c at (%.17g,%.17g): %g; "
                                 "seed %llu",
                                 kind_names[kind], names[b], t ? 'v' : 'u', u, v, perp,
                                 (unsigned long long)seed);
                }
                cj_vec3 cr = cj_v3_cross(su, sv);
                if (cj_v3_norm(cr) > 1e-6 * cj_v3_norm(su) * cj_v3_norm(sv)) {
                    if (cj_v3_dot(cr, n) <= 0.0)
                        fail_msg("%s %s: orientation flipped at (%.17g,%.17g); seed %llu",
                                 kind_names[kind], names[b], u, v, (unsigned long long)seed);
                } else {
                    /* Singular edge: the normal is the limit of interior normals. */
                    double vin = v == s.v0 ? v + 1e-7 * (s.v1 - s.v0) : v - 1e-7 * (s.v1 - s.v0);
                    cj_vec3 pi, sui, svi;
                    cj_surface_eval(&s, u, vin, &pi, &sui, &svi);
                    cj_vec3 ni = cj_v3_normalize(cj_v3_cross(sui, svi));
                    if (1.0 - cj_v3_dot(ni, n) > 1e-6)
                        fail_msg("%s %s: edge normal at (%.17g,%.17g) is not the interior limit "
                                 "(1-cos %g); seed %llu",
                                 kind_names[kind], names[b], u, v, 1.0 - cj_v3_dot(ni, n),
                                 (unsigned long long)seed);
                    ++singular;
                }
                ++checked;
            }
        }
    printf("deformed surfaces: %d points (5 bases x 3 deformations, %d on singular edges): "
           "partials vs FD worst %.2e (tol 1e-8), |n.S_u|/|S_u| worst %.2e (tol 1e-12), "
           "orientation kept, edge normals = interior limits\n",
           checked, singular, worst_fd, worst_perp);
}

static void test_vertices(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 4);
    enum { N = 64 };
    double pos[3 * N], nrm[3 * N], p0[3 * N], n0[3 * N];
    for (int kind = 0; kind < 3; ++kind) {
        cj_deform d;
        random_deform(&r, &d, kind);
        for (int i = 0; i < N; ++i) {
            cj_vec3 p = rvec(&r, -2, 2), n = cj_v3_normalize(rvec(&r, -1, 1));
            pos[3 * i] = p.x, pos[3 * i + 1] = p.y, pos[3 * i + 2] = p.z;
            nrm[3 * i] = n.x, nrm[3 * i + 1] = n.y, nrm[3 * i + 2] = n.z;
        }
        memcpy(p0, pos, sizeof pos);
        memcpy(n0, nrm, sizeof nrm);
        assert_int_equal(cj_deform_vertices(&d, pos, nrm, N), CJ_OK);
        for (int i = 0; i < N; ++i) {
            cj_vec3 p = cj_v3(p0[3 * i], p0[3 * i + 1], p0[3 * i + 2]);
            cj_vec3 n = cj_v3(n0[3 * i], n0[3 * i + 1], n0[3 * i + 2]), q, m;
            assert_int_equal(cj_deform_point(&d, p, &q), CJ_OK);
            assert_int_equal(cj_deform_normal(&d, p, n, &m), CJ_OK);
            assert_true(q.x == pos[3 * i] && q.y == pos[3 * i + 1] && q.z == pos[3 * i + 2]);
            assert_true(m.x == nrm[3 * i] && m.y == nrm[3 * i + 1] && m.z == nrm[3 * i + 2]);
        }
        memcpy(pos, p0, sizeof pos);
        assert_int_equal(cj_deform_vertices(&d, pos, NULL, N), CJ_OK);
        assert_true(memcmp(pos, p0, sizeof pos) != 0);
    }
    assert_int_equal(cj_deform_vertices(&(cj_deform){0}, NULL, NULL, 0), CJ_OK);
    /* All-or-nothing: vertex 7 sits where r(s) = 0, vertex 9 is NaN. */
    cj_deform d;
    assert_int_equal(cj_deform_taper(&d, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 0.0, 1.0, 0.0), CJ_OK);
    for (int i = 0; i < N; ++i) pos[3 * i + 2] = 0.5 + i * 0.01;
    pos[3 * 7 + 2] = 0.0;
    memcpy(p0, pos, sizeof pos);
    memcpy(n0, nrm, sizeof nrm);
    assert_int_equal(cj_deform_vertices(&d, pos, nrm, N), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "vertex 7"));
    assert_true(memcmp(pos, p0, sizeof pos) == 0 && memcmp(nrm, n0, sizeof nrm) == 0);
    /* A zero normal means "unknown" (mesh convention) and stays zero. */
    double zp[6] = {1, 2, 0.5, 0, 1, 1}, zn[6] = {0, 0, 0, 1, 0, 0};
    assert_int_equal(cj_deform_vertices(&d, zp, zn, 2), CJ_OK);
    assert_true(zn[0] == 0 && zn[1] == 0 && zn[2] == 0 &&
                cj_v3_norm(cj_v3(zn[3], zn[4], zn[5])) > 0.99);
    /* Without normals the collapse is allowed (points are well defined). */
    assert_int_equal(cj_deform_vertices(&d, pos, NULL, N), CJ_OK);
    memcpy(pos, p0, sizeof pos);
    pos[3 * 9 + 1] = NAN;
    memcpy(p0, pos, sizeof pos);
    assert_int_equal(cj_deform_vertices(&d, pos, NULL, N), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "vertex 9"));
    assert_true(memcmp(pos, p0, sizeof pos) == 0);
    printf("vertex arrays: 3 x %d vertices match the point/normal functions bit for bit; "
           "failures (collapse at vertex 7, NaN at vertex 9) leave the arrays untouched\n",
           N);
}

/* Meshes: a torus tessellated (cj_tessellate_surface) and then deformed with cj_deform_mesh is
 * the tessellation of the deformed torus surface, bit for bit (same parameters, same
 * arithmetic); the deformed mesh stays a closed manifold (Euler characteristic 0 for the
 * torus, 2 for the ellipsoid) and its faces stay counter-clockwise seen from the side of the
 * vertex normals. */
static void test_mesh(void **state) {
    (void)state;
    cj_torus tor;
    cj_quadric ell;
    assert_int_equal(cj_torus_init(&tor, cj_v3(0, 0, 0.2), cj_v3(0.3, 0.1, 1), 1.5, 0.5), CJ_OK);
    assert_int_equal(cj_quadric_ellipsoid(&ell, 1.0, 0.8, 1.6), CJ_OK);
    cj_param_surface bases[2];
    cj_torus_surface(&tor, &bases[0]);
    cj_quadric_surface(&ell, &bases[1]);
    const long euler[2] = {0, 2};
    cj_deform defs[2];
    assert_int_equal(cj_deform_twist(&defs[0], cj_v3(0, 0, 0), cj_v3(0, 0, 1), 1.1), CJ_OK);
    assert_int_equal(cj_deform_taper(&defs[1], cj_v3(0, 0, -2), cj_v3(0, 0, 1), 0.5, 0.3, 0.05),
                     CJ_OK);
    int meshes = 0;
    size_t tris = 0;
    for (int b = 0; b < 2; ++b)
        for (int k = 0; k < 2; ++k) {
            cj_mesh *m1 = NULL, *m2 = NULL;
            assert_int_equal(cj_mesh_create(NULL, &m1), CJ_OK);
            assert_int_equal(cj_mesh_create(NULL, &m2), CJ_OK);
            assert_int_equal(cj_tessellate_surface(&bases[b], 24, 16, 0, m1, NULL), CJ_OK);
            assert_int_equal(cj_deform_mesh(&defs[k], m1), CJ_OK);
            cj_deformed_surface store;
            cj_param_surface ds;
            assert_int_equal(cj_deform_surface(&defs[k], &bases[b], &store, &ds), CJ_OK);
            assert_int_equal(cj_tessellate_surface(&ds, 24, 16, 0, m2, NULL), CJ_OK);
            assert_int_equal(m1->vertex_count, m2->vertex_count);
            assert_int_equal(m1->triangle_count, m2->triangle_count);
            assert_memory_equal(m1->positions, m2->positions,
                                3 * m1->vertex_count * sizeof(double));
            assert_memory_equal(m1->normals, m2->normals, 3 * m1->vertex_count * sizeof(double));
            cj_mesh_topology topo;
            assert_int_equal(cj_mesh_topology_compute(m1, &topo), CJ_OK);
            assert_int_equal(topo.boundary_edges, 0);
            assert_int_equal(topo.nonmanifold_edges, 0);
            assert_int_equal(topo.misoriented_edges, 0);
            assert_int_equal(topo.euler, euler[b]);
            for (size_t t = 0; t < m1->triangle_count; ++t) {
                const uint32_t *ix = &m1->triangles[3 * t];
                cj_vec3 p[3], nsum = cj_v3(0, 0, 0);
                for (int c = 0; c < 3; ++c) {
                    const double *q = &m1->positions[3 * ix[c]], *n = &m1->normals[3 * ix[c]];
                    p[c] = cj_v3(q[0], q[1], q[2]);
                    nsum = cj_v3_add(nsum, cj_v3(n[0], n[1], n[2]));
                }
                cj_vec3 fn = cj_v3_cross(cj_v3_sub(p[1], p[0]), cj_v3_sub(p[2], p[0]));
                if (!(cj_v3_dot(fn, nsum) > 0.0))
                    fail_msg("mesh %d/%d: triangle %zu is not CCW seen from its normals", b, k, t);
            }
            tris += m1->triangle_count;
            ++meshes;
            cj_mesh_destroy(m1);
            cj_mesh_destroy(m2);
        }
    printf("meshes: %d deformed tessellations (torus, ellipsoid x twist, taper; %zu triangles) "
           "equal the tessellations of the deformed surfaces bit for bit, closed manifolds with "
           "the right Euler characteristic, faces CCW w.r.t. vertex normals\n",
           meshes, tris);
}

static void test_bad_input(void **state) {
    (void)state;
    cj_deform d;
    cj_vec3 o = cj_v3(0, 0, 0), z = cj_v3(0, 0, 1), q;
    assert_int_equal(cj_deform_twist(&d, o, cj_v3(0, 0, 0), 1.0), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "axis"));
    assert_int_equal(cj_deform_twist(&d, o, cj_v3(0, 0, 1e-310), 1.0), CJ_OK); /* subnormal */
    assert_true(d.a.z == 1.0);
    assert_int_equal(cj_deform_twist(&d, o, z, NAN), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "rate"));
    assert_int_equal(cj_deform_twist(&d, cj_v3(0, INFINITY, 0), z, 1.0), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "origin"));
    assert_int_equal(cj_deform_taper(&d, o, z, 0, 0, 0), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "identically zero"));
    assert_int_equal(cj_deform_taper(&d, o, z, 1, NAN, 0), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "coefficient k 1"));
    assert_int_equal(cj_deform_taper(&d, o, z, 1, 0, 0), CJ_OK);
    assert_int_equal(cj_deform_point(&d, cj_v3(NAN, 0, 0), &q), CJ_ERR_NONFINITE);
    assert_int_equal(cj_deform_normal(&d, o, cj_v3(0, 0, 0), &q), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_deform_taper(&d, o, z, 1e300, 0, 0), CJ_OK);
    assert_int_equal(cj_deform_point(&d, cj_v3(1e10, 0, 0), &q), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "overflow"));
    /* Deformed surface of a malformed base view. */
    cj_param_surface bad = {0};
    cj_deformed_surface store;
    cj_param_surface out;
    assert_int_equal(cj_deform_surface(&d, &bad, &store, &out), CJ_ERR_ARGUMENT);
    printf("bad input: zero/NaN axis, NaN rate and coefficients, zero taper, NaN point, zero "
           "normal, overflow, malformed base surface\n");
}

int main(void) {
    (void)PI;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_jacobian_vs_finite_differences),
        cmocka_unit_test(test_normals_inverse_transpose),
        cmocka_unit_test(test_closed_forms),
        cmocka_unit_test(test_geometric_identities),
        cmocka_unit_test(test_deformed_surfaces),
        cmocka_unit_test(test_vertices),
        cmocka_unit_test(test_mesh),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
