/* Contract of `casteljau animate`: frames A..B written as numbered PNGs; a range rendered from a
 * checkpoint is byte-identical to the same frames of one long run; bad input (keys out of
 * order, a channel on a field that does not exist, a bad step, a broken pattern) gives one
 * stderr line naming the file, exit status 2 and no frame. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli_run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[256];

static void write_file(const char *name, const char *text) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static const char SCENE[] =
    "{\"camera\": {\"eye\": [0, 2, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0]},\n"
    " \"settings\": {\"width\": 48, \"height\": 36, \"spp\": 1},\n"
    " \"lights\": [{\"type\": \"point\", \"position\": [3, 5, 4]}],\n"
    " \"objects\": [{\"name\": \"ball\", \"geometry\": {\"type\": \"sphere\", \"radius\": 1}}]}\n";

static const char ANIM[] =
    "{\"scene\": \"scene.json\", \"fps\": 12, \"frames\": [0, 9],\n"
    " \"gravity\": [0, -9.81, 0],\n"
    " \"colliders\": {\"spheres\": [{\"center\": [0, 0, 0], \"radius\": 1.02}]},\n"
    " \"cloth\": {\"grid\": [8, 8], \"corner\": [-1.2, 1.3, 1.2], \"edge_u\": [2.4, 0, 0],\n"
    "           \"edge_v\": [0, 0, -2.4], \"steps_per_frame\": 2},\n"
    " \"particles\": {\"capacity\": 40, \"seed\": 3, \"restitution\": 0.5, \"radius\": 0.05,\n"
    "   \"emitters\": [{\"position\": [0, 2.5, 0], \"rate\": 60, \"speed\": 2,\n"
    "   \"spread\": 0.8, \"direction\": [0, 1, 0], \"lifetime\": 2}]},\n"
    " \"channels\": [\n"
    "  {\"target\": \"camera.eye\", \"path\": {\"points\": [[0, 2, 5], [5, 2, 0], [0, 2, -5],\n"
    "   [-5, 2, 0]], \"closed\": true}, \"duration\": 1, \"ease\": \"smoothstep\"},\n"
    "  {\"target\": \"nodes[\\\"ball\\\"].scale\", \"times\": [0, 0.5],\n"
    "   \"values\": [[1, 1, 1], [0.9, 0.9, 0.9]]}]}\n";

static int count_frames(const char *prefix) {
    int n = 0;
    for (int f = 0; f < 20; ++f) {
        char p[512];
        snprintf(p, sizeof p, "%s/%s_%04d.png", dir, prefix, f);
        n += access(p, F_OK) == 0;
    }
    return n;
}

static int same_file(const char *a, const char *b) {
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb;
    while (same) {
        const int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb) same = 0;
        if (ca == EOF || cb == EOF) break;
    }
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return same;
}

static void run(const char *args, int want_status, cj_cli_result *r) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd %s && %s animate %s", dir, CJ_CLI, args);
    assert_int_equal(cj_cli_shell(cmd, r), 0);
    if (r->status != want_status)
        fail_msg("'%s': status %d (want %d), stderr: %s", args, r->status, want_status, r->err);
}

static void test_frames_and_checkpoints(void **state) {
    (void)state;
    write_file("scene.json", SCENE);
    write_file("a.json", ANIM);
    cj_cli_result r;
    run("a.json -o long_%04d.png --quiet --checkpoint-out ck_%04d.bin --checkpoint-every 4", 0, &r);
    cj_cli_result_free(&r);
    assert_int_equal(count_frames("long"), 10);
    run("a.json -o part_%04d.png --frames 4:9 --quiet --checkpoint-in ck_0004.bin", 0, &r);
    cj_cli_result_free(&r);
    assert_int_equal(count_frames("part"), 6);
    int same = 0;
    for (int f = 4; f <= 9; ++f) {
        char a[512], b[512];
        snprintf(a, sizeof a, "%s/long_%04d.png", dir, f);
        snprintf(b, sizeof b, "%s/part_%04d.png", dir, f);
        same += same_file(a, b);
    }
    /* frames differ from each other (the cloth falls, the camera moves) */
    char a0[512], a9[512];
    snprintf(a0, sizeof a0, "%s/long_0000.png", dir);
    snprintf(a9, sizeof a9, "%s/long_0009.png", dir);
    assert_false(same_file(a0, a9));
    printf("10 frames rendered (cloth + particles + camera path); frames 4..9 resumed from the "
           "checkpoint of frame 4 in another process: %d/6 byte-identical PNGs\n",
           same);
    assert_int_equal(same, 6);
    run("a.json --frames 0:3 --gif a.gif --quiet", 0, &r);
    cj_cli_result_free(&r);
    char gp[512], head[7] = {0};
    snprintf(gp, sizeof gp, "%s/a.gif", dir);
    FILE *g = fopen(gp, "rb");
    assert_non_null(g);
    assert_int_equal(fread(head, 1, 6, g), 6);
    fclose(g);
    assert_string_equal(head, "GIF89a");
    printf("--gif wrote an animated GIF89a\n");
    run("a.json --frames 9:9 --no-render --stage-report --quiet", 0, &r);
    assert_non_null(strstr(r.out, "\"name\":\"spring_forces\",\"ran\":true"));
    assert_non_null(strstr(r.out, "\"name\":\"particle_pass\",\"ran\":true"));
    assert_non_null(strstr(r.out, "\"name\":\"flocking\",\"ran\":false"));
    printf("stage report of frame 9: spring forces and particle pass ran, flocking left out\n");
    cj_cli_result_free(&r);
    /* one renderer for the animation: a line of each frame's tessellation cache hits/misses */
    run("a.json --frames 0:3 -o rep_%04d.png --stage-report --quiet", 0, &r);
    const char *frames = strstr(r.out, "{\"frames\":[{\"frame\":0,\"cache_hits\":0,");
    assert_non_null(frames);
    int rows = 0;
    for (const char *p = frames; (p = strstr(p, "\"cache_misses\"")) != NULL; ++p) ++rows;
    assert_int_equal(rows, 4);
    printf("--stage-report with rendering: one reuse row per frame (4 rows, frame 0 cold)\n");
    cj_cli_result_free(&r);
}

static void expect_bad(const char *doc, const char *args, const char *needle) {
    write_file("bad.json", doc);
    cj_cli_result r;
    char full[512];
    snprintf(full, sizeof full, "bad.json -o bad_%%04d.png --quiet %s", args);
    run(full, 2, &r);
    const char *nl = strchr(r.err, '\n');
    if (!strstr(r.err, needle) || !nl || nl[1] != '\0')
        fail_msg("expected one stderr line mentioning '%s', got: %s", needle, r.err);
    printf("  %s", r.err);
    cj_cli_result_free(&r);
    assert_int_equal(count_frames("bad"), 0);
}

static void test_bad_input(void **state) {
    (void)state;
    write_file("scene.json", SCENE);
    printf("bad input: exit 2, one line, no frame:\n");
    expect_bad("{\"scene\": \"scene.json\", \"channels\": [\n"
               " {\"target\": \"camera.eye\", \"times\": [0, 1, 0.5],\n"
               "  \"values\": [[0,2,5],[1,2,5],[2,2,5]]}]}\n",
               "", "bad.json:2: channels[0]: channel 0 (camera.eye): key 2: time 0.5 is not after");
    expect_bad("{\"scene\": \"scene.json\", \"channels\": [\n"
               " {\"target\": \"nodes[3].translate\", \"times\": [0], \"values\": [[0,0,0]]}]}\n",
               "", "bad.json:2: channel 0: nodes[3].translate: index 3 does not exist");
    expect_bad("{\"scene\": \"scene.json\", \"channels\": [\n"
               " {\"target\": \"camera.eye\", \"times\": [-1], \"values\": [[0,2,5]]}]}\n",
               "", "negative time");
    expect_bad("{\"scene\": \"scene.json\", \"fps\": 24, \"cloth\": {\"grid\": [4, 4],\n"
               " \"colour\": [1, 0, 0]}}\n",
               "", "bad.json:2: cloth.colour is not a known key");
    expect_bad("{\"scene\": \"scene.json\"}\n", "--fps -2", "--fps '-2'");
    expect_bad("{\"scene\": \"scene.json\"}\n", "--frames 5:2", "--frames '5:2'");
    expect_bad("{\"scene\": \"missing.json\"}\n", "", "missing.json");
    expect_bad("{\"scene\": \"scene.json\", \"particles\": {\"collide_with\": [\"pot\"]}}\n", "",
               "particles.collide_with[0]: no object named 'pot'");
    expect_bad("{\"scene\": \"scene.json\", \"particles\": {\"emitters\": [{\"spread\": 9}]}}\n",
               "", "bad.json:1: particles: emitter 0");
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/cj_test_animate_%ld", (long)getpid());
    mkdir(dir, 0755);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frames_and_checkpoints),
        cmocka_unit_test(test_bad_input),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) return 1;
    return rc;
}
