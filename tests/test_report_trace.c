/* test_report: the checks of the "trace" section (report/src/report_trace.c) on the quick report.
 *
 * Samples per pixel (rows "stratified" / "random", param = spp 1, 4, 16): RMSE finite and > 0;
 * the reference's own noise (column bound) well below every measured RMSE, so the figures are
 * errors of the image and not of the reference; the noise-corrected RMSE (column extra) within
 * [0, RMSE]; at 1 spp both samplings are the same picture (pixel centres, the light's centre),
 * so their RMSE must be identical; the RMSE falls with spp: at 16 spp at most half of 1 spp for
 * each sampling (1/sqrt(16) = 1/4 expected; measured 0.22-0.26 stratified, 0.34-0.38 random over
 * 12 image seeds x 3 pairs of 512-spp reference seeds); stratified at 16 spp at least 10 % below
 * random (measured 0.61-0.76 of it over the same seeds). The images are deterministic for a given
 * seed (the section fixes its seeds), so none of this is flaky.
 *
 * Patch tolerance (rows "patch direct", param = tolerance 1e-2 and 1e-6): RMSE against the image
 * at 1e-10 finite and >= 0, pixels differing by > 1/255 (column extra) an integer >= 0; the tight
 * tolerance no worse than the coarse one and differing in at most 1 % of the pixels, the coarse one
 * differing in at least one pixel (the option takes effect: 21 pixels measured at 32 x 24).
 *
 * At the end: the row counts (3 spp x 2 samplings, 2 tolerances, each exactly once), a Pareto
 * front among the spp rows, and the page and summary.md show both charts.
 *
 * Checked that it can fail, on mutants of report_trace.c: both samplings random, random always at
 * 1 spp, a 4-spp reference, one tolerance for both rows, the patch tolerance ignored. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "test_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int spp_rows, tol_rows, fronts, seen[2][3], tol_seen[2];
static double err[2][3];             /* [stratified, random][spp 1, 4, 16] */
static double tol_err[2], tol_px[2]; /* [1e-2, 1e-6]: RMSE, pixels differing */
static const int SPP[3] = {1, 4, 16};

void report_check_trace_row(char *const f[12]) {
    const double param = strtod(f[2], NULL), rmse = strtod(f[4], NULL);
    if (!strcmp(f[1], "patch direct")) {
        tol_rows++;
        const double px = strtod(f[10], NULL);
        assert_true(param > 0 && param <= 1);
        assert_true(isfinite(rmse) && rmse >= 0);
        assert_true(isfinite(px) && px >= 0 && px == floor(px));
        assert_true(fabs(param - 1e-2) < 1e-12 || fabs(param - 1e-6) < 1e-16);
        const int k = param < 1e-3;
        tol_seen[k]++;
        tol_err[k] = rmse, tol_px[k] = px;
        return;
    }
    const int m = !strcmp(f[1], "random");
    if (!m) assert_string_equal(f[1], "stratified");
    spp_rows++;
    fronts += !strcmp(f[11], "front");
    const int spp = atoi(f[2]);
    int i = 0;
    while (i < 3 && SPP[i] != spp) i++;
    if (i == 3) fail_msg("trace: unexpected spp %d in the quick report", spp);
    const double sigma_ref = strtod(f[6], NULL), corr = strtod(f[10], NULL);
    assert_true(isfinite(rmse) && rmse > 0);
    assert_true(isfinite(sigma_ref) && sigma_ref > 0);
    if (!(sigma_ref < 0.5 * rmse))
        fail_msg("trace %s %d spp: reference noise %g not well below the RMSE %g", f[1], spp,
                 sigma_ref, rmse);
    assert_true(isfinite(corr) && corr >= 0 && corr <= rmse);
    seen[m][i]++;
    err[m][i] = rmse;
}

void report_check_trace_end(const char *html, const char *md) {
    assert_int_equal(spp_rows, 3 * 2);
    assert_int_equal(tol_rows, 2);
    assert_true(fronts >= 1);
    for (int m = 0; m < 2; ++m)
        for (int i = 0; i < 3; ++i)
            if (seen[m][i] != 1)
                fail_msg("trace: %d rows for %s at %d spp", seen[m][i], m ? "random" : "stratified",
                         SPP[i]);
    assert_true(tol_seen[0] == 1 && tol_seen[1] == 1);
    /* 1 spp: the same picture whatever the sampling */
    if (err[0][0] != err[1][0])
        fail_msg("trace 1 spp: stratified RMSE %g differs from random %g", err[0][0], err[1][0]);
    for (int m = 0; m < 2; ++m)
        if (!(err[m][2] <= 0.5 * err[m][0]))
            fail_msg("trace %s: RMSE %g at 16 spp, more than half of %g at 1 spp",
                     m ? "random" : "stratified", err[m][2], err[m][0]);
    if (!(err[0][2] <= 0.9 * err[1][2]))
        fail_msg("trace 16 spp: stratified RMSE %g not 10 %% below random %g", err[0][2],
                 err[1][2]);
    /* the coarse tolerance shows (21 pixels at 32 x 24): the option takes effect */
    assert_true(tol_err[0] > 0 && tol_px[0] >= 1);
    assert_true(tol_err[1] <= tol_err[0]);
    if (!(tol_px[1] <= 0.01 * 32 * 24))
        fail_msg("trace: %g pixels differ at patch tolerance 1e-6", tol_px[1]);
    const char *const charts[2] = {"trace_spp.png", "trace_tol.png"};
    for (int k = 0; k < 2; ++k) {
        char ref[64];
        snprintf(ref, sizeof ref, "src=\"%s\"", charts[k]);
        if (!strstr(html, ref)) fail_msg("the page does not show %s", charts[k]);
        assert_non_null(strstr(md, charts[k]));
    }
    assert_non_null(strstr(html, "<h2>Ray tracer: samples per pixel</h2>"));
    assert_non_null(strstr(html, "<h2>Ray tracer: patch tolerance</h2>"));
    printf("trace: RMSE at 1/4/16 spp stratified %.4g %.4g %.4g, random %.4g %.4g %.4g (16 spp: "
           "<= 1/2 of 1 spp, stratified <= 0.9 x random); patch tolerance 1e-2: RMSE %.3g, %g "
           "pixels; 1e-6: RMSE %.3g, %g pixels\n",
           err[0][0], err[0][1], err[0][2], err[1][0], err[1][1], err[1][2], tol_err[0], tol_px[0],
           tol_err[1], tol_px[1]);
}
