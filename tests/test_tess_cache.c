/* The incremental tessellation cache (casteljau/tess_cache.h) against one-shot
 * cj_tessellate_patches: long seeded random edit sequences on the Utah teapot (32 bicubic
 * patches) and on an exact rational torus (16 biquadratic pieces). After every edit the cached
 * mesh and report must equal the from-scratch ones bit for bit; the work must be incremental
 * (only the edited patches re-planned; only they and neighbours whose shared side count changed
 * rebuilt); when the edit moves coincident control points together the mesh must stay crack
 * free (every mesh edge used by one triangle lies on an open side of its patch). Also: the
 * planner builds each teapot patch at most 1.1 times on average (issue 19's goal). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "casteljau/tess_cache.h"
#include "casteljau/tessellate.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SQRT1_2 0.70710678118654752440

static uint64_t seed;

/* A model the test edits: its patches own their arrays. */
typedef struct model {
    size_t count;
    cj_patch p[32];
    double pts[32][16 * 3], w[32][16];
} model;

static void same_mesh(const cj_mesh *a, const cj_mesh *b, const char *what, int step) {
    if (a->vertex_count != b->vertex_count || a->triangle_count != b->triangle_count)
        fail_msg("seed %llu %s step %d: cached %zu/%zu vertices/triangles, from scratch %zu/%zu",
                 (unsigned long long)seed, what, step, a->vertex_count, a->triangle_count,
                 b->vertex_count, b->triangle_count);
    const size_t nv = a->vertex_count, nt = a->triangle_count;
    assert_memory_equal(a->positions, b->positions, 3 * nv * sizeof(double));
    assert_memory_equal(a->normals, b->normals, 3 * nv * sizeof(double));
    assert_memory_equal(a->uvs, b->uvs, 2 * nv * sizeof(double));
    assert_memory_equal(a->triangles, b->triangles, 3 * nt * sizeof(uint32_t));
    assert_memory_equal(a->triangle_patch, b->triangle_patch, nt * sizeof(int32_t));
}

/* Control point index a (0..count-1) along side s (0: v=0, 1: u=1, 2: v=1, 3: u=0). */
static int side_index(const cj_patch *p, int s, int a) {
    const int m = p->deg_u;
    switch (s) {
    case 0:
        return a;
    case 1:
        return a * (m + 1) + m;
    case 2:
        return p->deg_v * (m + 1) + a;
    default:
        return a * (m + 1);
    }
}

static int same_cp(const cj_patch *p, int i, const cj_patch *r, int j) {
    const double *x = p->pts + 3 * i, *y = r->pts + 3 * j;
    const double wi = p->weights ? p->weights[i] : 1.0, wj = r->weights ? r->weights[j] : 1.0;
    return x[0] == y[0] && x[1] == y[1] && x[2] == y[2] && wi == wj;
}

/* open[4 q + s]: side s of patch q is shared by no other side (same control points, either
 * direction). */
static void open_sides(const model *M, int *open) {
    for (size_t q = 0; q < M->count; ++q)
        for (int s = 0; s < 4; ++s) {
            const cj_patch *p = &M->p[q];
            const int cnt = (s & 1 ? p->deg_v : p->deg_u) + 1;
            int shared = 0;
            for (size_t r = 0; r < M->count && !shared; ++r)
                for (int t = 0; t < 4 && !shared; ++t) {
                    if (r == q && t == s) continue;
                    const cj_patch *o = &M->p[r];
                    if ((t & 1 ? o->deg_v : o->deg_u) + 1 != cnt) continue;
                    int fw = 1, bw = 1;
                    for (int a = 0; a < cnt; ++a) {
                        fw &= same_cp(p, side_index(p, s, a), o, side_index(o, t, a));
                        bw &= same_cp(p, side_index(p, s, a), o, side_index(o, t, cnt - 1 - a));
                    }
                    shared = fw || bw;
                }
            open[4 * q + s] = !shared;
        }
}

typedef struct medge {
    double k[6]; /* the two end positions, smaller first */
    uint32_t t;
} medge;

static int cmp_medge(const void *x, const void *y) {
    const medge *a = x, *b = y;
    for (int i = 0; i < 6; ++i)
        if (a->k[i] != b->k[i]) return a->k[i] < b->k[i] ? -1 : 1;
    return 0;
}

/* Mesh edges (vertices identified by position) used by one triangle only that do not lie on an
 * open side of their patch: cracks. */
static size_t cracks(const cj_mesh *m, const int *open) {
    medge *e = malloc(sizeof *e * 3 * m->triangle_count + 1);
    assert_non_null(e);
    for (size_t t = 0; t < m->triangle_count; ++t)
        for (int c = 0; c < 3; ++c) {
            const double *a = m->positions + 3 * m->triangles[3 * t + c];
            const double *b = m->positions + 3 * m->triangles[3 * t + (c + 1) % 3];
            int swap = 0;
            for (int k = 0; k < 3 && !swap; ++k) {
                if (a[k] != b[k]) {
                    swap = b[k] < a[k];
                    break;
                }
            }
            if (swap) {
                const double *x = a;
                a = b;
                b = x;
            }
            medge *me = &e[3 * t + (size_t)c];
            memcpy(me->k, a, 3 * sizeof(double));
            memcpy(me->k + 3, b, 3 * sizeof(double));
            me->t = (uint32_t)(3 * t + (size_t)c);
        }
    const size_t ne = 3 * m->triangle_count;
    qsort(e, ne, sizeof *e, cmp_medge);
    size_t bad = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && cmp_medge(&e[i], &e[j]) == 0) ++j;
        if (j - i == 1) { /* a boundary edge: both (u,v) on one open side of its patch? */
            const size_t t = e[i].t / 3;
            const int c = (int)(e[i].t % 3);
            const double *ua = m->uvs + 2 * m->triangles[3 * t + (size_t)c];
            const double *ub = m->uvs + 2 * m->triangles[3 * t + (size_t)(c + 1) % 3];
            const int q = m->triangle_patch[t];
            const int on[4] = {ua[1] == 0.0 && ub[1] == 0.0, ua[0] == 1.0 && ub[0] == 1.0,
                               ua[1] == 1.0 && ub[1] == 1.0, ua[0] == 0.0 && ub[0] == 0.0};
            int ok = 0;
            for (int s = 0; s < 4; ++s) ok |= on[s] && open[4 * q + s];
            bad += !ok;
        }
        i = j;
    }
    free(e);
    return bad;
}

/* Whether control point i of patch q has a copy (same position and weight) in another patch. */
static int is_shared(const model *M, size_t q, int i) {
    const double *at = M->p[q].pts + 3 * i;
    const double wat = M->p[q].weights ? M->p[q].weights[i] : 1.0;
    for (size_t r = 0; r < M->count; ++r) {
        if (r == q) continue;
        const int np = (M->p[r].deg_u + 1) * (M->p[r].deg_v + 1);
        for (int j = 0; j < np; ++j) {
            const double *x = M->p[r].pts + 3 * j;
            const double wj = M->p[r].weights ? M->p[r].weights[j] : 1.0;
            if (x[0] == at[0] && x[1] == at[1] && x[2] == at[2] && wj == wat) return 1;
        }
    }
    return 0;
}

/* Moves control point i of patch q by d; with `together`, every control point of the model at
 * the same position (and weight) moves with it. Returns the number of patches touched. */
static int move_point(model *M, size_t q, int i, const double d[3], int together) {
    double at[3];
    memcpy(at, M->p[q].pts + 3 * i, sizeof at);
    const double wat = M->p[q].weights ? M->p[q].weights[i] : 1.0;
    int touched = 0;
    for (size_t r = 0; r < M->count; ++r) {
        int hit = 0;
        const int np = (M->p[r].deg_u + 1) * (M->p[r].deg_v + 1);
        for (int j = 0; j < np; ++j) {
            double *x = M->pts[r] + 3 * j;
            const double wj = M->p[r].weights ? M->p[r].weights[j] : 1.0;
            const int same = (r == q && j == i) || (together && x[0] == at[0] && x[1] == at[1] &&
                                                    x[2] == at[2] && wj == wat);
            if (!same) continue;
            for (int k = 0; k < 3; ++k) x[k] = at[k] + d[k];
            hit = 1;
        }
        touched += hit;
    }
    return touched;
}

/* n_steps random edits of M at tolerances tols[0..1]; checks as described above. */
static void edit_sequence(model *M, const double tols[2], int n_steps, double step_size,
                          const char *what) {
    cj_rng rng;
    cj_rng_init(&rng, seed);
    cj_tess_cache *cache = NULL;
    cj_mesh *a = NULL, *b = NULL;
    assert_int_equal(cj_tess_cache_create(NULL, &cache), CJ_OK);
    assert_int_equal(cj_mesh_create(NULL, &a), CJ_OK);
    assert_int_equal(cj_mesh_create(NULL, &b), CJ_OK);
    cj_tess_options opt = {tols[0], 0, 0, 0};
    cj_tess_report ra, rb;
    cj_tess_cache_stats st;
    assert_int_equal(cj_tess_cache_update(cache, M->p, M->count, &opt, a, &ra, &st), CJ_OK);
    assert_int_equal((int)st.planned, (int)M->count);
    assert_int_equal((int)st.built, (int)M->count);
    static int open[4 * 32];
    open_sides(M, open);
    assert_int_equal((int)cracks(a, open), 0);
    size_t cracked_unsealed = 0;
    size_t planned = 0, built = 0, reused = 0, crack_checks = 0, rebuilt_neighbours = 0;
    int tol_i = 0;
    for (int step = 0; step < n_steps; ++step) {
        const int kind = cj_rng_int(&rng, 0, 9);
        /* first half: the model stays sealed (a point or weight edited alone has no copy in
         * another patch); second half: seams may open */
        const int sealed = step < n_steps / 2;
        int edited = 0, together = 0;
        if (kind == 0) { /* tolerance change: everything re-planned */
            tol_i ^= 1;
            opt.tol = tols[tol_i];
            edited = (int)M->count;
        } else if (kind == 1 && M->p[0].weights) { /* a weight of one patch alone */
            const size_t q = (size_t)cj_rng_int(&rng, 0, (int)M->count - 1);
            const int np = (M->p[q].deg_u + 1) * (M->p[q].deg_v + 1);
            const int i = cj_rng_int(&rng, 0, np - 1);
            const double f = cj_rng_range(&rng, 0.7, 1.4);
            if (!sealed || !is_shared(M, q, i)) M->w[q][i] *= f;
            edited = 1;
        } else { /* a control point, with its coincident copies or alone */
            const size_t q = (size_t)cj_rng_int(&rng, 0, (int)M->count - 1);
            const int np = (M->p[q].deg_u + 1) * (M->p[q].deg_v + 1);
            const int i = cj_rng_int(&rng, 0, np - 1);
            const double d[3] = {cj_rng_range(&rng, -step_size, step_size),
                                 cj_rng_range(&rng, -step_size, step_size),
                                 cj_rng_range(&rng, -step_size, step_size)};
            together = kind >= 4 || (sealed && is_shared(M, q, i));
            edited = move_point(M, q, i, d, together);
        }
        cj_mesh_clear(a);
        cj_mesh_clear(b);
        assert_int_equal(cj_tess_cache_update(cache, M->p, M->count, &opt, a, &ra, &st), CJ_OK);
        assert_int_equal(cj_tessellate_patches(M->p, M->count, &opt, b, &rb), CJ_OK);
        same_mesh(a, b, what, step);
        assert_true(ra.bound == rb.bound && ra.triangles == rb.triangles &&
                    ra.vertices == rb.vertices && ra.dropped == rb.dropped &&
                    ra.max_nu == rb.max_nu && ra.max_nv == rb.max_nv);
        assert_true(ra.bound <= opt.tol);
        /* incremental: only the edited patches planned, the others' plans kept */
        if ((int)st.planned > edited)
            fail_msg("seed %llu %s step %d: %zu patches planned for %d edited",
                     (unsigned long long)seed, what, step, st.planned, edited);
        assert_int_equal((int)(st.planned + st.plans_reused), (int)M->count);
        assert_int_equal((int)(st.built + st.pieces_reused), (int)M->count);
        assert_true(st.built >= st.planned);
        rebuilt_neighbours += st.built - st.planned;
        planned += st.planned;
        built += st.built;
        reused += st.pieces_reused;
        if (!sealed && cracks(a, open)) ++cracked_unsealed; /* the check sees open seams */
        if (sealed) {
            const size_t bad = cracks(a, open);
            if (bad)
                fail_msg("seed %llu %s step %d (edit kind %d): %zu cracked edges",
                         (unsigned long long)seed, what, step, kind, bad);
            ++crack_checks;
        }
    }
    printf("%s: %d random edits (tol %g / %g, steps up to %g): cached mesh and report == one-shot "
           "bit for bit after every edit; %zu patches planned, %zu built (%zu of them neighbours "
           "whose shared side count changed), %zu pieces reused; %zu crack checks (every "
           "edge used once lies on an open side of its patch; cracks seen in %zu of "
           "the later, unsealed states: the check sees open seams)\n",
           what, n_steps, tols[0], tols[1], step_size, planned, built, rebuilt_neighbours, reused,
           crack_checks, cracked_unsealed);
    const cj_tess_cache_stats tot = cj_tess_cache_totals(cache);
    assert_int_equal((int)tot.planned, (int)(planned + M->count));
    cj_mesh_destroy(a);
    cj_mesh_destroy(b);
    cj_tess_cache_destroy(cache);
}

static void test_teapot_edits(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    static model M;
    M.count = set->count;
    for (size_t q = 0; q < set->count; ++q) {
        memcpy(M.pts[q], set->patches[q].pts, 16 * 3 * sizeof(double));
        M.p[q] = cj_patch_view(3, 3, M.pts[q], NULL);
    }
    double lo[3], hi[3], size;
    assert_int_equal(cj_patchset_bbox(set, lo, hi, &size), CJ_OK);
    cj_patchset_destroy(set);
    const double tols[2] = {2e-3 * size, 1e-3 * size};
    edit_sequence(&M, tols, 120, 0.05 * size, "teapot");
}

/* The planner builds each teapot patch once (bounds-only trials decide the grid): at most 1.1
 * builds per patch over a range of tolerances (the goal), and the report's bound holds. */
static void test_teapot_builds_per_patch(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    double lo[3], hi[3], size;
    assert_int_equal(cj_patchset_bbox(set, lo, hi, &size), CJ_OK);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    const double rel[4] = {1e-2, 1e-3, 1.25e-4, 1e-5};
    double worst = 0.0;
    for (int i = 0; i < 4; ++i) {
        cj_tess_options opt = {rel[i] * size, 0, 0, 0};
        cj_tess_report rep;
        cj_mesh_clear(mesh);
        assert_int_equal(cj_tessellate_patches(set->patches, set->count, &opt, mesh, &rep), CJ_OK);
        assert_true(rep.bound <= opt.tol);
        const double per = (double)rep.builds / (double)set->count;
        if (per > 1.1)
            fail_msg("teapot at %g of its size: %.3f builds per patch (goal <= 1.1)", rel[i], per);
        if (per > worst) worst = per;
        printf("teapot at %g of its size: %zu triangles, %.2f builds and %.2f bounds-only trials "
               "per patch\n",
               rel[i], rep.triangles, per, (double)rep.trials / (double)set->count);
    }
    printf("teapot: at most %.2f builds per patch (goal <= 1.1)\n", worst);
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
}

static const double QC[3][2] = {{1, 0}, {1, 1}, {0, 1}};
static const double QW[3] = {1, SQRT1_2, 1};

static void quarter_turn(int k, double x, double y, double *ox, double *oy) {
    for (int i = 0; i < (k & 3); ++i) {
        const double t = x;
        x = -y;
        y = t;
    }
    *ox = x;
    *oy = y;
}

static void test_torus_edits(void **state) {
    (void)state;
    static model M;
    M.count = 16;
    for (int k = 0; k < 16; ++k) {
        const int a = k % 4, b = k / 4;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                double x, y, cphi, sphi;
                quarter_turn(a, QC[i][0], QC[i][1], &x, &y);
                quarter_turn(b, QC[j][0], QC[j][1], &cphi, &sphi);
                const int q = j * 3 + i;
                M.pts[k][3 * q] = x * (2.0 + 0.5 * cphi);
                M.pts[k][3 * q + 1] = y * (2.0 + 0.5 * cphi);
                M.pts[k][3 * q + 2] = 0.5 * sphi;
                M.w[k][q] = QW[i] * QW[j];
            }
        M.p[k] = cj_patch_view(2, 2, M.pts[k], M.w[k]);
    }
    const double tols[2] = {8e-3, 4e-3};
    edit_sequence(&M, tols, 60, 0.1, "rational torus");
}

int main(void) {
    seed = cj_test_seed("test_tess_cache", 19);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot_builds_per_patch),
        cmocka_unit_test(test_teapot_edits),
        cmocka_unit_test(test_torus_edits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
