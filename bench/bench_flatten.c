/* bench_flatten: segment counts of the three flattening methods against the continuous optimum
 * ∫ sqrt(|κ|/(8 tol)) ds, their proven and measured deviations, and their speed.
 *
 * Curves: quarter circle r = 100 (rational quadratic), an inflection cubic, a near-cusp cubic,
 * a loop cubic, and 10 000 random cubics in a 500 x 500 box (fixed seed, or BENCH_SEED=<n>).
 * The optimum's integral ∫ sqrt(|κ|) ds = ∫ sqrt(|c' x c''|) / sqrt(|c'|) dt is computed by
 * adaptive Gauss–Kronrod quadrature (relative accuracy ~1e-10) on the exact derivatives.
 * The measured deviation is the largest distance from dense curve samples (64 per segment,
 * long-double evaluation) to their own segment, an upper estimate of the distance to the
 * polyline. Times are process CPU time (robust on a shared machine) of the count-then-fill
 * form into a preallocated buffer.
 * Goals (measured, not asserted): near-optimal <= 1.10x, uniform <= 1.3x, deviation <= tol.
 *
 * Peer table (issues 13 and 20; with cairo and kurbo when built with them, see
 * bench/areas/flatten.cmake): degrees 3 and 2, each 10 000 random curves in a 1000 x 1000 box
 * plus hard ones (loop, cusp, near-cusp, inflection; a quadratic turning back on itself),
 * tolerances 0.01, 0.25 and 1; ours (near-optimal and uniform) against kurbo 0.7's flatten
 * (Levien's method; bench/kurbo, a Rust static library) and cairo_copy_path_flat
 * (cairo_set_tolerance; quadratics as their exact cubic elevation), measured in the same run
 * with the repetitions interleaved, thread CPU time, median (and range) of 5. Deviation: the
 * largest distance from the curve to the whole polyline, enclosed to 1e-6 tol by the
 * branch-and-bound oracle of flatten_oracle.c; a curve counts as over tol only when the
 * enclosure's lower end is (proven), undecided when it straddles tol.
 * BENCH_NPEER=<n> takes n random curves instead (quick looks), BENCH_DEGREE=<2|3> one degree.
 * BENCH_PEERS_ONLY=1 prints the peer table alone. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "casteljau/flatten.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "bench_clock.h"
#include "flatten_oracle.h"
#ifdef CJ_HAVE_CAIRO
#include <cairo.h>
#endif

#define NRANDOM 10000

typedef struct curve {
    int n;
    double p[4 * 2];
    double w[4];
    int rational;
} curve;

/* ---- exact derivatives (homogeneous de Casteljau in long double) -------------------------- */

static void hom_eval(int n, const long double *h, long double t, long double *out) {
    long double w[4 * 3];
    memcpy(w, h, sizeof(long double) * (size_t)(n + 1) * 3);
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * 3; ++i) w[i] = (1 - t) * w[i] + t * w[i + 3];
    memcpy(out, w, sizeof(long double) * 3);
}

/* sqrt(|κ|) |c'| at t for a (rational) planar curve. */
static double integrand(const curve *c, long double t) {
    long double h0[4 * 3] = {0}, h1[3 * 3] = {0}, h2[2 * 3] = {0};
    const int n = c->n;
    for (int i = 0; i <= n; ++i) {
        const long double w = c->rational ? c->w[i] : 1.0L;
        h0[i * 3] = w * c->p[2 * i];
        h0[i * 3 + 1] = w * c->p[2 * i + 1];
        h0[i * 3 + 2] = w;
    }
    for (int i = 0; i < n * 3; ++i) h1[i] = n * (h0[i + 3] - h0[i]);
    for (int i = 0; i < (n - 1) * 3; ++i) h2[i] = (n - 1) * (h1[i + 3] - h1[i]);
    long double P[3], P1[3], P2[3] = {0, 0, 0};
    hom_eval(n, h0, t, P);
    hom_eval(n - 1, h1, t, P1);
    if (n >= 2) hom_eval(n - 2, h2, t, P2);
    /* c = P/W, c' = (P' - c W')/W, c'' = (P'' - 2 c' W' - c W'')/W */
    long double c0[2], c1[2], c2[2];
    for (int k = 0; k < 2; ++k) {
        c0[k] = P[k] / P[2];
        c1[k] = (P1[k] - c0[k] * P1[2]) / P[2];
        c2[k] = (P2[k] - 2 * c1[k] * P1[2] - c0[k] * P2[2]) / P[2];
    }
    const long double cr = fabsl(c1[0] * c2[1] - c1[1] * c2[0]);
    const long double sp = sqrtl(c1[0] * c1[0] + c1[1] * c1[1]);
    if (sp == 0) return 0.0;
    return (double)(sqrtl(cr) / sqrtl(sp));
}

static const double gk_x[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
static const double gk_wk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double gk_wg[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

static double gk15(const curve *c, double a, double b, double *err) {
    const double m = 0.5 * (a + b), h = 0.5 * (b - a);
    double k = gk_wk[7] * integrand(c, m), g = gk_wg[3] * integrand(c, m);
    for (int i = 0; i < 7; ++i) {
        const double f1 = integrand(c, m - h * gk_x[i]), f2 = integrand(c, m + h * gk_x[i]);
        k += gk_wk[i] * (f1 + f2);
        if (i % 2 == 1) g += gk_wg[i / 2] * (f1 + f2);
    }
    *err = fabs((k - g) * h);
    return k * h;
}

static double adapt(const curve *c, double a, double b, double tol, int depth) {
    double err;
    const double v = gk15(c, a, b, &err);
    if (err <= tol || depth > 40) return v;
    const double m = 0.5 * (a + b);
    return adapt(c, a, m, 0.5 * tol, depth + 1) + adapt(c, m, b, 0.5 * tol, depth + 1);
}

/* ∫ sqrt(|κ|) ds over the whole curve. */
static double sqrt_kappa_integral(const curve *c) {
    double rough = 0, err;
    for (int i = 0; i < 16; ++i) rough += gk15(c, i / 16.0, (i + 1) / 16.0, &err);
    double v = 0;
    for (int i = 0; i < 16; ++i)
        v += adapt(c, i / 16.0, (i + 1) / 16.0, fmax(rough, 1e-3) * 1e-11, 0);
    return v;
}

/* ---- measurement ------------------------------------------------------------------------ */

typedef struct coll {
    size_t n, cap;
    double *pts, *ts;
} coll;

static void collect(void *user, const double *pt, int dim, size_t piece, double t) {
    (void)dim;
    (void)piece;
    coll *cl = user;
    if (cl->n == cl->cap) {
        cl->cap = cl->cap ? 2 * cl->cap : 256;
        cl->pts = realloc(cl->pts, sizeof(double) * 2 * cl->cap);
        cl->ts = realloc(cl->ts, sizeof(double) * cl->cap);
        if (!cl->pts || !cl->ts) abort();
    }
    cl->pts[2 * cl->n] = pt[0];
    cl->pts[2 * cl->n + 1] = pt[1];
    cl->ts[cl->n++] = t;
}

static void exact_point(const curve *c, long double t, long double *out) {
    long double h[4 * 3], P[3];
    for (int i = 0; i <= c->n; ++i) {
        const long double w = c->rational ? c->w[i] : 1.0L;
        h[i * 3] = w * c->p[2 * i];
        h[i * 3 + 1] = w * c->p[2 * i + 1];
        h[i * 3 + 2] = w;
    }
    hom_eval(c->n, h, t, P);
    out[0] = P[0] / P[2];
    out[1] = P[1] / P[2];
}

static double measured_deviation(const curve *c, const coll *cl) {
    long double worst = 0;
    for (size_t j = 0; j + 1 < cl->n; ++j) {
        const double *a = cl->pts + 2 * j, *b = cl->pts + 2 * j + 2;
        const long double abx = (long double)b[0] - a[0], aby = (long double)b[1] - a[1];
        const long double ab2 = abx * abx + aby * aby;
        for (int s = 1; s < 64; ++s) {
            long double p[2];
            exact_point(c, cl->ts[j] + (cl->ts[j + 1] - (long double)cl->ts[j]) * s / 64, p);
            long double u = ab2 > 0 ? ((p[0] - a[0]) * abx + (p[1] - a[1]) * aby) / ab2 : 0;
            if (u < 0) u = 0;
            if (u > 1) u = 1;
            const long double dx = p[0] - (a[0] + u * abx), dy = p[1] - (a[1] + u * aby);
            const long double d = sqrtl(dx * dx + dy * dy);
            if (d > worst) worst = d;
        }
    }
    return (double)worst;
}

static cj_status flatten(const curve *c, const cj_flatten_opts *o, double *buf, size_t cap,
                         size_t *np, cj_flatten_stats *st) {
    if (c->rational) {
        cj_rbezier r = cj_rbezier_view(c->n, 2, c->p, c->w);
        return cj_flatten_rbezier(&r, o, buf, cap, np, st);
    }
    cj_bezier b = cj_bezier_view(c->n, 2, c->p);
    return cj_flatten_bezier(&b, o, buf, cap, np, st);
}

static uint64_t splitmix(uint64_t *s) {
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* ---- peer table ----------------------------------------------------------------------------- */

#define NPEER 10000
/* Random curves per degree in the peer table (NPEER, or BENCH_NPEER=<n> for quick looks). */
static int g_npeer = NPEER;
#define NHARD  4
#define NROUND 5
/* Oracle enclosure width, relative to tol. */
#define ORACLE_GAP 1e-6

typedef struct peer_out {
    size_t segs, over, undecided;
    double worst;
} peer_out;

enum { P_NEAR, P_UNIFORM, P_KURBO, P_CAIRO, P_COUNT };
static const char *const peer_name[P_COUNT] = {"casteljau near-optimal", "casteljau uniform",
                                               "kurbo 0.7 flatten", "cairo 1.16 copy_path_flat"};

#ifdef CJ_HAVE_KURBO
/* bench/kurbo/lib.rs */
size_t cj_bench_kurbo_flatten(int n, const double *p, double tol, double *out, size_t cap);
#endif

/* Whether peer m was built in. */
static int peer_present(int m) {
#ifndef CJ_HAVE_KURBO
    if (m == P_KURBO) return 0;
#endif
#ifndef CJ_HAVE_CAIRO
    if (m == P_CAIRO) return 0;
#endif
    (void)m;
    return 1;
}

#ifdef CJ_HAVE_CAIRO
static cairo_t *g_cr;
/* cairo's flattening of curve c into pts (room for cap points); returns the point count. */
static size_t cairo_flat(const curve *c, double *pts, size_t cap) {
    double q[8];
    if (c->n == 3) {
        memcpy(q, c->p, sizeof q);
    } else { /* exact degree elevation (up to rounding) */
        q[0] = c->p[0], q[1] = c->p[1], q[6] = c->p[4], q[7] = c->p[5];
        for (int k = 0; k < 2; ++k) {
            q[2 + k] = c->p[k] + 2.0 / 3.0 * (c->p[2 + k] - c->p[k]);
            q[4 + k] = c->p[4 + k] + 2.0 / 3.0 * (c->p[2 + k] - c->p[4 + k]);
        }
    }
    cairo_new_path(g_cr);
    cairo_move_to(g_cr, q[0], q[1]);
    cairo_curve_to(g_cr, q[2], q[3], q[4], q[5], q[6], q[7]);
    cairo_path_t *path = cairo_copy_path_flat(g_cr);
    size_t np = 0;
    for (int i = 0; i < path->num_data; i += path->data[i].header.length) {
        const cairo_path_data_t *d = &path->data[i];
        if (d->header.type == CAIRO_PATH_MOVE_TO || d->header.type == CAIRO_PATH_LINE_TO) {
            if (pts && np < cap) pts[2 * np] = d[1].point.x, pts[2 * np + 1] = d[1].point.y;
            ++np;
        }
    }
    cairo_path_destroy(path);
    return np;
}
#endif

static size_t run_peer(int m, const curve *c, double tol, double *buf, size_t cap) {
    if (m == P_KURBO) {
#ifdef CJ_HAVE_KURBO
        return cj_bench_kurbo_flatten(c->n, c->p, tol, buf, cap);
#else
        return 0;
#endif
    }
    if (m == P_CAIRO) {
#ifdef CJ_HAVE_CAIRO
        return cairo_flat(c, buf, cap);
#else
        return 0;
#endif
    }
    cj_flatten_opts o =
        cj_flatten_defaults(m == P_NEAR ? CJ_FLATTEN_NEAR_OPTIMAL : CJ_FLATTEN_UNIFORM, tol);
    size_t np = 0;
    if (flatten(c, &o, buf, cap, &np, NULL)) abort();
    return np;
}

static void peer_table(const curve *set, const double *I, int n, double *buf, size_t cap) {
    const double tols[3] = {0.01, 0.25, 1.0};
    const int count = g_npeer + NHARD;
#ifdef CJ_HAVE_CAIRO
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
    g_cr = cairo_create(sf);
#endif
    for (int ti = 0; ti < 3; ++ti) {
        const double tol = tols[ti];
#ifdef CJ_HAVE_CAIRO
        cairo_set_tolerance(g_cr, tol);
#endif
        double opt = 0;
        for (int i = 0; i < count; ++i) opt += I[i] / sqrt(8 * tol);
        peer_out po[P_COUNT];
        for (int m = 0; m < P_COUNT; ++m) {
            po[m] = (peer_out){0, 0, 0, 0};
            if (!peer_present(m)) continue;
            for (int i = 0; i < count; ++i) {
                const size_t np = run_peer(m, &set[i], tol, buf, cap);
                if (np > cap || np < 2) abort();
                const cj_oracle_dev dev =
                    cj_oracle_curve_polyline(set[i].n, set[i].p, buf, np, ORACLE_GAP, tol);
                po[m].segs += np - 1;
                if (dev.lo > tol)
                    po[m].over++;
                else if (dev.hi > tol)
                    po[m].undecided++;
                if (dev.lo / tol > po[m].worst) po[m].worst = dev.lo / tol;
            }
        }
        double tm[P_COUNT][NROUND];
        for (int r = 0; r < NROUND; ++r)
            for (int m = 0; m < P_COUNT; ++m) {
                if (!peer_present(m)) continue;
                const double t0 = cj_bench_thread_cpu();
                for (int i = 0; i < count; ++i) run_peer(m, &set[i], tol, buf, cap);
                tm[m][r] = (cj_bench_thread_cpu() - t0) / count * 1e6;
            }
        double med[P_COUNT], lo[P_COUNT], hi[P_COUNT];
        for (int m = 0; m < P_COUNT; ++m) {
            if (!peer_present(m)) continue;
            med[m] = cj_bench_median(tm[m], NROUND);
            lo[m] = hi[m] = tm[m][0];
            for (int r = 1; r < NROUND; ++r) {
                lo[m] = fmin(lo[m], tm[m][r]);
                hi[m] = fmax(hi[m], tm[m][r]);
            }
        }
        for (int m = 0; m < P_COUNT; ++m) {
            if (!peer_present(m)) continue;
            printf("| %d | %g | %s | %zu | %.3f | %.3f | %.4f | %zu | %zu | %.2f (%.2f-%.2f) |", n,
                   tol, peer_name[m], po[m].segs, (double)po[m].segs / (double)po[P_NEAR].segs,
                   po[m].segs / opt, po[m].worst, po[m].over, po[m].undecided, med[m], lo[m],
                   hi[m]);
            for (int q = P_KURBO; q <= P_CAIRO; ++q) {
                if (peer_present(q))
                    printf(" %.2f |", med[m] / med[q]);
                else
                    printf(" - |");
            }
            printf("\n");
        }
    }
#ifdef CJ_HAVE_CAIRO
    cairo_destroy(g_cr);
    cairo_surface_destroy(sf);
#endif
}

static void peers(void) {
    const char *np_env = getenv("BENCH_NPEER");
    if (np_env && atoi(np_env) > 0 && atoi(np_env) < NPEER) g_npeer = atoi(np_env);
    static curve set[NPEER + NHARD];
    static double I[NPEER + NHARD];
    size_t cap = 1 << 16;
    double *buf = malloc(sizeof(double) * 2 * cap);
    if (!buf) abort();
    printf("\n## Peers: %d random curves in a 1000 x 1000 box plus %d hard ones per degree, "
           "same run, thread CPU, median of %d interleaved rounds\n\n",
           g_npeer, NHARD, NROUND);
    printf("deviation = largest distance curve -> polyline, enclosed by the branch-and-bound "
           "oracle of bench/flatten_oracle.c to within %g tol; over tol: proven over (the "
           "oracle's lower end > tol); undecided: the enclosure straddles tol; optimum = "
           "Σ ∫sqrt(|κ|/(8 tol)) ds; µs/curve: median (min-max) of the rounds; time ÷ peer < 1: "
           "faster than the peer\n\n",
           ORACLE_GAP);
    printf("| degree | tol | method | segments | seg ÷ ours | seg/opt | worst dev ÷ tol | curves "
           "over tol | undecided | µs/curve | time ÷ kurbo | time ÷ cairo "
           "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    const char *only = getenv("BENCH_DEGREE");
    for (int n = 3; n >= 2; --n) {
        if (only && atoi(only) != n) continue;
        uint64_t s = 20261123 + (uint64_t)n;
        if (n == 3) {
            set[0] = (curve){3, {0, 0, 1000, 600, -400, 600, 1000, 0}, {0}, 0}; /* loop */
            set[1] = (curve){3, {0, 0, 1000, 1000, 0, 1000, 1000, 0}, {0}, 0};  /* cusp */
            set[2] = (curve){3, {0, 0, 1000, 1000, 0, 1000, 1000.5, 0}, {0}, 0};
            set[3] = (curve){3, {0, 0, 400, 600, 600, -600, 1000, 0}, {0}, 0}; /* inflection */
        } else {
            set[0] = (curve){2, {0, 0, 1000, 1000, 0, 0.5}, {0}, 0}; /* turns back (near-cusp) */
            set[1] = (curve){2, {0, 0, 2000, 10, 1000, 0}, {0}, 0};  /* control past the chord */
            set[2] = (curve){2, {0, 0, 500, 1000, 1000, 0}, {0}, 0};
            set[3] = (curve){2, {0, 0, 1000, 0, 1000, 1000}, {0}, 0};
        }
        for (int i = NHARD; i < g_npeer + NHARD; ++i) {
            set[i].n = n;
            set[i].rational = 0;
            for (int k = 0; k < 2 * (n + 1); ++k)
                set[i].p[k] = (double)(splitmix(&s) >> 11) * 0x1p-53 * 1000;
        }
        for (int i = 0; i < g_npeer + NHARD; ++i) I[i] = sqrt_kappa_integral(&set[i]);
        peer_table(set, I, n, buf, cap);
    }
    free(buf);
}

int main(void) {
    if (getenv("BENCH_PEERS_ONLY")) { /* only the peer table */
        peers();
        return 0;
    }
    static curve set[4 + NRANDOM];
    const char *names[5] = {"quarter circle r=100 (rational)", "inflection cubic",
                            "near-cusp cubic", "loop cubic", "10000 random cubics"};
    const double s2 = sqrt(0.5);
    set[0] = (curve){2, {100, 0, 100, 100, 0, 100}, {1, s2, 1}, 1};
    set[1] = (curve){3, {0, 0, 200, 300, 300, -300, 500, 0}, {0}, 0};
    set[2] = (curve){3, {0, 0, 500, 500, 0, 500, 500.5, 0}, {0}, 0};
    set[3] = (curve){3, {0, 0, 700, 400, -200, 400, 500, 0}, {0}, 0};
    uint64_t seed = 20261121;
    const char *env = getenv("BENCH_SEED");
    if (env) seed = strtoull(env, NULL, 10);
    uint64_t s = seed;
    for (int i = 0; i < NRANDOM; ++i) {
        set[4 + i].n = 3;
        set[4 + i].rational = 0;
        for (int k = 0; k < 8; ++k) set[4 + i].p[k] = (double)(splitmix(&s) >> 11) * 0x1p-53 * 500;
    }
    static double I[4 + NRANDOM];
    for (int i = 0; i < 4 + NRANDOM; ++i) I[i] = sqrt_kappa_integral(&set[i]);
    printf("# bench_flatten (random cubics seed %llu; optimum = ∫sqrt(|κ|/(8 tol)) ds by adaptive "
           "Gauss-Kronrod)\n\n",
           (unsigned long long)seed);
    printf("sanity: quarter circle ∫sqrt(κ) ds = %.10f (exact (π/2) sqrt(100) = %.10f)\n\n", I[0],
           acos(-1.0) / 2 * 10);
    printf("| curve | tol | method | segments | optimum | seg/opt | seg/Σceil(opt) | proven bound "
           "| measured dev | ns/curve | ns/segment |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    const double tols[4] = {0.01, 0.1, 0.25, 1.0};
    const char *mn[3] = {"uniform (Wang)", "subdivide", "near-optimal"};
    size_t bufcap = 1 << 20;
    double *buf = malloc(sizeof(double) * 2 * bufcap);
    coll cl = {0};
    int all_ok = 1;
    for (int g = 0; g < 5; ++g) {
        const int first = g < 4 ? g : 4, count = g < 4 ? 1 : NRANDOM;
        for (int ti = 0; ti < 4; ++ti) {
            const double tol = tols[ti];
            double opt = 0, optceil = 0;
            for (int i = first; i < first + count; ++i) {
                opt += I[i] / sqrt(8 * tol);
                optceil += fmax(1.0, ceil(I[i] / sqrt(8 * tol)));
            }
            for (int m = 0; m < 3; ++m) {
                cj_flatten_opts o = cj_flatten_defaults((cj_flatten_method)m, tol);
                size_t segs = 0;
                double bound = 0, dev = 0;
                for (int i = first; i < first + count; ++i) {
                    cj_flatten_stats st;
                    cl.n = 0;
                    cj_status r;
                    if (set[i].rational) {
                        cj_rbezier rb = cj_rbezier_view(set[i].n, 2, set[i].p, set[i].w);
                        r = cj_flatten_rbezier_cb(&rb, &o, collect, &cl, &st);
                    } else {
                        cj_bezier b = cj_bezier_view(set[i].n, 2, set[i].p);
                        r = cj_flatten_bezier_cb(&b, &o, collect, &cl, &st);
                    }
                    if (r) {
                        printf("flatten failed: %s\n", cj_last_error());
                        return 1;
                    }
                    segs += st.segments;
                    bound = fmax(bound, st.bound);
                    dev = fmax(dev, measured_deviation(&set[i], &cl));
                }
                if (dev > tol) all_ok = 0;
                /* timing: repeat until >= 50 ms */
                double t0 = (1e9 * cj_bench_process_cpu()), t1;
                long reps = 0;
                do {
                    for (int i = first; i < first + count; ++i) {
                        size_t np;
                        flatten(&set[i], &o, buf, bufcap, &np, NULL);
                    }
                    ++reps;
                    t1 = (1e9 * cj_bench_process_cpu());
                } while (t1 - t0 < 5e7);
                const double per_curve = (t1 - t0) / ((double)reps * count);
                printf("| %s | %g | %s | %zu | %.1f | %.3f | %.3f | %.4g | %.4g | %.0f | %.1f |\n",
                       names[g], tol, mn[m], segs, opt, segs / opt, segs / optceil, bound, dev,
                       per_curve, per_curve * count / (double)segs);
            }
        }
    }
    printf("\nevery measured deviation <= tol: %s\n", all_ok ? "yes" : "NO");
    peers();
    free(cl.pts);
    free(cl.ts);
    free(buf);
    return 0;
}
