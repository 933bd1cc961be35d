#define _POSIX_C_SOURCE 200809L
#include "cli_run.h"

#include <fcntl.h>
#include <stdarg.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* Reads the whole of an open temporary file from its start into a malloc'd string. */
static char *slurp(int fd, size_t *len) {
    if (lseek(fd, 0, SEEK_SET) < 0) return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    if (!buf) return NULL;
    for (;;) {
        if (n + 1 == cap) {
            char *grown = realloc(buf, cap *= 2);
            if (!grown) {
                free(buf);
                return NULL;
            }
            buf = grown;
        }
        ssize_t got = read(fd, buf + n, cap - 1 - n);
        if (got < 0) {
            free(buf);
            return NULL;
        }
        if (got == 0) break;
        n += (size_t)got;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

int cj_cli_spawn(char *const argv[], cj_cli_result *r) {
    memset(r, 0, sizeof *r);
    char out_path[] = "/tmp/cj_cli_outXXXXXX", err_path[] = "/tmp/cj_cli_errXXXXXX";
    int fo = mkstemp(out_path), fe = mkstemp(err_path);
    int rc = -1;
    if (fo < 0 || fe < 0) goto done;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    /* The tool reads standard input when given no data (eval without T): give it none. */
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, fo, 1);
    posix_spawn_file_actions_adddup2(&fa, fe, 2);
    pid_t pid;
    int spawned = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (spawned != 0) goto done;
    int ws = 0;
    if (waitpid(pid, &ws, 0) != pid) goto done;
    r->status = WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
    r->out = slurp(fo, &r->out_len);
    r->err = slurp(fe, &r->err_len);
    if (r->out && r->err) rc = 0;
done:
    if (fo >= 0) close(fo), unlink(out_path);
    if (fe >= 0) close(fe), unlink(err_path);
    if (rc) cj_cli_result_free(r);
    return rc;
}

int cj_cli_shell(const char *cmd, cj_cli_result *r) {
    char *const argv[] = {(char *)"/bin/sh", (char *)"-c", (char *)cmd, NULL};
    return cj_cli_spawn(argv, r);
}

cj_cli_result cj_cli_shellf(const char *fmt, ...) {
    char cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    const int n = vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    cj_cli_result r;
    if (n >= 0 && (size_t)n < sizeof cmd && cj_cli_shell(cmd, &r) == 0) return r;
    memset(&r, 0, sizeof r);
    r.status = -1;
    r.out = calloc(1, 1);
    const char *why = n < 0 || (size_t)n >= sizeof cmd ? "the command is longer than 4095 bytes"
                                                       : "the shell could not be run or captured";
    r.err = malloc(strlen(why) + 1);
    if (r.err) strcpy(r.err, why);
    r.err_len = r.err ? strlen(why) : 0;
    return r;
}

int cj_cli_one_line(const char *s) {
    const char *nl = strchr(s, '\n');
    return !nl || !nl[1];
}

void cj_cli_result_free(cj_cli_result *r) {
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
    r->out_len = r->err_len = 0;
}

int cj_cli_run_into(const char *exe, const char *sub, const char *const *args, int *status,
                    char *out, size_t out_size, char *err, size_t err_size) {
    char *argv[64];
    int argc = 0;
    argv[argc++] = (char *)exe;
    argv[argc++] = (char *)sub;
    for (const char *const *a = args; *a; ++a) {
        if (argc == 63) return -1;
        argv[argc++] = (char *)*a;
    }
    argv[argc] = NULL;
    cj_cli_result r;
    if (cj_cli_spawn(argv, &r)) return -1;
    int rc = -1;
    if (r.out_len < out_size && r.err_len < err_size) {
        memcpy(out, r.out, r.out_len + 1);
        memcpy(err, r.err, r.err_len + 1);
        *status = r.status;
        rc = 0;
    }
    cj_cli_result_free(&r);
    return rc;
}
