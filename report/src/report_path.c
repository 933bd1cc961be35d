/* casteljau report, section "path": the path tracer's convergence (docs/light.md).
 *
 * A small Cornell-like box built here (radiometric: white, red and green walls, a ceiling
 * emitter, a diffuse and a glossy sphere; colour bleeding and soft shadows) traced by the path
 * tracer (cj_trace_options.integrator = CJ_INTEGRATOR_PATH) at spp 1 .. 256 (quick 1 .. 16).
 * Error: the RMSE of the linear radiance against a reference, the mean of two independent
 * high-spp renders A and B with other seeds than the measured images; σ_ref = RMSE(A, B) / 2 is
 * the reference's own noise and √(RMSE² − σ_ref²) the error against the noise-free picture. A
 * Monte Carlo estimator's error falls as spp^(−1/2): the least-squares slope of log RMSE
 * against log spp is printed next to −1/2. Cost: wall ms of one frame on all cores (one run:
 * the section is about convergence; the ray tracer section measures costs). */
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
static const int SPP_FULL[NSPP] = {1, 4, 16, 64, 256}, SPP_QUICK[] = {1, 4, 16};
static const uint64_t SEED_IMG = 4242, SEED_REF_A = 5151, SEED_REF_B = 6262;

static cj_status wall(cj_scene *sc, cj_vec3 o, cj_vec3 eu, cj_vec3 ev, int mat) {
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    int gi = 0;
    cj_status st = cj_planar_patch_init(&g.u.planar, o, eu, ev);
    if (!st) st = cj_scene_add_geometry(sc, &g, &gi);
    cj_node n = cj_node_defaults(gi, mat);
    return st ? st : cj_scene_add_node(sc, &n, NULL);
}

static cj_status box_scene(cj_scene **out) {
    cj_scene *sc = NULL;
    cj_status st = cj_scene_create(NULL, &sc);
    if (st) return st;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 1, 3.6);
    cam.gaze = cj_v3(0, 0, -1);
    cam.fov_y = 0.68;
    cj_scene_settings set = cj_scene_settings_defaults();
    set.max_depth = 8;
    set.light_model = CJ_LIGHT_RADIOMETRIC;
    cj_light lamp = cj_light_defaults(CJ_LIGHT_AREA);
    lamp.position = cj_v3(-0.3, 1.99, -0.3);
    lamp.edge_u = cj_v3(0, 0, 0.6); /* edge_u × edge_v = −y: facing down */
    lamp.edge_v = cj_v3(0.6, 0, 0);
    lamp.intensity = 12;
    cj_material white = cj_material_defaults(), red, green, ball, gloss;
    white.color = (cj_rgb){0.75, 0.75, 0.75};
    white.ka = white.ks = 0, white.kd = 1, white.two_sided = 1;
    red = green = ball = white;
    red.color = (cj_rgb){0.7, 0.1, 0.08};
    green.color = (cj_rgb){0.12, 0.6, 0.1};
    ball.color = (cj_rgb){0.8, 0.7, 0.5};
    gloss = white;
    gloss.color = (cj_rgb){0.2, 0.3, 0.7};
    gloss.kd = 0.7, gloss.ks = 0.3, gloss.alpha = 40;
    int mw = 0, mr = 0, mg = 0, mb = 0, ms = 0;
    if (!st) st = cj_scene_set_camera(sc, &cam);
    if (!st) st = cj_scene_set_settings(sc, &set);
    if (!st) st = cj_scene_add_light(sc, &lamp, NULL);
    if (!st) st = cj_scene_add_material(sc, &white, &mw);
    if (!st) st = cj_scene_add_material(sc, &red, &mr);
    if (!st) st = cj_scene_add_material(sc, &green, &mg);
    if (!st) st = cj_scene_add_material(sc, &ball, &mb);
    if (!st) st = cj_scene_add_material(sc, &gloss, &ms);
    if (!st) st = wall(sc, cj_v3(-1, 0, 1), cj_v3(2, 0, 0), cj_v3(0, 0, -2), mw); /* floor */
    if (!st) st = wall(sc, cj_v3(-1, 2, -1), cj_v3(2, 0, 0), cj_v3(0, 0, 2), mw); /* ceiling */
    if (!st) st = wall(sc, cj_v3(-1, 0, -1), cj_v3(2, 0, 0), cj_v3(0, 2, 0), mw); /* back */
    if (!st) st = wall(sc, cj_v3(-1, 0, 1), cj_v3(0, 0, -2), cj_v3(0, 2, 0), mr); /* left */
    if (!st) st = wall(sc, cj_v3(1, 0, -1), cj_v3(0, 0, 2), cj_v3(0, 2, 0), mg);  /* right */
    cj_geometry s1, s2;
    memset(&s1, 0, sizeof s1);
    memset(&s2, 0, sizeof s2);
    s1.kind = s2.kind = CJ_GEOM_SPHERE;
    s1.u.sphere.center = cj_v3(-0.4, 0.35, -0.3), s1.u.sphere.radius = 0.35;
    s2.u.sphere.center = cj_v3(0.45, 0.3, 0.25), s2.u.sphere.radius = 0.3;
    int g1 = 0, g2 = 0;
    if (!st) st = cj_scene_add_geometry(sc, &s1, &g1);
    if (!st) st = cj_scene_add_geometry(sc, &s2, &g2);
    cj_node n1 = cj_node_defaults(g1, mb), n2 = cj_node_defaults(g2, ms);
    if (!st) st = cj_scene_add_node(sc, &n1, NULL);
    if (!st) st = cj_scene_add_node(sc, &n2, NULL);
    if (st) {
        cj_scene_destroy(sc);
        return st;
    }
    *out = sc;
    return CJ_OK;
}

static cj_status frame(const cj_scene *sc, int w, int h, int spp, uint64_t seed,
                       cj_render_image **img) {
    cj_render_options o = cj_render_options_defaults();
    o.width = w, o.height = h, o.spp = spp;
    o.use_seed = 1, o.seed = seed;
    cj_trace_options to;
    memset(&to, 0, sizeof to);
    to.integrator = CJ_INTEGRATOR_PATH;
    return cj_render_trace_with_options(sc, &o, &to, 0, NULL, img, NULL);
}

static double rmse(const float *a, const float *b, size_t np, int mean_of_two, const float *b2) {
    double s = 0;
    for (size_t i = 0; i < np; ++i)
        for (int k = 0; k < 3; ++k) {
            const double ref =
                mean_of_two ? 0.5 * ((double)b[4 * i + k] + b2[4 * i + k]) : (double)b[4 * i + k];
            const double d = (double)a[4 * i + k] - ref;
            s += d * d;
        }
    return sqrt(s / (3.0 * (double)np));
}

/* The least-squares slope of log y against log x. */
static double loglog_slope(const int *x, const double *y, int n) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < n; ++i) {
        const double lx = log((double)x[i]), ly = log(y[i]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int report_path(report *r) {
    const int *spps = r->quick ? SPP_QUICK : SPP_FULL, ns = r->quick ? 3 : NSPP;
    const int W = r->quick ? 32 : 64, H = r->quick ? 24 : 48, REF = r->quick ? 512 : 4096;
    const size_t np = (size_t)W * H;
    cj_scene *sc = NULL;
    if (box_scene(&sc)) return report_error("path: %s", cj_last_error());
    cj_render_image *ra = NULL, *rb = NULL;
    const double t0 = report_now_ns();
    if (frame(sc, W, H, REF, SEED_REF_A, &ra) || frame(sc, W, H, REF, SEED_REF_B, &rb)) {
        cj_render_image_destroy(ra);
        cj_scene_destroy(sc);
        return report_error("path reference: %s", cj_last_error());
    }
    const double ref_s = (report_now_ns() - t0) / 1e9;
    const double sigma_ref = rmse(ra->rgba, rb->rgba, np, 0, NULL) / 2;
    double err[NSPP], corr[NSPP], ms[NSPP];
    for (int i = 0; i < ns; ++i) {
        cj_render_image *img = NULL;
        const double a = report_now_ns();
        if (frame(sc, W, H, spps[i], SEED_IMG, &img)) {
            cj_render_image_destroy(ra), cj_render_image_destroy(rb), cj_scene_destroy(sc);
            return report_error("path: %s", cj_last_error());
        }
        ms[i] = (report_now_ns() - a) / 1e6;
        err[i] = rmse(img->rgba, ra->rgba, np, 1, rb->rgba);
        corr[i] = sqrt(fmax(0.0, err[i] * err[i] - sigma_ref * sigma_ref));
        cj_render_image_destroy(img);
    }
    cj_render_image_destroy(ra), cj_render_image_destroy(rb);
    cj_scene_destroy(sc);
    const double slope = loglog_slope(spps, corr, ns);
    int dom[NSPP];
    report_pareto((size_t)ns, ms, err, dom);
    fprintf(r->html,
            "<h2>Path tracer: convergence</h2>\n<p>The path tracer (next-event estimation, MIS, "
            "Russian roulette; docs/light.md) on a small Cornell-like box built in the report: "
            "white, red and green walls, a 0.6&times;0.6 ceiling emitter of radiance 12, a diffuse "
            "and a glossy sphere, radiometric, max depth 8, %d&times;%d pixels. Error: RMSE of the "
            "linear radiance over all pixels and the 3 channels against the mean of two "
            "independent %d-spp renders (%.1f s on all cores) with other seeds; their own noise "
            "&sigma;<sub>ref</sub> = %.3g, and &radic;(RMSE&sup2; &minus; "
            "&sigma;<sub>ref</sub>&sup2;) estimates the error against the noise-free picture. "
            "A Monte Carlo estimate's error falls as spp<sup>&minus;1/2</sup>: the least-squares "
            "slope of log(corrected RMSE) against log(spp) is <b>%.3f</b> (expected "
            "&minus;0.5). Cost: wall ms of one frame on all cores.</p>\n"
            "<table><tr><th class=l>integrator</th><th>spp</th><th>RMSE</th>"
            "<th>RMSE &minus; ref. noise</th><th>ms/frame</th><th class=l>Pareto</th></tr>\n",
            W, H, REF, ref_s, sigma_ref, slope);
    fprintf(r->md,
            "## Path tracer: convergence (Cornell-like box, %dx%d)\n\n"
            "RMSE against the mean of two %d-spp references (σ_ref = %.2g); log-log slope of "
            "the corrected RMSE against spp: **%.3f** (expected −0.5).\n\n"
            "| spp | RMSE | RMSE − ref. noise | ms/frame |\n|---|---|---|---|\n",
            W, H, REF, sigma_ref, slope);
    for (int i = 0; i < ns; ++i) {
        char par[64];
        if (dom[i] < 0)
            snprintf(par, sizeof par, "front");
        else
            snprintf(par, sizeof par, "dominated by %d spp", spps[dom[i]]);
        fprintf(r->html,
                "<tr%s><td class=l>path</td><td>%d</td><td>%.4g</td><td>%.4g</td><td>%.1f</td>"
                "<td class=l>%s</td></tr>\n",
                dom[i] < 0 ? "" : " class=dom", spps[i], err[i], corr[i], ms[i], par);
        fprintf(r->md, "| %d | %.4g | %.4g | %.1f |\n", spps[i], err[i], corr[i], ms[i]);
        fprintf(r->tsv, "path\tpath tracer\t%d\t\t%.6g\t\t%.6g\t%.6g\t\tnan\t%.6g\t%s\n", spps[i],
                err[i], sigma_ref, 1e6 * ms[i], corr[i], dom[i] < 0 ? "front" : "dominated");
    }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");

    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    char title[96];
    snprintf(title, sizeof title, "Path tracer: RMSE vs samples per pixel (slope %.3f)", slope);
    cj_chart_set_title(c, title);
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "samples per pixel");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "RMSE (linear radiance)");
    double x[NSPP], law[NSPP], fy[2] = {sigma_ref, sigma_ref}, fx[2];
    for (int i = 0; i < ns; ++i) x[i] = spps[i], law[i] = corr[0] / sqrt((double)spps[i]);
    fx[0] = x[0], fx[1] = x[ns - 1];
    cj_chart_series_opts lo = {"1/sqrt(spp) from 1 spp", cj_rgba_make(0x90, 0x90, 0x90, 255), 1.0,
                               CJ_MARKER_NONE, 0};
    cj_chart_add_series(c, x, law, (size_t)ns, &lo);
    cj_chart_series_opts fo = {"reference noise", cj_rgba_make(0xd6, 0x27, 0x28, 200), 1.0,
                               CJ_MARKER_NONE, 0};
    cj_chart_add_series(c, fx, fy, 2, &fo);
    cj_chart_series_opts eo = {"RMSE", cj_rgba_make(0x1f, 0x77, 0xb4, 255), 1.5, CJ_MARKER_CIRCLE,
                               5.0};
    cj_chart_add_series(c, x, err, (size_t)ns, &eo);
    cj_chart_series_opts co = {"RMSE - ref. noise", cj_rgba_make(0x2c, 0xa0, 0x2c, 255), 1.5,
                               CJ_MARKER_SQUARE, 5.0};
    cj_chart_add_series(c, x, corr, (size_t)ns, &co);
    const int st = report_chart(r, c, "path_convergence.png", 760, 480);
    cj_chart_destroy(c);
    return st;
}
