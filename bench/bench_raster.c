/* bench_raster: the exact triangle rasterizer (raster/src/tri_*.c), depth only (visibility
 * buffer, no shading callback).
 *
 *   large: 1024 × 1024, 24 triangles each covering about half the image, random depths;
 *          fill rate = covered samples / raster time (Mpixels/s at 1 spp).
 *   small: 1024 × 1024, 200 000 triangles with bounding boxes of S × S pixels (S = 4, 8, 16),
 *          random positions (--coherent: swept row by row like a mesh) and depths; triangles
 *          per second over prepare + raster.
 *   mesh:  1024 × 1024, a grid mesh of 4 × 4 pixel quads (131 072 triangles, vertices shared
 *          and jittered, one layer): triangles per second as above.
 * "raster" runs without a tile callback (clear, rasterize, depth test: the visibility pass);
 * "+vis" runs with an empty callback, so the visibility samples are also written out for it
 * (depth and source triangle per sample; barycentrics are switched off: depth only).
 * Each on 1 and 2 threads, at 1, 4 and 16 samples per pixel; the configurations are
 * interleaved over the repetitions and the median is printed.
 *
 * Frames write their set-up into one prep kept across frames (cj_raster_prepare_again, as a
 * renderer would); --fresh makes a new prep per frame (cj_raster_prepare, freshly mapped memory).
 *
 *   bench_raster [--reps N] [--callgrind] [--fresh]
 * --callgrind: one run of a fixed small workload per configuration (256 × 256, 4 large and
 * 20 000 small triangles), for instruction counts that repeat exactly under valgrind; only
 * the prepare and the visibility pass (no "+vis" run) are collected, so
 *     valgrind --tool=callgrind --collect-atstart=no bench_raster --callgrind --workload 1 \
 *         --spp 1 --threads 1
 * gives the instructions per small triangle as the callgrind total / 20 000. */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"
#include "raster3d_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

static uint64_t g_state = 0x2545f4914f6cdd1dull;
static double urand(void) {
    g_state ^= g_state << 13;
    g_state ^= g_state >> 7;
    g_state ^= g_state << 17;
    return (double)(g_state >> 11) * 0x1p-53;
}

static int g_coherent;
static int g_fresh;            /* --fresh: a new prep per frame (cj_raster_prepare), not reused */
static cj_raster_prep *g_prep; /* the prep the frames reuse (cj_raster_prepare_again) */
static int g_callgrind;        /* collect only prepare + the visibility pass */

typedef struct workload {
    int W, H;
    size_t nv, nt;
    double *clip;
    uint32_t *tris;
} workload;

/* Triangles with vertices in a box of side `side` pixels at a random place (large: side =
 * image, vertices anywhere in 1.3 × the image). */
static void make(workload *w, int W, int H, size_t nt, double side) {
    w->W = W;
    w->H = H;
    w->nt = nt;
    w->nv = 3 * nt;
    w->clip = malloc(sizeof(double) * 4 * w->nv);
    w->tris = malloc(sizeof(uint32_t) * 3 * nt);
    for (size_t t = 0; t < nt; ++t) {
        double ox, oy;
        if (side >= W) {
            ox = -0.15 * W;
            oy = -0.15 * H;
            side = 1.3 * W;
        } else if (g_coherent) {
            /* mesh-like input order: boxes swept row by row over the image */
            const size_t per_row = (size_t)(W / side) * 2, rows = (size_t)(H / side);
            const size_t cell = t % (per_row * rows);
            ox = (double)(cell % per_row) * side / 2;
            oy = (double)(cell / per_row) * side;
        } else {
            ox = urand() * (W - side);
            oy = urand() * (H - side);
        }
        const double z = 2 * urand() - 1;
        for (int k = 0; k < 3; ++k) {
            double *c = w->clip + 4 * (3 * t + k);
            const double px = ox + urand() * side, py = oy + urand() * side;
            c[0] = 2 * px / W - 1;
            c[1] = 2 * py / H - 1;
            c[2] = z * 0.99 + 0.005 * urand();
            c[3] = 1;
            w->tris[3 * t + k] = (uint32_t)(3 * t + k);
        }
    }
}

/* A mesh: a grid of quads of side `side` pixels (two triangles each, vertices shared and
 * jittered by up to a quarter of the side), depth varying smoothly, covering the image once. */
static void make_mesh(workload *w, int W, int H, int side) {
    const int nx = W / side, ny = H / side;
    w->W = W;
    w->H = H;
    w->nv = (size_t)(nx + 1) * (ny + 1);
    w->nt = (size_t)2 * nx * ny;
    w->clip = malloc(sizeof(double) * 4 * w->nv);
    w->tris = malloc(sizeof(uint32_t) * 3 * w->nt);
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const int inner = i > 0 && j > 0 && i < nx && j < ny;
            const double px = i * side + (inner ? (urand() - 0.5) * 0.5 * side : 0);
            const double py = j * side + (inner ? (urand() - 0.5) * 0.5 * side : 0);
            double *c = w->clip + 4 * ((size_t)j * (nx + 1) + i);
            c[0] = 2 * px / W - 1;
            c[1] = 2 * py / H - 1;
            c[2] = 0.5 * sin(0.01 * px) * cos(0.013 * py);
            c[3] = 1;
        }
    size_t t = 0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const uint32_t a = (uint32_t)(j * (nx + 1) + i), b = a + 1, c = a + (uint32_t)nx + 1,
                           d = c + 1;
            const uint32_t q[6] = {a, b, d, a, d, c};
            memcpy(w->tris + 3 * t, q, sizeof q);
            t += 2;
        }
}

static void release(workload *w) {
    free(w->clip);
    free(w->tris);
}

typedef struct counter {
    uint64_t n;
} counter;
static void count_frag(void *u, int x, int y, int s, uint32_t tri, float z, float b1, float b2) {
    (void)x, (void)y, (void)s, (void)tri, (void)z, (void)b1, (void)b2;
    ((counter *)u)->n++;
}
typedef struct fwd {
    const cj_raster_prep *prep;
    counter c;
    cj_vis_sample *buf;
} fwd;
static void count_tile(void *u, const cj_tile *t) {
    fwd *f = u;
    cj_tile c = *t;
    c.samples = f->buf;
    const size_t n = (size_t)(t->x1 - t->x0) * (t->y1 - t->y0) * t->spp;
    for (size_t i = 0; i < n; ++i) c.samples[i].depth = 2.0f;
    cj_raster_tile_forward(f->prep, &c, count_frag, &f->c);
}

/* Covered samples (every fragment, depth ignored). */
static uint64_t covered(const workload *w, int spp) {
    cj_raster_input in = {w->nv, w->clip, w->nt, w->tris, w->W, w->H, spp};
    cj_raster_prep *p;
    if (cj_raster_prepare(&in, 64, NULL, &p, NULL) != CJ_OK) exit(1);
    fwd f = {p, {0}, malloc(sizeof(cj_vis_sample) * 64 * 64 * spp)};
    cj_raster_run(p, 1, count_tile, &f, NULL, NULL);
    free(f.buf);
    cj_raster_prep_destroy(p);
    return f.c.n;
}

static void no_tile(void *u, const cj_tile *t) {
    (void)u;
    (void)t;
}

/* One frame: seconds of prepare and of raster. One thread: CPU time of this thread (the run
 * happens on it), which other processes on a shared machine do not inflate; two threads:
 * wall-clock time. */
static void frame(const workload *w, int spp, int threads, double *t_prep, double *t_run,
                  double *t_resolve) {
    cj_raster_input in = {w->nv, w->clip, w->nt, w->tris, w->W, w->H, spp};
    cj_raster_prep *p = g_prep;
    double (*clock)(void) = threads == 1 ? cj_bench_thread_cpu : cj_bench_wall;
    if (g_callgrind) CALLGRIND_TOGGLE_COLLECT;
    const double t0 = clock();
    if (p ? cj_raster_prepare_again(p, &in, 64, NULL) : cj_raster_prepare(&in, 64, NULL, &p, NULL))
        exit(1);
    cj_raster_prep_set_barycentrics(p, 0); /* depth only */
    const double t1 = clock();
    if (cj_raster_run(p, threads, NULL, NULL, NULL, NULL) != CJ_OK) exit(1);
    const double t2 = clock();
    if (g_callgrind) CALLGRIND_TOGGLE_COLLECT;
    /* Again with a (empty) tile callback: the visibility samples are written for it. */
    if (cj_raster_run(p, threads, no_tile, NULL, NULL, NULL) != CJ_OK) exit(1);
    const double t3 = clock();
    if (g_fresh)
        cj_raster_prep_destroy(p);
    else
        g_prep = p;
    *t_prep = t1 - t0;
    *t_run = t2 - t1;
    *t_resolve = t3 - t2;
}

#define NCONF 30
int main(int argc, char **argv) {
    int reps = 5, cg = 0, only_w = -1, only_spp = 0, only_thr = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--callgrind"))
            cg = 1;
        else if (!strcmp(argv[i], "--fresh"))
            g_fresh = 1;
        else if (!strcmp(argv[i], "--coherent"))
            g_coherent = 1;
        else if (!strcmp(argv[i], "--workload") && i + 1 < argc)
            only_w = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--spp") && i + 1 < argc)
            only_spp = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            only_thr = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_raster [--reps N] [--callgrind] [--fresh] [--coherent] "
                            "[--workload 0-4] [--spp 1|4|16] [--threads 1|2]\n");
            return 2;
        }
    }
    if (reps < 1) reps = 1;
    if (cg) reps = 1;
    g_callgrind = cg;
    const int S = cg ? 256 : 1024;
    workload large, small[4];
    make(&large, S, S, cg ? 4 : 24, S);
    static const int sides[3] = {4, 8, 16};
    for (int k = 0; k < 3; ++k) make(&small[k], S, S, cg ? 20000 : 200000, sides[k]);
    make_mesh(&small[3], S, S, 4);
    static const int spps[3] = {1, 4, 16};
    /* configuration c: workload (0 large, 1..3 small), spp, threads */
#define SKIP(k, s, th)                                                                             \
    ((only_w >= 0 && (k) != only_w) || (only_spp && spps[s] != only_spp) ||                        \
     (only_thr && (th) != only_thr))
    uint64_t cov[5][3];
    for (int k = 0; k < 5; ++k)
        for (int s = 0; s < 3; ++s)
            cov[k][s] =
                SKIP(k, s, 1) && SKIP(k, s, 2) ? 0 : covered(k ? &small[k - 1] : &large, spps[s]);
    double *tp = calloc((size_t)NCONF * reps, sizeof(double));
    double *tr = calloc((size_t)NCONF * reps, sizeof(double));
    double *tv = calloc((size_t)NCONF * reps, sizeof(double));
    for (int r = 0; r < reps; ++r)
        for (int c = 0; c < NCONF; ++c) {
            const int k = c / 6, s = (c / 2) % 3, th = 1 + c % 2;
            if (SKIP(k, s, th)) continue;
            frame(k ? &small[k - 1] : &large, spps[s], th, &tp[c * reps + r], &tr[c * reps + r],
                  &tv[c * reps + r]);
        }
    printf("bench_raster: depth-only visibility (no barycentrics), %d x %d, tiles 64, median of "
           "%d interleaved runs%s, %s; 1 thread: thread CPU time, 2 threads: wall time\n",
           S, S, reps, cg ? " (callgrind workload)" : "",
           g_fresh ? "a fresh prep per frame" : "one prep reused by every frame");
    FILE *la = fopen("/proc/loadavg", "r");
    double load = -1;
    if (la) {
        if (fscanf(la, "%lf", &load) != 1) load = -1;
        fclose(la);
    }
    if (load >= 0)
        printf("load average %.2f at the end (2-thread wall times need an idle machine)\n", load);
    printf("%-20s %3s %3s %10s %8s %9s %9s %10s %10s %8s %8s\n", "workload", "spp", "thr",
           "covered", "prep ms", "raster ms", "+vis ms", "fill Ms/s", "+vis Ms/s", "Mtris/s",
           "+vis");
    for (int c = 0; c < NCONF; ++c) {
        const int k = c / 6, s = (c / 2) % 3, th = 1 + c % 2;
        if (SKIP(k, s, th)) continue;
        const double p = cj_bench_median(&tp[c * reps], reps);
        const double q = cj_bench_median(&tr[c * reps], reps);
        const double v = cj_bench_median(&tv[c * reps], reps);
        const workload *w = k ? &small[k - 1] : &large;
        char name[64];
        if (k == 4)
            snprintf(name, sizeof name, "mesh of 4x4 quads");
        else if (k)
            snprintf(name, sizeof name, "small %dx%d box", sides[k - 1], sides[k - 1]);
        else
            snprintf(name, sizeof name, "large (1/2 image)");
        printf("%-20s %3d %3d %10llu %8.2f %9.2f %9.2f %10.1f %10.1f %8.2f %8.2f\n", name, spps[s],
               th, (unsigned long long)cov[k][s], 1e3 * p, 1e3 * q, 1e3 * v, cov[k][s] / q * 1e-6,
               cov[k][s] / v * 1e-6, w->nt / (p + q) * 1e-6, w->nt / (p + v) * 1e-6);
    }
    cj_raster_prep_destroy(g_prep);
    free(tp);
    free(tr);
    free(tv);
    release(&large);
    for (int k = 0; k < 4; ++k) release(&small[k]);
    return 0;
}
