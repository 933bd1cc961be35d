/* Clocks and medians shared by the bench/ programs (each program is built with
 * _POSIX_C_SOURCE for clock_gettime). */
#ifndef CJ_BENCH_CLOCK_H
#define CJ_BENCH_CLOCK_H

#include <stdlib.h>
#include <time.h>

/* Wall-clock seconds (CLOCK_MONOTONIC). */
static inline double cj_bench_wall(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds of this process. */
static inline double cj_bench_process_cpu(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds of this thread: insensitive to other processes sharing the machine. */
static inline double cj_bench_thread_cpu(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int cj_bench_cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of v[0..n-1] (n > 0; v is sorted in place). */
static inline double cj_bench_median(double *v, size_t n) {
    qsort(v, n, sizeof v[0], cj_bench_cmp_double);
    return v[n / 2];
}

#endif
