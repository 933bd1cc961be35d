/* test_render_overwrite: the rasterizer no longer clears a fresh image before drawing (issue
 * 20: every tile writes every pixel's colour, id and depth), so it must write all of them.
 * The demo scene (teapot, checkered floor, control net) and a smaller framing are drawn with
 * an allocator that fills every block with 0xFF bytes (NaN floats, ids 0xFFFFFFFF) and with
 * one that zeroes it, at 1 and 4 spp, tile sizes 8 and 64 (tiles cut at the image border),
 * 1 and 2 threads, ids and depth planes on: the images must be bit-identical and hold no
 * NaN. It fails if any pixel of any plane is left unwritten. */
#include "casteljau/render.h"
#include "casteljau/renderer.h"

#include "support/check.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *alloc_poison(void *user, size_t n) {
    (void)user;
    void *p = malloc(n);
    if (p) memset(p, 0xFF, n);
    return p;
}
static void *alloc_zero(void *user, size_t n) {
    (void)user;
    return calloc(1, n);
}
static void release(void *user, void *p) {
    (void)user;
    free(p);
}

static cj_render_image *draw(const cj_scene *s, const cj_allocator *a, int spp, int tile,
                             int threads, int w, int h) {
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.spp = spp;
    o.render.tile_size = tile;
    o.render.threads = threads;
    o.render.width = w;
    o.render.height = h;
    cj_renderer *r = NULL;
    cj_render_image *img = NULL;
    CHECK(!cj_renderer_create(&o, a, &r), "renderer");
    CHECK(!cj_renderer_draw(r, s, CJ_BACKEND_RASTER, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, &img, NULL),
          "draw");
    cj_renderer_destroy(r);
    return img;
}

int main(void) {
    cj_scene *scene = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &scene)) {
        fprintf(stderr, "cannot load the demo scene\n");
        return 1;
    }
    const cj_allocator poison = {alloc_poison, release, NULL}, zero = {alloc_zero, release, NULL};
    const int spps[2] = {1, 4}, tiles[2] = {8, 64}, threads[2] = {1, 2};
    int frames = 0;
    size_t values = 0;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c) {
                const int w = 77, h = 45; /* not multiples of the tile size */
                cj_render_image *p = draw(scene, &poison, spps[a], tiles[b], threads[c], w, h);
                cj_render_image *z = draw(scene, &zero, spps[a], tiles[b], threads[c], w, h);
                if (!p || !z) {
                    CHECK(0, "no image");
                    continue;
                }
                const size_t n = (size_t)w * (size_t)h;
                int nan = 0;
                for (size_t i = 0; i < 4 * n; ++i) nan |= isnan(p->rgba[i]);
                for (size_t i = 0; i < n; ++i) nan |= isnan(p->depth[i]);
                CHECK(!nan, "spp %d tile %d threads %d: unwritten (NaN) values", spps[a], tiles[b],
                      threads[c]);
                CHECK(!memcmp(p->rgba, z->rgba, 4 * n * sizeof(float)) &&
                          !memcmp(p->ids, z->ids, n * sizeof(uint32_t)) &&
                          !memcmp(p->depth, z->depth, n * sizeof(float)),
                      "spp %d tile %d threads %d: poisoned and zeroed memory give different "
                      "images",
                      spps[a], tiles[b], threads[c]);
                values += 6 * n;
                ++frames;
                cj_render_image_destroy(p);
                cj_render_image_destroy(z);
            }
    cj_scene_destroy(scene);
    printf("test_render_overwrite: %d frame pairs (demo scene 77 x 45, spp 1/4, tiles 8/64, "
           "threads 1/2): %zu values written over poisoned memory, equal to zeroed memory, no "
           "NaN\n",
           frames, values);
    return cj_check_exit();
}
