/* casteljau render: a 3D scene (JSON, or the built-in demo) through the rasterizer, to PNG or
 * EXR. Contract: bad input -> one stderr line (file:line: JSON path ...), nothing on stdout, no
 * image file, exit status 2; --stage-report prints the pipeline's report as JSON on stdout. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char render_usage[] =
    "usage: casteljau render (SCENE.json | --demo) -o OUT.png|OUT.exr [--width W --height H]\n"
    "                        [--spp 1|4|16] [--tol-px T] [--threads N] [--stage-report]\n"
    "                        [--exr-half] [--quiet]\n"
    "  SCENE.json      a scene file (see scene/include/casteljau/scene_json.h); image textures\n"
    "                  are read relative to its folder\n"
    "  --demo          the built-in scene: the lit, textured Utah teapot with its control net\n"
    "  -o              PNG (8-bit sRGB) or EXR (linear 32-bit float), the picture composited over\n"
    "                  the scene's background (opaque); no infinite value is ever written\n"
    "  --exr-half      store the EXR as half floats (a value above 65504 is refused)\n"
    "  --width/height  image size (default: the scene's settings)\n"
    "  --spp           samples per pixel (supersampling, box-filtered)\n"
    "  --tol-px        screen-space tessellation tolerance in pixels (default 0.25)\n"
    "  --threads       worker threads (default: one per core); the image does not depend on it\n"
    "  --stage-report  print the pipeline's stage report (JSON) on stdout\n"
    "  On a terminal, stderr shows the progress (tiles done, time left) and a summary line;\n"
    "  Ctrl-C stops the render cleanly (no image written, exit status 130).\n";

#if defined(CJ_HAVE_PLOT) /* the tool was built with viz/ (OpenImageIO), raster/ and scene/ */

#include "cli_progress.h"
#include "scene_cli.h"

#include "casteljau/render.h"
#include "casteljau/renderer.h"

enum { O_SPP = CLI_SO_COUNT, O_TOL };

/* render's own options (cli_own_option_fn). */
static int render_option(const char *cmd, int k, const char *v, void *ctx, cj_render_options *opt) {
    (void)ctx;
    long n;
    if (k == O_SPP) {
        if (cli_parse_int(v, 1, 16, &n) || (n != 1 && n != 4 && n != 16))
            return cli_fail(cmd, "--spp '%s' must be 1, 4 or 16", v);
        opt->spp = (int)n;
    } else if (cli_parse_double(v, &opt->tol_px) || !(opt->tol_px > 0.0)) { /* O_TOL */
        return cli_fail(cmd, "--tol-px '%s' is not a positive finite number", v);
    }
    return 0;
}

int cmd_render(int argc, char **argv) {
    const char *cmd = "render";
    static const cli_opt opts[] = {CLI_SCENE_OPTIONS, {"--spp", NULL, 1}, {"--tol-px", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, cmd, render_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    cli_scene_args a;
    cj_render_options opt = cj_render_options_defaults();
    cj_scene *scene = NULL;
    int exr;
    const int rc = cli_scene_command_args(&ps, render_option, NULL, cj_render_demo_scene, &a, &opt,
                                          &exr, &scene);
    if (rc >= 0) return rc;
    cj_renderer_options ro = cj_renderer_options_defaults();
    ro.render = opt;
    return cli_render_scene(cmd, &a, exr, scene, ro, CJ_BACKEND_RASTER, 0, 1.0, NULL);
}

#else

int cmd_render(int argc, char **argv) {
    (void)argc;
    (void)argv;
    (void)render_usage;
    return cli_fail("render", "this build has no image output (configure with OpenImageIO)");
}

#endif
