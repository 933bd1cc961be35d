/* casteljau report, section "tessellation": uniform (the smallest K x K grid whose proven bound
 * meets the tolerance, found by doubling and bisection) against adaptive, at tolerances relative
 * to each surface's size (its control-box diagonal), on four surfaces:
 *  - the Utah teapot (32 bicubic patches): measured deviation = the library's sampled
 *    |S(x) - L(x)| (lattice of step 1/4 on every triangle, cj_tess_options.measure);
 *  - three exact rational models, built here from the library's quarter circle
 *    (cj_rbezier_ellipse_arc): the unit sphere (8 biquadratic octants), a torus (R = 2, r = 0.5,
 *    16 biquadratic pieces) and a cylinder (radius 1, height 2, 4 pieces of degree (2, 1)). Their
 *    measured deviation is EXACT: the distance of every point of a lattice of step 1/8 on every
 *    mesh triangle to the true surface, in closed form (| |p| - 1 | for the sphere,
 *    | sqrt((sqrt(x² + y²) - R)² + z²) - r | for the torus, | sqrt(x² + y²) - 1 | for the
 *    cylinder, whose mesh stays within its height). The proven bound covers this distance (it
 *    bounds surface -> mesh and mesh -> surface, see tessellate.h).
 * Per (surface, method, tolerance): triangles, bound, measured deviation, µs per patch (median of
 * interleaved runs, without measuring), instructions per patch by callgrind (full report, at
 * the coarse tolerances only: >= 3e-3 of the size on the teapot, 1e-2 on the rational models,
 * where callgrind takes seconds). Pareto fronts per surface: a sphere and a teapot are
 * different problems. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include "casteljau/patchset.h"
#include "casteljau/rational.h"
#include "casteljau/tessellate.h"

#include <math.h>
#include <stdio.h>

enum { NSURF = 4, NTOL = 5, MAXP = 32 };
static const char *const SNAME[NSURF] = {"teapot", "sphere", "torus", "cylinder"};
static const double TORUS_R = 2.0, TORUS_r = 0.5;
/* Patches per callgrind run (N; 2N in the second run), see report_tess_workload. */
static const long CG_UNITS[NSURF] = {32, 2, 4, 1};

typedef struct surf {
    cj_patchset *set; /* the teapot's, else NULL */
    const cj_patch *patches;
    size_t count;
    double size;
    double pts[16][27], w[16][9]; /* the rational models' nets */
    cj_patch own[16];
} surf;

/* The quarter circle (1,0) -> (0,1) of the library, its coordinates snapped to the 0 and 1 they
 * approximate (cos π/2 is 6e-17 in double): the pole rows then collapse exactly and rotated
 * copies meet bit-identically (the tessellator's crack-free edges need identical nets). */
static cj_status quarter_circle(double q[3][2], double w[3]) {
    double p[6];
    const cj_status st = cj_rbezier_ellipse_arc(0, 0, 1, 1, 0, 0, 1.5707963267948966, p, w);
    for (int i = 0; i < 6; ++i) {
        const double v = round(p[i]);
        if (fabs(p[i] - v) > 1e-15) return CJ_ERR_DEGENERATE; /* not the expected arc */
        q[i / 2][i % 2] = v;
    }
    return st;
}

/* (x, y) turned by k quarter turns (exact). */
static void turn(int k, const double *in, double *out) {
    double x = in[0], y = in[1];
    for (int i = 0; i < (k & 3); ++i) {
        const double t = x;
        x = -y, y = t;
    }
    out[0] = x, out[1] = y;
}

/* Fills s with rational model `which` (1 sphere, 2 torus, 3 cylinder), outward normals. */
static cj_status build_model(int which, surf *s) {
    double q[3][2], qw[3];
    cj_status st = quarter_circle(q, qw);
    if (st) return st;
    s->set = NULL;
    s->count = which == 1 ? 8 : which == 2 ? 16 : 4;
    for (size_t k = 0; k < s->count; ++k) {
        double *P = s->pts[k], *W = s->w[k];
        const int a = (int)(k % 4), b = (int)(k / 4), nv = which == 3 ? 2 : 3;
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < 3; ++i) {
                double *p = P + 3 * (j * 3 + i), c[2], tube[2];
                if (which == 1) { /* S = (C(u) r(v), z(v)); u reversed in the south */
                    const int ii = b ? 2 - i : i;
                    turn(a, q[ii], c);
                    p[0] = c[0] * q[j][0], p[1] = c[1] * q[j][0], p[2] = b ? -q[j][1] : q[j][1];
                    W[j * 3 + i] = qw[ii] * qw[j];
                } else if (which == 2) { /* S = ((R + r cos φ) C(u), r sin φ) */
                    turn(a, q[i], c);
                    turn(b, q[j], tube);
                    const double rad = TORUS_R + TORUS_r * tube[0];
                    p[0] = c[0] * rad, p[1] = c[1] * rad, p[2] = TORUS_r * tube[1];
                    W[j * 3 + i] = qw[i] * qw[j];
                } else { /* S = (C(u), z), z from -1 to 1 */
                    turn(a, q[i], c);
                    p[0] = c[0], p[1] = c[1], p[2] = j ? 1.0 : -1.0;
                    W[j * 3 + i] = qw[i];
                }
            }
        s->own[k] = cj_patch_view(2, nv - 1, P, W);
    }
    s->patches = s->own;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < s->count; ++k) {
        double l[3], h[3];
        if ((st = cj_patch_bbox(&s->own[k], l, h))) return st;
        for (int d = 0; d < 3; ++d) lo[d] = fmin(lo[d], l[d]), hi[d] = fmax(hi[d], h[d]);
    }
    s->size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return CJ_OK;
}

static cj_status load_surface(int which, surf *s) {
    if (which) return build_model(which, s);
    s->set = NULL;
    if (cj_patchset_load_bpt(report_teapot_path(), NULL, &s->set)) return CJ_ERR_IO;
    s->patches = s->set->patches, s->count = s->set->count;
    double lo[3], hi[3];
    cj_patchset_bbox(s->set, lo, hi, &s->size);
    return CJ_OK;
}

/* Distance of p to the true surface (rational models only). */
static double exact_dist(int which, const double *p) {
    if (which == 1) return fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0);
    if (which == 2) return fabs(hypot(hypot(p[0], p[1]) - TORUS_R, p[2]) - TORUS_r);
    return fabs(hypot(p[0], p[1]) - 1.0);
}

/* Largest exact distance to the surface over a lattice of step 1/L on every triangle. */
static double mesh_exact_dev(const cj_mesh *m, int which, int L) {
    double dev = 0;
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const double *a = m->positions + 3 * m->triangles[3 * t],
                     *b = m->positions + 3 * m->triangles[3 * t + 1],
                     *c = m->positions + 3 * m->triangles[3 * t + 2];
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const int k = L - i - j;
                double p[3];
                for (int d = 0; d < 3; ++d) p[d] = (i * a[d] + j * b[d] + k * c[d]) / L;
                dev = fmax(dev, exact_dist(which, p));
            }
    }
    return dev;
}

static cj_status tess(const surf *s, cj_mesh *mesh, double tol, int K, int measure,
                      cj_tess_report *rep) {
    cj_mesh_clear(mesh);
    cj_tess_options opt = {tol, K, measure, 0};
    return cj_tessellate_patches(s->patches, s->count, &opt, mesh, rep);
}

/* n patch tessellations: "tess:K:RELTOL[:S]", K > 0 uniform K x K, K = 0 adaptive at RELTOL
 * times the surface's size; S = 0 teapot (default), 1 sphere, 2 torus, 3 cylinder. Unit k
 * tessellates patch 5k mod count (5 is prime to 32, 16, 8 and 4): every count consecutive units
 * cover every patch once, and so do 4 consecutive units of the torus every quarter of its tube
 * (patch b*4 + a) and 2 of the sphere both hemispheres, whose patches are congruent by exact
 * quarter turns and mirrors: the report counts 2, 4 and 1 units there (see CG_UNITS). */
int report_tess_workload(const char *spec, long n) {
    int K = -1, which = 0;
    double rel = 0;
    const int got = sscanf(spec, "tess:%d:%lf:%d", &K, &rel, &which);
    if (got < 2 || K < 0 || K > 1024 || !(rel > 0 && rel < 1) || which < 0 || which >= NSURF)
        return report_fail("bad workload '%s' (tess:K:RELTOL[:SURFACE], K = 0 adaptive)", spec);
    static surf s;
    cj_mesh *mesh = NULL;
    if (load_surface(which, &s) || cj_mesh_create(NULL, &mesh)) {
        cj_patchset_destroy(s.set);
        return report_error("%s", cj_last_error());
    }
    int rc = 0;
    for (long k = 0; k < n && !rc; ++k) {
        cj_mesh_clear(mesh);
        cj_tess_options opt = {rel * s.size, K, 0, 0};
        cj_tess_report rep;
        rc = cj_tessellate_patches(s.patches + (5 * k) % (long)s.count, 1, &opt, mesh, &rep) != 0;
    }
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(s.set);
    return rc;
}

typedef struct cell {
    double us, spread, meas, bound, tris, instr;
    int K;
} cell;

/* Measures surface `which` at nt relative tolerances into c[method][tol]. */
static int measure_surface(report *r, int which, const surf *s, cj_mesh *mesh, const double *rels,
                           int nt, cell c[2][NTOL]) {
    const int runs = r->quick ? 3 : 11;
    const double min_ns = r->quick ? 2e4 : 2e5;
    for (int t = 0; t < nt; ++t) {
        const double tol = rels[t] * s->size;
        cj_tess_report rep;
        int lo_k = 0, hi_k = 1;
        cj_status st;
        while (!(st = tess(s, mesh, 0, hi_k, 0, &rep)) && rep.bound > tol) lo_k = hi_k, hi_k *= 2;
        while (!st && hi_k - lo_k > 1) {
            const int mid = (lo_k + hi_k) / 2;
            if ((st = tess(s, mesh, 0, mid, 0, &rep))) break;
            if (rep.bound > tol)
                lo_k = mid;
            else
                hi_k = mid;
        }
        double tm[2][16];
        for (int run = 0; run < runs && !st; ++run)
            for (int m = 0; m < 2 && !st; ++m) {
                long reps = 0;
                const double t0 = report_now_ns();
                double t1 = t0;
                do {
                    st = tess(s, mesh, tol, m ? 0 : hi_k, 0, &rep);
                    reps++;
                } while (!st && (t1 = report_now_ns()) - t0 < min_ns);
                tm[m][run] = (t1 - t0) / 1e3 / (double)reps / (double)s->count;
            }
        for (int m = 0; m < 2 && !st; ++m) {
            cell *e = &c[m][t];
            e->K = m ? 0 : hi_k;
            e->us = report_median(tm[m], (size_t)runs, &e->spread);
            if ((st = tess(s, mesh, tol, e->K, which ? 0 : 4, &rep))) break;
            e->meas = which ? mesh_exact_dev(mesh, which, 8) : rep.measured;
            e->bound = rep.bound, e->tris = (double)rep.triangles;
            char spec[64];
            snprintf(spec, sizeof spec, "tess:%d:%g:%d", e->K, rels[t], which);
            /* N and 2N patches (the teapot: all 32; the rational models: a set that represents
             * their congruent patches, CG_UNITS), only at the coarse tolerances (the teapot
             * >= 3e-3 of its size, the models 1e-2, whose adaptive planning costs milliseconds
             * per patch at any tolerance), where callgrind takes seconds */
            e->instr = r->quick || rels[t] < (which ? 1e-2 : 3e-3)
                           ? NAN
                           : report_callgrind(r, spec, CG_UNITS[which], NULL);
        }
        if (st) return report_error("tessellation (%s): %s", SNAME[which], cj_last_error());
    }
    return 0;
}

int report_tess(report *r) {
    static const double REL_FULL[NTOL] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4}, REL_QUICK[] = {1e-2, 1e-3},
                        REL_QUICK_Q[] = {1e-3};
    static surf S[NSURF];
    static cell C[NSURF][2][NTOL];
    int nts[NSURF], have[NSURF];
    const double *relsof[NSURF];
    cj_mesh *mesh = NULL;
    if (cj_mesh_create(NULL, &mesh)) return report_error("%s", cj_last_error());
    int status = 0;
    for (int s = 0; s < NSURF && !status; ++s) {
        relsof[s] = r->quick ? (s ? REL_QUICK_Q : REL_QUICK) : REL_FULL;
        nts[s] = r->quick ? (s ? 1 : 2) : NTOL;
        have[s] = !load_surface(s, &S[s]);
        if (!have[s] && s) status = report_error("tessellation: %s: %s", SNAME[s], cj_last_error());
        if (have[s] && !status)
            status = measure_surface(r, s, &S[s], mesh, relsof[s], nts[s], C[s]);
    }
    cj_mesh_destroy(mesh);
    if (!have[0]) fprintf(r->html, "<p>No teapot.bpt: the teapot is left out.</p>\n");
    if (status) {
        for (int s = 0; s < NSURF; ++s) cj_patchset_destroy(have[s] ? S[s].set : NULL);
        return status;
    }
    static const char *const NAME[2] = {"uniform", "adaptive"};
    int dom[NSURF][2 * NTOL];
    double cost[NSURF][2 * NTOL], err[NSURF][2 * NTOL];
    for (int s = 0; s < NSURF; ++s) {
        if (!have[s]) continue;
        const int nt = nts[s];
        for (int m = 0; m < 2; ++m)
            for (int t = 0; t < nt; ++t)
                cost[s][m * nt + t] = C[s][m][t].us, err[s][m * nt + t] = C[s][m][t].meas;
        report_pareto((size_t)(2 * nt), cost[s], err[s], dom[s]);
    }
    fprintf(r->html,
            "<h2>Tessellation</h2>\n<p>Four surfaces: the Utah teapot (%zu bicubic patches) and "
            "three exact rational models built from the library's quarter circle: the unit sphere "
            "(8 biquadratic octants), a torus (R = 2, r = 0.5; 16 biquadratic pieces) and a "
            "cylinder (radius 1, height 2; 4 pieces of degree (2, 1)). Tolerances are relative to "
            "each surface's size (its control-box diagonal). Uniform: the smallest K&times;K grid "
            "whose proven bound meets the tolerance; adaptive: cj_tessellate_patches with the "
            "tolerance. Measured deviation: on the teapot the library's sampled |S &minus; L| "
            "(lattice of step 1/4 per triangle); on the rational models the EXACT distance of the "
            "mesh to the true sphere, torus or cylinder (closed form, lattice of step 1/8 per "
            "triangle). &micro;s per patch without measuring. Pareto front per surface (cost "
            "&micro;s/patch, error the measured deviation).</p>\n"
            "<table><tr><th class=l>method</th><th>tol/size</th><th>grid</th><th>triangles</th>"
            "<th>bound</th><th>measured</th><th>&micro;s/patch</th><th>spread</th><th>instr/patch"
            "</th><th class=l>Pareto</th></tr>\n",
            have[0] ? S[0].count : (size_t)32);
    fprintf(r->md, "## Tessellation (teapot, sphere, torus, cylinder)\n\n| method | tol/size | "
                   "triangles | bound | measured | µs/patch | instr/patch | Pareto |\n"
                   "|---|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < NSURF; ++s) {
        if (!have[s]) continue;
        const int nt = nts[s];
        const double *rels = relsof[s];
        for (int m = 0; m < 2; ++m)
            for (int t = 0; t < nt; ++t) {
                const int i = m * nt + t;
                const cell *e = &C[s][m][t];
                char par[96], grid[32], ins[32], name[32];
                snprintf(name, sizeof name, "%s %s", NAME[m], SNAME[s]);
                if (dom[s][i] < 0)
                    snprintf(par, sizeof par, "front");
                else
                    snprintf(par, sizeof par, "dominated by %s %s at %.0e", NAME[dom[s][i] / nt],
                             SNAME[s], rels[dom[s][i] % nt]);
                if (m)
                    snprintf(grid, sizeof grid, "adaptive");
                else
                    snprintf(grid, sizeof grid, "K=%d", e->K);
                if (isfinite(e->instr))
                    snprintf(ins, sizeof ins, "%.0f", e->instr);
                else
                    snprintf(ins, sizeof ins, "—");
                fprintf(r->html,
                        "<tr%s><td class=l>%s</td><td>%.0e</td><td>%s</td><td>%.0f</td><td>%.3g"
                        "</td><td>%.3g</td><td>%.2f</td><td>%.0f %%</td><td>%s</td><td class=l>%s"
                        "</td></tr>\n",
                        dom[s][i] < 0 ? "" : " class=dom", name, rels[t], grid, e->tris, e->bound,
                        e->meas, e->us, e->spread, ins, par);
                fprintf(r->md, "| %s | %.0e | %.0f | %.3g | %.3g | %.2f | %s | %s |\n", name,
                        rels[t], e->tris, e->bound, e->meas, e->us, ins, par);
                fprintf(r->tsv, "tess\t%s\t%.6g\t\t%.6g\t\t%.6g\t%.6g\t%.3f\t%.6g\t%.0f\t%s\n",
                        name, rels[t] * S[s].size, e->meas, e->bound, 1e3 * e->us, e->spread,
                        e->instr, e->tris, dom[s][i] < 0 ? "front" : "dominated");
            }
    }
    fprintf(r->html, "</table>\n");
    fprintf(r->md, "\n");
    for (int s = 0; s < NSURF; ++s) cj_patchset_destroy(have[s] ? S[s].set : NULL);
    /* one chart: deviation relative to the size against µs per patch; a colour per surface,
     * a marker per method (uniform: squares, adaptive: circles) */
    cj_chart *c = NULL;
    if (cj_chart_create(NULL, &c)) return report_error("%s", cj_last_error());
    cj_chart_set_title(c, "Tessellation: deviation vs cost (ringed: dominated, tol/size)");
    cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE);
    cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "µs per patch (median)");
    cj_chart_set_axis(c, 1, CJ_CHART_LOG10, "max distance surface - mesh / size");
    static const cj_rgba COL[NSURF][2] = {{{0xff, 0x7f, 0x0e, 255}, {0xc0, 0x50, 0x00, 255}},
                                          {{0x6b, 0xae, 0xd6, 255}, {0x1f, 0x4e, 0x94, 255}},
                                          {{0x74, 0xc4, 0x76, 255}, {0x1a, 0x7a, 0x1a, 255}},
                                          {{0xc2, 0x9b, 0xe0, 255}, {0x6a, 0x3d, 0x9a, 255}}};
    int labelled = 0;
    for (int s = 0; s < NSURF; ++s) {
        if (!have[s]) continue;
        const int nt = nts[s];
        double y[2 * NTOL];
        for (int i = 0; i < 2 * nt; ++i) y[i] = fmax(err[s][i], 1e-300) / S[s].size;
        report_front_series(c, (size_t)(2 * nt), cost[s], y, dom[s], 1e-300,
                            labelled++ ? NULL : "Pareto front (per surface)");
        for (int m = 0; m < 2; ++m) {
            char name[32];
            snprintf(name, sizeof name, "%s %s", NAME[m], SNAME[s]);
            cj_chart_series_opts o = {name, COL[s][m], 1.5, m ? CJ_MARKER_CIRCLE : CJ_MARKER_SQUARE,
                                      5.0};
            if (cj_chart_add_series(c, cost[s] + m * nt, y + m * nt, (size_t)nt, &o)) {
                cj_chart_destroy(c);
                return report_error("chart: %s", cj_last_error());
            }
            for (int t = 0; t < nt; ++t)
                if (dom[s][m * nt + t] >= 0) {
                    char txt[48];
                    snprintf(txt, sizeof txt, "%.0e", relsof[s][t]);
                    cj_chart_annotate(c, cost[s][m * nt + t], y[m * nt + t], txt,
                                      cj_rgba_make(0x60, 0x60, 0x60, 255));
                }
        }
    }
    const int st = report_chart(r, c, "tess.png", 860, 520);
    cj_chart_destroy(c);
    return st;
}
