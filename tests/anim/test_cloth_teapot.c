/* The shipped cloth-on-teapot animation (scenes/anim_cloth_teapot.json): after every frame, no
 * cloth particle is inside the teapot by more than DEPTH_TOL. The teapot's surface is open: its
 * lid's edge (radius 1.3) rests inside the rim (radius 1.4), both in the plane z = 2.4 (world
 * y = 2.4), leaving a ring through which a cloth sinks into the pot. The closed body of the
 * test is the patches plus that flat ring, written here analytically (radii between 1.3 and 1.4
 * in the plane; the model's Bézier circles are within 3.5e-4 of the true ones). Inside = an odd
 * number of crossings of the vertical ray (+y) with the patches (at their world placement) and
 * the ring (the body is closed above by the lid; the handle and spout are closed tubes along a
 * vertical line); the depth of an inside particle is its certified distance to the nearest
 * patch (cj_patch_nearest) or to the ring. The simulation is the one `casteljau animate` runs. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/anim_json.h"
#include "casteljau/patch_nearest.h"
#include "casteljau/ray.h"
#include "casteljau/scene_json.h"
#include "casteljau/springs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEPTH_TOL 1e-3 /* world units; the teapot is about 6.4 wide, the cloth spacing 0.17 */

typedef struct world_patches {
    size_t count;
    cj_patch p[64];
    double pts[64][16 * 3];
} world_patches;

static void teapot_world(const cj_scene *s, world_patches *W) {
    int node = -1;
    for (size_t i = 0; i < cj_scene_node_count(s); ++i) {
        const char *nm = cj_scene_node(s, (int)i)->name;
        if (nm && !strcmp(nm, "teapot")) node = (int)i;
    }
    assert_true(node >= 0);
    const cj_geometry *g = cj_scene_geometry(s, cj_scene_node(s, node)->geometry);
    assert_int_equal(g->kind, CJ_GEOM_PATCHES);
    cj_xform3 world;
    assert_int_equal(cj_scene_node_world(s, node, &world), CJ_OK);
    W->count = g->u.patches.count;
    assert_true(W->count <= 64);
    for (size_t q = 0; q < W->count; ++q) {
        const cj_patch *p = &g->u.patches.patches[q];
        assert_true(p->deg_u == 3 && p->deg_v == 3 && !p->weights);
        assert_int_equal(cj_xform3_apply_points(&world, p->pts, 16, W->pts[q]), CJ_OK);
        W->p[q] = cj_patch_view(3, 3, W->pts[q], NULL);
    }
}

#define RING_Y  2.4
#define RING_R0 1.3
#define RING_R1 1.4

/* Crossings of the ray x + t (0,1,0), t > 0, with the patches and the ring. */
static int crossings(const world_patches *W, const double x[3]) {
    const double rad = hypot(x[0], x[2]);
    int n = x[1] < RING_Y && rad > RING_R0 && rad < RING_R1;
    for (size_t q = 0; q < W->count; ++q) {
        cj_ray ray;
        ray.org = cj_v3(x[0], x[1], x[2]);
        ray.dir = cj_v3(0.0, 1.0, 0.0);
        ray.tmin = 0.0;
        ray.tmax = 100.0;
        cj_hit h;
        for (int k = 0; k < 16 && cj_ray_patch(&ray, &W->p[q], 1e-9, &h, NULL); ++k) {
            ++n;
            ray.tmin = h.t + 1e-7;
        }
    }
    return n;
}

static double nearest(const world_patches *W, const double x[3]) {
    const double rad = hypot(x[0], x[2]);
    const double dr = rad < RING_R0 ? RING_R0 - rad : rad > RING_R1 ? rad - RING_R1 : 0.0;
    double best = hypot(x[1] - RING_Y, dr);
    for (size_t q = 0; q < W->count; ++q) {
        cj_patch_nearest_result r;
        assert_int_equal(cj_patch_nearest(&W->p[q], x, 1e-6, &r), CJ_OK);
        if (r.lower < best) best = r.lower;
    }
    return best;
}

static void test_cloth_stays_outside(void **state) {
    (void)state;
    cj_anim_doc *doc = NULL;
    assert_int_equal(cj_anim_doc_load(CJ_SCENES_DIR "/anim_cloth_teapot.json", &doc), CJ_OK);
    cj_scene *s = NULL;
    const cj_scene_json_options jo = {CJ_TEAPOT_PATH};
    const cj_status lst = cj_scene_load_json_with_options(doc->scene_path, &jo, NULL, &s);
    if (lst) fail_msg("%s: %s", doc->scene_path, cj_last_error());
    assert_int_equal(cj_anim_doc_attach(doc, s), CJ_OK);
    static world_patches W;
    teapot_world(s, &W);
    const size_t seals = cj_patch_collider_seals(doc->cloth_colliders[0]);
    printf("the cloth's collider seals %zu gaps between open sides (the lid's ring: 4)\n", seals);
    assert_int_equal(seals, 4);
    double worst = 0.0;
    long worst_frame = -1;
    size_t inside_total = 0, checked = 0;
    for (long f = doc->frame_first; f <= doc->frame_last; ++f) {
        assert_int_equal(cj_anim_doc_frame(doc, s, f, NULL), CJ_OK);
        const double *x = cj_springs_positions(doc->cloth);
        const size_t n = cj_springs_count(doc->cloth);
        size_t inside = 0;
        for (size_t i = 0; i < n; ++i) {
            ++checked;
            if (!(crossings(&W, x + 3 * i) & 1)) continue;
            const double d = nearest(&W, x + 3 * i);
            if (d > DEPTH_TOL) ++inside;
            if (getenv("CJ_CLOTH_DEBUG") && d > DEPTH_TOL && f == doc->frame_last) {
                size_t bq = 0;
                double bd = INFINITY;
                for (size_t q = 0; q < W.count; ++q) {
                    cj_patch_nearest_result r;
                    cj_patch_nearest(&W.p[q], x + 3 * i, 1e-6, &r);
                    if (r.lower < bd) {
                        bd = r.lower;
                        bq = q;
                    }
                }
                printf("  particle %zu at %.3f %.3f %.3f: depth %.3f, nearest patch %zu\n", i,
                       x[3 * i], x[3 * i + 1], x[3 * i + 2], d, bq);
            }
            if (d > worst) {
                worst = d;
                worst_frame = f;
            }
        }
        inside_total += inside;
        if (f % 8 == 0 || f == doc->frame_last)
            printf("frame %ld: %zu of %zu cloth particles inside the teapot by more than %g\n", f,
                   inside, n, DEPTH_TOL);
    }
    printf("cloth on the teapot, frames %d..%d: %zu particle positions checked, %zu inside by "
           "more than %g; deepest inside %.3g (frame %ld)\n",
           doc->frame_first, doc->frame_last, checked, inside_total, DEPTH_TOL, worst, worst_frame);
    assert_int_equal(inside_total, 0);
    cj_scene_destroy(s);
    cj_anim_doc_destroy(doc);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cloth_stays_outside),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
