/* The draw of render and trace as the user sees it: warnings first (very large work, a scene
 * without lights), progress, Ctrl-C. */
#include "cli.h"
#include "cli_progress.h"
#include "scene_cli.h"

#include "casteljau/status.h"

#include <stdio.h>

/* Samples (times rays per sample) above which a run is announced: 1e8 is twenty times the
 * demo at 640 x 480 x 16 spp, where a render takes seconds to minutes on a few cores. */
#define LARGE_WORK_SAMPLES 1e8

int cli_draw_scene(const char *cmd, const char *name, cj_renderer_options ro, const cj_scene *scene,
                   cj_backend backend, unsigned planes, double ray_factor, cj_render_image **img,
                   cj_stage_report *rep) {
    const cj_scene_settings *s = cj_scene_get_settings(scene);
    const int w = ro.render.width ? ro.render.width : s->width;
    const int h = ro.render.height ? ro.render.height : s->height;
    const int spp = ro.render.spp ? ro.render.spp : s->spp;
    const double samples = (double)w * (double)h * (double)(spp > 0 ? spp : 1) * ray_factor;
    if (samples >= LARGE_WORK_SAMPLES) {
        char what[160];
        snprintf(what, sizeof what,
                 "%d x %d pixels x %d sample(s)%s = %.3g G samples, %.1f GB of "
                 "image",
                 w, h, spp, ray_factor > 1 ? " x rays" : "", samples * 1e-9,
                 (double)w * (double)h * 16.0 * 1e-9);
        cli_warn_large(cmd, what);
    }
    if (cj_scene_light_count(scene) == 0 && !(planes & CJ_IMAGE_IDS))
        cli_warn(cmd,
                 "%s has no lights (not even ambient): only emissive surfaces will show; add "
                 "a \"lights\" entry",
                 name);
    cli_progress pr;
    cli_progress_begin(&pr, cmd, "tiles");
    cli_progress_note(&pr, "preparing (scene, tessellation, image buffers)");
    ro.render.progress = cli_progress_step;
    ro.render.progress_user = &pr;
    cj_renderer *r = NULL;
    cj_status st = cj_renderer_create(&ro, NULL, &r);
    if (!st) st = cj_renderer_draw(r, scene, backend, planes, img, rep);
    cj_renderer_destroy(r);
    cli_progress_end(&pr);
    if (st == CJ_ERR_CANCELLED && cli_progress_interrupted())
        return cli_error(cmd, "stopped by Ctrl-C; no image written"), 130;
    if (st) return cli_fail(cmd, "%s: %s", name, cj_last_error());
    return 0;
}
