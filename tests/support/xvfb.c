#define _GNU_SOURCE
#include "xvfb.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

pid_t cj_test_xvfb_start(int width, int height) {
    int fds[2];
    if (pipe(fds) != 0) {
        perror("xvfb: pipe");
        return -1;
    }
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        perror("xvfb: fork");
        return -1;
    }
    if (pid == 0) {
        prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (getppid() != parent) _exit(1);
        close(fds[0]);
        const int devnull = open("/dev/null", O_RDWR);
        if (devnull >= 0) {
            dup2(devnull, 0);
            dup2(devnull, 1);
            dup2(devnull, 2);
        }
        char fd[16], screen[48];
        snprintf(fd, sizeof fd, "%d", fds[1]);
        snprintf(screen, sizeof screen, "%dx%dx24", width, height);
        execlp("Xvfb", "Xvfb", "-displayfd", fd, "-screen", "0", screen, "-nolisten", "tcp",
               "-noreset", (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    /* Xvfb writes the display number once it is ready for clients. */
    char buf[32] = {0};
    size_t got = 0;
    while (got + 1 < sizeof buf) {
        const ssize_t k = read(fds[0], buf + got, sizeof buf - 1 - got);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        got += (size_t)k;
        if (memchr(buf, '\n', got)) break;
    }
    close(fds[0]);
    if (got == 0 || buf[0] < '0' || buf[0] > '9') {
        fprintf(stderr, "xvfb: could not start Xvfb (is the xvfb package installed?)\n");
        cj_test_xvfb_stop(pid);
        return -1;
    }
    char display[40];
    snprintf(display, sizeof display, ":%d", atoi(buf));
    setenv("DISPLAY", display, 1);
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    return pid;
}

void cj_test_xvfb_stop(pid_t pid) {
    if (pid <= 0) return;
    kill(pid, SIGTERM);
    int status;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
}
