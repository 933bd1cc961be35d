/* bench_startup: start-up cost of the casteljau tool, over 100 launches per command: wall time
 * (median and 90th percentile) and peak resident memory (from wait4's rusage), for commands
 * that write no image (they must not load OpenImageIO), for render and plot to PNG (libpng,
 * no plug-in) and, for contrast, the same to TIFF (which loads the OpenImageIO plug-in).
 *   bench_startup [path/to/casteljau] [launches] */
#define _DEFAULT_SOURCE
#include "bench_clock.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef CJ_CLI
#define CJ_CLI "./casteljau"
#endif

/* One launch with stdout/stderr to /dev/null; returns wall seconds, the child's CPU seconds
 * (user + system: what the launch costs, insensitive to other load on the machine) and peak
 * RSS in KiB. */
static double launch(char *const argv[], double *cpu, long *rss_kib, int *status) {
    const double t0 = cj_bench_wall();
    pid_t pid = fork();
    if (pid < 0) return -1.0;
    if (pid == 0) {
        int fd = open("/dev/null", O_RDWR);
        if (fd >= 0) {
            dup2(fd, 0);
            dup2(fd, 1);
            dup2(fd, 2);
        }
        execv(argv[0], argv);
        _exit(127);
    }
    int ws = 0;
    struct rusage ru;
    if (wait4(pid, &ws, 0, &ru) != pid) return -1.0;
    const double t = cj_bench_wall() - t0;
    *rss_kib = ru.ru_maxrss;
    *cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
    *status = WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
    return t;
}

int main(int argc, char **argv) {
    char *exe = argc > 1 ? argv[1] : CJ_CLI;
    const int n = argc > 2 ? atoi(argv[2]) : 100;
    char out[] = "/tmp/cj_bench_startup_XXXXXX";
    if (!mkdtemp(out)) return 1;
    char png[64], obj[64], tif[64];
    snprintf(png, sizeof png, "%s/p.png", out);
    snprintf(obj, sizeof obj, "%s/t.obj", out);
    snprintf(tif, sizeof tif, "%s/p.tif", out);
    struct {
        const char *what;
        char *argv[12];
    } cmds[] = {
        {"/bin/true (any launch costs this)", {"/bin/true", NULL}},
        {"eval (3 points, 1 parameter)", {exe, "eval", "--points", "0,0;1,2;2,0", "0.5", NULL}},
        {"interp (4 points)", {exe, "interp", "--points", "0,0;1,2;3,1;4,0", NULL}},
        {"contour (circle, 8x8 grid)",
         {exe, "contour", "--circle", "0,0,1", "--box", "-2,-2,2,2", "--grid", "8", NULL}},
        {"tessellate (teapot, uniform 2)",
         {exe, "tessellate", "--teapot", "--uniform", "2", "-o", obj, NULL}},
        {"--version", {exe, "--version", NULL}},
        /* PNG goes through libpng (issue 20's goal: <= 50 ms and <= 30 MB for render) */
        {"render --demo 64x64 -o x.png",
         {exe, "render", "--demo", "--width", "64", "--height", "64", "-o", png, NULL}},
        {"plot --demo 64x64 -o x.png",
         {exe, "plot", "--demo", "--width", "64", "--height", "64", "-o", png, NULL}},
        /* the same plot through the OpenImageIO plug-in (as every PNG was written before; render
         * writes PNG or EXR only) */
        {"plot --demo 64x64 -o x.tif (OIIO)",
         {exe, "plot", "--demo", "--width", "64", "--height", "64", "-o", tif, NULL}},
    };
    printf("casteljau start-up, %d launches each (%s)\n", n, exe);
    printf("%-40s %10s %10s %10s %12s\n", "command", "wall ms", "wall p90", "CPU ms",
           "max RSS MiB");
    double *t = malloc(sizeof(double) * (size_t)n), *cpu = malloc(sizeof(double) * (size_t)n);
    if (!t || !cpu) return 1;
    for (size_t c = 0; c < sizeof cmds / sizeof cmds[0]; ++c) {
        long rss_max = 0;
        int failed = 0;
        for (int i = 0; i < n && !failed; ++i) {
            long rss = 0;
            int st = 0;
            t[i] = launch(cmds[c].argv, &cpu[i], &rss, &st);
            if (t[i] < 0 || st != 0) failed = 1;
            if (rss > rss_max) rss_max = rss;
        }
        if (failed) {
            printf("%-40s (fails with this executable)\n", cmds[c].what);
            continue;
        }
        qsort(t, (size_t)n, sizeof *t, cj_bench_cmp_double);
        qsort(cpu, (size_t)n, sizeof *cpu, cj_bench_cmp_double);
        printf("%-40s %10.2f %10.2f %10.2f %12.1f\n", cmds[c].what, 1e3 * t[n / 2],
               1e3 * t[(9 * n) / 10], 1e3 * cpu[n / 2], rss_max / 1024.0);
    }
    printf("(wall and CPU: medians; CPU = user + system time of the launch)\n");
    free(t);
    free(cpu);
    unlink(png);
    unlink(obj);
    unlink(tif);
    rmdir(out);
    return 0;
}
