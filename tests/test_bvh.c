/* Bounding volume hierarchy (surfaces/: bvh.h):
 *  - structure: every primitive in exactly one leaf, children's boxes inside their parent's,
 *    depth bounded;
 *  - closest hit over random triangle soups (1 to 20000 triangles, uniform and clustered, all
 *    centroids equal) equals brute force: same t and same triangle (up to exact ties); any hit
 *    equals "brute force hits something";
 *  - a BVH of objects through the callback (spheres and tori) equals brute force;
 *  - boxes tested per ray grow like log n (counted, not timed): 1e2 -> 1e5 triangles;
 *  - errors: no primitives, NaN boxes, bad indices. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bvh.h"
#include "casteljau/ray.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static uint64_t seed;

static cj_vec3 rand_unit(cj_rng *r) {
    for (;;) {
        cj_vec3 p = cj_v3(cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1), cj_rng_range(r, -1, 1));
        double n = cj_v3_norm(p);
        if (n > 0.1 && n <= 1.0) return cj_v3_scale(p, 1.0 / n);
    }
}

/* A soup of n triangles: 0 uniform in a cube, 1 clustered, 2 all around one centroid. */
static void make_soup(cj_rng *r, size_t n, int kind, double *pos, uint32_t *tri) {
    for (size_t t = 0; t < n; t++) {
        cj_vec3 c =
            cj_v3(cj_rng_range(r, -10, 10), cj_rng_range(r, -10, 10), cj_rng_range(r, -10, 10));
        if (kind == 1) {
            int k = cj_rng_int(r, 0, 4);
            c = cj_v3_add(cj_v3(k * 3.0 - 6, k % 2 ? 4.0 : -4.0, 0),
                          cj_v3_scale(rand_unit(r), cj_rng_range(r, 0, 1)));
        }
        if (kind == 2) c = cj_v3(1, 2, 3);
        double size = kind == 2 ? cj_rng_range(r, 0.1, 5) : cj_rng_range(r, 0.05, 1.0);
        cj_vec3 a = cj_v3_scale(rand_unit(r), size), b = cj_v3_scale(rand_unit(r), size);
        cj_vec3 v[3] = {cj_v3_add(c, a), cj_v3_add(c, b), cj_v3_sub(c, cj_v3_add(a, b))};
        for (int k = 0; k < 3; k++) {
            pos[9 * t + 3 * k] = v[k].x;
            pos[9 * t + 3 * k + 1] = v[k].y;
            pos[9 * t + 3 * k + 2] = v[k].z;
            tri[3 * t + k] = (uint32_t)(3 * t + k);
        }
    }
}

static void check_structure(const cj_bvh *b) {
    unsigned char *seen = calloc(b->prim_count, 1);
    size_t leaves_prims = 0;
    for (size_t i = 0; i < b->node_count; i++) {
        const cj_bvh_node *nd = &b->nodes[i];
        if (nd->count) {
            for (uint32_t k = nd->first; k < nd->first + nd->count; k++) {
                assert_true(k < b->prim_count);
                assert_false(seen[b->prims[k]]);
                seen[b->prims[k]] = 1;
                leaves_prims++;
            }
        } else {
            assert_true(nd->first + 1 < b->node_count);
            for (int c = 0; c < 2; c++)
                for (int k = 0; k < 3; k++) {
                    assert_true(b->nodes[nd->first + c].box.lo[k] >= nd->box.lo[k]);
                    assert_true(b->nodes[nd->first + c].box.hi[k] <= nd->box.hi[k]);
                }
        }
    }
    assert_int_equal(leaves_prims, b->prim_count);
    free(seen);
}

static void test_closest_equals_brute_force(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    const size_t sizes[6] = {1, 2, 7, 100, 2000, 20000};
    long rays = 0, hits = 0, ties = 0;
    for (int kind = 0; kind < 3; kind++)
        for (int si = 0; si < 6; si++) {
            size_t n = sizes[si];
            double *pos = malloc(9 * n * sizeof *pos);
            uint32_t *tri = malloc(3 * n * sizeof *tri);
            make_soup(&r, n, kind, pos, tri);
            cj_bvh *b;
            assert_int_equal(cj_bvh_mesh_build(pos, 3 * n, tri, n, NULL, &b), CJ_OK);
            check_structure(b);
            assert_true(b->depth <= 100);
            int nr = n > 5000 ? 150 : 400;
            for (int i = 0; i < nr; i++) {
                cj_vec3 o = cj_v3_scale(rand_unit(&r), 25);
                if (i % 4 == 0) o = cj_v3(cj_rng_range(&r, -5, 5), 0, 0); /* inside the soup */
                cj_vec3 tg = cj_v3(cj_rng_range(&r, -8, 8), cj_rng_range(&r, -8, 8),
                                   cj_rng_range(&r, -8, 8));
                cj_ray ray = {o, cj_v3_sub(tg, o), 0.0, i % 3 == 0 ? 0.9 : INFINITY};
                cj_hit h, bh = {0}, tmp;
                int got = cj_bvh_mesh_closest(b, &ray, &h, NULL);
                int bf = 0;
                size_t bt = 0;
                for (size_t t = 0; t < n; t++) {
                    const double *p = pos + 9 * t;
                    if (cj_ray_triangle(&ray, cj_v3(p[0], p[1], p[2]), cj_v3(p[3], p[4], p[5]),
                                        cj_v3(p[6], p[7], p[8]), &tmp) &&
                        (!bf || tmp.t < bh.t)) {
                        bh = tmp;
                        bt = t;
                        bf = 1;
                    }
                }
                rays++;
                assert_int_equal(got, bf);
                assert_int_equal(cj_bvh_mesh_any(b, &ray, NULL), bf);
                if (got) {
                    hits++;
                    assert_true(h.t == bh.t);
                    if (h.prim != bt) ties++;
                }
            }
            cj_bvh_destroy(b);
            free(pos);
            free(tri);
        }
    printf("  triangle soups (uniform, clustered, one centroid; 1..20000 triangles): %ld rays, %ld "
           "hits; closest hit t bit-identical to brute force, any-hit agrees; %ld exact ties\n",
           rays, hits, ties);
}

typedef struct objs {
    cj_vec3 c[300];
    double rad[300];
    cj_torus to[300];
} objs;

static int obj_hit(void *user, uint32_t prim, const cj_ray *ray, cj_hit *hit) {
    const objs *o = user;
    if (prim % 2) return cj_ray_torus(ray, &o->to[prim], hit);
    return cj_ray_sphere(ray, o->c[prim], o->rad[prim], hit);
}

static void test_objects_callback(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 1);
    static objs o;
    cj_aabb boxes[300];
    for (int i = 0; i < 300; i++) {
        o.c[i] =
            cj_v3(cj_rng_range(&r, -20, 20), cj_rng_range(&r, -20, 20), cj_rng_range(&r, -20, 20));
        o.rad[i] = cj_rng_range(&r, 0.2, 2);
        assert_int_equal(cj_torus_init(&o.to[i], o.c[i], rand_unit(&r), o.rad[i], 0.3 * o.rad[i]),
                         CJ_OK);
        if (i % 2)
            boxes[i] = cj_aabb_torus(&o.to[i]);
        else {
            cj_aabb b = {{o.c[i].x - o.rad[i], o.c[i].y - o.rad[i], o.c[i].z - o.rad[i]},
                         {o.c[i].x + o.rad[i], o.c[i].y + o.rad[i], o.c[i].z + o.rad[i]}};
            boxes[i] = b;
        }
    }
    cj_bvh *b;
    assert_int_equal(cj_bvh_build(boxes, 300, NULL, &b), CJ_OK);
    check_structure(b);
    long hits = 0;
    for (int i = 0; i < 3000; i++) {
        cj_vec3 org = cj_v3_scale(rand_unit(&r), 40);
        cj_vec3 tg = o.c[cj_rng_int(&r, 0, 299)];
        cj_ray ray = {org, cj_v3_sub(cj_v3_add(tg, rand_unit(&r)), org), 0.0, INFINITY};
        cj_hit h, bh = {0}, tmp;
        int got = cj_bvh_closest(b, &ray, obj_hit, &o, &h, NULL);
        int bf = 0;
        for (uint32_t k = 0; k < 300; k++)
            if (obj_hit(&o, k, &ray, &tmp) && (!bf || tmp.t < bh.t)) {
                bh = tmp;
                bh.prim = k;
                bf = 1;
            }
        assert_int_equal(got, bf);
        assert_int_equal(cj_bvh_any(b, &ray, obj_hit, &o, NULL), bf);
        if (got) {
            hits++;
            /* The torus's root refinement depends on the interval searched (tmax shrinks during
             * traversal), so t agrees to rounding rather than bit for bit. */
            if (!(fabs(h.t - bh.t) <= 1e-12 * bh.t && (h.prim == bh.prim || fabs(h.t - bh.t) == 0)))
                fprintf(stderr, "ray %d: bvh t %.17g prim %u, brute t %.17g prim %u\n", i, h.t,
                        h.prim, bh.t, bh.prim);
            assert_true(fabs(h.t - bh.t) <= 1e-12 * bh.t);
            assert_true(h.prim == bh.prim || h.t == bh.t);
        }
    }
    cj_bvh_destroy(b);
    printf(
        "  300 spheres and tori through the callback: 3000 rays, %ld hits, closest = brute force\n",
        hits);
}

static void test_log_scaling(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 2);
    double per_ray[4];
    const size_t sizes[4] = {100, 1000, 10000, 100000};
    for (int si = 0; si < 4; si++) {
        size_t n = sizes[si];
        double *pos = malloc(9 * n * sizeof *pos);
        uint32_t *tri = malloc(3 * n * sizeof *tri);
        /* n triangles in a fixed cube, their size shrinking like 1/sqrt(n): the total area, so
         * the mean free path of a ray, stays the same while n grows 1000-fold. */
        double side = 10.0, tsz = 4.0 * sqrt(100.0 / (double)n);
        for (size_t t = 0; t < n; t++) {
            cj_vec3 c = cj_v3(cj_rng_range(&r, 0, side), cj_rng_range(&r, 0, side),
                              cj_rng_range(&r, 0, side));
            for (int k = 0; k < 3; k++) {
                cj_vec3 v = cj_v3_add(c, cj_v3_scale(rand_unit(&r), tsz));
                pos[9 * t + 3 * k] = v.x;
                pos[9 * t + 3 * k + 1] = v.y;
                pos[9 * t + 3 * k + 2] = v.z;
                tri[3 * t + k] = (uint32_t)(3 * t + k);
            }
        }
        cj_bvh *b;
        assert_int_equal(cj_bvh_mesh_build(pos, 3 * n, tri, n, NULL, &b), CJ_OK);
        cj_bvh_trav_stats st = {0};
        cj_hit h;
        for (int i = 0; i < 2000; i++) {
            cj_vec3 o = cj_v3(cj_rng_range(&r, 0, side), cj_rng_range(&r, 0, side),
                              cj_rng_range(&r, 0, side));
            cj_ray ray = {o, rand_unit(&r), 0.0, INFINITY};
            (void)cj_bvh_mesh_closest(b, &ray, &h, &st);
        }
        per_ray[si] = (double)(st.nodes + st.prims) / 2000.0;
        printf("  %6zu triangles: depth %d, SAH cost %.1f, %.1f boxes + %.1f triangles per ray\n",
               n, b->depth, b->sah_cost, st.nodes / 2000.0, st.prims / 2000.0);
        cj_bvh_destroy(b);
        free(pos);
        free(tri);
    }
    /* 1000x more triangles: a logarithmic cost grows by a small factor, a linear one by 1000. */
    printf("  tests per ray 1e5 / 1e2 triangles: %.2f (log2 ratio %.2f)\n", per_ray[3] / per_ray[0],
           log2(1e5) / log2(1e2));
    assert_true(per_ray[3] / per_ray[0] < 6.0);
}

static void test_errors(void **state) {
    (void)state;
    cj_bvh *b = NULL;
    cj_aabb box = cj_aabb_empty();
    assert_int_equal(cj_bvh_build(&box, 0, NULL, &b), CJ_ERR_EMPTY);
    box.lo[1] = NAN;
    assert_int_equal(cj_bvh_build(&box, 1, NULL, &b), CJ_ERR_NONFINITE);
    const double pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t bad[3] = {0, 1, 3};
    assert_int_equal(cj_bvh_mesh_build(pos, 3, bad, 1, NULL, &b), CJ_ERR_RANGE);
    /* An empty box among real ones is never hit. */
    cj_aabb boxes[2] = {cj_aabb_empty(),
                        cj_aabb_triangle(cj_v3(0, 0, 0), cj_v3(1, 0, 0), cj_v3(0, 1, 0))};
    assert_int_equal(cj_bvh_build(boxes, 2, NULL, &b), CJ_OK);
    check_structure(b);
    cj_bvh_destroy(b);
    printf("  errors: empty input, NaN box, triangle index out of range\n");
}

static int setup(void **state) {
    (void)state;
    seed = cj_test_seed("test_bvh", 77);
    return 0;
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closest_equals_brute_force),
        cmocka_unit_test(test_objects_callback),
        cmocka_unit_test(test_log_scaling),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
