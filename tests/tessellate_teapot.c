/* test_tessellate, the Utah teapot: its data (32 bicubic patches, shared edges), and its
 * tessellations at several tolerances: within tolerance, and no cracks along the shared edges. */
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

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

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

void test_teapot_data(void **state) {
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

void test_teapot_tolerances_and_cracks(void **state) {
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
