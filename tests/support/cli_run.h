/* Runs the casteljau executable (or a shell pipeline) for the command-line contract tests and
 * captures its exit status, stdout and stderr. */
#ifndef CJ_TEST_CLI_RUN_H
#define CJ_TEST_CLI_RUN_H

#include <stddef.h>

typedef struct cj_cli_result {
    int status; /* exit status, or -1 if the child did not exit normally */
    char *out;  /* stdout, NUL-terminated (malloc'd) */
    size_t out_len;
    char *err; /* stderr, NUL-terminated (malloc'd) */
    size_t err_len;
} cj_cli_result;

/* Runs argv[0] (a path) with argv, NULL-terminated, in the environment of the test. Returns 0,
 * or -1 if the process could not be started or its output not captured. */
int cj_cli_spawn(char *const argv[], cj_cli_result *r);

/* Runs `/bin/sh -c cmd` (for pipelines and quoting); same capture. */
int cj_cli_shell(const char *cmd, cj_cli_result *r);

/* Runs `/bin/sh -c` on the printf-style command (at most 4095 bytes). When the command does not
 * fit, or could not be run or captured, the result has status -1, out "" and err saying so, so
 * the caller's checks of status and messages fail with a reason. Free with cj_cli_result_free. */
cj_cli_result cj_cli_shellf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* 1 when s (a program's stderr) is exactly one line: no newline but a last one. */
int cj_cli_one_line(const char *s);

void cj_cli_result_free(cj_cli_result *r);

/* Runs `exe sub args...` (args NULL-terminated, at most 60) and copies the exit status and both
 * streams into the caller's buffers. Returns -1 if it could not run or an output does not fit
 * (a test must not judge truncated output). */
int cj_cli_run_into(const char *exe, const char *sub, const char *const *args, int *status,
                    char *out, size_t out_size, char *err, size_t err_size);

#endif
