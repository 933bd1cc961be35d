/* casteljau report: the price list (issue 12) — accuracy against cost for the library's
 * approximations, measured when the report is built, drawn by our own charts (raster/chart.h).
 *
 *   casteljau report -o DIR [--quick] [--no-callgrind]
 *
 * writes DIR/index.html (sections with their PNG charts next to it), DIR/summary.md (the short
 * Markdown version the README embeds) and DIR/data.tsv (every table row, tab-separated, for
 * scripts and the test). This file is the command's front: it parses the options and calls the
 * report module (report/: report_run, and report_workload for the hidden mode). The measuring
 * is done there, calling the library directly (not by
 * running the bench programs): the sections need the per-point errors against the MPFR oracle
 * (oracle/, the library cj_oracle_mpfr) and the timing loop of
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
#include "cli.h"

#ifdef CJ_HAVE_REPORT
#include "cli_progress.h"
#include "report.h"

#include <string.h>

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
    "                  under callgrind; SPEC as eval:M:DEG, see report/include/report.h)\n";

/* The report's messages are the command's: one escaped line "casteljau report: ...". */
static void say(const char *prefix, const char *msg) {
    cli_error("report", "%s%s", prefix, msg);
}

/* Progress by section on a terminal: their costs differ, so the time left is a rough guide. */
static cli_progress progress;
static int on_section(unsigned i, unsigned n, const char *name) {
    return cli_progress_label(&progress, i, n, name);
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
    const report_host host = {cli_teapot_path(), say, on_section};
    report_host_set(&host);
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
    cli_progress_begin(&progress, "report", "sections");
    const int status = report_run(&r);
    cli_progress_end(&progress);
    if (!status) {
        char what[4200];
        snprintf(what, sizeof what, "%s/index.html", r.dir);
        cli_summary("report", what, what, "with summary.md, data.tsv and charts", progress.t0);
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
