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

/* Independent evaluation: the Bernstein sum (polynomial or rational). */
static void bern_eval(const cj_patch *p, double u, double v, double out[3]) {
    const int m = p->deg_u, n = p->deg_v;
    double bu[CJ_PATCH_MAX_DEGREE + 1], bv[CJ_PATCH_MAX_DEGREE + 1];
    /* B_i^m(u) = C(m,i) u^i (1-u)^(m-i), powers by repeated products */
    double pu[CJ_PATCH_MAX_DEGREE + 1], qu[CJ_PATCH_MAX_DEGREE + 1];
    pu[0] = qu[0] = 1.0;
    for (int i = 1; i <= m; ++i) pu[i] = pu[i - 1] * u, qu[i] = qu[i - 1] * (1 - u);
    for (int i = 0; i <= m; ++i) bu[i] = tess_binom(m, i) * pu[i] * qu[m - i];
    pu[0] = qu[0] = 1.0;
    for (int j = 1; j <= n; ++j) pu[j] = pu[j - 1] * v, qu[j] = qu[j - 1] * (1 - v);
    for (int j = 0; j <= n; ++j) bv[j] = tess_binom(n, j) * pu[j] * qu[n - j];
    double num[3] = {0, 0, 0}, den = 0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const int q = j * (m + 1) + i;
            const double w = bu[i] * bv[j] * (p->weights ? p->weights[q] : 1.0);
            den += w;
            for (int k = 0; k < 3; ++k) num[k] += w * p->pts[3 * q + k];
        }
    for (int k = 0; k < 3; ++k) out[k] = p->weights ? num[k] / den : num[k];
}

/* max over triangles of max over the barycentric lattice (step 1/L) of |S(x) - L(x)|, with
 * S evaluated by the oracle at the interpolated (u,v). Also checks every vertex lies on its
 * patch (within 1e-12 of the size). */
static double sample_deviation(const cj_mesh *mesh, const cj_patch *patches, int L, double size) {
    double worst = 0.0;
    for (size_t t = 0; t < mesh->triangle_count; ++t) {
        const cj_patch *p = &patches[mesh->triangle_patch[t]];
        const uint32_t *v = mesh->triangles + 3 * t;
        const double *uv[3], *P[3];
        for (int k = 0; k < 3; ++k) {
            uv[k] = mesh->uvs + 2 * (size_t)v[k];
            P[k] = mesh->positions + 3 * (size_t)v[k];
            double s[3];
            bern_eval(p, uv[k][0], uv[k][1], s);
            for (int c = 0; c < 3; ++c)
                if (fabs(s[c] - P[k][c]) > 1e-12 * size)
                    fail_msg("triangle %zu vertex %d is not on patch %d", t, k,
                             (int)mesh->triangle_patch[t]);
        }
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const double a = (double)i / L, b = (double)j / L, c = 1.0 - a - b;
                double s[3], d2 = 0.0;
                bern_eval(p, a * uv[0][0] + b * uv[1][0] + c * uv[2][0],
                          a * uv[0][1] + b * uv[1][1] + c * uv[2][1], s);
                for (int k = 0; k < 3; ++k) {
                    const double x = s[k] - (a * P[0][k] + b * P[1][k] + c * P[2][k]);
                    d2 += x * x;
                }
                worst = fmax(worst, sqrt(d2));
            }
    }
    return worst;
}

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

/* ---- teapot ---------------------------------------------------------------------------- */

typedef struct edge_ref {
    int patch, side, degree, collapsed;
    double pts[4 * 3];
} edge_ref;

static void teapot_edges(const cj_patchset *set, edge_ref *e) {
    for (size_t q = 0; q < set->count; ++q)
        for (int s = 0; s < 4; ++s) {
            edge_ref *x = &e[q * 4 + (size_t)s];
            x->patch = (int)q;
            x->side = s;
            assert_int_equal(
                cj_patch_boundary(&set->patches[q], (cj_patch_edge)s, x->pts, NULL, &x->degree),
                CJ_OK);
            x->collapsed = 1;
            for (int a = 1; a <= x->degree; ++a)
                if (memcmp(x->pts, x->pts + 3 * a, 3 * sizeof(double))) x->collapsed = 0;
        }
}

/* Whether edges x and y have the same control points, forward or reversed. */
static int same_edge(const edge_ref *x, const edge_ref *y) {
    if (x->degree != y->degree) return 0;
    const int d = x->degree;
    int fwd = 1, rev = 1;
    for (int a = 0; a <= d; ++a) {
        if (memcmp(x->pts + 3 * a, y->pts + 3 * a, 24)) fwd = 0;
        if (memcmp(x->pts + 3 * a, y->pts + 3 * (d - a), 24)) rev = 0;
    }
    return fwd || rev;
}

static void test_teapot_data(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    assert_int_equal((int)set->count, 32);
    for (size_t q = 0; q < 32; ++q) {
        assert_int_equal(set->patches[q].deg_u, 3);
        assert_int_equal(set->patches[q].deg_v, 3);
    }
    double lo[3], hi[3], diag;
    assert_int_equal(cj_patchset_bbox(set, lo, hi, &diag), CJ_OK);
    const double elo[3] = {-3.0, -2.0, 0.0}, ehi[3] = {3.525, 2.0, 3.15};
    for (int k = 0; k < 3; ++k) {
        assert_true(lo[k] == elo[k]);
        assert_true(hi[k] == ehi[k]);
    }
    edge_ref e[128];
    teapot_edges(set, e);
    int pairs = 0, open = 0, collapsed = 0;
    for (int i = 0; i < 128; ++i) {
        if (e[i].collapsed) {
            ++collapsed;
            continue;
        }
        int partners = 0;
        for (int j = 0; j < 128; ++j)
            if (j != i && !e[j].collapsed && same_edge(&e[i], &e[j])) ++partners;
        assert_true(partners <= 1);
        if (partners == 0) ++open;
        if (partners == 1) ++pairs;
    }
    pairs /= 2;
    /* rim/body/bottom 4+4+4+4+4+4+4, handle 6, spout 6, lid 4+4+4 = 52; open: rim, lid rim,
     * handle and spout ends (4 each); collapsed: lid top and bottom centre (4 each) */
    assert_int_equal(pairs, 52);
    assert_int_equal(open, 16);
    assert_int_equal(collapsed, 8);
    cj_patchset_destroy(set);
    printf("teapot data: 32 bicubic patches, control box [-3,3.525]x[-2,2]x[0,3.15], 52 shared "
           "edge pairs (exact control points), 16 open and 8 collapsed edges\n");
}

static int cmp3(const void *a, const void *b) {
    const double *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* Positions of patch q's vertices on side s (by their (u,v)), sorted. Returns the count. */
static size_t side_positions(const cj_mesh *mesh, const size_t *vlo, const size_t *vhi, int q,
                             int s, double *out) {
    size_t n = 0;
    for (size_t i = vlo[q]; i <= vhi[q]; ++i) {
        const double *uv = mesh->uvs + 2 * i;
        const int on = (s == 0 && uv[1] == 0.0) || (s == 1 && uv[0] == 1.0) ||
                       (s == 2 && uv[1] == 1.0) || (s == 3 && uv[0] == 0.0);
        if (on) memcpy(out + 3 * n++, mesh->positions + 3 * i, 3 * sizeof(double));
    }
    qsort(out, n, 3 * sizeof(double), cmp3);
    return n;
}

static void teapot_at(const cj_patchset *set, const edge_ref *e, double tol, int uniform,
                      int lattice) {
    double lo[3], hi[3], size;
    cj_patchset_bbox(set, lo, hi, &size);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {tol, uniform, 0, 0};
    cj_tess_report rep;
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, mesh, &rep), CJ_OK);
    if (!uniform) assert_true(rep.bound <= tol);
    const double dev = sample_deviation(mesh, set->patches, lattice, size);
    if (dev > rep.bound)
        fail_msg("teapot tol %g: deviation %.6g > bound %.6g", tol, dev, rep.bound);
    /* vertex ranges per patch (the tessellator appends patch by patch) */
    size_t vlo[32], vhi[32];
    for (int q = 0; q < 32; ++q) vlo[q] = (size_t)-1, vhi[q] = 0;
    for (size_t t = 0; t < mesh->triangle_count; ++t) {
        const int q = mesh->triangle_patch[t];
        for (int k = 0; k < 3; ++k) {
            const size_t v = mesh->triangles[3 * t + k];
            if (v < vlo[q]) vlo[q] = v;
            if (v > vhi[q]) vhi[q] = v;
        }
    }
    /* every shared edge: the same positions, bit for bit, on both sides */
    double *a = malloc(sizeof(double) * 3 * 8192), *b = malloc(sizeof(double) * 3 * 8192);
    assert_non_null(a);
    assert_non_null(b);
    int shared_checked = 0;
    size_t expected_boundary = 0;
    for (int i = 0; i < 128; ++i) {
        if (e[i].collapsed) continue;
        int partner = -1;
        for (int j = 0; j < 128; ++j)
            if (j != i && !e[j].collapsed && same_edge(&e[i], &e[j])) partner = j;
        if (partner < 0) {
            expected_boundary +=
                uniform ? (size_t)uniform
                        : (size_t)cj_tess_edge_segments(e[i].pts, e[i].degree, 0.25 * tol, 1 << 20);
            continue;
        }
        if (partner < i) continue;
        const size_t na = side_positions(mesh, vlo, vhi, e[i].patch, e[i].side, a);
        const size_t nb = side_positions(mesh, vlo, vhi, e[partner].patch, e[partner].side, b);
        if (na != nb || memcmp(a, b, na * 3 * sizeof(double)))
            fail_msg("teapot tol %g: patches %d and %d disagree along their shared edge (%zu vs "
                     "%zu vertices)",
                     tol, e[i].patch, e[partner].patch, na, nb);
        ++shared_checked;
    }
    free(a);
    free(b);
    assert_int_equal(shared_checked, 52);
    cj_mesh_topology topo;
    assert_int_equal(cj_mesh_topology_compute(mesh, &topo), CJ_OK);
    /* no cracks: boundary edges are exactly the segments of the 16 open edges */
    if (topo.boundary_edges != expected_boundary)
        fail_msg("teapot tol %g: %zu boundary edges, expected %zu on the open boundary", tol,
                 topo.boundary_edges, expected_boundary);
    assert_int_equal((int)topo.nonmanifold_edges, 0);
    assert_int_equal((int)topo.misoriented_edges, 0);
    /* welding keeps the same topology */
    const size_t tris = mesh->triangle_count;
    size_t dropped;
    assert_int_equal(cj_mesh_weld(mesh, &dropped), CJ_OK);
    assert_int_equal((int)dropped, 0);
    assert_int_equal(mesh->triangle_count, tris);
    cj_mesh_topology t2;
    cj_mesh_topology_compute(mesh, &t2);
    assert_int_equal(t2.vertices, mesh->vertex_count);
    assert_int_equal(t2.boundary_edges, topo.boundary_edges);
    printf("teapot %s %-8g: %7zu triangles, bound %.4g, sampled deviation %.4g; 52 shared edges "
           "bit-identical, %zu boundary edges = open-boundary segments, manifold, consistently "
           "oriented\n",
           uniform ? "uniform K" : "tol", uniform ? (double)uniform : tol, tris, rep.bound, dev,
           topo.boundary_edges);
    cj_mesh_destroy(mesh);
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

static void test_teapot_tolerances_and_cracks(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    edge_ref e[128];
    teapot_edges(set, e);
    double lo[3], hi[3], size;
    cj_patchset_bbox(set, lo, hi, &size);
    teapot_at(set, e, 1e-2 * size, 0, 4);
    teapot_at(set, e, 3e-3 * size, 0, 3);
    teapot_at(set, e, 1e-3 * size, 0, 2);
    teapot_at(set, e, 0.0, 12, 4);
    cj_patchset_destroy(set);
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
