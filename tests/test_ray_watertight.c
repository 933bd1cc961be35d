/* Watertight ray–triangle intersection (surfaces/: ray.h): rays exactly through shared
 * vertices and edges of meshes never slip between triangles and never hit twice.
 *  - a tessellated sphere (star-shaped about every point within 0.5 of its centre): lines
 *    through a vertex or an edge point and an interior point cross it EXACTLY twice;
 *  - random planar fans: a line through the centre vertex (any valence) hits exactly once;
 *  - the tessellated, welded teapot: a ray through an interior vertex or edge point, from the
 *    side every incident triangle faces, hits exactly one triangle of the neighbourhood;
 *  - an integer grid with axis-aligned and dyadic-slope rays exactly through vertices and
 *    edge midpoints (edge functions exactly zero: the tie-break decides).
 * Origins are placed exactly at the aimed point with tmin = -inf, so the transformed point is
 * exactly the ray's: the edge functions there are exact zeros (vertices) or exact tiny values.
 * Counts are by brute force over the triangles (independent of any BVH). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh.h"
#include "casteljau/patchset.h"
#include "casteljau/quadric.h"
#include "casteljau/ray.h"
#include "casteljau/tessellate.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t seed;
static long total_rays;

static cj_vec3 vpos(const cj_mesh *m, uint32_t i) {
    return cj_v3(m->positions[3 * i], m->positions[3 * i + 1], m->positions[3 * i + 2]);
}

static int count_hits(const cj_mesh *m, const cj_ray *ray, const uint32_t *subset, size_t ns) {
    int hits = 0;
    cj_hit h;
    size_t n = subset ? ns : m->triangle_count;
    for (size_t k = 0; k < n; k++) {
        size_t t = subset ? subset[k] : k;
        const uint32_t *tri = m->triangles + 3 * t;
        hits += cj_ray_triangle(ray, vpos(m, tri[0]), vpos(m, tri[1]), vpos(m, tri[2]), &h);
    }
    return hits;
}

static cj_vec3 rand_in_ball(cj_rng *r, double rad) {
    for (;;) {
        cj_vec3 p = cj_v3(cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1));
        if (cj_v3_dot(p, p) <= 1.0) return cj_v3_scale(p, rad);
    }
}

static void test_sphere_lines(void **state) {
    (void)state;
    cj_quadric q;
    assert_int_equal(cj_quadric_ellipsoid(&q, 1.0, 1.0, 1.0), CJ_OK);
    cj_param_surface s;
    cj_quadric_surface(&q, &s);
    cj_mesh *m;
    assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
    assert_int_equal(cj_tessellate_surface(&s, 24, 12, 0, m, NULL), CJ_OK);
    assert_int_equal(cj_mesh_weld(m, NULL), CJ_OK);
    cj_rng r;
    cj_rng_init(&r, seed);
    long bad_miss = 0, bad_double = 0, n = 0;
    for (int i = 0; i < 30000; i++) {
        cj_vec3 p;
        if (i % 2 == 0) {
            p = vpos(m, (uint32_t)cj_rng_int(&r, 0, (int)m->vertex_count - 1));
        } else {
            size_t t = (size_t)cj_rng_int(&r, 0, (int)m->triangle_count - 1);
            int e = cj_rng_int(&r, 0, 2);
            cj_vec3 a = vpos(m, m->triangles[3 * t + e]),
                    b = vpos(m, m->triangles[3 * t + (e + 1) % 3]);
            double u = (i % 6 == 1) ? 0.5 : cj_rng_unit(&r);
            p = cj_v3_lerp(a, b, u);
        }
        cj_vec3 c = rand_in_ball(&r, 0.5);
        cj_ray ray = {p, cj_v3_sub(c, p), -INFINITY, INFINITY};
        int h = count_hits(m, &ray, NULL, 0);
        n++;
        if (h < 2) bad_miss++;
        if (h > 2) bad_double++;
    }
    total_rays += n;
    printf("  sphere (%zu triangles): %ld lines through vertices/edge points: %ld with a missed "
           "crossing, %ld with a double hit\n",
           m->triangle_count, n, bad_miss, bad_double);
    assert_int_equal(bad_miss, 0);
    assert_int_equal(bad_double, 0);
    cj_mesh_destroy(m);
}

static void test_fans(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 1);
    long bad = 0, n = 0;
    for (int f = 0; f < 2000; f++) {
        int k = cj_rng_int(&r, 3, 12);
        double ang[12];
        /* Sorted random angles with every gap below pi, so the fan surrounds its centre. */
        for (;;) {
            for (int i = 0; i < k; i++) ang[i] = cj_rng_range(&r, 0, 6.283185307179586);
            for (int i = 1; i < k; i++)
                for (int j = i; j > 0 && ang[j] < ang[j - 1]; j--) {
                    double s = ang[j];
                    ang[j] = ang[j - 1];
                    ang[j - 1] = s;
                }
            int ok = 1;
            for (int i = 0; i < k; i++) {
                double gap = (i + 1 < k ? ang[i + 1] : ang[0] + 6.283185307179586) - ang[i];
                if (gap >= 3.0) ok = 0;
            }
            if (ok) break;
        }
        /* The fan in a random plane through a random centre. */
        cj_vec3 c =
            cj_v3(cj_rng_range(&r, -10, 10), cj_rng_range(&r, -10, 10), cj_rng_range(&r, -10, 10));
        cj_vec3 nrm = cj_v3_normalize(rand_in_ball(&r, 1.0)), e1, e2;
        cj_frame_from_axis(nrm, &e1, &e2);
        cj_vec3 rim[12];
        for (int i = 0; i < k; i++) {
            double rad = cj_rng_range(&r, 0.1, 3.0);
            rim[i] = cj_v3_add(c, cj_v3_add(cj_v3_scale(e1, rad * cos(ang[i])),
                                            cj_v3_scale(e2, rad * sin(ang[i]))));
        }
        for (int j = 0; j < 10; j++) {
            cj_vec3 d = cj_v3_normalize(rand_in_ball(&r, 1.0));
            if (fabs(cj_v3_dot(d, nrm)) < 0.05) continue;
            /* Through the centre vertex (exact) or through a point of a spoke (rounded). */
            cj_vec3 p = c;
            if (j % 2) p = cj_v3_lerp(c, rim[cj_rng_int(&r, 0, k - 1)], cj_rng_range(&r, 0.0, 0.3));
            cj_ray ray = {p, d, -INFINITY, INFINITY};
            int h = 0;
            cj_hit hit;
            for (int i = 0; i < k; i++)
                h += cj_ray_triangle(&ray, c, rim[i], rim[(i + 1) % k], &hit);
            n++;
            if (h != 1) bad++;
        }
    }
    total_rays += n;
    printf("  planar fans (valence 3-12, random planes): %ld rays through the centre or a spoke, "
           "%ld not hitting exactly one triangle\n",
           n, bad);
    assert_int_equal(bad, 0);
}

typedef struct edge_rec {
    uint32_t a, b;
    uint32_t t;
} edge_rec;

static int edge_cmp(const void *x, const void *y) {
    const edge_rec *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return 0;
}

static void test_teapot_mesh(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    cj_mesh *m;
    assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
    cj_tess_options opt = {0};
    opt.tol = 2e-3;
    cj_tess_report rep;
    assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, m, &rep), CJ_OK);
    assert_int_equal(cj_mesh_weld(m, NULL), CJ_OK);
    size_t nt = m->triangle_count, nv = m->vertex_count;
    /* Edge use counts: vertices on an edge not shared by exactly two triangles are skipped. */
    edge_rec *edges = malloc(3 * nt * sizeof *edges);
    for (size_t t = 0; t < nt; t++)
        for (int e = 0; e < 3; e++) {
            uint32_t a = m->triangles[3 * t + e], b = m->triangles[3 * t + (e + 1) % 3];
            edges[3 * t + e] = (edge_rec){a < b ? a : b, a < b ? b : a, (uint32_t)t};
        }
    qsort(edges, 3 * nt, sizeof *edges, edge_cmp);
    unsigned char *bad_v = calloc(nv, 1);
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i;
        while (j < 3 * nt && edges[j].a == edges[i].a && edges[j].b == edges[i].b) j++;
        if (j - i != 2) bad_v[edges[i].a] = bad_v[edges[i].b] = 1;
        i = j;
    }
    /* One-ring: triangles per vertex (CSR). */
    uint32_t *start = calloc(nv + 1, sizeof *start), *ring = malloc(3 * nt * sizeof *ring);
    for (size_t t = 0; t < 3 * nt; t++) start[m->triangles[t] + 1]++;
    for (size_t v = 0; v < nv; v++) start[v + 1] += start[v];
    uint32_t *fill = calloc(nv, sizeof *fill);
    for (size_t t = 0; t < nt; t++)
        for (int e = 0; e < 3; e++) {
            uint32_t v = m->triangles[3 * t + e];
            ring[start[v] + fill[v]++] = (uint32_t)t;
        }
    cj_rng r;
    cj_rng_init(&r, seed + 2);
    long n_vert = 0, n_edge = 0, bad = 0;
    uint32_t sub[256];
    for (int it = 0; it < 60000 && n_vert + n_edge < 40000; it++) {
        size_t t = (size_t)cj_rng_int(&r, 0, (int)nt - 1);
        int e = cj_rng_int(&r, 0, 2);
        uint32_t a = m->triangles[3 * t + e], b = m->triangles[3 * t + (e + 1) % 3];
        int at_vertex = it % 2;
        if (bad_v[a] || (!at_vertex && bad_v[b])) continue;
        size_t ns = 0;
        for (uint32_t k = start[a]; k < start[a + 1] && ns < 256; k++) sub[ns++] = ring[k];
        if (!at_vertex)
            for (uint32_t k = start[b]; k < start[b + 1] && ns < 256; k++) sub[ns++] = ring[k];
        /* Deduplicate (the two rings share the edge's triangles). */
        for (size_t i = 0; i < ns; i++)
            for (size_t j = i + 1; j < ns;)
                if (sub[j] == sub[i])
                    sub[j] = sub[--ns];
                else
                    j++;
        /* A direction every triangle of the neighbourhood faces: the mean normal, jittered. */
        cj_vec3 nsum = cj_v3(0, 0, 0);
        for (size_t i = 0; i < ns; i++) {
            const uint32_t *tri = m->triangles + 3 * (size_t)sub[i];
            cj_vec3 p0 = vpos(m, tri[0]);
            cj_vec3 fn =
                cj_v3_cross(cj_v3_sub(vpos(m, tri[1]), p0), cj_v3_sub(vpos(m, tri[2]), p0));
            if (cj_v3_norm(fn) > 0) nsum = cj_v3_add(nsum, cj_v3_normalize(fn));
        }
        if (cj_v3_norm(nsum) == 0) continue;
        cj_vec3 d = cj_v3_add(cj_v3_normalize(nsum), rand_in_ball(&r, 0.4));
        int ok = 1;
        for (size_t i = 0; i < ns && ok; i++) {
            const uint32_t *tri = m->triangles + 3 * (size_t)sub[i];
            cj_vec3 p0 = vpos(m, tri[0]);
            cj_vec3 fn = cj_v3_normalize(
                cj_v3_cross(cj_v3_sub(vpos(m, tri[1]), p0), cj_v3_sub(vpos(m, tri[2]), p0)));
            if (cj_v3_dot(fn, cj_v3_normalize(d)) < 0.2) ok = 0;
        }
        if (!ok) continue;
        cj_vec3 p = at_vertex ? vpos(m, a) : cj_v3_lerp(vpos(m, a), vpos(m, b), cj_rng_unit(&r));
        cj_ray ray = {p, cj_v3_scale(d, -1.0), -INFINITY, INFINITY};
        int h = count_hits(m, &ray, sub, ns);
        if (at_vertex)
            n_vert++;
        else
            n_edge++;
        if (h != 1) bad++;
    }
    total_rays += n_vert + n_edge;
    printf("  teapot (%zu welded triangles): %ld rays through interior vertices (valence up to "
           "the lid's pole), %ld through edge points: %ld not hitting exactly one triangle of "
           "the neighbourhood\n",
           nt, n_vert, n_edge, bad);
    assert_true(n_vert + n_edge >= 30000);
    assert_int_equal(bad, 0);
    free(edges);
    free(bad_v);
    free(start);
    free(ring);
    free(fill);
    cj_mesh_destroy(m);
    cj_patchset_destroy(set);
}

/* Integer grid z = 0 (every cell split along an alternating diagonal): rays exactly through
 * vertices and edge midpoints, where edge functions are exact zeros. */
static void test_exact_grid(void **state) {
    (void)state;
    enum { N = 17 };
    cj_vec3 v[N][N];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) v[i][j] = cj_v3(i, j, 0.0);
    cj_rng r;
    cj_rng_init(&r, seed + 3);
    long bad = 0, n = 0;
    const double slopes[5] = {0.0, 0.25, -0.5, 0.125, 1.0};
    for (int it = 0; it < 12000; it++) {
        int i = cj_rng_int(&r, 2, N - 3), j = cj_rng_int(&r, 2, N - 3);
        double px = i, py = j;
        int kind = it % 4; /* vertex, horizontal edge, vertical edge, diagonal edge midpoint */
        if (kind == 1) px += 0.5;
        if (kind == 2) py += 0.5;
        if (kind == 3) {
            px += 0.5;
            py += 0.5;
        }
        cj_vec3 d = cj_v3(slopes[cj_rng_int(&r, 0, 4)], slopes[cj_rng_int(&r, 0, 4)],
                          it % 8 < 4 ? -1.0 : 1.0);
        cj_ray ray = {cj_v3(px, py, 0.0), d, -INFINITY, INFINITY};
        int h = 0;
        cj_hit hit;
        for (int a = 0; a + 1 < N; a++)
            for (int b = 0; b + 1 < N; b++) {
                if ((a + b) % 2 == 0) {
                    h += cj_ray_triangle(&ray, v[a][b], v[a + 1][b], v[a + 1][b + 1], &hit);
                    h += cj_ray_triangle(&ray, v[a][b], v[a + 1][b + 1], v[a][b + 1], &hit);
                } else {
                    h += cj_ray_triangle(&ray, v[a][b], v[a + 1][b], v[a][b + 1], &hit);
                    h += cj_ray_triangle(&ray, v[a + 1][b], v[a + 1][b + 1], v[a][b + 1], &hit);
                }
            }
        n++;
        if (h != 1) bad++;
    }
    total_rays += n;
    printf("  integer grid: %ld rays exactly through vertices and edge midpoints (exact-zero edge "
           "functions, dyadic slopes, both sides): %ld not hitting exactly one triangle\n",
           n, bad);
    assert_int_equal(bad, 0);
}

static int setup(void **state) {
    (void)state;
    seed = cj_test_seed("test_ray_watertight", 20261123);
    return 0;
}

static int teardown(void **state) {
    (void)state;
    printf("test_ray_watertight: %ld rays in total, 0 misses and 0 double hits\n", total_rays);
    return 0;
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_lines),
        cmocka_unit_test(test_fans),
        cmocka_unit_test(test_teapot_mesh),
        cmocka_unit_test(test_exact_grid),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
