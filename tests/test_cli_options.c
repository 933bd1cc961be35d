/* The options of every command (issue 25, "fits the user's hands"), run as child processes of
 * `casteljau`: -h is help only on its own (among other arguments it is an error, never a silent
 * exit 0 without the work); an unknown option names the nearest known one ("--sp" -> "--spp")
 * and only when one is near; every option a command takes (--list-options) appears in its
 * --help; the animate --help example of splitting a run over processes runs as printed. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "cli_run.h"

#include "check.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef CJ_CLI
#define CJ_CLI "casteljau"
#endif
#ifndef CJ_SCENES_DIR
#define CJ_SCENES_DIR "scenes"
#endif

/* Runs `casteljau args...` (NULL-terminated, at most 30). */
static void run(cj_cli_result *r, const char *const *args) {
    char *argv[32];
    int n = 0;
    argv[n++] = (char *)CJ_CLI;
    for (; args[n - 1] && n < 31; ++n) argv[n] = (char *)args[n - 1];
    argv[n] = NULL;
    if (cj_cli_spawn(argv, r)) {
        fprintf(stderr, "cannot run %s\n", CJ_CLI);
        exit(1);
    }
}

static int exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

static int count_lines(const char *s) {
    int n = 0;
    for (; *s; ++s) n += *s == '\n';
    return n;
}

static void test_h_alone(const char *dir) {
    char png[256];
    snprintf(png, sizeof png, "%s/h.png", dir);
    cj_cli_result r;
    const char *slip[] = {"render", "--demo", "-o", png, "--width=640", "-h", "480", NULL};
    run(&r, slip);
    CHECK(r.status == 2, "render ... -h 480: exit %d, not 2", r.status);
    CHECK(r.out_len == 0, "render ... -h 480 printed on stdout: '%s'", r.out);
    CHECK(count_lines(r.err) == 1 && strstr(r.err, "'-h'") && strstr(r.err, "--height"),
          "render ... -h 480: stderr '%s'", r.err);
    CHECK(!exists(png), "render ... -h 480 wrote an image");
    cj_cli_result_free(&r);
    printf("render --demo -o X --width=640 -h 480: exit 2, one line naming -h and --height, "
           "nothing on stdout, no image\n");
    const char *cmds[] = {"render", "trace", "animate", "eval", "plot", "fit", "report"};
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; ++i) {
        const char *alone[] = {cmds[i], "-h", NULL};
        run(&r, alone);
        char want[64];
        snprintf(want, sizeof want, "usage: casteljau %s", cmds[i]);
        CHECK(r.status == 0 && !strncmp(r.out, want, strlen(want)), "%s -h: exit %d, out '%.80s'",
              cmds[i], r.status, r.out);
        cj_cli_result_free(&r);
        const char *mixed[] = {cmds[i], "--quiet", "-h", NULL};
        run(&r, mixed);
        CHECK(r.status == 2 && r.out_len == 0 && strstr(r.err, "'-h' means help only"),
              "%s --quiet -h: exit %d, err '%s'", cmds[i], r.status, r.err);
        cj_cli_result_free(&r);
    }
    printf("-h alone prints the usage (exit 0) and after another argument is an error (exit 2) "
           "in 7 commands\n");
}

static void test_suggestions(void) {
    static const struct {
        const char *cmd, *typed, *want; /* want NULL: no suggestion */
    } cases[] = {
        {"render", "--sp", "--spp"},         {"render", "--wid", "--width"},
        {"render", "--thread", "--threads"}, {"trace", "--indirct", "--indirect"},
        {"eval", "--pionts", "--points"},    {"animate", "--chekpoint-in", "--checkpoint-in"},
        {"render", "--quite", "--quiet"},    {"render", "--x", NULL},
        {"render", "--colour", NULL}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        cj_cli_result r;
        const char *args[] = {cases[i].cmd, cases[i].typed, "1", NULL};
        run(&r, args);
        char want[96];
        snprintf(want, sizeof want, "did you mean '%s'?", cases[i].want ? cases[i].want : "");
        CHECK(r.status == 2 && count_lines(r.err) == 1 && strstr(r.err, "unknown option"),
              "%s %s: exit %d, err '%s'", cases[i].cmd, cases[i].typed, r.status, r.err);
        if (cases[i].want)
            CHECK(strstr(r.err, want), "%s %s: no '%s' in '%s'", cases[i].cmd, cases[i].typed, want,
                  r.err);
        else
            CHECK(!strstr(r.err, "did you mean"), "%s %s: a far suggestion '%s'", cases[i].cmd,
                  cases[i].typed, r.err);
        printf("%s %s -> %s\n", cases[i].cmd, cases[i].typed,
               cases[i].want ? cases[i].want : "(no suggestion)");
        cj_cli_result_free(&r);
    }
}

static void test_usage_complete(void) {
    const char *cmds[] = {"eval",  "interp",  "contour", "plot",   "tessellate", "render",
                          "trace", "animate", "view",    "report", "fit"};
    int checked = 0;
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; ++i) {
        cj_cli_result help, list;
        const char *h[] = {cmds[i], "--help", NULL}, *l[] = {cmds[i], "--list-options", NULL};
        run(&help, h);
        run(&list, l);
        CHECK(help.status == 0 && list.status == 0 && list.out_len > 0, "%s: exit %d / %d", cmds[i],
              help.status, list.status);
        if (strstr(help.out, "no image output") || strstr(help.out, "this build has no")) {
            cj_cli_result_free(&help);
            cj_cli_result_free(&list);
            continue;
        }
        for (char *opt = strtok(list.out, "\n"); opt; opt = strtok(NULL, "\n"), ++checked) {
            /* the option as a word: "--spp" must not be found inside "--spp-x" */
            const char *at = help.out;
            int found = 0;
            while (!found && (at = strstr(at, opt)) != NULL) {
                const char after = at[strlen(opt)];
                found = !(after == '-' || (after >= 'a' && after <= 'z'));
                at += strlen(opt);
            }
            CHECK(found, "'casteljau %s --help' does not mention %s", cmds[i], opt);
        }
        cj_cli_result_free(&help);
        cj_cli_result_free(&list);
    }
    CHECK(checked > 100, "only %d options checked", checked);
    printf("usage complete: the %d options of 11 commands (--list-options) each appear in the "
           "command's --help\n",
           checked);
}

/* Replaces "a.json" in s (in place, s of 1024) by the shipped fly-by's path: the animation's
 * scene is found beside the document. */
static void use_flyby(char *s) {
    char *at = strstr(s, "a.json");
    if (!at) return;
    char rest[1024];
    snprintf(rest, sizeof rest, "%s", at + 6);
    snprintf(at, 1024 - (size_t)(at - s), "%s/anim_flyby.json%s", CJ_SCENES_DIR, rest);
}

/* The lines of the example in `animate --help`, joined where a line ends in a backslash. */
static void example_commands(const char *help, char first[1024], char second[1024]) {
    const char *a = strstr(help, "\n  casteljau animate a.json --frames");
    const char *b = strstr(help, "\n  seq 0 48 192 | parallel '");
    first[0] = second[0] = '\0';
    if (!a || !b) return;
    const char *from[2] = {a + 3, b + 3};
    char *to[2] = {first, second};
    for (int k = 0; k < 2; ++k) {
        size_t n = 0;
        for (const char *c = from[k]; *c && n < 1000; ++c) {
            if (c[0] == '\\' && c[1] == '\n') { /* a continuation, as the shell joins it */
                ++c;
                continue;
            }
            if (*c == '\n') break;
            to[k][n++] = *c;
        }
        to[k][n] = '\0';
    }
}

static void test_animate_example(const char *dir) {
    cj_cli_result r;
    const char *h[] = {"animate", "--help", NULL};
    run(&r, h);
    char first[1024], second[1024], cmd[4096];
    example_commands(r.out, first, second);
    cj_cli_result_free(&r);
    CHECK(first[0] && second[0], "the example is not in animate --help");
    if (!first[0] || !second[0]) return;
    /* `casteljau` on the PATH, a.json the shipped fly-by */
    use_flyby(first);
    use_flyby(second);
    char bin[1024];
    snprintf(bin, sizeof bin, "%s", CJ_CLI);
    char *slash = strrchr(bin, '/');
    if (slash) *slash = '\0';
    snprintf(cmd, sizeof cmd, "cd '%s' && PATH='%s':\"$PATH\" %s", dir, bin, first);
    CHECK(cj_cli_shell(cmd, &r) == 0 && r.status == 0, "the first example command: exit %d: %s",
          r.status, r.err);
    cj_cli_result_free(&r);
    char ck[256];
    snprintf(ck, sizeof ck, "%s/ckpt_0192.bin", dir);
    CHECK(exists(ck), "the first example command wrote no %s", ck);
    /* the second as GNU parallel runs it for the last range, {} = 192, smaller frames (the
     * options may come after the others) */
    char *q0 = strchr(second, '\''), *q1 = strrchr(second, '\'');
    CHECK(q0 && q1 > q0, "no quoted command in '%s'", second);
    if (!q0 || q1 <= q0) return;
    *q1 = '\0';
    char job[1024];
    size_t n = 0;
    for (const char *c = q0 + 1; *c && n < sizeof job - 8; ++c) {
        if (c[0] == '{' && c[1] == '}') {
            memcpy(job + n, "192", 3), n += 3, ++c;
            continue;
        }
        job[n++] = *c;
    }
    job[n] = '\0';
    snprintf(cmd, sizeof cmd, "cd '%s' && PATH='%s':\"$PATH\" %s --width 64 --height 48", dir, bin,
             job);
    CHECK(cj_cli_shell(cmd, &r) == 0 && r.status == 0, "the parallel job '%s': exit %d: %s", job,
          r.status, r.err);
    cj_cli_result_free(&r);
    char f0[256], f1[256];
    snprintf(f0, sizeof f0, "%s/f_0192.png", dir);
    snprintf(f1, sizeof f1, "%s/f_0239.png", dir);
    CHECK(exists(f0) && exists(f1), "the parallel job wrote no frames 192..239");
    printf("animate --help example: the checkpoint run and the parallel job for {} = 192 ran as "
           "printed (a.json the shipped fly-by; checkpoints 0..192, frames 192..239)\n");
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(cj_cli_shell(cmd, &r) == 0, "cleanup");
    cj_cli_result_free(&r);
}

int main(void) {
    char dir[] = "/tmp/cj_options_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    test_h_alone(dir);
    test_suggestions();
    test_usage_complete();
    test_animate_example(dir);
    return cj_check_exit();
}
