/* The helpers every section of `casteljau report` shares (timing, medians, Pareto fronts, charts
 * to PNG, the workload dispatch) and the host hooks (messages, the teapot's path) the front in
 * app/cmd_report.c sets: the sections call these, never the page runner or the command. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "clock_internal.h"

#include "casteljau/framebuffer.h"
#include "casteljau/image_io.h"
#include "casteljau/status.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static report_host host;

void report_host_set(const report_host *h) {
    host = *h;
}

int report_section_start(unsigned i, unsigned n, const char *name) {
    return host.section ? host.section(i, n, name) : 0;
}

const char *report_teapot_path(void) {
    return host.teapot_path ? host.teapot_path : "data/teapot.bpt";
}

static void say(const char *prefix, const char *fmt, va_list ap) {
    char msg[2048];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (host.say)
        host.say(prefix, msg);
    else
        fprintf(stderr, "casteljau report: %s%s\n", prefix, msg);
}

int report_fail(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    say("", fmt, ap);
    va_end(ap);
    return REPORT_EXIT_USAGE;
}

int report_error(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    say("", fmt, ap);
    va_end(ap);
    return REPORT_EXIT_FAILURE;
}

void report_warn(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    say("warning: ", fmt, ap);
    va_end(ap);
}

const char *report_g3(char *buf, double v) {
    if (isfinite(v))
        snprintf(buf, 32, "%.3g", v);
    else
        snprintf(buf, 32, "—");
    return buf;
}

double report_now_ns(void) {
    return 1e9 * cj_clock_seconds();
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
    if (st) return report_error("chart %s: %s", name, cj_last_error());
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
    return report_fail("unknown workload '%s'", spec);
}
