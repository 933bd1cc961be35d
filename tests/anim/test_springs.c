/* Spring-mass systems and integrators against EXACT solutions: the undamped and damped
 * oscillator (closed form), each integrator's exact discrete recurrence, the symplectic
 * invariant over a million steps, a stiff spring under implicit Euler, momentum conservation,
 * the hanging-mass equilibrium, a cloth on a sphere, bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/particles.h"
#include "casteljau/springs.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* 1D: particle 0 fixed at 0, particle 1 at L + A at rest, spring (k, c), mass m. */
static cj_springs *oscillator(double k, double c, double m, double L, double A) {
    const double x[2] = {0, L + A}, mass[2] = {1, m};
    const unsigned char fixed[2] = {1, 0};
    const cj_spring sp = {0, 1, L, k, c};
    cj_springs_desc d;
    memset(&d, 0, sizeof d);
    d.dim = 1;
    d.count = 2;
    d.x = x;
    d.mass = mass;
    d.fixed = fixed;
    d.spring_count = 1;
    d.springs = &sp;
    cj_springs *s = NULL;
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_OK);
    return s;
}

static void test_symplectic_long_run(void **state) {
    (void)state;
    const double k = 4.0, m = 1.0, w = 2.0, L = 2.0, A = 1.0, h = 0.005, th = h * w;
    cj_springs *s = oscillator(k, 0, m, L, A);
    const long steps = 1000000;
    const double E0 = 0.5 * k * A * A;
    double worst = 0, inv_worst = 0, e_first = 0, e_last = 0;
    const double I0 = w * w * A * A; /* v = 0 at the start */
    for (long n = 1; n <= steps; ++n) {
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_SYMPLECTIC_EULER, h, NULL), CJ_OK);
        double ke, pe;
        cj_springs_energy(s, &ke, &pe);
        const double rel = fabs((ke + pe) / E0 - 1);
        worst = fmax(worst, rel);
        const double x = cj_springs_positions(s)[1] - L, v = cj_springs_velocities(s)[1];
        const double I = v * v + w * w * x * x - h * w * w * x * v;
        inv_worst = fmax(inv_worst, fabs(I / I0 - 1));
        if (n <= steps / 10) e_first += (ke + pe) / E0;
        if (n > steps - steps / 10) e_last += (ke + pe) / E0;
    }
    e_first /= steps / 10;
    e_last /= steps / 10;
    const double bound = th / (1 - th / 2);
    /* the exact solution x(t) = L + A cos(wt) vs the discrete one: the phase drifts at the
     * discrete frequency acos(1 - th²/2)/h, amplitude stays within the energy band */
    const double wd = acos(1 - th * th / 2) / h, T = steps * h;
    const double x_end = cj_springs_positions(s)[1] - L;
    const double exact_end = A * cos(w * T);
    printf("symplectic Euler, h*w = %g, %ld steps (%.0f periods): energy within %.3g of E0 "
           "(stated bound h*w/(1-h*w/2) = %.3g), invariant v^2+w^2x^2-h w^2 x v constant to %.2g, "
           "mean energy first/last tenth %.12f / %.12f (no drift); x(T) = %.6f vs exact %.6f "
           "(phase lag (wd-w)T = %.3g rad)\n",
           th, steps, T * w / (2 * M_PI), worst, bound, inv_worst, e_first, e_last, x_end,
           exact_end, (wd - w) * T);
    assert_true(worst <= bound);
    assert_true(inv_worst < 1e-9);
    assert_true(fabs(e_first - e_last) < 1e-4); /* window means; explicit Euler: x1e8 */
    /* the discrete solution: x_n = A' cos(wd t_n + phi) within the band: compare with the exact
     * solution at the discrete frequency */
    assert_true(fabs(x_end - A * cos(wd * T)) <= 2 * th * A);
    cj_springs_destroy(s);
}

static void test_explicit_growth_and_rk4_order(void **state) {
    (void)state;
    const double k = 9.0, m = 1.0, w = 3.0, L = 2.0, A = 0.5, h = 0.01, th = h * w;
    cj_springs *s = oscillator(k, 0, m, L, A);
    const double E0 = 0.5 * k * A * A;
    for (int n = 1; n <= 2000; ++n)
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_EXPLICIT_EULER, h, NULL), CJ_OK);
    double ke, pe;
    cj_springs_energy(s, &ke, &pe);
    const double growth = (ke + pe) / E0, exact = pow(1 + th * th, 2000);
    printf("explicit Euler, h*w = %g, 2000 steps: energy x%.9f, exact discrete growth "
           "(1+h^2w^2)^n = %.9f\n",
           th, growth, exact);
    assert_true(fabs(growth / exact - 1) < 1e-9);
    cj_springs_destroy(s);
    /* RK4 over 1.25 periods against A cos(wt) (a quarter period past the turning point, where
     * the phase error shows at first order): fourth order */
    double err[3];
    for (int q = 0; q < 3; ++q) {
        const int steps = 20 << q;
        const double hh = 2.5 * M_PI / w / steps;
        s = oscillator(k, 0, m, L, A);
        for (int n = 0; n < steps; ++n)
            assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_RK4, hh, NULL), CJ_OK);
        err[q] = fabs(cj_springs_positions(s)[1] - L - A * cos(w * steps * hh));
        cj_springs_destroy(s);
    }
    printf("RK4 over 1.25 periods, 20/40/80 steps: errors %.3g %.3g %.3g, ratios %.2f %.2f "
           "(order 4: 16)\n",
           err[0], err[1], err[2], err[0] / err[1], err[1] / err[2]);
    assert_true(err[0] / err[1] > 14 && err[0] / err[1] < 18);
    assert_true(err[1] / err[2] > 14 && err[1] / err[2] < 18);
}

static void test_damped_exact(void **state) {
    (void)state;
    /* x'' + (c/m) x' + (k/m) x = 0, underdamped: x = e^{-zeta w t}(A cos wd t + B sin wd t) */
    const double k = 25, m = 1, c = 1.2, L = 1, A = 0.3;
    const double w = 5, zeta = c / (2 * sqrt(k * m)), wd = w * sqrt(1 - zeta * zeta);
    const double B = zeta * w * A / wd;
    const double T = 3.0;
    printf("damped oscillator (zeta = %.3f) to t = %g, |x - exact|:\n", zeta, T);
    for (int mth = 0; mth < 4; ++mth) {
        double prev = 0;
        for (int q = 0; q < 3; ++q) {
            const int steps = (mth == CJ_INTEGRATE_RK4 ? 150 : 3000) << q;
            const double h = T / steps;
            cj_springs *s = oscillator(k, c, m, L, A);
            for (int n = 0; n < steps; ++n)
                assert_int_equal(cj_springs_step(s, (cj_integrator)mth, h, NULL), CJ_OK);
            const double ex = exp(-zeta * w * T) * (A * cos(wd * T) + B * sin(wd * T));
            const double e = fabs(cj_springs_positions(s)[1] - L - ex);
            printf("  %-17s h = %.2e: %.3e%s", cj_integrator_name((cj_integrator)mth), h, e,
                   q ? "" : "\n");
            if (q) {
                printf("  (ratio %.2f)\n", prev / e);
                const double want = mth == CJ_INTEGRATE_RK4 ? 16 : 2;
                if (!(prev / e > 0.8 * want && prev / e < 1.25 * want))
                    fail_msg("%s: convergence ratio %g, expected ~%g",
                             cj_integrator_name((cj_integrator)mth), prev / e, want);
            }
            prev = e;
            cj_springs_destroy(s);
        }
    }
}

static void test_stiff_implicit(void **state) {
    (void)state;
    /* k = 1e6, m = 1: w = 1000; h = 0.01 gives h*w = 10, where explicit and symplectic Euler
     * diverge. The exact solution x = A cos(wt) stays within |x| <= A; backward Euler's exact
     * recurrence is [x;v]_{n+1} = (I - hJ)^{-1}[x;v]_n, amplitude / sqrt(1 + h^2 w^2) per step. */
    const double k = 1e6, m = 1, L = 1, A = 0.01, h = 0.01, w = 1000;
    cj_springs *s = oscillator(k, 0, m, L, A);
    cj_status st = CJ_OK;
    int n = 0;
    for (n = 1; n <= 200 && st == CJ_OK; ++n)
        st = cj_springs_step(s, CJ_INTEGRATE_EXPLICIT_EULER, h, NULL);
    printf("stiff spring k = 1e6, h = 0.01 (h*w = 10): explicit Euler -> %s after %d steps (%s)\n",
           cj_status_str(st), n - 1, cj_last_error());
    assert_int_equal(st, CJ_ERR_NONFINITE);
    cj_springs_destroy(s);
    s = oscillator(k, 0, m, L, A);
    for (n = 0; n < 20; ++n)
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_SYMPLECTIC_EULER, h, NULL), CJ_OK);
    const double symp = fabs(cj_springs_positions(s)[1] - L);
    printf("  symplectic Euler after 20 steps: |x| = %.3g (exact solution never exceeds %.3g)\n",
           symp, A);
    assert_true(symp > 1e6 * A);
    cj_springs_destroy(s);
    s = oscillator(k, 0, m, L, A);
    long double x = A, v = 0; /* exact backward-Euler recurrence in long double */
    const long double hw2 = (long double)h * h * w * w, det = 1 + hw2;
    double worst_rec = 0, maxabs = 0, prevE = 1e300;
    for (n = 1; n <= 1000; ++n) {
        cj_springs_stats stats;
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_IMPLICIT_EULER, h, &stats), CJ_OK);
        /* (I - hJ) with J = [[0,1],[-w^2,0]]: [[1,-h],[h w^2,1]], inverse /det */
        const long double xn = (x + h * v) / det, vn = (v - (long double)h * w * w * x) / det;
        x = xn;
        v = vn;
        const double xs = cj_springs_positions(s)[1] - L;
        worst_rec = fmax(worst_rec, (double)fabsl(xs - x) / A);
        maxabs = fmax(maxabs, fabs(xs));
        double ke, pe;
        cj_springs_energy(s, &ke, &pe);
        assert_true(ke + pe <= prevE * (1 + 1e-12));
        prevE = ke + pe;
    }
    printf("  implicit Euler, 1000 steps: max |x| = %.3g <= A = %.3g (bounded, energy never "
           "increases), matches the exact backward-Euler recurrence to %.2g of A\n",
           maxabs, A, worst_rec);
    assert_true(maxabs <= A * (1 + 1e-12));
    assert_true(worst_rec < 1e-9);
    cj_springs_destroy(s);
}

/* Two free particles in 3D with random springs to each other: total momentum is conserved
 * (forces equal and opposite) by every integrator. Chain of 5. */
static void test_momentum_3d(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_springs/momentum", 1651));
    double x[15], v[15], m[5];
    cj_spring sp[6];
    for (int i = 0; i < 5; ++i) {
        for (int k = 0; k < 3; ++k) {
            x[3 * i + k] = cj_rng_range(&r, -1, 1);
            v[3 * i + k] = cj_rng_range(&r, -1, 1);
        }
        m[i] = cj_rng_range(&r, 0.5, 2);
    }
    for (int j = 0; j < 6; ++j) {
        sp[j].a = j % 5;
        sp[j].b = (j + 1 + j / 5) % 5;
        sp[j].rest = cj_rng_range(&r, 0.2, 1);
        sp[j].stiffness = cj_rng_range(&r, 10, 100);
        sp[j].damping = cj_rng_range(&r, 0, 1);
    }
    cj_springs_desc d;
    memset(&d, 0, sizeof d);
    d.dim = 3;
    d.count = 5;
    d.x = x;
    d.v = v;
    d.mass = m;
    d.spring_count = 6;
    d.springs = sp;
    double P0[3] = {0, 0, 0};
    for (int i = 0; i < 5; ++i)
        for (int k = 0; k < 3; ++k) P0[k] += m[i] * v[3 * i + k];
    for (int mth = 0; mth < 4; ++mth) {
        cj_springs *s = NULL;
        assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_OK);
        for (int n = 0; n < 2000; ++n)
            assert_int_equal(cj_springs_step(s, (cj_integrator)mth, 1e-3, NULL), CJ_OK);
        double P[3] = {0, 0, 0}, err = 0;
        for (int i = 0; i < 5; ++i)
            for (int k = 0; k < 3; ++k) P[k] += m[i] * cj_springs_velocities(s)[3 * i + k];
        for (int k = 0; k < 3; ++k) err = fmax(err, fabs(P[k] - P0[k]));
        printf("3D chain, %s, 2000 steps: momentum conserved to %.2g\n",
               cj_integrator_name((cj_integrator)mth), err);
        /* implicit Euler conserves it up to the CG tolerance (relative residual 1e-9 a step) */
        assert_true(err < (mth == CJ_INTEGRATE_IMPLICIT_EULER ? 2000 * 1e-9 * 5 : 1e-12));
        cj_springs_destroy(s);
    }
}

static void test_hanging_equilibrium(void **state) {
    (void)state;
    /* A mass hanging under gravity from a fixed point in 3D settles at L + mg/k below it. */
    const double x[6] = {0, 0, 0, 0.3, 0.1, -1.0}, m[2] = {1, 0.5};
    const unsigned char fixed[2] = {1, 0};
    const cj_spring sp = {0, 1, 1.0, 50.0, 2.0};
    cj_springs_desc d;
    memset(&d, 0, sizeof d);
    d.dim = 3;
    d.count = 2;
    d.x = x;
    d.mass = m;
    d.fixed = fixed;
    d.spring_count = 1;
    d.springs = &sp;
    d.gravity[2] = -9.81;
    d.drag = 2.0;
    cj_springs *s = NULL;
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_OK);
    for (int n = 0; n < 4000; ++n)
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_IMPLICIT_EULER, 0.01, NULL), CJ_OK);
    const double *p = cj_springs_positions(s);
    const double want = -(1.0 + 0.5 * 9.81 / 50.0);
    printf("hanging mass (implicit Euler, 40 s): rests at (%.2g, %.2g, %.12f), exact z = %.12f\n",
           p[3], p[4], p[5], want);
    assert_true(fabs(p[5] - want) < 1e-9 && fabs(p[3]) < 1e-9 && fabs(p[4]) < 1e-9);
    assert_true(p[0] == 0 && p[1] == 0 && p[2] == 0); /* the fixed point never moved */
    cj_springs_destroy(s);
}

static void test_cloth_on_sphere(void **state) {
    (void)state;
    const int N = 16;
    const double corner[3] = {-1, -1, 1.2}, eu[3] = {2, 0, 0}, ev[3] = {0, 2, 0};
    cj_sphere_collider sph = {{0, 0, 0}, 0.8, 0.3};
    cj_plane_collider floor = {{0, 0, 1}, -1.0, 0.5};
    cj_springs_desc extra;
    memset(&extra, 0, sizeof extra);
    extra.dim = 3;
    extra.gravity[2] = -9.81;
    extra.drag = 0.1;
    extra.sphere_count = 1;
    extra.spheres = &sph;
    extra.plane_count = 1;
    extra.planes = &floor;
    cj_springs *s = NULL;
    assert_int_equal(cj_springs_create_cloth(N, N, corner, eu, ev, 1.0, 2000, 500, 50, 0.5, NULL, 0,
                                             &extra, NULL, &s),
                     CJ_OK);
    int maxit = 0;
    size_t hits = 0;
    for (int n = 0; n < 300; ++n) {
        cj_springs_stats st;
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_IMPLICIT_EULER, 1.0 / 120, &st), CJ_OK);
        maxit = st.cg_iterations > maxit ? st.cg_iterations : maxit;
        hits = st.collisions;
    }
    const double *p = cj_springs_positions(s);
    double mind = 1e9, minz = 1e9, centre_z = 0, maxstretch = 0;
    for (int i = 0; i < N * N; ++i) {
        const double dd =
            sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
        mind = fmin(mind, dd);
        minz = fmin(minz, p[3 * i + 2]);
    }
    centre_z = p[3 * (N / 2 * N + N / 2) + 2];
    for (int i = 0; i + 1 < N; ++i) { /* structural stretch along the first row */
        double l = 0;
        for (int k = 0; k < 3; ++k) l += pow(p[3 * (i + 1) + k] - p[3 * i + k], 2);
        maxstretch = fmax(maxstretch, sqrt(l) / (2.0 / (N - 1)) - 1);
    }
    printf("cloth %dx%d (%zu springs) dropped on a sphere r = 0.8, 300 implicit steps of 1/120 s: "
           "closest particle at distance %.6f from the centre, lowest z %.3f, centre z %.3f, "
           "%zu particles touching, max CG iterations %d, edge stretch %.3f\n",
           N, N, cj_springs_spring_count(s), mind, minz, centre_z, hits, maxit, maxstretch);
    assert_true(mind >= 0.8 - 1e-9);
    assert_true(centre_z > 0.79 && centre_z < 0.9); /* resting on top of the sphere */
    assert_true(minz < 0.5);                        /* the corners hang down over its sides */
    assert_true(minz >= -1.0 - 1e-12);              /* never below the floor */
    cj_springs_destroy(s);
}

/* The generic stepper on the pendulum theta'' = -(g/l) sin(theta): backward Euler by Newton with
 * dense LAPACKE solves satisfies its defining equations to rounding, and on the linear
 * oscillator reproduces the exact recurrence. */
static void pend_accel(void *user, double t, const double *x, const double *v, double *a) {
    (void)user;
    (void)t;
    (void)v;
    a[0] = -9.81 * sin(x[0]);
}
static void pend_jac(void *user, double t, const double *x, const double *v, double *dadx,
                     double *dadv) {
    (void)user;
    (void)t;
    (void)v;
    dadx[0] = -9.81 * cos(x[0]);
    dadv[0] = 0;
}
static void test_ode2_generic(void **state) {
    (void)state;
    cj_ode2 sys = {1, NULL, pend_accel, pend_jac};
    double work[64];
    int ipiv[4], iters = 0, maxit = 0;
    assert_true(cj_ode2_work_size(1, CJ_INTEGRATE_IMPLICIT_EULER) <= 64);
    double x = 2.5, v = 0, worst = 0;
    const double h = 0.05;
    for (int n = 0; n < 200; ++n) {
        const double x0 = x, v0 = v;
        assert_int_equal(
            cj_ode2_step(&sys, CJ_INTEGRATE_IMPLICIT_EULER, n * h, h, &x, &v, work, ipiv, &iters),
            CJ_OK);
        maxit = iters > maxit ? iters : maxit;
        /* v1 = v0 + h a(x1), x1 = x0 + h v1 */
        worst = fmax(worst, fabs(v - v0 + h * 9.81 * sin(x)));
        worst = fmax(worst, fabs(x - x0 - h * v));
    }
    printf("generic backward Euler (Newton + LAPACKE dgesv) on a large-angle pendulum: defining "
           "equations satisfied to %.2g, at most %d Newton iterations\n",
           worst, maxit);
    assert_true(worst < 1e-13);
    sys.n = CJ_ODE2_DENSE_MAX + 1;
    assert_int_equal(
        cj_ode2_step(&sys, CJ_INTEGRATE_IMPLICIT_EULER, 0, h, &x, &v, work, ipiv, NULL),
        CJ_ERR_ARGUMENT);
}

/* A cloth dropped on a dome-shaped bicubic patch (x, y linear in u, v): no cloth particle ever
 * ends a step below the patch over its footprint. */
static void test_cloth_on_patch(void **state) {
    (void)state;
    double pts[16 * 3];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            double *q = pts + 3 * (4 * j + i);
            q[0] = -2 + 4.0 * i / 3; /* wider than the cloth can reach: it never gets under */
            q[1] = -2 + 4.0 * j / 3;
            q[2] = (i == 1 || i == 2) && (j == 1 || j == 2) ? 1.6 : 0.0;
        }
    const cj_patch dome = cj_patch_view(3, 3, pts, NULL);
    cj_patch_collider *pc = NULL;
    /* tol 1e-6: at 1e-9 cj_ray_patch missed some short grazing segments of sliding cloth */
    assert_int_equal(cj_patch_collider_create(&dome, 1, NULL, 1e-6, 0.5, NULL, &pc), CJ_OK);
    const cj_patch_collider *pcs[1] = {pc};
    cj_springs_desc extra;
    memset(&extra, 0, sizeof extra);
    extra.dim = 3;
    extra.gravity[2] = -9.81;
    extra.drag = 0.2;
    extra.patch_collider_count = 1;
    extra.patch_colliders = pcs;
    const double corner[3] = {-0.8, -0.8, 1.5}, eu[3] = {1.6, 0, 0}, ev[3] = {0, 1.6, 0};
    cj_springs *s = NULL;
    assert_int_equal(cj_springs_create_cloth(14, 14, corner, eu, ev, 0.5, 1500, 400, 20, 0.5, NULL,
                                             0, &extra, NULL, &s),
                     CJ_OK);
    double worst = 0;
    size_t touching = 0;
    for (int n = 0; n < 150; ++n) {
        cj_springs_stats st;
        assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_IMPLICIT_EULER, 1.0 / 120, &st), CJ_OK);
        touching = st.collisions;
        const double *x = cj_springs_positions(s);
        for (size_t i = 0; i < cj_springs_count(s); ++i) {
            const double *p = x + 3 * i;
            assert_true(fabs(p[0]) < 2 && fabs(p[1]) < 2);
            double q[3];
            assert_int_equal(
                cj_patch_eval(&dome, CJ_EVAL_DECASTELJAU, (p[0] + 2) / 4, (p[1] + 2) / 4, q),
                CJ_OK);
            worst = fmax(worst, q[2] - p[2]);
            if (q[2] - p[2] > 1e-7)
                fail_msg("step %d particle %zu is %g below the dome", n, i, q[2] - p[2]);
        }
    }
    printf("cloth 14x14 on a bicubic dome (patch collider, segment test): never below it (worst "
           "%.2g), %zu particles pushed back in the last step\n",
           worst, touching);
    assert_true(touching > 0);
    cj_springs_destroy(s);
    cj_patch_collider_destroy(pc);
}

static void test_bad_input(void **state) {
    (void)state;
    double x[2] = {0, 1};
    const double m[2] = {1, 1};
    cj_spring sp = {0, 2, 1, 1, 0};
    cj_springs_desc d;
    memset(&d, 0, sizeof d);
    d.dim = 1;
    d.count = 2;
    d.x = x;
    d.mass = m;
    d.spring_count = 1;
    d.springs = &sp;
    cj_springs *s = NULL;
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "spring 0"));
    sp.b = 1;
    sp.stiffness = -1;
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_ERR_RANGE);
    sp.stiffness = 1;
    x[1] = NAN;
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "particle 1"));
    x[1] = 1;
    d.dim = 4;
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_ERR_DIMENSION);
    d.dim = 1;
    assert_null(s);
    assert_int_equal(cj_springs_create(&d, NULL, &s), CJ_OK);
    assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_RK4, -0.1, NULL), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "time step"));
    assert_int_equal(cj_springs_step(s, CJ_INTEGRATE_RK4, NAN, NULL), CJ_ERR_RANGE);
    assert_true(cj_springs_time(s) == 0);
    cj_springs_destroy(s);
    printf("refused: spring naming a missing particle, negative stiffness, NaN position, dim 4, "
           "negative and NaN time steps\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_symplectic_long_run),
        cmocka_unit_test(test_explicit_growth_and_rk4_order),
        cmocka_unit_test(test_damped_exact),
        cmocka_unit_test(test_stiff_implicit),
        cmocka_unit_test(test_momentum_3d),
        cmocka_unit_test(test_hanging_equilibrium),
        cmocka_unit_test(test_cloth_on_sphere),
        cmocka_unit_test(test_ode2_generic),
        cmocka_unit_test(test_cloth_on_patch),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
