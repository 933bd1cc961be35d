/* How long work shows itself (app/cli_progress.h), run as child processes of `casteljau`:
 * with stderr on a pseudo-terminal, render and trace draw a progress line (percent of tiles,
 * elapsed, time left) and end with a summary line (file, size, time), as tessellate does;
 * --quiet and a stderr that is not a terminal show none of it (stderr stays empty). Very large
 * work is announced up front, and Ctrl-C (SIGINT) during it stops cleanly: exit status 130, no
 * image written. */
#define _XOPEN_SOURCE 700 /* posix_openpt, grantpt, unlockpt, ptsname, mkdtemp */
#include "check.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef CJ_CLI
#define CJ_CLI "casteljau"
#endif

typedef struct child {
    pid_t pid;
    int err_fd; /* the pty master, or the read end of a pipe */
    char err[65536];
    size_t len;
} child;

/* Starts CJ_CLI args with stdout on /dev/null and stderr on a new pseudo-terminal (tty = 1) or
 * a pipe (tty = 0). */
static void start(child *c, const char *const *args, int tty) {
    memset(c, 0, sizeof *c);
    int slave = -1;
    if (tty) {
        c->err_fd = posix_openpt(O_RDWR | O_NOCTTY);
        if (c->err_fd < 0 || grantpt(c->err_fd) || unlockpt(c->err_fd)) {
            perror("posix_openpt");
            exit(1);
        }
        slave = open(ptsname(c->err_fd), O_RDWR | O_NOCTTY);
    } else {
        int p[2];
        if (pipe(p)) exit(1);
        c->err_fd = p[0];
        slave = p[1];
    }
    if (slave < 0) exit(1);
    fflush(NULL);
    c->pid = fork();
    if (c->pid == 0) {
        int devnull = open("/dev/null", O_RDWR);
        dup2(devnull, 0);
        dup2(devnull, 1);
        dup2(slave, 2);
        close(c->err_fd);
        execv(CJ_CLI, (char *const *)args);
        _exit(127);
    }
    close(slave);
}

/* Reads stderr until `until` appears (when not NULL) or the child closes it; a 120 s guard. */
static void read_err(child *c, const char *until) {
    for (int waited = 0; waited < 1200;) {
        struct pollfd pf = {c->err_fd, POLLIN, 0};
        int n = poll(&pf, 1, 100);
        if (n == 0) {
            ++waited;
            continue;
        }
        ssize_t got = read(c->err_fd, c->err + c->len, sizeof c->err - 1 - c->len);
        if (got <= 0) break; /* EOF (pipe) or EIO (pty with no slave left) */
        c->len += (size_t)got;
        c->err[c->len] = '\0';
        if (until && strstr(c->err, until)) return;
    }
}

static int finish(child *c) {
    read_err(c, NULL);
    close(c->err_fd);
    int st = 0;
    waitpid(c->pid, &st, 0);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

static int exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

int main(void) {
    char dir[] = "/tmp/cj_progress_XXXXXX", png[128];
    if (!mkdtemp(dir)) return 1;
    snprintf(png, sizeof png, "%s/demo.png", dir);
    const char *cmds[] = {"render", "trace"};
    for (int ci = 0; ci < 2; ++ci) {
        const char *cmd = cmds[ci];
        child c;
        const char *args[] = {CJ_CLI,    cmd,         "--demo",   "-o",  png,
                              "--width", "320",       "--height", "240", "--spp",
                              "1",       "--threads", "2",        NULL,  NULL};
        start(&c, args, 1);
        int rc = finish(&c);
        CHECK(rc == 0, "%s on a pty: exit %d, stderr '%s'", cmd, rc, c.err);
        CHECK(strstr(c.err, "% (") && strstr(c.err, "tiles") && strstr(c.err, "elapsed"),
              "%s: no progress line on a terminal: '%s'", cmd, c.err);
        CHECK(strstr(c.err, "100% ("), "%s: the progress line never reached 100%%: '%s'", cmd,
              c.err);
        char want[256];
        snprintf(want, sizeof want, "casteljau %s: wrote %s (320 x 240, ", cmd, png);
        CHECK(strstr(c.err, want) && strstr(c.err, "KiB") &&
                  (strstr(c.err, " s\r\n") || strstr(c.err, " s\n")),
              "%s: no summary '%s... KiB) in T s' on the terminal: '%s'", cmd, want, c.err);
        CHECK(exists(png), "%s: no image", cmd);
        printf("%s: on a pseudo-terminal, a progress line up to 100%% of the tiles and the "
               "summary '%s...'\n",
               cmd, want);
        remove(png);

        args[13] = "--quiet";
        start(&c, args, 1);
        rc = finish(&c);
        CHECK(rc == 0 && c.len == 0 && exists(png), "%s --quiet on a pty: exit %d, stderr '%s'",
              cmd, rc, c.err);
        printf("%s --quiet: nothing on the terminal, the image written\n", cmd);
        remove(png);

        args[13] = NULL;
        start(&c, args, 0);
        rc = finish(&c);
        CHECK(rc == 0 && c.len == 0 && exists(png), "%s on a pipe: exit %d, stderr '%s'", cmd, rc,
              c.err);
        printf("%s with stderr on a pipe: stderr empty, the image written\n", cmd);
        remove(png);
    }

    /* a command without progress (short work) still ends with the summary, on a terminal only */
    {
        char obj[128], want[256];
        snprintf(obj, sizeof obj, "%s/t.obj", dir);
        snprintf(want, sizeof want, "casteljau tessellate: wrote %s (", obj);
        const char *args[] = {CJ_CLI, "tessellate", "--teapot", "-o", obj, NULL};
        for (int tty = 1; tty >= 0; --tty) {
            child c;
            start(&c, args, tty);
            int rc = finish(&c);
            CHECK(rc == 0, "tessellate: exit %d", rc);
            if (tty)
                CHECK(strstr(c.err, want) && strstr(c.err, " triangles, "),
                      "tessellate on a pty: no summary '%s...': '%s'", want, c.err);
            else
                CHECK(c.len == 0, "tessellate on a pipe: stderr '%s'", c.err);
            remove(obj);
        }
        printf("tessellate: the summary '%s... triangles, SIZE) in T s' on a terminal, nothing on "
               "a pipe\n",
               want);
    }

    /* a scene without lights renders (dark), with one warning, on a pipe too */
    {
        char scene[128];
        snprintf(scene, sizeof scene, "%s/dark.json", dir);
        FILE *f = fopen(scene, "w");
        if (!f) return 1;
        fputs("{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0]},\n"
              " \"materials\": [{\"name\": \"m\", \"color\": [0.5, 0.5, 0.5]}],\n"
              " \"objects\": [{\"name\": \"ball\", \"material\": \"m\",\n"
              "   \"geometry\": {\"type\": \"sphere\", \"radius\": 1}}]}\n",
              f);
        fclose(f);
        const char *args[] = {CJ_CLI,    "render", scene,      "-o", png,
                              "--width", "64",     "--height", "48", NULL};
        child c;
        start(&c, args, 0);
        int rc = finish(&c);
        CHECK(rc == 0 && exists(png), "render of a scene without lights: exit %d: '%s'", rc, c.err);
        CHECK(strstr(c.err, "warning: ") && strstr(c.err, "has no lights") &&
                  strchr(c.err, '\n') == c.err + c.len - 1,
              "no lights: not one warning line: '%s'", c.err);
        const char *with_lights[] = {CJ_CLI,    "render", "--demo",   "-o", png,
                                     "--width", "64",     "--height", "48", NULL};
        start(&c, with_lights, 0);
        rc = finish(&c);
        CHECK(rc == 0 && c.len == 0, "the demo (lit): stderr '%s'", c.err);
        printf("a scene without lights: rendered with one warning line (on a pipe too); the lit "
               "demo: none\n");
        remove(png);
        remove(scene);
    }

    /* 2000 x 2000 x 1 spp x (1 + 24 indirect) rays = 1e8: announced; Ctrl-C stops it. */
    {
        child c;
        const char *args[] = {CJ_CLI, "trace",     "--demo", "-o",    png, "--width",
                              "2000", "--height",  "2000",   "--spp", "1", "--indirect",
                              "24",   "--threads", "2",      NULL};
        start(&c, args, 1);
        read_err(&c, "tiles");
        kill(c.pid, SIGINT);
        int rc = finish(&c);
        CHECK(strstr(c.err, "very large work") && strstr(c.err, "Ctrl-C stops it"),
              "large trace: no warning up front: '%s'", c.err);
        CHECK(rc == 130, "Ctrl-C: exit status %d, not 130 ('%s')", rc, c.err);
        CHECK(strstr(c.err, "stopped by Ctrl-C; no image written"), "Ctrl-C: no message: '%s'",
              c.err);
        CHECK(!exists(png), "Ctrl-C: an image was written");
        printf("trace 2000 x 2000 with 24 indirect rays: warned up front; SIGINT after the first "
               "progress line -> exit 130, 'stopped by Ctrl-C', no image\n");
        remove(png);
    }
    rmdir(dir);
    return cj_check_exit();
}
