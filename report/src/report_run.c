/* casteljau report: the page (index.html, summary.md, data.tsv) and the order of its sections.
 * The command's front (app/cmd_report.c) parses the options and calls report_run.
 */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "file_internal.h"

#include "casteljau/status.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

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

int report_run(report *r) {
    if (!r->dir) return report_fail("no output folder: give -o DIR");
    /* The destination is checked before any work (exit 2, as every command does): the folder
     * can be made, and it takes new files. */
    if (mkdir(r->dir, 0777) != 0 && errno != EEXIST)
        return report_fail("cannot create %s: %s", r->dir, strerror(errno));
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/index.html", r->dir);
    if (cj_file_check_output(probe, "report")) return report_fail("%s", cj_last_error());
    /* the tool itself, for the callgrind runs (argv[0] here is the command name) */
    static char self[4096];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0)
        r->callgrind = 0;
    else
        self[len] = 0;
    r->self = self;
    if (r->callgrind && (has_quote(r->dir) || has_quote(r->self) ||
                         system("valgrind --version >/dev/null 2>&1") != 0))
        r->callgrind = 0;
#ifdef CJ_REPORT_ASAN
    if (r->callgrind) {
        r->callgrind = 0;
        snprintf(r->note, sizeof r->note,
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
        snprintf(path, sizeof path, "%s/%s", r->dir, names[i]);
        if (cj_atomic_open(&files[i], path)) {
            const int rc = report_error("%s", cj_last_error());
            for (int j = 0; j < i; ++j) cj_atomic_abandon(&files[j]);
            return rc;
        }
    }
    r->html = files[0].fp;
    r->md = files[1].fp;
    r->tsv = files[2].fp;
    if (cj_font_open(NULL, &r->font) != CJ_OK) {
        report_warn("no font (%s): charts without text", cj_last_error());
        r->font = NULL;
    }
    time_t now = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", gmtime(&now));
    fprintf(r->html,
            "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>casteljau: the price "
            "list</title>\n<style>body{font-family:sans-serif;max-width:980px;margin:auto}"
            "table{border-collapse:collapse;font-size:13px}td,th{border:1px solid #ccc;"
            "padding:2px 6px;text-align:right}td.l{text-align:left}tr.dom{color:#888}</style>"
            "</head><body>\n<h1>casteljau: what accuracy costs</h1>\n<p>Measured on this machine "
            "at %s (%s report). Every figure was measured when this page was built. Times: median "
            "of interleaved repeated runs, spread = (max &minus; min) / median. Instructions: "
            "valgrind --tool=callgrind, difference of an N- and a 2N-unit run.</p>\n",
            when, r->quick ? "quick" : "full");
    fprintf(r->md, "# casteljau: what accuracy costs (%s report, %s)\n\n",
            r->quick ? "quick" : "full", when);
    fprintf(r->tsv, "section\tmethod\tparam\tcond\terr_max\terr_mean\tbound\tns\tspread_pct\t"
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
    const unsigned nsections = (unsigned)(sizeof sections / sizeof sections[0]);
    int status = 0;
    for (unsigned i = 0; i < nsections && !status; ++i)
        status = report_section_start(i, nsections, sections[i].name)
                     ? report_error("stopped by Ctrl-C; the report is incomplete")
                     : sections[i].run(r);
    if (!status && r->cg_fail[0]) { /* no instruction counts: say why, here and on stderr */
        snprintf(r->note, sizeof r->note,
                 "No instruction counts: %s. Run that workload by hand (casteljau report "
                 "--workload SPEC 10 under valgrind --tool=callgrind) to see valgrind's message; "
                 "an instruction set valgrind cannot decode (AVX-512) needs a build without it.",
                 r->cg_fail);
        fprintf(stderr, "casteljau report: warning: %s; the report has no instruction counts\n",
                r->cg_fail);
    }
    if (!status && r->note[0]) {
        fprintf(r->html, "<h2>Reproducibility</h2>\n<p>%s</p>\n", r->note);
        fprintf(r->md, "%s\n", r->note);
    }
    fprintf(r->html, "</body></html>\n");
    cj_font_close(r->font);
    for (int i = 0; i < 3; ++i) {
        if (status) {
            cj_atomic_abandon(&files[i]);
        } else if (cj_atomic_commit(&files[i])) {
            status = report_error("%s", cj_last_error());
            for (int j = i + 1; j < 3; ++j) cj_atomic_abandon(&files[j]);
            break;
        }
    }
    if (!status) printf("wrote %s/index.html, summary.md, data.tsv\n", r->dir);
    return status;
}
