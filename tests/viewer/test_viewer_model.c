/* The viewer's editor models without a window (casteljau/viewer_model.h, viewer_scene.h):
 * 10^4 random seeded edits undone and redone bit for bit, scripted drags that move exactly the
 * chosen point to the expected place, the exact pick comparison against 128-bit integer
 * arithmetic, the tie rule, save/load round trips, 3D drags on the camera plane and along an
 * axis, the elevation clamp of the orbit camera. */
#define _DEFAULT_SOURCE /* mkstemps */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/viewer_model.h"
#include "casteljau/viewer_scene.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Every bit of the document's geometry and style, for bitwise comparison. */
typedef struct snap {
    unsigned char *b;
    size_t n, cap;
} snap;

static void put(snap *s, const void *p, size_t n) {
    if (s->n + n > s->cap) {
        s->cap = 2 * (s->n + n) + 256;
        s->b = realloc(s->b, s->cap);
        assert_non_null(s->b);
    }
    memcpy(s->b + s->n, p, n);
    s->n += n;
}

static snap take(const cj_vdoc *d) {
    snap s = {NULL, 0, 0};
    const size_t nc = cj_vdoc_curve_count(d);
    put(&s, &nc, sizeof nc);
    for (size_t i = 0; i < nc; ++i) {
        const cj_vcurve *c = cj_vdoc_curve(d, i);
        cj_vcurve h = *c;
        h.pts = h.weights = NULL;
        put(&s, &h, sizeof h);
        put(&s, c->pts, 2 * c->count * sizeof(double));
        if (c->weights) put(&s, c->weights, c->count * sizeof(double));
    }
    return s;
}

static int same(const snap *a, const snap *b) {
    return a->n == b->n && !memcmp(a->b, b->b, a->n);
}

static cj_vdoc *three_curves(void) {
    cj_vdoc *d = NULL;
    assert_int_equal(cj_vdoc_create(&d), CJ_OK);
    const double cub[] = {0, 0, 1, 2.4, 3.2, 2.6, 4, 0.2};
    const double quad[] = {1, 0, 1, 1, 0, 1}, w[] = {1, 0.70710678118654757, 1};
    const double sp[] = {0, 0, 1, 1.6, 1.4, 1.7, 3, 0.2, 4, 1.8};
    cj_vcurve a = cj_vcurve_init(CJ_VCURVE_BEZIER, 4, cub, NULL);
    cj_vcurve b = cj_vcurve_init(CJ_VCURVE_RATIONAL, 3, quad, w);
    cj_vcurve c = cj_vcurve_init(CJ_VCURVE_SPLINE, 5, sp, NULL);
    assert_int_equal(cj_vdoc_add_curve(d, &a), CJ_OK);
    assert_int_equal(cj_vdoc_add_curve(d, &b), CJ_OK);
    assert_int_equal(cj_vdoc_add_curve(d, &c), CJ_OK);
    cj_vdoc_clear_log(d);
    return d;
}

static void test_random_edits_undo_redo(void **state) {
    (void)state;
    cj_rng r;
    const uint64_t seed = cj_test_seed("test_viewer_model/undo_redo", 1101);
    cj_rng_init(&r, seed);
    cj_vdoc *d = three_curves();
    snap start = take(d);
    size_t ok = 0, refused = 0, kinds[9] = {0};
    for (int e = 0; e < 10000; ++e) {
        const size_t nc = cj_vdoc_curve_count(d);
        const size_t ci = nc ? (size_t)cj_rng_int(&r, 0, (int)nc - 1) : 0;
        const cj_vcurve *c = cj_vdoc_curve(d, ci);
        const size_t np = c ? c->count : 0;
        const size_t pi = np ? (size_t)cj_rng_int(&r, 0, (int)np - 1) : 0;
        const int op = cj_rng_int(&r, 0, 8);
        const double x = cj_rng_range(&r, -5, 5), y = cj_rng_range(&r, -5, 5);
        snap before = take(d);
        cj_status st = CJ_OK;
        switch (op) {
        case 0:
            st = cj_vdoc_move_point(d, ci, pi, x, y);
            break;
        case 1: /* a drag: several moves, one command */
            cj_vdoc_begin_drag(d);
            for (int k = 0; k < 3 && !st; ++k) st = cj_vdoc_move_point(d, ci, pi, x + k, y - k);
            cj_vdoc_end_drag(d);
            break;
        case 2:
            st = np < 24 ? cj_vdoc_insert_point(d, ci, (size_t)cj_rng_int(&r, 0, (int)np), x, y)
                         : CJ_ERR_RANGE;
            break;
        case 3:
            st = cj_vdoc_delete_point(d, ci, pi);
            break;
        case 4:
            st = np < 24 ? cj_vdoc_elevate(d, ci) : CJ_ERR_RANGE;
            break;
        case 5:
            st = nc < 10 ? cj_vdoc_split(d, ci, cj_rng_unit(&r)) : CJ_ERR_RANGE;
            break;
        case 6:
            st = cj_vdoc_set_weight(d, ci, pi, cj_rng_range(&r, 0.1, 4));
            break;
        case 7:
            st = nc > 2 ? cj_vdoc_remove_curve(d, ci) : CJ_ERR_RANGE;
            break;
        default: {
            double p[6] = {x, y, y, x, x + 1, y + 1};
            cj_vcurve n = cj_vcurve_init(CJ_VCURVE_BEZIER, 3, p, NULL);
            st = nc < 10 ? cj_vdoc_add_curve(d, &n) : CJ_ERR_RANGE;
        }
        }
        if (st) {
            snap after = take(d);
            assert_true(same(&before, &after)); /* a refused edit changes nothing */
            free(after.b);
            ++refused;
        } else {
            ++ok;
            ++kinds[op];
        }
        free(before.b);
    }
    snap end = take(d);
    const size_t depth = cj_vdoc_undo_depth(d);
    assert_int_equal(depth, ok);
    for (size_t i = 0; i < depth; ++i) assert_int_equal(cj_vdoc_undo(d), CJ_OK);
    assert_int_equal(cj_vdoc_undo(d), CJ_ERR_EMPTY);
    snap back = take(d);
    assert_true(same(&start, &back));
    for (size_t i = 0; i < depth; ++i) assert_int_equal(cj_vdoc_redo(d), CJ_OK);
    assert_int_equal(cj_vdoc_redo(d), CJ_ERR_EMPTY);
    snap again = take(d);
    assert_true(same(&end, &again));
    printf("seed %llu: 10000 random edits (%zu applied: moves %zu, drags %zu, inserts %zu, "
           "deletes %zu, elevations %zu, splits %zu, weights %zu, removals %zu, additions %zu; "
           "%zu refused leaving the document bit-identical), undo all -> start bit-identical, "
           "redo all -> end bit-identical\n",
           (unsigned long long)seed, ok, kinds[0], kinds[1], kinds[2], kinds[3], kinds[4], kinds[5],
           kinds[6], kinds[7], kinds[8], refused);
    free(start.b);
    free(end.b);
    free(back.b);
    free(again.b);
    cj_vdoc_destroy(d);
}

static void test_scripted_drag_2d(void **state) {
    (void)state;
    cj_vdoc *d = three_curves();
    cj_vview v = {-0.5, -0.5, 4.5, 3.0, 800, 600};
    snap before = take(d);
    /* Press on point 2 of curve 0 and drag by (37, -12) pixels in 5 steps, as the viewer does:
     * the point's pixel position plus the cursor displacement, mapped back. */
    const cj_vcurve *c = cj_vdoc_curve(d, 0);
    double p0[2], px[2];
    cj_vview_to_px(&v, c->pts[4], c->pts[5], p0);
    size_t ci = 9, pi = 9;
    assert_true(cj_vdoc_pick(d, &v, p0[0] + 3.5, p0[1] - 2.5, 8.0, &ci, &pi));
    assert_int_equal(ci, 0);
    assert_int_equal(pi, 2);
    cj_vdoc_begin_drag(d);
    double expect[2] = {0, 0};
    for (int k = 1; k <= 5; ++k) {
        cj_vview_from_px(&v, p0[0] + 37.0 * k / 5, p0[1] - 12.0 * k / 5, px);
        assert_int_equal(cj_vdoc_move_point(d, 0, 2, px[0], px[1]), CJ_OK);
        expect[0] = px[0], expect[1] = px[1];
    }
    cj_vdoc_end_drag(d);
    assert_int_equal(cj_vdoc_undo_depth(d), 1); /* one command for the whole drag */
    c = cj_vdoc_curve(d, 0);
    assert_memory_equal(c->pts + 4, expect, sizeof expect);
    double q[2];
    cj_vview_to_px(&v, c->pts[4], c->pts[5], q);
    assert_true(fabs(q[0] - (p0[0] + 37)) < 1e-9 && fabs(q[1] - (p0[1] - 12)) < 1e-9);
    /* every other coordinate untouched */
    snap after = take(d);
    size_t diff = 0;
    for (size_t i = 0; i < after.n; ++i) diff += after.b[i] != before.b[i];
    assert_true(diff > 0 && diff <= 16);
    assert_int_equal(cj_vdoc_undo(d), CJ_OK);
    snap undone = take(d);
    assert_true(same(&before, &undone));
    printf("scripted 2D drag: point 2 of curve 0 picked 4.3 px away, dragged (37, -12) px in 5 "
           "moves = 1 command; lands at %.17g, %.17g (its pixel position moved by exactly the "
           "cursor's), %zu bytes of the document changed (only that point), undo restores it\n",
           expect[0], expect[1], diff);
    free(before.b);
    free(after.b);
    free(undone.b);
    cj_vdoc_destroy(d);
}

/* Exact oracle: integers scaled by a power of two, squared in 128-bit arithmetic. */
__extension__ typedef __int128 i128;

static void test_pick_exact_and_ties(void **state) {
    (void)state;
    cj_rng r;
    const uint64_t seed = cj_test_seed("test_viewer_model/pick", 1102);
    cj_rng_init(&r, seed);
    size_t naive_wrong = 0;
    for (int i = 0; i < 200000; ++i) {
        const int64_t base = (int64_t)(cj_rng_next(&r) >> 24); /* up to 2^40 */
        int64_t v[4];
        for (int k = 0; k < 4; ++k) v[k] = (k % 2 == 0 ? base : 0) + (int64_t)cj_rng_int(&r, -3, 3);
        const int sh = cj_rng_int(&r, 0, 60);
        double dv[4];
        for (int k = 0; k < 4; ++k) dv[k] = ldexp((double)v[k], -sh);
        i128 a = (i128)v[0] * v[0] + (i128)v[1] * v[1];
        i128 b = (i128)v[2] * v[2] + (i128)v[3] * v[3];
        const int want = a < b ? -1 : a > b;
        assert_int_equal(cj_vpick_compare(dv[0], dv[1], dv[2], dv[3]), want);
        const double na = dv[0] * dv[0] + dv[1] * dv[1], nb = dv[2] * dv[2] + dv[3] * dv[3];
        naive_wrong += (na < nb ? -1 : na > nb) != want;
    }
    /* Ties: two points mirrored about the cursor: the lower index wins, in both orders. */
    cj_vdoc *d = NULL;
    assert_int_equal(cj_vdoc_create(&d), CJ_OK);
    const double pts[] = {1, 0, 3, 0};
    cj_vcurve c = cj_vcurve_init(CJ_VCURVE_BEZIER, 2, pts, NULL);
    assert_int_equal(cj_vdoc_add_curve(d, &c), CJ_OK);
    cj_vview v = {0, -2, 4, 2, 400, 400};
    double a[2], b[2];
    cj_vview_to_px(&v, 1, 0, a);
    cj_vview_to_px(&v, 3, 0, b);
    size_t ci, pi;
    assert_true(cj_vdoc_pick(d, &v, 0.5 * (a[0] + b[0]), a[1], 1000, &ci, &pi));
    assert_int_equal(pi, 0);
    assert_int_equal(cj_vdoc_move_point(d, 0, 0, 3, 0), CJ_OK); /* coincident points */
    assert_true(cj_vdoc_pick(d, &v, b[0], b[1], 1, &ci, &pi));
    assert_int_equal(pi, 0);
    assert_false(cj_vdoc_pick(d, &v, b[0] + 5, b[1], 4.999, &ci, &pi));
    assert_true(cj_vdoc_pick(d, &v, b[0] + 5, b[1], 5, &ci, &pi)); /* the radius is inclusive */
    printf("seed %llu: 200000 squared-distance comparisons equal the 128-bit integer oracle "
           "(plain double arithmetic got %zu of them wrong); ties go to the lowest index; the "
           "pick radius is inclusive\n",
           (unsigned long long)seed, naive_wrong);
    cj_vdoc_destroy(d);
}

static void test_save_load_round_trip(void **state) {
    (void)state;
    cj_vdoc *d = three_curves();
    assert_int_equal(cj_vdoc_split(d, 0, 0.3), CJ_OK);
    assert_int_equal(cj_vdoc_elevate(d, 2), CJ_OK);
    cj_vview v = {-0.123456789, -1.0 / 3.0, 4.5, 3.0, 640, 480};
    cj_vdoc_display disp = {cj_rgba_make(250, 250, 240, 255), 1, 0.3, 1, 1};
    char path[] = "/tmp/cj_viewer_XXXXXX.json";
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(cj_vdoc_save_json(d, &v, &disp, path), CJ_OK);
    cj_vdoc *e = NULL;
    cj_vview w;
    cj_vdoc_display de;
    assert_int_equal(cj_vdoc_load_json(path, &e, &w, &de), CJ_OK);
    assert_memory_equal(&v, &w, sizeof v);
    assert_int_equal(cj_vdoc_curve_count(e), cj_vdoc_curve_count(d));
    for (size_t i = 0; i < cj_vdoc_curve_count(d); ++i) {
        const cj_vcurve *a = cj_vdoc_curve(d, i), *b = cj_vdoc_curve(e, i);
        assert_int_equal(a->kind, b->kind);
        assert_int_equal(a->count, b->count);
        assert_memory_equal(a->pts, b->pts, 2 * a->count * sizeof(double));
        if (a->weights) assert_memory_equal(a->weights, b->weights, a->count * sizeof(double));
    }
    assert_int_equal(de.curve, 1);
    assert_true(de.construction && de.t == 0.3);
    /* A failed save keeps the old file: a folder that does not exist. */
    assert_int_equal(cj_vdoc_save_json(d, &v, &disp, "/nonexistent-dir/x.json"), CJ_ERR_IO);
    /* Refusals name the file. */
    FILE *f = fopen(path, "w");
    fputs("{\"items\": [{\"type\": \"implicit\", \"circle\": [0, 0, 1]}]}", f);
    fclose(f);
    cj_vdoc *bad = NULL;
    assert_int_equal(cj_vdoc_load_json(path, &bad, &w, &de), CJ_ERR_PARSE);
    assert_non_null(strstr(cj_last_error(), path));
    unlink(path);
    printf("save -> load: %zu curves (Bezier, split halves, elevated rational, spline) and the "
           "view bit-identical; construction state kept; failed save -> CJ_ERR_IO; an implicit "
           "item is refused naming the file\n",
           cj_vdoc_curve_count(d));
    cj_vdoc_destroy(d);
    cj_vdoc_destroy(e);
}

static cj_vscene *one_patch_scene(void) {
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    double pts[48];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            double *p = pts + 3 * (4 * j + i);
            p[0] = i - 1.5, p[1] = j - 1.5, p[2] = 0.3 * ((i + j) % 2);
        }
    cj_patch pa = cj_patch_view(3, 3, pts, NULL);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = 1;
    g.u.patches.patches = &pa;
    int gi, mi, ni;
    cj_material m = cj_material_defaults();
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    assert_int_equal(cj_scene_add_material(s, &m, &mi), CJ_OK);
    cj_node n = cj_node_defaults(gi, mi);
    n.local.translate = cj_v3(0.25, 0, 0); /* a non-identity transform */
    assert_int_equal(cj_scene_add_node(s, &n, &ni), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(1, -6, 4);
    cam.gaze = cj_v3(-1, 6, -4);
    cam.up = cj_v3(0, 0, 1);
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    cj_vscene *vs = NULL;
    assert_int_equal(cj_vscene_create(s, &vs), CJ_OK);
    return vs;
}

static void test_scene_drags(void **state) {
    (void)state;
    cj_vscene *vs = one_patch_scene();
    const int W = 640, H = 480;
    assert_int_equal(cj_vscene_point_count(vs), 16);
    cj_vec3 before[16];
    for (size_t k = 0; k < 16; ++k) assert_int_equal(cj_vscene_point(vs, k, &before[k]), CJ_OK);
    double q0[3];
    assert_true(cj_vscene_project(vs, 5, W, H, q0));
    size_t k = 99;
    assert_true(cj_vscene_pick(vs, W, H, NULL, q0[0] + 1, q0[1] + 1, 6, &k));
    assert_int_equal(k, 5);
    /* Drag in the plane facing the camera: the point follows the cursor on screen. */
    cj_vscene_begin_drag(vs);
    for (int s = 1; s <= 4; ++s)
        assert_int_equal(
            cj_vscene_drag(vs, 5, W, H, q0[0], q0[1], q0[0] + 10.0 * s, q0[1] - 5.0 * s, -1),
            CJ_OK);
    cj_vscene_end_drag(vs);
    assert_int_equal(cj_vscene_undo_depth(vs), 1);
    double q1[3];
    assert_true(cj_vscene_project(vs, 5, W, H, q1));
    const double err = fmax(fabs(q1[0] - (q0[0] + 40)), fabs(q1[1] - (q0[1] - 20)));
    assert_true(err < 1e-6);
    cj_vec3 now, g = cj_v3_normalize(cj_scene_get_camera(cj_vscene_scene(vs))->gaze);
    assert_int_equal(cj_vscene_point(vs, 5, &now), CJ_OK);
    const double off_plane = fabs(cj_v3_dot(cj_v3_sub(now, before[5]), g));
    assert_true(off_plane < 1e-12);
    for (size_t i = 0; i < 16; ++i) {
        cj_vec3 p;
        cj_vscene_point(vs, i, &p);
        if (i != 5) assert_memory_equal(&p, &before[i], sizeof p);
    }
    /* Along the z axis: x and y stay bit-identical. */
    assert_int_equal(cj_vscene_drag(vs, 5, W, H, q1[0], q1[1], q1[0], q1[1] - 30, 2), CJ_OK);
    cj_vec3 z;
    cj_vscene_point(vs, 5, &z);
    assert_true(z.x == now.x && z.y == now.y && z.z != now.z);
    assert_int_equal(cj_vscene_undo(vs), CJ_OK);
    assert_int_equal(cj_vscene_undo(vs), CJ_OK);
    cj_vscene_point(vs, 5, &now);
    assert_memory_equal(&now, &before[5], sizeof now);
    assert_int_equal(cj_vscene_redo(vs), CJ_OK);
    /* The orbit clamps the elevation at 89 degrees. */
    assert_int_equal(cj_vscene_orbit(vs, 0, 1e6), CJ_OK);
    const cj_camera *cam = cj_scene_get_camera(cj_vscene_scene(vs));
    const double el = asin(-cj_v3_normalize(cam->gaze).z) * 180 / 3.14159265358979323846;
    assert_true(fabs(el - 89.0) < 1e-9);
    assert_int_equal(cj_scene_check(cj_vscene_scene(vs)), CJ_OK);
    printf("3D drag on the camera plane: the point's projection moved by the cursor's (40, -20) "
           "px within %.1e px, off the plane by %.1e, 15 other points bit-identical; an axis "
           "drag changes only z; undo x2 restores it bit for bit; orbit elevation clamped to "
           "89 deg (%.12f)\n",
           err, off_plane, el);
    cj_vscene_destroy(vs);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_edits_undo_redo),
        cmocka_unit_test(test_scripted_drag_2d),
        cmocka_unit_test(test_pick_exact_and_ties),
        cmocka_unit_test(test_save_load_round_trip),
        cmocka_unit_test(test_scene_drags),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
