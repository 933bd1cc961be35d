/* test_render_band: the render cache's tolerance band on a steady approach (raster/src/
 * render_cache.c). The demo teapot is drawn by one renderer while the camera moves 0.5 % of its
 * distance closer each frame, 40 frames: each frame needs a slightly finer object tolerance.
 * Checked: every frame's proven bound is within the tolerance asked (bound_px <= tol_px); the
 * first frame and the first frame that re-tessellates (the first departure from the band, made
 * at exactly the needed tolerance) are bit-identical (colour, ids, depth) to one-shot renders;
 * and the teapot is re-tessellated whole at most 4 times in the 40 frames (a departure
 * downwards after another re-tessellates at needed/sqrt 2, which lasts about 70 such frames;
 * re-tessellating at exactly the needed tolerance, as before, redid all 32 patches in every
 * frame). */
#include "casteljau/render.h"
#include "casteljau/renderer.h"
#include "casteljau/stage_report.h"

#include "support/check.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static double value(const cj_stage_report *R, const char *stage, const char *key) {
    const cj_stage *s = cj_stage_report_find(R, stage);
    if (s)
        for (int i = 0; i < s->extra_count; ++i)
            if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    return -1.0;
}

static int same(const cj_render_image *a, const cj_render_image *b) {
    if (!a || !b || a->width != b->width || a->height != b->height) return 0;
    const size_t px = (size_t)a->width * (size_t)a->height;
    return !memcmp(a->rgba, b->rgba, px * 4 * sizeof(float)) &&
           !memcmp(a->ids, b->ids, px * sizeof(uint32_t)) &&
           !memcmp(a->depth, b->depth, px * sizeof(float));
}

static int matches_one_shot(const cj_scene *s, const cj_render_options *o,
                            const cj_render_image *img) {
    cj_render_image *ref = NULL;
    CHECK(!cj_render_raster(s, o, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, NULL, &ref, NULL), "one-shot");
    const int eq = same(img, ref);
    cj_render_image_destroy(ref);
    return eq;
}

int main(void) {
    cj_scene *s = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s)) {
        fprintf(stderr, "cannot load the demo scene\n");
        return 1;
    }
    const cj_camera cam0 = *cj_scene_get_camera(s);
    const cj_vec3 target = cj_v3_add(cam0.eye, cam0.gaze);
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.width = 160;
    o.render.height = 120;
    o.render.spp = 1;
    o.render.threads = 2;
    cj_renderer *r = NULL;
    CHECK(!cj_renderer_create(&o, NULL, &r), "renderer");
    cj_render_image *img = NULL;
    const int frames = 40;
    int redone = 0, first_checked = 0;
    for (int f = 0; f <= frames && r; ++f) {
        cj_camera cam = cam0;
        cam.eye = cj_v3_add(target, cj_v3_scale(cj_v3_sub(cam0.eye, target), pow(0.995, f)));
        cam.gaze = cj_v3_sub(target, cam.eye);
        CHECK(!cj_scene_set_camera(s, &cam), "camera");
        cj_stage_report R;
        CHECK(!cj_renderer_draw(r, s, CJ_BACKEND_RASTER, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, &img, &R),
              "frame %d", f);
        const double built = value(&R, "tessellate_patches", "patches_built");
        const double bound = value(&R, "tessellate_patches", "bound_px");
        const double tol = value(&R, "tessellate_patches", "tol_px");
        CHECK(bound >= 0.0 && bound <= tol, "frame %d: bound %g px over the tolerance %g px", f,
              bound, tol);
        if (f == 0) {
            CHECK(built > 0, "frame 0 built nothing");
            CHECK(matches_one_shot(s, &o.render, img), "frame 0 differs from a one-shot render");
            continue;
        }
        if (built > 0) {
            ++redone;
            printf("frame %2d: %g patches re-tessellated, bound %.4f px of %.4f\n", f, built, bound,
                   tol);
            if (!first_checked) {
                CHECK(matches_one_shot(s, &o.render, img),
                      "frame %d (the first departure from the band) differs from a one-shot "
                      "render",
                      f);
                first_checked = 1;
            }
        }
    }
    CHECK(redone >= 1, "the approach never left the band (the test moves too little)");
    CHECK(redone <= 4,
          "%d of %d frames re-tessellated the teapot (a steady approach should "
          "pre-refine)",
          redone, frames);
    if (!cj_check_failures)
        printf("ok: %d frames approaching, every bound within its tolerance, %d re-tessellations, "
               "the first frame and the first re-tessellation equal to one-shot renders\n",
               frames, redone);
    cj_render_image_destroy(img);
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
    return cj_check_exit();
}
