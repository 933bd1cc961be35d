/* casteljau view: the interactive viewer and control-point editor (GLFW + OpenGL, see
 * viz/include/casteljau/viewer.h). Contract: bad arguments or input -> one line on stderr, exit
 * status 2; no display -> one line saying so, exit status 1. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char view_usage[] =
    "usage: casteljau view (CURVES.json | SCENE.json | PATCHES.bpt | --teapot)\n"
    "                      [--width W --height H] [--spp N] [--tol-px T] [--threads N]\n"
    "                      [--replay EVENTS.txt] [--screenshot OUT.png] [--frame-times F]\n"
    "                      [--hide-overlay] [--title T] [--timeline F]\n"
    "  CURVES.json     a plot JSON document of one plot with bezier / catmull-rom items: 2D\n"
    "                  mode (drag control points, insert/delete, elevate, split, undo, save)\n"
    "  SCENE.json      a scene (as `casteljau render` reads), PATCHES.bpt Bezier patches, or\n"
    "  --teapot        the render demo scene: 3D mode (orbit/pan/zoom, drag control points)\n"
    "  --width/height  window size (default: the document's / the scene's settings)\n"
    "  --spp, --tol-px 3D: samples per pixel and screen tolerance, stored in the scene\n"
    "  --replay        run a script of input events, then close (see\n"
    "                  " CJ_DOC_DIR "/viewer.md)\n"
    "  --screenshot    PNG of the window's back buffer after the replay (or at exit)\n"
    "  --frame-times   write each frame's wall and CPU seconds (render + upload + swap)\n"
    "  --hide-overlay  start without the text overlay (the picture alone)\n"
    "  --timeline      3D: write input events, render passes and frames shown, timed\n"
    "Keys: F1 in the window lists them. Ctrl+S saves to the input file (a .bpt or the teapot\n"
    "as a scene JSON beside it / teapot_scene.json), atomically.\n"
    "Exit status: 0; 2 bad arguments, input or script; 1 no display or no memory.\n";

#if defined(CJ_HAVE_VIEWER)

#include "casteljau/viewer.h"

int cmd_view(int argc, char **argv) {
    const char *cmd = "view";
    cj_viewer_options o;
    memset(&o, 0, sizeof o);
    int teapot = 0;
    enum {
        O_W,
        O_H,
        O_SPP,
        O_TOL,
        O_THR,
        O_REPLAY,
        O_SHOT,
        O_TIMES,
        O_HIDE,
        O_TITLE,
        O_TIMELINE,
        O_TEAPOT
    };
    static const cli_opt opts[] = {
        {"--width", NULL, 1},      {"--height", NULL, 1},      {"--spp", NULL, 1},
        {"--tol-px", NULL, 1},     {"--threads", NULL, 1},     {"--replay", NULL, 1},
        {"--screenshot", NULL, 1}, {"--frame-times", NULL, 1}, {"--hide-overlay", NULL, 0},
        {"--title", NULL, 1},      {"--timeline", NULL, 1},    {"--teapot", NULL, 0}};
    cli_parser ps;
    cli_parser_init(&ps, cmd, view_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    const char *v;
    int k, status;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        long n;
        switch (k) {
        case CLI_POSITIONAL:
            if (o.path) return cli_fail(cmd, "more than one input ('%s', '%s')", o.path, v);
            o.path = v;
            break;
        case O_W:
        case O_H:
            if (cli_parse_int(v, 64, 8192, &n))
                return cli_fail(cmd, "%s '%s' is not a whole number in 64..8192", opts[k].name, v);
            *(k == O_W ? &o.width : &o.height) = (int)n;
            break;
        case O_SPP:
            if (cli_parse_int(v, 1, 1024, &n))
                return cli_fail(cmd, "--spp '%s' is not in 1..1024", v);
            o.spp = (int)n;
            break;
        case O_TOL:
            if (cli_parse_double(v, &o.tol_px) || !(o.tol_px > 0))
                return cli_fail(cmd, "--tol-px '%s' is not a positive number", v);
            break;
        case O_THR:
            if (cli_parse_int(v, 1, 1024, &n))
                return cli_fail(cmd, "--threads '%s' is not in 1..1024", v);
            o.threads = (int)n;
            break;
        case O_REPLAY:
            o.replay = v;
            break;
        case O_SHOT:
            o.screenshot = v;
            break;
        case O_TIMES:
            o.frame_times = v;
            break;
        case O_HIDE:
            o.hide_overlay = 1;
            break;
        case O_TITLE:
            o.title = v;
            break;
        case O_TIMELINE:
            o.timeline = v;
            break;
        default:
            teapot = 1;
            break;
        }
    }
    if (status >= 0) return status;
    if (teapot && o.path) return cli_fail(cmd, "give either a file or --teapot, not both");
    if (!teapot && !o.path) return cli_fail(cmd, "nothing to view: give a file or --teapot");
    o.teapot_path = cli_teapot_path(); /* beside the executable first: a moved prefix works */
    const cj_status st = cj_viewer_run(&o);
    if (st == CJ_ERR_UNSUPPORTED || st == CJ_ERR_NOMEM)
        return cli_error(cmd, "%s", cj_last_error());
    if (st) return cli_fail(cmd, "%s", cj_last_error());
    return 0;
}

#else

int cmd_view(int argc, char **argv) {
    for (int i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(view_usage, stdout);
            return 0;
        }
    return cli_error("view", "this build has no viewer: reconfigure with -DCJ_WITH_GLFW=ON "
                             "(needs libglfw3-dev) and OpenImageIO");
}

#endif
