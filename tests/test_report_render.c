/* test_report: the checks of the "render" section (report/src/report_render.c): the rasterizer on
 * the demo teapot, tol_px x spp against a 16-spp reference at a tighter tolerance. Per row: the
 * fields parse, the differing share is a percentage, the proven bound is within the tolerance
 * asked for (the demo's camera keeps the teapot far from the near plane, so the pipeline never
 * has to coarsen), the triangle count is plausible, instructions are absent (quick) or
 * positive. At the end: the quick grid (2 tolerances x 2 spp), the same triangles at the same
 * tolerance whatever the spp, more triangles at a finer tolerance, the coarsest 1-spp choice
 * worse than the finest at the highest spp, a finer tolerance better at the highest spp, a
 * Pareto front, and the page showing the section's charts and pictures. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "test_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAXROWS = 32 };
static int rows, fronts;
static struct {
    double tol, pct, tris;
    int spp;
} cell[MAXROWS];

void report_check_render_row(char *const f[12]) {
    char *end = NULL;
    const long spp = strtol(f[1], &end, 10);
    assert_true(spp == 1 || spp == 4 || spp == 16);
    assert_string_equal(end, " spp");
    const double tol = strtod(f[2], NULL), pct = strtod(f[4], NULL), rmse = strtod(f[5], NULL),
                 bound = strtod(f[6], NULL), instr = strtod(f[9], NULL), tris = strtod(f[10], NULL);
    assert_true(isfinite(tol) && tol > 0);
    if (!(pct >= 0 && pct <= 100)) fail_msg("render %s at tol %g: differing %g %%", f[1], tol, pct);
    assert_true(isfinite(rmse) && rmse >= 0 && rmse <= 255);
    if (!(isfinite(bound) && bound > 0 && bound <= tol * (1 + 1e-9)))
        fail_msg("render %s at tol %g px: proven bound %g px", f[1], tol, bound);
    assert_true(tris >= 32 * 2); /* at least two triangles per teapot patch */
    assert_true(isnan(instr) || instr > 0);
    assert_true(!strcmp(f[11], "front") || !strcmp(f[11], "dominated"));
    fronts += !strcmp(f[11], "front");
    assert_true(rows < MAXROWS);
    cell[rows].tol = tol, cell[rows].pct = pct, cell[rows].tris = tris, cell[rows].spp = (int)spp;
    rows++;
}

void report_check_render_end(const char *html, const char *md) {
    assert_int_equal(rows, 2 * 2); /* quick: tol_px 2, 0.25 x 1, 4 spp */
    int lo_spp = 99, hi_spp = 0;
    double coarse = 0, fine = INFINITY;
    for (int i = 0; i < rows; ++i) {
        lo_spp = cell[i].spp < lo_spp ? cell[i].spp : lo_spp;
        hi_spp = cell[i].spp > hi_spp ? cell[i].spp : hi_spp;
        coarse = fmax(coarse, cell[i].tol), fine = fmin(fine, cell[i].tol);
        for (int j = 0; j < rows; ++j) {
            if (cell[i].tol == cell[j].tol && cell[i].tris != cell[j].tris)
                fail_msg("tol %g px: %g triangles at %d spp, %g at %d spp", cell[i].tol,
                         cell[i].tris, cell[i].spp, cell[j].tris, cell[j].spp);
            if (cell[i].tol < cell[j].tol && !(cell[i].tris > cell[j].tris))
                fail_msg("tol %g px gives %g triangles, not more than %g at tol %g px", cell[i].tol,
                         cell[i].tris, cell[j].tris, cell[j].tol);
        }
    }
    double worst = -1, best = -1, hi_coarse = -1;
    for (int i = 0; i < rows; ++i) {
        if (cell[i].spp == lo_spp && cell[i].tol == coarse) worst = cell[i].pct;
        if (cell[i].spp == hi_spp && cell[i].tol == fine) best = cell[i].pct;
        if (cell[i].spp == hi_spp && cell[i].tol == coarse) hi_coarse = cell[i].pct;
    }
    assert_true(worst >= 0 && best >= 0 && hi_coarse >= 0);
    if (!(worst > best))
        fail_msg("tol %g px at %d spp differs in %g %% of the pixels, no more than tol %g px at "
                 "%d spp (%g %%)",
                 coarse, lo_spp, worst, fine, hi_spp, best);
    if (!(best < hi_coarse))
        fail_msg("at %d spp, tol %g px differs in %g %%, not fewer than tol %g px (%g %%)", hi_spp,
                 fine, best, coarse, hi_coarse);
    assert_true(fronts >= 1);
    assert_non_null(strstr(html, "<h2>Renderer</h2>"));
    assert_non_null(strstr(md, "## Renderer"));
    static const char *const IMG[3] = {"src=\"render.png\"", "src=\"render_cost.png\"",
                                       "src=\"render_pictures.png\""};
    for (int k = 0; k < 3; ++k)
        if (!strstr(html, IMG[k])) fail_msg("the page does not show %s", IMG[k]);
    printf("render: %d rows, bounds within tol_px, triangles rise as tol_px falls (same at every "
           "spp), tol %g at %d spp differs in %.3g %% of the pixels, tol %g at %d spp in %.3g %% "
           "(%.3g %% at tol %g), %d on the front, charts shown\n",
           rows, coarse, lo_spp, worst, fine, hi_spp, best, hi_coarse, coarse, fronts);
}
