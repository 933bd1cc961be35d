/* A counting check for test programs that run every case and report at the end: CHECK(cond,
 * fmt, ...) prints "FAILED file:line: cond: message" and counts; cj_check_exit() prints the
 * count and gives the program's exit status (0 only when nothing failed). */
#ifndef CJ_TEST_CHECK_H
#define CJ_TEST_CHECK_H

#include <stdio.h>

static int cj_check_failures = 0;

#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++cj_check_failures;                                                                   \
            fprintf(stderr, "FAILED %s:%d: %s: ", __FILE__, __LINE__, #cond);                      \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
        }                                                                                          \
    } while (0)

static inline int cj_check_exit(void) {
    if (cj_check_failures) fprintf(stderr, "%d check(s) failed\n", cj_check_failures);
    return cj_check_failures ? 1 : 0;
}

#endif
