/* Cancelling the incremental tessellation (casteljau/tess_cache.h, CANCELLATION) and a cached
 * render's preparation (casteljau/render.h, PROGRESS AND CANCELLATION). A progress callback
 * that cancels at every k-th call: each cancelled update must return CJ_ERR_CANCELLED and append
 * nothing; repeating the update until it succeeds must give the mesh (and report) of a one-shot
 * tessellation bit for bit, with no patch planned or built twice (the cache kept the finished
 * work, and the entries the cancelled update had not reached). The same through random
 * control-point edits of the teapot and weight edits of a rational torus, and for the renderer:
 * a frame cancelled while it tessellates, then drawn, equals the one-shot render. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patchset.h"
#include "casteljau/tess_cache.h"
#include "casteljau/tessellate.h"
#include "render_test_util.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t seed;

typedef struct canceller {
    size_t calls, every, cancels;
    size_t last_done, last_total;
} canceller;

static int cancel_every(void *user, size_t done, size_t total) {
    canceller *c = user;
    assert_true(done < total);
    c->last_done = done;
    c->last_total = total;
    if (++c->calls % c->every == 0) {
        ++c->cancels;
        return 1;
    }
    return 0;
}

static void same_mesh(const cj_mesh *a, const cj_mesh *b) {
    assert_int_equal(a->vertex_count, b->vertex_count);
    assert_int_equal(a->triangle_count, b->triangle_count);
    const size_t nv = a->vertex_count, nt = a->triangle_count;
    assert_memory_equal(a->positions, b->positions, 3 * nv * sizeof(double));
    assert_memory_equal(a->normals, b->normals, 3 * nv * sizeof(double));
    assert_memory_equal(a->uvs, b->uvs, 2 * nv * sizeof(double));
    assert_memory_equal(a->triangles, b->triangles, 3 * nt * sizeof(uint32_t));
    assert_memory_equal(a->triangle_patch, b->triangle_patch, nt * sizeof(int32_t));
}

/* Updates until success, cancelling at every c->every-th step; checks each cancelled update
 * appended nothing. Returns the work summed over the attempts. */
static cj_tess_cache_stats update_with_cancels(cj_tess_cache *cache, const cj_patch *p, size_t n,
                                               const cj_tess_options *opt, cj_mesh *mesh,
                                               cj_tess_report *rep, canceller *c) {
    cj_tess_cache_stats sum = {0, 0, 0, 0};
    cj_tess_cache_set_progress(cache, cancel_every, c);
    for (int attempt = 0;; ++attempt) {
        assert_true(attempt < 1000);
        const size_t v0 = mesh->vertex_count, t0 = mesh->triangle_count;
        cj_tess_cache_stats w;
        const cj_status st = cj_tess_cache_update(cache, p, n, opt, mesh, rep, &w);
        sum.planned += w.planned;
        sum.built += w.built;
        if (st == CJ_OK) break;
        assert_int_equal(st, CJ_ERR_CANCELLED);
        assert_int_equal(mesh->vertex_count, v0);
        assert_int_equal(mesh->triangle_count, t0);
    }
    cj_tess_cache_set_progress(cache, NULL, NULL);
    return sum;
}

typedef struct model {
    size_t count;
    cj_patch p[32];
    double pts[32][16 * 3], w[32][16];
} model;

static void load_teapot(model *M, double *size) {
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    M->count = set->count;
    for (size_t q = 0; q < set->count; ++q) {
        memcpy(M->pts[q], set->patches[q].pts, 16 * 3 * sizeof(double));
        M->p[q] = cj_patch_view(3, 3, M->pts[q], NULL);
    }
    double lo[3], hi[3];
    assert_int_equal(cj_patchset_bbox(set, lo, hi, size), CJ_OK);
    cj_patchset_destroy(set);
}

/* Moves control point i of patch q and every coincident copy by d; returns the patches touched. */
static size_t move_point(model *M, size_t q, int i, const double d[3]) {
    const int np = (M->p[q].deg_u + 1) * (M->p[q].deg_v + 1);
    double at[3];
    memcpy(at, M->pts[q] + 3 * i, sizeof at);
    size_t touched = 0;
    for (size_t r = 0; r < M->count; ++r) {
        int hit = 0;
        for (int j = 0; j < np; ++j) {
            double *x = M->pts[r] + 3 * j;
            if (x[0] == at[0] && x[1] == at[1] && x[2] == at[2]) {
                for (int k = 0; k < 3; ++k) x[k] = at[k] + d[k];
                hit = 1;
            }
        }
        touched += (size_t)hit;
    }
    return touched;
}

/* Cold update of the teapot, cancelled at every k-th step for several k. */
static void test_cold_cancelled(void **state) {
    (void)state;
    static model M;
    double size;
    load_teapot(&M, &size);
    const cj_tess_options opt = {1e-3 * size, 0, 0, 0};
    cj_mesh *ref, *mesh;
    cj_tess_report rref, rep;
    assert_int_equal(cj_mesh_create(NULL, &ref), CJ_OK);
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    assert_int_equal(cj_tessellate_patches(M.p, M.count, &opt, ref, &rref), CJ_OK);
    const size_t every[] = {2, 3, 5, 7, 13, 40};
    for (size_t i = 0; i < sizeof every / sizeof every[0]; ++i) {
        cj_tess_cache *cache;
        assert_int_equal(cj_tess_cache_create(NULL, &cache), CJ_OK);
        canceller c = {0, every[i], 0, 0, 0};
        cj_mesh_clear(mesh);
        const cj_tess_cache_stats w =
            update_with_cancels(cache, M.p, M.count, &opt, mesh, &rep, &c);
        same_mesh(mesh, ref);
        assert_true(rep.bound == rref.bound && rep.triangles == rref.triangles);
        /* nothing planned or built twice: the cancelled updates' work was kept */
        assert_int_equal(w.planned, M.count);
        assert_int_equal(w.built, M.count);
        assert_int_equal(c.last_total, 2 * M.count);
        assert_true(c.cancels > 0);
        printf("teapot cold, cancelled at every %zu-th step: %zu cancels, then the mesh == "
               "one-shot (%zu triangles) bit for bit; %zu plans and %zu builds in all\n",
               every[i], c.cancels, mesh->triangle_count, w.planned, w.built);
        cj_tess_cache_destroy(cache);
    }
    cj_mesh_destroy(ref);
    cj_mesh_destroy(mesh);
}

/* Random edits, each update cancelled at every k-th step (k drawn per edit) before it finishes. */
static void edits_cancelled(model *M, double tol, double step, int edits, const char *what) {
    cj_rng rng;
    cj_rng_init(&rng, seed);
    cj_tess_cache *cache;
    assert_int_equal(cj_tess_cache_create(NULL, &cache), CJ_OK);
    cj_mesh *ref, *mesh;
    assert_int_equal(cj_mesh_create(NULL, &ref), CJ_OK);
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    const cj_tess_options opt = {tol, 0, 0, 0};
    cj_tess_report rep, rref;
    assert_int_equal(cj_tess_cache_update(cache, M->p, M->count, &opt, mesh, &rep, NULL), CJ_OK);
    size_t cancels = 0, planned = 0, touched_sum = 0;
    for (int e = 0; e < edits; ++e) {
        const size_t q = (size_t)cj_rng_int(&rng, 0, (int)M->count - 1);
        const int np = (M->p[q].deg_u + 1) * (M->p[q].deg_v + 1);
        const int i = cj_rng_int(&rng, 0, np - 1);
        size_t touched;
        if (M->p[q].weights && cj_rng_int(&rng, 0, 1)) {
            M->w[q][i] *= cj_rng_range(&rng, 0.8, 1.25);
            touched = 1;
        } else {
            const double d[3] = {cj_rng_range(&rng, -step, step), cj_rng_range(&rng, -step, step),
                                 cj_rng_range(&rng, -step, step)};
            touched = move_point(M, q, i, d);
        }
        canceller c = {0, (size_t)cj_rng_int(&rng, 1, 4), 0, 0, 0};
        if (c.every == 1) c.every = 2; /* every call cancelling would never finish */
        cj_mesh_clear(mesh);
        cj_mesh_clear(ref);
        const cj_tess_cache_stats w =
            update_with_cancels(cache, M->p, M->count, &opt, mesh, &rep, &c);
        assert_int_equal(cj_tessellate_patches(M->p, M->count, &opt, ref, &rref), CJ_OK);
        same_mesh(mesh, ref);
        assert_true(rep.bound == rref.bound && rep.triangles == rref.triangles &&
                    rep.dropped == rref.dropped);
        if (w.planned > touched)
            fail_msg("seed %llu %s edit %d: %zu plans for %zu patches edited (work lost to a "
                     "cancel)",
                     (unsigned long long)seed, what, e, w.planned, touched);
        cancels += c.cancels;
        planned += w.planned;
        touched_sum += touched;
    }
    printf("%s: %d random edits, each update cancelled at every k-th step (k in 2..4) and "
           "repeated: %zu cancels, every final mesh == one-shot bit for bit, %zu patches planned "
           "for %zu edited (none planned twice)\n",
           what, edits, cancels, planned, touched_sum);
    assert_true(cancels > 0);
    cj_mesh_destroy(ref);
    cj_mesh_destroy(mesh);
    cj_tess_cache_destroy(cache);
}

static void test_teapot_edits_cancelled(void **state) {
    (void)state;
    static model M;
    double size;
    load_teapot(&M, &size);
    edits_cancelled(&M, 2e-3 * size, 0.05 * size, 30, "teapot");
}

static void test_torus_edits_cancelled(void **state) {
    (void)state;
    static model M;
    static const double QC[3][2] = {{1, 0}, {1, 1}, {0, 1}};
    const double QW[3] = {1, sqrt(0.5), 1};
    M.count = 16;
    for (int k = 0; k < 16; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                double x = QC[i][0], y = QC[i][1], c = QC[j][0], s = QC[j][1];
                for (int r = 0; r < (k & 3); ++r) {
                    const double t = x;
                    x = -y;
                    y = t;
                }
                for (int r = 0; r < (k >> 2); ++r) {
                    const double t = c;
                    c = -s;
                    s = t;
                }
                const int q = j * 3 + i;
                M.pts[k][3 * q] = x * (2.0 + 0.5 * c);
                M.pts[k][3 * q + 1] = y * (2.0 + 0.5 * c);
                M.pts[k][3 * q + 2] = 0.5 * s;
                M.w[k][q] = QW[i] * QW[j];
                M.p[k] = cj_patch_view(2, 2, M.pts[k], M.w[k]);
            }
    edits_cancelled(&M, 8e-3, 0.1, 20, "rational torus");
}

/* The renderer: a frame whose callback cancels during preparation returns CJ_ERR_CANCELLED; a
 * frame after it equals the one-shot render. */
typedef struct frame_cancel {
    size_t preparing, tiles, cancel_at;
} frame_cancel;

static int on_progress(void *user, uint64_t done, uint64_t total) {
    frame_cancel *f = user;
    if (done == 0 && total == 0) return ++f->preparing == f->cancel_at;
    ++f->tiles;
    return 0;
}

static void test_render_cancelled(void **state) {
    (void)state;
    cj_scene *s = NULL;
    assert_int_equal(cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s), CJ_OK);
    cj_render_options o = cj_render_options_defaults();
    o.width = 160;
    o.height = 120;
    o.tol_px = 0.5;
    cj_render_options oc = o;
    assert_int_equal(cj_render_cache_create(NULL, &oc.cache), CJ_OK);
    frame_cancel f = {0, 0, 5};
    oc.progress = on_progress;
    oc.progress_user = &f;
    size_t cancelled = 0;
    cj_render_image *img = NULL;
    cj_stage_report rep;
    for (int attempt = 0; attempt < 100; ++attempt) {
        f.preparing = f.tiles = 0;
        const cj_status st = cj_render_raster(s, &oc, 0, NULL, &img, &rep);
        if (st == CJ_OK) break;
        assert_int_equal(st, CJ_ERR_CANCELLED);
        assert_null(img);
        assert_int_equal(f.tiles, 0); /* stopped before any tile */
        ++cancelled;
    }
    assert_non_null(img);
    cj_render_image *one_shot = render(s, &o, 0, NULL);
    assert_true(same_image(img, one_shot));
    printf("renderer with a cache, teapot 160x120: %zu frames cancelled at the 5th patch of "
           "their preparation, then a frame finished (%zu tiles): image == one-shot bit for "
           "bit\n",
           cancelled, f.tiles);
    assert_true(cancelled > 0);
    cj_render_image_destroy(img);
    cj_render_image_destroy(one_shot);
    cj_render_cache_destroy(oc.cache);
    cj_scene_destroy(s);
}

static double stage_value(const cj_stage_report *r, const char *key) {
    const cj_stage *s = cj_stage_report_find(r, "tessellate_patches");
    assert_non_null(s);
    for (int i = 0; i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    fail_msg("tessellate_patches has no value %s", key);
    return 0.0;
}

/* A frame within the tolerance band (the viewer's drag frames): the cache tessellated at 0.5 px,
 * the frame needs 0.8 px (kept at the cached tolerance) after a control point moved; cancelled
 * in its preparation, the next frame resumes at the band's tolerance: it plans only the edited
 * patch (a cancel used to forget the band, and the next frame re-planned every patch at the
 * exact needed tolerance). */
static void test_render_cancelled_in_band(void **state) {
    (void)state;
    cj_scene *s = NULL;
    assert_int_equal(cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s), CJ_OK);
    cj_scene_node_mut(s, 0)->overlay.flags = 0;
    cj_geometry *g = cj_scene_geometry_mut(s, cj_scene_node(s, 0)->geometry);
    assert_int_equal(g->kind, CJ_GEOM_PATCHES);
    const size_t np = g->u.patches.count;
    cj_render_options oc = cj_render_options_defaults();
    oc.width = 160;
    oc.height = 120;
    oc.tol_px = 0.5;
    assert_int_equal(cj_render_cache_create(NULL, &oc.cache), CJ_OK);
    cj_stage_report rep;
    cj_render_image_destroy(render(s, &oc, 0, &rep)); /* cold, at 0.5 px */
    assert_true(stage_value(&rep, "patches_planned") == (double)np);
    /* an interior point of patch 0 (moved alone: no other patch changes) */
    ((double *)g->u.patches.patches[0].pts)[3 * 5 + 2] += 0.05;
    oc.tol_px = 0.8;
    frame_cancel f = {0, 0, 1};
    oc.progress = on_progress;
    oc.progress_user = &f;
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_raster(s, &oc, 0, NULL, &img, &rep), CJ_ERR_CANCELLED);
    assert_null(img);
    oc.progress = NULL;
    cj_render_image_destroy(render(s, &oc, 0, &rep));
    const double planned = stage_value(&rep, "patches_planned");
    const double reused = stage_value(&rep, "patches_reused");
    if (planned != 1.0)
        fail_msg("the frame after a cancelled one in the band planned %g patches (reused %g): "
                 "want only the edited one",
                 planned, reused);
    printf("renderer with a cache, teapot 160x120 cached at 0.5 px: a frame needing 0.8 px after "
           "an edit, cancelled at its first patch, then the next frame: %g patch planned, %g "
           "reused (the band's tolerance kept across the cancel)\n",
           planned, reused);
    cj_render_cache_destroy(oc.cache);
    cj_scene_destroy(s);
}

int main(void) {
    seed = cj_test_seed("test_tess_cancel", 25);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cold_cancelled),
        cmocka_unit_test(test_teapot_edits_cancelled),
        cmocka_unit_test(test_torus_edits_cancelled),
        cmocka_unit_test(test_render_cancelled),
        cmocka_unit_test(test_render_cancelled_in_band),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
