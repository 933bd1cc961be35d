/* Particle systems: ballistic and drag motion against their exact discrete and continuous
 * solutions, lifetimes, bounces off planes and spheres, flocking rules, seeded reproducibility,
 * and a checkpoint written mid-run that resumes bit-identically. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/particles.h"
#include "casteljau/transform.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static cj_particles_desc base_desc(size_t cap) {
    cj_particles_desc d;
    memset(&d, 0, sizeof d);
    d.capacity = cap;
    d.seed = 42;
    return d;
}

static cj_particles *make(const cj_particles_desc *d) {
    cj_particles *p = NULL;
    if (cj_particles_create(d, NULL, &p) != CJ_OK) fail_msg("create: %s", cj_last_error());
    return p;
}

static void test_ballistic_and_drag(void **state) {
    (void)state;
    cj_particles_desc d = base_desc(4);
    d.gravity[2] = -9.81;
    cj_particles *p = make(&d);
    const double x0[3] = {1, 2, 3}, v0[3] = {0.5, -1, 4}, h = 0.01;
    assert_int_equal(cj_particles_add(p, x0, v0, 100), CJ_OK);
    const int N = 150;
    for (int n = 0; n < N; ++n) assert_int_equal(cj_particles_step(p, h, NULL), CJ_OK);
    const double *x = cj_particles_positions(p);
    /* symplectic Euler, constant g: x_N = x0 + N h v0 + h² g N(N+1)/2 */
    const double zd = x0[2] + N * h * v0[2] + h * h * -9.81 * N * (N + 1) / 2.0;
    const double t = N * h, zc = x0[2] + v0[2] * t - 9.81 * t * t / 2;
    printf("ballistic, 150 steps of 0.01: z = %.15f, exact discrete %.15f, exact continuous "
           "%.15f (difference g h t / 2 = %.6f)\n",
           x[2], zd, zc, 9.81 * h * t / 2);
    assert_true(fabs(x[2] - zd) < 1e-12);
    assert_true(fabs(x[0] - (x0[0] + v0[0] * t)) < 1e-12);
    assert_true(fabs((zc - x[2]) - 9.81 * h * t / 2) < 1e-12);
    cj_particles_destroy(p);
    /* drag towards a wind: v_N = w + (v0 − w)(1 − h k)^N, continuous w + (v0 − w) e^{−kt} */
    d = base_desc(4);
    d.drag = 2.0;
    d.wind[0] = 3.0;
    p = make(&d);
    const double z3[3] = {0, 0, 0}, vv[3] = {-1, 0, 0};
    assert_int_equal(cj_particles_add(p, z3, vv, 100), CJ_OK);
    for (int n = 0; n < N; ++n) assert_int_equal(cj_particles_step(p, h, NULL), CJ_OK);
    const double vd = 3 + (-1 - 3) * pow(1 - h * 2, N), vc = 3 + (-1 - 3) * exp(-2 * t);
    const double vx = cj_particles_velocities(p)[0];
    printf("drag k = 2 towards wind 3: v = %.12f, exact discrete %.12f, continuous %.12f\n", vx, vd,
           vc);
    assert_true(fabs(vx - vd) < 1e-12);
    assert_true(fabs(vx - vc) < 2 * h * 2 * 4); /* first order: O(h k |v0 - w|) */
    cj_particles_destroy(p);
}

static void test_lifetimes(void **state) {
    (void)state;
    cj_particles_desc d = base_desc(1000);
    cj_emitter e = cj_emitter_defaults();
    e.rate = 100;
    e.lifetime = 0.505;
    d.emitter_count = 1;
    d.emitters = &e;
    cj_particles *p = make(&d);
    size_t emitted = 0, died = 0;
    for (int n = 0; n < 300; ++n) {
        cj_particles_stats st;
        assert_int_equal(cj_particles_step(p, 0.01, &st), CJ_OK);
        emitted += st.emitted;
        died += st.died;
        for (size_t i = 0; i < cj_particles_count(p); ++i)
            assert_true(cj_particles_ages(p)[i] < cj_particles_lifetimes(p)[i]);
    }
    printf("emitter 100/s, lifetime 0.505 s, 3 s of steps 0.01: %zu alive (steady state "
           "rate x lifetime = 50.5), %zu emitted, %zu died\n",
           cj_particles_count(p), emitted, died);
    assert_true(emitted == 300 && emitted - died == cj_particles_count(p));
    assert_true(cj_particles_count(p) == 50 || cj_particles_count(p) == 51);
    cj_particles_destroy(p);
    /* a full pool drops particles and says so */
    d.capacity = 10;
    p = make(&d);
    size_t dropped = 0;
    for (int n = 0; n < 30; ++n) {
        cj_particles_stats st;
        assert_int_equal(cj_particles_step(p, 0.01, &st), CJ_OK);
        dropped += st.dropped;
    }
    assert_true(cj_particles_count(p) == 10 && dropped == 20);
    cj_particles_destroy(p);
}

static double apex_after_bounce(double restitution) {
    cj_particles_desc d = base_desc(1);
    d.gravity[2] = -9.81;
    cj_plane_collider floor = {{0, 0, 1}, 0.0, 0.0};
    d.plane_count = 1;
    d.planes = &floor;
    d.restitution = restitution;
    cj_particles *p = make(&d);
    const double x0[3] = {0, 0, 1}, v0[3] = {0, 0, 0};
    assert_int_equal(cj_particles_add(p, x0, v0, 100), CJ_OK);
    int bounced = 0;
    double apex = 0, prevz = 1;
    for (int n = 0; n < 20000; ++n) {
        cj_particles_stats st;
        assert_int_equal(cj_particles_step(p, 1e-4, &st), CJ_OK);
        const double z = cj_particles_positions(p)[2];
        assert_true(z >= 0);
        if (st.collisions) bounced = 1;
        if (bounced) apex = fmax(apex, z);
        if (bounced && z < prevz && apex > 0 && cj_particles_velocities(p)[2] < 0) break;
        prevz = z;
    }
    cj_particles_destroy(p);
    return apex;
}

static void test_bounces(void **state) {
    (void)state;
    const double a1 = apex_after_bounce(1.0), a5 = apex_after_bounce(0.5);
    printf("drop from z = 1 on a plane (h = 1e-4): apex after the bounce %.5f with restitution 1 "
           "(exact 1), %.5f with 0.5 (exact 0.25)\n",
           a1, a5);
    assert_true(fabs(a1 - 1) < 2e-3);
    assert_true(fabs(a5 - 0.25) < 2e-3);
    /* a shower on a sphere: nobody inside after any step */
    cj_particles_desc d = base_desc(2000);
    cj_emitter e = cj_emitter_defaults();
    e.position[2] = 2;
    e.direction[2] = -1;
    e.spread = 0.4;
    e.speed = 2;
    e.rate = 2000;
    e.jitter_radius = 0.3;
    d.emitter_count = 1;
    d.emitters = &e;
    d.gravity[2] = -9.81;
    cj_sphere_collider sph = {{0, 0, 0}, 0.7, 0.1};
    d.sphere_count = 1;
    d.spheres = &sph;
    d.restitution = 0.6;
    cj_particles *p = make(&d);
    double mind = 1e9;
    size_t hits = 0;
    for (int n = 0; n < 150; ++n) {
        cj_particles_stats st;
        assert_int_equal(cj_particles_step(p, 1.0 / 240, &st), CJ_OK);
        hits += st.collisions;
        for (size_t i = 0; i < cj_particles_count(p); ++i) {
            const double *x = cj_particles_positions(p) + 3 * i;
            mind = fmin(mind, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
        }
    }
    printf("shower of %zu particles on a sphere r = 0.7: %zu collisions, closest particle at %.12f "
           "after any step\n",
           cj_particles_count(p), hits, mind);
    assert_true(hits > 100 && mind >= 0.7 - 1e-12);
    cj_particles_destroy(p);
}

static double spread_of(const double *a, size_t n) {
    double m[3] = {0, 0, 0}, s = 0;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) m[k] += a[3 * i + k] / (double)n;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) s += (a[3 * i + k] - m[k]) * (a[3 * i + k] - m[k]);
    return sqrt(s / (double)n);
}

static void test_flocking(void **state) {
    (void)state;
    double res[4][2];
    for (int rule = 0; rule < 4; ++rule) {
        cj_particles_desc d = base_desc(64);
        d.flocking.radius = rule == 3 ? 0 : 100;
        d.flocking.separation = rule == 0 ? 0.05 : 0;
        d.flocking.alignment = rule == 1 ? 2 : 0;
        d.flocking.cohesion = rule == 2 ? 1 : 0;
        cj_particles *p = make(&d);
        for (int i = 0; i < 64; ++i) { /* a fixed, irregular start (no RNG involved) */
            const double x[3] = {sin(i * 1.7), cos(i * 2.3), sin(i * 0.9 + 1)};
            const double v[3] = {cos(i * 1.1), sin(i * 0.7), cos(i * 3.1)};
            assert_int_equal(cj_particles_add(p, x, v, 100), CJ_OK);
        }
        double mind0 = 1e9;
        for (int i = 0; i < 64; ++i)
            for (int j = 0; j < i; ++j) {
                double s = 0;
                for (int k = 0; k < 3; ++k)
                    s += pow(cj_particles_positions(p)[3 * i + k] -
                                 cj_particles_positions(p)[3 * j + k],
                             2);
                mind0 = fmin(mind0, sqrt(s));
            }
        const double vs0 = spread_of(cj_particles_velocities(p), 64);
        for (int n = 0; n < 100; ++n) assert_int_equal(cj_particles_step(p, 0.01, NULL), CJ_OK);
        res[rule][0] = spread_of(cj_particles_positions(p), 64);
        res[rule][1] = spread_of(cj_particles_velocities(p), 64) / vs0;
        cj_particles_destroy(p);
    }
    printf("flocking after 1 s (64 boids): position spread separation %.3f / none %.3f / "
           "cohesion %.3f; velocity spread (relative) alignment %.3f / none %.3f\n",
           res[0][0], res[3][0], res[2][0], res[1][1], res[3][1]);
    assert_true(res[0][0] > res[3][0] * 1.01);                   /* separation spreads the flock */
    assert_true(res[2][0] < res[3][0] * 0.9);                    /* cohesion gathers it */
    assert_true(res[1][1] < 0.5 && fabs(res[3][1] - 1) < 1e-12); /* alignment equalises v */
}

static cj_particles_desc busy_desc(cj_emitter *e, cj_sphere_collider *s, cj_plane_collider *pl) {
    cj_particles_desc d = base_desc(250);
    *e = cj_emitter_defaults();
    e->rate = 150;
    e->speed = 3;
    e->speed_jitter = 0.3;
    e->lifetime = 1.5;
    e->lifetime_jitter = 0.5;
    e->jitter_radius = 0.2;
    e->spread = 0.8;
    d.emitter_count = 1;
    d.emitters = e;
    d.gravity[2] = -9.81;
    d.drag = 0.3;
    d.wind[0] = 1;
    *s = (cj_sphere_collider){{0.3, 0, 1.0}, 0.4, 0.2};
    *pl = (cj_plane_collider){{0, 0, 1}, -0.5, 0.3};
    d.sphere_count = 1;
    d.spheres = s;
    d.plane_count = 1;
    d.planes = pl;
    d.restitution = 0.7;
    d.flocking = (cj_flocking){0.3, 0.01, 0.1, 0.1, 6};
    return d;
}

static int same_state(const cj_particles *a, const cj_particles *b) {
    const size_t n = cj_particles_count(a);
    return n == cj_particles_count(b) && cj_particles_time(a) == cj_particles_time(b) &&
           !memcmp(cj_particles_positions(a), cj_particles_positions(b), sizeof(double) * 3 * n) &&
           !memcmp(cj_particles_velocities(a), cj_particles_velocities(b),
                   sizeof(double) * 3 * n) &&
           !memcmp(cj_particles_ages(a), cj_particles_ages(b), sizeof(double) * n) &&
           !memcmp(cj_particles_lifetimes(a), cj_particles_lifetimes(b), sizeof(double) * n);
}

static void test_checkpoint_resume(void **state) {
    (void)state;
    cj_emitter e;
    cj_sphere_collider s;
    cj_plane_collider pl;
    const cj_particles_desc d = busy_desc(&e, &s, &pl);
    const double h = 1.0 / 120;
    cj_particles *a = make(&d), *b = make(&d), *c = make(&d);
    FILE *f = tmpfile();
    assert_non_null(f);
    for (int n = 0; n < 240; ++n) {
        assert_int_equal(cj_particles_step(a, h, NULL), CJ_OK);
        assert_int_equal(cj_particles_step(c, h, NULL), CJ_OK);
        if (n < 120) assert_int_equal(cj_particles_step(b, h, NULL), CJ_OK);
        if (n == 119) assert_int_equal(cj_particles_save(b, f), CJ_OK);
    }
    assert_true(same_state(a, c)); /* same seed, same steps: identical */
    cj_particles_destroy(b);
    b = make(&d); /* a fresh process */
    rewind(f);
    assert_int_equal(cj_particles_load(b, f), CJ_OK);
    assert_true(cj_particles_steps(b) == 120);
    for (int n = 120; n < 240; ++n) assert_int_equal(cj_particles_step(b, h, NULL), CJ_OK);
    printf("checkpoint at step 120 of 240 (%zu particles alive at the end, emitter + drag + "
           "wind + flocking + sphere + plane): resumed run bit-identical to the uninterrupted "
           "one: %s\n",
           cj_particles_count(a), same_state(a, b) ? "yes" : "NO");
    assert_true(same_state(a, b));
    assert_true(cj_particles_count(a) > 50);
    /* another seed gives another run */
    cj_particles_desc d2 = d;
    d2.seed = 43;
    cj_particles *o = make(&d2);
    for (int n = 0; n < 240; ++n) assert_int_equal(cj_particles_step(o, h, NULL), CJ_OK);
    assert_false(same_state(a, o));
    /* a checkpoint of another system, or a truncated one, changes nothing */
    cj_particles_desc d3 = d;
    d3.capacity = 200;
    cj_particles *w = make(&d3);
    rewind(f);
    assert_int_equal(cj_particles_load(w, f), CJ_ERR_PARSE);
    printf("  refused: %s\n", cj_last_error());
    FILE *g = tmpfile();
    assert_int_equal(cj_particles_save(a, g), CJ_OK);
    const long len = ftell(g);
    rewind(g);
    char buf[1 << 16];
    assert_true(len < (long)sizeof buf);
    assert_true(fread(buf, 1, (size_t)len, g) == (size_t)len);
    fclose(g);
    g = tmpfile();
    fwrite(buf, 1, (size_t)len - 5, g);
    rewind(g);
    assert_int_equal(cj_particles_load(o, g), CJ_ERR_PARSE);
    printf("  refused: %s\n", cj_last_error());
    assert_true(cj_particles_steps(o) == 240); /* unchanged */
    fclose(g);
    fclose(f);
    cj_particles_destroy(a);
    cj_particles_destroy(b);
    cj_particles_destroy(c);
    cj_particles_destroy(o);
    cj_particles_destroy(w);
}

/* Rain onto a wavy bicubic height field z = S(x/2, y/2) (x and y linear in u and v): fast
 * particles (half a bump per step) never end a step below the surface — the segment test of the
 * ray tracer's patch intersection stops tunnelling. */
static void test_patch_collider(void **state) {
    (void)state;
    double pts[16 * 3];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            double *q = pts + 3 * (4 * j + i);
            q[0] = 2.0 * i / 3;
            q[1] = 2.0 * j / 3;
            q[2] = 0.6 * sin(1.7 * i + 2.3 * j) - 0.5;
        }
    const cj_patch patch = cj_patch_view(3, 3, pts, NULL);
    const cj_xform3 up = cj_xform3_translate(0, 0, 0.5); /* the collider lifts it back to z ~ 0 */
    cj_patch_collider *pc = NULL;
    assert_int_equal(cj_patch_collider_create(&patch, 1, &up, 1e-9, 0.2, NULL, &pc), CJ_OK);
    cj_particles_desc d = base_desc(400);
    cj_emitter e = cj_emitter_defaults();
    e.position[0] = e.position[1] = 1;
    e.position[2] = 1.5;
    e.jitter_radius = 0.7;
    e.direction[2] = -1;
    e.spread = 0.2;
    e.speed = 25;
    e.rate = 600;
    e.lifetime = 1;
    d.emitter_count = 1;
    d.emitters = &e;
    d.gravity[2] = -9.81;
    d.restitution = 0.5;
    const cj_patch_collider *pcs[1] = {pc};
    d.patch_collider_count = 1;
    d.patch_colliders = pcs;
    cj_particles *p = make(&d);
    size_t hits = 0, checked = 0;
    double worst = 0;
    for (int n = 0; n < 60; ++n) {
        cj_particles_stats st;
        assert_int_equal(cj_particles_step(p, 1.0 / 60, &st), CJ_OK);
        hits += st.collisions;
        for (size_t i = 0; i < cj_particles_count(p); ++i) {
            const double *x = cj_particles_positions(p) + 3 * i;
            if (x[0] < 0.01 || x[0] > 1.99 || x[1] < 0.01 || x[1] > 1.99) continue;
            double s[3];
            assert_int_equal(cj_patch_eval(&patch, CJ_EVAL_DECASTELJAU, x[0] / 2, x[1] / 2, s),
                             CJ_OK);
            const double below = (s[2] + 0.5) - x[2];
            worst = fmax(worst, below);
            ++checked;
            if (below > 1e-7)
                fail_msg("step %d particle %zu at (%g, %g, %g) is %g below the surface", n, i, x[0],
                         x[1], x[2], below);
        }
    }
    printf("rain at 25 m/s (0.4 per step) on a wavy bicubic patch collider: %zu hits, %zu "
           "positions over the patch checked, none below it (worst %.2g)\n",
           hits, checked, worst);
    assert_true(hits > 100 && checked > 1000);
    cj_particles_destroy(p);
    /* the segment query itself */
    const double a[3] = {1, 1, 3}, b[3] = {1, 1, -3};
    double t, q[3], nn[3], s[3];
    assert_int_equal(cj_patch_collider_segment(pc, a, b, &t, q, nn), 1);
    assert_int_equal(cj_patch_eval(&patch, CJ_EVAL_DECASTELJAU, 0.5, 0.5, s), CJ_OK);
    assert_true(fabs(q[2] - (s[2] + 0.5)) < 1e-8 && nn[2] > 0);
    const double c1[3] = {5, 5, 3}, c2[3] = {5, 5, -3};
    assert_int_equal(cj_patch_collider_segment(pc, c1, c2, &t, q, nn), 0);
    cj_patch_collider_destroy(pc);
}

static void test_bad_input(void **state) {
    (void)state;
    cj_particles_desc d = base_desc(10);
    cj_emitter e = cj_emitter_defaults();
    e.direction[1] = NAN;
    d.emitter_count = 1;
    d.emitters = &e;
    cj_particles *p = NULL;
    assert_int_equal(cj_particles_create(&d, NULL, &p), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "emitter 0"));
    e.direction[1] = 0;
    e.spread = 4;
    assert_int_equal(cj_particles_create(&d, NULL, &p), CJ_ERR_RANGE);
    e.spread = 0.1;
    d.restitution = 1.5;
    assert_int_equal(cj_particles_create(&d, NULL, &p), CJ_ERR_RANGE);
    d.restitution = 0.5;
    d.capacity = 0;
    assert_int_equal(cj_particles_create(&d, NULL, &p), CJ_ERR_EMPTY);
    d.capacity = 10;
    assert_null(p);
    p = make(&d);
    assert_int_equal(cj_particles_step(p, 0, NULL), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "time step"));
    assert_int_equal(cj_particles_step(p, NAN, NULL), CJ_ERR_RANGE);
    cj_particles_destroy(p);
    printf("refused: NaN emitter direction (named), spread > pi, restitution 1.5, capacity 0, "
           "time steps 0 and NaN\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ballistic_and_drag),
        cmocka_unit_test(test_lifetimes),
        cmocka_unit_test(test_bounces),
        cmocka_unit_test(test_flocking),
        cmocka_unit_test(test_checkpoint_resume),
        cmocka_unit_test(test_patch_collider),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
