/* test_render_planes: the texture (u,v) planes of the rasterizer are built lazily, by the first
 * sample that needs one (raster/src/render_shade.c, cj_rshade_plane), on whichever worker
 * shades it. The demo scene (teapot, checkered floor with a footprint-filtered checker) is
 * drawn at 1 and 4 spp with 1, 2 and 4 threads and tiles of 8, 24 and 64 pixels: every image
 * (colour, ids, depth) must be bit-identical to the one-thread, 64-pixel-tile image of the same
 * spp, and the number of planes built (the stage report's texture.planes_built) must be the
 * same in every configuration (the set of triangles that win a textured sample does not depend
 * on threads or tiles), more than 0 and fewer than the triangles set up (so the laziness is
 * real). test_render_overwrite (poisoned memory) fails if a plane is read before it is built. */
#include "casteljau/render.h"
#include "casteljau/renderer.h"
#include "casteljau/stage_report.h"

#include "support/check.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double stage_value(const cj_stage_report *R, const char *stage, const char *key) {
    const cj_stage *s = cj_stage_report_find(R, stage);
    if (s)
        for (int i = 0; i < s->extra_count; ++i)
            if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    return -1.0;
}

static cj_render_image *draw(const cj_scene *s, int spp, int tile, int threads, double *planes,
                             uint64_t *tris) {
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.spp = spp;
    o.render.tile_size = tile;
    o.render.threads = threads;
    o.render.width = 320;
    o.render.height = 240;
    cj_renderer *r = NULL;
    cj_render_image *img = NULL;
    cj_stage_report R;
    CHECK(!cj_renderer_create(&o, NULL, &r), "renderer");
    /* two frames: the second runs on the renderer's pool (the first starts it) */
    for (int f = 0; f < 2; ++f) {
        cj_render_image_destroy(img);
        img = NULL;
        CHECK(!cj_renderer_draw(r, s, CJ_BACKEND_RASTER, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, &img, &R),
              "draw");
    }
    cj_renderer_destroy(r);
    *planes = stage_value(&R, "texture", "planes_built");
    const cj_stage *setup = cj_stage_report_find(&R, "raster_setup");
    *tris = setup ? setup->out : 0;
    return img;
}

static int same(const cj_render_image *a, const cj_render_image *b) {
    if (!a || !b) return 0;
    const size_t px = (size_t)a->width * (size_t)a->height;
    return a->width == b->width && a->height == b->height &&
           !memcmp(a->rgba, b->rgba, px * 4 * sizeof(float)) &&
           !memcmp(a->ids, b->ids, px * sizeof(uint32_t)) &&
           !memcmp(a->depth, b->depth, px * sizeof(float));
}

int main(void) {
    cj_scene *scene = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &scene)) {
        fprintf(stderr, "cannot load the demo scene\n");
        return 1;
    }
    const int spps[2] = {1, 4}, tiles[3] = {8, 24, 64}, threads[3] = {1, 2, 4};
    int compared = 0;
    for (int a = 0; a < 2; ++a) {
        double ref_planes = 0.0;
        uint64_t tris = 0;
        cj_render_image *ref = draw(scene, spps[a], 64, 1, &ref_planes, &tris);
        printf("spp %d: %.0f planes built for %llu triangles set up\n", spps[a], ref_planes,
               (unsigned long long)tris);
        CHECK(ref_planes > 0.0 && ref_planes < (double)tris,
              "spp %d: %.0f planes built of %llu triangles (expected some, not all)", spps[a],
              ref_planes, (unsigned long long)tris);
        for (int b = 0; b < 3; ++b)
            for (int c = 0; c < 3; ++c) {
                if (tiles[b] == 64 && threads[c] == 1) continue;
                double planes = 0.0;
                uint64_t t = 0;
                cj_render_image *img = draw(scene, spps[a], tiles[b], threads[c], &planes, &t);
                CHECK(same(img, ref), "spp %d tile %d threads %d: image differs from 1 thread",
                      spps[a], tiles[b], threads[c]);
                CHECK(planes == ref_planes,
                      "spp %d tile %d threads %d: %.0f planes built, %.0f with 1 thread", spps[a],
                      tiles[b], threads[c], planes, ref_planes);
                cj_render_image_destroy(img);
                ++compared;
            }
        cj_render_image_destroy(ref);
    }
    if (!cj_check_failures)
        printf("ok: %d images (spp 1/4, tiles 8/24/64, threads 1/2/4) bit-identical to one thread, "
               "the same planes built lazily in each\n",
               compared);
    cj_scene_destroy(scene);
    return cj_check_exit();
}
