/* The report module (report/, internal to the tool; issue 12, the price list): the page being
 * written, the entry points the `report` command calls (report_run, report_workload) and the
 * helpers every section shares (timing, Pareto fronts, charts to PNG, table rows), which live in
 * report_util.c so that the sections never call back into the page runner or the command. */
#ifndef CASTELJAU_REPORT_H
#define CASTELJAU_REPORT_H

#include "casteljau/chart.h"
#include "casteljau/text.h"

#include <stddef.h>
#include <stdio.h>

#if defined(__GNUC__)
#define REPORT_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define REPORT_PRINTF(a, b)
#endif

typedef struct report {
    const char *dir;   /* output folder */
    int quick;         /* few points per plot, short timings (the test suite's version) */
    FILE *html, *md;   /* index.html and summary.md, open for writing */
    FILE *tsv;         /* data.tsv: every table row, machine-readable (checked by the test) */
    cj_font *font;     /* NULL: charts without text */
    const char *self;  /* path of the tool, for callgrind runs of the workload mode */
    int callgrind;     /* 1: instruction counts by valgrind --tool=callgrind */
    char note[1024];   /* the callgrind repeatability line, or why there are no counts */
    char cg_fail[256]; /* why the first failed callgrind run failed ("" while none has) */
} report;

/* Exit statuses of the tool: bad input (as the command's usage errors), and failure. */
#define REPORT_EXIT_USAGE   2
#define REPORT_EXIT_FAILURE 1

/* What the front (app/cmd_report.c) lends the module: the path of data/teapot.bpt as the tool
 * finds it (the renderer and tracer sections' scene) and the printer of one message line
 * (prefix "" or "warning: ", then the message); say NULL prints "casteljau report: ..." on
 * stderr. Set once before report_run or report_workload; the struct is copied. */
typedef struct report_host {
    const char *teapot_path;
    void (*say)(const char *prefix, const char *msg);
    /* NULL, or called before section i of n ("evaluation", ...) starts; nonzero stops the
     * report there (an interrupted run: nothing is written) */
    int (*section)(unsigned i, unsigned n, const char *name);
} report_host;
void report_host_set(const report_host *host);
/* Tells the host that section i of n starts; nonzero: stop (see report_host.section). */
int report_section_start(unsigned i, unsigned n, const char *name);
/* The teapot's path lent by the host ("data/teapot.bpt" when none was). */
const char *report_teapot_path(void);
/* Prints the message through the host and returns REPORT_EXIT_USAGE (bad input: a workload
 * spec, a missing -o) or REPORT_EXIT_FAILURE (anything else); report_warn prints a warning. */
int report_fail(const char *fmt, ...) REPORT_PRINTF(1, 2);
int report_error(const char *fmt, ...) REPORT_PRINTF(1, 2);
void report_warn(const char *fmt, ...) REPORT_PRINTF(1, 2);

/* Writes the whole page into r->dir (created if missing): index.html, summary.md, data.tsv and
 * the charts; r->dir, r->quick and r->callgrind are read, the rest is filled in. Returns 0, or
 * an exit status after a message. */
int report_run(report *r);

/* v as "%.3g" in buf (at least 32 bytes), or "—" when v is not finite (no such figure). */
const char *report_g3(char *buf, double v);
/* Monotonic clock in nanoseconds. */
double report_now_ns(void);
/* Median of v[0..n-1] (sorted in place) and the spread (max - min) / median in percent. */
double report_median(double *v, size_t n, double *spread_pct);
/* dominated_by[i] = index of a choice with cost <= and error <= (one strictly), the cheapest
 * such; -1 when i is on the Pareto front. */
void report_pareto(size_t n, const double *cost, const double *err, int *dominated_by);
/* Adds the Pareto front of the n choices (those with dominated_by < 0) as a thin dark line
 * through them in order of cost, errors drawn at least at floor (as the section draws its
 * points); label NULL = no legend entry. */
void report_front_series(cj_chart *c, size_t n, const double *cost, const double *err,
                         const int *dominated_by, double floor, const char *label);
/* Renders the chart (w x h) to DIR/name (PNG) and adds <img> to the page; 0 on success. */
int report_chart(report *r, const cj_chart *c, const char *name, int w, int h);
/* Instructions per unit of the workload "casteljau report --workload SPEC N", from two
 * callgrind runs with N and 2N units (the difference removes start-up); NAN when valgrind is
 * missing or fails. rel_diff receives |run2 - run1| / run1 of a repeated N-unit run (the 0.5 %
 * repeatability check) when not NULL. */
double report_callgrind(report *r, const char *spec, long n, double *rel_diff);
/* Runs one workload (for callgrind): returns 0, or 2 for an unknown spec. */
int report_workload(const char *spec, long n);
/* One cell of a section's full table: runs `units` units of its computation (0: its set-up
 * only); 0 on success. */
typedef int (*report_cell_fn)(void *ctx, int cell, long units);
/* Workload side of report_callgrind_cells (report_cgbatch.c): runs every cell with 0 and with
 * n units, each between callgrind client requests (zero the counters, dump them). */
int report_cells_workload(int ncell, long n, report_cell_fn cell, void *ctx);
/* Instructions per unit of every cell of the workload "SECTION:all" from ONE callgrind run:
 * out[i] = (dump of n units - dump of 0 units) / n; NAN when valgrind is off or fails (then
 * returns -1). */
int report_callgrind_cells(report *r, const char *spec, long n, int ncell, double *out);
/* Records the first failed valgrind command (its workload and exit status) in r->cg_fail. */
void report_callgrind_failed(report *r, const char *spec, int status);

int report_eval(report *r);
int report_flatten(report *r);
int report_tess(report *r);
int report_arclen(report *r);
int report_interp(report *r);
int report_contour(report *r);
int report_ode(report *r);
int report_render(report *r); /* the rasterizer: screen tolerance x spp (report_render.c) */
int report_trace(report *r);  /* the ray tracer: spp x sampling (report_trace.c) */
int report_path(report *r);   /* the path tracer's convergence (report_path.c) */
/* Workloads for callgrind, "SECTION:..." (report_workload dispatches on the prefix); each
 * does n units of the section's measured computation and prints nothing. */
int report_eval_workload(const char *spec, long n);    /* "eval:M:DEG" */
int report_flatten_workload(const char *spec, long n); /* "flatten:M:TOL" */
int report_tess_workload(const char *spec, long n);    /* "tess:K:RELTOL" */
int report_arclen_workload(const char *spec, long n);  /* "arclen:M:TOL_OR_N" */
int report_interp_workload(const char *spec, long n);  /* "interp:M:DEG" */
int report_contour_workload(const char *spec, long n); /* "contour:GRID:TOL" */
int report_ode_workload(const char *spec, long n);     /* "ode:M:N" */
int report_render_workload(const char *spec, long n);  /* "render:..." (report_render.c) */
int report_trace_workload(const char *spec, long n);   /* "trace:..." (report_trace.c) */

#endif
