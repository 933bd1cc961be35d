/* bench_flatten_icount: the fixed workload behind the flattening instruction counts of
 * docs/flattening.md (issue 20), for callgrind (bench/flatten_callgrind.sh) and for same-process
 * time ratios against kurbo.
 *
 *   bench_flatten_icount ours|kurbo N REPS DEGREE SEED_OFFSET [TOL_INDEX]
 *       flattens N random curves (degree 2 or 3, control points uniform in a 1000 x 1000 box,
 *       the seed of bench_flatten's peer table plus SEED_OFFSET) REPS times at tol 0.01, 0.25
 *       and 1, or only at tols[TOL_INDEX]; N = 0 measures the start-up alone.
 *   bench_flatten_icount time N REPS DEGREE SEED_OFFSET
 *       ours and kurbo alternately, 7 rounds each, thread CPU time; prints the medians and
 *       their ratio per tolerance. */
#define _POSIX_C_SOURCE 200809L
#include "casteljau/flatten.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef CJ_HAVE_KURBO
size_t cj_bench_kurbo_flatten(int n, const double *p, double tol, double *out, size_t cap);
#endif

#define CAP (1 << 16)
static double g_buf[2 * CAP];
static const double g_tols[3] = {0.01, 0.25, 1.0};

static uint64_t splitmix(uint64_t *s) {
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Points written by one flattening (ours near-optimal, or kurbo's); 0 on failure. */
static size_t run_one(int kurbo, int deg, const double *ctrl, double tol) {
#ifdef CJ_HAVE_KURBO
    if (kurbo) return cj_bench_kurbo_flatten(deg, ctrl, tol, g_buf, CAP);
#else
    (void)kurbo;
#endif
    const cj_bezier c = cj_bezier_view(deg, 2, ctrl);
    const cj_flatten_opts op = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
    size_t np = 0;
    if (cj_flatten_bezier(&c, &op, g_buf, CAP, &np, NULL)) return 0;
    return np;
}

static double thread_seconds(void) {
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    if (argc < 6) {
        fprintf(stderr, "usage: %s ours|kurbo|time N REPS DEGREE SEED_OFFSET [TOL_INDEX]\n",
                argv[0]);
        return 2;
    }
    const char *mode = argv[1];
    const int N = atoi(argv[2]), reps = atoi(argv[3]), deg = atoi(argv[4]);
    const int only = argc > 6 ? atoi(argv[6]) : -1;
    if (N < 0 || reps < 1 || (deg != 2 && deg != 3)) {
        fprintf(stderr, "bad N %d, REPS %d or DEGREE %d\n", N, reps, deg);
        return 2;
    }
#ifndef CJ_HAVE_KURBO
    if (strcmp(mode, "ours") != 0) {
        fprintf(stderr, "built without kurbo: only mode 'ours'\n");
        return 2;
    }
#endif
    uint64_t s = 20261123u + (uint64_t)deg + strtoull(argv[5], NULL, 10);
    double *ctrl = malloc(sizeof(double) * 8 * (size_t)(N > 0 ? N : 1));
    if (!ctrl) return 1;
    for (int i = 0; i < N; ++i)
        for (int k = 0; k < 2 * (deg + 1); ++k)
            ctrl[8 * i + k] = (double)(splitmix(&s) >> 11) * 0x1p-53 * 1000;
    if (!strcmp(mode, "time")) {
        printf("%d random degree-%d curves x %d, 7 alternated rounds, thread CPU, median\n", N, deg,
               reps);
        for (int ti = 0; ti < 3; ++ti) {
            double tm[2][7];
            for (int r = 0; r < 7; ++r)
                for (int k = 0; k < 2; ++k) {
                    const double t0 = thread_seconds();
                    for (int rr = 0; rr < reps; ++rr)
                        for (int i = 0; i < N; ++i) run_one(k, deg, ctrl + 8 * i, g_tols[ti]);
                    tm[k][r] = (thread_seconds() - t0) / ((double)N * reps) * 1e6;
                }
            qsort(tm[0], 7, sizeof(double), cmp_double);
            qsort(tm[1], 7, sizeof(double), cmp_double);
            printf("tol %g: ours %.3f us (%.3f-%.3f), kurbo %.3f us (%.3f-%.3f), ratio %.3f\n",
                   g_tols[ti], tm[0][3], tm[0][0], tm[0][6], tm[1][3], tm[1][0], tm[1][6],
                   tm[0][3] / tm[1][3]);
        }
        free(ctrl);
        return 0;
    }
    const int kurbo = !strcmp(mode, "kurbo");
    size_t total = 0;
    for (int r = 0; r < reps; ++r)
        for (int ti = 0; ti < 3; ++ti) {
            if (only >= 0 && only != ti) continue;
            for (int i = 0; i < N; ++i) total += run_one(kurbo, deg, ctrl + 8 * i, g_tols[ti]);
        }
    printf("points %zu\n", total);
    free(ctrl);
    return 0;
}
