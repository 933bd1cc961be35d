/* casteljau trace: a 3D scene (JSON or the built-in demo) through the ray tracer, to PNG or
 * EXR. Same contract as `casteljau render`: bad input -> one stderr line, nothing on stdout, no
 * image file, exit status 2; --stage-report prints the tracer's report (rays of each kind and
 * their time) as JSON on stdout. */
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

static const char trace_usage[] =
    "usage: casteljau trace (SCENE.json | --demo) -o OUT.png|OUT.exr [--width W --height H]\n"
    "                       [--spp N] [--max-depth D] [--seed S] [--threads N] [--signature]\n"
    "                       [--stage-report]\n"
    "  SCENE.json      a scene file (the same files `casteljau render` reads)\n"
    "  --demo          built-in scene: a mirror sphere, a glass sphere and the Utah teapot\n"
    "                  (its Bezier patches traced directly) on a checkered floor\n"
    "  -o              PNG (8-bit sRGB) or EXR (linear float)\n"
    "  --width/height  image size (default: the scene's settings)\n"
    "  --spp           samples per pixel, any N >= 1 (stratified; area lights and glossy\n"
    "                  materials are sampled only when N > 1)\n"
    "  --max-depth     recursion depth of reflected/refracted rays (default: the scene's)\n"
    "  --seed          sampling seed (the image is the same for any thread count)\n"
    "  --threads       worker threads (default: one per core)\n"
    "  --signature     write the scene signature image instead: each object id its colour\n"
    "  --stage-report  print the stage report (JSON) on stdout\n";

#if defined(CJ_HAVE_PLOT)

#include "casteljau/image_io.h"
#include "casteljau/scene_json.h"
#include "casteljau/scene_textures.h"
#include "casteljau/trace.h"

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

static int parse_long(const char *s, long lo, long hi, long *out) {
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < lo || v > hi) return -1;
    *out = v;
    return 0;
}

static const char *teapot_path(void) {
    return access(CJ_TEAPOT_SOURCE, R_OK) == 0 ? CJ_TEAPOT_SOURCE : CJ_TEAPOT_INSTALLED;
}

static const char *dir_of(const char *path, char *buf, size_t size) {
    const char *slash = strrchr(path, '/');
    if (!slash) return "";
    size_t n = (size_t)(slash - path);
    if (n >= size) n = size - 1;
    memcpy(buf, path, n);
    buf[n] = '\0';
    return n ? buf : "/";
}

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

static int write_image(const char *cmd, const char *out, int exr, cj_render_image *img,
                       int signature) {
    size_t n = (size_t)img->width * (size_t)img->height;
    if (signature)
        for (size_t i = 0; i < n; ++i) id_colour(img->ids[i], img->rgba + 4 * i);
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

int cmd_trace(int argc, char **argv) {
    const char *cmd = "trace";
    const char *scene_path = NULL, *out = NULL;
    int demo = 0, report = 0, signature = 0;
    cj_render_options opt = cj_render_options_default();
    long v_;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(trace_usage, stdout);
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
        if (!strcmp(a, "--signature")) {
            signature = 1;
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
            if (parse_long(v, 1, 32768, &v_))
                return cli_fail(cmd, "--width '%s' is not an integer in 1..32768", v);
            opt.width = (int)v_;
        } else if (!strcmp(a, "--height")) {
            if (parse_long(v, 1, 32768, &v_))
                return cli_fail(cmd, "--height '%s' is not an integer in 1..32768", v);
            opt.height = (int)v_;
        } else if (!strcmp(a, "--spp")) {
            if (parse_long(v, 1, 65536, &v_))
                return cli_fail(cmd, "--spp '%s' is not an integer in 1..65536", v);
            opt.spp = (int)v_;
        } else if (!strcmp(a, "--max-depth")) {
            if (parse_long(v, 0, 64, &v_))
                return cli_fail(cmd, "--max-depth '%s' is not an integer in 0..64", v);
            opt.max_depth = (int)v_;
            if (v_ == 0) opt.max_depth = -1; /* 0 means "the scene's" in the options: see below */
        } else if (!strcmp(a, "--seed")) {
            char *end;
            unsigned long long s = strtoull(v, &end, 10);
            if (end == v || *end || v[0] == '-')
                return cli_fail(cmd, "--seed '%s' is not a non-negative integer", v);
            opt.use_seed = 1;
            opt.seed = (uint64_t)s;
        } else if (!strcmp(a, "--threads")) {
            if (parse_long(v, 1, 1024, &v_))
                return cli_fail(cmd, "--threads '%s' is not an integer in 1..1024", v);
            opt.threads = (int)v_;
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
        st = cj_trace_demo_scene(teapot_path(), NULL, &scene);
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
    if (opt.max_depth < 0) {
        /* --max-depth 0: primary rays only; the options use 0 for "the scene's" */
        cj_scene_settings s = *cj_scene_settings_get(scene);
        s.max_depth = 0;
        cj_scene_set_settings(scene, &s);
        opt.max_depth = 0;
    }
    cj_render_image *img = NULL;
    cj_stage_report rep;
    st = cj_render_trace(scene, &opt, signature ? CJ_IMAGE_IDS : 0, NULL, &img, &rep);
    if (st) {
        cj_scene_destroy(scene);
        return cli_fail(cmd, "%s%s%s", scene_path ? scene_path : "demo", ": ", cj_last_error());
    }
    int rc = write_image(cmd, out, exr, img, signature);
    cj_render_image_destroy(img);
    cj_scene_destroy(scene);
    if (rc) return rc;
    if (report && cj_stage_report_json(&rep, stdout)) return cli_fail(cmd, "%s", cj_last_error());
    return 0;
}

#else

int cmd_trace(int argc, char **argv) {
    (void)argc;
    (void)argv;
    (void)trace_usage;
    return cli_fail("trace", "this build has no image output (configure with OpenImageIO)");
}

#endif
