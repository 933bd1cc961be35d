/* libFuzzer target: the command-line front end. The input is split at NUL bytes into argv;
 * the first byte picks the command (eval, interp, contour, or the shared parsers alone).
 * Commands that write files are not run (a fuzzer must not write where it likes). */
#include "../app/cli.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

int LLVMFuzzerInitialize(int *argc, char ***argv) {
    (void)argc;
    (void)argv;
    /* The commands print results (stdout: dropped) and one-line messages (stderr: kept, it is
     * where libFuzzer and the sanitizers report); eval without T reads standard input. */
    if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "r", stdin)) abort();
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1 || size > 4096) return 0;
    char *buf = malloc(size + 1);
    if (!buf) return 0;
    memcpy(buf, data + 1, size - 1);
    buf[size - 1] = '\0';
    char *argv[66];
    int argc = 0;
    argv[argc++] = "cmd";
    for (char *p = buf; p < buf + size - 1 && argc < 64; p += strlen(p) + 1) argv[argc++] = p;
    argv[argc] = NULL;
    switch (data[0] % 4) {
    case 0:
        cmd_eval(argc, argv);
        break;
    case 1:
        cmd_interp(argc, argv);
        break;
    case 2:
        cmd_contour(argc, argv);
        break;
    default: {
        /* the shared parsers on every argument */
        for (int i = 1; i < argc; ++i) {
            double *v = NULL, d;
            size_t n;
            int dim;
            char why[256];
            if (cli_parse_points(argv[i], &v, &n, &dim, why, sizeof why) == 0) free(v);
            v = NULL;
            if (cli_parse_list(argv[i], &v, &n, why, sizeof why) == 0) free(v);
            (void)cli_parse_double(argv[i], &d);
        }
        break;
    }
    }
    clearerr(stdin);
    free(buf);
    return 0;
}
