/* casteljau report, section "render": the rasterizer (cj_render_raster) on the demo scene of
 * `casteljau render --demo` (the textured, Phong-lit Utah teapot with its control net on a
 * checkered floor), screen tolerance tol_px x samples per pixel, against a reference rendered
 * once at the tightest tolerance and 16 spp.
 *
 * Error: the share (in %) of pixels whose 8-bit sRGB colour (cj_render_image_to_srgb8, over
 * the scene's background) differs from the reference's by more than one level in any of R, G,
 * B; next to it the RMSE and the largest difference in 8-bit levels over all R, G, B values,
 * and the differing share against the reference tessellation at the same spp (tol_px alone).
 * Cost: ms per full frame on one thread, tessellation included (no render cache: a user who
 * picks tol_px pays the tessellation every time the view changes), the median of interleaved
 * runs. From the stage report: the teapot's triangles and the bound in pixels the pipeline
 * proved. Instructions per frame by callgrind on the same scene at WL_W x WL_H, every cell in
 * one valgrind run (workload "render:all"; "render:TOL:SPP" runs one cell). */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/image_io.h"
#include "casteljau/render.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The callgrind workload's frame is small: at the finest tolerance a frame is mostly
 * tessellation, and the 18 cells under callgrind must stay within a few minutes (one frame
 * each in one valgrind run, "render:all"; 3 frames and 2 valgrind start-ups per cell with
 * report_callgrind took 3.4 min on the busy machine). */
enum { NT_MAX = 6, NS_MAX = 3, RUNS_MAX = 8, WL_W = 96, WL_H = 72 };

static const double TOL_FULL[] = {4, 2, 1, 0.5, 0.25, 0.1}, TOL_QUICK[] = {2, 0.25};
static const int SPP_FULL[] = {1, 4, 16}, SPP_QUICK[] = {1, 4};
static const cj_rgba COL[NS_MAX] = {
    {0xd6, 0x27, 0x28, 255}, {0xff, 0x7f, 0x0e, 255}, {0x1f, 0x77, 0xb4, 255}};
static const cj_chart_marker MK[NS_MAX] = {CJ_MARKER_SQUARE, CJ_MARKER_TRIANGLE, CJ_MARKER_CIRCLE};

static cj_status frame(const cj_scene *s, int w, int h, double tol, int spp, cj_render_cache *cache,
                       cj_render_image **img, cj_stage_report *rep) {
    cj_render_options o = cj_render_options_defaults();
    o.width = w, o.height = h, o.spp = spp, o.tol_px = tol, o.cache = cache;
    o.threads = 1; /* deterministic instruction counts; steadier times on a shared machine */
    return cj_render_raster(s, &o, 0, NULL, img, rep);
}

/* The teapot's triangles, the larger proven bound (patches, floor) and the tessellation's
 * seconds, from the stage report. */
static void tess_figures(const cj_stage_report *rep, double *tris, double *bound, double *sec) {
    *tris = 0, *bound = 0, *sec = 0;
    static const char *const ST[2] = {"tessellate_patches", "tessellate_surfaces"};
    for (int k = 0; k < 2; ++k) {
        const cj_stage *s = cj_stage_report_find(rep, ST[k]);
        if (!s) continue;
        if (k == 0) *tris = (double)s->out;
        *sec += s->seconds;
        for (int i = 0; i < s->extra_count; ++i)
            if (!strcmp(s->extra[i].key, "bound_px")) *bound = fmax(*bound, s->extra[i].value);
    }
}

typedef struct diff {
    double pct, rmse; /* % of pixels off by > 1 level; RMSE in levels over R, G, B */
    int maxd;         /* largest difference in levels */
} diff;

static diff compare(const uint8_t *a, const uint8_t *ref, size_t npx) {
    diff d = {0, 0, 0};
    size_t off = 0;
    double sq = 0;
    for (size_t p = 0; p < npx; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int e = abs((int)a[4 * p + c] - (int)ref[4 * p + c]);
            sq += (double)(e * e);
            if (e > worst) worst = e;
        }
        off += worst > 1;
        if (worst > d.maxd) d.maxd = worst;
    }
    d.pct = 100.0 * (double)off / (double)npx;
    d.rmse = sqrt(sq / (3.0 * (double)npx));
    return d;
}

static cj_status to_srgb(const cj_render_image *img, uint8_t *out) {
    return cj_render_image_to_srgb8(img, out, 0);
}

static int frames(const cj_scene *s, double tol, int spp, long n) {
    int rc = 0;
    for (long k = 0; k < n && !rc; ++k) {
        cj_render_image *img = NULL;
        rc = frame(s, WL_W, WL_H, tol, spp, NULL, &img, NULL) != CJ_OK;
        cj_render_image_destroy(img);
    }
    return rc;
}

/* cell i of the full table (tol index i / 3, spp index i % 3) */
static int render_cell(void *ctx, int i, long units) {
    return frames(ctx, TOL_FULL[i / NS_MAX], SPP_FULL[i % NS_MAX], units);
}

/* n frames at WL_W x WL_H, tol_px TOL, SPP samples, one thread; "render:all": every cell of
 * the full table (report_cells_workload). */
int report_render_workload(const char *spec, long n) {
    double tol = 0;
    int spp = 0, all = !strcmp(spec, "render:all");
    if (!all && (sscanf(spec, "render:%lf:%d", &tol, &spp) != 2 || !(tol >= 1e-3 && tol <= 100) ||
                 (spp != 1 && spp != 4 && spp != 16)))
        return report_fail("bad workload '%s' (render:TOL:SPP, SPP 1, 4 or 16; render:all)", spec);
    cj_scene *s = NULL;
    if (cj_render_demo_scene(report_teapot_path(), NULL, &s))
        return report_error("%s", cj_last_error());
    const int rc =
        all ? report_cells_workload(NT_MAX * NS_MAX, n, render_cell, s) : frames(s, tol, spp, n);
    cj_scene_destroy(s);
    return rc ? report_error("%s", cj_last_error()) : 0;
}

/* render_pictures.png: the reference | the coarsest choice at 1 spp | where they differ (red
 * over the dimmed reference), so a reader sees what "differing pixels" are. */
static int pictures(report *r, int w, int h, const uint8_t *ref, const uint8_t *coarse,
                    double tol) {
    const int W3 = 3 * w;
    uint8_t *pic = malloc((size_t)W3 * (size_t)h * 4);
    if (!pic) return report_error("render: out of memory");
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint8_t *a = ref + 4 * ((size_t)y * (size_t)w + (size_t)x),
                          *b = coarse + 4 * ((size_t)y * (size_t)w + (size_t)x);
            uint8_t *row = pic + 4 * (size_t)y * (size_t)W3;
            int worst = 0;
            for (int c = 0; c < 3; ++c) {
                row[4 * x + c] = a[c];
                row[4 * (w + x) + c] = b[c];
                const int e = abs((int)a[c] - (int)b[c]);
                if (e > worst) worst = e;
                row[4 * (2 * w + x) + c] = (uint8_t)(a[c] / 3);
            }
            if (worst > 1) {
                uint8_t *m = row + 4 * (2 * w + x);
                m[0] = 255, m[1] = (uint8_t)(worst > 16 ? 0 : 160), m[2] = 0;
            }
            row[4 * x + 3] = row[4 * (w + x) + 3] = row[4 * (2 * w + x) + 3] = 255;
        }
    char path[4096];
    snprintf(path, sizeof path, "%s/render_pictures.png", r->dir);
    const cj_status st = cj_image_write(path, W3, h, pic, 0);
    free(pic);
    if (st) return report_error("render_pictures.png: %s", cj_last_error());
    fprintf(r->html,
            "<p><img src=\"render_pictures.png\" width=\"%d\" height=\"%d\" alt=\"reference, "
            "tol %g px at 1 spp, differing pixels\"><br>Left: the reference. Middle: tol_px = %g "
            "at 1 spp. Right: the pixels where they differ by more than one level (orange: by at "
            "most 16 levels, red: by more).</p>\n",
            W3 > 960 ? 960 : W3, W3 > 960 ? h * 960 / W3 : h, tol, tol);
    fprintf(r->md, "![render_pictures.png](render_pictures.png)\n\n");
    return 0;
}

int report_render(report *r) {
    const int nt = r->quick ? 2 : 6, ns = r->quick ? 2 : 3, runs = r->quick ? 3 : 5;
    const double *tols = r->quick ? TOL_QUICK : TOL_FULL;
    const int *spps = r->quick ? SPP_QUICK : SPP_FULL;
    /* full: 512 x 384 keeps the demo's 4:3 framing with enough pixels that one differing pixel
     * is 0.0005 %, and its 16 spp frames stay under a second on one core */
    const int w = r->quick ? 128 : 512, h = r->quick ? 96 : 384;
    const double ref_tol = r->quick ? 0.1 : 0.02; /* quick: 2.5x below its finest */
    const size_t npx = (size_t)w * (size_t)h;
    cj_scene *s = NULL;
    if (cj_render_demo_scene(report_teapot_path(), NULL, &s)) {
        fprintf(r->html, "<h2>Renderer</h2><p>Skipped: no teapot.bpt (%s).</p>\n", cj_last_error());
        return 0;
    }
    /* ref: tol ref_tol at 16 spp; same[k]: at spps[k] (tessellation alone), from the same
     * tessellation (a render cache: the same view and tolerance give the same image) */
    uint8_t *ref = malloc(npx * 4), *cur = malloc(npx * 4), *coarse = malloc(npx * 4),
            *same[NS_MAX] = {NULL, NULL, NULL};
    for (int k = 0; k < ns; ++k) same[k] = spps[k] == 16 ? NULL : malloc(npx * 4);
    cj_render_cache *cache = NULL;
    double ms[NT_MAX * NS_MAX], spread[NT_MAX * NS_MAX], tris[NT_MAX * NS_MAX],
        bound[NT_MAX * NS_MAX], instr[NT_MAX * NS_MAX], tm[NT_MAX * NS_MAX][RUNS_MAX],
        tess_ms[NT_MAX][NS_MAX * RUNS_MAX], tess_med[NT_MAX];
    diff d[NT_MAX * NS_MAX], dsame[NT_MAX * NS_MAX];
    double ref_tris = 0, ref_bound = 0, ref_ms = 0;
    cj_stage_report rep;
    cj_render_image *img = NULL;
    int oom = !ref || !cur || !coarse;
    for (int k = 0; k < ns; ++k) oom |= spps[k] != 16 && !same[k];
    cj_status st = oom ? CJ_ERR_NOMEM : CJ_OK;
    if (!st) st = cj_render_cache_create(NULL, &cache);
    if (!st) {
        const double t0 = report_now_ns();
        st = frame(s, w, h, ref_tol, 16, cache, &img, &rep);
        ref_ms = (report_now_ns() - t0) / 1e6;
    }
    if (!st) st = to_srgb(img, ref);
    cj_render_image_destroy(img), img = NULL;
    if (!st) {
        double sec;
        tess_figures(&rep, &ref_tris, &ref_bound, &sec);
    }
    for (int k = 0; k < ns && !st; ++k) {
        if (spps[k] == 16) {
            same[k] = ref;
            continue;
        }
        st = frame(s, w, h, ref_tol, spps[k], cache, &img, NULL);
        if (!st) st = to_srgb(img, same[k]);
        cj_render_image_destroy(img), img = NULL;
    }
    cj_render_cache_destroy(cache);
    /* cell i = tol index * ns + spp index; the cells alternate within every run */
    for (int run = 0; run < runs && !st; ++run)
        for (int i = 0; i < nt * ns && !st; ++i) {
            const int t = i / ns, k = i % ns;
            const double t0 = report_now_ns();
            st = frame(s, w, h, tols[t], spps[k], NULL, &img, &rep);
            tm[i][run] = (report_now_ns() - t0) / 1e6;
            if (st) break;
            double sec;
            tess_figures(&rep, &tris[i], &bound[i], &sec);
            tess_ms[t][run * ns + k] = 1e3 * sec;
            if (run == 0) {
                st = to_srgb(img, cur);
                d[i] = compare(cur, ref, npx);
                dsame[i] = compare(cur, same[k], npx);
                if (i == 0) memcpy(coarse, cur, npx * 4);
            }
            cj_render_image_destroy(img), img = NULL;
        }
    cj_scene_destroy(s);
    free(cur);
    for (int k = 0; k < ns; ++k)
        if (same[k] != ref) free(same[k]);
    if (st) {
        free(ref), free(coarse);
        return report_error("render: %s", oom ? "out of memory" : cj_last_error());
    }
    for (int i = 0; i < nt * ns; ++i) {
        ms[i] = report_median(tm[i], (size_t)runs, &spread[i]);
        instr[i] = NAN;
    }
    /* one frame per cell, every cell in one callgrind run (the full grid is the workload's) */
    if (!r->quick) report_callgrind_cells(r, "render:all", 1, NT_MAX * NS_MAX, instr);
    for (int t = 0; t < nt; ++t) tess_med[t] = report_median(tess_ms[t], (size_t)(runs * ns), NULL);
    int dom[NT_MAX * NS_MAX];
    double err[NT_MAX * NS_MAX];
    for (int i = 0; i < nt * ns; ++i) err[i] = d[i].pct;
    report_pareto((size_t)(nt * ns), ms, err, dom);

    fprintf(r->html,
            "<h2>Renderer</h2>\n<p>cj_render_raster on the demo scene (<code>casteljau render "
            "--demo</code>: the textured, Phong-lit Utah teapot with its control net on a "
            "checkered floor) at %d&times;%d, screen tolerance tol_px &times; samples per pixel, "
            "against a reference rendered once at tol_px = %g and 16 spp (%.0f teapot triangles, "
            "bound %.3g px, %.0f ms). Differing: the share of pixels whose 8-bit sRGB colour "
            "differs from the reference's by more than one level in any of R, G, B; RMSE and max: "
            "in 8-bit levels over all R, G, B values. Tess only: the differing share against the "
            "reference tessellation rendered at the same spp (what tol_px alone costs; at 1 spp "
            "the rest is sampling: edges, texture filtering, highlights). Cost: ms per full frame "
            "on one thread "
            "(the image does not depend on the thread count), tessellation included (no render "
            "cache: picking tol_px means paying its tessellation whenever the view changes; the "
            "tess column is that part, the rest is what a warm cache would cost), median of %d "
            "interleaved runs. Triangles: the teapot's, bound: the largest the pipeline proved "
            "(stage report). Instructions per frame: callgrind on the same scene at %d&times;%d, "
            "one thread. Pareto front over all choices (ms against differing %%); on the chart a "
            "choice with no differing pixel would be drawn at half a pixel's share.</p>\n"
            "<table><tr><th>spp</th><th>tol_px</th><th>triangles</th><th>bound_px</th>"
            "<th>differing</th><th>tess "
            "only</th><th>RMSE</th><th>max</th><th>ms/frame</th><th>spread</th>"
            "<th>tess ms</th><th>instr/frame (%d&times;%d)</th><th class=l>Pareto</th></tr>\n",
            w, h, ref_tol, ref_tris, ref_bound, ref_ms, runs, WL_W, WL_H, WL_W, WL_H);
    fprintf(r->md,
            "## Renderer (demo teapot, %dx%d, reference tol_px %g at 16 spp)\n\n| spp | "
            "tol_px | triangles | bound_px | differing %% | tess only %% | RMSE | ms/frame | "
            "Pareto |\n|---|---|---|---|---|---|---|---|---|\n",
            w, h, ref_tol);
    for (int k = 0; k < ns; ++k)
        for (int t = 0; t < nt; ++t) {
            const int i = t * ns + k;
            char par[96];
            if (dom[i] < 0)
                snprintf(par, sizeof par, "front");
            else
                snprintf(par, sizeof par, "dominated by %d spp at tol %g", spps[dom[i] % ns],
                         tols[dom[i] / ns]);
            fprintf(
                r->html,
                "<tr%s><td>%d</td><td>%g</td><td>%.0f</td><td>%.3g</td><td>%.3g %%</td>"
                "<td>%.3g %%</td><td>%.3g</td><td>%d</td><td>%.1f</td><td>%.0f %%</td><td>%.1f</td>"
                "<td>%.4g</td><td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", spps[k], tols[t], tris[i], bound[i], d[i].pct,
                dsame[i].pct, d[i].rmse, d[i].maxd, ms[i], spread[i], tess_med[t], instr[i], par);
            fprintf(r->md, "| %d | %g | %.0f | %.3g | %.3g | %.3g | %.3g | %.1f | %s |\n", spps[k],
                    tols[t], tris[i], bound[i], d[i].pct, dsame[i].pct, d[i].rmse, ms[i], par);
            fprintf(r->tsv, "render\t%d spp\t%g\t\t%.6g\t%.6g\t%.6g\t%.6g\t%.3f\t%.6g\t%.0f\t%s\n",
                    spps[k], tols[t], d[i].pct, d[i].rmse, bound[i], 1e6 * ms[i], spread[i],
                    instr[i], tris[i], dom[i] < 0 ? "front" : "dominated");
        }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");

    /* error against cost; no differing pixel at all is drawn at half a pixel's share */
    const double floor_pct = 50.0 / (double)npx;
    cj_chart *c = NULL;
    int rc = cj_chart_create(NULL, &c) ? report_error("%s", cj_last_error()) : 0;
    if (!rc) {
        cj_chart_set_title(c,
                           "Renderer: differing pixels vs ms per frame (ringed: dominated, tol)");
        cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
        cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ms per frame, one thread (median)");
        cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "% pixels off by > 1 level (0 at floor)");
        report_front_series(c, (size_t)(nt * ns), ms, err, dom, floor_pct, "Pareto front");
        for (int k = 0; k < ns; ++k) {
            double x[NT_MAX], y[NT_MAX];
            char label[32];
            snprintf(label, sizeof label, "%d spp", spps[k]);
            for (int t = 0; t < nt; ++t)
                x[t] = ms[t * ns + k], y[t] = fmax(err[t * ns + k], floor_pct);
            cj_chart_series_opts o = {label, COL[k], 1.5, MK[k], 5.0};
            cj_chart_add_series(c, x, y, (size_t)nt, &o);
            for (int t = 0; t < nt; ++t) {
                if (dom[t * ns + k] < 0) continue;
                char txt[16];
                snprintf(txt, sizeof txt, "%g", tols[t]);
                cj_chart_annotate(c, x[t], y[t], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
            }
        }
        rc = report_chart(r, c, "render.png", 760, 480);
        cj_chart_destroy(c), c = NULL;
    }
    /* where the time goes: frame and tessellation ms against tol_px */
    if (!rc && cj_chart_create(NULL, &c)) rc = report_error("%s", cj_last_error());
    if (!rc) {
        cj_chart_set_title(c, "Renderer: ms per frame and tessellation vs tol_px (triangles)");
        cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
        cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "tol_px (screen tolerance, pixels)");
        cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "ms (median, one thread)");
        for (int k = 0; k < ns; ++k) {
            double y[NT_MAX];
            char label[40];
            snprintf(label, sizeof label, "frame, %d spp", spps[k]);
            for (int t = 0; t < nt; ++t) y[t] = ms[t * ns + k];
            cj_chart_series_opts o = {label, COL[k], 1.5, MK[k], 5.0};
            cj_chart_add_series(c, tols, y, (size_t)nt, &o);
        }
        double y[NT_MAX];
        for (int t = 0; t < nt; ++t) y[t] = fmax(tess_med[t], 1e-3);
        cj_chart_series_opts o = {"tessellation", cj_rgba_make(0x30, 0x30, 0x30, 255), 2.5,
                                  CJ_MARKER_DIAMOND, 5.0};
        cj_chart_add_series(c, tols, y, (size_t)nt, &o);
        for (int t = 0; t < nt; ++t) {
            char txt[32];
            snprintf(txt, sizeof txt, "%.0f tri", tris[t * ns]);
            cj_chart_annotate(c, tols[t], y[t], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
        }
        rc = report_chart(r, c, "render_cost.png", 760, 480);
        cj_chart_destroy(c);
    }
    if (!rc) rc = pictures(r, w, h, ref, coarse, tols[0]);
    free(ref), free(coarse);
    return rc;
}
