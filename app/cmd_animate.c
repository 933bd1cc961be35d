/* casteljau animate: an animation document (keyframes, paths at controlled speed, a cloth) over
 * its scene, rendered frame by frame with our rasterizer. Contract: bad input -> one stderr line
 * (file:line: path ...), no frame written, exit status 2. Frames are a pure function of the frame
 * number and the simulation state, so any range renders the same pixels anywhere: checkpoints
 * carry the simulation state between processes. */
#define _POSIX_C_SOURCE 200809L /* open_memstream, fmemopen */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char animate_usage[] =
    "usage: casteljau animate ANIM.json -o frames/frame_%04d.png [--frames A:B] [--fps F]\n"
    "                         [--width W --height H] [--spp 1|4|16] [--threads N]\n"
    "                         [--checkpoint-in FILE] [--checkpoint-out PATTERN]\n"
    "                         [--checkpoint-every K] [--no-render] [--trace] [--stage-report]\n"
    "                         [--quiet]\n"
    "  ANIM.json           an animation document naming its scene (see\n"
    "                      scene/include/casteljau/anim_json.h): channels on scene fields,\n"
    "                      motion along paths at controlled speed, a cloth on colliders\n"
    "  -o PATTERN          one PNG per frame; PATTERN holds one %d (e.g. %04d) for the frame\n"
    "  -o FILM.mp4         instead, one film (.mp4 .mkv .mov: H.264; .webm: VP9; FFmpeg),\n"
    "                      or -o FILM.gif (as --gif FILM.gif)\n"
    "                      each frame encoded as it is rendered; width and height even\n"
    "  --quality Q         film quality 1..100 (default 55 = H.264 CRF 23; 100 near lossless)\n"
    "  --gif OUT.gif       also (or instead) one animated GIF of the range, looping, each frame\n"
    "                      quantised to its own 256 colours (libimagequant) and dithered\n"
    "  --dither D          GIF dithering level 0..1 (default 1; 0 = none, shows bands)\n"
    "  --frames A:B        frames A..B inclusive (default: the document's \"frames\")\n"
    "  --fps F             frames per second (default: the document's; the cloth takes\n"
    "                      steps_per_frame steps of 1/(F*steps) s per frame)\n"
    "  --width/--height/--spp/--threads   as in 'casteljau render'\n"
    "  --trace             render with the ray tracer ('casteljau trace') instead of the\n"
    "                      rasterizer (shadows, mirrors; slower); with the document's\n"
    "                      \"shutter\" it blurs what moves (motion blur, docs/light.md); the\n"
    "                      rasterizer ignores the shutter and draws the frame's instant\n"
    "  --checkpoint-in F   start from the simulation state saved in F (its frame <= A)\n"
    "  --checkpoint-out P  write the state after frame f to P with %d replaced by f, for every\n"
    "                      f in A..B that is a multiple of K (--checkpoint-every K) and for B\n"
    "  --no-render         simulate and write checkpoints only (no images)\n"
    "  --stage-report      print the last frame's stage reports (animation, renderer) as JSON\n"
    "  --quiet             no progress line and no summary on a terminal's stderr\n"
    "Splitting a long animation over processes: save the simulation state every K frames once,\n"
    "then render each range A..A+K-1 from the state of frame A, e.g. with K = 48 (GNU parallel;\n"
    "both commands copy and paste into a POSIX shell):\n"
    "  casteljau animate a.json --frames 0:239 --no-render --checkpoint-every 48 \\\n"
    "      --checkpoint-out 'ckpt_%04d.bin'\n"
    "  seq 0 48 192 | parallel 'casteljau animate a.json -o f_%04d.png \\\n"
    "      --frames {}:$(({} + 47)) --checkpoint-in ckpt_$(printf %04d {}).bin'\n"
    "(or one Slurm array task per range). A range rendered from a checkpoint is bit-identical\n"
    "to the same frames of one long run.\n";

#if defined(CJ_HAVE_PLOT)

#include "anim_gif.h"
#include "cli_progress.h"
#include "anim_video.h"
#include "cli_guard.h"
#include "error_internal.h"
#include "file_internal.h"
#include "json_write_internal.h"
#include "scene_cli.h"
#include "casteljau/anim_json.h"
#include "casteljau/image_io.h"
#include "casteljau/render.h"
#include "casteljau/renderer.h"
#include "casteljau/trace.h"
#include "casteljau/scene_json.h"
#include "casteljau/scene_textures.h"

#include <stdio.h>
#include <unistd.h>

/* A printf pattern with exactly one integer conversion (%d, %0Nd, %Nd) and no other '%'
 * (except "%%"). */
static int pattern_ok(const char *p) {
    int n = 0;
    for (const char *s = p; *s; ++s) {
        if (*s != '%') continue;
        if (s[1] == '%') {
            ++s;
            continue;
        }
        ++s;
        while (*s >= '0' && *s <= '9') ++s;
        if (*s != 'd') return 0;
        ++n;
    }
    return n == 1;
}

static void frame_name(const char *pattern, long frame, char *out, size_t size) {
    cli_frame_name(pattern, frame, out, size);
}

/* Where the frames go besides PNGs: a GIF and a film, each opened at the first frame. */
typedef struct anim_sinks {
    const char *gif_path, *film_path;
    anim_gif *gif;
    anim_video *film;
    double dither;
    long quality;
} anim_sinks;

/* The frame as opaque 8-bit sRGB, to a PNG (out may be NULL) and to the GIF and film. */
static int write_frame(const char *cmd, const char *out, anim_sinks *sinks, double fps,
                       const cj_render_image *img) {
    const char *gif_path = sinks->gif_path;
    anim_gif **gif = &sinks->gif;
    const size_t n = (size_t)img->width * (size_t)img->height;
    uint8_t *px = malloc(n * 4);
    if (!px) return cli_error(cmd, "out of memory for a %d x %d image", img->width, img->height);
    cj_status st = cj_render_image_to_srgb8(img, px, 0);
    for (size_t i = 0; i < n; ++i) px[4 * i + 3] = 255;
    if (!st && out) st = cj_image_write_png(out, img->width, img->height, px, 0);
    if (st) {
        free(px);
        return cli_error(cmd, "%s", cj_last_error());
    }
    char why[256];
    if (gif_path && !*gif) {
        const double cs = 100.0 / fps + 0.5; /* GIF delays are 16-bit hundredths */
        const int delay = cs > 65535.0 ? 65535 : cs < 2.0 ? 2 : (int)cs;
        *gif = anim_gif_open(gif_path, img->width, img->height, delay, sinks->dither, why,
                             (int)sizeof why);
        if (!*gif) {
            free(px);
            return cli_error(cmd, "%s", why);
        }
    }
    if (gif_path && anim_gif_add(*gif, px, why, (int)sizeof why)) {
        free(px);
        return cli_error(cmd, "%s: %s", gif_path, why);
    }
    if (sinks->film_path && !sinks->film)
        sinks->film = anim_video_open(sinks->film_path, img->width, img->height, fps,
                                      (int)sinks->quality, why, (int)sizeof why);
    if (sinks->film_path &&
        (!sinks->film || anim_video_add(sinks->film, px, why, (int)sizeof why))) {
        free(px);
        return cli_error(cmd, "%s: %s", sinks->film_path, why);
    }
    free(px);
    return 0;
}

static int save_checkpoint(const char *cmd, const cj_anim_doc *doc, const char *pattern,
                           long frame) {
    char path[4096];
    frame_name(pattern, frame, path, sizeof path);
    cj_atomic_file f;
    if (cj_atomic_open(&f, path)) return cli_error(cmd, "checkpoint: %s", cj_last_error());
    if (cj_anim_doc_save_state(doc, f.fp)) {
        cj_atomic_abandon(&f);
        return cli_error(cmd, "%s: %s", path, cj_last_error());
    }
    if (cj_atomic_commit(&f)) return cli_error(cmd, "checkpoint: %s", cj_last_error());
    return 0;
}

/* What each frame's renderer reused (the tessellation cache, or the tracer's BVHs). */
typedef struct reuse_row {
    long frame;
    double hits, misses;
} reuse_row;
typedef struct reuse_log {
    reuse_row *rows;
    size_t count, cap;
} reuse_log;

static double stage_value(const cj_stage_report *r, const char *stage, const char *key) {
    const cj_stage *s = cj_stage_report_find(r, stage);
    for (int i = 0; s && i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    return 0.0;
}

static int reuse_add(reuse_log *log, long frame, const cj_stage_report *r, int trace) {
    if (log->count == log->cap) {
        size_t cap = log->cap ? 2 * log->cap : 64;
        reuse_row *rows = realloc(log->rows, cap * sizeof *rows);
        if (!rows) return 1;
        log->rows = rows;
        log->cap = cap;
    }
    reuse_row *row = &log->rows[log->count++];
    row->frame = frame;
    row->hits = trace ? stage_value(r, "build_bvh", "bvh_reused")
                      : stage_value(r, "tessellate_patches", "cache_hits");
    row->misses = trace ? stage_value(r, "build_bvh", "bvh_built")
                        : stage_value(r, "tessellate_patches", "cache_misses");
    return 0;
}

/* The reuse log as JSON on f, printed by cJSON: {"frames": [{"frame", hits, misses}, ...]}. */
static cj_status reuse_print(const reuse_log *log, int trace, FILE *f) {
    cJSON *root = cJSON_CreateObject(), *frames = cJSON_CreateArray();
    int bad = !root || !frames || !cJSON_AddItemToObject(root, "frames", frames);
    if (bad) cJSON_Delete(frames);
    for (size_t i = 0; !bad && i < log->count; ++i) {
        cJSON *row = cJSON_CreateObject();
        bad = !row || !cJSON_AddItemToArray(frames, row);
        if (bad) cJSON_Delete(row);
        bad = bad || cj_json_add_number(row, "frame", (double)log->rows[i].frame) ||
              cj_json_add_number(row, trace ? "bvh_reused" : "cache_hits", log->rows[i].hits) ||
              cj_json_add_number(row, trace ? "bvh_built" : "cache_misses", log->rows[i].misses);
    }
    const cj_status st = bad ? cj_fail(CJ_ERR_NOMEM, "animate: out of memory (reuse log)")
                             : cj_json_print(root, 0, f, "animate");
    cJSON_Delete(root);
    return st;
}

int cmd_animate(int argc, char **argv) {
    const char *cmd = "animate";
    const char *doc_path = NULL, *out = NULL, *ck_in = NULL, *ck_out = NULL, *gif_path = NULL;
    anim_sinks sinks = {NULL, NULL, NULL, NULL, 1.0, ANIM_VIDEO_QUALITY_DEFAULT};
    long fa = -1, fb = -1, every = 0;
    double fps = 0;
    int no_render = 0, report = 0, trace = 0;
    cj_render_options opt = cj_render_options_defaults();
    enum {
        O_NO_RENDER,
        O_REPORT,
        O_TRACE,
        O_OUT,
        O_GIF,
        O_QUALITY,
        O_DITHER,
        O_FRAMES,
        O_FPS,
        O_WIDTH,
        O_HEIGHT,
        O_SPP,
        O_THREADS,
        O_CK_IN,
        O_CK_OUT,
        O_CK_EVERY
    };
    static const cli_opt opts[] = {
        {"--no-render", NULL, 0},       {"--stage-report", NULL, 0},  {"--trace", NULL, 0},
        {"--output", "-o", 1},          {"--gif", NULL, 1},           {"--quality", NULL, 1},
        {"--dither", NULL, 1},          {"--frames", NULL, 1},        {"--fps", NULL, 1},
        {"--width", NULL, 1},           {"--height", NULL, 1},        {"--spp", NULL, 1},
        {"--threads", NULL, 1},         {"--checkpoint-in", NULL, 1}, {"--checkpoint-out", NULL, 1},
        {"--checkpoint-every", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, cmd, animate_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    const char *v;
    int k, status;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        long lv;
        switch (k) {
        case CLI_POSITIONAL:
            if (doc_path) return cli_fail(cmd, "more than one animation ('%s', '%s')", doc_path, v);
            doc_path = v;
            break;
        case O_NO_RENDER:
            no_render = 1;
            break;
        case O_REPORT:
            report = 1;
            break;
        case O_TRACE:
            trace = 1;
            break;
        case O_OUT:
            out = v;
            break;
        case O_GIF:
            gif_path = v;
            break;
        case O_QUALITY:
            if (cli_parse_int(v, 1, 100, &sinks.quality))
                return cli_fail(cmd, "--quality '%s' is not an integer in 1..100", v);
            break;
        case O_DITHER:
            if (cli_parse_double(v, &sinks.dither) || !(sinks.dither >= 0 && sinks.dither <= 1))
                return cli_fail(cmd, "--dither '%s' must be a number in [0, 1]", v);
            break;
        case O_FRAMES: {
            const char *colon = strchr(v, ':');
            char first[32];
            if (!colon || (size_t)(colon - v) >= sizeof first)
                return cli_fail(cmd, "--frames '%s' must be A:B", v);
            memcpy(first, v, (size_t)(colon - v));
            first[colon - v] = 0;
            if (cli_parse_int(first, 0, 10000000, &fa) ||
                cli_parse_int(colon + 1, 0, 10000000, &fb) || fb < fa)
                return cli_fail(cmd, "--frames '%s' must be A:B with 0 <= A <= B", v);
            break;
        }
        case O_FPS:
            if (cli_parse_double(v, &fps) || !(fps >= CJ_ANIM_MIN_FPS && fps <= CJ_ANIM_MAX_FPS))
                return cli_fail(cmd, "--fps '%s' must be a number in [%g, %g]", v, CJ_ANIM_MIN_FPS,
                                CJ_ANIM_MAX_FPS);
            break;
        case O_WIDTH:
        case O_HEIGHT:
            if (cli_parse_int(v, 1, 32768, &lv))
                return cli_fail(cmd, "%s '%s' is not an integer in 1..32768", opts[k].name, v);
            *(k == O_WIDTH ? &opt.width : &opt.height) = (int)lv;
            break;
        case O_SPP:
            if (cli_parse_int(v, 1, 16, &lv) || (lv != 1 && lv != 4 && lv != 16))
                return cli_fail(cmd, "--spp '%s' must be 1, 4 or 16", v);
            opt.spp = (int)lv;
            break;
        case O_THREADS:
            if (cli_parse_int(v, 1, 1024, &lv))
                return cli_fail(cmd, "--threads '%s' is not an integer in 1..1024", v);
            opt.threads = (int)lv;
            break;
        case O_CK_IN:
            ck_in = v;
            break;
        case O_CK_OUT:
            ck_out = v;
            break;
        case O_CK_EVERY:
            if (cli_parse_int(v, 1, 10000000, &every))
                return cli_fail(cmd, "--checkpoint-every '%s' is not a positive integer", v);
            break;
        }
    }
    if (status >= 0) return status;
    if (!doc_path) return cli_fail(cmd, "no animation: give ANIM.json (try --help)");
    if (out && anim_video_is_film(out)) { /* -o film.mp4: one film instead of PNGs */
        sinks.film_path = out;
        out = NULL;
        if (no_render) return cli_fail(cmd, "a film needs rendering (drop --no-render)");
    }
    if (out && !gif_path && anim_gif_is_gif(out)) { /* -o film.gif: as --gif */
        gif_path = out;
        out = NULL;
    }
    sinks.gif_path = gif_path;
    if (!no_render && !out && !gif_path && !sinks.film_path)
        return cli_fail(cmd, "no output: give -o frames/frame_%%04d.png or --gif OUT.gif");
    if (no_render && gif_path) return cli_fail(cmd, "--gif needs rendering (drop --no-render)");
    if (out && !pattern_ok(out))
        return cli_fail(cmd, "output pattern '%s' must hold exactly one %%d (e.g. %%04d)", out);
    if (out && !cli_has_ext(out, ".png"))
        return cli_fail(cmd, "output pattern '%s' must end in .png (the frames are PNG images)",
                        out);
    if (gif_path && !cli_has_ext(gif_path, ".gif"))
        return cli_fail(cmd, "--gif '%s' must end in .gif", gif_path);
    if (ck_out && !pattern_ok(ck_out))
        return cli_fail(cmd, "checkpoint pattern '%s' must hold exactly one %%d", ck_out);
    if (every && !ck_out) return cli_fail(cmd, "--checkpoint-every needs --checkpoint-out");

    cj_anim_doc *doc = NULL;
    const cj_status load_st = cj_anim_doc_load(doc_path, &doc);
    if (load_st) return cli_fail_status(cmd, load_st, "%s", cj_last_error());
    int rc = 0;
    const double t0 = cj_clock_seconds();
    long written = 0;
    cli_progress pr; /* by frame, on a terminal; Ctrl-C stops after the frame being drawn */
    cli_progress_begin(&pr, cmd, "frames");
    cj_scene *scene = NULL;
    char *snapshot = NULL;
    /* one renderer for the whole animation: unchanged patches keep their tessellation (or BVH),
     * the threads, tile buffers and the image live from the first frame to the last */
    cj_renderer *ren = NULL;
    cj_render_image *img = NULL;
    cj_xform3 *motion = NULL; /* the shutter's poses of every node (motion blur) */
    reuse_log reuse = {NULL, 0, 0};
    if (fps > 0 && cj_anim_doc_set_fps(doc, fps, "--fps")) {
        rc = cli_fail(cmd, "%s", cj_last_error());
        goto done;
    }
    if (fa < 0) {
        fa = doc->frame_first;
        fb = doc->frame_last;
    }
    /* Every destination is checked before any work (as render does). */
    char name[4096];
    for (int end = 0; out && end < 2 && !rc; ++end) {
        frame_name(out, end ? fb : fa, name, sizeof name);
        rc = cli_check_output(cmd, "frame", name);
    }
    if (!rc && gif_path) rc = cli_check_output(cmd, "GIF", gif_path);
    if (!rc && sinks.film_path) rc = cli_check_output(cmd, "film", sinks.film_path);
    for (int end = 0; ck_out && end < 2 && !rc; ++end) {
        frame_name(ck_out, end ? fb : fa, name, sizeof name);
        rc = cli_check_output(cmd, "checkpoint", name);
    }
    if (rc) goto done;
    if (!no_render) {
        cj_renderer_options ro = cj_renderer_options_defaults();
        ro.render = opt;
        if (cj_renderer_create(&ro, NULL, &ren)) {
            rc = cli_fail(cmd, "%s", cj_last_error());
            goto done;
        }
    }
    if (!doc->scene_path[0]) {
        rc = cli_fail(cmd, "%s: the document names no \"scene\"", doc_path);
        goto done;
    }
    if ((rc = cli_load_scene(cmd, doc->scene_path, &scene))) goto done;
    if (cj_anim_doc_attach(doc, scene)) {
        rc = cli_fail(cmd, "%s", cj_last_error()); /* names the document (and line) already */
        goto done;
    }
    if (ck_in) {
        char *bytes = NULL;
        size_t len = 0;
        cj_status st = cj_file_read_all(ck_in, CJ_FILE_MAX_BYTES, "checkpoint", &bytes, &len);
        if (st) {
            rc = cli_fail_status(cmd, st, "%s", cj_last_error());
            goto done;
        }
        FILE *f = len ? fmemopen(bytes, len, "rb") : NULL;
        st = f ? cj_anim_doc_load_state(doc, f) : CJ_ERR_PARSE;
        if (f) fclose(f);
        free(bytes);
        if (st) {
            rc = cli_fail_status(cmd, st, "%s: %s", ck_in,
                                 len ? cj_last_error() : "empty, not a checkpoint");
            goto done;
        }
        if (doc->sim_frame > fa) {
            rc = cli_fail(cmd, "%s holds frame %ld, after the first frame %ld", ck_in,
                          doc->sim_frame, fa);
            goto done;
        }
    }
    /* Every input is read now (document, scene, its textures and geometry files, checkpoint):
     * no output may be one of them. */
    if ((out && (rc = cli_guard_pattern(cmd, "-o", out, fa, fb))) ||
        (ck_out && (rc = cli_guard_pattern(cmd, "--checkpoint-out", ck_out, fa, fb))) ||
        (gif_path && (rc = cli_guard_output(cmd, "--gif", gif_path))) ||
        (sinks.film_path && (rc = cli_guard_output(cmd, "-o", sinks.film_path))))
        goto done;
    /* Validate every frame's pose before writing anything: posing depends on t alone. */
    for (long f = fa; f <= fb; ++f) {
        cj_status st = cj_anim_pose(scene, doc->anim, (double)f / doc->fps, NULL);
        if (!st) st = cj_scene_check(scene);
        if (st) {
            rc = cli_fail(cmd, "%s: frame %ld (t = %g s): %s", doc_path, f, (double)f / doc->fps,
                          cj_last_error());
            goto done;
        }
    }
    /* A simulation that blows up can only be found by simulating: run it over the range first
     * (from a snapshot of the state, restored after), so that a failure leaves no frame. */
    if (!no_render && (doc->cloth || doc->particles)) {
        size_t snap_len = 0;
        FILE *ms = open_memstream(&snapshot, &snap_len);
        cj_status st = ms ? cj_anim_doc_save_state(doc, ms) : CJ_ERR_NOMEM;
        if (ms && fclose(ms) != 0 && !st) st = CJ_ERR_NOMEM;
        if (st) {
            rc = cli_error(cmd, "no memory for a snapshot of the simulation");
            goto done;
        }
        long f = fa;
        for (; f <= fb && !st; ++f) {
            st = cj_anim_doc_frame(doc, scene, f, NULL);
            if (st) break;
            if ((st = cj_scene_check(scene))) {
                char msg[512];
                snprintf(msg, sizeof msg, "%s", cj_last_error());
                st = cj_fail(st, "%s: frame %ld: the simulation left the scene's limits: %s",
                             doc_path, f, msg);
            }
        }
        if (st) {
            rc = cli_fail_status(cmd, st, "%s", cj_last_error());
            goto done;
        }
        FILE *rs = fmemopen(snapshot, snap_len, "rb");
        st = rs ? cj_anim_doc_load_state(doc, rs) : CJ_ERR_NOMEM;
        if (rs) fclose(rs);
        if (st) {
            rc = cli_error(cmd, "restoring the simulation snapshot failed: %s", cj_last_error());
            goto done;
        }
    }
    const int blur = !no_render && trace && doc->has_shutter;
    if (!no_render && !trace && doc->has_shutter)
        cli_warn(cmd, "%s: the rasterizer ignores the shutter (motion blur needs --trace)",
                 doc_path);
    if (blur) {
        const size_t n = (size_t)doc->shutter_poses * cj_scene_node_count(scene);
        motion = malloc(n * sizeof *motion);
        if (!motion) {
            rc = cli_error(cmd, "no memory for %d poses of the shutter", doc->shutter_poses);
            goto done;
        }
    }
    for (long f = fa; f <= fb && !rc; ++f) {
        cj_stage_report anim_rep, ren_rep;
        cj_stage_report_init(&anim_rep, "animate");
        if (cj_anim_doc_frame(doc, scene, f, &anim_rep)) {
            rc = cli_error(cmd, "%s: frame %ld: %s", doc_path, f, cj_last_error());
            break;
        }
        if (blur) { /* the node transforms over the shutter, then the frame's pose again */
            const double t = (double)f / doc->fps;
            const cj_motion m = {doc->shutter_poses, cj_scene_node_count(scene), motion};
            if (cj_anim_sample_motion(scene, doc->anim, t + doc->shutter[0] / doc->fps,
                                      t + doc->shutter[1] / doc->fps, doc->shutter_poses, motion) ||
                cj_anim_pose(scene, doc->anim, t, NULL) || cj_renderer_set_motion(ren, &m)) {
                rc = cli_error(cmd, "%s: frame %ld: shutter: %s", doc_path, f, cj_last_error());
                break;
            }
        }
        if (!no_render) {
            const cj_status rs = cj_renderer_draw(
                ren, scene, trace ? CJ_BACKEND_TRACE : CJ_BACKEND_RASTER, 0, &img, &ren_rep);
            if (rs) {
                rc = cli_error(cmd, "%s: frame %ld: %s", doc_path, f, cj_last_error());
                break;
            }
            if (report && reuse_add(&reuse, f, &ren_rep, trace)) {
                rc = cli_error(cmd, "out of memory for the frame report");
                break;
            }
            if (out) frame_name(out, f, name, sizeof name);
            rc = write_frame(cmd, out ? name : NULL, &sinks, doc->fps, img);
        }
        if (!rc && ck_out && (f == fb || (every && f % every == 0)))
            rc = save_checkpoint(cmd, doc, ck_out, f);
        if (!rc && !no_render) ++written;
        if (cli_progress_label(&pr, (uint64_t)(f - fa + 1), (uint64_t)(fb - fa + 1), NULL) && !rc &&
            f < fb) {
            cli_error(cmd, "stopped by Ctrl-C after frame %ld (frames %ld..%ld done)", f, fa, f);
            rc = 130;
            break;
        }
        if (!rc && report && f == fb) {
            cj_stage_report_json(&anim_rep, stdout);
            fputc('\n', stdout);
            if (!no_render) {
                cj_stage_report_json(&ren_rep, stdout);
                fputc('\n', stdout);
                if (reuse_print(&reuse, trace, stdout)) rc = cli_error(cmd, "%s", cj_last_error());
            }
        }
    }
done:
    cli_progress_end(&pr);
    cj_render_image_destroy(img);
    cj_renderer_destroy(ren);
    free(reuse.rows);
    free(snapshot);
    free(motion);
    if (sinks.gif && rc) {
        anim_gif_abandon(sinks.gif); /* an old GIF stays as it was */
    } else if (sinks.gif) {
        char why[512];
        if (anim_gif_close(sinks.gif, why, (int)sizeof why)) rc = cli_error(cmd, "%s", why);
    }
    if (sinks.film) {
        char why[256];
        if (anim_video_close(sinks.film, why, (int)sizeof why) && !rc)
            rc = cli_error(cmd, "%s: %s", sinks.film_path, why);
    }
    if (!rc && (!no_render || ck_out)) {
        char what[4200], detail[64];
        const char *file = sinks.film_path ? sinks.film_path : gif_path;
        snprintf(detail, sizeof detail, "%ld frame%s", written, written == 1 ? "" : "s");
        if (file)
            snprintf(what, sizeof what, "%s%s%s", file, out && file ? " and " : "",
                     out && file ? out : "");
        else
            snprintf(what, sizeof what, "%s", out ? out : "checkpoints");
        cli_summary(cmd, what, file, no_render ? NULL : detail, t0);
    }
    cj_scene_destroy(scene);
    cj_anim_doc_destroy(doc);
    return rc;
}

#else

int cmd_animate(int argc, char **argv) {
    (void)argc;
    (void)argv;
    (void)animate_usage;
    return cli_fail("animate", "this build has no image output (configure with OpenImageIO)");
}

#endif
