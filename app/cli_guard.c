/* The checks before any work (cli_guard.h). */
#define _POSIX_C_SOURCE 200809L
#include "cli_guard.h"

#include "cli.h"
#include "file_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_exit_status(cj_status st) {
    return st == CJ_ERR_NOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
}

int cli_fail_status(const char *cmd, cj_status st, const char *fmt, ...) {
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (cli_exit_status(st) == CLI_EXIT_FAILURE) return cli_error(cmd, "%s", msg);
    return cli_fail(cmd, "%s", msg);
}

int cli_guard_output(const char *cmd, const char *what, const char *out) {
    const char *in = cj_file_input_named(out);
    if (!in) return 0;
    if (!strcmp(in, out))
        return cli_fail(cmd, "%s '%s' is also an input: refusing to overwrite it", what, out);
    return cli_fail(cmd, "%s '%s' is the input '%s' (the same file): refusing to overwrite it",
                    what, out, in);
}

void cli_frame_name(const char *pattern, long frame, char *out, size_t size) {
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
#endif
    snprintf(out, size, pattern, (int)frame);
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
}

static const char *base_of(const char *p) {
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* The frame number an input's name would have under the pattern, or -1. */
static long frame_of(const char *pattern, const char *input) {
    const char *pb = base_of(pattern), *ib = base_of(input);
    const char *pct = strchr(pb, '%');
    while (pct && pct[1] == '%') pct = strchr(pct + 2, '%');
    if (!pct) return -1;
    const char *conv = pct + 1;
    while (*conv >= '0' && *conv <= '9') ++conv;
    if (*conv != 'd') return -1;
    const size_t pre = (size_t)(pct - pb), suf = strlen(conv + 1), n = strlen(ib);
    if (n <= pre + suf || strncmp(ib, pb, pre) || strcmp(ib + n - suf, conv + 1)) return -1;
    long f = 0;
    for (size_t i = pre; i < n - suf; ++i) {
        if (ib[i] < '0' || ib[i] > '9' || f > 100000000) return -1;
        f = 10 * f + (ib[i] - '0');
    }
    return f;
}

int cli_guard_pattern(const char *cmd, const char *what, const char *pattern, long fa, long fb) {
    char name[4096];
    for (size_t i = 0; cj_file_input_path(i); ++i) {
        const long f = frame_of(pattern, cj_file_input_path(i));
        if (f < fa || f > fb) continue;
        cli_frame_name(pattern, f, name, sizeof name);
        if (cj_file_input_named(name))
            return cli_fail(cmd,
                            "%s '%s' names the input '%s' at frame %ld: refusing to "
                            "overwrite it",
                            what, pattern, cj_file_input_named(name), f);
    }
    for (long f = fa; fb - fa <= 10000 && f <= fb; ++f) {
        cli_frame_name(pattern, f, name, sizeof name);
        if (cj_file_input_named(name))
            return cli_fail(cmd,
                            "%s '%s' names the input '%s' at frame %ld: refusing to "
                            "overwrite it",
                            what, pattern, cj_file_input_named(name), f);
    }
    return 0;
}

int cli_check_output(const char *cmd, const char *what, const char *path) {
    char desc[64];
    snprintf(desc, sizeof desc, "%s", what);
    if (cj_file_check_output(path, desc)) return cli_fail(cmd, "%s", cj_last_error());
    return 0;
}
