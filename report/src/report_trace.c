/* casteljau report, section "trace": what the ray tracer's samples cost.
 *
 * Part 1, distribution ray tracing: a scene built here whose picture needs many samples (an
 * area light's soft shadows, a glossy sphere, a checkered floor whose edges alias at 1 spp),
 * traced by cj_render_trace_with_options at spp 1 .. 256 (quick 1 .. 16) with stratified and with
 * plain random sampling (cj_trace_options.random_sampling). Error: the RMSE of the linear radiance
 * against a reference, sqrt(Σ (c − ref)² / 3P) over the P pixels and the 3 channels. The
 * reference is the mean of two random-sampled high-spp renders A and B with other seeds than
 * the measured images (same seeds would correlate the errors); A and B are independent, so the
 * reference's own noise is estimated as σ_ref = RMSE(A, B) / 2 and the error against the true
 * image as sqrt(max(0, RMSE² − σ_ref²)). Random-sampled, so that the reference does not share
 * the stratification of the rows it judges; the full report also renders the stratified pair
 * and prints how far it is from the reference. Cost: ms per frame on one thread (the
 * image does not depend on the thread count), median of interleaved runs.
 *
 * Part 2, what the direct Bézier-patch intersection's accuracy costs: the trace demo (the
 * teapot's 32 patches intersected directly, a mirror and a glass sphere) at 1 spp with
 * cj_trace_options.patch_tolerance from 1e-1 to 1e-9 of the teapot's size, against the image
 * at 1e-10: RMSE, pixels differing by more than 1/255, the largest distance from an accepted
 * hit to its ray (stage "patch_rays", max_err), ms per frame.
 *
 * Instruction counts: `casteljau report --workload trace:stratified|random:SPP N` and
 * `trace:patch:TOLEXP N` trace N frames of the same scene at the full report's size (40 x 30)
 * on one thread. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/trace.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NSPP 5
#define NTOL 8
/* the full report's frame, also the workload's: callgrind of all 18 cells takes about 2.5
 * minutes at this size (the 256-spp cells most of it) */
#define WL_W    40
#define WL_H    30
#define REF_TOL 1e-10

static const int SPP_FULL[NSPP] = {1, 4, 16, 64, 256}, SPP_QUICK[] = {1, 4, 16};
static const int TE_FULL[NTOL] = {1, 2, 3, 4, 5, 6, 7, 9}, TE_QUICK[] = {2, 6};
static const char *const SNAME[2] = {"stratified", "random"};
/* the measured images and the two halves of the reference use unrelated seeds */
static const uint64_t SEED_IMG = 777, SEED_REF_A = 1001, SEED_REF_B = 2002;

/* A floor with large checks, a diffuse sphere and a glossy one under a square area light and
 * a little ambient light: soft shadows, glossy reflections and aliased checker edges. */
static cj_status soft_scene(cj_scene **out) {
    cj_scene *sc = NULL;
    cj_status st = cj_scene_create(NULL, &sc);
    if (st) return st;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 3.2, 6.5);
    cam.gaze = cj_v3(0, -2.6, -6.5);
    cam.fov_y = 0.75;
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = 64;
    set.height = 48;
    set.max_depth = 3;
    set.background = (cj_rgb){0.05, 0.06, 0.09};
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT), area = cj_light_defaults(CJ_LIGHT_AREA);
    amb.intensity = 0.15;
    area.position = cj_v3(-1.5, 4, -1.2);
    area.edge_u = cj_v3(2.5, 0, 0);
    area.edge_v = cj_v3(0, 0, 2.5);
    area.intensity = 0.9;
    cj_texture tex = cj_texture_defaults(CJ_TEX_CHECKER);
    tex.checks_u = tex.checks_v = 10;
    tex.checker_a = (cj_rgb){0.85, 0.85, 0.85};
    tex.checker_b = (cj_rgb){0.25, 0.25, 0.3};
    cj_material floor = cj_material_defaults(), red = cj_material_defaults(),
                gloss = cj_material_defaults();
    red.color = (cj_rgb){0.8, 0.2, 0.15};
    gloss.color = (cj_rgb){0.7, 0.75, 0.8};
    gloss.kd = 0.2;
    gloss.ks = 0.5;
    gloss.alpha = 80;
    gloss.mirror = 0.7;
    gloss.glossiness = 60;
    int ti = 0, mf = 0, mr = 0, mg = 0, gf = 0, gr = 0, gg = 0;
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    cj_planar_patch_init(&g.u.planar, cj_v3(-10, 0, 10), cj_v3(20, 0, 0), cj_v3(0, 0, -20));
    cj_geometry s1 = {0}, s2 = {0};
    s1.kind = s2.kind = CJ_GEOM_SPHERE;
    s1.u.sphere.center = cj_v3(-1.1, 1, 0), s1.u.sphere.radius = 1;
    s2.u.sphere.center = cj_v3(1.3, 0.8, 0.9), s2.u.sphere.radius = 0.8;
    if (!st) st = cj_scene_set_camera(sc, &cam);
    if (!st) st = cj_scene_set_settings(sc, &set);
    if (!st) st = cj_scene_add_light(sc, &amb, NULL);
    if (!st) st = cj_scene_add_light(sc, &area, NULL);
    if (!st) st = cj_scene_add_texture(sc, &tex, &ti);
    floor.texture = ti;
    if (!st) st = cj_scene_add_material(sc, &floor, &mf);
    if (!st) st = cj_scene_add_material(sc, &red, &mr);
    if (!st) st = cj_scene_add_material(sc, &gloss, &mg);
    if (!st) st = cj_scene_add_geometry(sc, &g, &gf);
    if (!st) st = cj_scene_add_geometry(sc, &s1, &gr);
    if (!st) st = cj_scene_add_geometry(sc, &s2, &gg);
    const int geo[3] = {gf, gr, gg}, mat[3] = {mf, mr, mg};
    for (int i = 0; i < 3 && !st; ++i) {
        cj_node n = cj_node_defaults(geo[i], mat[i]);
        st = cj_scene_add_node(sc, &n, NULL);
    }
    if (st) {
        cj_scene_destroy(sc);
        return st;
    }
    *out = sc;
    return CJ_OK;
}

typedef struct cell {
    int spp, random;
    double ptol; /* 0: the default */
} cell;

static cj_status frame(const cj_scene *sc, int w, int h, const cell *c, int threads, uint64_t seed,
                       cj_render_image **img, cj_stage_report *rep) {
    cj_render_options o = cj_render_options_defaults();
    o.width = w, o.height = h, o.spp = c->spp, o.threads = threads;
    o.use_seed = 1, o.seed = seed;
    const cj_trace_options to = {c->random, c->ptol, 0, 0, 0};
    return cj_render_trace_with_options(sc, &o, &to, 0, NULL, img, rep);
}

/* sqrt(Σ (a − b)² / 3P) over the colour channels of P pixels. */
static double rmse(const float *a, const double *b, size_t np) {
    double s = 0;
    for (size_t i = 0; i < np; ++i)
        for (int k = 0; k < 3; ++k) {
            const double d = (double)a[4 * i + k] - b[4 * i + k];
            s += d * d;
        }
    return sqrt(s / (3.0 * (double)np));
}

/* ms per frame of each cell on one thread: `runs` interleaved runs (the direction of the
 * sweep alternates run by run), each repeating frames for at least min_ms. */
static int time_cells(const cj_scene *sc, int w, int h, const cell *cells, int nc, int runs,
                      double min_ms, double *ms, double *spread) {
    double t[16][16]; /* nc <= 2 * NSPP, runs <= 7 */
    for (int k = 0; k < runs; ++k)
        for (int j = 0; j < nc; ++j) {
            const int i = k % 2 ? nc - 1 - j : j;
            const double t0 = report_now_ns();
            double t1;
            long reps = 0;
            do {
                cj_render_image *img = NULL;
                if (frame(sc, w, h, &cells[i], 1, SEED_IMG, &img, NULL)) return 1;
                cj_render_image_destroy(img);
                reps++;
            } while ((t1 = report_now_ns()) - t0 < 1e6 * min_ms);
            t[i][k] = (t1 - t0) / 1e6 / (double)reps;
        }
    for (int i = 0; i < nc; ++i) ms[i] = report_median(t[i], (size_t)runs, &spread[i]);
    return 0;
}

int report_trace_workload(const char *spec, long n) {
    char kind[16] = "";
    int v = 0;
    if (sscanf(spec, "trace:%15[a-z]:%d", kind, &v) != 2)
        return report_fail("bad workload '%s' (trace:stratified|random:SPP, "
                           "trace:patch:TOLEXP)",
                           spec);
    cell c = {1, 0, 0};
    cj_scene *sc = NULL;
    cj_status st;
    if (!strcmp(kind, "patch") && v >= 1 && v <= 10) {
        c.ptol = pow(10.0, -v);
        st = cj_trace_demo_scene(report_teapot_path(), NULL, &sc);
    } else if ((!strcmp(kind, "stratified") || !strcmp(kind, "random")) && v >= 1 && v <= 4096) {
        c.spp = v, c.random = kind[0] == 'r';
        st = soft_scene(&sc);
    } else
        return report_fail("bad workload '%s'", spec);
    if (st) return report_error("trace workload: %s", cj_last_error());
    for (long k = 0; k < n && !st; ++k) {
        cj_render_image *img = NULL;
        st = frame(sc, WL_W, WL_H, &c, 1, SEED_IMG, &img, NULL);
        cj_render_image_destroy(img);
    }
    cj_scene_destroy(sc);
    return st ? report_error("trace workload: %s", cj_last_error()) : 0;
}

/* Part 1: spp x sampling against RMSE. */
static int trace_spp(report *r) {
    const int *spps = r->quick ? SPP_QUICK : SPP_FULL;
    const int ns = r->quick ? 3 : NSPP, nc = 2 * ns, runs = r->quick ? 3 : 7;
    const int W = r->quick ? 32 : WL_W, H = r->quick ? 24 : WL_H, REF = r->quick ? 512 : 4096;
    const size_t np = (size_t)W * H;
    cj_scene *sc = NULL;
    if (soft_scene(&sc)) return report_error("trace: %s", cj_last_error());
    /* the reference: two independent renders A and B on all cores, averaged, random-sampled
     * (an estimator unlike the stratified rows it judges) */
    cj_render_image *ra = NULL, *rb = NULL;
    const cell rc = {REF, 1, 0};
    const double t0 = report_now_ns();
    if (frame(sc, W, H, &rc, 0, SEED_REF_A, &ra, NULL) ||
        frame(sc, W, H, &rc, 0, SEED_REF_B, &rb, NULL)) {
        cj_render_image_destroy(ra);
        cj_scene_destroy(sc);
        return report_error("trace reference: %s", cj_last_error());
    }
    const double ref_s = (report_now_ns() - t0) / 1e9;
    double *ref = malloc(np * 4 * sizeof *ref), *half = malloc(np * 4 * sizeof *half);
    if (!ref || !half) {
        free(ref), free(half);
        cj_render_image_destroy(ra), cj_render_image_destroy(rb), cj_scene_destroy(sc);
        return report_error("trace: out of memory");
    }
    for (size_t i = 0; i < 4 * np; ++i) {
        ref[i] = 0.5 * ((double)ra->rgba[i] + rb->rgba[i]);
        half[i] = rb->rgba[i];
    }
    /* RMSE(A, B)² = 2 σ_A², and the mean of A and B has σ_ref² = σ_A² / 2 */
    const double sigma_ref = rmse(ra->rgba, half, np) / 2;
    cj_render_image_destroy(ra), cj_render_image_destroy(rb);
    /* full report: the same pair stratified, to show that both samplings converge to one
     * picture (until 2026-11 the tracer paired pixel and light strata by a cyclic shift, and
     * this pair stayed 6x farther apart than the random one) */
    double strat_pair = NAN, strat_ref_dist = NAN;
    if (!r->quick) {
        const cell sc2 = {REF, 0, 0};
        if (frame(sc, W, H, &sc2, 0, SEED_REF_A, &ra, NULL) ||
            frame(sc, W, H, &sc2, 0, SEED_REF_B, &rb, NULL)) {
            cj_render_image_destroy(ra);
            free(ref), free(half), cj_scene_destroy(sc);
            return report_error("trace reference: %s", cj_last_error());
        }
        for (size_t i = 0; i < 4 * np; ++i) half[i] = rb->rgba[i];
        strat_pair = rmse(ra->rgba, half, np);
        strat_ref_dist = rmse(ra->rgba, ref, np);
        cj_render_image_destroy(ra), cj_render_image_destroy(rb);
    }
    free(half);
    cell cells[2 * NSPP];
    double err[2 * NSPP], corr[2 * NSPP], ms[2 * NSPP], spread[2 * NSPP], instr[2 * NSPP];
    for (int m = 0; m < 2; ++m)
        for (int i = 0; i < ns; ++i) {
            const int k = m * ns + i;
            cells[k] = (cell){spps[i], m, 0};
            cj_render_image *img = NULL;
            if (frame(sc, W, H, &cells[k], 0, SEED_IMG, &img, NULL)) {
                free(ref), cj_scene_destroy(sc);
                return report_error("trace: %s", cj_last_error());
            }
            err[k] = rmse(img->rgba, ref, np);
            corr[k] = sqrt(fmax(0.0, err[k] * err[k] - sigma_ref * sigma_ref));
            cj_render_image_destroy(img);
        }
    free(ref);
    /* timed with the two samplings of one spp next to each other, so that they see the same
     * load on the machine */
    cell tc[2 * NSPP];
    double tms[2 * NSPP], tsp[2 * NSPP];
    for (int k = 0; k < nc; ++k) tc[k] = cells[(k % 2) * ns + k / 2];
    if (time_cells(sc, W, H, tc, nc, runs, r->quick ? 2.0 : 40.0, tms, tsp)) {
        cj_scene_destroy(sc);
        return report_error("trace: %s", cj_last_error());
    }
    for (int k = 0; k < nc; ++k)
        ms[(k % 2) * ns + k / 2] = tms[k], spread[(k % 2) * ns + k / 2] = tsp[k];
    cj_scene_destroy(sc);
    for (int k = 0; k < nc; ++k) {
        char spec[64];
        snprintf(spec, sizeof spec, "trace:%s:%d", SNAME[cells[k].random], cells[k].spp);
        instr[k] = r->quick ? NAN : report_callgrind(r, spec, 1, NULL);
    }
    int dom[2 * NSPP];
    report_pareto((size_t)nc, ms, err, dom);
    fprintf(r->html,
            "<h2>Ray tracer: samples per pixel</h2>\n<p>cj_render_trace_with_options on a scene "
            "that needs "
            "many samples: a square area light over a checkered floor, a diffuse and a glossy "
            "sphere (mirror 0.7, Phong lobe exponent 60), max depth 3, %d&times;%d pixels. "
            "Stratified sampling jitters pixel positions in a k&times;k grid and draws area-light "
            "points stratified; random sampling draws both uniformly (glossy directions are "
            "random in both). At 1 spp both are the same picture: pixel centres, the light's "
            "centre, a sharp mirror (which of the two is then marked dominated is timing noise). "
            "Error: RMSE of the linear radiance over all pixels and the 3 "
            "channels against a reference, the mean of two independent %d-spp renders A and B "
            "with random sampling and other seeds than the measured images (%.1f s on all cores). "
            "Their difference gives the reference's own noise, &sigma;<sub>ref</sub> = RMSE(A, "
            "B) / 2 = %.3g: no RMSE much below it can be measured, and &radic;(RMSE&sup2; "
            "&minus; &sigma;<sub>ref</sub>&sup2;) estimates the error against the noise-free "
            "picture. Cost: ms per frame on one thread (the image is the same for any thread "
            "count), median of %d interleaved runs; instructions per %d&times;%d frame "
            "(callgrind, one thread). Pareto front over all choices.</p>\n",
            W, H, REF, ref_s, sigma_ref, runs, WL_W, WL_H);
    if (isfinite(strat_pair))
        fprintf(r->html,
                "<p>Both samplings converge to the same picture: two stratified %d-spp renders "
                "with the seeds of A and B differ by RMSE %.3g (the random pair: %.3g), and the "
                "first is %.3g from the reference. The tracer pairs a sample's pixel stratum "
                "with its area-light stratum through a random permutation per pixel "
                "(trace_shade.c); a fixed pairing would leave each pixel a variance that more "
                "samples do not lower.</p>\n",
                REF, strat_pair, 2 * sigma_ref, strat_ref_dist);
    fprintf(r->html,
            "<table><tr><th class=l>sampling</th><th>spp</th><th>RMSE</th>"
            "<th>RMSE &minus; ref. noise</th><th>ms/frame</th><th>spread</th>"
            "<th>instr/frame (%d&times;%d)</th><th class=l>Pareto</th></tr>\n",
            WL_W, WL_H);
    fprintf(r->md,
            "## Ray tracer: samples per pixel (soft shadows, glossy sphere, %dx%d)\n\n"
            "RMSE against the mean of two %d-spp random-sampled references; their own noise "
            "σ_ref = %.2g.\n\n"
            "| sampling | spp | RMSE | RMSE − ref. noise | ms/frame | instr/frame | Pareto |\n"
            "|---|---|---|---|---|---|---|\n",
            W, H, REF, sigma_ref);
    for (int k = 0; k < nc; ++k) {
        char par[96], ins[32];
        if (dom[k] < 0)
            snprintf(par, sizeof par, "front");
        else
            snprintf(par, sizeof par, "dominated by %s %d spp", SNAME[cells[dom[k]].random],
                     cells[dom[k]].spp);
        report_g3(ins, instr[k]);
        const char *name = SNAME[cells[k].random];
        fprintf(r->html,
                "<tr%s><td class=l>%s</td><td>%d</td><td>%.4g</td><td>%.4g</td><td>%.2f</td>"
                "<td>%.0f %%</td><td>%s</td><td class=l>%s</td></tr>\n",
                dom[k] < 0 ? "" : " class=dom", name, cells[k].spp, err[k], corr[k], ms[k],
                spread[k], ins, par);
        fprintf(r->md, "| %s | %d | %.4g | %.4g | %.2f | %s | %s |\n", name, cells[k].spp, err[k],
                corr[k], ms[k], ins, par);
        fprintf(r->tsv, "trace\t%s\t%d\t\t%.6g\t\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%s\n", name,
                cells[k].spp, err[k], sigma_ref, 1e6 * ms[k], spread[k], instr[k], corr[k],
                dom[k] < 0 ? "front" : "dominated");
    }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");

    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    cj_chart_set_title(c, "Ray tracer: RMSE vs ms per frame (ringed: dominated, spp)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ms per frame, 1 thread (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "RMSE (linear radiance)");
    report_front_series(c, (size_t)nc, ms, err, dom, 1e-300, "Pareto front");
    /* the 1/sqrt(spp) law through the 1-spp point, at the stratified costs */
    double lx[NSPP], ly[NSPP], fx[2], fy[2];
    for (int i = 0; i < ns; ++i) lx[i] = ms[i], ly[i] = err[0] / sqrt((double)spps[i]);
    cj_chart_series_opts lo = {"1/sqrt(spp) from 1 spp", cj_rgba_make(0x90, 0x90, 0x90, 255), 1.0,
                               CJ_MARKER_DIAMOND, 3.0};
    cj_chart_add_series(c, lx, ly, (size_t)ns, &lo);
    fx[0] = fmin(ms[0], ms[ns]), fx[1] = fmax(ms[ns - 1], ms[nc - 1]);
    fy[0] = fy[1] = sigma_ref;
    cj_chart_series_opts fo = {"reference noise", cj_rgba_make(0xd6, 0x27, 0x28, 200), 1.0,
                               CJ_MARKER_NONE, 0};
    cj_chart_add_series(c, fx, fy, 2, &fo);
    static const cj_rgba COL[2] = {{0x1f, 0x77, 0xb4, 255}, {0xff, 0x7f, 0x0e, 255}};
    static const cj_chart_marker MK[2] = {CJ_MARKER_CIRCLE, CJ_MARKER_SQUARE};
    for (int m = 0; m < 2; ++m) {
        cj_chart_series_opts o = {SNAME[m], COL[m], 1.5, MK[m], 5.0};
        cj_chart_add_series(c, ms + m * ns, err + m * ns, (size_t)ns, &o);
        for (int i = 0; i < ns; ++i) {
            if (dom[m * ns + i] < 0) continue;
            char txt[16];
            snprintf(txt, sizeof txt, "%d", spps[i]);
            cj_chart_annotate(c, ms[m * ns + i], err[m * ns + i], txt,
                              cj_rgba_make(0x60, 0x60, 0x60, 255));
        }
    }
    const int st = report_chart(r, c, "trace_spp.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}

/* Part 2: the direct patch intersection's tolerance against the image at REF_TOL. */
static int trace_tol(report *r) {
    const int *tes = r->quick ? TE_QUICK : TE_FULL;
    const int nt = r->quick ? 2 : NTOL, runs = r->quick ? 3 : 5;
    const int W = r->quick ? 32 : WL_W, H = r->quick ? 24 : WL_H;
    const size_t np = (size_t)W * H;
    cj_scene *sc = NULL;
    if (cj_trace_demo_scene(report_teapot_path(), NULL, &sc))
        return report_error("trace demo: %s", cj_last_error());
    cell cells[NTOL];
    double err[NTOL], ms[NTOL], spread[NTOL], instr[NTOL], maxerr[NTOL], ndiff[NTOL], rays[NTOL];
    cj_render_image *ri = NULL;
    const cell rc = {1, 0, REF_TOL};
    double *ref = malloc(np * 4 * sizeof *ref);
    if (!ref || frame(sc, W, H, &rc, 0, SEED_IMG, &ri, NULL)) {
        free(ref), cj_scene_destroy(sc);
        return report_error("trace demo: %s", cj_last_error());
    }
    for (size_t i = 0; i < 4 * np; ++i) ref[i] = ri->rgba[i];
    cj_render_image_destroy(ri);
    for (int i = 0; i < nt; ++i) {
        cells[i] = (cell){1, 0, pow(10.0, -tes[i])};
        cj_render_image *img = NULL;
        cj_stage_report rep;
        if (frame(sc, W, H, &cells[i], 0, SEED_IMG, &img, &rep)) {
            free(ref), cj_scene_destroy(sc);
            return report_error("trace demo: %s", cj_last_error());
        }
        err[i] = rmse(img->rgba, ref, np);
        size_t nd = 0;
        for (size_t p = 0; p < np; ++p) {
            double d = 0;
            for (int k = 0; k < 3; ++k) d = fmax(d, fabs(img->rgba[4 * p + k] - ref[4 * p + k]));
            nd += d > 1.0 / 255;
        }
        ndiff[i] = (double)nd;
        maxerr[i] = NAN;
        rays[i] = 0; /* every kind of ray: equal counts mean the cost is per intersection */
        for (int k = 0; k < rep.count; ++k)
            if (strstr(rep.stages[k].name, "_rays") && strcmp(rep.stages[k].name, "patch_rays"))
                rays[i] += (double)rep.stages[k].in;
        const cj_stage *s = cj_stage_report_find(&rep, "patch_rays");
        for (int k = 0; s && k < s->extra_count; ++k)
            if (!strcmp(s->extra[k].key, "max_err")) maxerr[i] = s->extra[k].value;
        cj_render_image_destroy(img);
    }
    free(ref);
    if (time_cells(sc, W, H, cells, nt, runs, r->quick ? 2.0 : 40.0, ms, spread)) {
        cj_scene_destroy(sc);
        return report_error("trace demo: %s", cj_last_error());
    }
    cj_scene_destroy(sc);
    for (int i = 0; i < nt; ++i) {
        char spec[64];
        snprintf(spec, sizeof spec, "trace:patch:%d", tes[i]);
        instr[i] = r->quick ? NAN : report_callgrind(r, spec, 1, NULL);
    }
    /* RMSE 0 (the same picture as the reference) drawn at a floor on the log axis */
    double minerr = INFINITY, y[NTOL];
    for (int i = 0; i < nt; ++i)
        if (err[i] > 0) minerr = fmin(minerr, err[i]);
    const double yfloor = isfinite(minerr) ? pow(10.0, floor(log10(minerr)) - 1) : 1e-6;
    for (int i = 0; i < nt; ++i) y[i] = fmax(err[i], yfloor);
    int dom[NTOL];
    report_pareto((size_t)nt, ms, err, dom);
    fprintf(r->html,
            "<h2>Ray tracer: patch tolerance</h2>\n<p>The trace demo (the Utah teapot's 32 "
            "bicubic patches intersected directly by subdivision and Newton, a mirror and a glass "
            "sphere, max depth 6) at %d&times;%d, 1 spp, with the patch tolerance (the largest "
            "distance from an accepted hit to its ray, relative to the teapot's box diagonal) "
            "from 1e&minus;%d to 1e&minus;%d, against the image at %.0e. Error: RMSE as above, "
            "pixels differing by more than 1/255 in a channel; max err: the largest distance to "
            "the ray accepted (stage patch_rays, in the teapot's object units; its box diagonal "
            "is about 8.3); rays: all rays the frame cast (primary, shadow, reflected, "
            "refracted). Cost: ms per frame on one thread, median of %d interleaved runs; "
            "instructions per %d&times;%d frame. On the chart an RMSE of 0 (the same image as "
            "the reference) is drawn a decade below the smallest non-zero one.</p>\n<table><tr>"
            "<th class=l>intersection</th><th>tol</th><th>RMSE</th><th>pixels &gt; 1/255</th>"
            "<th>max err</th><th>rays</th><th>ms/frame</th><th>spread</th>"
            "<th>instr/frame (%d&times;%d)</th><th class=l>Pareto</th></tr>\n",
            W, H, tes[0], tes[nt - 1], REF_TOL, runs, WL_W, WL_H, WL_W, WL_H);
    fprintf(r->md,
            "## Ray tracer: patch tolerance (trace demo, %dx%d, 1 spp, against tol %.0e)\n\n"
            "| tol | RMSE | pixels > 1/255 | max err | ms/frame | instr/frame | Pareto |\n"
            "|---|---|---|---|---|---|---|\n",
            W, H, REF_TOL);
    for (int i = 0; i < nt; ++i) {
        char par[96], ins[32];
        if (dom[i] < 0)
            snprintf(par, sizeof par, "front");
        else
            snprintf(par, sizeof par, "dominated by tol 1e-%d", tes[dom[i]]);
        report_g3(ins, instr[i]);
        fprintf(r->html,
                "<tr%s><td class=l>patch direct</td><td>1e-%d</td><td>%.3g</td><td>%.0f</td>"
                "<td>%.2g</td><td>%.0f</td><td>%.2f</td><td>%.0f %%</td><td>%s</td>"
                "<td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", tes[i], err[i], ndiff[i], maxerr[i], rays[i], ms[i],
                spread[i], ins, par);
        fprintf(r->md, "| 1e-%d | %.3g | %.0f | %.2g | %.2f | %s | %s |\n", tes[i], err[i],
                ndiff[i], maxerr[i], ms[i], ins, par);
        fprintf(r->tsv, "trace\tpatch direct\t%.6g\t\t%.6g\t\t%.6g\t%.6g\t%.6g\t%.6g\t%.0f\t%s\n",
                cells[i].ptol, err[i], maxerr[i], 1e6 * ms[i], spread[i], instr[i], ndiff[i],
                dom[i] < 0 ? "front" : "dominated");
    }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    cj_chart_set_title(c, "Teapot patches: RMSE vs cost, labelled with the tolerance");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "ms per frame, 1 thread (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "RMSE against tol 1e-10");
    double ymax = yfloor; /* room for the labels above the top point and below the floor */
    for (int i = 0; i < nt; ++i) ymax = fmax(ymax, y[i]);
    cj_chart_set_range(c, 1, yfloor / 3, ymax * 3);
    report_front_series(c, (size_t)nt, ms, y, dom, yfloor, "Pareto front");
    cj_chart_series_opts o = {"patch direct", cj_rgba_make(0x2c, 0xa0, 0x2c, 255), 1.0,
                              CJ_MARKER_CIRCLE, 5.0};
    cj_chart_add_series(c, ms, y, (size_t)nt, &o);
    /* one method: every point is labelled; those with RMSE 0 (they pile up) once, at the
     * cheapest of them */
    int z = -1, nz = 0;
    for (int i = 0; i < nt; ++i) {
        char txt[48];
        if (err[i] > 0) {
            snprintf(txt, sizeof txt, "1e-%d", tes[i]);
            cj_chart_annotate(c, ms[i], y[i], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
        } else {
            nz++;
            if (z < 0 || ms[i] < ms[z]) z = i;
        }
    }
    if (z >= 0) {
        char txt[48];
        int lo = 99, hi = 0;
        for (int i = 0; i < nt; ++i)
            if (!(err[i] > 0)) lo = tes[i] < lo ? tes[i] : lo, hi = tes[i] > hi ? tes[i] : hi;
        if (nz > 1)
            snprintf(txt, sizeof txt, "1e-%d .. 1e-%d: RMSE 0", lo, hi);
        else
            snprintf(txt, sizeof txt, "1e-%d: RMSE 0", lo);
        cj_chart_annotate(c, ms[z], y[z], txt, cj_rgba_make(0x60, 0x60, 0x60, 255));
    }
    const int st = report_chart(r, c, "trace_tol.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}

int report_trace(report *r) {
    int st = trace_spp(r);
    if (!st) st = trace_tol(r);
    return st ? st : report_path(r); /* the path tracer's convergence (report_path.c) */
}
