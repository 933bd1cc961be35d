/* Transforms: known matrices, composition order, inverse round trips, normals under the
 * inverse transpose, projective points at infinity, bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/transform.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CHECK_CLOSE(a, b, tol)                                                                     \
    do {                                                                                           \
        double a_ = (a), b_ = (b), t_ = (tol);                                                     \
        if (!(fabs(a_ - b_) <= t_))                                                                \
            fail_msg("%s = %.17g, expected %s = %.17g (tol %.3g)", #a, a_, #b, b_, t_);            \
    } while (0)

static const double PI = 3.14159265358979323846;

static cj_vec2 pt2(const cj_xform2 *m, double x, double y) {
    cj_vec2 r;
    assert_int_equal(cj_xform2_apply_point(m, cj_v2(x, y), &r), CJ_OK);
    return r;
}

static cj_vec3 pt3(const cj_xform3 *m, double x, double y, double z) {
    cj_vec3 r;
    assert_int_equal(cj_xform3_apply_point(m, cj_v3(x, y, z), &r), CJ_OK);
    return r;
}

static void test_known_2d(void **state) {
    (void)state;
    cj_xform2 id = cj_xform2_identity(), t = cj_xform2_translate(3, -2),
              r = cj_xform2_rotate(PI / 2), s = cj_xform2_scale(2, 5), sh = cj_xform2_shear(2, 0);
    cj_vec2 p = pt2(&id, 1.5, -7);
    assert_true(p.x == 1.5 && p.y == -7);
    p = pt2(&t, 1, 1);
    assert_true(p.x == 4 && p.y == -1);
    p = pt2(&r, 1, 0); /* quarter turn ccw: (1,0) -> (0,1) */
    CHECK_CLOSE(p.x, 0, 1e-16);
    CHECK_CLOSE(p.y, 1, 1e-16);
    p = pt2(&s, 1, 1);
    assert_true(p.x == 2 && p.y == 5);
    p = pt2(&sh, 1, 1); /* x' = x + 2y */
    assert_true(p.x == 3 && p.y == 1);
    /* Vectors ignore the translation. */
    cj_vec2 v;
    assert_int_equal(cj_xform2_apply_vector(&t, cj_v2(1, 1), &v), CJ_OK);
    assert_true(v.x == 1 && v.y == 1);
    /* Reflection about y = x swaps coordinates; about the x-axis flips y. */
    cj_xform2 f;
    assert_int_equal(cj_xform2_reflect(cj_v2(2, 2), &f), CJ_OK);
    p = pt2(&f, 3, -1);
    CHECK_CLOSE(p.x, -1, 1e-15);
    CHECK_CLOSE(p.y, 3, 1e-15);
    assert_int_equal(cj_xform2_reflect(cj_v2(5, 0), &f), CJ_OK);
    p = pt2(&f, 3, -1);
    assert_true(p.x == 3 && p.y == 1);
    /* Composition: compose(T, R) rotates first, then translates. */
    cj_xform2 tr = cj_xform2_compose(&t, &r);
    p = pt2(&tr, 1, 0);
    CHECK_CLOSE(p.x, 3, 1e-15);
    CHECK_CLOSE(p.y, -1, 1e-15);
    cj_xform2 rt = cj_xform2_compose(&r, &t);
    p = pt2(&rt, 1, 0); /* (4,-2) rotated: (2,4) */
    CHECK_CLOSE(p.x, 2, 1e-15);
    CHECK_CLOSE(p.y, 4, 1e-15);
    assert_true(cj_xform2_is_affine(&rt));
}

static void test_known_3d(void **state) {
    (void)state;
    cj_xform3 rx = cj_xform3_rotate_x(PI / 2), ry = cj_xform3_rotate_y(PI / 2),
              rz = cj_xform3_rotate_z(PI / 2);
    /* Right-handed quarter turns: x: y -> z; y: z -> x; z: x -> y. */
    cj_vec3 p = pt3(&rx, 0, 1, 0);
    CHECK_CLOSE(p.z, 1, 1e-16);
    CHECK_CLOSE(p.y, 0, 1e-16);
    p = pt3(&ry, 0, 0, 1);
    CHECK_CLOSE(p.x, 1, 1e-16);
    CHECK_CLOSE(p.z, 0, 1e-16);
    p = pt3(&rz, 1, 0, 0);
    CHECK_CLOSE(p.y, 1, 1e-16);
    CHECK_CLOSE(p.x, 0, 1e-16);
    /* Rodrigues about a coordinate axis equals the dedicated rotation; about (1,1,1) by 120
     * degrees it permutes the axes x -> y -> z -> x. */
    cj_xform3 ra;
    assert_int_equal(cj_xform3_rotate_axis(cj_v3(0, 0, 3), 0.7, &ra), CJ_OK);
    cj_xform3 rz7 = cj_xform3_rotate_z(0.7);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) CHECK_CLOSE(ra.m[i][j], rz7.m[i][j], 1e-16);
    assert_int_equal(cj_xform3_rotate_axis(cj_v3(1, 1, 1), 2 * PI / 3, &ra), CJ_OK);
    p = pt3(&ra, 1, 0, 0);
    CHECK_CLOSE(p.x, 0, 1e-15);
    CHECK_CLOSE(p.y, 1, 1e-15);
    CHECK_CLOSE(p.z, 0, 1e-15);
    p = pt3(&ra, 0, 0, 1);
    CHECK_CLOSE(p.x, 1, 1e-15);
    /* Scale, shear, translate, reflect. */
    cj_xform3 s = cj_xform3_scale(2, 3, -1);
    p = pt3(&s, 1, 1, 1);
    assert_true(p.x == 2 && p.y == 3 && p.z == -1);
    cj_xform3 sh = cj_xform3_shear(1, 0, 0, 0, 0, 2); /* x' = x + y, z' = z + 2y */
    p = pt3(&sh, 1, 1, 1);
    assert_true(p.x == 2 && p.y == 1 && p.z == 3);
    cj_xform3 t = cj_xform3_translate(1, 2, 3);
    p = pt3(&t, 0, 0, 0);
    assert_true(p.x == 1 && p.y == 2 && p.z == 3);
    cj_xform3 f;
    assert_int_equal(cj_xform3_reflect(cj_v3(0, 0, 7), &f), CJ_OK);
    p = pt3(&f, 1, 2, 3);
    assert_true(p.x == 1 && p.y == 2 && p.z == -3);
    cj_xform3 ff = cj_xform3_compose(&f, &f);
    assert_int_equal(cj_xform3_reflect(cj_v3(1, -2, 0.5), &f), CJ_OK);
    ff = cj_xform3_compose(&f, &f);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) CHECK_CLOSE(ff.m[i][j], i == j, 1e-15);
}

/* Random affine matrices: inverse round trip, composition associativity, normals stay
 * perpendicular to transformed tangent planes, rotations stay orthonormal. */
static void test_random_round_trips(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("transform round trips", 77));
    const int cases = 2000;
    for (int cs = 0; cs < cases; ++cs) {
        cj_xform3 m = cj_xform3_identity();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) m.m[i][j] = cj_rng_range(&rng, -2, 2);
        cj_xform3 inv;
        cj_status st = cj_xform3_inverse(&m, &inv);
        if (st == CJ_ERR_SINGULAR) continue; /* vanishingly rare for random entries */
        assert_int_equal(st, CJ_OK);
        cj_xform3 prod = cj_xform3_compose(&m, &inv);
        /* Residual bound: cond-independent check of M M^-1 = I relative to |M||M^-1|. */
        double nm = 0, ni = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                nm = fmax(nm, fabs(m.m[i][j]));
                ni = fmax(ni, fabs(inv.m[i][j]));
            }
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                if (fabs(prod.m[i][j] - (i == j)) > 64 * 0x1p-53 * 4 * nm * ni)
                    fail_msg("case %d: (M M^-1)[%d][%d] = %.17g", cs, i, j, prod.m[i][j]);
            }
        /* Normals: plane through p spanned by u, v; n = u x v. After the transform, n' must be
         * perpendicular to M u and M v. */
        cj_vec3 u =
            cj_v3(cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1));
        cj_vec3 v =
            cj_v3(cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1));
        cj_vec3 n = cj_v3_cross(u, v), mu, mv, mn;
        assert_int_equal(cj_xform3_apply_vector(&m, u, &mu), CJ_OK);
        assert_int_equal(cj_xform3_apply_vector(&m, v, &mv), CJ_OK);
        assert_int_equal(cj_xform3_apply_normal(&m, n, &mn), CJ_OK);
        const double scale = cj_v3_norm(mn) * (cj_v3_norm(mu) + cj_v3_norm(mv));
        if (fabs(cj_v3_dot(mn, mu)) > 1e-12 * scale || fabs(cj_v3_dot(mn, mv)) > 1e-12 * scale)
            fail_msg("seed case %d: transformed normal not perpendicular (%.3g, %.3g)", cs,
                     cj_v3_dot(mn, mu), cj_v3_dot(mn, mv));
        /* Point round trip through the inverse. */
        cj_vec3 p = cj_v3(cj_rng_range(&rng, -10, 10), cj_rng_range(&rng, -10, 10),
                          cj_rng_range(&rng, -10, 10));
        cj_vec3 q, back;
        assert_int_equal(cj_xform3_apply_point(&m, p, &q), CJ_OK);
        assert_int_equal(cj_xform3_apply_point(&inv, q, &back), CJ_OK);
        if (cj_v3_norm(cj_v3_sub(back, p)) > 1e-10 * (1 + cj_v3_norm(p)) * nm * ni)
            fail_msg("case %d: point round trip off by %.3g", cs, cj_v3_norm(cj_v3_sub(back, p)));
        /* Rodrigues rotation: orthonormal, det +1 (columns form a right-handed frame). */
        cj_xform3 r;
        assert_int_equal(cj_xform3_rotate_axis(u, cj_rng_range(&rng, -7, 7), &r), CJ_OK);
        cj_vec3 c0 = cj_v3(r.m[0][0], r.m[1][0], r.m[2][0]);
        cj_vec3 c1 = cj_v3(r.m[0][1], r.m[1][1], r.m[2][1]);
        cj_vec3 c2 = cj_v3(r.m[0][2], r.m[1][2], r.m[2][2]);
        /* Each entry carries a few ulps of rounding; products of three add up to ~ 30 u. */
        const double ot = 30 * 0x1p-53;
        CHECK_CLOSE(cj_v3_dot(c0, c1), 0, ot);
        CHECK_CLOSE(cj_v3_dot(c0, c0), 1, ot);
        cj_vec3 x = cj_v3_cross(c0, c1);
        CHECK_CLOSE(cj_v3_norm(cj_v3_sub(x, c2)), 0, ot);
        /* The axis is fixed. */
        cj_vec3 ru;
        assert_int_equal(cj_xform3_apply_vector(&r, u, &ru), CJ_OK);
        CHECK_CLOSE(cj_v3_norm(cj_v3_sub(ru, u)), 0, ot * cj_v3_norm(u));
    }
    /* 2D: inverse of a composition is the reversed composition of inverses. */
    for (int cs = 0; cs < cases; ++cs) {
        cj_xform2 a = cj_xform2_rotate(cj_rng_range(&rng, -4, 4));
        cj_xform2 b = cj_xform2_scale(cj_rng_range(&rng, 0.5, 2), cj_rng_range(&rng, -2, -0.5));
        cj_xform2 c = cj_xform2_translate(cj_rng_range(&rng, -5, 5), cj_rng_range(&rng, -5, 5));
        cj_xform2 ab = cj_xform2_compose(&a, &b), abc = cj_xform2_compose(&ab, &c);
        cj_xform2 ia, ib, ic, iabc;
        assert_int_equal(cj_xform2_inverse(&a, &ia), CJ_OK);
        assert_int_equal(cj_xform2_inverse(&b, &ib), CJ_OK);
        assert_int_equal(cj_xform2_inverse(&c, &ic), CJ_OK);
        assert_int_equal(cj_xform2_inverse(&abc, &iabc), CJ_OK);
        cj_xform2 cb = cj_xform2_compose(&ic, &ib), cba = cj_xform2_compose(&cb, &ia);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (fabs(cba.m[i][j] - iabc.m[i][j]) > 1e-13)
                    fail_msg("case %d: (ABC)^-1 != C^-1 B^-1 A^-1 at [%d][%d]", cs, i, j);
        /* 2D normal of a line stays perpendicular (b has a mirror: orientation flips). */
        cj_vec2 d = cj_v2(cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1));
        cj_vec2 nn = cj_v2_perp(d), md, mn;
        assert_int_equal(cj_xform2_apply_vector(&abc, d, &md), CJ_OK);
        assert_int_equal(cj_xform2_apply_normal(&abc, nn, &mn), CJ_OK);
        CHECK_CLOSE(cj_v2_dot(md, mn), 0, 1e-13 * cj_v2_norm(md) * cj_v2_norm(mn));
    }
    printf("transforms: %d random 3D affine inverses/normals/rotations and %d 2D compositions "
           "checked\n",
           cases, cases);
}

static void test_projective_and_bad_input(void **state) {
    (void)state;
    /* A perspective-like 2D matrix: w' = x + 1. */
    cj_xform2 p = cj_xform2_identity();
    p.m[2][0] = 1;
    assert_false(cj_xform2_is_affine(&p));
    cj_vec2 q;
    assert_int_equal(cj_xform2_apply_point(&p, cj_v2(1, 4), &q), CJ_OK);
    assert_true(q.x == 0.5 && q.y == 2);
    q = cj_v2(42, 42);
    assert_int_equal(cj_xform2_apply_point(&p, cj_v2(-1, 4), &q), CJ_ERR_DEGENERATE);
    assert_true(q.x == 42 && q.y == 42);
    /* Batch: one bad point leaves the whole array untouched, even in place. */
    double pts[] = {1, 1, 2, 2, -1, 3};
    const double orig[] = {1, 1, 2, 2, -1, 3};
    assert_int_equal(cj_xform2_apply_points(&p, pts, 3, pts), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "point 2"));
    assert_memory_equal(pts, orig, sizeof pts);
    /* In-place batch equals single applications. */
    cj_xform3 m = cj_xform3_translate(1e8, -3, 0.5);
    cj_xform3 rot = cj_xform3_rotate_y(0.3);
    m = cj_xform3_compose(&m, &rot);
    double a3[] = {1, 2, 3, -4, 5, 6};
    double out3[6];
    assert_int_equal(cj_xform3_apply_points(&m, a3, 2, out3), CJ_OK);
    assert_int_equal(cj_xform3_apply_points(&m, a3, 2, a3), CJ_OK);
    assert_memory_equal(a3, out3, sizeof a3);
    cj_vec3 single = pt3(&m, -4, 5, 6);
    assert_true(single.x == out3[3] && single.y == out3[4] && single.z == out3[5]);
    /* Singular matrices. */
    cj_xform2 s = cj_xform2_scale(1, 0), inv;
    assert_int_equal(cj_xform2_inverse(&s, &inv), CJ_ERR_SINGULAR);
    assert_int_equal(cj_xform2_apply_normal(&s, cj_v2(0, 1), &q), CJ_ERR_SINGULAR);
    cj_xform3 s3 = cj_xform3_shear(1, 0, 1, 0, 0, 0), inv3; /* rows x+y, x+y, z */
    assert_int_equal(cj_xform3_inverse(&s3, &inv3), CJ_ERR_SINGULAR);
    /* Non-finite inputs and degenerate constructors. */
    cj_xform2 nanrot = cj_xform2_rotate(NAN);
    assert_int_equal(cj_xform2_apply_point(&nanrot, cj_v2(1, 1), &q), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "entry"));
    cj_xform2 id = cj_xform2_identity();
    assert_int_equal(cj_xform2_apply_point(&id, cj_v2(INFINITY, 1), &q), CJ_ERR_NONFINITE);
    assert_int_equal(cj_xform2_inverse(&nanrot, &inv), CJ_ERR_NONFINITE);
    cj_xform2 f2;
    assert_int_equal(cj_xform2_reflect(cj_v2(0, 0), &f2), CJ_ERR_DEGENERATE);
    cj_xform3 f3;
    assert_int_equal(cj_xform3_reflect(cj_v3(0, 0, 0), &f3), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_xform3_rotate_axis(cj_v3(0, 0, 0), 1, &f3), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_xform3_rotate_axis(cj_v3(1, 0, 0), INFINITY, &f3), CJ_ERR_NONFINITE);
    /* w' = 0 in 3D. */
    cj_xform3 p3 = cj_xform3_identity();
    p3.m[3][2] = -1;
    p3.m[3][3] = 0; /* w' = -z, a camera-style projection */
    cj_vec3 r3;
    assert_int_equal(cj_xform3_apply_point(&p3, cj_v3(1, 1, 0), &r3), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_xform3_apply_point(&p3, cj_v3(2, 4, -2), &r3), CJ_OK);
    assert_true(r3.x == 1 && r3.y == 2 && r3.z == -1);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_known_2d),
        cmocka_unit_test(test_known_3d),
        cmocka_unit_test(test_random_round_trips),
        cmocka_unit_test(test_projective_and_bad_input),
    };
    printf("transforms: known matrices, composition order, inverses, normals, w = 0, bad input\n");
    return cmocka_run_group_tests(tests, NULL, NULL);
}
