/* casteljau report: the price list (issue 12) — accuracy against cost for the library's
 * approximations, measured when the report is built, drawn by our own charts (raster/chart.h).
 *
 *   casteljau report -o DIR [--quick] [--no-callgrind]
 *
 * writes DIR/index.html (sections with their PNG charts next to it), DIR/summary.md (the short
 * Markdown version the README embeds) and DIR/data.tsv (every table row, tab-separated, for
 * scripts and the test). The measuring is done here, calling the library directly (not by
 * running the bench programs): the sections need the per-point errors against the MPFR oracle
 * (tests/support/oracle_mpfr.c, linked into the tool for this command) and the timing loop of
 * each method, and parsing the benches' human tables would be more fragile than this.
 *
 * Costs are given twice: the median of interleaved repeated runs (methods alternate run by run
 * so that a busy machine slows them alike) with the spread (max - min over median), and the
 * instructions counted by valgrind --tool=callgrind on a fixed workload (the hidden mode
 * `casteljau report --workload SPEC N`), as the difference of an N- and a 2N-unit run so that
 * start-up cancels; a repeated N-unit run checks that counts repeat (printed on the page).
 * --quick: few points per plot, short timings, callgrind only for that repeatability check
 * (the test suite builds it in seconds). --no-callgrind skips valgrind entirely.
 */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#ifdef CJ_HAVE_REPORT
#include "cli_progress.h"
#include "report.h"
#include "file_internal.h"

#include "casteljau/framebuffer.h"
#include "casteljau/image_io.h"
#include "casteljau/status.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static const char usage_text[] =
    "usage: casteljau report -o DIR [--quick] [--no-callgrind] [--quiet]\n"
    "  Measures error against cost for curve evaluation (4 methods x degrees x condition\n"
    "  numbers, error against an MPFR oracle), flattening (3 methods x tolerances) and\n"
    "  tessellation (teapot, uniform vs adaptive x tolerances), arc length, interpolation\n"
    "  (Chebyshev vs equispaced), implicit contouring and the ODE integrators, and\n"
    "  writes DIR/index.html with PNG charts, DIR/summary.md and DIR/data.tsv.\n"
    "  --quick         a few points per chart (seconds; what the test suite builds)\n"
    "  --no-callgrind  no instruction counts (valgrind is used when installed)\n"
    "  --workload SPEC N  run N units of one measured workload and exit (what the report runs\n"
    "                  under callgrind; SPEC as eval:M:DEG, see app/report.h)\n";

const char *report_g3(char *buf, double v) {
    if (isfinite(v))
        snprintf(buf, 32, "%.3g", v);
    else
        snprintf(buf, 32, "—");
    return buf;
}

double report_now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double report_median(double *v, size_t n, double *spread_pct) {
    qsort(v, n, sizeof *v, cmp_double);
    const double m = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    if (spread_pct) *spread_pct = m > 0 ? 100.0 * (v[n - 1] - v[0]) / m : 0.0;
    return m;
}

void report_pareto(size_t n, const double *cost, const double *err, int *dominated_by) {
    for (size_t i = 0; i < n; ++i) {
        dominated_by[i] = -1;
        for (size_t j = 0; j < n; ++j) {
            if (j == i || !(cost[j] <= cost[i] && err[j] <= err[i])) continue;
            if (!(cost[j] < cost[i] || err[j] < err[i])) continue;
            if (dominated_by[i] < 0 || cost[j] < cost[dominated_by[i]]) dominated_by[i] = (int)j;
        }
    }
}

void report_front_series(cj_chart *c, size_t n, const double *cost, const double *err,
                         const int *dominated_by, double floor, const char *label) {
    double x[64], y[64];
    size_t k = 0;
    for (size_t i = 0; i < n && k < 64; ++i)
        if (dominated_by[i] < 0) x[k] = cost[i], y[k] = fmax(err[i], floor), k++;
    for (size_t i = 1; i < k; ++i) /* insertion sort by cost */
        for (size_t j = i; j > 0 && x[j] < x[j - 1]; --j) {
            double t = x[j];
            x[j] = x[j - 1], x[j - 1] = t;
            t = y[j], y[j] = y[j - 1], y[j - 1] = t;
        }
    if (k < 2) return;
    cj_chart_series_opts o = {label, cj_rgba_make(0x30, 0x30, 0x30, 160), 4.0, CJ_MARKER_NONE, 0};
    cj_chart_add_series(c, x, y, k, &o);
}

int report_chart(report *r, const cj_chart *c, const char *name, int w, int h) {
    cj_framebuffer *fb = NULL;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", r->dir, name);
    cj_status st = cj_framebuffer_create(w, h, 0, NULL, &fb);
    if (!st) st = cj_chart_render(c, fb, 0, 0, w, h, r->font);
    if (!st)
        st = cj_image_write(path, w, h, (const uint8_t *)fb->pixels,
                            (size_t)fb->stride * sizeof *fb->pixels);
    cj_framebuffer_destroy(fb);
    if (st) return cli_error("report", "chart %s: %s", name, cj_last_error());
    fprintf(r->html, "<p><img src=\"%s\" width=\"%d\" height=\"%d\" alt=\"%s\"></p>\n", name, w, h,
            name);
    fprintf(r->md, "![%s](%s)\n\n", name, name);
    return 0;
}

int report_workload(const char *spec, long n) {
    if (!strncmp(spec, "eval:", 5)) return report_eval_workload(spec, n);
    if (!strncmp(spec, "flatten:", 8)) return report_flatten_workload(spec, n);
    if (!strncmp(spec, "tess:", 5)) return report_tess_workload(spec, n);
    if (!strncmp(spec, "arclen:", 7)) return report_arclen_workload(spec, n);
    if (!strncmp(spec, "interp:", 7)) return report_interp_workload(spec, n);
    if (!strncmp(spec, "contour:", 8)) return report_contour_workload(spec, n);
    if (!strncmp(spec, "ode:", 4)) return report_ode_workload(spec, n);
    if (!strncmp(spec, "render:", 7)) return report_render_workload(spec, n);
    if (!strncmp(spec, "trace:", 6)) return report_trace_workload(spec, n);
    return cli_fail("report", "unknown workload '%s'", spec);
}

/* valgrind cannot run a program built with AddressSanitizer */
#if defined(__SANITIZE_ADDRESS__)
#define CJ_REPORT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CJ_REPORT_ASAN 1
#endif
#endif

static int has_quote(const char *s) {
    return strchr(s, '\'') != NULL;
}

int cmd_report(int argc, char **argv) {
    static const cli_opt opts[] = {{"--output", "-o", 1},
                                   {"--quick", NULL, 0},
                                   {"--no-callgrind", NULL, 0},
                                   {"--workload", NULL, 1}};
    cli_parser p;
    cli_parser_init(&p, "report", usage_text, argc, argv, opts, sizeof opts / sizeof opts[0]);
    report r;
    memset(&r, 0, sizeof r);
    r.callgrind = 1;
    const char *workload = NULL, *count = NULL, *v = NULL;
    for (int k; (k = cli_next(&p, &v)) != CLI_END;) {
        if (k == CLI_EXIT_OK) return 0;
        if (k == CLI_BAD) return CLI_EXIT_USAGE;
        if (k == CLI_POSITIONAL) {
            if (!workload || count) return cli_fail("report", "unexpected argument '%s'", v);
            count = v;
        } else if (k == 0)
            r.dir = v;
        else if (k == 1)
            r.quick = 1;
        else if (k == 2)
            r.callgrind = 0;
        else
            workload = v;
    }
    if (workload) {
        long n = 0;
        if (!count || cli_parse_int(count, 1, 100000000, &n))
            return cli_fail("report", "--workload needs a unit count 1..1e8");
        return report_workload(workload, n);
    }
    if (!r.dir) return cli_fail("report", "no output folder: give -o DIR");
    /* The destination is checked before any work (exit 2, as every command does): the folder
     * can be made, and it takes new files. */
    if (mkdir(r.dir, 0777) != 0 && errno != EEXIST)
        return cli_fail("report", "cannot create %s: %s", r.dir, strerror(errno));
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/index.html", r.dir);
    if (cj_file_check_output(probe, "report")) return cli_fail("report", "%s", cj_last_error());
    /* the tool itself, for the callgrind runs (argv[0] here is the command name) */
    static char self[4096];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        r.callgrind = 0;
    else
        self[len] = 0;
    r.self = self;
    if (r.callgrind && (has_quote(r.dir) || has_quote(r.self) ||
                        system("valgrind --version >/dev/null 2>&1") != 0))
        r.callgrind = 0;
#ifdef CJ_REPORT_ASAN
    if (r.callgrind) {
        r.callgrind = 0;
        snprintf(r.note, sizeof r.note,
                 "No instruction counts: this build has AddressSanitizer, whose shadow memory "
                 "valgrind cannot run.");
    }
#endif
    /* The three files through the atomic writer: each is complete or keeps its old content,
     * and "wrote ..." is printed only when all three reached the disk. */
    static const char *const names[3] = {"index.html", "summary.md", "data.tsv"};
    cj_atomic_file files[3];
    for (int i = 0; i < 3; ++i) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", r.dir, names[i]);
        if (cj_atomic_open(&files[i], path)) {
            const int rc = cli_error("report", "%s", cj_last_error());
            for (int j = 0; j < i; ++j) cj_atomic_abandon(&files[j]);
            return rc;
        }
    }
    r.html = files[0].fp;
    r.md = files[1].fp;
    r.tsv = files[2].fp;
    if (cj_font_open(NULL, &r.font) != CJ_OK) {
        cli_warn("report", "no font (%s): charts without text", cj_last_error());
        r.font = NULL;
    }
    time_t now = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", gmtime(&now));
    fprintf(r.html,
            "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>casteljau: the price "
            "list</title>\n<style>body{font-family:sans-serif;max-width:980px;margin:auto}"
            "table{border-collapse:collapse;font-size:13px}td,th{border:1px solid #ccc;"
            "padding:2px 6px;text-align:right}td.l{text-align:left}tr.dom{color:#888}</style>"
            "</head><body>\n<h1>casteljau: what accuracy costs</h1>\n<p>Measured on this machine "
            "at %s (%s report). Every figure was measured when this page was built. Times: median "
            "of interleaved repeated runs, spread = (max &minus; min) / median. Instructions: "
            "valgrind --tool=callgrind, difference of an N- and a 2N-unit run.</p>\n",
            when, r.quick ? "quick" : "full");
    fprintf(r.md, "# casteljau: what accuracy costs (%s report, %s)\n\n",
            r.quick ? "quick" : "full", when);
    fprintf(r.tsv, "section\tmethod\tparam\tcond\terr_max\terr_mean\tbound\tns\tspread_pct\t"
                   "instr\textra\tpareto\n");
    static const struct {
        const char *name;
        int (*run)(report *);
    } sections[] = {{"evaluation", report_eval},
                    {"flattening", report_flatten},
                    {"tessellation", report_tess},
                    {"arc length", report_arclen},
                    {"interpolation", report_interp},
                    {"contouring", report_contour},
                    {"ODE", report_ode},
                    {"rasterizer", report_render},
                    {"ray tracer", report_trace}};
    const uint64_t nsections = sizeof sections / sizeof sections[0];
    cli_progress pr; /* by section: their costs differ, so the time left is a rough guide */
    cli_progress_begin(&pr, "report", "sections");
    int status = 0;
    for (uint64_t i = 0; i < nsections && !status; ++i) {
        if (cli_progress_label(&pr, i, nsections, sections[i].name))
            status = cli_error("report", "stopped by Ctrl-C; the report is incomplete");
        else
            status = sections[i].run(&r);
    }
    cli_progress_end(&pr);
    if (!status && r.cg_fail[0]) { /* no instruction counts: say why, here and on stderr */
        snprintf(r.note, sizeof r.note,
                 "No instruction counts: %s. Run that workload by hand (casteljau report "
                 "--workload SPEC 10 under valgrind --tool=callgrind) to see valgrind's message; "
                 "an instruction set valgrind cannot decode (AVX-512) needs a build without it.",
                 r.cg_fail);
        fprintf(stderr, "casteljau report: warning: %s; the report has no instruction counts\n",
                r.cg_fail);
    }
    if (!status && r.note[0]) {
        fprintf(r.html, "<h2>Reproducibility</h2>\n<p>%s</p>\n", r.note);
        fprintf(r.md, "%s\n", r.note);
    }
    fprintf(r.html, "</body></html>\n");
    cj_font_close(r.font);
    for (int i = 0; i < 3; ++i) {
        if (status) {
            cj_atomic_abandon(&files[i]);
        } else if (cj_atomic_commit(&files[i])) {
            status = cli_error("report", "%s", cj_last_error());
            for (int j = i + 1; j < 3; ++j) cj_atomic_abandon(&files[j]);
            break;
        }
    }
    if (!status) printf("wrote %s/index.html, summary.md, data.tsv\n", r.dir);
    if (!status) {
        char what[4200];
        snprintf(what, sizeof what, "%s/index.html", r.dir);
        cli_summary("report", what, what, "with summary.md, data.tsv and charts", pr.t0);
    }
    return status;
}

#else
#include <stdio.h>
int cmd_report(int argc, char **argv) {
    (void)argc;
    (void)argv;
    return cli_fail("report", "this build has no report (needs OpenImageIO, raster/ and MPFR)");
}
#endif
