/* `casteljau animate` films and GIFs (issue 25): the .mp4 (H.264) and .webm (VP9) films are
 * decoded back through libavformat/libavcodec and checked for frame count, size, frame rate and
 * the colours of a frame against the PNG of the same frame; an odd size is refused with a
 * message; GIF palettes from libimagequant keep more of a smooth gradient's colours with
 * dithering than without. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli_run.h"
#include "casteljau/image_io.h"

#include <gif_lib.h>
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char dir[256];

static void write_file(const char *name, const char *text) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* A red ball moving across a blue background, 12 frames at 12 fps. */
static const char SCENE[] =
    "{\"camera\": {\"eye\": [0, 2, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0]},\n"
    " \"settings\": {\"width\": 96, \"height\": 72, \"spp\": 4, \"background\": [0.1, 0.2, 0.5]},\n"
    " \"lights\": [{\"type\": \"ambient\", \"intensity\": 0.2},\n"
    "            {\"type\": \"point\", \"position\": [3, 5, 4]}],\n"
    " \"materials\": [{\"name\": \"red\", \"color\": [0.9, 0.2, 0.1]}],\n"
    " \"objects\": [{\"name\": \"ball\", \"geometry\": {\"type\": \"sphere\", \"radius\": 1},\n"
    "              \"material\": \"red\"}]}\n";
static const char ANIM[] =
    "{\"scene\": \"scene.json\", \"fps\": 12, \"frames\": [0, 11],\n"
    " \"channels\": [{\"target\": \"nodes[\\\"ball\\\"].translate\", \"times\": [0, 1],\n"
    "                \"values\": [[-1, 0, 0], [1, 0, 0]]}]}\n";

/* Smooth shading in many hues: a sphere on a floor under red, green and blue lights. */
static const char GRADIENT_SCENE[] =
    "{\"camera\": {\"eye\": [0, 1.5, 4], \"look_at\": [0, 0.3, 0], \"up\": [0, 1, 0]},\n"
    " \"settings\": {\"width\": 160, \"height\": 120, \"spp\": 16},\n"
    " \"lights\": [{\"type\": \"ambient\", \"intensity\": 0.05},\n"
    "   {\"type\": \"point\", \"position\": [-3, 2, 2], \"color\": [1, 0.2, 0.1]},\n"
    "   {\"type\": \"point\", \"position\": [3, 2, 2], \"color\": [0.1, 0.3, 1]},\n"
    "   {\"type\": \"point\", \"position\": [0, 3, -2], \"color\": [0.2, 1, 0.2]}],\n"
    " \"materials\": [{\"name\": \"m\", \"color\": [0.9, 0.9, 0.9], \"ks\": 0.3, \"alpha\": 12}],\n"
    " \"objects\": [{\"name\": \"ball\", \"geometry\": {\"type\": \"sphere\", \"radius\": 0.8},\n"
    "              \"material\": \"m\"},\n"
    "   {\"name\": \"floor\", \"geometry\": {\"type\": \"planar\", \"origin\": [-6, -0.8, 3],\n"
    "    \"edge_u\": [12, 0, 0], \"edge_v\": [0, 0, -12]}, \"material\": \"m\"}]}\n";
static const char GRADIENT_ANIM[] = "{\"scene\": \"gscene.json\", \"fps\": 10, \"frames\": [0, "
                                    "1]}\n";

static void run(const char *args, int want_status, cj_cli_result *r) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd %s && %s animate %s", dir, CJ_CLI, args);
    assert_int_equal(cj_cli_shell(cmd, r), 0);
    if (r->status != want_status)
        fail_msg("'%s': status %d (want %d), stderr: %s", args, r->status, want_status, r->err);
}

typedef struct decoded {
    int frames, width, height;
    double fps;
    uint8_t *rgba; /* frame `keep`, top-down RGBA */
} decoded;

/* Decodes every frame of a film; keeps frame `keep` as RGBA (BT.601 limited range, the
 * conversion the writer used). */
static void decode(const char *path, int keep, decoded *d) {
    AVFormatContext *fmt = NULL;
    memset(d, 0, sizeof *d);
    assert_int_equal(avformat_open_input(&fmt, path, NULL, NULL), 0);
    assert_true(avformat_find_stream_info(fmt, NULL) >= 0);
    const AVCodec *codec = NULL;
    const int si = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    assert_true(si >= 0 && codec);
    AVCodecContext *dec = avcodec_alloc_context3(codec);
    assert_non_null(dec);
    assert_true(avcodec_parameters_to_context(dec, fmt->streams[si]->codecpar) >= 0);
    assert_int_equal(avcodec_open2(dec, codec, NULL), 0);
    d->fps = av_q2d(fmt->streams[si]->avg_frame_rate);
    AVPacket *pkt = av_packet_alloc();
    AVFrame *frame = av_frame_alloc();
    int flushing = 0;
    for (;;) {
        if (!flushing) {
            if (av_read_frame(fmt, pkt) < 0) {
                flushing = 1;
                avcodec_send_packet(dec, NULL);
            } else {
                if (pkt->stream_index == si) avcodec_send_packet(dec, pkt);
                av_packet_unref(pkt);
            }
        }
        int got;
        while ((got = avcodec_receive_frame(dec, frame)) == 0) {
            d->width = frame->width;
            d->height = frame->height;
            if (d->frames == keep) {
                d->rgba = malloc((size_t)4 * frame->width * frame->height);
                assert_non_null(d->rgba);
                struct SwsContext *sws =
                    sws_getContext(frame->width, frame->height, frame->format, frame->width,
                                   frame->height, AV_PIX_FMT_RGBA, SWS_BICUBIC, NULL, NULL, NULL);
                assert_non_null(sws);
                uint8_t *dst[1] = {d->rgba};
                const int stride[1] = {4 * frame->width};
                sws_scale(sws, (const uint8_t *const *)frame->data, frame->linesize, 0,
                          frame->height, dst, stride);
                sws_freeContext(sws);
            }
            ++d->frames;
        }
        if (flushing && got == AVERROR_EOF) break;
    }
    av_frame_free(&frame);
    av_packet_free(&pkt);
    avcodec_free_context(&dec);
    avformat_close_input(&fmt);
}

static void check_film(const char *ext, double max_mean_diff) {
    cj_cli_result r;
    char args[256], path[512], png[512];
    snprintf(args, sizeof args, "a.json -o film.%s --quality 90 --quiet", ext);
    run(args, 0, &r);
    cj_cli_result_free(&r);
    snprintf(path, sizeof path, "%s/film.%s", dir, ext);
    decoded d;
    decode(path, 6, &d);
    printf("film.%s: %d frames of %d x %d at %.3g fps\n", ext, d.frames, d.width, d.height, d.fps);
    assert_int_equal(d.frames, 12);
    assert_int_equal(d.width, 96);
    assert_int_equal(d.height, 72);
    assert_true(fabs(d.fps - 12.0) < 1e-6);
    assert_non_null(d.rgba);
    /* frame 6 against the PNG of frame 6 (bottom-up rows from cj_image_read) */
    snprintf(png, sizeof png, "%s/f_06.png", dir);
    int w, h;
    uint8_t *ref = NULL;
    assert_int_equal(cj_image_read(png, &w, &h, &ref), 0);
    assert_int_equal(w, 96);
    assert_int_equal(h, 72);
    double sum = 0;
    int worst = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const int a = d.rgba[4 * ((size_t)y * w + x) + c];
                const int b = ref[4 * ((size_t)(h - 1 - y) * w + x) + c];
                sum += abs(a - b);
                if (abs(a - b) > worst) worst = abs(a - b);
            }
    const double mean = sum / (3.0 * w * h);
    /* the ball is red where the PNG is red, the background blue */
    const uint8_t *centre = d.rgba + 4 * ((size_t)(h / 2) * w + w / 2 + 6);
    const uint8_t *corner = d.rgba + 4 * ((size_t)2 * w + 2);
    printf("  frame 6 vs its PNG: mean |difference| %.2f levels (worst %d); ball centre "
           "(%d,%d,%d), corner (%d,%d,%d)\n",
           mean, worst, centre[0], centre[1], centre[2], corner[0], corner[1], corner[2]);
    assert_true(mean < max_mean_diff);
    assert_true(centre[0] > 2 * centre[2] && centre[0] > 100);
    assert_true(corner[2] > 2 * corner[0] && corner[2] > 120);
    cj_image_free(ref);
    free(d.rgba);
}

static void test_films(void **state) {
    (void)state;
    write_file("scene.json", SCENE);
    write_file("a.json", ANIM);
    cj_cli_result r;
    run("a.json -o f_%02d.png --quiet", 0, &r);
    cj_cli_result_free(&r);
    check_film("mp4", 2.5);
    check_film("webm", 2.5);
    /* lower quality: a smaller file */
    run("a.json -o small.mp4 --quality 10 --quiet", 0, &r);
    cj_cli_result_free(&r);
    char p1[512], p2[512];
    snprintf(p1, sizeof p1, "%s/film.mp4", dir);
    snprintf(p2, sizeof p2, "%s/small.mp4", dir);
    FILE *a = fopen(p1, "rb"), *b = fopen(p2, "rb");
    assert_non_null(a);
    assert_non_null(b);
    fseek(a, 0, SEEK_END);
    fseek(b, 0, SEEK_END);
    printf("--quality 90: %ld bytes, --quality 10: %ld bytes\n", ftell(a), ftell(b));
    assert_true(ftell(b) < ftell(a));
    fclose(a);
    fclose(b);
    /* odd sizes cannot be 4:2:0: refused with a message naming the size */
    run("a.json -o odd.mp4 --width 95 --quiet", 1, &r);
    printf("odd width: %s", r.err);
    assert_non_null(strstr(r.err, "even"));
    assert_non_null(strstr(r.err, "95 x 72"));
    cj_cli_result_free(&r);
    run("a.json -o bad.mp4 --quality 0 --quiet", 2, &r);
    assert_non_null(strstr(r.err, "--quality"));
    cj_cli_result_free(&r);
}

enum { CROP = 40, CROP_X = 4, CROP_Y = 76 }; /* the floor's gradient, top-down rows */

/* The crop of frame 0 of a GIF as RGB. */
static void gif_crop(const char *name, uint8_t rgb[CROP][CROP][3]) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    int err = 0;
    GifFileType *g = DGifOpenFileName(p, &err);
    assert_non_null(g);
    assert_int_equal(DGifSlurp(g), GIF_OK);
    assert_true(g->ImageCount >= 1);
    const SavedImage *im = &g->SavedImages[0];
    const ColorMapObject *map = im->ImageDesc.ColorMap ? im->ImageDesc.ColorMap : g->SColorMap;
    assert_non_null(map);
    for (int y = 0; y < CROP; ++y)
        for (int x = 0; x < CROP; ++x) {
            const int i = (CROP_Y + y) * im->ImageDesc.Width + CROP_X + x;
            const GifColorType c = map->Colors[im->RasterBits[i]];
            rgb[y][x][0] = c.Red, rgb[y][x][1] = c.Green, rgb[y][x][2] = c.Blue;
        }
    DGifCloseFile(g, &err);
}

static void png_crop(const char *name, uint8_t rgb[CROP][CROP][3]) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    int w, h;
    uint8_t *px = NULL;
    assert_int_equal(cj_image_read(p, &w, &h, &px), 0);
    for (int y = 0; y < CROP; ++y)
        for (int x = 0; x < CROP; ++x)
            memcpy(rgb[y][x], px + 4 * ((size_t)(h - 1 - CROP_Y - y) * w + CROP_X + x), 3);
    cj_image_free(px);
}

static int distinct_colours(uint8_t rgb[CROP][CROP][3]) {
    static uint32_t seen[CROP * CROP];
    int count = 0;
    for (int y = 0; y < CROP; ++y)
        for (int x = 0; x < CROP; ++x) {
            const uint32_t key =
                (uint32_t)rgb[y][x][0] << 16 | (uint32_t)rgb[y][x][1] << 8 | rgb[y][x][2];
            int found = 0;
            for (int i = 0; i < count && !found; ++i) found = seen[i] == key;
            if (!found) seen[count++] = key;
        }
    return count;
}

/* Mean |difference| of 4x4 box averages: what the eye sees from a little further away, where
 * dithering's mixtures reproduce the gradient and banding does not. */
static double smoothed_error(uint8_t a[CROP][CROP][3], uint8_t b[CROP][CROP][3]) {
    double sum = 0;
    int n = 0;
    for (int y = 0; y + 4 <= CROP; y += 4)
        for (int x = 0; x + 4 <= CROP; x += 4)
            for (int c = 0; c < 3; ++c) {
                int sa = 0, sb = 0;
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 4; ++i) sa += a[y + j][x + i][c], sb += b[y + j][x + i][c];
                sum += abs(sa - sb) / 16.0;
                ++n;
            }
    return sum / n;
}

static void test_gif_dithering(void **state) {
    (void)state;
    write_file("gscene.json", GRADIENT_SCENE);
    write_file("g.json", GRADIENT_ANIM);
    cj_cli_result r;
    run("g.json --frames 0:0 -o g_%d.png --gif dithered.gif --quiet", 0, &r);
    cj_cli_result_free(&r);
    run("g.json --frames 0:0 --gif plain.gif --dither 0 --quiet", 0, &r);
    cj_cli_result_free(&r);
    static uint8_t png[CROP][CROP][3], plain[CROP][CROP][3], dithered[CROP][CROP][3];
    png_crop("g_0.png", png);
    gif_crop("plain.gif", plain);
    gif_crop("dithered.gif", dithered);
    const int n_png = distinct_colours(png), n_plain = distinct_colours(plain),
              n_dith = distinct_colours(dithered);
    const double e_plain = smoothed_error(plain, png), e_dith = smoothed_error(dithered, png);
    printf("%dx%d crop of a lit floor: %d colours in the PNG; GIF without dithering %d "
           "colours, 4x4-average error %.3f levels; with dithering %d colours, error %.3f\n",
           CROP, CROP, n_png, n_plain, e_plain, n_dith, e_dith);
    assert_true(n_png > 256);
    assert_true(n_dith > n_plain);
    assert_true(e_dith < 0.75 * e_plain);
    /* -o OUT.gif is --gif OUT.gif */
    run("g.json --frames 0:0 -o same.gif --quiet", 0, &r);
    cj_cli_result_free(&r);
    static uint8_t same[CROP][CROP][3];
    gif_crop("same.gif", same);
    assert_memory_equal(same, dithered, sizeof same);
    printf("-o same.gif: the same GIF as --gif\n");
    run("g.json --gif x.gif --dither 2 --quiet", 2, &r);
    assert_non_null(strstr(r.err, "--dither"));
    cj_cli_result_free(&r);
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/cj_anim_video_XXXXXX");
    if (!mkdtemp(dir)) return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_films),
        cmocka_unit_test(test_gif_dithering),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) return 1;
    return rc;
}
