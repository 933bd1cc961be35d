/* What the scene-drawing commands share (scene_cli.h). */
#define _POSIX_C_SOURCE 200809L
#include "scene_cli.h"
#include "cli_progress.h"

#include "cli.h"
#include "cli_guard.h"

#include "casteljau/image_io.h"
#include "casteljau/scene_json.h"
#include "casteljau/scene_textures.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int cli_load_scene(const char *cmd, const char *path, cj_scene **out) {
    cj_scene_json_options jo = {cli_teapot_path()};
    cj_scene *scene = NULL;
    const cj_status st = cj_scene_load_with_textures(path, &jo, NULL, &scene);
    if (st) return cli_fail_status(cmd, st, "%s", cj_last_error());
    *out = scene;
    return 0;
}

int cli_render_output(const char *cmd, const char *out, int *exr) {
    *exr = cli_has_ext(out, ".exr");
    if (!*exr && !cli_has_ext(out, ".png"))
        return cli_fail(cmd, "output '%s' must end in .png or .exr", out);
    if (cj_image_check_destination(out, *exr)) return cli_fail(cmd, "%s", cj_last_error());
    return 0;
}

int cli_write_render(const char *cmd, const char *out, int exr, const cj_render_image *img) {
    size_t n = (size_t)img->width * (size_t)img->height;
    cj_status st;
    /* Radiance that overflowed is a property of the input (the scene checks bound lights and
     * emission, so this is a last guard): no image with inf or NaN pixels is written. */
    for (size_t i = 0; i < 4 * n; ++i)
        if (!isfinite(img->rgba[i]))
            return cli_fail(cmd,
                            "pixel (%zu, %zu) channel %zu is %s: the scene's radiance overflows "
                            "(lower light intensities or emission); nothing written to '%s'",
                            (i / 4) % (size_t)img->width, (i / 4) / (size_t)img->width, i % 4,
                            isnan(img->rgba[i]) ? "NaN" : "infinite", out);
    if (exr) {
        float *px = malloc(n * 4 * sizeof(float));
        if (!px)
            return cli_error(cmd, "out of memory for a %d x %d image", img->width, img->height);
        for (size_t i = 0; i < n; ++i) {
            memcpy(px + 4 * i, img->rgba + 4 * i, 3 * sizeof(float));
            px[4 * i + 3] = 1.0f;
        }
        st = cj_image_write_float_with_flags(out, img->width, img->height, px, 0,
                                             exr == 2 ? (unsigned)CJ_IMAGE_FLOAT_HALF : 0u);
        free(px);
    } else {
        uint8_t *px = malloc(n * 4);
        if (!px)
            return cli_error(cmd, "out of memory for a %d x %d image", img->width, img->height);
        st = cj_render_image_to_srgb8(img, px, 0);
        for (size_t i = 0; i < n; ++i) px[4 * i + 3] = 255;
        if (!st) st = cj_image_write_png(out, img->width, img->height, px, 0);
        free(px);
    }
    if (st) return cli_error(cmd, "%s", cj_last_error());
    return 0;
}

int cli_scene_arg(const char *cmd, int k, const char *v, cli_scene_args *a,
                  cj_render_options *opt) {
    long n;
    switch (k) {
    case CLI_POSITIONAL:
        if (a->scene_path)
            return cli_fail(cmd, "more than one scene file ('%s', '%s')", a->scene_path, v);
        a->scene_path = v;
        break;
    case CLI_SO_DEMO:
        a->demo = 1;
        break;
    case CLI_SO_REPORT:
        a->report = 1;
        break;
    case CLI_SO_OUT:
        a->out = v;
        break;
    case CLI_SO_WIDTH:
    case CLI_SO_HEIGHT:
        if (cli_parse_int(v, 1, 32768, &n))
            return cli_fail(cmd, "%s '%s' is not an integer in 1..32768",
                            k == CLI_SO_WIDTH ? "--width" : "--height", v);
        *(k == CLI_SO_WIDTH ? &opt->width : &opt->height) = (int)n;
        break;
    case CLI_SO_EXR_HALF:
        a->exr_half = 1;
        break;
    default: /* CLI_SO_THREADS */
        if (cli_parse_int(v, 1, 1024, &n))
            return cli_fail(cmd, "--threads '%s' is not an integer in 1..1024", v);
        opt->threads = (int)n;
        break;
    }
    return 0;
}

int cli_open_scene(const char *cmd, const cli_scene_args *a, cli_demo_scene_fn make_demo, int *exr,
                   cj_scene **scene) {
    if (a->demo && a->scene_path)
        return cli_fail(cmd, "give either a scene file or --demo, not both");
    if (!a->demo && !a->scene_path) return cli_fail(cmd, "no scene: give SCENE.json or --demo");
    if (!a->out) return cli_fail(cmd, "no output file: give -o OUT.png or -o OUT.exr");
    int rc = cli_render_output(cmd, a->out, exr);
    if (rc) return rc;
    if (*exr && a->exr_half) *exr = 2; /* cli_write_render: half floats */
    *scene = NULL;
    if (!a->demo) {
        rc = cli_load_scene(cmd, a->scene_path, scene);
        /* The scene and every file it named (textures, .bpt, OBJ) are read now: the output must
         * be none of them. */
        if (!rc) rc = cli_guard_output(cmd, "output", a->out);
        /* One validation for both renderers (cj_scene_check), before any work. */
        if (!rc && cj_scene_check(*scene))
            rc = cli_fail(cmd, "%s: %s", a->scene_path, cj_last_error());
        if (rc) {
            cj_scene_destroy(*scene);
            *scene = NULL;
        }
        return rc;
    }
    if (make_demo(cli_teapot_path(), NULL, scene)) return cli_fail(cmd, "%s", cj_last_error());
    if ((rc = cli_guard_output(cmd, "output", a->out))) {
        cj_scene_destroy(*scene);
        *scene = NULL;
    }
    return rc;
}

int cli_finish_render(const char *cmd, const char *out, int exr, cj_render_image *img,
                      const cj_stage_report *report, double t0) {
    const int rc = cli_write_render(cmd, out, exr, img);
    char size[48];
    snprintf(size, sizeof size, "%d x %d", img->width, img->height);
    cj_render_image_destroy(img);
    if (rc) return rc;
    cli_summary(cmd, out, out, size, t0);
    if (report && cj_stage_report_json(report, stdout))
        return cli_error(cmd, "%s", cj_last_error());
    return 0;
}

int cli_render_scene(const char *cmd, const cli_scene_args *a, int exr, cj_scene *scene,
                     cj_renderer_options ro, cj_backend backend, unsigned planes, double ray_factor,
                     void (*touch)(cj_render_image *img)) {
    cj_render_image *img = NULL;
    cj_stage_report rep;
    const double t0 = cj_clock_seconds();
    const int rc = cli_draw_scene(cmd, a->scene_path ? a->scene_path : "demo", ro, scene, backend,
                                  planes, ray_factor, &img, &rep);
    cj_scene_destroy(scene);
    if (rc) return rc;
    if (touch) touch(img);
    return cli_finish_render(cmd, a->out, exr, img, a->report ? &rep : NULL, t0);
}

int cli_scene_command_args(cli_parser *ps, cli_own_option_fn own_option, void *ctx,
                           cli_demo_scene_fn make_demo, cli_scene_args *a, cj_render_options *opt,
                           int *exr, cj_scene **scene) {
    const char *v;
    int k, status;
    memset(a, 0, sizeof *a);
    while (cli_next_arg(ps, &k, &v, &status)) {
        const int bad = k >= CLI_SO_COUNT ? own_option(ps->cmd, k, v, ctx, opt)
                                          : cli_scene_arg(ps->cmd, k, v, a, opt);
        if (bad) return bad;
    }
    if (status >= 0) return status;
    const int rc = cli_open_scene(ps->cmd, a, make_demo, exr, scene);
    return rc ? rc : -1;
}
