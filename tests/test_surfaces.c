/* Analytic surfaces (surfaces/: surface.h, quadric.h, analytic.h):
 *  - partial derivatives against central finite differences,
 *  - points of the parametric forms satisfy the implicit equations,
 *  - parametric normals (including pole limits) agree in direction with implicit gradients,
 *  - closure flags and orientation (outward on closed surfaces),
 *  - bad input gives the documented status and a message naming the input. */
#include "surfaces_catalogue.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* Partials vs central differences. Step h = 1e-5 of the domain width (near cbrt(eps)):
 * truncation error <= h^2/6 max|S'''| and rounding <= eps |S| / h, both about 1e-11 of the
 * local size for these smooth surfaces of size O(1..10) on domains O(1..2pi); the tolerance
 * 1e-8 (|S| + |S_u| + |S_v| + 1) leaves a margin of ~100 while still catching a wrong sign,
 * a missing factor or a swapped component (all O(1) relative errors). */
static void test_partials_vs_finite_differences(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    int checked = 0;
    double worst = 0.0;
    for (int c = 0; c < ncases; ++c) {
        const cj_param_surface *s = &cases[c].ps;
        double hu = 1e-5 * (s->u1 - s->u0), hv = 1e-5 * (s->v1 - s->v0);
        for (int k = 0; k < 300; ++k) {
            double u, v;
            draw_uv(&r, s, 2e-5, &u, &v);
            cj_vec3 p, su, sv, a, b, dummy;
            assert_int_equal(cj_surface_eval(s, u, v, &p, &su, &sv), CJ_OK);
            assert_int_equal(cj_surface_eval(s, u + hu, v, &a, &dummy, &dummy), CJ_OK);
            assert_int_equal(cj_surface_eval(s, u - hu, v, &b, &dummy, &dummy), CJ_OK);
            cj_vec3 fu = cj_v3_scale(cj_v3_sub(a, b), 0.5 / hu);
            assert_int_equal(cj_surface_eval(s, u, v + hv, &a, NULL, NULL), CJ_OK);
            assert_int_equal(cj_surface_eval(s, u, v - hv, &b, NULL, NULL), CJ_OK);
            cj_vec3 fv = cj_v3_scale(cj_v3_sub(a, b), 0.5 / hv);
            double scale = cj_v3_norm(p) + cj_v3_norm(su) + cj_v3_norm(sv) + 1.0;
            double eu = cj_v3_norm(cj_v3_sub(fu, su)) / scale;
            double ev = cj_v3_norm(cj_v3_sub(fv, sv)) / scale;
            if (eu > worst) worst = eu;
            if (ev > worst) worst = ev;
            if (eu > 1e-8 || ev > 1e-8)
                fail_msg("%s: partials vs finite differences at (u,v)=(%.17g,%.17g): rel. error "
                         "%g (u), %g (v); seed %llu",
                         cases[c].name, u, v, eu, ev, (unsigned long long)seed);
            ++checked;
        }
    }
    printf("partials vs central differences: %d points on %d surfaces, worst rel. error %.2e "
           "(tol 1e-8)\n",
           checked, ncases, worst);
}

static void test_parametric_points_satisfy_implicit(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 1);
    int checked = 0, surfaces = 0;
    double worst = 0.0;
    for (int c = 0; c < ncases; ++c) {
        const tcase *t = &cases[c];
        if (!t->has_implicit) continue;
        ++surfaces;
        for (int k = 0; k < 500; ++k) {
            double u, v, rel;
            draw_uv(&r, &t->ps, 0.0, &u, &v);
            cj_vec3 p, n;
            assert_int_equal(cj_surface_eval(&t->ps, u, v, &p, NULL, NULL), CJ_OK);
            if (!on_surface(t, p, &rel))
                fail_msg("%s: S(%.17g,%.17g) off the implicit surface (|f|/tol = %g); seed %llu",
                         t->name, u, v, rel, (unsigned long long)seed);
            if (rel > worst) worst = rel;
            /* Negative control: 1e-11 (|p|+1) along the normal is detected (except near a cone
             * apex, where grad f -> 0 and the absolute floor of the tolerance dominates). */
            {
                double f0;
                cj_vec3 g0;
                assert_int_equal(cj_implicit_eval(&t->is, p, &f0, &g0), CJ_OK);
                if (cj_v3_norm(g0) < 1e-2) continue; /* within ~1e-2 of a cone apex */
            }
            assert_int_equal(cj_surface_normal(&t->ps, u, v, &n), CJ_OK);
            cj_vec3 off = cj_v3_add(p, cj_v3_scale(n, 1e-11 * (cj_v3_norm(p) + 1.0)));
            if (on_surface(t, off, &rel))
                fail_msg("%s: displaced point not detected at (%.17g,%.17g); seed %llu", t->name, u,
                         v, (unsigned long long)seed);
            ++checked;
        }
    }
    printf("parametric points on implicit surfaces: %d points on %d surfaces, worst |f|/tol "
           "%.2e; displaced points all rejected\n",
           checked, surfaces, worst);
}

/* The parametric normal (with its pole limits) against the implicit gradient: same direction
 * AND same orientation (the documented convention), 1 - n.g <= 1e-12 (angles <~ 1.4e-6 rad;
 * both are computed to ~1e-15, so 1e-12 leaves room for the conditioning of normalisation
 * near flat points). Also n against the normalised S_u x S_v away from singular points. */
static void test_normals_agree_with_gradients(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 2);
    int checked = 0, at_edges = 0, surfaces = 0;
    double worst = 0.0;
    for (int c = 0; c < ncases; ++c) {
        const tcase *t = &cases[c];
        if (!t->has_implicit) continue;
        ++surfaces;
        for (int k = 0; k < 500; ++k) {
            double u, v;
            draw_uv(&r, &t->ps, 0.0, &u, &v);
            cj_vec3 p, su, sv, n, g;
            assert_int_equal(cj_surface_eval(&t->ps, u, v, &p, &su, &sv), CJ_OK);
            assert_int_equal(cj_surface_normal(&t->ps, u, v, &n), CJ_OK);
            assert_true(fabs(cj_v3_norm(n) - 1.0) < 1e-14);
            cj_status st = cj_implicit_normal(&t->is, p, &g);
            if (st == CJ_ERR_DEGENERATE) {
                /* Only the cone apex has a vanishing gradient. */
                assert_true(strstr(t->name, "cone") != NULL && fabs(v) == 0.0);
                continue;
            }
            assert_int_equal(st, CJ_OK);
            double d = 1.0 - cj_v3_dot(n, g);
            if (d > worst) worst = d;
            if (d > 1e-12)
                fail_msg("%s: normal vs gradient at (u,v)=(%.17g,%.17g): 1-n.g = %g; seed %llu",
                         t->name, u, v, d, (unsigned long long)seed);
            cj_vec3 cr = cj_v3_cross(su, sv);
            double ncr = cj_v3_norm(cr);
            if (ncr > 1e-6 * cj_v3_norm(su) * cj_v3_norm(sv)) {
                double e = 1.0 - cj_v3_dot(n, cj_v3_scale(cr, 1.0 / ncr));
                if (e > 1e-12)
                    fail_msg("%s: normal vs S_u x S_v at (%.17g,%.17g): 1-cos = %g; seed %llu",
                             t->name, u, v, e, (unsigned long long)seed);
            } else {
                ++at_edges;
            }
            if (t->outward) assert_true(cj_v3_dot(n, cj_v3_sub(p, t->center)) > 0.0);
            ++checked;
        }
    }
    printf("normals vs implicit gradients: %d points on %d surfaces (%d at singular edges), "
           "worst 1-cos %.2e (tol 1e-12)\n",
           checked, surfaces, at_edges, worst);
}

/* Poles explicitly: exact expected normals, computed by hand from the formulas. */
static void test_pole_normals(void **state) {
    (void)state;
    cj_param_surface s;
    cj_vec3 n;
    const double us[] = {0.0, 1.0, 2.5, 2.0 * PI};
    for (int i = 0; i < 4; ++i) {
        cj_quadric_surface(&q_ell, &s);
        assert_int_equal(cj_surface_normal(&s, us[i], -0.5 * PI, &n), CJ_OK);
        assert_true(fabs(n.z + 1.0) < 1e-15 && fabs(n.x) < 1e-15 && fabs(n.y) < 1e-15);
        assert_int_equal(cj_surface_normal(&s, us[i], 0.5 * PI, &n), CJ_OK);
        assert_true(fabs(n.z - 1.0) < 1e-15);
        cj_quadric_surface(&q_h2u, &s);
        assert_int_equal(cj_surface_normal(&s, us[i], 0.0, &n), CJ_OK);
        assert_true(n.z == -1.0);
        cj_quadric_surface(&q_h2l, &s);
        assert_int_equal(cj_surface_normal(&s, us[i], 0.0, &n), CJ_OK);
        assert_true(n.z == 1.0);
        cj_quadric_surface(&q_par, &s);
        assert_int_equal(cj_surface_normal(&s, us[i], 0.0, &n), CJ_OK);
        assert_true(n.z == -1.0);
        /* Bézier revolution: the profile leaves the axis horizontally at both ends. */
        cj_revolution_surface(&rev_bez, &s);
        assert_int_equal(cj_surface_normal(&s, us[i], 0.0, &n), CJ_OK);
        assert_true(fabs(n.z + 1.0) < 1e-15);
        assert_int_equal(cj_surface_normal(&s, us[i], 1.0, &n), CJ_OK);
        assert_true(fabs(n.z - 1.0) < 1e-15);
        /* Cone apex: the normal of the generator at angle u, from the domain's side. */
        cj_quadric_surface(&q_cone, &s);
        cj_vec3 p, su, sv;
        assert_int_equal(cj_surface_normal(&s, us[i], 0.0, &n), CJ_OK);
        assert_int_equal(cj_surface_eval(&s, us[i], 1.0, &p, &su, &sv), CJ_OK);
        cj_vec3 m = cj_v3_normalize(cj_v3_cross(su, sv));
        assert_true(cj_v3_dot(n, m) > 1.0 - 1e-14);
        cj_quadric_surface(&q_cone_neg, &s);
        assert_int_equal(cj_surface_normal(&s, us[i], 0.0, &n), CJ_OK);
        assert_int_equal(cj_surface_eval(&s, us[i], -1.0, &p, &su, &sv), CJ_OK);
        m = cj_v3_normalize(cj_v3_cross(su, sv));
        assert_true(cj_v3_dot(n, m) > 1.0 - 1e-14);
    }
    /* The generic fallback (no normal callback) reaches the same pole limit approximately. */
    cj_revolution_surface(&rev_bez, &s);
    s.normal = NULL;
    assert_int_equal(cj_surface_normal(&s, 1.0, 0.0, &n), CJ_OK);
    assert_true(n.z < -1.0 + 1e-6);
    cj_quadric_surface(&q_ell, &s);
    s.normal = NULL;
    assert_int_equal(cj_surface_normal(&s, 0.3, 0.5 * PI, &n), CJ_OK);
    assert_true(n.z > 1.0 - 1e-6);
    /* Bilinear patch collapsed to a triangle (p00 == p10): edge v = 0 is a point. */
    assert_int_equal(
        cj_bilinear_init(&bil_tri, cj_v3(0, 0, 0), cj_v3(0, 0, 0), cj_v3(0, 1, 0), cj_v3(1, 1, 0)),
        CJ_OK);
    assert_true(bil_tri.flags == CJ_SURF_COLLAPSED_V0);
    cj_bilinear_surface(&bil_tri, &s);
    assert_int_equal(cj_surface_normal(&s, 0.5, 0.0, &n), CJ_OK);
    /* S_u = v (1,0,0), S_v = (u,1,0): S_u x S_v = v (0,0,1); the limit v -> 0+ is +z. */
    assert_true(n.z > 1.0 - 1e-12);
    printf("pole normals: ellipsoid, hyperboloid sheets, paraboloid, Bezier revolution exact; "
           "cone apex = generator normal; generic fallback within 1e-6\n");
}

static void test_flags_and_periodicity(void **state) {
    (void)state;
    cj_param_surface s;
    cj_quadric_surface(&q_ell, &s);
    assert_true(s.flags == (CJ_SURF_PERIODIC_U | CJ_SURF_COLLAPSED_V0 | CJ_SURF_COLLAPSED_V1));
    cj_revolution_surface(&rev_bez, &s);
    assert_true(s.flags == (CJ_SURF_PERIODIC_U | CJ_SURF_COLLAPSED_V0 | CJ_SURF_COLLAPSED_V1));
    cj_revolution_surface(&rev_torus, &s);
    assert_true(s.flags == (CJ_SURF_PERIODIC_U | CJ_SURF_PERIODIC_V));
    cj_quadric_surface(&q_hp, &s);
    assert_true(s.flags == 0u);
    cj_quadric_surface(&q_cone_neg, &s);
    assert_true(s.flags == (CJ_SURF_PERIODIC_U | CJ_SURF_COLLAPSED_V1));
    int checked = 0;
    for (int c = 0; c < ncases; ++c) {
        const cj_param_surface *ps = &cases[c].ps;
        for (int k = 0; k <= 16; ++k) {
            double t = k / 16.0;
            cj_vec3 a, b;
            double v = ps->v0 + t * (ps->v1 - ps->v0), u = ps->u0 + t * (ps->u1 - ps->u0);
            if (ps->flags & CJ_SURF_PERIODIC_U) {
                cj_surface_eval(ps, ps->u0, v, &a, NULL, NULL);
                cj_surface_eval(ps, ps->u1, v, &b, NULL, NULL);
                assert_true(cj_v3_norm(cj_v3_sub(a, b)) <= 1e-14 * (cj_v3_norm(a) + 1));
                ++checked;
            }
            if (ps->flags & CJ_SURF_PERIODIC_V) {
                cj_surface_eval(ps, u, ps->v0, &a, NULL, NULL);
                cj_surface_eval(ps, u, ps->v1, &b, NULL, NULL);
                assert_true(cj_v3_norm(cj_v3_sub(a, b)) <= 1e-14 * (cj_v3_norm(a) + 1));
                ++checked;
            }
            const unsigned edge[4] = {CJ_SURF_COLLAPSED_U0, CJ_SURF_COLLAPSED_U1,
                                      CJ_SURF_COLLAPSED_V0, CJ_SURF_COLLAPSED_V1};
            for (int e = 0; e < 4; ++e) {
                if (!(ps->flags & edge[e])) continue;
                double eu = e == 0 ? ps->u0 : e == 1 ? ps->u1 : u;
                double ev = e == 2 ? ps->v0 : e == 3 ? ps->v1 : v;
                double fu = e < 2 ? eu : ps->u0, fv = e < 2 ? ps->v0 : ev;
                cj_surface_eval(ps, eu, ev, &a, NULL, NULL);
                cj_surface_eval(ps, fu, fv, &b, NULL, NULL);
                assert_true(cj_v3_norm(cj_v3_sub(a, b)) <= 1e-14 * (cj_v3_norm(a) + 1));
                ++checked;
            }
        }
    }
    printf("closure flags: %d periodic/collapsed edge samples coincide to 1e-14\n", checked);
}

static void test_frame(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 3);
    for (int k = 0; k < 2000; ++k) {
        cj_vec3 a = cj_v3(rnd(&r, -1, 1), rnd(&r, -1, 1), rnd(&r, -1, 1));
        if (k == 0) a = cj_v3(0, 0, 1);
        if (k == 1) a = cj_v3(0, 0, -1);
        if (k == 2) a = cj_v3(1e-300, 0, -1);
        if (cj_v3_norm(a) < 1e-3) continue;
        a = cj_v3_normalize(a);
        cj_vec3 e1, e2;
        cj_frame_from_axis(a, &e1, &e2);
        assert_true(fabs(cj_v3_norm(e1) - 1) < 1e-14 && fabs(cj_v3_norm(e2) - 1) < 1e-14);
        assert_true(fabs(cj_v3_dot(e1, e2)) < 1e-14 && fabs(cj_v3_dot(e1, a)) < 1e-14);
        assert_true(cj_v3_norm(cj_v3_sub(cj_v3_cross(e1, e2), a)) < 1e-14);
    }
    printf("frames: 2000 random axes (incl. +-z) give right-handed orthonormal frames\n");
}

static int n_expect;
static void expect(cj_status got, cj_status want, const char *needle) {
    ++n_expect;
    if (got != want)
        fail_msg("expected status %s, got %s (%s)", cj_status_str(want), cj_status_str(got),
                 cj_last_error());
    if (needle && !strstr(cj_last_error(), needle))
        fail_msg("message \"%s\" does not mention \"%s\"", cj_last_error(), needle);
}

static void test_bad_input(void **state) {
    (void)state;
    cj_quadric q;
    const double nan = NAN;
    expect(cj_quadric_ellipsoid(&q, 1, 0, 1), CJ_ERR_DEGENERATE, "semi-axis b");
    expect(cj_quadric_ellipsoid(&q, nan, 1, 1), CJ_ERR_NONFINITE, "semi-axis a");
    expect(cj_quadric_ellipsoid(&q, 1, 1, -2), CJ_ERR_DEGENERATE, "semi-axis c");
    expect(cj_quadric_hyperboloid1(&q, 1, 1, 1, 2, 1), CJ_ERR_ARGUMENT, "v range");
    expect(cj_quadric_hyperboloid1(&q, 1, 1, 1, 0, 800), CJ_ERR_RANGE, "700");
    expect(cj_quadric_hyperboloid2(&q, 1, 1, 1, 2, 1), CJ_ERR_ARGUMENT, "sheet");
    expect(cj_quadric_hyperboloid2(&q, 1, 1, 1, 0, 0), CJ_ERR_ARGUMENT, "v range");
    expect(cj_quadric_cone(&q, 1, 1, 1, 0, INFINITY), CJ_ERR_NONFINITE, "v range");
    expect(cj_quadric_paraboloid(&q, 0, 1, 1), CJ_ERR_DEGENERATE, "semi-axis a");
    expect(cj_quadric_hyperbolic_paraboloid(&q, 1, 1, 0, 1, 1, 1), CJ_ERR_ARGUMENT, "v range");
    double f;
    expect(cj_quadric_implicit_eval(&q_ell, cj_v3(nan, 0, 0), &f, NULL), CJ_ERR_NONFINITE,
           "not finite");
    cj_vec3 n;
    cj_implicit_surface is;
    cj_quadric_implicit(&q_cone, &is);
    expect(cj_implicit_normal(&is, cj_v3(0, 0, 0), &n), CJ_ERR_DEGENERATE, "gradient vanishes");
    cj_param_surface s;
    cj_quadric_surface(&q_ell, &s);
    cj_vec3 p;
    expect(cj_surface_eval(&s, nan, 0, &p, NULL, NULL), CJ_ERR_NONFINITE, "parameter u");
    expect(cj_surface_eval(&s, 0, INFINITY, &p, NULL, NULL), CJ_ERR_NONFINITE, "parameter v");
    expect(cj_surface_eval(&s, 7.0, 0, &p, NULL, NULL), CJ_ERR_RANGE, "u = 7");
    expect(cj_surface_normal(&s, 0, -2.0, &n), CJ_ERR_RANGE, "v = -2");
    /* Rounding slack: one ulp past the edge is clamped, not refused. */
    assert_int_equal(cj_surface_eval(&s, nextafter(s.u1, 10.0), 0.0, &p, NULL, NULL), CJ_OK);
    cj_param_surface bad = s;
    bad.v1 = bad.v0;
    expect(cj_param_surface_check(&bad), CJ_ERR_ARGUMENT, "v-domain");
    bad = s;
    bad.eval = NULL;
    expect(cj_param_surface_check(&bad), CJ_ERR_ARGUMENT, "callback");

    cj_torus t;
    cj_vec3 o = cj_v3(0, 0, 0), z = cj_v3(0, 0, 1);
    expect(cj_torus_init(&t, o, cj_v3(0, 0, 0), 2, 1), CJ_ERR_DEGENERATE, "axis");
    expect(cj_torus_init(&t, o, cj_v3(0, nan, 1), 2, 1), CJ_ERR_NONFINITE, "axis");
    expect(cj_torus_init(&t, o, z, 1, 1), CJ_ERR_ARGUMENT, "minor radius");
    expect(cj_torus_init(&t, o, z, 2, 0), CJ_ERR_DEGENERATE, "minor radius");
    expect(cj_torus_init(&t, cj_v3(INFINITY, 0, 0), z, 2, 1), CJ_ERR_NONFINITE, "center");
    /* Huge and subnormal (but non-zero) axes are fine: they are normalised safely. */
    assert_int_equal(cj_torus_init(&t, o, cj_v3(1e300, 1e300, 0), 2, 1), CJ_OK);
    assert_true(fabs(cj_v3_norm(t.a) - 1.0) < 1e-15);
    assert_int_equal(cj_torus_init(&t, o, cj_v3(0, 4e-320, 0), 2, 1), CJ_OK);
    assert_true(t.a.y == 1.0);
    cj_cylinder cy;
    expect(cj_cylinder_init(&cy, o, z, 0.0, 0, 1), CJ_ERR_DEGENERATE, "radius");
    expect(cj_cylinder_init(&cy, o, z, 1.0, 1, 1), CJ_ERR_ARGUMENT, "height");
    expect(cj_cylinder_init(&cy, o, cj_v3(0, 0, 0), 1.0, 0, 1), CJ_ERR_DEGENERATE, "axis");
    cj_plane pl;
    expect(cj_plane_from_points(&pl, o, cj_v3(1, 1, 1), cj_v3(2, 2, 2)), CJ_ERR_DEGENERATE,
           "collinear");
    expect(cj_plane_from_point_normal(&pl, o, cj_v3(0, 0, 0)), CJ_ERR_DEGENERATE, "normal");
    cj_planar_patch pp;
    expect(cj_planar_patch_init(&pp, o, cj_v3(1, 0, 0), cj_v3(-2, 0, 0)), CJ_ERR_DEGENERATE,
           "parallel");
    cj_bilinear b;
    expect(cj_bilinear_init(&b, o, cj_v3(1, 0, 0), cj_v3(2, 0, 0), cj_v3(3, 0, 0)),
           CJ_ERR_DEGENERATE, "collinear");
    expect(cj_bilinear_init(&b, o, cj_v3(1, 0, 0), cj_v3(0, nan, 0), cj_v3(3, 0, 0)),
           CJ_ERR_NONFINITE, "corner p01");
    cj_gen_cylinder g;
    expect(cj_gen_cylinder_init(&g, &dir_curve, o, cj_v3(1, 0, 0), cj_v3(0, 1, 0), cj_v3(1, 1, 0),
                                0, 1),
           CJ_ERR_DEGENERATE, "lies in the plane");
    expect(cj_gen_cylinder_init(&g, &dir_curve, o, cj_v3(1, 0, 0), cj_v3(2, 0, 0), cj_v3(0, 0, 1),
                                0, 1),
           CJ_ERR_DEGENERATE, "parallel");
    expect(cj_gen_cylinder_init(&g, &dir_curve, o, cj_v3(1, 0, 0), cj_v3(0, 1, 0), cj_v3(0, 0, 0),
                                0, 1),
           CJ_ERR_DEGENERATE, "direction");
    cj_curve2 cc;
    const double pts3[] = {0, 0, 0, 1, 1, 1};
    cj_bezier b3 = cj_bezier_view(1, 3, pts3);
    expect(cj_curve2_from_bezier(&b3, &cc), CJ_ERR_DIMENSION, NULL);
    const double ptsnan[] = {0, 0, NAN, 1};
    cj_bezier bn = cj_bezier_view(1, 2, ptsnan);
    expect(cj_curve2_from_bezier(&bn, &cc), CJ_ERR_NONFINITE, NULL);
    cj_revolution rv;
    cj_curve2 empty = semi_curve;
    empty.t1 = empty.t0;
    expect(cj_revolution_init(&rv, &empty, o, z), CJ_ERR_ARGUMENT, "empty parameter range");
    /* A profile that is a single point on the axis. */
    const double axis_pt[] = {0, 0, 0, 0};
    cj_bezier bp = cj_bezier_view(1, 2, axis_pt);
    assert_int_equal(cj_curve2_from_bezier(&bp, &cc), CJ_OK);
    expect(cj_revolution_init(&rv, &cc, o, z), CJ_ERR_DEGENERATE, "point on the axis");
    printf("bad input: %d cases give the documented status and a message naming the input\n",
           n_expect);
}

/* Affine placement. A unit sphere scaled by (2, 1, 0.5), rotated and translated must be the
 * ellipsoid (2, 1, 0.5) under the same rigid motion: its points satisfy the ellipsoid's
 * implicit form moved by the rigid motion only, and its normals agree with that gradient. */
static void test_affine_placement(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 4);
    cj_quadric unit, ell;
    assert_int_equal(cj_quadric_ellipsoid(&unit, 1, 1, 1), CJ_OK);
    assert_int_equal(cj_quadric_ellipsoid(&ell, 2, 1, 0.5), CJ_OK);
    cj_xform3 rot, scale = cj_xform3_scale(2, 1, 0.5), tr = cj_xform3_translate(1, -2, 3);
    assert_int_equal(cj_xform3_rotate_axis(cj_v3(1, 2, 0.5), 0.8, &rot), CJ_OK);
    cj_xform3 rigid = cj_xform3_compose(&tr, &rot), full = cj_xform3_compose(&rigid, &scale);
    cj_param_surface us, ps;
    cj_implicit_surface ei, pi;
    cj_quadric_surface(&unit, &us);
    cj_quadric_implicit(&ell, &ei);
    cj_transformed_surface st_p, st_i;
    assert_int_equal(cj_surface_transform(&full, &us, &st_p, &ps), CJ_OK);
    assert_int_equal(cj_implicit_transform(&rigid, &ei, &st_i, &pi), CJ_OK);
    assert_true(ps.flags == us.flags && ps.v0 == us.v0);
    tcase t = {"placed ellipsoid", ps, pi, 1, {1, -2, 3}, 1};
    double worst = 0.0, worst_fd = 0.0;
    for (int k = 0; k < 1000; ++k) {
        double u, v, rel;
        draw_uv(&r, &ps, 0.0, &u, &v);
        cj_vec3 p, su, sv, n, g;
        assert_int_equal(cj_surface_eval(&ps, u, v, &p, &su, &sv), CJ_OK);
        if (!on_surface(&t, p, &rel))
            fail_msg("placed ellipsoid: S(%.17g,%.17g) off the surface (%g); seed %llu", u, v, rel,
                     (unsigned long long)seed);
        assert_int_equal(cj_surface_normal(&ps, u, v, &n), CJ_OK);
        assert_int_equal(cj_implicit_normal(&pi, p, &g), CJ_OK);
        double d = 1.0 - cj_v3_dot(n, g);
        if (d > worst) worst = d;
        if (d > 1e-12)
            fail_msg("placed ellipsoid: normal vs gradient at (%.17g,%.17g): %g; seed %llu", u, v,
                     d, (unsigned long long)seed);
        assert_true(cj_v3_dot(n, cj_v3_sub(p, t.center)) > 0.0);
        if (v > ps.v0 + 1e-4 && v < ps.v1 - 1e-4 && u > ps.u0 + 1e-4 && u < ps.u1 - 1e-4) {
            double h = 1e-5;
            cj_vec3 a, b;
            cj_surface_eval(&ps, u + h, v, &a, NULL, NULL);
            cj_surface_eval(&ps, u - h, v, &b, NULL, NULL);
            double e = cj_v3_norm(cj_v3_sub(cj_v3_scale(cj_v3_sub(a, b), 0.5 / h), su)) /
                       (cj_v3_norm(p) + cj_v3_norm(su) + 1);
            if (e > worst_fd) worst_fd = e;
            assert_true(e < 1e-8);
        }
    }
    /* A mirror turns the parametric normal inward; the implicit gradient stays outward. */
    cj_xform3 mirror = cj_xform3_scale(-1, 1, 1);
    cj_transformed_surface st_m, st_mi;
    cj_param_surface ms;
    cj_implicit_surface mi;
    cj_quadric_implicit(&unit, &ei);
    assert_int_equal(cj_surface_transform(&mirror, &us, &st_m, &ms), CJ_OK);
    assert_int_equal(cj_implicit_transform(&mirror, &ei, &st_mi, &mi), CJ_OK);
    cj_vec3 p, n, g;
    assert_int_equal(cj_surface_eval(&ms, 0.3, 0.2, &p, NULL, NULL), CJ_OK);
    assert_int_equal(cj_surface_normal(&ms, 0.3, 0.2, &n), CJ_OK);
    assert_int_equal(cj_implicit_normal(&mi, p, &g), CJ_OK);
    assert_true(cj_v3_dot(n, g) < -1.0 + 1e-14 && cj_v3_dot(g, p) > 0.0);
    /* Bad matrices. */
    cj_xform3 proj = cj_xform3_identity(), sing = cj_xform3_scale(1, 0, 1), nanm = proj;
    proj.m[3][2] = 0.5;
    nanm.m[1][3] = NAN;
    expect(cj_surface_transform(&proj, &us, &st_m, &ms), CJ_ERR_UNSUPPORTED, "projective");
    expect(cj_surface_transform(&sing, &us, &st_m, &ms), CJ_ERR_SINGULAR, NULL);
    expect(cj_implicit_transform(&nanm, &ei, &st_mi, &mi), CJ_ERR_NONFINITE, "(1,3)");
    printf("affine placement: scaled+rotated+translated unit sphere = placed ellipsoid (1000 "
           "points, worst 1-cos %.2e, partials vs FD %.2e); mirror flips the parametric normal "
           "only; projective/singular/NaN matrices refused\n",
           worst, worst_fd);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_partials_vs_finite_differences),
        cmocka_unit_test(test_parametric_points_satisfy_implicit),
        cmocka_unit_test(test_normals_agree_with_gradients),
        cmocka_unit_test(test_pole_normals),
        cmocka_unit_test(test_flags_and_periodicity),
        cmocka_unit_test(test_frame),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_affine_placement),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
