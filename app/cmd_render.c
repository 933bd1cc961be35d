/* casteljau render: a 3D scene (JSON, or the built-in demo) through the rasterizer, to PNG or
 * EXR. Contract: bad input -> one stderr line (file:line: JSON path ...), nothing on stdout, no
 * image file, exit status 2; --stage-report prints the pipeline's report as JSON on stdout. */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CJ_TEAPOT_SOURCE
#define CJ_TEAPOT_SOURCE "data/teapot.bpt"
#endif
#ifndef CJ_TEAPOT_INSTALLED
#define CJ_TEAPOT_INSTALLED "/usr/local/share/casteljau/teapot.bpt"
#endif

static const char render_usage[] =
    "usage: casteljau render (SCENE.json | --demo) -o OUT.png|OUT.exr [--width W --height H]\n"
    "                        [--spp 1|4|16] [--tol-px T] [--threads N] [--stage-report]\n"
    "  SCENE.json      a scene file (see scene/include/casteljau/scene_json.h); image textures\n"
    "                  are read relative to its folder\n"
    "  --demo          the built-in scene: the lit, textured Utah teapot with its control net\n"
    "  -o              PNG (8-bit sRGB) or EXR (linear half float), the picture composited over\n"
    "                  the scene's background (opaque)\n"
    "  --width/height  image size (default: the scene's settings)\n"
    "  --spp           samples per pixel (supersampling, box-filtered)\n"
    "  --tol-px        screen-space tessellation tolerance in pixels (default 0.25)\n"
    "  --threads       worker threads (default: one per core); the image does not depend on it\n"
    "  --stage-report  print the pipeline's stage report (JSON) on stdout\n";

#if defined(CJ_HAVE_PLOT) /* the tool was built with viz/ (OpenImageIO), raster/ and scene/ */

#include "casteljau/image_io.h"
#include "casteljau/render.h"
#include "casteljau/scene_json.h"
#include "casteljau/scene_textures.h"

#include <unistd.h>

static int ends_with(const char *path, const char *ext) {
    size_t a = strlen(path), b = strlen(ext);
    if (a <= b) return 0;
    for (size_t i = 0; i < b; ++i) {
        char c = path[a - b + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != ext[i]) return 0;
    }
    return 1;
}

static int parse_int(const char *s, int lo, int hi, int *out) {
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

static const char *teapot_path(void) {
    return access(CJ_TEAPOT_SOURCE, R_OK) == 0 ? CJ_TEAPOT_SOURCE : CJ_TEAPOT_INSTALLED;
}

/* The folder of a path ("" for a bare name), into buf. */
static const char *dir_of(const char *path, char *buf, size_t size) {
    const char *slash = strrchr(path, '/');
    if (!slash) return "";
    size_t n = (size_t)(slash - path);
    if (n >= size) n = size - 1;
    memcpy(buf, path, n);
    buf[n] = '\0';
    return n ? buf : "/";
}

static int write_image(const char *cmd, const char *out, int exr, const cj_render_image *img) {
    size_t n = (size_t)img->width * (size_t)img->height;
    cj_status st;
    if (exr) {
        float *px = malloc(n * 4 * sizeof(float));
        if (!px) return cli_fail(cmd, "out of memory for a %d x %d image", img->width, img->height);
        for (size_t i = 0; i < n; ++i) {
            memcpy(px + 4 * i, img->rgba + 4 * i, 3 * sizeof(float));
            px[4 * i + 3] = 1.0f;
        }
        st = cj_image_write_float(out, img->width, img->height, px, 0);
        free(px);
    } else {
        uint8_t *px = malloc(n * 4);
        if (!px) return cli_fail(cmd, "out of memory for a %d x %d image", img->width, img->height);
        st = cj_render_image_to_srgb8(img, px, 0);
        for (size_t i = 0; i < n; ++i) px[4 * i + 3] = 255;
        if (!st) st = cj_image_write_png(out, img->width, img->height, px, 0);
        free(px);
    }
    if (st) return cli_fail(cmd, "%s", cj_last_error());
    return 0;
}

int cmd_render(int argc, char **argv) {
    const char *cmd = "render";
    const char *scene_path = NULL, *out = NULL;
    int demo = 0, report = 0;
    cj_render_options opt = cj_render_options_default();
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(render_usage, stdout);
            return 0;
        }
        if (!strcmp(a, "--demo")) {
            demo = 1;
            continue;
        }
        if (!strcmp(a, "--stage-report")) {
            report = 1;
            continue;
        }
        if (a[0] != '-' || a[1] == '\0') {
            if (scene_path)
                return cli_fail(cmd, "more than one scene file ('%s', '%s')", scene_path, a);
            scene_path = a;
            continue;
        }
        if (i + 1 >= argc) return cli_fail(cmd, "option '%s' needs a value (or is unknown)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "-o")) {
            out = v;
        } else if (!strcmp(a, "--width")) {
            if (parse_int(v, 1, 32768, &opt.width))
                return cli_fail(cmd, "--width '%s' is not an integer in 1..32768", v);
        } else if (!strcmp(a, "--height")) {
            if (parse_int(v, 1, 32768, &opt.height))
                return cli_fail(cmd, "--height '%s' is not an integer in 1..32768", v);
        } else if (!strcmp(a, "--spp")) {
            if (parse_int(v, 1, 16, &opt.spp) || (opt.spp != 1 && opt.spp != 4 && opt.spp != 16))
                return cli_fail(cmd, "--spp '%s' must be 1, 4 or 16", v);
        } else if (!strcmp(a, "--tol-px")) {
            if (cli_parse_double(v, &opt.tol_px) || !(opt.tol_px > 0.0))
                return cli_fail(cmd, "--tol-px '%s' is not a positive finite number", v);
        } else if (!strcmp(a, "--threads")) {
            if (parse_int(v, 1, 1024, &opt.threads))
                return cli_fail(cmd, "--threads '%s' is not an integer in 1..1024", v);
        } else {
            return cli_fail(cmd, "unknown option '%s' (try --help)", a);
        }
    }
    if (demo && scene_path) return cli_fail(cmd, "give either a scene file or --demo, not both");
    if (!demo && !scene_path) return cli_fail(cmd, "no scene: give SCENE.json or --demo");
    if (!out) return cli_fail(cmd, "no output file: give -o OUT.png or -o OUT.exr");
    int exr = ends_with(out, ".exr");
    if (!exr && !ends_with(out, ".png"))
        return cli_fail(cmd, "output '%s' must end in .png or .exr", out);
    if (cj_image_check_destination(out, exr)) return cli_fail(cmd, "%s", cj_last_error());

    cj_scene *scene = NULL;
    cj_status st;
    if (demo) {
        st = cj_render_demo_scene(teapot_path(), NULL, &scene);
    } else {
        cj_scene_json_options jo = {teapot_path()};
        st = cj_scene_load_json_ex(scene_path, &jo, NULL, &scene);
        char dir[4096];
        if (!st) {
            st = cj_scene_load_textures(scene, dir_of(scene_path, dir, sizeof dir));
            if (st) {
                cj_scene_destroy(scene);
                scene = NULL;
            }
        }
    }
    if (st) return cli_fail(cmd, "%s", cj_last_error());
    cj_render_image *img = NULL;
    cj_stage_report rep;
    st = cj_render_raster(scene, &opt, 0, NULL, &img, &rep);
    if (st) {
        cj_scene_destroy(scene);
        return cli_fail(cmd, "%s%s%s", scene_path ? scene_path : "demo", ": ", cj_last_error());
    }
    int rc = write_image(cmd, out, exr, img);
    cj_render_image_destroy(img);
    cj_scene_destroy(scene);
    if (rc) return rc;
    if (report && cj_stage_report_json(&rep, stdout)) return cli_fail(cmd, "%s", cj_last_error());
    return 0;
}

#else

int cmd_render(int argc, char **argv) {
    (void)argc;
    (void)argv;
    (void)render_usage;
    return cli_fail("render", "this build has no image output (configure with OpenImageIO)");
}

#endif
