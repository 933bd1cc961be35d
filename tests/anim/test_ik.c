/* Kinematics: forward kinematics against products of cj_xform3 matrices; inverse kinematics of
 * a planar two-link arm against its analytic solutions (reachable: residual <= 1e-10 and the
 * angles of one of the two closed-form elbows; unreachable: the closest pose, residual exactly
 * d - (l1 + l2) or (|l1 - l2| - d), CJ_ERR_CAP, no NaN), limits, two effectors on a tree,
 * the Jacobian transpose for comparison, bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/kinematics.h"
#include "casteljau/transform.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static cj_chain two_link(double l1) {
    cj_chain c;
    memset(&c, 0, sizeof c);
    c.count = 2;
    for (int j = 0; j < 2; ++j) {
        c.joints[j].parent = j - 1;
        c.joints[j].kind = CJ_JOINT_REVOLUTE;
        c.joints[j].axis[2] = 1;
        c.joints[j].lo = -INFINITY;
        c.joints[j].hi = INFINITY;
    }
    c.joints[1].offset[0] = l1;
    return c;
}

static double wrap(double a) {
    return remainder(a, 2 * M_PI);
}

static void test_two_link_reachable(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_ik/two_link", 1631));
    int worst_it = 0, worst_it_t = 0, transpose_ok = 0;
    double worst_res = 0, worst_ang = 0, worst_res_t = 0;
    for (int cas = 0; cas < 300; ++cas) {
        const double l1 = cj_rng_range(&r, 0.5, 2), l2 = cj_rng_range(&r, 0.5, 2);
        cj_chain c = two_link(l1);
        const double rin = fabs(l1 - l2), rout = l1 + l2;
        const double rad = cj_rng_range(&r, rin + 0.05 * (rout - rin), rout - 0.05 * (rout - rin));
        const double phi = cj_rng_range(&r, -M_PI, M_PI);
        cj_ik_effector e = {1, {l2, 0, 0}, {rad * cos(phi), rad * sin(phi), 0}};
        double q[2] = {cj_rng_range(&r, -3, 3), cj_rng_range(&r, -3, 3)};
        cj_ik_options o = cj_ik_defaults(CJ_IK_DLS);
        cj_ik_result res;
        const cj_status st = cj_ik_solve(&c, q, &e, 1, &o, &res);
        if (st != CJ_OK) fail_msg("case %d: %s", cas, cj_last_error());
        worst_res = fmax(worst_res, res.residual);
        worst_it = res.iterations > worst_it ? res.iterations : worst_it;
        /* analytic: cos q2 = (r² - l1² - l2²)/(2 l1 l2), q1 = phi - atan2(l2 sin q2, l1 + l2 cos
         * q2) */
        double best = 1e9;
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            const double q2 = sgn * acos((rad * rad - l1 * l1 - l2 * l2) / (2 * l1 * l2));
            const double q1 = phi - atan2(l2 * sin(q2), l1 + l2 * cos(q2));
            best = fmin(best, fmax(fabs(wrap(q[0] - q1)), fabs(wrap(q[1] - q2))));
        }
        worst_ang = fmax(worst_ang, best);
        if (best > 1e-8)
            fail_msg("case %d: angles (%g, %g) match no analytic elbow (%g)", cas, q[0], q[1],
                     best);
        if (cas < 60) { /* the transpose method from the same start, for comparison */
            double qt[2] = {0.3, 0.4};
            cj_ik_options ot = cj_ik_defaults(CJ_IK_TRANSPOSE);
            ot.tol = 1e-8;
            if (cj_ik_solve(&c, qt, &e, 1, &ot, &res) == CJ_OK) ++transpose_ok;
            worst_res_t = fmax(worst_res_t, res.residual);
            worst_it_t = res.iterations > worst_it_t ? res.iterations : worst_it_t;
        }
    }
    printf("two-link arm, 300 reachable targets: DLS residual <= %.2g in <= %d iterations, "
           "angles within %.2g rad of an analytic elbow; Jacobian transpose (tol 1e-8): %d/60 "
           "reached, <= %d iterations, worst residual %.2g\n",
           worst_res, worst_it, worst_ang, transpose_ok, worst_it_t, worst_res_t);
    assert_true(worst_res <= 1e-10);
    assert_true(transpose_ok >= 55);
}

static void test_two_link_unreachable(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_ik/unreachable", 1632));
    double worst = 0;
    for (int cas = 0; cas < 100; ++cas) {
        const double l1 = cj_rng_range(&r, 0.5, 2), l2 = cj_rng_range(&r, 0.5, 2);
        cj_chain c = two_link(l1);
        const int outside = cas % 2 == 0;
        const double rad = outside ? (l1 + l2) * cj_rng_range(&r, 1.05, 3)
                                   : fabs(l1 - l2) * cj_rng_range(&r, 0.0, 0.9);
        if (!outside && fabs(l1 - l2) < 0.1) continue;
        const double phi = cj_rng_range(&r, -M_PI, M_PI);
        cj_ik_effector e = {1, {l2, 0, 0}, {rad * cos(phi), rad * sin(phi), 0}};
        double q[2] = {cj_rng_range(&r, -3, 3), cj_rng_range(&r, -3, 3)};
        cj_ik_result res;
        const cj_status st = cj_ik_solve(&c, q, &e, 1, NULL, &res);
        assert_int_equal(st, CJ_ERR_CAP);
        assert_true(res.outcome == CJ_IK_STALLED);
        assert_true(isfinite(q[0]) && isfinite(q[1]));
        const double want = outside ? rad - (l1 + l2) : fabs(l1 - l2) - rad;
        worst = fmax(worst, fabs(res.residual - want));
        if (fabs(res.residual - want) > 1e-8)
            fail_msg("case %d (%s): residual %.12g, closest possible %.12g", cas,
                     outside ? "beyond reach" : "inside the inner hole", res.residual, want);
    }
    printf("two-link arm, unreachable targets (beyond l1+l2, inside |l1-l2|): CJ_ERR_CAP / "
           "stalled at the closest pose, residual = exact distance to the workspace within %.2g\n",
           worst);
    printf("  e.g. %s\n", cj_last_error());
}

static void test_fk_against_matrices(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_ik/fk", 1633));
    double worst = 0;
    for (int cas = 0; cas < 100; ++cas) {
        cj_chain c;
        memset(&c, 0, sizeof c);
        c.count = 6;
        for (int k = 0; k < 3; ++k) c.base[k] = cj_rng_range(&r, -1, 1);
        double q[6];
        cj_xform3 M = cj_xform3_translate(c.base[0], c.base[1], c.base[2]);
        for (int j = 0; j < 6; ++j) {
            cj_joint *J = &c.joints[j];
            J->parent = j - 1;
            J->kind = cj_rng_unit(&r) < 0.3 ? CJ_JOINT_PRISMATIC : CJ_JOINT_REVOLUTE;
            for (int k = 0; k < 3; ++k) {
                J->offset[k] = cj_rng_range(&r, -1, 1);
                J->axis[k] = cj_rng_range(&r, -1, 1);
            }
            J->lo = -10;
            J->hi = 10;
            q[j] = cj_rng_range(&r, -2, 2);
            /* independent composition: M <- M T(offset) [Rot(axis, q) | T(q axis)] */
            const cj_xform3 T = cj_xform3_translate(J->offset[0], J->offset[1], J->offset[2]);
            M = cj_xform3_compose(&M, &T);
            if (J->kind == CJ_JOINT_REVOLUTE) {
                cj_xform3 R;
                assert_int_equal(
                    cj_xform3_rotate_axis(cj_v3(J->axis[0], J->axis[1], J->axis[2]), q[j], &R),
                    CJ_OK);
                M = cj_xform3_compose(&M, &R);
            } else {
                const double n = sqrt(J->axis[0] * J->axis[0] + J->axis[1] * J->axis[1] +
                                      J->axis[2] * J->axis[2]);
                const cj_xform3 P = cj_xform3_translate(
                    q[j] * J->axis[0] / n, q[j] * J->axis[1] / n, q[j] * J->axis[2] / n);
                M = cj_xform3_compose(&M, &P);
            }
        }
        cj_chain_pose pose;
        assert_int_equal(cj_chain_fk(&c, q, &pose), CJ_OK);
        const double loc[3] = {0.3, -0.2, 0.5};
        double x[3];
        cj_chain_point(&pose, 5, loc, x);
        cj_vec3 y;
        assert_int_equal(cj_xform3_apply_point(&M, cj_v3(loc[0], loc[1], loc[2]), &y), CJ_OK);
        worst = fmax(worst, fmax(fabs(x[0] - y.x), fmax(fabs(x[1] - y.y), fabs(x[2] - y.z))));
    }
    printf("forward kinematics of 100 random 6-joint 3D chains (revolute + prismatic) = products "
           "of cj_xform3 matrices: worst %.2g\n",
           worst);
    assert_true(worst < 1e-13);
}

static void test_limits_and_tree(void **state) {
    (void)state;
    /* limits: the elbow may bend only to [0, 0.5]; a target needing more bend is not reached,
     * the values stay inside their limits */
    cj_chain c = two_link(1);
    c.joints[1].lo = 0;
    c.joints[1].hi = 0.5;
    double q[2] = {0, 0.2};
    cj_ik_effector e = {1, {1, 0, 0}, {0.5, 0.5, 0}};
    cj_ik_result res;
    assert_int_equal(cj_ik_solve(&c, q, &e, 1, NULL, &res), CJ_ERR_CAP);
    assert_true(q[1] >= 0 && q[1] <= 0.5 && isfinite(q[0]));
    printf("elbow limited to [0, 0.5]: target needing a sharper bend ends at q = (%.4f, %.4f), "
           "residual %.4f, within limits\n",
           q[0], q[1], res.residual);
    assert_true(fabs(q[1] - 0.5) < 1e-9); /* pressed against the limit */
    /* a tree: a torso joint with two 3D arms (3 revolute joints each), both hands at targets
     * taken from a random pose, so both are reachable at once */
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_ik/tree", 1634));
    int reached = 0, maxit = 0, reached_zero = 0;
    for (int cas = 0; cas < 40; ++cas) {
        cj_chain t;
        memset(&t, 0, sizeof t);
        t.count = 7;
        const double axes[3][3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
        t.joints[0] = (cj_joint){-1, CJ_JOINT_REVOLUTE, {0, 0, 0}, {0, 0, 1}, -INFINITY, INFINITY};
        for (int arm = 0; arm < 2; ++arm)
            for (int j = 0; j < 3; ++j) {
                cj_joint *J = &t.joints[1 + 3 * arm + j];
                J->parent = j == 0 ? 0 : 3 * arm + j;
                J->kind = CJ_JOINT_REVOLUTE;
                J->offset[0] = j == 0 ? (arm ? -0.5 : 0.5) : 0.7;
                memcpy(J->axis, axes[j], sizeof J->axis);
                J->lo = -INFINITY;
                J->hi = INFINITY;
            }
        double qt[7], qs[7], qz[7] = {0};
        for (int j = 0; j < 7; ++j) qt[j] = cj_rng_range(&r, -1.5, 1.5);
        for (int j = 0; j < 7; ++j) qs[j] = qt[j] + cj_rng_range(&r, -0.5, 0.5);
        cj_chain_pose pose;
        assert_int_equal(cj_chain_fk(&t, qt, &pose), CJ_OK);
        cj_ik_effector two[2] = {{3, {0.5, 0.2, 0}, {0}}, {6, {0.5, 0.2, 0}, {0}}};
        cj_chain_point(&pose, 3, two[0].local, two[0].target);
        cj_chain_point(&pose, 6, two[1].local, two[1].target);
        if (cj_ik_solve(&t, qs, two, 2, NULL, &res) == CJ_OK) ++reached;
        maxit = res.iterations > maxit ? res.iterations : maxit;
        /* from the zero pose a local minimum (a singular pose with e orthogonal to J's range)
         * may catch the solver: counted, reported as CJ_ERR_CAP/stalled, never a NaN */
        const cj_status stz = cj_ik_solve(&t, qz, two, 2, NULL, &res);
        if (stz == CJ_OK)
            ++reached_zero;
        else
            assert_true(stz == CJ_ERR_CAP && res.outcome != CJ_IK_REACHED &&
                        isfinite(res.residual));
    }
    printf("tree (torso + two 3-joint arms), two effectors at poses of the tree itself: %d/40 "
           "reached to 1e-10 from a start within 0.5 rad per joint (<= %d iterations); from the "
           "zero pose %d/40 (the rest stall in local minima, reported)\n",
           reached, maxit, reached_zero);
    assert_true(reached == 40);
}

static void test_bad_input(void **state) {
    (void)state;
    cj_chain c = two_link(1);
    double q[2] = {0, 0};
    cj_ik_effector e = {1, {1, 0, 0}, {NAN, 0, 0}};
    assert_int_equal(cj_ik_solve(&c, q, &e, 1, NULL, NULL), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "effector 0"));
    e.target[0] = 1;
    e.joint = 5;
    assert_int_equal(cj_ik_solve(&c, q, &e, 1, NULL, NULL), CJ_ERR_ARGUMENT);
    e.joint = 1;
    c.joints[1].axis[2] = 0;
    assert_int_equal(cj_ik_solve(&c, q, &e, 1, NULL, NULL), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "joint 1"));
    c.joints[1].axis[2] = 1;
    c.joints[0].parent = 1;
    assert_int_equal(cj_ik_solve(&c, q, &e, 1, NULL, NULL), CJ_ERR_ARGUMENT);
    c.joints[0].parent = -1;
    q[1] = NAN;
    assert_int_equal(cj_ik_solve(&c, q, &e, 1, NULL, NULL), CJ_ERR_NONFINITE);
    printf("refused: NaN target, effector on a missing joint, zero axis, parent after child, NaN "
           "value\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_link_reachable),  cmocka_unit_test(test_two_link_unreachable),
        cmocka_unit_test(test_fk_against_matrices), cmocka_unit_test(test_limits_and_tree),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
