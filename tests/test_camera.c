/* scene/: the camera model (seed 6): frame, viewing transform, perspective and orthographic
 * projection with pseudodepth in [−1, 1], primary rays consistent with the projection, and
 * refusal of bad cameras. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/scene.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static uint64_t g_seed;

static cj_vec3 rand_dir(cj_rng *r) {
    for (;;) {
        cj_vec3 v = cj_v3(cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1));
        const double n = cj_v3_norm(v);
        if (n > 0.1 && n <= 1.0) return v;
    }
}

static cj_camera rand_camera(cj_rng *r, int ortho) {
    cj_camera c = cj_camera_defaults();
    c.eye = cj_v3(cj_rng_range(r, -10, 10), cj_rng_range(r, -10, 10), cj_rng_range(r, -10, 10));
    c.gaze = cj_v3_scale(rand_dir(r), cj_rng_range(r, 0.01, 100));
    for (;;) {
        c.up = cj_v3_scale(rand_dir(r), cj_rng_range(r, 0.1, 10));
        const double s = cj_v3_norm(cj_v3_cross(cj_v3_normalize(c.up), cj_v3_normalize(c.gaze)));
        if (s > 0.05) break;
    }
    c.near = -cj_rng_range(r, 0.01, 2);
    c.far = c.near - cj_rng_range(r, 1, 1000);
    c.projection = ortho ? CJ_PROJ_ORTHOGRAPHIC : CJ_PROJ_PERSPECTIVE;
    c.fov_y = cj_rng_range(r, 0.05, 3.0);
    c.ortho_height = cj_rng_range(r, 0.1, 50);
    return c;
}

static cj_vec3 apply(const cj_xform3 *m, cj_vec3 p, double *w) {
    double in[4] = {p.x, p.y, p.z, 1.0}, out[4];
    for (int i = 0; i < 4; ++i) {
        out[i] = 0;
        for (int j = 0; j < 4; ++j) out[i] += m->m[i][j] * in[j];
    }
    if (w) *w = out[3];
    return cj_v3(out[0], out[1], out[2]);
}

static void test_default_and_basis(void **state) {
    (void)state;
    cj_camera c = cj_camera_defaults();
    assert_int_equal(cj_camera_check(&c), CJ_OK);
    cj_vec3 u, v, w;
    assert_int_equal(cj_camera_basis(&c, &u, &v, &w), CJ_OK);
    /* Default: gaze −z, up +y => u = +x, v = +y, w = +z. */
    assert_true(fabs(u.x - 1) < 1e-15 && fabs(v.y - 1) < 1e-15 && fabs(w.z - 1) < 1e-15);
    cj_rng r;
    cj_rng_init(&r, g_seed);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        cj_camera k = rand_camera(&r, i & 1);
        assert_int_equal(cj_camera_basis(&k, &u, &v, &w), CJ_OK);
        const double e[] = {cj_v3_norm(u) - 1, cj_v3_norm(v) - 1, cj_v3_norm(w) - 1,
                            cj_v3_dot(u, v),   cj_v3_dot(v, w),   cj_v3_dot(u, w)};
        for (int j = 0; j < 6; ++j) worst = fmax(worst, fabs(e[j]));
        const cj_vec3 x = cj_v3_sub(cj_v3_cross(u, v), w); /* right-handed */
        worst = fmax(worst, cj_v3_norm(x));
        /* w is −gaze, v is on the up side. */
        assert_true(cj_v3_dot(w, k.gaze) < 0);
        assert_true(cj_v3_dot(v, k.up) > 0);
        assert_true(fabs(cj_v3_dot(u, k.up)) < 1e-12 * cj_v3_norm(k.up));
    }
    printf("test_camera: 2000 random frames orthonormal and right-handed, worst error %.2e\n",
           worst);
    assert_true(worst < 1e-14);
}

static void test_view(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 1);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        cj_camera k = rand_camera(&r, i & 1);
        cj_xform3 m;
        assert_int_equal(cj_camera_view(&k, &m), CJ_OK);
        double w;
        cj_vec3 e = apply(&m, k.eye, &w);
        assert_true(w == 1.0);
        const double scale = 1 + cj_v3_norm(k.eye);
        worst = fmax(worst, cj_v3_norm(e) / scale);
        cj_vec3 g = apply(&m, cj_v3_add(k.eye, k.gaze), &w);
        const double gn = cj_v3_norm(k.gaze);
        worst = fmax(worst, (fabs(g.x) + fabs(g.y) + fabs(g.z + gn)) / (scale + gn));
        cj_vec3 t = apply(&m, cj_v3_add(k.eye, k.up), &w); /* up lands in the y-z plane, y > 0 */
        worst = fmax(worst, fabs(t.x) / (scale + cj_v3_norm(k.up)));
        assert_true(t.y > 0);
    }
    printf("test_camera: view maps eye -> 0, gaze -> -z, up -> +y half of y-z plane; worst "
           "relative error %.2e\n",
           worst);
    assert_true(worst < 1e-13);
}

static void test_projection(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 2);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const int ortho = i & 1;
        cj_camera k = rand_camera(&r, ortho);
        const double aspect = cj_rng_range(&r, 0.2, 5);
        cj_xform3 P;
        assert_int_equal(cj_camera_projection(&k, aspect, &P), CJ_OK);
        const double zs[2] = {k.near, k.far};
        for (int j = 0; j < 2; ++j) {
            const double z = zs[j];
            /* Frustum corners at depth z. */
            const double hy = ortho ? 0.5 * k.ortho_height : -z * tan(0.5 * k.fov_y);
            const double hx = hy * aspect;
            for (int c = 0; c < 4; ++c) {
                const double sx = (c & 1) ? 1 : -1, sy = (c & 2) ? 1 : -1;
                double w;
                cj_vec3 q = apply(&P, cj_v3(sx * hx, sy * hy, z), &w);
                assert_true(w > 0);
                worst = fmax(worst, fabs(q.x / w - sx));
                worst = fmax(worst, fabs(q.y / w - sy));
                worst = fmax(worst, fabs(q.z / w - (j == 0 ? -1.0 : 1.0)));
            }
        }
        /* Pseudodepth strictly increasing from near to far. */
        double prev = -2;
        for (int s = 0; s <= 64; ++s) {
            const double z = k.near + (k.far - k.near) * s / 64.0;
            double w;
            cj_vec3 q = apply(&P, cj_v3(0, 0, z), &w);
            const double zn = q.z / w;
            assert_true(zn > prev);
            prev = zn;
        }
    }
    printf("test_camera: near/far -> -1/+1, frustum corners -> (+-1, +-1) on 2000 cameras, "
           "pseudodepth increasing; worst error %.2e\n",
           worst);
    assert_true(worst < 1e-9);
}

static void test_ray_round_trip(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 3);
    double worst = 0;
    int checked = 0;
    for (int i = 0; i < 4000; ++i) {
        const int ortho = i & 1;
        cj_camera k = rand_camera(&r, ortho);
        k.fov_y = cj_rng_range(&r, 0.1, 2.5);
        const int W = cj_rng_int(&r, 1, 4000), H = cj_rng_int(&r, 1, 4000);
        const double aspect = (double)W / H;
        cj_xform3 M;
        assert_int_equal(cj_camera_world_to_clip(&k, aspect, &M), CJ_OK);
        const double px = cj_rng_range(&r, 0, W), py = cj_rng_range(&r, 0, H);
        cj_vec3 o, d;
        assert_int_equal(cj_camera_ray(&k, W, H, px, py, &o, &d), CJ_OK);
        assert_true(fabs(cj_v3_norm(d) - 1) < 1e-14);
        cj_vec3 u, v, w;
        assert_int_equal(cj_camera_basis(&k, &u, &v, &w), CJ_OK);
        if (ortho)
            assert_true(fabs(cj_v3_dot(cj_v3_sub(o, k.eye), w)) < 1e-9 * (1 + cj_v3_norm(k.eye)));
        else
            assert_true(cj_v3_norm(cj_v3_sub(o, k.eye)) == 0);
        /* A point of the ray between the planes projects back to (px, py). */
        const double zc = cj_rng_range(&r, k.far, k.near); /* camera depth wanted */
        const double t = zc / cj_v3_dot(d, w);             /* (o + t d − ē)·w = zc */
        const cj_vec3 pp = cj_v3_add(o, cj_v3_scale(d, t));
        double wc;
        cj_vec3 q = apply(&M, pp, &wc);
        assert_true(wc > 0);
        const double sx = (q.x / wc + 1) * W / 2, sy = (q.y / wc + 1) * H / 2;
        const double e = fmax(fabs(sx - px), fabs(sy - py));
        worst = fmax(worst, e);
        assert_true(q.z / wc >= -1 - 1e-9 && q.z / wc <= 1 + 1e-9);
        checked++;
    }
    printf("test_camera: %d rays through random image points reproject to their point, worst "
           "%.2e px\n",
           checked, worst);
    assert_true(worst < 1e-6);
}

static void test_errors(void **state) {
    (void)state;
    cj_camera c = cj_camera_defaults();
    cj_xform3 m;
    cj_vec3 u, v, w;
    c.far = c.near;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_RANGE);
    assert_int_equal(cj_camera_projection(&c, 1.0, &m), CJ_ERR_RANGE);
    c = cj_camera_defaults();
    c.far = -0.05; /* F > f */
    assert_int_equal(cj_camera_check(&c), CJ_ERR_RANGE);
    c = cj_camera_defaults();
    c.near = 0;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_RANGE);
    c.near = 0.5;
    assert_int_equal(cj_camera_view(&c, &m), CJ_ERR_RANGE);
    c = cj_camera_defaults();
    c.gaze = cj_v3(0, 0, 0);
    assert_int_equal(cj_camera_basis(&c, &u, &v, &w), CJ_ERR_DEGENERATE);
    c = cj_camera_defaults();
    c.up = cj_v3(0, 0, 3); /* parallel to the gaze */
    assert_int_equal(cj_camera_check(&c), CJ_ERR_DEGENERATE);
    c.up = cj_v3(0, 0, 0);
    assert_int_equal(cj_camera_check(&c), CJ_ERR_DEGENERATE);
    c = cj_camera_defaults();
    c.eye.y = NAN;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_NONFINITE);
    c = cj_camera_defaults();
    c.near = NAN;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_NONFINITE);
    c = cj_camera_defaults();
    c.gaze.x = INFINITY;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_NONFINITE);
    c = cj_camera_defaults();
    c.fov_y = 3.2;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_RANGE);
    c.fov_y = NAN;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_NONFINITE);
    c = cj_camera_defaults();
    c.projection = CJ_PROJ_ORTHOGRAPHIC;
    c.ortho_height = 0;
    assert_int_equal(cj_camera_check(&c), CJ_ERR_RANGE);
    c = cj_camera_defaults();
    assert_int_equal(cj_camera_projection(&c, 0.0, &m), CJ_ERR_RANGE);
    assert_int_equal(cj_camera_projection(&c, NAN, &m), CJ_ERR_NONFINITE);
    cj_vec3 o, d;
    assert_int_equal(cj_camera_ray(&c, 0, 10, 1, 1, &o, &d), CJ_ERR_RANGE);
    assert_int_equal(cj_camera_ray(&c, 10, 10, NAN, 1, &o, &d), CJ_ERR_NONFINITE);
    printf("test_camera: F >= f, f >= 0, zero gaze, up parallel to gaze or zero, NaN/Inf, fov and "
           "ortho height out of range, bad aspect and image size refused\n");
}

int main(void) {
    g_seed = cj_test_seed("test_camera", 20261123);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_and_basis),
        cmocka_unit_test(test_view),
        cmocka_unit_test(test_projection),
        cmocka_unit_test(test_ray_round_trip),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
