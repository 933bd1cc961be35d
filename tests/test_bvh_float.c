/* The float BVH walk's two private pieces against exact oracles (surfaces/src/bvh_internal.h,
 * bvh_leaf_internal.h):
 *  - the float slab test of the 4-wide nodes (boxes rounded outward, directed origin rounding,
 *    padded entry/exit) never misses a box that the ray meets in exact rational arithmetic
 *    (GMP mpq): random boxes of several scales, rays aimed exactly at corners, edge points and
 *    face points (and one float step outside them), axis-parallel and nearly parallel
 *    directions, tmax exactly at the box. The same cases through a naive float test (origin
 *    rounded to nearest, no padding) do miss some, so the cases can catch a lost box;
 *  - the 4-lane triangle packet test gives, lane by lane, bit-identical answers (hit, t, edge
 *    values, their sum) to the scalar watertight test, on random triangles and on triangles
 *    through which the ray passes exactly along an edge or a vertex (edge values of zero);
 *  - the mesh BVH's array of nodes and packets is consistent (test_layout). */
#include "bvh_internal.h"
#include "bvh_leaf_internal.h"
#include "check.h"
#include "rng.h"

#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Exact: does o + t d, t in [tmin, tmax], meet the closed box [lo, hi]? Each slab gives an
 * interval of t (rational); the ray meets the box when the intersection is not empty. */
static int exact_hit(const double lo[3], const double hi[3], const double o[3], const double d[3],
                     double tmin, double tmax) {
    mpq_t a, b, t0, t1, x;
    mpq_inits(a, b, t0, t1, x, NULL);
    int lo_inf = isinf(tmin), hi_inf = isinf(tmax), hit = 1;
    if (!lo_inf) mpq_set_d(t0, tmin);
    if (!hi_inf) mpq_set_d(t1, tmax);
    for (int k = 0; k < 3 && hit; ++k) {
        if (d[k] == 0.0) {
            if (!(lo[k] <= o[k] && o[k] <= hi[k])) hit = 0;
            continue;
        }
        mpq_set_d(a, lo[k]);
        mpq_set_d(x, o[k]);
        mpq_sub(a, a, x);
        mpq_set_d(b, hi[k]);
        mpq_sub(b, b, x);
        mpq_set_d(x, d[k]);
        mpq_div(a, a, x);
        mpq_div(b, b, x);
        if (d[k] < 0) mpq_swap(a, b);
        if (lo_inf || mpq_cmp(a, t0) > 0) mpq_set(t0, a), lo_inf = 0;
        if (hi_inf || mpq_cmp(b, t1) < 0) mpq_set(t1, b), hi_inf = 0;
        if (!lo_inf && !hi_inf && mpq_cmp(t0, t1) > 0) hit = 0;
    }
    mpq_clears(a, b, t0, t1, x, NULL);
    return hit;
}

/* The naive float test the padding replaces: origin and bounds rounded to nearest, no margin. */
static int naive_hit(const double lo[3], const double hi[3], const double o[3], const double d[3],
                     double tmin, double tmax) {
    float vn = (float)tmin, vf = (float)tmax;
    for (int k = 0; k < 3; ++k) {
        const float inv = (float)(1.0 / d[k]), of = (float)o[k];
        float tn = ((float)lo[k] - of) * inv, tf = ((float)hi[k] - of) * inv;
        if (tn > tf) {
            const float s = tn;
            tn = tf;
            tf = s;
        }
        if (tn > vn) vn = tn;
        if (tf < vf) vf = tf;
    }
    return vn <= vf;
}

/* The box in slot `slot` of an otherwise empty wide node (every slot is exercised, so each SIMD
 * lane's arithmetic is). */
static int float_hit(const double lo[3], const double hi[3], const cj_ray *ray, int slot) {
    cj_bvhw_node n;
    memset(&n, 0, sizeof n);
    for (int i = 0; i < CJ_BVHW_W; ++i)
        for (int k = 0; k < 3; ++k) n.b[2 * k][i] = INFINITY, n.b[2 * k + 1][i] = -INFINITY;
    for (int k = 0; k < 3; ++k) {
        n.b[2 * k][slot] = cj_f32_down(lo[k]);
        n.b[2 * k + 1][slot] = cj_f32_up(hi[k]);
    }
    n.count = CJ_BVHW_W;
    n.valid = (1 << CJ_BVHW_W) - 1;
    cj_bvhw_ray r;
    cj_bvhw_ray_setup(ray, &r);
    float t0[CJ_BVHW_W];
    const int m = cj_bvhw_slab(&n, &r, cj_f32_down(ray->tmin), cj_f32_up(ray->tmax), t0);
    return m == (1 << slot) ? 1 : (m == 0 ? 0 : -1); /* -1: an empty slot reported met */
}

static double step_out(double x, double dir) {
    return nextafter(x, dir > 0 ? INFINITY : -INFINITY);
}

static void test_slab(uint64_t seed) {
    cj_rng rng;
    cj_rng_init(&rng, seed);
    long cases = 0, exact_hits = 0, lost = 0, naive_lost = 0, ghosts = 0;
    const double scales[4] = {1.0, 1e-3, 1e3, 1e7};
    for (int it = 0; it < 200000; ++it) {
        const double s = scales[it % 4];
        const double off = s * cj_rng_range(&rng, -100, 100);
        double lo[3], hi[3], o[3], d[3], p[3];
        for (int k = 0; k < 3; ++k) {
            const double a = off + s * cj_rng_range(&rng, -1, 1);
            const double w = (it % 7 == 0 && k == 1) ? 0.0 : s * cj_rng_range(&rng, 0, 1);
            lo[k] = a, hi[k] = a + w; /* flat boxes too */
            o[k] = off + s * cj_rng_range(&rng, -20, 20);
        }
        /* a target on the boundary: corner, edge point, face point, or a step outside it */
        const int kind = cj_rng_int(&rng, 0, 3);
        for (int k = 0; k < 3; ++k) {
            const int on_bound = kind == 0 || k < kind;
            p[k] = on_bound ? (cj_rng_int(&rng, 0, 1) ? lo[k] : hi[k])
                            : lo[k] + cj_rng_unit(&rng) * (hi[k] - lo[k]);
        }
        if (cj_rng_int(&rng, 0, 3) == 0) { /* one double step outside in a bound coordinate */
            const int k = cj_rng_int(&rng, 0, 2);
            p[k] = step_out(p[k], p[k] == lo[k] ? -1 : 1);
        }
        for (int k = 0; k < 3; ++k) d[k] = p[k] - o[k];
        const int par = cj_rng_int(&rng, 0, 5);
        if (par == 0) { /* parallel to an axis plane: origin coordinate on the target's */
            const int k = cj_rng_int(&rng, 0, 2);
            o[k] = p[k];
            d[k] = 0.0;
        } else if (par == 1) { /* nearly parallel */
            const int k = cj_rng_int(&rng, 0, 2);
            d[k] = s * 1e-12 * cj_rng_range(&rng, -1, 1);
        }
        if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) continue;
        double tmin = 0.0, tmax = INFINITY;
        const int tk = cj_rng_int(&rng, 0, 3);
        if (tk == 1) tmax = 1.0; /* the target exactly at tmax */
        if (tk == 2) tmin = 1.0; /* the target exactly at tmin */
        if (tk == 3) tmin = -INFINITY, tmax = cj_rng_range(&rng, -2, 2);
        const cj_ray ray = {cj_v3(o[0], o[1], o[2]), cj_v3(d[0], d[1], d[2]), tmin, tmax};
        const int ex = exact_hit(lo, hi, o, d, tmin, tmax);
        const int fh = float_hit(lo, hi, &ray, it % CJ_BVHW_W);
        ++cases;
        ghosts += fh < 0;
        if (!ex) continue;
        ++exact_hits;
        if (fh != 1) {
            if (++lost <= 5)
                fprintf(stderr, "lost box: o (%a %a %a) d (%a %a %a) box (%a %a %a)-(%a %a %a)\n",
                        o[0], o[1], o[2], d[0], d[1], d[2], lo[0], lo[1], lo[2], hi[0], hi[1],
                        hi[2]);
        }
        naive_lost += !naive_hit(lo, hi, o, d, tmin, tmax);
    }
    printf("float slab test (%d-wide nodes, the box in each slot in turn): %ld rays, %ld meet "
           "their box exactly; lost by the float test: %ld; empty slots reported met: %ld; lost "
           "by a naive float test: %ld\n",
           CJ_BVHW_W, cases, exact_hits, lost, ghosts, naive_lost);
    CHECK(lost == 0, "%ld boxes lost", lost);
    CHECK(ghosts == 0, "%ld empty slots reported met", ghosts);
    CHECK(naive_lost > 0, "the cases cannot tell a naive float test from a conservative one");
    CHECK(exact_hits > cases / 4, "too few hits (%ld of %ld) to test anything", exact_hits, cases);
}

/* Scalar watertight test against the packet test, lane by lane. */
static void test_packets(uint64_t seed) {
    cj_rng rng;
    cj_rng_init(&rng, seed);
    long lanes = 0, hits = 0, zero_lanes = 0, differ = 0;
    for (int it = 0; it < 50000; ++it) {
        double tri[36];
        cj_bvhw_tris p;
        const int grid = it % 2; /* integer grid: edge values of exactly zero */
        for (int l = 0; l < 4; ++l) {
            for (int r = 0; r < 9; ++r) {
                tri[9 * l + r] = grid ? (double)cj_rng_int(&rng, -3, 3) : cj_rng_range(&rng, -1, 1);
                p.v[r][l] = tri[9 * l + r];
            }
            p.idx[l] = (uint32_t)l;
        }
        const int unused = cj_rng_int(&rng, 0, 4); /* a lane left empty, as in a short leaf */
        if (unused < 4) {
            p.idx[unused] = UINT32_MAX;
            for (int r = 0; r < 9; ++r) p.v[r][unused] = NAN;
        }
        cj_ray ray;
        if (grid) { /* through grid points, along grid lines */
            ray.org = cj_v3(cj_rng_int(&rng, -3, 3), cj_rng_int(&rng, -3, 3), -10);
            ray.dir = cj_v3(cj_rng_int(&rng, -1, 1), cj_rng_int(&rng, -1, 1), 1);
        } else {
            ray.org = cj_v3(cj_rng_range(&rng, -1, 1), cj_rng_range(&rng, -1, 1), -5);
            ray.dir = cj_v3(cj_rng_range(&rng, -0.2, 0.2), cj_rng_range(&rng, -0.2, 0.2), 1);
        }
        ray.tmin = 0.0;
        ray.tmax = cj_rng_int(&rng, 0, 1) ? INFINITY : cj_rng_range(&rng, 0, 12);
        cj_ray_tri_pre pre;
        cj_ray_triangle_prepare(&ray, &pre);
        cj_bvhw_tri_hits th;
        cj_bvhw_tris_test(&p, &ray, &pre, &th);
        for (int l = 0; l < 4; ++l) {
            if (p.idx[l] == UINT32_MAX) {
                differ += (th.mask >> l) & 1;
                continue;
            }
            ++lanes;
            double t, e[3], det;
            const int got = cj_tri_core_v(&ray, &pre, tri + 9 * l, &t, e, &det);
            const int lane = (th.mask >> l) & 1;
            hits += got;
            const double ev[3] = {e[0], e[1], e[2]};
            if (got) zero_lanes += ev[0] == 0.0 || ev[1] == 0.0 || ev[2] == 0.0;
            int same = got == lane;
            if (same && got)
                same = !memcmp(&t, &th.t[l], 8) && !memcmp(&e[0], &th.e0[l], 8) &&
                       !memcmp(&e[1], &th.e1[l], 8) && !memcmp(&e[2], &th.e2[l], 8) &&
                       !memcmp(&det, &th.det[l], 8);
            differ += !same;
        }
    }
    printf("triangle packets: %ld lanes, %ld hits (%ld with an edge value of exactly zero), %ld "
           "differ from the scalar test bit for bit\n",
           lanes, hits, zero_lanes, differ);
    CHECK(differ == 0, "%ld lanes differ", differ);
    CHECK(zero_lanes > 100, "only %ld tie-break hits exercised", zero_lanes);
}

/* The mesh BVH's interleaved array (bvh_internal.h, cj_bvhw): walked depth first from line 0,
 * every node is reached once, its references stay inside the array, every child's float box
 * lies inside its parent's slot box, every leaf's lanes hold the vertices of the triangles the
 * index names and lie inside the slot's box, and each triangle sits in exactly one lane, except
 * those with two equal vertices, which are in none. */
static void test_layout(uint64_t seed) {
    cj_rng rng;
    cj_rng_init(&rng, seed);
    const size_t nt = 5000, nv = 3 * nt;
    double *pos = malloc(3 * nv * sizeof *pos);
    uint32_t *tri = malloc(3 * nt * sizeof *tri);
    unsigned char *seen = calloc(nt, 1);
    long degenerate = 0;
    for (size_t t = 0; t < nt; ++t) {
        const double c[3] = {cj_rng_range(&rng, -10, 10), cj_rng_range(&rng, -10, 10),
                             cj_rng_range(&rng, -10, 10)};
        for (int j = 0; j < 3; ++j) {
            for (int k = 0; k < 3; ++k) pos[9 * t + 3 * j + k] = c[k] + cj_rng_range(&rng, -1, 1);
            tri[3 * t + j] = (uint32_t)(3 * t + (size_t)j);
        }
        if (t % 50 == 0) { /* two equal vertices */
            memcpy(pos + 9 * t + 3, pos + 9 * t, 3 * sizeof *pos);
            ++degenerate;
        }
    }
    cj_bvh *b = NULL;
    CHECK(cj_bvh_mesh_build(pos, nv, tri, nt, NULL, &b) == CJ_OK, "mesh BVH build failed");
    const cj_bvhw *w = b->wide_;
    long bad = 0, nodes = 0, lanes = 0;
    /* pending: (line, slot box of its parent as 6 floats) */
    size_t cap = w->count + 1, n = 0;
    uint32_t *todo = malloc(cap * sizeof *todo);
    float *tbox = malloc(6 * cap * sizeof *tbox);
    todo[n] = 0;
    for (int k = 0; k < 3; ++k) tbox[6 * n + 2 * k] = -INFINITY, tbox[6 * n + 2 * k + 1] = INFINITY;
    ++n;
    while (n > 0 && bad == 0) {
        --n;
        const uint32_t line = todo[n];
        float pb[6];
        memcpy(pb, tbox + 6 * n, sizeof pb);
        if ((size_t)line + 4 > w->line_count) {
            ++bad;
            break;
        }
        const cj_bvhw_node *wn = (const cj_bvhw_node *)(const void *)(w->lines + 64 * (size_t)line);
        ++nodes;
        if (wn->count < 1 || wn->count > CJ_BVHW_W || wn->valid != (1 << wn->count) - 1) ++bad;
        for (int i = 0; i < wn->count && !bad; ++i) {
            float cb[6];
            for (int r = 0; r < 6; ++r) cb[r] = wn->b[r][i];
            for (int k = 0; k < 3; ++k) /* inside the parent's slot box */
                if (!(cb[2 * k] >= pb[2 * k] && cb[2 * k + 1] <= pb[2 * k + 1])) ++bad;
            if (wn->child[i] >= 0) {
                if (n >= cap) {
                    ++bad;
                    break;
                }
                todo[n] = (uint32_t)wn->child[i];
                memcpy(tbox + 6 * n, cb, sizeof cb);
                ++n;
                continue;
            }
            const size_t first = ~(uint32_t)wn->child[i], np = (wn->nprim[i] + 3u) / 4u;
            if (first + 5 * np > w->line_count) {
                ++bad;
                break;
            }
            const cj_bvhw_tris *pk = (const cj_bvhw_tris *)(const void *)(w->lines + 64 * first);
            for (size_t q = 0; q < np; ++q)
                for (int l = 0; l < 4; ++l) {
                    const uint32_t id = pk[q].idx[l];
                    if (id == UINT32_MAX) continue;
                    ++lanes;
                    if (id >= nt || seen[id]++) {
                        ++bad;
                        continue;
                    }
                    for (int r = 0; r < 9; ++r) {
                        const double v = pk[q].v[r][l], k = r % 3;
                        if (memcmp(&v, &pos[9 * id + (size_t)r], sizeof v)) ++bad;
                        if (!(v >= cb[2 * (int)k] && v <= cb[2 * (int)k + 1])) ++bad;
                    }
                }
        }
    }
    long missing = 0, present_degenerate = 0;
    for (size_t t = 0; t < nt; ++t) {
        if (t % 50 == 0)
            present_degenerate += seen[t] != 0;
        else
            missing += seen[t] == 0;
    }
    printf("mesh BVH layout: %zu triangles (%ld with two equal vertices), %ld wide nodes reached "
           "of %zu, %ld lanes; broken references, boxes or vertices: %ld; triangles missing: %ld; "
           "degenerate triangles stored: %ld\n",
           nt, degenerate, nodes, w->count, lanes, bad, missing, present_degenerate);
    CHECK(bad == 0, "%ld layout errors", bad);
    CHECK(nodes == (long)w->count, "%ld of %zu nodes reached", nodes, w->count);
    CHECK(missing == 0 && present_degenerate == 0, "%ld missing, %ld degenerate stored", missing,
          present_degenerate);
    CHECK(lanes == (long)(nt - (size_t)degenerate), "%ld lanes for %zu triangles", lanes,
          nt - (size_t)degenerate);
    cj_bvh_destroy(b);
    free(todo);
    free(tbox);
    free(seen);
    free(pos);
    free(tri);
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_bvh_float", 20261126u);
    test_slab(seed);
    test_packets(seed + 1);
    test_layout(seed + 2);
    return cj_check_exit();
}
