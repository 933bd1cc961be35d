/* Tessellation: the surface-to-mesh deviation, measured by dense sampling with an independent
 * Bernstein-sum evaluator, stays within the reported bound and the tolerance (random patches
 * and the teapot at 1e-2, 3e-3, 1e-3 of its size); the teapot mesh has zero cracks (every
 * shared patch edge carries bit-identical vertices on both sides; boundary edges only on the
 * true open boundary); closed meshes (torus, ellipsoid) are manifold with Euler characteristic
 * 0 and 2; patches with straight edges across which they twist (the twisted bilinear patch,
 * random ones) need no more triangles adaptively than the smallest uniform grid meeting tol,
 * and a straight edge shared with a flat patch carries the same vertices on both sides; the
 * teapot data's shared edges; a quarter-circle rational patch and the options. Rational patches
 * in depth: test_tessellate_rational.c; export and the .bpt loader: test_tessellate_io.c. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/analytic.h"
#include "casteljau/patchset.h"
#include "casteljau/quadric.h"
#include "casteljau/tessellate.h"
#include "rng.h"
#include "tessellate_teapot.h"
#include "tessellate_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI      3.14159265358979323846
#define SQRT1_2 0.70710678118654752440

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static uint64_t seed;

static void test_random_patches_within_tol(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    int cases = 0;
    double worst_ratio = 0.0;
    for (int c = 0; c < 24; ++c) {
        const int m = cj_rng_int(&r, 1, 5), n = cj_rng_int(&r, 1, 5);
        double pts[36 * 3];
        for (int q = 0; q < (m + 1) * (n + 1); ++q) {
            tess_random_point(&r, m, n, q, pts + 3 * q);
        }
        cj_patch p = cj_patch_view(m, n, pts, NULL);
        double size;
        cj_patch_size(&p, &size);
        const double tol = (c % 2 ? 1e-2 : 4e-3) * size;
        for (int mode = 0; mode < 2; ++mode) {
            cj_mesh *mesh;
            assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
            cj_tess_options opt = {tol, mode ? 9 : 0, 0, 0};
            cj_tess_report rep;
            const cj_status st = cj_tessellate_patches(&p, 1, &opt, mesh, &rep);
            if (st != CJ_OK)
                fail_msg("seed %llu case %d mode %d (deg %d,%d): %s", (unsigned long long)seed, c,
                         mode, m, n, cj_last_error());
            const double dev = sample_deviation(mesh, &p, 4, size);
            if (dev > rep.bound)
                fail_msg("seed %llu case %d mode %d: sampled deviation %.6g > proven bound %.6g",
                         (unsigned long long)seed, c, mode, dev, rep.bound);
            if (mode == 0 && rep.bound > tol)
                fail_msg("seed %llu case %d: bound %.6g > tol %.6g", (unsigned long long)seed, c,
                         rep.bound, tol);
            worst_ratio = fmax(worst_ratio, dev / rep.bound);
            /* all triangles counter-clockwise in (u,v) */
            for (size_t t = 0; t < mesh->triangle_count; ++t) {
                const double *a = mesh->uvs + 2 * (size_t)mesh->triangles[3 * t],
                             *b = mesh->uvs + 2 * (size_t)mesh->triangles[3 * t + 1],
                             *cc = mesh->uvs + 2 * (size_t)mesh->triangles[3 * t + 2];
                assert_true((b[0] - a[0]) * (cc[1] - a[1]) - (b[1] - a[1]) * (cc[0] - a[0]) > 0);
            }
            cj_mesh_destroy(mesh);
            ++cases;
        }
    }
    printf(
        "random patches (deg 1..5): %d tessellations (adaptive to tol and uniform 9x9), "
        "sampled deviation <= proven bound <= tol; worst deviation/bound %.3f; all CCW in (u,v)\n",
        cases, worst_ratio);
}

/* ---- straight edges on twisted patches --------------------------------------------------- */

/* Adaptive at tol: bound <= tol, sampled deviation <= bound, no more triangles than the
 * smallest uniform K meeting tol. Returns the adaptive triangle count; the mesh is kept. */
static size_t adaptive_vs_uniform(const cj_patch *p, size_t np, double tol, const char *what, int c,
                                  cj_mesh *mesh, int *K_out, size_t *uni_out) {
    cj_mesh_clear(mesh);
    cj_tess_options opt = {tol, 0, 0, 0};
    cj_tess_report rep;
    if (cj_tessellate_patches(p, np, &opt, mesh, &rep) != CJ_OK)
        fail_msg("seed %llu %s case %d: %s", (unsigned long long)seed, what, c, cj_last_error());
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < mesh->vertex_count; ++i)
        for (int k = 0; k < 3; ++k) {
            lo[k] = fmin(lo[k], mesh->positions[3 * i + k]);
            hi[k] = fmax(hi[k], mesh->positions[3 * i + k]);
        }
    const double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
    const double dev = sample_deviation(mesh, p, 6, size);
    if (rep.bound > tol)
        fail_msg("seed %llu %s case %d: bound %.6g > tol %.6g", (unsigned long long)seed, what, c,
                 rep.bound, tol);
    if (dev > rep.bound)
        fail_msg("seed %llu %s case %d: sampled deviation %.6g > bound %.6g",
                 (unsigned long long)seed, what, c, dev, rep.bound);
    size_t uni;
    const int K = tess_smallest_uniform(p, np, tol, &uni);
    if (rep.triangles > uni)
        fail_msg("seed %llu %s case %d: adaptive %zu triangles > uniform K=%d %zu triangles",
                 (unsigned long long)seed, what, c, rep.triangles, K, uni);
    *K_out = K;
    *uni_out = uni;
    return rep.triangles;
}

/* A patch of degree (m,n) whose four edges are straight, evenly parametrized segments between
 * random corners (so each edge alone needs one segment), with random interior control
 * points: the patch bends and twists across its straight edges. */
static void straight_edged_patch(cj_rng *r, int m, int n, double *pts) {
    double c[4][3];
    for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k)
            c[a][k] =
                (k < 2 ? (double)((k == 0 ? a : a >> 1) & 1) : 0.0) + cj_rng_range(r, -0.3, 0.3);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const double s = (double)i / m, t = (double)j / n;
            double *x = pts + 3 * (j * (m + 1) + i);
            const int interior = i > 0 && i < m && j > 0 && j < n;
            for (int k = 0; k < 3; ++k) {
                const double bil = (1 - t) * ((1 - s) * c[0][k] + s * c[1][k]) +
                                   t * ((1 - s) * c[2][k] + s * c[3][k]);
                x[k] = interior ? bil + cj_rng_range(r, -0.6, 0.6) : bil;
            }
        }
}

static void test_straight_edges_twisted(void **state) {
    (void)state;
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    /* the twisted bilinear patch: straight edges, twist S_uv = (0,0,1) */
    const double tw[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
    const cj_patch twisted = cj_patch_view(1, 1, tw, NULL);
    int K;
    size_t uni;
    const size_t ntw =
        adaptive_vs_uniform(&twisted, 1, 0.01, "twisted bilinear", 0, mesh, &K, &uni);
    /* independent: the bound of a K x K grid is S_uv/(4 K^2) = 1/(4 K^2) <= 0.01 first at K = 6
     * (K = 5 hits 0.01 exactly and the rounding allowance puts it over) */
    assert_int_equal(K, 6);
    printf("twisted bilinear patch, tol 0.01: adaptive %zu triangles, uniform K=%d %zu\n", ntw, K,
           uni);
    /* random straight-edged patches */
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x5ea1);
    size_t sum_a = 0, sum_u = 0;
    for (int c = 0; c < 8; ++c) {
        const int m = cj_rng_int(&r, 1, 4), n = cj_rng_int(&r, 1, 4);
        double pts[25 * 3];
        straight_edged_patch(&r, m, n, pts);
        const cj_patch p = cj_patch_view(m, n, pts, NULL);
        double size;
        cj_patch_size(&p, &size);
        sum_a += adaptive_vs_uniform(&p, 1, (c % 2 ? 1e-2 : 3e-3) * size, "straight-edged", c, mesh,
                                     &K, &uni);
        sum_u += uni;
    }
    /* two patches sharing a straight edge: the twisted one and a flat one (alone 2 triangles);
     * the shared edge must carry the twisted side's count on both sides, bit-identically */
    const double flat[12] = {1, 0, 0, 2, 0, 0, 1, 1, 1, 2, 1, 1};
    const cj_patch pair[2] = {twisted, cj_patch_view(1, 1, flat, NULL)};
    const size_t npair = adaptive_vs_uniform(pair, 2, 0.01, "shared edge", 0, mesh, &K, &uni);
    double a[64 * 3], b[64 * 3];
    size_t na = 0, nb = 0, flat_tris = 0;
    for (size_t i = 0; i < mesh->vertex_count; ++i) {
        const double *uv = mesh->uvs + 2 * i, *x = mesh->positions + 3 * i;
        if (x[0] != 1.0) continue; /* the shared edge is x = 1: u = 1 on patch 0, u = 0 on 1 */
        if (uv[0] == 1.0 && na < 64) memcpy(a + 3 * na++, x, 3 * sizeof(double));
        if (uv[0] == 0.0 && nb < 64) memcpy(b + 3 * nb++, x, 3 * sizeof(double));
    }
    qsort(a, na, 3 * sizeof(double), cmp3);
    qsort(b, nb, 3 * sizeof(double), cmp3);
    for (size_t t = 0; t < mesh->triangle_count; ++t) flat_tris += mesh->triangle_patch[t] == 1;
    assert_true(na >= 3 && na < 64); /* more than the flat patch alone needs */
    if (na != nb || memcmp(a, b, na * 3 * sizeof(double)))
        fail_msg("shared straight edge: %zu vs %zu vertices, or positions differ", na, nb);
    size_t dropped;
    assert_int_equal(cj_mesh_weld(mesh, &dropped), CJ_OK);
    cj_mesh_topology topo;
    assert_int_equal(cj_mesh_topology_compute(mesh, &topo), CJ_OK);
    assert_int_equal((int)topo.nonmanifold_edges, 0);
    assert_int_equal((int)topo.misoriented_edges, 0);
    /* no crack: every mesh edge on x = 1 is interior (shared by both patches' triangles) */
    size_t open_on_shared = 0;
    for (size_t t = 0; t < mesh->triangle_count; ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t v0 = mesh->triangles[3 * t + e],
                           v1 = mesh->triangles[3 * t + (e + 1) % 3];
            if (mesh->positions[3 * (size_t)v0] != 1.0 || mesh->positions[3 * (size_t)v1] != 1.0)
                continue;
            int uses = 0;
            for (size_t s = 0; s < mesh->triangle_count; ++s)
                for (int f = 0; f < 3; ++f) {
                    const uint32_t w0 = mesh->triangles[3 * s + f],
                                   w1 = mesh->triangles[3 * s + (f + 1) % 3];
                    uses += (w0 == v0 && w1 == v1) || (w0 == v1 && w1 == v0);
                }
            open_on_shared += uses != 2;
        }
    assert_int_equal((int)open_on_shared, 0);
    cj_mesh_destroy(mesh);
    printf("straight-edged random patches (8, deg 1..4): adaptive %zu triangles vs smallest "
           "uniform meeting tol %zu; twisted + flat patch sharing a straight edge: %zu triangles "
           "(flat one %zu), %zu bit-identical vertices on the shared edge, no crack after weld; "
           "all bound <= tol, sampled deviation <= bound\n",
           sum_a, sum_u, npair, flat_tris, na);
}

static double signed_volume(const cj_mesh *m) {
    double vol = 0.0;
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const double *a = m->positions + 3 * (size_t)m->triangles[3 * t],
                     *b = m->positions + 3 * (size_t)m->triangles[3 * t + 1],
                     *c = m->positions + 3 * (size_t)m->triangles[3 * t + 2];
        vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) /
               6.0;
    }
    return vol;
}

static void test_closed_meshes(void **state) {
    (void)state;
    /* torus R = 2, r = 0.5 */
    cj_torus to;
    assert_int_equal(cj_torus_init(&to, cj_v3(0, 0, 0), cj_v3(0, 0, 1), 2.0, 0.5), CJ_OK);
    cj_param_surface s;
    cj_torus_surface(&to, &s);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    assert_int_equal(cj_tessellate_surface(&s, 48, 24, 0, mesh, NULL), CJ_OK);
    cj_mesh_topology t;
    assert_int_equal(cj_mesh_topology_compute(mesh, &t), CJ_OK);
    assert_int_equal((int)t.boundary_edges, 0);
    assert_int_equal((int)t.nonmanifold_edges, 0);
    assert_int_equal((int)t.misoriented_edges, 0);
    assert_int_equal((int)t.euler, 0);
    const double vt = signed_volume(mesh), vt_exact = 2 * PI * PI * 2.0 * 0.25;
    assert_true(fabs(vt - vt_exact) < 0.02 * vt_exact); /* outward: positive volume */
    cj_mesh_clear(mesh);
    /* ellipsoid 1 x 2 x 3 */
    cj_quadric q;
    assert_int_equal(cj_quadric_ellipsoid(&q, 1.0, 2.0, 3.0), CJ_OK);
    cj_quadric_surface(&q, &s);
    size_t dropped = 0;
    assert_int_equal(cj_tessellate_surface(&s, 40, 20, 1, mesh, &dropped), CJ_OK);
    assert_int_equal(cj_mesh_topology_compute(mesh, &t), CJ_OK);
    assert_int_equal((int)t.boundary_edges, 0);
    assert_int_equal((int)t.nonmanifold_edges, 0);
    assert_int_equal((int)t.misoriented_edges, 0);
    assert_int_equal((int)t.euler, 2);
    assert_int_equal((int)dropped, 2 * 40); /* one fan row of degenerate triangles per pole */
    const double ve = signed_volume(mesh), ve_exact = 4.0 / 3.0 * PI * 6.0;
    assert_true(fabs(ve - ve_exact) < 0.02 * ve_exact);
    /* normals of the mesh point outward: n . (p - centre) > 0 */
    for (size_t i = 0; i < mesh->vertex_count; ++i) {
        const double *p = mesh->positions + 3 * i, *n = mesh->normals + 3 * i;
        assert_true(p[0] * n[0] + p[1] * n[1] + p[2] * n[2] > 0.0);
    }
    cj_mesh_destroy(mesh);
    printf("closed meshes: torus 48x24 and ellipsoid 40x20 are manifold, boundary-free, "
           "consistently oriented, Euler 0 and 2, outward (volumes %.4f ~ %.4f, %.4f ~ %.4f)\n",
           vt, vt_exact, ve, ve_exact);
}

static void test_rational_and_options(void **state) {
    (void)state;
    /* a rational quadratic patch (quarter cylinder): uniform and adaptive, both with a finite
     * proven bound that the exact distance of the mesh to the cylinder respects */
    const double pts[27] = {1,   0, 0, 1,   1, 0, 0, 1, 0, 1, 0, 0.5, 1, 1,
                            0.5, 0, 1, 0.5, 1, 0, 1, 1, 1, 1, 0, 1,   1};
    const double w[9] = {1, SQRT1_2, 1, 1, SQRT1_2, 1, 1, SQRT1_2, 1};
    cj_patch p = cj_patch_view(2, 2, pts, w);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {0.0, 8, 0, 0};
    cj_tess_report rep;
    assert_int_equal(cj_tessellate_patches(&p, 1, &opt, mesh, &rep), CJ_OK);
    assert_true(isfinite(rep.bound) && rep.bound > 0.0);
    for (size_t i = 0; i < mesh->vertex_count; ++i) { /* on the unit cylinder */
        const double *x = mesh->positions + 3 * i;
        assert_true(fabs(hypot(x[0], x[1]) - 1.0) < 1e-14);
    }
    /* the sagitta of a chord of angle pi/16 on the unit circle: the exact deviation of the
     * 8 x 8 mesh (the straight direction is exact), which the bound must cover */
    const double sagitta = 1.0 - cos(PI / 32);
    assert_true(rep.bound >= sagitta && rep.bound < 4.0 * sagitta);
    const double uniform_bound = rep.bound;
    opt.uniform = 0;
    opt.tol = 1e-3;
    cj_mesh_clear(mesh);
    assert_int_equal(cj_tessellate_patches(&p, 1, &opt, mesh, &rep), CJ_OK);
    assert_true(rep.bound <= 1e-3);
    /* not far from the fewest triangles possible: one strip of chords whose sagitta
     * 1 - cos(theta/2) is <= tol, two triangles each (the straight direction needs no
     * subdivision) */
    const double chords = ceil((PI / 2) / (2.0 * acos(1.0 - 1e-3)));
    assert_true((double)rep.triangles <= 4.0 * 2.0 * chords);
    for (size_t t = 0; t < mesh->triangle_count; ++t) { /* triangle centroids: inside by <= bound */
        double c[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d)
                c[d] += mesh->positions[3 * (size_t)mesh->triangles[3 * t + k] + d] / 3.0;
        assert_true(1.0 - hypot(c[0], c[1]) <= rep.bound);
    }
    const size_t adaptive_tris = rep.triangles;
    const double adaptive_bound = rep.bound;
    cj_mesh_clear(mesh);
    { /* mixed with a polynomial patch (the saddle z = uv over the unit square) */
        const double sp[12] = {0, 0, 2, 1, 0, 2, 0, 1, 2, 1, 1, 3};
        const cj_patch two[2] = {p, cj_patch_view(1, 1, sp, NULL)};
        assert_int_equal(cj_tessellate_patches(two, 2, &opt, mesh, &rep), CJ_OK);
        assert_true(rep.bound <= 1e-3 && rep.triangles > adaptive_tris);
        cj_mesh_clear(mesh);
    }
    opt.tol = -1;
    assert_int_equal(cj_tessellate_patches(&p, 1, &opt, mesh, &rep), CJ_ERR_ARGUMENT);
    opt.tol = NAN;
    assert_int_equal(cj_tessellate_patches(&p, 1, &opt, mesh, &rep), CJ_ERR_NONFINITE);
    /* the cap is reported */
    const double hp[27] = {0,  0, 0, 1, 0, 5, 2, 0, 0, 0, 1, 5, 1, 1,
                           -9, 2, 1, 5, 0, 2, 0, 1, 2, 5, 2, 2, 0};
    cj_patch hpp = cj_patch_view(2, 2, hp, NULL);
    cj_tess_options capped = {1e-9, 0, 0, 16};
    assert_int_equal(cj_tessellate_patches(&hpp, 1, &capped, mesh, &rep), CJ_ERR_CAP);
    cj_mesh_destroy(mesh);
    printf("rational patch (exact quarter cylinder): uniform 8x8 bound %.4g >= sagitta %.4g; "
           "adaptive tol 1e-3: %zu triangles (<= 4 x the %.0f of one strip of chords), bound %.4g, "
           "centroids within it of the cylinder; "
           "bad tolerances; segment cap reported as CJ_ERR_CAP\n",
           uniform_bound, sagitta, adaptive_tris, 2.0 * chords, adaptive_bound);
}

int main(void) {
    seed = cj_test_seed("test_tessellate", 5905);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_patches_within_tol),
        cmocka_unit_test(test_teapot_data),
        cmocka_unit_test(test_teapot_tolerances_and_cracks),
        cmocka_unit_test(test_straight_edges_twisted),
        cmocka_unit_test(test_closed_meshes),
        cmocka_unit_test(test_rational_and_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
