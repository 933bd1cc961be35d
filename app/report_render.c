/* casteljau report, section "render": SKELETON, being written (issue 12). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "cli.h"

int report_render(report *r) {
    (void)r;
    return 0;
}

int report_render_workload(const char *spec, long n) {
    (void)n;
    return cli_fail("report", "bad workload '%s'", spec);
}
