/* bench_tess_live: the tessellation rows of issue 19 ("Live"), on the Utah teapot at the object
 * tolerance the demo camera needs at 0.25 px on 1024 x 1024 (TEAPOT_TOL), and on exact rational
 * models (a unit sphere of 8 biquadratic octants, a torus R = 2, r = 0.5 of 16 pieces).
 * Each mode prints medians of wall time over repetitions; for instruction counts run it under
 *     valgrind --tool=callgrind --collect-atstart=no <bench> <mode> ...
 * which counts only the measured call (CALLGRIND_TOGGLE_COLLECT around the first repetition; under
 * valgrind the other repetitions are skipped):
 * bench/tess_callgrind.sh runs every row that way.
 * Modes:
 *   cold                  one cj_tessellate_patches of the teapot at TEAPOT_TOL: triangles,
 *                         builds and bounds-only trials per patch, ms
 *   one MODEL adaptive TOL    one adaptive tessellation of MODEL (teapot, sphere, torus)
 *   one MODEL uniform TOL     the uniform one with the smallest K whose proven bound <= TOL
 *   ratio                 the adaptive / uniform table (times; triangles; K) for the three
 *   drag [0|1]            the incremental cache (casteljau/tess_cache.h): one interior control
 *                         point of the teapot moved per frame (0), then a shared corner moved
 *                         with its coincident copies (1): plans and pieces redone per frame, ms
 * Built against the library before issue 19 (CJ_BENCH_OLD: no cache, no builds count) it gives
 * the "before" figures of the same calls. */
#define _POSIX_C_SOURCE 199309L
#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"
#ifndef CJ_BENCH_OLD
#include "casteljau/tess_cache.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>
#include <valgrind/valgrind.h>
#include "bench_clock.h"

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

/* The object tolerance of the demo teapot at 0.25 px, 1024 x 1024 (the renderer's
 * cj_rview_world_tol at the nearest visible patch, as bench_render's frames use). */
#define TEAPOT_TOL 0.0010335430324191963

#define SQRT1_2 0.70710678118654752440
#define REPS    9

typedef struct model {
    size_t count;
    cj_patch p[32];
    double pts[32][16 * 3], w[32][16];
} model;

static const double QC[3][2] = {{1, 0}, {1, 1}, {0, 1}};
static const double QW[3] = {1, SQRT1_2, 1};

static void quarter_turn(int k, double x, double y, double *ox, double *oy) {
    for (int i = 0; i < (k & 3); ++i) {
        const double t = x;
        x = -y;
        y = t;
    }
    *ox = x;
    *oy = y;
}

/* The models: teapot (its .bpt), sphere (8 exact octants), torus (16 exact pieces). */
static int load_model(const char *name, model *M) {
    memset(M, 0, sizeof *M);
    if (!strcmp(name, "teapot")) {
        cj_patchset *set;
        if (cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set)) return -1;
        M->count = set->count;
        for (size_t q = 0; q < set->count && q < 32; ++q) {
            memcpy(M->pts[q], set->patches[q].pts, 16 * 3 * sizeof(double));
            M->p[q] = cj_patch_view(3, 3, M->pts[q], NULL);
        }
        cj_patchset_destroy(set);
        return 0;
    }
    const int sphere = !strcmp(name, "sphere");
    if (!sphere && strcmp(name, "torus")) return -1;
    M->count = sphere ? 8 : 16;
    for (size_t k = 0; k < M->count; ++k) {
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                const int q = j * 3 + i;
                double x, y;
                if (sphere) { /* octant k % 4 around z, north or south */
                    const int hemi = (int)k / 4, ii = hemi ? 2 - i : i;
                    quarter_turn((int)k % 4, QC[ii][0], QC[ii][1], &x, &y);
                    M->pts[k][3 * q] = x * QC[j][0];
                    M->pts[k][3 * q + 1] = y * QC[j][0];
                    M->pts[k][3 * q + 2] = hemi ? -QC[j][1] : QC[j][1];
                    M->w[k][q] = QW[ii] * QW[j];
                } else {
                    double c, s;
                    quarter_turn((int)k % 4, QC[i][0], QC[i][1], &x, &y);
                    quarter_turn((int)k / 4, QC[j][0], QC[j][1], &c, &s);
                    M->pts[k][3 * q] = x * (2.0 + 0.5 * c);
                    M->pts[k][3 * q + 1] = y * (2.0 + 0.5 * c);
                    M->pts[k][3 * q + 2] = 0.5 * s;
                    M->w[k][q] = QW[i] * QW[j];
                }
            }
        M->p[k] = cj_patch_view(2, 2, M->pts[k], M->w[k]);
    }
    return 0;
}

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *t, int n) {
    qsort(t, (size_t)n, sizeof *t, cmp_double);
    return t[n / 2];
}

/* REPS runs of one tessellation; the first is the one callgrind counts. Returns the median
 * ms; *rep receives the report. */
static double timed(const model *M, const cj_tess_options *opt, cj_mesh *mesh,
                    cj_tess_report *rep) {
    double t[REPS];
    const int reps = RUNNING_ON_VALGRIND ? 1 : REPS; /* under callgrind: the counted run only */
    for (int r = 0; r < reps; ++r) {
        cj_mesh_clear(mesh);
        const double t0 = cj_bench_wall();
        if (r == 0) CALLGRIND_TOGGLE_COLLECT;
        const cj_status st = cj_tessellate_patches(M->p, M->count, opt, mesh, rep);
        if (r == 0) CALLGRIND_TOGGLE_COLLECT;
        t[r] = 1e3 * (cj_bench_wall() - t0);
        if (st) {
            fprintf(stderr, "bench_tess_live: %s\n", cj_last_error());
            exit(1);
        }
    }
    return median(t, reps);
}

/* Smallest K whose uniform K x K tessellation has a proven bound <= tol. */
static int smallest_uniform(const model *M, double tol, cj_mesh *mesh) {
    int lo = 0, hi = 1;
    for (;;) {
        cj_tess_options o = {0.0, hi, 0, 0};
        cj_tess_report r;
        cj_mesh_clear(mesh);
        if (cj_tessellate_patches(M->p, M->count, &o, mesh, &r)) exit(1);
        if (r.bound <= tol) break;
        lo = hi;
        hi *= 2;
    }
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        cj_tess_options o = {0.0, mid, 0, 0};
        cj_tess_report r;
        cj_mesh_clear(mesh);
        if (cj_tessellate_patches(M->p, M->count, &o, mesh, &r)) exit(1);
        if (r.bound <= tol)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

static void print_report(const char *what, const cj_tess_report *r, size_t patches, double ms) {
#ifndef CJ_BENCH_OLD
    printf("%-26s %9zu triangles, bound %.4e, %.2f builds and %.2f bounds-only trials per "
           "patch, median %.2f ms\n",
           what, r->triangles, r->bound, (double)r->builds / (double)patches,
           (double)r->trials / (double)patches, ms);
#else
    printf("%-26s %9zu triangles, bound %.4e, median %.2f ms\n", what, r->triangles, r->bound, ms);
    (void)patches;
#endif
}

static const double model_tol[3] = {TEAPOT_TOL, 1e-4, 2.5e-4};
static const char *model_name[3] = {"teapot", "sphere", "torus"};

int main(int argc, char **argv) {
    const char *mode = argc > 1 ? argv[1] : "ratio";
    static model M;
    cj_mesh *mesh;
    if (cj_mesh_create(NULL, &mesh)) return 1;
    cj_tess_report rep;
    if (!strcmp(mode, "cold")) {
        if (load_model("teapot", &M)) return 1;
        const cj_tess_options o = {TEAPOT_TOL, 0, 0, 0};
        const double ms = timed(&M, &o, mesh, &rep);
        print_report("teapot, tol 0.25 px", &rep, M.count, ms);
    } else if (!strcmp(mode, "one") && argc == 5) {
        if (load_model(argv[2], &M)) return 1;
        const double tol = atof(argv[4]);
        cj_tess_options o = {tol, 0, 0, 0};
        if (!strcmp(argv[3], "uniform")) o.uniform = smallest_uniform(&M, tol, mesh);
        const double ms = timed(&M, &o, mesh, &rep);
        char what[64];
        snprintf(what, sizeof what, "%s %s K=%d", argv[2], argv[3], o.uniform);
        print_report(what, &rep, M.count, ms);
    } else if (!strcmp(mode, "ratio")) {
        printf("adaptive vs uniform at the same proven bound (uniform: the smallest K with bound "
               "<= tol), median of %d\n",
               REPS);
        for (int k = 0; k < 3; ++k) {
            if (load_model(model_name[k], &M)) return 1;
            const double tol = model_tol[k];
            cj_tess_options oa = {tol, 0, 0, 0}, ou = {tol, 0, 0, 0};
            ou.uniform = smallest_uniform(&M, tol, mesh);
            cj_tess_report ra, ru;
            const double ta = timed(&M, &oa, mesh, &ra), tu = timed(&M, &ou, mesh, &ru);
            printf("%-7s tol %.4g: adaptive %8zu triangles %8.2f ms; uniform K=%-4d %8zu "
                   "triangles %8.2f ms; time ratio %.2f, triangle ratio %.2f\n",
                   model_name[k], tol, ra.triangles, ta, ou.uniform, ru.triangles, tu, ta / tu,
                   (double)ra.triangles / (double)ru.triangles);
        }
#ifndef CJ_BENCH_OLD
    } else if (!strcmp(mode, "drag")) {
        if (load_model("teapot", &M)) return 1;
        cj_tess_cache *cache;
        if (cj_tess_cache_create(NULL, &cache)) return 1;
        const cj_tess_options o = {TEAPOT_TOL, 0, 0, 0};
        cj_tess_cache_stats w;
        if (cj_tess_cache_update(cache, M.p, M.count, &o, mesh, &rep, &w)) return 1;
        /* interior point 5 of patch 0; corner 0 of patch 0 (shared by its neighbours) */
        static const int which[2] = {5, 0};
        static const char *what[2] = {"interior point", "shared corner"};
        const int only = argc > 2 ? atoi(argv[2]) : -1; /* drag 0 | drag 1: one case */
        for (int c = 0; c < 2; ++c) {
            if (only >= 0 && c != only) continue;
            double t[REPS];
            size_t planned = 0, built = 0, reused = 0;
            double at[3];
            memcpy(at, M.pts[0] + 3 * which[c], sizeof at);
            for (int r = 0; r < REPS; ++r) {
                const double d = (r & 1) ? -0.01 : 0.01; /* there and back */
                double from[3];
                memcpy(from, M.pts[0] + 3 * which[c], sizeof from);
                for (size_t q = 0; q < M.count; ++q)
                    for (int i = 0; i < 16; ++i) {
                        double *x = M.pts[q] + 3 * i;
                        if (x[0] == from[0] && x[1] == from[1] && x[2] == from[2]) x[2] += d;
                    }
                cj_mesh_clear(mesh);
                const double t0 = cj_bench_wall();
                if (r == 0) CALLGRIND_TOGGLE_COLLECT;
                const cj_status st = cj_tess_cache_update(cache, M.p, M.count, &o, mesh, &rep, &w);
                if (r == 0) CALLGRIND_TOGGLE_COLLECT;
                t[r] = 1e3 * (cj_bench_wall() - t0);
                if (st) return 1;
                planned += w.planned;
                built += w.built;
                reused += w.pieces_reused;
            }
            printf("drag the teapot's %s (one frame = one cache update): %.1f patches "
                   "re-planned, %.1f rebuilt, %.1f reused of %zu; median %.3f ms\n",
                   what[c], (double)planned / REPS, (double)built / REPS, (double)reused / REPS,
                   M.count, median(t, REPS));
            (void)at;
        }
        cj_tess_cache_destroy(cache);
#endif
    } else {
        fprintf(stderr, "usage: bench_tess_live cold | one MODEL adaptive|uniform TOL | ratio | "
                        "drag [0|1]\n");
        return 2;
    }
    cj_mesh_destroy(mesh);
    return 0;
}
