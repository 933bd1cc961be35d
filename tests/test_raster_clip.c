/* raster/: depth, perspective-correct barycentrics and clipping of the triangle rasterizer,
 * against exact values computed in GMP rationals: the ray through a pixel centre,
 * {(x_ndc·w, y_ndc·w, z, w)} in clip space, meets the plane of the source triangle at
 * Σ λ_i P_i with Σ λ_i = 1, where λ = a × b / Σ(a × b), a_i = x_i − x_ndc w_i,
 * b_i = y_i − y_ndc w_i: λ are the exact perspective-correct barycentrics and
 * Σ λ_i z_i / Σ λ_i w_i the exact pseudodepth. Triangles crossing the eye plane, behind the
 * camera, across near and far, and beyond the guard band are covered exactly where the exact
 * visible part is (away from a 1/128-pixel band along its boundary), never wrapped. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/scene.h"
#include "raster_ref.h"
#include "rng.h"

#include <stdio.h>

static uint64_t g_seed;

/* Stated bounds (float storage of values in [−1, 1] is exact to 2^-25..2^-24; the double
 * set-up adds far less for the triangles drawn here). */
#define DEPTH_BOUND 0x1p-23
#define BARY_BOUND  0x1p-23

typedef struct exact {
    int inside; /* all λ >= 0, w > 0, z in [−1, 1] */
    double z, b1, b2, w;
} exact;

/* The exact ray–plane values at screen point (px, py) (pixels) of triangle P (clip, 3 × 4). */
static exact exact_at(double P[3][4], int W, int H, double px, double py) {
    mpq_t xn, yn, a[3], b[3], c[3], t, u, s, wq, zq;
    mpq_inits(xn, yn, t, u, s, wq, zq, NULL);
    for (int i = 0; i < 3; ++i) mpq_inits(a[i], b[i], c[i], NULL);
    mpq_set_d(t, px);
    mpq_set_d(u, (double)W);
    mpq_div(xn, t, u);
    mpq_add(xn, xn, xn);
    mpq_set_si(t, 1, 1);
    mpq_sub(xn, xn, t);
    mpq_set_d(t, py);
    mpq_set_d(u, (double)H);
    mpq_div(yn, t, u);
    mpq_add(yn, yn, yn);
    mpq_set_si(t, 1, 1);
    mpq_sub(yn, yn, t);
    for (int i = 0; i < 3; ++i) {
        mpq_set_d(t, P[i][3]);
        mpq_mul(u, xn, t);
        mpq_set_d(a[i], P[i][0]);
        mpq_sub(a[i], a[i], u);
        mpq_mul(u, yn, t);
        mpq_set_d(b[i], P[i][1]);
        mpq_sub(b[i], b[i], u);
    }
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        mpq_mul(t, a[j], b[k]);
        mpq_mul(u, a[k], b[j]);
        mpq_sub(c[i], t, u);
    }
    mpq_add(s, c[0], c[1]);
    mpq_add(s, s, c[2]);
    exact e;
    memset(&e, 0, sizeof e);
    if (mpq_sgn(s) == 0) { /* the ray is parallel to the plane: edge-on, nothing to see */
        e.inside = 0;
    } else {
        int neg = 0;
        for (int i = 0; i < 3; ++i) {
            mpq_div(c[i], c[i], s);
            neg |= mpq_sgn(c[i]) < 0;
        }
        mpq_set_ui(wq, 0, 1);
        mpq_set_ui(zq, 0, 1);
        for (int i = 0; i < 3; ++i) {
            mpq_set_d(t, P[i][3]);
            mpq_mul(t, t, c[i]);
            mpq_add(wq, wq, t);
            mpq_set_d(t, P[i][2]);
            mpq_mul(t, t, c[i]);
            mpq_add(zq, zq, t);
        }
        e.w = mpq_get_d(wq);
        if (mpq_sgn(wq) > 0) {
            mpq_div(zq, zq, wq);
            e.z = mpq_get_d(zq);
            mpq_set_si(t, -1, 1);
            mpq_set_si(u, 1, 1);
            e.inside = !neg && mpq_cmp(zq, t) >= 0 && mpq_cmp(zq, u) <= 0;
        }
        e.b1 = mpq_get_d(c[1]);
        e.b2 = mpq_get_d(c[2]);
    }
    mpq_clears(xn, yn, t, u, s, wq, zq, NULL);
    for (int i = 0; i < 3; ++i) mpq_clears(a[i], b[i], c[i], NULL);
    return e;
}

/* The same in double: only to find the centres within 1/128 pixel of the boundary of the
 * visible part (the band), where rounding is 10 orders of magnitude below the distance. */
static int inside_d(double P[3][4], int W, int H, double px, double py) {
    const double xn = 2 * px / W - 1, yn = 2 * py / H - 1;
    double a[3], b[3], c[3];
    for (int i = 0; i < 3; ++i) {
        a[i] = P[i][0] - xn * P[i][3];
        b[i] = P[i][1] - yn * P[i][3];
    }
    for (int i = 0; i < 3; ++i)
        c[i] = a[(i + 1) % 3] * b[(i + 2) % 3] - a[(i + 2) % 3] * b[(i + 1) % 3];
    const double s = c[0] + c[1] + c[2];
    if (s == 0) return 0;
    double w = 0, z = 0;
    for (int i = 0; i < 3; ++i) {
        if (c[i] / s < 0) return 0;
        w += c[i] / s * P[i][3];
        z += c[i] / s * P[i][2];
    }
    return w > 0 && z / w >= -1 && z / w <= 1;
}

/* Fragments of one run (spp 1), per pixel: hit count and the values of the last hit. */
typedef struct frags {
    int W, H;
    int *cnt;
    float *z, *b1, *b2;
} frags;

static void on_frag(void *u, int x, int y, int s, uint32_t tri, float z, float b1, float b2) {
    (void)s;
    (void)tri;
    frags *f = u;
    const size_t i = (size_t)y * f->W + x;
    f->cnt[i]++;
    f->z[i] = z;
    f->b1[i] = b1;
    f->b2[i] = b2;
}

typedef struct check {
    size_t covered, robust_in, robust_out, band, gaps, wraps, doubles;
    double dz, db;
} check;

/* Renders triangle P alone at spp 1 and checks every pixel centre: coverage where the exact
 * answer is the same at the centre and at the four points 1/128 pixel away (snapping moves an
 * edge by at most 2^-9 pixel·√2), depth and barycentrics at every covered centre. */
static void check_triangle(double P[3][4], int W, int H, check *ck) {
    const uint32_t tri[3] = {0, 1, 2};
    cj_raster_input in = {3, &P[0][0], 1, tri, W, H, 1};
    frags f = {W,
               H,
               calloc((size_t)W * H, sizeof(int)),
               calloc((size_t)W * H, sizeof(float)),
               calloc((size_t)W * H, sizeof(float)),
               calloc((size_t)W * H, sizeof(float))};
    assert_int_equal(rh_render(&in, 32, 1, NULL, on_frag, &f, NULL), CJ_OK);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = (size_t)y * W + x;
            const double px = x + 0.5, py = y + 0.5;
            const int c = f.cnt[i];
            const int in_d = inside_d(P, W, H, px, py);
            static const double d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            int same = 1;
            for (int k = 0; k < 4 && same; ++k)
                same = inside_d(P, W, H, px + d[k][0] / 128, py + d[k][1] / 128) == in_d;
            exact e;
            memset(&e, 0, sizeof e);
            if (c || in_d) e = exact_at(P, W, H, px, py);
            if (same) assert_int_equal(e.inside, in_d);
            ck->doubles += c > 1;
            if (!same)
                ck->band++;
            else if (e.inside) {
                ck->robust_in++;
                ck->gaps += c == 0;
            } else {
                ck->robust_out++;
                ck->wraps += c != 0;
            }
            if (c) {
                ck->covered++;
                assert_true(e.w > 0); /* never a point behind the eye */
                const double ze = e.z < -1 ? -1 : e.z > 1 ? 1 : e.z;
                ck->dz = fmax(ck->dz, fabs(f.z[i] - ze));
                ck->db = fmax(ck->db, fmax(fabs(f.b1[i] - e.b1), fabs(f.b2[i] - e.b2)));
            }
        }
    free(f.cnt);
    free(f.z);
    free(f.b1);
    free(f.b2);
}

static void to_clip(const cj_xform3 *M, const double p[3], double out[4]) {
    for (int r = 0; r < 4; ++r)
        out[r] = M->m[r][0] * p[0] + M->m[r][1] * p[1] + M->m[r][2] * p[2] + M->m[r][3];
}

static void test_depth_and_barycentrics(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed);
    check ck;
    memset(&ck, 0, sizeof ck);
    int tris = 0;
    for (int it = 0; it < 40; ++it) {
        const int W = cj_rng_int(&r, 24, 64), H = cj_rng_int(&r, 24, 64);
        cj_camera cam = cj_camera_defaults();
        cam.projection = it % 4 == 3 ? CJ_PROJ_ORTHOGRAPHIC : CJ_PROJ_PERSPECTIVE;
        cam.ortho_height = 3;
        cam.fov_y = cj_rng_range(&r, 0.3, 1.5);
        cam.near = -cj_rng_range(&r, 0.05, 1);
        cam.far = -cj_rng_range(&r, 20, 200);
        cj_xform3 M;
        assert_int_equal(cj_camera_world_to_clip(&cam, (double)W / H, &M), CJ_OK);
        double P[3][4];
        for (int k = 0; k < 3; ++k) {
            const double p[3] = {cj_rng_range(&r, -2, 2), cj_rng_range(&r, -2, 2),
                                 cj_rng_range(&r, -6, 3)};
            to_clip(&M, p, P[k]);
        }
        check_triangle(P, W, H, &ck);
        tris++;
    }
    printf("test_raster_clip: %d random triangles (perspective and orthographic, some cut by the "
           "near plane): %zu covered centres; vs exact: %zu gaps, %zu wraps, %zu double hits "
           "(%zu centres in the 1/128 px band); max |depth error| %.3g (bound %.3g), max "
           "|barycentric error| %.3g (bound %.3g)\n",
           tris, ck.covered, ck.gaps, ck.wraps, ck.doubles, ck.band, ck.dz, DEPTH_BOUND, ck.db,
           BARY_BOUND);
    assert_int_equal(ck.gaps + ck.wraps + ck.doubles, 0);
    assert_true(ck.covered > 1000);
    assert_true(ck.dz <= DEPTH_BOUND);
    assert_true(ck.db <= BARY_BOUND);
}

/* Camera at the origin looking down −z (clip = projection only). */
static void camera_clip(double near, double far, int W, int H, cj_xform3 *M) {
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 0, 0);
    cam.gaze = cj_v3(0, 0, -1);
    cam.near = near;
    cam.far = far;
    cam.fov_y = 1.2;
    assert_int_equal(cj_camera_world_to_clip(&cam, (double)W / H, M), CJ_OK);
}

static void test_clip_cases(void **state) {
    (void)state;
    const int W = 80, H = 60;
    cj_xform3 M;
    camera_clip(-0.5, -20, W, H, &M);
    static const struct {
        const char *name;
        double p[3][3];
        int expect_pixels; /* 1: some pixels drawn, 0: none */
    } cases[] = {
        {"crossing the eye plane", {{-1, -0.5, -3}, {1.5, -0.3, -2}, {0.2, 0.8, 2}}, 1},
        {"a vertex on the eye plane", {{-1, -1, -4}, {1, -0.5, -3}, {2, 1, 0}}, 1},
        {"behind the camera", {{-1, -1, 1}, {1, -1, 2}, {0, 1, 3}}, 0},
        {"across near and far", {{-0.3, -0.4, -0.1}, {0.5, -0.2, -40}, {-0.1, 0.6, -30}}, 1},
        {"beyond the guard band", {{-40000, -0.2, -0.51}, {30000, -0.3, -0.52}, {0, 0.5, -3}}, 1},
        {"edge-on through the eye", {{0, -1, -2}, {0, 1, -2}, {0, 0, 1}}, 0},
    };
    check total;
    memset(&total, 0, sizeof total);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        double P[3][4];
        for (int k = 0; k < 3; ++k) to_clip(&M, cases[c].p[k], P[k]);
        check ck;
        memset(&ck, 0, sizeof ck);
        check_triangle(P, W, H, &ck);
        const uint32_t tri[3] = {0, 1, 2};
        cj_raster_input in = {3, &P[0][0], 1, tri, W, H, 1};
        cj_raster_prep *prep;
        cj_raster_stats st;
        assert_int_equal(cj_raster_prepare(&in, 16, NULL, &prep, &st), CJ_OK);
        cj_raster_prep_destroy(prep);
        printf("test_raster_clip: %-24s: %4zu centres covered (%zu robustly inside, %zu band), "
               "%zu gaps, %zu wraps, clipped %d, rejected %d, pieces %d, depth err %.2g, bary "
               "err %.2g\n",
               cases[c].name, ck.covered, ck.robust_in, ck.band, ck.gaps, ck.wraps,
               (int)st.tris_clipped, (int)st.tris_rejected, (int)st.tris_setup, ck.dz, ck.db);
        assert_int_equal(ck.gaps + ck.wraps + ck.doubles, 0);
        assert_true(ck.dz <= DEPTH_BOUND);
        assert_true(ck.db <= BARY_BOUND);
        if (cases[c].expect_pixels) {
            assert_true(ck.robust_in > 20);
            assert_int_equal(st.tris_clipped, 1);
        } else {
            assert_int_equal(ck.covered, 0);
        }
    }
}

static void test_depth_order_and_forward(void **state) {
    (void)state;
    /* Two screen-filling triangles pairs in clip space (w = 1): A at z = 0.5, B at z = 0.2,
     * C equal to A. B drawn after A wins; C ties with A and loses. */
    const int W = 16, H = 12;
    double clip[3 * 4 * 3];
    const double zs[3] = {0.5, 0.2, 0.5};
    const double xy[4][2] = {{-1, -1}, {3, -1}, {-1, 3}, {0, 0}};
    for (int t = 0; t < 3; ++t)
        for (int k = 0; k < 3; ++k) {
            double *c = clip + 4 * (3 * t + k);
            c[0] = xy[k][0];
            c[1] = xy[k][1];
            c[2] = zs[t];
            c[3] = 1;
        }
    const uint32_t tris[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    cj_raster_input in = {9, clip, 3, tris, W, H, 4};
    cj_vis_sample *vis = malloc(sizeof *vis * W * H * 4);
    cj_raster_stats st;
    assert_int_equal(rh_render(&in, 8, 2, vis, NULL, NULL, &st), CJ_OK);
    for (int i = 0; i < W * H * 4; ++i) {
        assert_int_equal(vis[i].tri, 1);
        assert_true(vis[i].depth == 0.2f);
    }
    assert_int_equal(st.samples_written, 2 * W * H * 4); /* A everywhere, then B; C never */
    /* Nothing drawn: depth +1, no triangle. */
    cj_raster_input none = {9, clip, 0, tris, W, H, 16};
    cj_vis_sample *v16 = malloc(sizeof *v16 * W * H * 16);
    assert_int_equal(rh_render(&none, 8, 1, v16, NULL, NULL, NULL), CJ_OK);
    for (int i = 0; i < W * H * 16; ++i) {
        assert_int_equal(v16[i].tri, CJ_RASTER_NO_TRI);
        assert_true(v16[i].depth == 1.0f);
    }
    printf("test_raster_clip: depth test strictly-less in input order (later nearer wins, a tie "
           "keeps the earlier), empty frame is depth +1 / no triangle\n");
    free(vis);
    free(v16);
}

/* Counts drawn samples (one worker: the counter is not shared safely). */
static void count_drawn(void *u, const cj_tile *t) {
    const size_t n = (size_t)(t->x1 - t->x0) * (size_t)(t->y1 - t->y0) * (size_t)t->spp;
    for (size_t i = 0; i < n; ++i) *(size_t *)u += t->samples[i].tri != CJ_RASTER_NO_TRI;
}

/* cj_raster_prepare_again: a failed preparation leaves a prep that draws nothing, and the next
 * good one (other sizes, spp, tiles; more triangles than the prep had room for) draws what a
 * fresh prep draws. */
static void test_prepare_again(void **state) {
    (void)state;
    double clip[16] = {-1, -1, 0, 1, 1, -1, 0, 1, -1, 1, 0, 1, 1, 1, 0.5, 1};
    uint32_t tris[6] = {0, 1, 2, 2, 1, 3};
    cj_raster_input in = {4, clip, 1, tris, 8, 8, 1};
    cj_raster_prep *p = NULL, *fresh = NULL;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_OK);
    size_t drawn = 0;
    assert_int_equal(cj_raster_run(p, 1, count_drawn, &drawn, NULL, NULL), CJ_OK);
    assert_true(drawn >= 28 && drawn <= 36); /* the lower-left half, the diagonal's owner aside */
    clip[5] = NAN;
    assert_int_equal(cj_raster_prepare_again(p, &in, 8, NULL), CJ_ERR_NONFINITE);
    drawn = 0;
    assert_int_equal(cj_raster_run(p, 1, count_drawn, &drawn, NULL, NULL), CJ_OK);
    assert_int_equal(drawn, 0);
    clip[5] = -1;
    assert_int_equal(cj_raster_prepare_again(p, &in, 0, NULL), CJ_ERR_RANGE);
    drawn = 0;
    assert_int_equal(cj_raster_run(p, 1, count_drawn, &drawn, NULL, NULL), CJ_OK);
    assert_int_equal(drawn, 0);
    const int sizes[3][3] = {{37, 29, 4}, {200, 150, 16}, {5, 3, 1}}; /* W, H, spp */
    for (int k = 0; k < 3; ++k) {
        in.tri_count = 2;
        in.width = sizes[k][0];
        in.height = sizes[k][1];
        in.spp = sizes[k][2];
        cj_raster_stats sa, sf;
        assert_int_equal(cj_raster_prepare_again(p, &in, 16, &sa), CJ_OK);
        assert_int_equal(cj_raster_prepare(&in, 16, NULL, &fresh, &sf), CJ_OK);
        assert_int_equal(sa.tris_setup, sf.tris_setup);
        size_t a = 0, f = 0;
        assert_int_equal(cj_raster_run(p, 1, count_drawn, &a, NULL, NULL), CJ_OK);
        assert_int_equal(cj_raster_run(fresh, 1, count_drawn, &f, NULL, NULL), CJ_OK);
        assert_int_equal(a, f);
        assert_int_equal(a, (size_t)in.width * in.height * in.spp); /* the square, once */
        cj_raster_prep_destroy(fresh);
        fresh = NULL;
    }
    cj_raster_prep_destroy(p);
    printf("test_raster_clip: prepare_again after errors draws nothing; then 3 layouts drawn as "
           "by a fresh prep (each sample once)\n");
}

static void test_errors_and_pattern(void **state) {
    (void)state;
    double clip[12] = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1};
    uint32_t tri[3] = {0, 1, 2};
    cj_raster_input in = {3, clip, 1, tri, 8, 8, 1};
    cj_raster_prep *p = NULL;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_OK);
    int w, h, spp, ts;
    cj_raster_prep_layout(p, &w, &h, &spp, &ts);
    assert_true(w == 8 && h == 8 && spp == 1 && ts == 8);
    assert_int_equal(cj_raster_run(p, -1, NULL, NULL, NULL, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_raster_run(p, 0, NULL, NULL, NULL, NULL), CJ_OK);
    cj_raster_prep_destroy(p);
    p = NULL;
    assert_int_equal(cj_raster_prepare(&in, 0, NULL, &p, NULL), CJ_ERR_RANGE);
    in.spp = 2;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_ERR_RANGE);
    in.spp = 1;
    in.width = 0;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_ERR_RANGE);
    in.width = 8;
    tri[2] = 3;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_ERR_ARGUMENT);
    tri[2] = 2;
    clip[5] = NAN;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_ERR_NONFINITE);
    clip[5] = INFINITY;
    assert_int_equal(cj_raster_prepare(&in, 8, NULL, &p, NULL), CJ_ERR_NONFINITE);
    assert_null(p);
    /* Patterns: multiples of 1/256 inside the pixel; 16 samples with distinct x and y. */
    assert_null(cj_raster_sample_pattern(2));
    int64_t ox[16], oy[16];
    for (int n = 1; n <= 16; n *= 4) {
        assert_true(ref_pattern(n, ox, oy));
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < i; ++j) assert_true(ox[i] != ox[j] && oy[i] != oy[j]);
    }
    assert_true(ox[0] >= 0);
    printf("test_raster_clip: bad spp, sizes, tile size, thread count, vertex index, NaN/Inf "
           "refused; sample patterns on the 1/256 grid, rows and columns distinct\n");
}

int main(void) {
    g_seed = cj_test_seed("test_raster_clip", 20261123);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_depth_and_barycentrics),  cmocka_unit_test(test_clip_cases),
        cmocka_unit_test(test_depth_order_and_forward), cmocka_unit_test(test_errors_and_pattern),
        cmocka_unit_test(test_prepare_again),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
