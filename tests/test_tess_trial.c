/* Planning's slab-table trial without triangles (cj_tess_slab_trial, surfaces/src/tess_trial.c)
 * against the triangle-by-triangle trial it replaces (cj_tess_build_patch with P->predict, every
 * triangle bounded with the slab cells its box meets): the same bound bit for bit and the same
 * triangle count, on every teapot patch and on seeded random polynomial patches (degrees 1..4),
 * for random increasing grid lines (fine and coarse against the 16 slabs, lines on slab
 * boundaries) and random side counts, regular grids included. Also: the normals of the
 * teapot's side points, now taken from grid columns, equal cj_patch_normal at their (u,v) bit for
 * bit. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"
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

static void test_side_normals(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    cj_mesh *m;
    assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
    cj_tess_options o;
    memset(&o, 0, sizeof o);
    o.tol = 1e-3;
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &o, m, NULL), CJ_OK);
    int *patch_of = malloc(sizeof(int) * m->vertex_count);
    assert_non_null(patch_of);
    for (size_t i = 0; i < m->vertex_count; ++i) patch_of[i] = -1;
    for (size_t t = 0; t < m->triangle_count; ++t)
        for (int k = 0; k < 3; ++k) patch_of[m->triangles[3 * t + k]] = m->triangle_patch[t];
    size_t side = 0;
    for (size_t i = 0; i < m->vertex_count; ++i) {
        const double u = m->uvs[2 * i], v = m->uvs[2 * i + 1];
        if (patch_of[i] < 0 || !(u == 0.0 || u == 1.0 || v == 0.0 || v == 1.0)) continue;
        double n[3];
        if (cj_patch_normal(&set->patches[patch_of[i]], u, v, n, NULL) != CJ_OK)
            n[0] = n[1] = n[2] = 0.0;
        if (memcmp(n, m->normals + 3 * i, sizeof n) != 0)
            fail_msg("patch %d side point (%.17g, %.17g): normal (%.17g %.17g %.17g), "
                     "cj_patch_normal (%.17g %.17g %.17g)",
                     patch_of[i], u, v, m->normals[3 * i], m->normals[3 * i + 1],
                     m->normals[3 * i + 2], n[0], n[1], n[2]);
        ++side;
    }
    assert_true(side > 1000);
    printf("teapot at 1e-3: the normals of %zu side points == cj_patch_normal, bit for bit\n",
           side);
    free(patch_of);
    cj_mesh_destroy(m);
    cj_patchset_destroy(set);
}

int main(void) {
    seed = cj_test_seed("test_tess_trial", 19);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot),
        cmocka_unit_test(test_random_patches),
        cmocka_unit_test(test_side_normals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
