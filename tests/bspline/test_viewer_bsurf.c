/* The 3D editor on B-spline / NURBS surfaces (casteljau/viewer_scene.h over scene_bspline.h):
 * the editable points of scenes/bsplines.json's surfaces are their B-spline nets; a move of
 * point (1, 1) of the bicubic sheet re-derives exactly the 4 patches of its support (the others
 * keep their bits), the incremental tessellation re-plans those 4 only, the patches equal a
 * fresh conversion of the edited net, undo/redo restore bit for bit, the save writes the edited
 * "bspline_surface", and the reloaded file renders to the same pixels as the edited scene. */
#include "casteljau/bspline_surface.h"
#include "casteljau/mesh.h"
#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/scene_bspline.h"
#include "casteljau/scene_json.h"
#include "casteljau/tess_cache.h"
#include "casteljau/viewer_scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++failures;                                                                            \
            printf("FAIL line %d: ", __LINE__);                                                    \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

/* The patch control points of geometry g, concatenated (all patches of one degree). */
static double *snapshot(const cj_geometry *g, size_t *len) {
    const size_t per = cj_patch_point_count(&g->u.patches.patches[0]);
    *len = 3 * per * g->u.patches.count;
    double *out = malloc(*len * sizeof(double));
    for (size_t k = 0; k < g->u.patches.count; ++k)
        memcpy(out + 3 * per * k, g->u.patches.patches[k].pts, 3 * per * sizeof(double));
    return out;
}

static int matches_conversion(const cj_geometry *g, const cj_bspline_surface *s) {
    int np = 0;
    if (cj_bspline_surface_patch_count(s, &np) || (size_t)np != g->u.patches.count) return 0;
    const size_t per = (size_t)(s->deg_u + 1) * (size_t)(s->deg_v + 1);
    double *pts = malloc(sizeof(double) * 3 * per * (size_t)np);
    int same = !cj_bspline_surface_to_patches(s, pts, NULL, NULL, NULL, np, NULL);
    for (int k = 0; same && k < np; ++k)
        same = !memcmp(g->u.patches.patches[k].pts, pts + 3 * per * (size_t)k,
                       3 * per * sizeof(double));
    free(pts);
    return same;
}

static size_t plan(cj_tess_cache *cache, const cj_geometry *g) {
    cj_mesh *mesh = NULL;
    cj_tess_options opt = {0.002, 0, 0, 0};
    cj_tess_cache_stats stats = {0, 0, 0, 0};
    cj_status st = cj_mesh_create(NULL, &mesh);
    if (!st)
        st = cj_tess_cache_update(cache, g->u.patches.patches, g->u.patches.count, &opt, mesh, NULL,
                                  &stats);
    CHECK(st == CJ_OK, "tessellation: %s", cj_last_error());
    cj_mesh_destroy(mesh);
    return stats.planned;
}

int main(void) {
    cj_scene *scene = NULL;
    cj_vscene *vs = NULL;
    cj_status st = cj_scene_load_json(CJ_SCENE_FILE, NULL, &scene);
    if (!st) st = cj_vscene_create(scene, &vs);
    CHECK(st == CJ_OK, "load %s: %s", CJ_SCENE_FILE, cj_last_error());
    if (st) return 1;
    cj_scene *s = cj_vscene_scene(vs);
    /* the bicubic sheet: its node and its first editable point */
    int gi = -1;
    size_t first = (size_t)-1, nsheet = 0;
    for (size_t k = 0; k < cj_vscene_point_count(vs); ++k) {
        const int node = cj_vscene_point_node(vs, k);
        const int g = cj_scene_node(s, node)->geometry;
        const cj_bspline_surface *b = cj_scene_geometry_bspline(s, g);
        if (!b || b->weights) continue;
        if (first == (size_t)-1) first = k;
        gi = g;
        ++nsheet;
    }
    const cj_bspline_surface *b = gi >= 0 ? cj_scene_geometry_bspline(s, gi) : NULL;
    CHECK(b && nsheet == (size_t)(b->npts_u * b->npts_v),
          "the sheet's editable points are its %d net points (got %zu)",
          b ? b->npts_u * b->npts_v : -1, nsheet);
    if (!b) return 1;
    const cj_geometry *g = cj_scene_geometry(s, gi);
    cj_tess_cache *cache = NULL;
    CHECK(!cj_tess_cache_create(NULL, &cache), "cache");
    const size_t planned0 = plan(cache, g);
    size_t len;
    double *before = snapshot(g, &len);
    const size_t k = first + (size_t)b->npts_u * 1 + 1; /* point (1, 1) */
    cj_vec3 w;
    CHECK(!cj_vscene_point(vs, k, &w), "point");
    w.y += 0.4;
    w.x -= 0.1;
    st = cj_vscene_set_point(vs, k, w);
    CHECK(st == CJ_OK, "move: %s", cj_last_error());
    double *after = snapshot(g, &len);
    const size_t per = 3 * 16;
    int changed = 0;
    for (size_t p = 0; p < g->u.patches.count; ++p)
        changed += memcmp(before + per * p, after + per * p, per * sizeof(double)) != 0;
    const int support = cj_scene_bspline_support(s, gi, 1, 1, NULL, 0);
    CHECK(changed == 4 && support == 4,
          "point (1,1) of the bicubic changed %d patches (support %d, "
          "want 4 of %zu)",
          changed, support, g->u.patches.count);
    CHECK(matches_conversion(g, b), "the patches differ from a conversion of the edited net");
    const size_t planned1 = plan(cache, g);
    CHECK(planned0 == g->u.patches.count && planned1 == (size_t)changed,
          "tessellation planned %zu patches at first, %zu after the move (want %d)", planned0,
          planned1, changed);
    /* undo / redo restore bit for bit */
    CHECK(!cj_vscene_undo(vs), "undo");
    double *undone = snapshot(g, &len);
    CHECK(!memcmp(undone, before, len * sizeof(double)), "undo does not restore the patches");
    CHECK(!cj_vscene_redo(vs), "redo");
    double *redone = snapshot(g, &len);
    CHECK(!memcmp(redone, after, len * sizeof(double)), "redo does not restore the move");
    /* a weight of the NURBS torus: net point (1, 0) lies on the seam row v = 0, which the last
     * row repeats, so with linking its copy (1, 8) changes too and the torus stays closed */
    int tg = -1;
    size_t tfirst = (size_t)-1;
    for (size_t q = 0; q < cj_vscene_point_count(vs) && tg < 0; ++q) {
        const int gq = cj_scene_node(s, cj_vscene_point_node(vs, q))->geometry;
        const cj_bspline_surface *tb = cj_scene_geometry_bspline(s, gq);
        if (tb && tb->weights) tg = gq, tfirst = q;
    }
    const cj_bspline_surface *tb = tg >= 0 ? cj_scene_geometry_bspline(s, tg) : NULL;
    int wchanged = -1, wsame = 0;
    double w0 = 0, wsheet = 0;
    CHECK(!cj_vscene_point_weight(vs, k, &wsheet) &&
              cj_vscene_set_weight(vs, k, 2.0) == CJ_ERR_ARGUMENT,
          "a polynomial sheet's point has no weight to set");
    if (tb) {
        const size_t kt = tfirst + 1, nt = (size_t)(tb->npts_u * tb->npts_v);
        const cj_geometry *tgeo = cj_scene_geometry(s, tg);
        const size_t np = tgeo->u.patches.count;
        double *tb0 = malloc(nt * sizeof(double)), *pw0 = malloc(9 * np * sizeof(double));
        memcpy(tb0, tb->weights, nt * sizeof(double));
        for (size_t p = 0; p < np; ++p)
            memcpy(pw0 + 9 * p, tgeo->u.patches.patches[p].weights, 9 * sizeof(double));
        CHECK(cj_vscene_point_weight(vs, kt, &w0), "torus point has a weight");
        st = cj_vscene_set_weight(vs, kt, w0 * 1.25);
        CHECK(st == CJ_OK, "weight: %s", cj_last_error());
        const size_t last = (size_t)(tb->npts_v - 1) * (size_t)tb->npts_u + 1;
        wsame = tb->weights[1] == w0 * 1.25 && tb->weights[last] == w0 * 1.25;
        CHECK(wsame, "the seam copies' weights: %.17g and %.17g (want %.17g)", tb->weights[1],
              tb->weights[last], w0 * 1.25);
        wchanged = 0;
        for (size_t p = 0; p < np; ++p)
            wchanged +=
                memcmp(pw0 + 9 * p, tgeo->u.patches.patches[p].weights, 9 * sizeof(double)) != 0;
        const int s1 = cj_scene_bspline_support(s, tg, 1, 0, NULL, 0);
        const int s2 = cj_scene_bspline_support(s, tg, 1, tb->npts_v - 1, NULL, 0);
        CHECK(wchanged == s1 + s2 && wchanged == 2,
              "the weight changed %d torus patches (supports %d + %d, want 2)", wchanged, s1, s2);
        int stale = -1;
        CHECK(cj_scene_bspline_refresh(s, tg, NULL, 0, &stale) == CJ_OK && stale == 0,
              "the torus patches were not up to date after the weight change (%d)", stale);
        CHECK(!cj_vscene_undo(vs), "undo weight");
        CHECK(!memcmp(tb0, tb->weights, nt * sizeof(double)), "undo does not restore weights");
        CHECK(!cj_vscene_redo(vs), "redo weight");
        free(tb0);
        free(pw0);
    }
    CHECK(tb != NULL, "no NURBS surface in the scene");
    /* save, reload: the same net; the same pixels */
    const char *file = "test_viewer_bsurf.json";
    st = cj_scene_save_json(s, file);
    cj_scene *re = NULL;
    if (!st) st = cj_scene_load_json(file, NULL, &re);
    CHECK(st == CJ_OK, "save/reload: %s", cj_last_error());
    long differ = -1;
    if (!st) {
        const cj_bspline_surface *rb = cj_scene_geometry_bspline(re, gi);
        CHECK(rb && !memcmp(rb->pts, b->pts, 3 * sizeof(double) * (size_t)(b->npts_u * b->npts_v)),
              "the reloaded sheet's net differs from the edited one");
        cj_render_options ro = cj_render_options_defaults();
        ro.width = 200;
        ro.height = 120;
        cj_render_image *i1 = NULL, *i2 = NULL;
        st = cj_render_raster(s, &ro, 0, NULL, &i1, NULL);
        if (!st) st = cj_render_raster(re, &ro, 0, NULL, &i2, NULL);
        CHECK(st == CJ_OK, "render: %s", cj_last_error());
        if (!st) {
            differ = 0;
            for (size_t q = 0; q < 4u * 200u * 120u; ++q) differ += i1->rgba[q] != i2->rgba[q];
        }
        CHECK(differ == 0, "%ld colour values differ between the edited and the reloaded scene",
              differ);
        cj_render_image_destroy(i1);
        cj_render_image_destroy(i2);
        cj_scene_destroy(re);
    }
    remove(file);
    printf("3D editor on %s: the bicubic sheet's %zu net points are the editable points; moving "
           "point (1, 1) changed %d of %zu patches (its support, (p+1)(q+1) = 16 at most), the "
           "tessellation cache re-planned %zu of them (first frame %zu), the patches equal a "
           "fresh conversion, undo/redo restore bit for bit; weight x1.25 of torus point (1, 0) "
           "also set its seam copy (1, 8) and changed %d rational patches; the saved scene reloads "
           "to the same nets and "
           "renders to the same pixels (%ld values differ)\n",
           CJ_SCENE_FILE, nsheet, changed, g->u.patches.count, planned1, planned0, wchanged,
           differ);
    free(before);
    free(after);
    free(undone);
    free(redone);
    cj_tess_cache_destroy(cache);
    cj_vscene_destroy(vs);
    if (failures) {
        printf("%d failure(s)\n", failures);
        return 1;
    }
    printf("test_viewer_bsurf: all checks passed\n");
    return 0;
}
