/* casteljau report: the instruction counts, by valgrind --tool=callgrind on the hidden workload
 * mode (`casteljau report --workload SPEC N`).
 *
 * report_callgrind: one cell, from an N- and a 2N-unit process (start-up cancels).
 *
 * report_callgrind_cells: all the cells of a section in ONE callgrind run, for the sections
 * with many cheap cells (arc length, interpolation, contouring, integrators, renderer).
 * report_callgrind runs valgrind twice per cell, and valgrind's start-up (about 1 s, more on a
 * busy machine) is most of a cheap cell's run: 100 cells cost minutes. Here the workload
 * "SECTION:all" runs every cell of the section's full table in turn, each twice between
 * callgrind client requests (counters zeroed before, dumped after): once with 0 units (the
 * cell's set-up only) and once with N units, and the count per unit is the difference of the
 * two dumps over N, as report_callgrind's difference of an N- and a 2N-unit process (set-up,
 * start-up and the client requests cancel). One unit of the first cell runs before any
 * counting, so that no cell pays for a lazy initialisation. Without valgrind's header at build
 * time the requests are no-ops, the dumps are missing and the counts NAN. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define CJ_REPORT_CG_REQUESTS 1
#endif
#endif

int report_cells_workload(int ncell, long n, report_cell_fn cell, void *ctx) {
    if (cell(ctx, 0, 1)) return 1; /* warm-up, not counted */
    for (int i = 0; i < ncell; ++i)
        for (int k = 0; k < 2; ++k) {
#ifdef CJ_REPORT_CG_REQUESTS
            CALLGRIND_ZERO_STATS;
#endif
            const int rc = cell(ctx, i, k ? n : 0);
#ifdef CJ_REPORT_CG_REQUESTS
            CALLGRIND_DUMP_STATS;
#endif
            if (rc) return 1;
        }
    return 0;
}

/* Instruction total of a callgrind dump file, NAN if unreadable. */
static double dump_total(const char *path) {
    FILE *f = fopen(path, "r");
    if (!f) return NAN;
    char line[512];
    double total = NAN;
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, "summary:", 8) || !strncmp(line, "totals:", 7))
            total = strtod(strchr(line, ':') + 1, NULL);
    fclose(f);
    return total;
}

/* Runs the workload SPEC with n units under callgrind, dumps into out (with client requests,
 * also out.1, out.2, ...); 1 on success, else 0 with the failure recorded in r->cg_fail. */
static int run_callgrind(report *r, const char *out, const char *spec, long n) {
    char cmd[9000];
    snprintf(cmd, sizeof cmd,
             "valgrind --tool=callgrind --callgrind-out-file='%s' '%s' report --workload '%s' %ld "
             ">/dev/null 2>&1",
             out, r->self, spec, n);
    const int status = system(cmd);
    if (status != 0) report_callgrind_failed(r, spec, status);
    return status == 0;
}

/* Instruction total of one callgrind run, or NAN. */
static double callgrind_once(report *r, const char *spec, long n) {
    char out[4096];
    snprintf(out, sizeof out, "%s/.callgrind.out", r->dir);
    const double total = run_callgrind(r, out, spec, n) ? dump_total(out) : NAN;
    remove(out);
    return total;
}

double report_callgrind(report *r, const char *spec, long n, double *rel_diff) {
    if (!r->callgrind) return NAN;
    const double a = callgrind_once(r, spec, n), b = callgrind_once(r, spec, 2 * n);
    if (rel_diff) {
        const double a2 = callgrind_once(r, spec, n);
        *rel_diff = fabs(a2 - a) / a;
    }
    return (b - a) / (double)n;
}

int report_callgrind_cells(report *r, const char *spec, long n, int ncell, double *out) {
    for (int i = 0; i < ncell; ++i) out[i] = NAN;
    if (!r->callgrind) return 0;
    char base[4096], path[4200];
    snprintf(base, sizeof base, "%s/.callgrind.cells", r->dir);
    const int ok = run_callgrind(r, base, spec, n);
    for (int i = 0; i < ncell; ++i) {
        double t[2];
        for (int k = 0; k < 2; ++k) {
            snprintf(path, sizeof path, "%s.%d", base, 2 * i + k + 1);
            t[k] = ok ? dump_total(path) : NAN;
        }
        out[i] = (t[1] - t[0]) / (double)n;
    }
    for (int d = 1; d <= 2 * ncell; ++d) { /* also after a failed run: no stale dumps */
        snprintf(path, sizeof path, "%s.%d", base, d);
        remove(path);
    }
    remove(base);
    return ok ? 0 : -1;
}

void report_callgrind_failed(report *r, const char *spec, int status) {
    if (r->cg_fail[0]) return;
    /* a signal (SIGILL: an instruction valgrind cannot decode) or an exit status */
    if (WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) > 128))
        snprintf(r->cg_fail, sizeof r->cg_fail,
                 "valgrind --tool=callgrind on the workload %s was killed by signal %d", spec,
                 WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status) - 128);
    else
        snprintf(r->cg_fail, sizeof r->cg_fail,
                 "valgrind --tool=callgrind on the workload %s failed (status %d)", spec,
                 WIFEXITED(status) ? WEXITSTATUS(status) : status);
}
