/* Cross-check against VTK: our Bézier patches as VTK_BEZIER_QUADRILATERAL cells, evaluated by
 * VTK (vtkBezierQuadrilateral::EvaluateLocation) at 1024 (u,v) pairs per patch and compared with
 * cj_patch_eval (compensated), degrees 1..6 in each direction, polynomial and rational: agreement
 * to 1e-12 relative to the patch size. Also: our node order equals VTK's PointIndexFromIJK, and
 * the teapot round-trips through a .vtu file. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "casteljau/vtk_patches.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static uint64_t seed;

static void test_node_order(void **state) {
    (void)state;
    for (int m = 1; m <= 6; ++m)
        for (int n = 1; n <= 6; ++n) {
            cj_status st = cj_vtk_quad_node_check(m, n);
            if (st) fail_msg("%s", cj_last_error());
        }
    printf("node order: our corner/edge/interior mapping equals VTK's PointIndexFromIJK for "
           "degrees 1..6 x 1..6\n");
}

static void test_vtk_evaluation(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    enum { NUV = 1024 };
    double *uv = malloc(sizeof(double) * 2 * NUV), *ours = malloc(sizeof(double) * 3 * NUV),
           *theirs = malloc(sizeof(double) * 3 * NUV);
    assert_non_null(uv);
    assert_non_null(ours);
    assert_non_null(theirs);
    double worst = 0.0;
    int patches = 0;
    for (int m = 1; m <= 6; ++m)
        for (int n = 1; n <= 6; ++n)
            for (int rational = 0; rational < 2; ++rational) {
                double pts[49 * 3], w[49];
                for (int q = 0; q < (m + 1) * (n + 1); ++q) {
                    pts[3 * q] = 10.0 * (q % (m + 1)) / m + cj_rng_range(&r, -3, 3);
                    pts[3 * q + 1] = 10.0 * (q / (m + 1)) / n + cj_rng_range(&r, -3, 3);
                    pts[3 * q + 2] = cj_rng_range(&r, -5, 5);
                    w[q] = cj_rng_range(&r, 0.3, 3.0);
                }
                cj_patch p = cj_patch_view(m, n, pts, rational ? w : NULL);
                double size;
                assert_int_equal(cj_patch_size(&p, &size), CJ_OK);
                for (int k = 0; k < NUV; ++k) { /* the four corners, then random points */
                    uv[2 * k] = k < 4 ? (double)(k & 1) : cj_rng_unit(&r);
                    uv[2 * k + 1] = k < 4 ? (double)(k >> 1) : cj_rng_unit(&r);
                    assert_int_equal(cj_patch_eval(&p, CJ_EVAL_COMPENSATED, uv[2 * k],
                                                   uv[2 * k + 1], ours + 3 * k),
                                     CJ_OK);
                }
                cj_status st = cj_vtk_eval_patch(&p, uv, NUV, theirs);
                if (st) fail_msg("degree (%d,%d): %s", m, n, cj_last_error());
                for (int k = 0; k < NUV; ++k) {
                    const double *a = ours + 3 * k, *b = theirs + 3 * k;
                    const double d =
                        sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                             (a[2] - b[2]) * (a[2] - b[2])) /
                        size;
                    worst = fmax(worst, d);
                    if (!(d <= 1e-12))
                        fail_msg("seed %llu degree (%d,%d) rational %d at (%.17g, %.17g): ours "
                                 "(%.17g %.17g %.17g), VTK (%.17g %.17g %.17g), rel %.3g",
                                 (unsigned long long)seed, m, n, rational, uv[2 * k], uv[2 * k + 1],
                                 a[0], a[1], a[2], b[0], b[1], b[2], d);
                }
                ++patches;
            }
    free(uv);
    free(ours);
    free(theirs);
    printf("VTK evaluation of %d patches (degrees 1..6 x 1..6, polynomial and rational) at %d "
           "(u,v) each agrees with ours: worst distance %.3g of the patch size (limit 1e-12)\n",
           patches, NUV, worst);
}

static void test_teapot_vtu(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    char dir[] = "/tmp/cj_vtkp_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[128], bad[128];
    snprintf(path, sizeof path, "%s/teapot.vtu", dir);
    snprintf(bad, sizeof bad, "%s/missing/teapot.vtu", dir);
    assert_int_equal(cj_vtk_write_patches(path, set->patches, set->count), CJ_OK);
    size_t ncells = 0;
    int deg[2] = {0, 0};
    assert_int_equal(cj_vtk_read_patch_count(path, &ncells, deg), CJ_OK);
    assert_int_equal((int)ncells, 32);
    assert_int_equal(deg[0], 3);
    assert_int_equal(deg[1], 3);
    assert_int_equal(cj_vtk_write_patches(bad, set->patches, set->count), CJ_ERR_IO);
    assert_int_equal(access(bad, F_OK), -1);
    assert_int_equal(cj_vtk_write_patches(path, set->patches, 0), CJ_ERR_EMPTY);
    double line[6] = {0, 0, 0, 1, 0, 0};
    cj_patch flat = cj_patch_view(1, 0, line, NULL);
    assert_int_equal(cj_vtk_write_patches(path, &flat, 1), CJ_ERR_DEGREE);
    double uvbad[2] = {0.5, 1.5}, out[3];
    assert_int_equal(cj_vtk_eval_patch(&set->patches[0], uvbad, 1, out), CJ_ERR_RANGE);
    unlink(path);
    rmdir(dir);
    cj_patchset_destroy(set);
    printf("teapot -> .vtu: 32 bicubic cells read back by VTK; unwritable path, empty set, "
           "degree 0 and out-of-range (u,v) rejected\n");
}

int main(void) {
    seed = cj_test_seed("test_vtk_patches", 1965);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_node_order),
        cmocka_unit_test(test_vtk_evaluation),
        cmocka_unit_test(test_teapot_vtu),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
