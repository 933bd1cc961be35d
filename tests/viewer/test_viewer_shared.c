/* Shared corners in the 3D editor (casteljau/viewer_scene.h): the teapot's patches keep their
 * own copies of shared corner and edge points; with linking on (the default) a move of one
 * moves the coincident ones, so after a seeded sequence of random moves every shared patch
 * edge still has identical control points and the tessellation is watertight (its only
 * boundary edges are the segments of the teapot's open edges, as test_tessellate counts them);
 * undo restores every point bit for bit. With linking off one move of a shared point opens a
 * seam, which the same check sees. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "casteljau/render.h"
#include "casteljau/tessellate.h"
#include "casteljau/viewer_scene.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The teapot's 32 patches as the one geometry of a scene, under a non-identity transform. */
static cj_vscene *teapot_scene(void) {
    cj_patchset *set = NULL;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = set->count;
    g.u.patches.patches = set->patches;
    int gi, mi, ni;
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cj_patchset_destroy(set);
    cj_material m = cj_material_defaults();
    assert_int_equal(cj_scene_add_material(s, &m, &mi), CJ_OK);
    cj_node n = cj_node_defaults(gi, mi);
    n.local.translate = cj_v3(0.5, -0.25, 0.125);
    n.local.scale = cj_v3(0.5, 0.5, 0.5);
    assert_int_equal(cj_scene_add_node(s, &n, &ni), CJ_OK);
    cj_vscene *vs = NULL;
    assert_int_equal(cj_vscene_create(s, &vs), CJ_OK);
    return vs;
}

static const cj_geometry *patches_of(cj_vscene *vs) {
    const cj_geometry *g = cj_scene_geometry(cj_vscene_scene(vs), 0);
    assert_int_equal(g->kind, CJ_GEOM_PATCHES);
    return g;
}

typedef struct edge {
    int degree, collapsed;
    double pts[4 * 3];
} edge;

static int same_edge(const edge *x, const edge *y) {
    if (x->degree != y->degree) return 0;
    int fwd = 1, rev = 1;
    for (int a = 0; a <= x->degree; ++a) {
        if (memcmp(x->pts + 3 * a, y->pts + 3 * a, 24)) fwd = 0;
        if (memcmp(x->pts + 3 * a, y->pts + 3 * (x->degree - a), 24)) rev = 0;
    }
    return fwd || rev;
}

typedef struct seam_check {
    int shared_pairs;   /* patch edges with an identical partner (the teapot has 52 pairs) */
    int mismatched;     /* shared pairs whose two sides got different mesh vertices (cracks) */
    size_t boundary;    /* boundary edges of the tessellation */
    size_t open_segs;   /* mesh segments along the edges without a partner */
    size_t nonmanifold; /* edges used by more than two triangles */
} seam_check;

static int cmp3(const void *a, const void *b) {
    const double *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* Positions of patch q's mesh vertices on side s (by their (u, v)), sorted; their number. */
static size_t side_positions(const cj_mesh *m, size_t q, int s, double *out) {
    size_t n = 0;
    for (size_t t = 0; t < m->triangle_count; ++t) {
        if ((size_t)m->triangle_patch[t] != q) continue;
        for (int k = 0; k < 3; ++k) {
            const size_t i = m->triangles[3 * t + k];
            const double *uv = m->uvs + 2 * i;
            const int on = (s == 0 && uv[1] == 0.0) || (s == 1 && uv[0] == 1.0) ||
                           (s == 2 && uv[1] == 1.0) || (s == 3 && uv[0] == 0.0);
            if (on) memcpy(out + 3 * n++, m->positions + 3 * i, 3 * sizeof(double));
        }
    }
    qsort(out, n, 3 * sizeof(double), cmp3);
    size_t u = 0; /* distinct positions */
    for (size_t i = 0; i < n; ++i)
        if (!u || cmp3(out + 3 * (u - 1), out + 3 * i)) memmove(out + 3 * u++, out + 3 * i, 24);
    return u;
}

/* Tessellates the patches at tol: cracks show as shared edges whose two sides carry different
 * vertices, or boundary edges beyond the segments of the open edges. */
static seam_check check_seams(const cj_geometry *g, double tol) {
    const size_t np = g->u.patches.count;
    edge *e = calloc(4 * np, sizeof *e);
    assert_non_null(e);
    for (size_t q = 0; q < np; ++q)
        for (int s = 0; s < 4; ++s) {
            edge *x = &e[4 * q + (size_t)s];
            assert_int_equal(cj_patch_boundary(&g->u.patches.patches[q], (cj_patch_edge)s, x->pts,
                                               NULL, &x->degree),
                             CJ_OK);
            x->collapsed = 1;
            for (int a = 1; a <= x->degree; ++a)
                if (memcmp(x->pts, x->pts + 3 * a, 24)) x->collapsed = 0;
        }
    cj_mesh *mesh = NULL;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {tol, 0, 0, 0};
    cj_tess_report rep;
    assert_int_equal(cj_tessellate_patches(g->u.patches.patches, np, &opt, mesh, &rep), CJ_OK);
    double *a = malloc(3 * sizeof(double) * mesh->vertex_count);
    double *b = malloc(3 * sizeof(double) * mesh->vertex_count);
    assert_non_null(a);
    assert_non_null(b);
    seam_check c = {0, 0, 0, 0, 0};
    for (size_t i = 0; i < 4 * np; ++i) {
        if (e[i].collapsed) continue;
        size_t partner = (size_t)-1;
        for (size_t j = 0; j < 4 * np && partner == (size_t)-1; ++j)
            if (j != i && !e[j].collapsed && same_edge(&e[i], &e[j])) partner = j;
        const size_t na = side_positions(mesh, i / 4, (int)(i % 4), a);
        if (partner == (size_t)-1) {
            c.open_segs += na - 1;
            continue;
        }
        if (partner < i) continue;
        ++c.shared_pairs;
        const size_t nb = side_positions(mesh, partner / 4, (int)(partner % 4), b);
        c.mismatched += na != nb || memcmp(a, b, 3 * na * sizeof(double)) != 0;
    }
    free(a);
    free(b);
    free(e);
    cj_mesh_topology topo;
    assert_int_equal(cj_mesh_topology_compute(mesh, &topo), CJ_OK);
    c.boundary = topo.boundary_edges;
    c.nonmanifold = topo.nonmanifold_edges;
    cj_mesh_destroy(mesh);
    return c;
}

/* All control points' local coordinates, for bitwise comparison. */
static double *points_copy(const cj_geometry *g) {
    double *p = malloc(g->u.patches.count * 16 * 3 * sizeof *p);
    assert_non_null(p);
    for (size_t q = 0; q < g->u.patches.count; ++q)
        memcpy(p + 48 * q, g->u.patches.patches[q].pts, 48 * sizeof *p);
    return p;
}

static void test_linked_moves_stay_watertight(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_viewer_shared", 19);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    cj_vscene *vs = teapot_scene();
    const cj_geometry *g = patches_of(vs);
    const double tol = 3e-3;
    const seam_check c0 = check_seams(g, tol);
    assert_int_equal(c0.shared_pairs, 52);
    assert_int_equal(c0.mismatched, 0);
    assert_int_equal(c0.boundary, c0.open_segs);
    double *start = points_copy(g);
    assert_int_equal(cj_vscene_linked(vs), 1);
    const size_t n = cj_vscene_point_count(vs);
    assert_int_equal(n, 512);
    /* a corner of four patches and an edge point of two exist in the teapot */
    size_t corners = 0, edges = 0, shared_moves = 0;
    for (size_t k = 0; k < n; ++k) {
        corners += cj_vscene_shared_count(vs, k) == 4;
        edges += cj_vscene_shared_count(vs, k) == 2;
    }
    assert_true(corners > 0 && edges > 0);
    enum { MOVES = 60 };
    for (int i = 0; i < MOVES; ++i) {
        /* half of the moves on shared points (corners or edge points), the rest anywhere */
        size_t k;
        do k = (size_t)cj_rng_int(&rng, 0, (int)n - 1);
        while (i % 2 == 0 && cj_vscene_shared_count(vs, k) < 2);
        shared_moves += cj_vscene_shared_count(vs, k) > 1;
        cj_vec3 w;
        assert_int_equal(cj_vscene_point(vs, k, &w), CJ_OK);
        w = cj_v3_add(w, cj_v3(cj_rng_range(&rng, -0.3, 0.3), cj_rng_range(&rng, -0.3, 0.3),
                               cj_rng_range(&rng, -0.3, 0.3)));
        assert_int_equal(cj_vscene_set_point(vs, k, w), CJ_OK);
        cj_vec3 now;
        cj_vscene_point(vs, k, &now);
        assert_true(cj_v3_norm(cj_v3_sub(now, w)) < 1e-12);
    }
    assert_int_equal(cj_vscene_undo_depth(vs), MOVES);
    const seam_check c1 = check_seams(g, tol);
    if (c1.shared_pairs != 52 || c1.mismatched || c1.boundary != c1.open_segs || c1.nonmanifold)
        fail_msg("seed %llu: after %d linked moves %d shared edge pairs (52), %d with different "
                 "vertices on their two sides, %zu boundary edges (%zu on the open edges), %zu "
                 "non-manifold",
                 (unsigned long long)seed, MOVES, c1.shared_pairs, c1.mismatched, c1.boundary,
                 c1.open_segs, c1.nonmanifold);
    /* undo all: every point bit-identical to the start */
    for (int i = 0; i < MOVES; ++i) assert_int_equal(cj_vscene_undo(vs), CJ_OK);
    double *back = points_copy(g);
    assert_memory_equal(back, start, 32 * 48 * sizeof *back);
    free(back);
    printf("seed %llu: %d random moves of teapot control points (%zu of them on points shared by "
           "2 or 4 patches; of the 512, %zu lie where 3 others lie and %zu where 1 other does), "
           "linking "
           "on: still 52 shared edge pairs with identical control points; tessellated at %g: "
           "each pair's two sides carry identical vertices, %zu boundary edges = the %zu "
           "segments of the open edges, 0 non-manifold (watertight); undo x%d restores all 512 "
           "points bit for bit\n",
           (unsigned long long)seed, MOVES, shared_moves, corners, edges, tol, c1.boundary,
           c1.open_segs, MOVES);

    /* linking off: one move of a shared corner opens the seam, and the check sees it */
    size_t k = 0;
    while (cj_vscene_shared_count(vs, k) != 4) ++k;
    cj_vscene_set_linked(vs, 0);
    assert_int_equal(cj_vscene_shared_count(vs, k), 1);
    cj_vec3 w;
    cj_vscene_point(vs, k, &w);
    assert_int_equal(cj_vscene_set_point(vs, k, cj_v3_add(w, cj_v3(0.1, 0.1, 0.1))), CJ_OK);
    const seam_check c2 = check_seams(g, tol);
    assert_true(c2.shared_pairs < 52);
    assert_true(c2.boundary > c0.boundary);
    printf("linking off: moving corner point %zu alone leaves %d of 52 shared edge pairs and "
           "%zu boundary edges (the intact teapot: %zu): the seam the check detects\n",
           k, c2.shared_pairs, c2.boundary, c0.boundary);
    free(start);
    cj_vscene_destroy(vs);
}

/* A drag of a linked point is one command, merged over its moves, and moves all copies. */
static void test_linked_drag_one_command(void **state) {
    (void)state;
    cj_vscene *vs = teapot_scene();
    const int W = 640, H = 480;
    size_t k = 0;
    while (cj_vscene_shared_count(vs, k) != 4) ++k;
    double q[3];
    int on_screen = cj_vscene_project(vs, k, W, H, q);
    assert_true(on_screen);
    cj_vscene_begin_drag(vs);
    for (int s = 1; s <= 5; ++s)
        assert_int_equal(cj_vscene_drag(vs, k, W, H, q[0], q[1], q[0] + 3.0 * s, q[1] + s, -1),
                         CJ_OK);
    cj_vscene_end_drag(vs);
    assert_int_equal(cj_vscene_undo_depth(vs), 1);
    cj_vec3 p;
    cj_vscene_point(vs, k, &p);
    size_t same = 0;
    for (size_t i = 0; i < cj_vscene_point_count(vs); ++i) {
        cj_vec3 r;
        cj_vscene_point(vs, i, &r);
        same += !memcmp(&r, &p, sizeof r);
    }
    assert_int_equal(same, 4);
    assert_int_equal(cj_vscene_undo(vs), CJ_OK);
    assert_int_equal(cj_vscene_undo_depth(vs), 0);
    assert_int_equal(cj_vscene_redo(vs), CJ_OK);
    cj_vec3 r;
    cj_vscene_point(vs, k, &r);
    assert_memory_equal(&r, &p, sizeof r);
    printf("a 5-move drag of corner point %zu (shared by 4 patches): one command, the 4 copies "
           "at the same place; undo and redo restore it\n",
           k);
    cj_vscene_destroy(vs);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linked_moves_stay_watertight),
        cmocka_unit_test(test_linked_drag_one_command),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
