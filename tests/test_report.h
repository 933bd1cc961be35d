/* test_report's per-section checkers: the main loop of test_report.c splits data.tsv into rows
 * of 12 fields (section method param cond err_max err_mean bound ns spread_pct instr extra
 * pareto; see docs/report.md) and hands each row of a section to that section's checker, which
 * asserts what the section promises; *_end runs after the last row (row counts, fronts, the
 * page's charts). Each section's checks live in their own file, test_report_<section>.c. */
#ifndef CASTELJAU_TEST_REPORT_H
#define CASTELJAU_TEST_REPORT_H

void report_check_render_row(char *const f[12]);
void report_check_render_end(const char *html, const char *md);
void report_check_trace_row(char *const f[12]);
void report_check_trace_end(const char *html, const char *md);

#endif
