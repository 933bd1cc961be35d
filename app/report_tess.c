/* casteljau report, section "tessellation": the Utah teapot (32 bicubic patches), uniform (the
 * smallest K x K grid whose proven bound meets the tolerance, found by doubling and bisection)
 * against adaptive, at tolerances relative to the teapot's size (its control-box diagonal):
 * triangles, proven bound, measured deviation (lattice of step 1/4 on every triangle, see
 * cj_tess_options.measure), µs per patch (median of interleaved runs, without measuring),
 * instructions per patch by callgrind at tolerances >= 3e-3 of the size. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"
#include "cli.h"

#include <math.h>
#include <stdio.h>

static cj_status tess(const cj_patchset *set, cj_mesh *mesh, double tol, int K, int measure,
                      cj_tess_report *rep) {
    cj_mesh_clear(mesh);
    cj_tess_options opt = {tol, K, measure, 0};
    return cj_tessellate_patches(set->patches, set->count, &opt, mesh, rep);
}

/* n patch tessellations (the teapot's patches in turn): K > 0 uniform K x K, K = 0 adaptive at
 * rel times the teapot's size. */
int report_tess_workload(const char *spec, long n) {
    int K = -1;
    double rel = 0;
    if (sscanf(spec, "tess:%d:%lf", &K, &rel) != 2 || K < 0 || K > 1024 || !(rel > 0 && rel < 1))
        return cli_fail("report", "bad workload '%s' (tess:K:RELTOL, K = 0 adaptive)", spec);
    cj_patchset *set = NULL;
    cj_mesh *mesh = NULL;
    if ((cj_patchset_load_bpt(CJ_TEAPOT_SOURCE, NULL, &set) &&
         cj_patchset_load_bpt(CJ_TEAPOT_INSTALLED, NULL, &set)) ||
        cj_mesh_create(NULL, &mesh)) {
        cj_patchset_destroy(set);
        return cli_error("report", "%s", cj_last_error());
    }
    double lo[3], hi[3], size;
    cj_patchset_bbox(set, lo, hi, &size);
    int rc = 0;
    for (long k = 0; k < n && !rc; ++k) {
        cj_mesh_clear(mesh);
        cj_tess_options opt = {rel * size, K, 0, 0};
        cj_tess_report rep;
        rc = cj_tessellate_patches(set->patches + k % (long)set->count, 1, &opt, mesh, &rep) != 0;
    }
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    return rc;
}

int report_tess(report *r) {
    cj_patchset *set = NULL;
    if (cj_patchset_load_bpt(CJ_TEAPOT_SOURCE, NULL, &set) &&
        cj_patchset_load_bpt(CJ_TEAPOT_INSTALLED, NULL, &set)) {
        fprintf(r->html, "<h2>Tessellation</h2><p>Skipped: no teapot.bpt (%s).</p>\n",
                cj_last_error());
        return 0;
    }
    cj_mesh *mesh = NULL;
    if (cj_mesh_create(NULL, &mesh)) {
        cj_patchset_destroy(set);
        return cli_error("report", "%s", cj_last_error());
    }
    double lo[3], hi[3], size;
    cj_patchset_bbox(set, lo, hi, &size);
    static const double REL_FULL[] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4}, REL_QUICK[] = {1e-2, 1e-3};
    const double *rels = r->quick ? REL_QUICK : REL_FULL;
    const int nt = r->quick ? 2 : 5, runs = r->quick ? 3 : 11;
    double us[2][5], spread[2][5], meas[2][5], bound[2][5], tris[2][5], instr[2][5];
    int Ks[5];
    int status = 0;
    for (int t = 0; t < nt && !status; ++t) {
        const double tol = rels[t] * size;
        cj_tess_report rep;
        int lo_k = 0, hi_k = 1;
        while (!status && !(status = tess(set, mesh, 0, hi_k, 0, &rep)) && rep.bound > tol)
            lo_k = hi_k, hi_k *= 2;
        while (!status && hi_k - lo_k > 1) {
            const int mid = (lo_k + hi_k) / 2;
            if ((status = tess(set, mesh, 0, mid, 0, &rep))) break;
            if (rep.bound > tol)
                lo_k = mid;
            else
                hi_k = mid;
        }
        Ks[t] = hi_k;
        double tm[2][16];
        for (int run = 0; run < runs && !status; ++run)
            for (int m = 0; m < 2 && !status; ++m) {
                const double t0 = report_now_ns();
                status = tess(set, mesh, tol, m ? 0 : hi_k, 0, &rep);
                tm[m][run] = (report_now_ns() - t0) / 1e3 / (double)set->count;
            }
        for (int m = 0; m < 2 && !status; ++m) {
            us[m][t] = report_median(tm[m], (size_t)runs, &spread[m][t]);
            if ((status = tess(set, mesh, tol, m ? 0 : hi_k, 4, &rep))) break;
            meas[m][t] = rep.measured, bound[m][t] = rep.bound, tris[m][t] = (double)rep.triangles;
            char spec[64];
            snprintf(spec, sizeof spec, "tess:%d:%g", m ? 0 : hi_k, rels[t]);
            /* 32 and 64 patches (whole teapots, so the difference is the teapot's mean); only
             * at the coarse tolerances, where callgrind takes seconds, not minutes */
            instr[m][t] = r->quick || rels[t] < 3e-3 ? NAN : report_callgrind(r, spec, 32, NULL);
        }
    }
    cj_mesh_destroy(mesh);
    const size_t npatch = set->count;
    cj_patchset_destroy(set);
    if (status) return cli_error("report", "tessellation: %s", cj_last_error());
    static const char *const NAME[2] = {"uniform", "adaptive"};
    double cost[10], err[10];
    int dom[10];
    for (int m = 0; m < 2; ++m)
        for (int t = 0; t < nt; ++t) cost[m * nt + t] = us[m][t], err[m * nt + t] = meas[m][t];
    report_pareto((size_t)(2 * nt), cost, err, dom);
    fprintf(r->html,
            "<h2>Tessellation</h2>\n<p>The Utah teapot (%zu bicubic patches, size %.4g = its "
            "control-box diagonal). Uniform: the smallest K&times;K grid whose proven bound meets "
            "the tolerance; adaptive: cj_tessellate_patches with the tolerance. Measured deviation "
            "on a lattice of step 1/4 per triangle; &micro;s per patch without measuring. Pareto "
            "front over all choices (cost &micro;s/patch, error the measured deviation).</p>\n"
            "<table><tr><th class=l>method</th><th>tol/size</th><th>grid</th><th>triangles</th>"
            "<th>bound</th><th>measured</th><th>&micro;s/patch</th><th>spread</th><th>instr/patch"
            "</th><th class=l>Pareto</th></tr>\n",
            npatch, size);
    fprintf(r->md, "## Tessellation (teapot)\n\n| method | tol/size | triangles | bound | measured "
                   "| µs/patch | Pareto |\n|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < 2; ++m)
        for (int t = 0; t < nt; ++t) {
            const int i = m * nt + t;
            char par[96], grid[32];
            if (dom[i] < 0)
                snprintf(par, sizeof par, "front");
            else
                snprintf(par, sizeof par, "dominated by %s at %.0e", NAME[dom[i] / nt],
                         rels[dom[i] % nt]);
            if (m)
                snprintf(grid, sizeof grid, "adaptive");
            else
                snprintf(grid, sizeof grid, "K=%d", Ks[t]);
            fprintf(
                r->html,
                "<tr%s><td class=l>%s</td><td>%.0e</td><td>%s</td><td>%.0f</td><td>%.3g</td>"
                "<td>%.3g</td><td>%.1f</td><td>%.0f %%</td><td>%.0f</td><td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", NAME[m], rels[t], grid, tris[m][t], bound[m][t],
                meas[m][t], us[m][t], spread[m][t], instr[m][t], par);
            fprintf(r->md, "| %s | %.0e | %.0f | %.3g | %.3g | %.1f | %s |\n", NAME[m], rels[t],
                    tris[m][t], bound[m][t], meas[m][t], us[m][t], par);
            fprintf(r->tsv, "tess\t%s\t%.6g\t\t%.6g\t\t%.6g\t%.6g\t%.3f\t%.6g\t%.0f\t%s\n", NAME[m],
                    rels[t] * size, meas[m][t], bound[m][t], 1e3 * us[m][t], spread[m][t],
                    instr[m][t], tris[m][t], dom[i] < 0 ? "front" : "dominated");
        }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return cli_error("report", "%s", cj_last_error());
    cj_chart_set_title(c, "Teapot tessellation: deviation vs cost (ringed: dominated, tol)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "µs per patch (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max distance patch - mesh");
    report_front_series(c, (size_t)(2 * nt), cost, err, dom, 1e-300, "Pareto front");
    static const cj_rgba COL[2] = {{0xff, 0x7f, 0x0e, 255}, {0x1f, 0x77, 0xb4, 255}};
    for (int m = 0; m < 2; ++m) {
        cj_chart_series_opts o = {NAME[m], COL[m], 1.5, m ? CJ_MARKER_CIRCLE : CJ_MARKER_SQUARE,
                                  5.0};
        double y[5];
        for (int t = 0; t < nt; ++t) y[t] = fmax(meas[m][t], 1e-300);
        cj_chart_add_series(c, us[m], y, (size_t)nt, &o);
        for (int t = 0; t < nt; ++t)
            if (dom[m * nt + t] >= 0) {
                char txt[48];
                snprintf(txt, sizeof txt, "%.0e", rels[t]);
                cj_chart_annotate(c, us[m][t], y[t], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
            }
    }
    const int st = report_chart(r, c, "tess.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}
