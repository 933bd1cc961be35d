/* casteljau trace: a 3D scene (JSON or the built-in demo) through the ray tracer, to PNG or
 * EXR. Same contract as `casteljau render`: bad input -> one stderr line, nothing on stdout, no
 * image file, exit status 2; --stage-report prints the tracer's report (rays of each kind and
 * their time) as JSON on stdout. */
#include "cli.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char trace_usage[] =
    "usage: casteljau trace (SCENE.json | --demo) -o OUT.png|OUT.exr [--width W --height H]\n"
    "                       [--spp N] [--max-depth D] [--seed S] [--threads N] [--signature]\n"
    "                       [--indirect N] [--integrator whitted|path] [--exr-half]\n"
    "                       [--stage-report] [--quiet]\n"
    "  SCENE.json      a scene file (the same files `casteljau render` reads)\n"
    "  --demo          built-in scene: a mirror sphere, a glass sphere and the Utah teapot\n"
    "                  (its Bezier patches traced directly) on a checkered floor\n"
    "  -o              PNG (8-bit sRGB) or EXR (linear 32-bit float; no infinite value is\n"
    "                  ever written)\n"
    "  --exr-half      store the EXR as half floats (a value above 65504 is refused)\n"
    "  --width/height  image size (default: the scene's settings)\n"
    "  --spp           samples per pixel, any N >= 1 (stratified; area lights and glossy\n"
    "                  materials are sampled only when N > 1)\n"
    "  --max-depth     recursion depth of reflected/refracted rays (default: the scene's)\n"
    "  --seed          sampling seed (the image is the same for any thread count)\n"
    "  --threads       worker threads (default: one per core)\n"
    "  --indirect      one-bounce diffuse interreflection: N cosine-weighted rays per diffuse\n"
    "                  hit (default 0: off)\n"
    "  --integrator    whitted (default): local shading, mirror and refraction rays; path: a\n"
    "                  path tracer (next-event estimation, MIS, Russian roulette; lights read\n"
    "                  radiometrically; " CJ_DOC_DIR "/light.md)\n"
    "  --signature     write the scene signature image instead: each object id its colour\n"
    "  --stage-report  print the stage report (JSON) on stdout\n"
    "  On a terminal, stderr shows the progress (tiles done, time left) and a summary line;\n"
    "  Ctrl-C stops the trace cleanly (no image written, exit status 130).\n";

#if defined(CJ_HAVE_PLOT)

#include "cli_progress.h"
#include "scene_cli.h"

#include "casteljau/renderer.h"
#include "casteljau/trace.h"

/* A distinct colour per object id (0, the background, is black). */
static void id_colour(uint32_t id, float c[3]) {
    if (!id) {
        c[0] = c[1] = c[2] = 0.0f;
        return;
    }
    uint32_t h = id * 2654435761u;
    c[0] = 0.15f + 0.85f * (float)((h >> 8) & 255) / 255.0f;
    c[1] = 0.15f + 0.85f * (float)((h >> 16) & 255) / 255.0f;
    c[2] = 0.15f + 0.85f * (float)((h >> 24) & 255) / 255.0f;
}

/* --signature: each object id its own colour; the background black. */
static void colour_ids(cj_render_image *img) {
    const size_t npx = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < npx; ++i) id_colour(img->ids[i], img->rgba + 4 * i);
}

enum { O_SIGNATURE = CLI_SO_COUNT, O_SPP, O_DEPTH, O_SEED, O_INDIRECT, O_INTEGRATOR };

/* What trace's own options set besides the render options. */
typedef struct trace_args {
    int signature;
    cj_trace_options topt;
} trace_args;

/* trace's own options (cli_own_option_fn). */
static int trace_option(const char *cmd, int k, const char *v, void *ctx, cj_render_options *opt) {
    trace_args *t = ctx;
    long n;
    switch (k) {
    case O_SIGNATURE:
        t->signature = 1;
        break;
    case O_SPP:
        if (cli_parse_int(v, 1, 65536, &n))
            return cli_fail(cmd, "--spp '%s' is not an integer in 1..65536", v);
        opt->spp = (int)n;
        break;
    case O_DEPTH:
        if (cli_parse_int(v, 0, 64, &n))
            return cli_fail(cmd, "--max-depth '%s' is not an integer in 0..64", v);
        opt->max_depth = n ? (int)n : -1; /* 0 means "the scene's" in the options: see below */
        break;
    case O_SEED: {
        char *end;
        errno = 0;
        unsigned long long sd = strtoull(v, &end, 10);
        if (end == v || *end || v[0] == '-' || v[0] == '+' || errno == ERANGE)
            return cli_fail(cmd, "--seed '%s' is not an integer in 0..18446744073709551615", v);
        opt->use_seed = 1;
        opt->seed = (uint64_t)sd;
        break;
    }
    case O_INDIRECT:
        if (cli_parse_int(v, 0, 4096, &n))
            return cli_fail(cmd, "--indirect '%s' is not an integer in 0..4096", v);
        t->topt.indirect_samples = (int)n;
        break;
    default: /* O_INTEGRATOR */
        if (!strcmp(v, "whitted"))
            t->topt.integrator = CJ_INTEGRATOR_WHITTED;
        else if (!strcmp(v, "path"))
            t->topt.integrator = CJ_INTEGRATOR_PATH;
        else
            return cli_fail(cmd, "--integrator '%s' is neither whitted nor path", v);
        break;
    }
    return 0;
}

int cmd_trace(int argc, char **argv) {
    const char *cmd = "trace";
    static const cli_opt opts[] = {CLI_SCENE_OPTIONS,        {"--signature", NULL, 0},
                                   {"--spp", NULL, 1},       {"--max-depth", NULL, 1},
                                   {"--seed", NULL, 1},      {"--indirect", NULL, 1},
                                   {"--integrator", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, cmd, trace_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    cli_scene_args a;
    trace_args t;
    memset(&t, 0, sizeof t);
    cj_render_options opt = cj_render_options_defaults();
    cj_scene *scene = NULL;
    int exr;
    const int rc =
        cli_scene_command_args(&ps, trace_option, &t, cj_trace_demo_scene, &a, &opt, &exr, &scene);
    if (rc >= 0) return rc;
    if (opt.max_depth < 0) {
        /* --max-depth 0: primary rays only; the options use 0 for "the scene's" */
        cj_scene_settings s = *cj_scene_get_settings(scene);
        s.max_depth = 0;
        cj_scene_set_settings(scene, &s);
        opt.max_depth = 0;
    }
    cj_renderer_options ro = cj_renderer_options_defaults();
    ro.render = opt;
    ro.trace = t.topt;
    return cli_render_scene(cmd, &a, exr, scene, ro, CJ_BACKEND_TRACE,
                            t.signature ? CJ_IMAGE_IDS : 0, 1.0 + t.topt.indirect_samples,
                            t.signature ? colour_ids : NULL);
}

#else

int cmd_trace(int argc, char **argv) {
    (void)argc;
    (void)argv;
    (void)trace_usage;
    return cli_fail("trace", "this build has no image output (configure with OpenImageIO)");
}

#endif
