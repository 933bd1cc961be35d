/* Planning's slab-table trial without triangles (cj_tess_slab_trial, surfaces/src/tess_trial.c)
 * against the triangle-by-triangle trial it replaces (cj_tess_build_patch with P->predict, every
 * triangle bounded with the slab cells its box meets): the same bound bit for bit and the same
 * triangle count, on every teapot patch and on seeded random polynomial patches (degrees 1..4),
 * for random increasing grid lines (fine and coarse against the 16 slabs, lines on slab
 * boundaries) and random side counts, regular grids included. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "rng.h"
#include "tessellate_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t seed;
static size_t compared, regular_grids;

/* Increasing lines 0 = t[0] < ... < t[n] = 1: uniform, on slab boundaries, or random. */
static void random_lines(cj_rng *r, int n, double *t) {
    const int kind = cj_rng_int(r, 0, 2);
    t[0] = 0.0;
    t[n] = 1.0;
    if (kind == 0 || (kind == 1 && n > CJ_TESS_SLABS)) {
        for (int i = 1; i < n; ++i) t[i] = (double)i / n;
    } else if (kind == 1) { /* n distinct multiples of 1/16 */
        int used[CJ_TESS_SLABS + 1] = {0};
        int have = 0;
        while (have < n - 1) {
            const int a = cj_rng_int(r, 1, CJ_TESS_SLABS - 1);
            if (!used[a]) used[a] = 1, ++have;
        }
        for (int a = 1, i = 1; a < CJ_TESS_SLABS; ++a)
            if (used[a]) t[i++] = (double)a / CJ_TESS_SLABS;
    } else { /* random gaps */
        double acc = 0.0, gap[200];
        for (int i = 0; i < n; ++i) acc += gap[i] = cj_rng_range(r, 0.05, 1.0);
        double run = 0.0;
        for (int i = 1; i < n; ++i) {
            run += gap[i - 1];
            t[i] = run / acc;
        }
    }
}

/* Both trials of patch p on random grids. */
static void compare_patch(cj_rng *r, const cj_patch *p, size_t q, int grids) {
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    static ptess P;
    cj_tess_setup(&P, p, q, mesh, 0);
    P.planning = 1;
    P.pm = P.pmbuf;
    double rho_u[CJ_TESS_SLABS], rho_v[CJ_TESS_SLABS], bu, bv;
    cj_tess_patch_densities(&P, 1e-3, rho_u, rho_v, &bu, &bv);
    for (int g = 0; g < grids; ++g) {
        const int nu = cj_rng_int(r, 2, 120), nv = cj_rng_int(r, 2, 120);
        double ub[121], vb[121];
        random_lines(r, nu, ub);
        random_lines(r, nv, vb);
        int k[4];
        const int reg = cj_rng_int(r, 0, 3) == 0;
        for (int s = 0; s < 4; ++s) {
            const int ng = (s & 1) ? nv : nu;
            k[s] = P.e[s].collapsed || reg ? ng : cj_rng_int(r, 1, 130);
        }
        /* the old trial: every triangle, bounded with its slab cells */
        P.predict = 1;
        P.bounds_only = 1;
        P.abort_over = 0.0;
        assert_int_equal(cj_tess_build_patch(&P, nu, ub, nv, vb, k), CJ_OK);
        const double old_bound = P.bound;
        const size_t old_tris = P.tris;
        assert_int_equal(cj_tess_slab_trial(&P, nu, ub, nv, vb, k), CJ_OK);
        P.predict = 0;
        P.bounds_only = 0;
        if (memcmp(&old_bound, &P.bound, sizeof(double)) != 0 || old_tris != P.tris)
            fail_msg("seed %llu patch %zu (degree %d x %d) grid %d x %d, sides %d %d %d %d: "
                     "triangle by triangle bound %.17g, %zu triangles; slab trial %.17g, %zu",
                     (unsigned long long)seed, q, p->deg_u, p->deg_v, nu, nv, k[0], k[1], k[2],
                     k[3], old_bound, old_tris, P.bound, P.tris);
        ++compared;
        if (old_tris == 2 * (size_t)nu * (size_t)nv) ++regular_grids;
    }
    cj_mesh_destroy(mesh);
}

static void test_teapot(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    cj_rng r;
    cj_rng_init(&r, seed);
    compared = regular_grids = 0;
    for (size_t q = 0; q < set->count; ++q) compare_patch(&r, &set->patches[q], q, 40);
    printf("teapot: %zu grids on 32 patches (%zu regular): slab trial == triangle by triangle, "
           "bound bit for bit, triangle counts equal\n",
           compared, regular_grids);
    cj_patchset_destroy(set);
}

static void test_random_patches(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x5eedull);
    compared = regular_grids = 0;
    static double pts[25 * 3];
    for (int t = 0; t < 60; ++t) {
        const int m = cj_rng_int(&r, 1, 4), n = cj_rng_int(&r, 1, 4);
        const double scale = pow(10.0, cj_rng_range(&r, -3.0, 3.0));
        for (int i = 0; i < 3 * (m + 1) * (n + 1); ++i) pts[i] = scale * cj_rng_range(&r, -1, 1);
        if (t % 5 == 0) /* a collapsed side, as the teapot's lid and bottom */
            for (int i = 1; i <= m; ++i) memcpy(pts + 3 * i, pts, 3 * sizeof(double));
        const cj_patch p = cj_patch_view(m, n, pts, NULL);
        compare_patch(&r, &p, (size_t)t, 20);
    }
    printf("random patches: %zu grids on 60 patches of degrees 1..4 (%zu regular): slab trial "
           "== triangle by triangle, bound bit for bit, triangle counts equal\n",
           compared, regular_grids);
}

int main(void) {
    seed = cj_test_seed("test_tess_trial", 19);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot),
        cmocka_unit_test(test_random_patches),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
