/* Tessellation: the surface-to-mesh deviation, measured by dense sampling with an independent
 * Bernstein-sum evaluator, stays within the reported bound and the tolerance (random patches
 * and the teapot at 1e-2, 3e-3, 1e-3 of its size); the teapot mesh has zero cracks (every
 * shared patch edge carries bit-identical vertices on both sides; boundary edges only on the
 * true open boundary); closed meshes (torus, ellipsoid) are manifold with Euler characteristic
 * 0 and 2; patches with straight edges across which they twist (the twisted bilinear patch,
 * random ones) need no more triangles adaptively than the smallest uniform grid meeting tol,
 * and a straight edge shared with a flat patch carries the same vertices on both sides; the
 * teapot data's shared edges; OBJ/PLY export; the .bpt loader's messages. Rational patches
 * (random, degrees 1..4, weights in [0.2,5]; exact sphere octants and torus pieces closing into
 * a sphere and a torus; a quarter cylinder), adaptive and uniform: the distance from the
 * surface (independent homogeneous Bernstein sums) to its mesh points L(x) (linear) and Q(x)
 * (homogeneous linear) and to its triangle,
 * and the exact distance of the mesh to the sphere/torus/cylinder, stay within the proven
 * bound (<= tol in adaptive mode); the closed ones are crack-free manifolds. */
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

static double binom(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

/* Independent evaluation: the Bernstein sum (polynomial or rational). */
static void bern_eval(const cj_patch *p, double u, double v, double out[3]) {
    const int m = p->deg_u, n = p->deg_v;
    double bu[CJ_PATCH_MAX_DEGREE + 1], bv[CJ_PATCH_MAX_DEGREE + 1];
    /* B_i^m(u) = C(m,i) u^i (1-u)^(m-i), powers by repeated products */
    double pu[CJ_PATCH_MAX_DEGREE + 1], qu[CJ_PATCH_MAX_DEGREE + 1];
    pu[0] = qu[0] = 1.0;
    for (int i = 1; i <= m; ++i) pu[i] = pu[i - 1] * u, qu[i] = qu[i - 1] * (1 - u);
    for (int i = 0; i <= m; ++i) bu[i] = binom(m, i) * pu[i] * qu[m - i];
    pu[0] = qu[0] = 1.0;
    for (int j = 1; j <= n; ++j) pu[j] = pu[j - 1] * v, qu[j] = qu[j - 1] * (1 - v);
    for (int j = 0; j <= n; ++j) bv[j] = binom(n, j) * pu[j] * qu[n - j];
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
            pts[3 * q] = (double)(q % (m + 1)) / m + cj_rng_range(&r, -0.4, 0.4);
            pts[3 * q + 1] = (double)(q / (m + 1)) / n + cj_rng_range(&r, -0.4, 0.4);
            pts[3 * q + 2] = cj_rng_range(&r, -0.8, 0.8);
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

/* The smallest K whose uniform K x K tessellation has a proven bound <= tol, and its triangle
 * count. */
static int smallest_uniform(const cj_patch *p, size_t np, double tol, size_t *tris) {
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    int K = 1;
    for (;; ++K) {
        assert_true(K <= 400);
        cj_mesh_clear(mesh);
        cj_tess_options opt = {0.0, K, 0, 0};
        cj_tess_report rep;
        assert_int_equal(cj_tessellate_patches(p, np, &opt, mesh, &rep), CJ_OK);
        if (rep.bound <= tol) {
            *tris = rep.triangles;
            break;
        }
    }
    cj_mesh_destroy(mesh);
    return K;
}

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
    const int K = smallest_uniform(p, np, tol, &uni);
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

/* ---- rational patches -------------------------------------------------------------------- */

/* Independent homogeneous evaluation: numerator and denominator Bernstein sums. */
static void bern_eval_h(const cj_patch *p, double u, double v, double num[3], double *den) {
    const int m = p->deg_u, n = p->deg_v;
    double bu[CJ_PATCH_MAX_DEGREE + 1], bv[CJ_PATCH_MAX_DEGREE + 1];
    double pu[CJ_PATCH_MAX_DEGREE + 1], qu[CJ_PATCH_MAX_DEGREE + 1];
    pu[0] = qu[0] = 1.0;
    for (int i = 1; i <= m; ++i) pu[i] = pu[i - 1] * u, qu[i] = qu[i - 1] * (1 - u);
    for (int i = 0; i <= m; ++i) bu[i] = binom(m, i) * pu[i] * qu[m - i];
    pu[0] = qu[0] = 1.0;
    for (int j = 1; j <= n; ++j) pu[j] = pu[j - 1] * v, qu[j] = qu[j - 1] * (1 - v);
    for (int j = 0; j <= n; ++j) bv[j] = binom(n, j) * pu[j] * qu[n - j];
    num[0] = num[1] = num[2] = *den = 0.0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const int q = j * (m + 1) + i;
            const double w = bu[i] * bv[j] * (p->weights ? p->weights[q] : 1.0);
            *den += w;
            for (int k = 0; k < 3; ++k) num[k] += w * p->pts[3 * q + k];
        }
}

static double dist3(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* Distance from point x to triangle (a, b, c): minimum over the plane projection when it falls
 * inside, else over the three edges (closest point on a segment). */
static double point_triangle_distance(const double *x, const double *a, const double *b,
                                      const double *c) {
    double e0[3], e1[3], d[3], nrm[3];
    for (int k = 0; k < 3; ++k) e0[k] = b[k] - a[k], e1[k] = c[k] - a[k], d[k] = x[k] - a[k];
    nrm[0] = e0[1] * e1[2] - e0[2] * e1[1];
    nrm[1] = e0[2] * e1[0] - e0[0] * e1[2];
    nrm[2] = e0[0] * e1[1] - e0[1] * e1[0];
    const double nn = nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2];
    if (nn > 0.0) {
        /* barycentric of the projection by sub-areas */
        const double *P3[3] = {a, b, c};
        const double t = (d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2]) / nn;
        double y[3];
        for (int k = 0; k < 3; ++k) y[k] = x[k] - t * nrm[k];
        int inside = 1;
        for (int e = 0; e < 3 && inside; ++e) {
            const double *p0 = P3[e], *p1 = P3[(e + 1) % 3];
            double f[3], g[3];
            for (int k = 0; k < 3; ++k) f[k] = p1[k] - p0[k], g[k] = y[k] - p0[k];
            const double cr[3] = {f[1] * g[2] - f[2] * g[1], f[2] * g[0] - f[0] * g[2],
                                  f[0] * g[1] - f[1] * g[0]};
            if (cr[0] * nrm[0] + cr[1] * nrm[1] + cr[2] * nrm[2] < 0.0) inside = 0;
        }
        if (inside) return fabs(t) * sqrt(nn);
    }
    double best = INFINITY;
    const double *P3[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) {
        const double *p0 = P3[e], *p1 = P3[(e + 1) % 3];
        double f[3], ff = 0.0, fg = 0.0;
        for (int k = 0; k < 3; ++k) {
            f[k] = p1[k] - p0[k];
            ff += f[k] * f[k];
            fg += f[k] * (x[k] - p0[k]);
        }
        double t = ff > 0.0 ? fg / ff : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        double q[3];
        for (int k = 0; k < 3; ++k) q[k] = p0[k] + t * f[k];
        best = fmin(best, dist3(x, q));
    }
    return best;
}

typedef double (*exact_dist_fn)(const double *x); /* distance to an exact surface */

typedef struct rat_stats {
    double dev;        /* max of min(|S(x) - L(x)|, |S(x) - Q(x)|) */
    double tri_dist;   /* max distance from S(x) to its triangle */
    double mesh_exact; /* max distance of the mesh points L(x) to the exact surface */
    double surf_exact; /* max distance of the oracle's S(x) to the exact surface */
} rat_stats;

/* Samples every triangle on the barycentric lattice of step 1/L with the independent oracle:
 * S(x) at the interpolated (u,v); the mesh points L(x) = Σ λ_i V_i and Q(x) = Σ λ_i w_i V_i /
 * Σ λ_i w_i (w_i the oracle's weight at vertex i), the deviation being the smaller of
 * |S - L| and |S - Q| (the quantity the rational bound bounds); the distance from S(x) to the
 * triangle, which must not exceed it; with `exact`, the distances of S(x) and L(x) to the
 * exact surface. Also checks every vertex lies on its patch (within 1e-12 of the size). */
static rat_stats rational_deviation(const cj_mesh *mesh, const cj_patch *patches, int L,
                                    double size, exact_dist_fn exact) {
    rat_stats st = {0.0, 0.0, 0.0, 0.0};
    for (size_t t = 0; t < mesh->triangle_count; ++t) {
        const cj_patch *p = &patches[mesh->triangle_patch[t]];
        const uint32_t *vi = mesh->triangles + 3 * t;
        const double *uv[3], *V[3];
        double w[3];
        for (int k = 0; k < 3; ++k) {
            uv[k] = mesh->uvs + 2 * (size_t)vi[k];
            V[k] = mesh->positions + 3 * (size_t)vi[k];
            double num[3], s[3];
            bern_eval_h(p, uv[k][0], uv[k][1], num, &w[k]);
            for (int c = 0; c < 3; ++c) s[c] = num[c] / w[k];
            if (dist3(s, V[k]) > 1e-12 * size)
                fail_msg("seed %llu: triangle %zu vertex %d is not on patch %d",
                         (unsigned long long)seed, t, k, (int)mesh->triangle_patch[t]);
        }
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const double l[3] = {(double)i / L, (double)j / L,
                                     1.0 - (double)i / L - (double)j / L};
                double num[3], den, s[3], q[3] = {0, 0, 0};
                bern_eval_h(p, l[0] * uv[0][0] + l[1] * uv[1][0] + l[2] * uv[2][0],
                            l[0] * uv[0][1] + l[1] * uv[1][1] + l[2] * uv[2][1], num, &den);
                for (int c = 0; c < 3; ++c) s[c] = num[c] / den;
                double qh[3] = {0, 0, 0};
                const double sw = l[0] * w[0] + l[1] * w[1] + l[2] * w[2];
                for (int k = 0; k < 3; ++k)
                    for (int c = 0; c < 3; ++c) {
                        q[c] += l[k] * V[k][c];
                        qh[c] += l[k] * w[k] / sw * V[k][c];
                    }
                const double dev = fmin(dist3(s, q), dist3(s, qh));
                const double td = point_triangle_distance(s, V[0], V[1], V[2]);
                if (td > dev + 1e-13 * size)
                    fail_msg("seed %llu: triangle %zu: distance to the triangle %.6g exceeds the "
                             "distance %.6g to one of its points",
                             (unsigned long long)seed, t, td, dev);
                st.dev = fmax(st.dev, dev);
                st.tri_dist = fmax(st.tri_dist, td);
                if (exact) {
                    st.mesh_exact = fmax(st.mesh_exact, exact(q));
                    st.surf_exact = fmax(st.surf_exact, exact(s));
                }
            }
    }
    return st;
}

static void test_rational_random(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x9e3779b97f4a7c15ull);
    int cases = 0;
    double worst_ratio = 0.0, best_ratio = 1.0;
    size_t tris[2] = {0, 0}, uni_tris = 0, ada6 = 0;
    for (int c = 0; c < 12; ++c) {
        const int m = cj_rng_int(&r, 1, 4), n = cj_rng_int(&r, 1, 4);
        double pts[25 * 3], w[25], w3[25];
        for (int q = 0; q < (m + 1) * (n + 1); ++q) {
            pts[3 * q] = (double)(q % (m + 1)) / m + cj_rng_range(&r, -0.4, 0.4);
            pts[3 * q + 1] = (double)(q / (m + 1)) / n + cj_rng_range(&r, -0.4, 0.4);
            pts[3 * q + 2] = cj_rng_range(&r, -0.8, 0.8);
            w[q] = exp(cj_rng_range(&r, log(0.2), log(5.0))); /* in [0.2, 5] */
            w3[q] = 3.0 * w[q];
        }
        cj_patch p = cj_patch_view(m, n, pts, w);
        double size;
        cj_patch_size(&p, &size);
        const double tol = (c % 2 ? 1e-2 : 4e-3) * size;
        for (int mode = 0; mode < 2; ++mode) {
            cj_mesh *mesh;
            assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
            cj_tess_options opt = {tol, mode ? 9 : 0, 3, 0};
            cj_tess_report rep;
            const cj_status st = cj_tessellate_patches(&p, 1, &opt, mesh, &rep);
            if (st != CJ_OK)
                fail_msg("seed %llu rational case %d mode %d (deg %d,%d): %s",
                         (unsigned long long)seed, c, mode, m, n, cj_last_error());
            const rat_stats rs = rational_deviation(mesh, &p, 4, size, NULL);
            if (!isfinite(rep.bound) || rs.dev > rep.bound || rep.measured > rep.bound)
                fail_msg("seed %llu rational case %d mode %d: sampled deviation %.6g (library "
                         "%.6g) > proven bound %.6g",
                         (unsigned long long)seed, c, mode, rs.dev, rep.measured, rep.bound);
            if (mode == 0 && rep.bound > tol)
                fail_msg("seed %llu rational case %d: bound %.6g > tol %.6g",
                         (unsigned long long)seed, c, rep.bound, tol);
            if (mode == 0 && c < 4) { /* (a linear search: the first cases only) */
                size_t uni;
                const int K = smallest_uniform(&p, 1, tol, &uni);
                if (rep.triangles > uni)
                    fail_msg("seed %llu rational case %d: adaptive %zu triangles > uniform K=%d "
                             "%zu triangles",
                             (unsigned long long)seed, c, rep.triangles, K, uni);
                uni_tris += uni;
                ada6 += rep.triangles;
            }
            if (mode == 1) {
                /* the surface does not change when every weight is scaled: nor does the bound
                 * (up to rounding) */
                cj_patch p3 = cj_patch_view(m, n, pts, w3);
                cj_tess_report rep3;
                cj_mesh_clear(mesh);
                assert_int_equal(cj_tessellate_patches(&p3, 1, &opt, mesh, &rep3), CJ_OK);
                if (fabs(rep3.bound - rep.bound) > 1e-9 * rep.bound)
                    fail_msg("seed %llu rational case %d: bound %.17g changes to %.17g when the "
                             "weights are scaled by 3",
                             (unsigned long long)seed, c, rep.bound, rep3.bound);
            }
            worst_ratio = fmax(worst_ratio, rs.dev / rep.bound);
            best_ratio = fmin(best_ratio, rs.dev / rep.bound);
            tris[mode] += rep.triangles;
            cj_mesh_destroy(mesh);
            ++cases;
        }
    }
    printf("random rational patches (deg 1..4, weights in [0.2,5]): %d tessellations, sampled "
           "deviation min(|S-L|,|S-Q|) <= proven bound (<= tol adaptive, finite uniform), "
           "deviation/bound in "
           "[%.3f, %.3f]; adaptive %zu triangles (first 4 cases %zu <= %zu of the smallest "
           "uniform grids meeting tol), uniform 9x9 %zu; bound invariant under weight scaling\n",
           cases, best_ratio, worst_ratio, tris[0], ada6, uni_tris, tris[1]);
}

/* Exact rational nets: the tensor product of two rational quadratic quarter circles. */
static const double QC[3][2] = {{1, 0}, {1, 1}, {0, 1}};
static const double QW[3] = {1, SQRT1_2, 1};

/* Rotates (x, y) by k quarter turns (exact). */
static void quarter_turn(int k, double x, double y, double *ox, double *oy) {
    for (int i = 0; i < (k & 3); ++i) {
        const double t = x;
        x = -y;
        y = t;
    }
    *ox = x;
    *oy = y;
}

/* Sphere octant k (0..3 around z), north (hemi = 0) or south (1): S = (C(u) r(v), z(v)) with
 * C the quarter circle from angle k 90deg (reversed in the south so the normal points out) and
 * (r, z) the quarter circle from the equator to the pole. Unit sphere; the pole row collapses
 * (identical points, weights 1, 1/sqrt2, 1). */
static void sphere_octant(int k, int hemi, double *pts, double *w) {
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const int ii = hemi ? 2 - i : i;
            double x, y;
            quarter_turn(k, QC[ii][0], QC[ii][1], &x, &y);
            const int q = j * 3 + i;
            pts[3 * q] = x * QC[j][0];
            pts[3 * q + 1] = y * QC[j][0];
            pts[3 * q + 2] = hemi ? -QC[j][1] : QC[j][1];
            w[q] = QW[ii] * QW[j];
        }
}

/* Torus piece (a, b): R = 2, tube r = 0.5, around z by quarter a, around the tube by quarter
 * b: S = ((R + r cos phi) C(u), r sin phi). */
static void torus_piece(int a, int b, double *pts, double *w) {
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            double x, y, cphi, sphi;
            quarter_turn(a, QC[i][0], QC[i][1], &x, &y);
            quarter_turn(b, QC[j][0], QC[j][1], &cphi, &sphi);
            const int q = j * 3 + i;
            pts[3 * q] = x * (2.0 + 0.5 * cphi);
            pts[3 * q + 1] = y * (2.0 + 0.5 * cphi);
            pts[3 * q + 2] = 0.5 * sphi;
            w[q] = QW[i] * QW[j];
        }
}

static double sphere_dist(const double *x) {
    return fabs(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1.0);
}
static double torus_dist(const double *x) {
    return fabs(hypot(hypot(x[0], x[1]) - 2.0, x[2]) - 0.5);
}

/* One closed rational model at one setting: bound/tol, oracle deviation <= bound, exact
 * distances <= bound, closed manifold of the given Euler characteristic after identifying
 * equal positions (zero cracks). */
static void exact_model(const char *name, const cj_patch *pp, size_t np, exact_dist_fn exact,
                        long euler, double tol, int uniform, int L) {
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {tol, uniform, 0, 0};
    cj_tess_report rep;
    if (cj_tessellate_patches(pp, np, &opt, mesh, &rep) != CJ_OK)
        fail_msg("%s tol %g uniform %d: %s", name, tol, uniform, cj_last_error());
    const rat_stats rs = rational_deviation(mesh, pp, L, 4.0, exact);
    if (!(rep.bound < INFINITY) || (!uniform && rep.bound > tol) || rs.dev > rep.bound ||
        rs.mesh_exact > rep.bound || rs.tri_dist > rep.bound || rs.surf_exact > 1e-14)
        fail_msg("%s tol %g uniform %d: bound %.6g, deviation %.6g, to triangle %.6g, mesh to "
                 "exact surface %.6g, oracle off the surface by %.3g",
                 name, tol, uniform, rep.bound, rs.dev, rs.tri_dist, rs.mesh_exact, rs.surf_exact);
    cj_mesh_topology t;
    assert_int_equal(cj_mesh_topology_compute(mesh, &t), CJ_OK);
    if (t.boundary_edges || t.nonmanifold_edges || t.misoriented_edges || t.euler != euler)
        fail_msg("%s tol %g uniform %d: %zu boundary, %zu non-manifold, %zu misoriented edges, "
                 "Euler %ld (want %ld)",
                 name, tol, uniform, t.boundary_edges, t.nonmanifold_edges, t.misoriented_edges,
                 t.euler, euler);
    char what[32];
    if (uniform)
        snprintf(what, sizeof what, "uniform K %d", uniform);
    else
        snprintf(what, sizeof what, "tol %g", tol);
    printf("  %-6s %-12s %7zu triangles, bound %.4g, deviation min(|S-L|,|S-Q|) %.4g, surface to "
           "triangle %.4g, mesh to exact surface %.4g (ratio %.2f)\n",
           name, what, rep.triangles, rep.bound, rs.dev, rs.tri_dist, rs.mesh_exact,
           rs.dev / rep.bound);
    cj_mesh_destroy(mesh);
}

static void test_rational_exact(void **state) {
    (void)state;
    double sp[8][27], sw[8][9], tp[16][27], tw[16][9];
    cj_patch sphere[8], torus[16];
    for (int k = 0; k < 8; ++k) {
        sphere_octant(k % 4, k / 4, sp[k], sw[k]);
        sphere[k] = cj_patch_view(2, 2, sp[k], sw[k]);
    }
    for (int k = 0; k < 16; ++k) {
        torus_piece(k % 4, k / 4, tp[k], tw[k]);
        torus[k] = cj_patch_view(2, 2, tp[k], tw[k]);
    }
    /* the nets are exact: the oracle's points lie on the quadric / torus */
    printf("exact rational patches (sphere: 8 biquadratic octants, torus R=2 r=0.5: 16 "
           "biquadratic pieces), closed manifold meshes, every distance <= proven bound:\n");
    const double tols[3] = {1e-2, 1e-3, 3e-4};
    for (int i = 0; i < 3; ++i) {
        exact_model("sphere", sphere, 8, sphere_dist, 2, tols[i], 0, i == 2 ? 2 : 4);
        if (i < 2) exact_model("torus", torus, 16, torus_dist, 0, tols[i], 0, 4);
    }
    exact_model("sphere", sphere, 8, sphere_dist, 2, 0.0, 8, 5);
    exact_model("torus", torus, 16, torus_dist, 0, 0.0, 8, 5);
}

static void slurp(const char *path, char **buf, size_t *len) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    *buf = malloc((size_t)n + 1);
    assert_true(fread(*buf, 1, (size_t)n, f) == (size_t)n);
    (*buf)[n] = '\0';
    *len = (size_t)n;
    fclose(f);
}

static void test_export(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {0.0, 3, 0, 0};
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, mesh, NULL), CJ_OK);
    char dir[] = "/tmp/cj_tess_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char obj[256], ply[256], bad[256], plya[256];
    snprintf(obj, sizeof obj, "%s/t.obj", dir);
    snprintf(ply, sizeof ply, "%s/t.ply", dir);
    snprintf(plya, sizeof plya, "%s/ta.ply", dir);
    snprintf(bad, sizeof bad, "%s/missing/t.obj", dir);
    assert_int_equal(cj_mesh_write(mesh, obj), CJ_OK);
    assert_int_equal(cj_mesh_write(mesh, ply), CJ_OK);
    assert_int_equal(cj_mesh_write_ply(mesh, plya, 0), CJ_OK);
    assert_int_equal(cj_mesh_write(mesh, bad), CJ_ERR_IO);
    assert_int_equal(access(bad, F_OK), -1);
    assert_int_equal(cj_mesh_write(mesh, "x.stl"), CJ_ERR_ARGUMENT);
    /* OBJ: one v per distinct position, vt/vn per vertex, a g per patch, faces p/t/n */
    cj_mesh_topology topo;
    cj_mesh_topology_compute(mesh, &topo);
    char *text;
    size_t len;
    slurp(obj, &text, &len);
    size_t nv = 0, nvt = 0, nvn = 0, nf = 0, ng = 0;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        if (!strncmp(line, "v ", 2)) ++nv;
        if (!strncmp(line, "vt ", 3)) ++nvt;
        if (!strncmp(line, "vn ", 3)) ++nvn;
        if (!strncmp(line, "g patch_", 8)) ++ng;
        if (!strncmp(line, "f ", 2)) {
            unsigned a[9];
            assert_int_equal(sscanf(line, "f %u/%u/%u %u/%u/%u %u/%u/%u", &a[0], &a[1], &a[2],
                                    &a[3], &a[4], &a[5], &a[6], &a[7], &a[8]),
                             9);
            ++nf;
        }
    }
    free(text);
    assert_int_equal(nvt, mesh->vertex_count);
    assert_int_equal(nvn, mesh->vertex_count);
    assert_int_equal(nf, mesh->triangle_count);
    assert_int_equal(ng, 32);
    assert_true(nv < mesh->vertex_count); /* welded: seam vertices written once */
    /* PLY binary: header + 8 doubles per vertex + (1 + 3*4) bytes per face */
    slurp(ply, &text, &len);
    char *end = strstr(text, "end_header\n");
    assert_non_null(end);
    assert_non_null(strstr(text, "binary_little_endian"));
    const size_t header = (size_t)(end - text) + strlen("end_header\n");
    assert_int_equal(len, header + 64 * mesh->vertex_count + 13 * mesh->triangle_count);
    double x0;
    memcpy(&x0, text + header, 8);
    assert_true(x0 == mesh->positions[0]);
    free(text);
    slurp(plya, &text, &len);
    assert_non_null(strstr(text, "format ascii 1.0"));
    free(text);
    unlink(obj);
    unlink(ply);
    unlink(plya);
    rmdir(dir);
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    printf("export: OBJ (welded v, per-vertex vt/vn, 32 g groups, p/t/n faces), binary and ascii "
           "PLY layout, unwritable path -> CJ_ERR_IO and no file, unknown extension\n");
}

static void test_bpt_errors(void **state) {
    (void)state;
    cj_patchset *set = NULL;
    assert_int_equal(
        cj_patchset_parse_bpt("1\n1 1\n0 0 0\n1 0 0\n0 x 0\n1 1 1\n", "a.bpt", NULL, &set),
        CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), "a.bpt:5:"));
    assert_non_null(strstr(cj_last_error(), "'x'"));
    assert_int_equal(cj_patchset_parse_bpt("1\n1 1\n0 0 0\n1 0 0\n", "b.bpt", NULL, &set),
                     CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), "end of file"));
    assert_int_equal(cj_patchset_parse_bpt("1\n40 1\n", "c.bpt", NULL, &set), CJ_ERR_DEGREE);
    assert_non_null(strstr(cj_last_error(), "c.bpt:2:"));
    assert_int_equal(cj_patchset_parse_bpt("1 # one patch\n0 0\n1 2 3\n7\n", "d.bpt", NULL, &set),
                     CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), "d.bpt:4:"));
    assert_int_equal(
        cj_patchset_parse_bpt("1 # one patch\n0 0\n1 2 3 # a point\n", "e.bpt", NULL, &set), CJ_OK);
    assert_true(set->count == 1 && set->patches[0].pts[2] == 3.0);
    cj_patchset_destroy(set);
    assert_int_equal(cj_patchset_load_bpt("/nonexistent/x.bpt", NULL, &set), CJ_ERR_IO);
    assert_non_null(strstr(cj_last_error(), "/nonexistent/x.bpt"));
    printf(".bpt loader: line-numbered messages for a bad number, end of file, a degree over the "
           "limit, trailing data; comments; missing file names the path\n");
}

typedef struct counting {
    size_t allocs, frees;
} counting;

static void *count_alloc(void *user, size_t bytes) {
    ++((counting *)user)->allocs;
    return malloc(bytes);
}
static void count_free(void *user, void *ptr) {
    if (ptr) ++((counting *)user)->frees;
    free(ptr);
}

static void test_allocator_and_mesh_errors(void **state) {
    (void)state;
    counting c = {0, 0};
    const cj_allocator a = {count_alloc, count_free, &c};
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, &a, &set), CJ_OK);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(&a, &mesh), CJ_OK);
    cj_tess_options opt = {1e-2, 0, 0, 0};
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, mesh, NULL), CJ_OK);
    assert_true(c.allocs > 10);
    const double p[3] = {0, 0, 0}, bad[3] = {0, NAN, 0};
    uint32_t idx;
    assert_int_equal(cj_mesh_add_vertex(mesh, bad, NULL, NULL, &idx), CJ_ERR_NONFINITE);
    assert_int_equal(cj_mesh_add_vertex(mesh, p, NULL, NULL, &idx), CJ_OK);
    assert_int_equal(cj_mesh_add_triangle(mesh, idx, idx + 1, 0, 0), CJ_ERR_RANGE);
    assert_non_null(strstr(cj_last_error(), "vertex index"));
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    assert_int_equal(c.allocs, c.frees);
    printf("allocator: %zu allocations of the teapot set, mesh and tessellation temporaries all "
           "through the caller's allocator and all released; NaN vertex and bad index rejected\n",
           c.allocs);
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
        cmocka_unit_test(test_rational_random),
        cmocka_unit_test(test_rational_exact),
        cmocka_unit_test(test_export),
        cmocka_unit_test(test_bpt_errors),
        cmocka_unit_test(test_allocator_and_mesh_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
