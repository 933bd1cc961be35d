/* Cubic Bézier pieces fitted to the polylines of a plane section, each piece's distance to the
 * polyline and to its vertices measured so that the model section's bound is proven
 * (patch_section.h, cj_patches_section_curves). */
#include "patch_section_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SAMPLES 1024

static void bez(double B[4][3], double t, double out[3]) {
    double s = 1.0 - t;
    for (int k = 0; k < 3; ++k) {
        double a = s * B[0][k] + t * B[1][k], b = s * B[1][k] + t * B[2][k],
               c = s * B[2][k] + t * B[3][k];
        double ab = s * a + t * b, bc = s * b + t * c;
        out[k] = s * ab + t * bc;
    }
}

/* First and second derivatives at t. */
static void bez_d(double B[4][3], double t, double d1[3], double d2[3]) {
    double s = 1.0 - t;
    for (int k = 0; k < 3; ++k) {
        double a = B[1][k] - B[0][k], b = B[2][k] - B[1][k], c = B[3][k] - B[2][k];
        d1[k] = 3.0 * (s * (s * a + t * b) + t * (s * b + t * c));
        d2[k] = 6.0 * (s * (b - a) + t * (c - b));
    }
}

static double dist3(const double a[3], const double b[3]) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Distance from x to the segment [a, b]. */
static double seg_dist(const double x[3], const double a[3], const double b[3]) {
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
           ax[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    double l2 = dot3(ab, ab), t = l2 > 0.0 ? dot3(ax, ab) / l2 : 0.0;
    t = fmin(1.0, fmax(0.0, t));
    double p[3] = {a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]};
    return dist3(x, p);
}

/* The cubic through P[i] and P[j] with end tangents along T[i] and T[j], their lengths by least
 * squares on the chord-length parameters of the vertices between (a straight piece for one
 * segment, or when the least squares give no positive lengths). */
static void fit_cubic(const double *P, const double *T, int i, int j, double B[4][3]) {
    const double *p0 = P + 3 * i, *p3 = P + 3 * j;
    double chord = dist3(p0, p3);
    for (int k = 0; k < 3; ++k) {
        B[0][k] = p0[k];
        B[3][k] = p3[k];
        B[1][k] = p0[k] + (p3[k] - p0[k]) / 3.0;
        B[2][k] = p3[k] - (p3[k] - p0[k]) / 3.0;
    }
    if (j == i + 1 || !(chord > 0.0)) return;
    double total = 0.0;
    for (int k = i; k < j; ++k) total += dist3(P + 3 * k, P + 3 * (k + 1));
    const double *t0 = T + 3 * i, *t1 = T + 3 * j;
    double c11 = 0, c12 = 0, c22 = 0, x1 = 0, x2 = 0, run = 0.0;
    for (int k = i + 1; k < j; ++k) {
        run += dist3(P + 3 * (k - 1), P + 3 * k);
        double u = run / total, s = 1.0 - u;
        double b0 = s * s * s, b1 = 3 * u * s * s, b2 = 3 * u * u * s, b3 = u * u * u;
        double a1[3], a2[3], r[3];
        for (int q = 0; q < 3; ++q) {
            a1[q] = t0[q] * b1;
            a2[q] = -t1[q] * b2;
            r[q] = P[3 * k + q] - (p0[q] * (b0 + b1) + p3[q] * (b2 + b3));
        }
        c11 += dot3(a1, a1);
        c12 += dot3(a1, a2);
        c22 += dot3(a2, a2);
        x1 += dot3(a1, r);
        x2 += dot3(a2, r);
    }
    double det = c11 * c22 - c12 * c12, al = 0, be = 0;
    if (fabs(det) > 1e-12 * c11 * c22) {
        al = (x1 * c22 - x2 * c12) / det;
        be = (c11 * x2 - c12 * x1) / det;
    }
    if (!(al > 1e-6 * chord && be > 1e-6 * chord && al < 2.0 * total && be < 2.0 * total))
        al = be = chord / 3.0;
    for (int q = 0; q < 3; ++q) {
        B[1][q] = p0[q] + al * t0[q];
        B[2][q] = p3[q] - be * t1[q];
    }
}

/* max(e_v, e_s + 3L/2S) of the piece B for the vertices i..j (patch_section.h), or +inf as soon
 * as it passes `target` (then the range is halved anyway). */
static double piece_error(double B[4][3], const double *P, int i, int j, double target) {
    double L = 0.0;
    for (int k = 0; k < 3; ++k) L = fmax(L, dist3(B[k], B[k + 1]));
    int S = (int)fmin(MAX_SAMPLES, fmax(8.0, ceil(6.0 * L / target)));
    double move = 1.5 * L / S;
    if (move > target) return INFINITY;
    static _Thread_local double smp[MAX_SAMPLES + 1][3];
    for (int s = 0; s <= S; ++s) bez(B, (double)s / S, smp[s]);
    /* e_s: every sample to the polyline of the range; segments searched from the last one hit */
    double es = 0.0;
    int near = i;
    for (int s = 0; s <= S; ++s) {
        double best = INFINITY;
        int at = near;
        for (int k = near; k < j && best > 0.0; ++k) {
            double dd = seg_dist(smp[s], P + 3 * k, P + 3 * (k + 1));
            if (dd < best) best = dd, at = k;
            if (best <= 0.25 * target && k > at + 8) break; /* walked past: upper bound kept */
        }
        if (best + move > target) /* the whole range, not only forwards */
            for (int k = i; k < j; ++k) {
                double dd = seg_dist(smp[s], P + 3 * k, P + 3 * (k + 1));
                if (dd < best) best = dd, at = k;
            }
        near = at;
        es = fmax(es, best);
        if (es + move > target) return INFINITY;
    }
    /* e_v: every vertex between to the cubic, at evaluated points (upper bounds) */
    double ev = 0.0;
    int ns = 0;
    for (int k = i + 1; k < j; ++k) {
        const double *x = P + 3 * k;
        double best = INFINITY;
        int bs = ns;
        for (int s = ns; s <= S; ++s) {
            double dd = dist3(smp[s], x);
            if (dd < best) best = dd, bs = s;
            if (s > bs + 8 && dd > best + 2 * move) break;
        }
        double t = (double)bs / S;
        for (int it = 0; it < 4 && best > 0.0; ++it) {
            double c[3], d1[3], d2[3], e[3];
            bez(B, t, c);
            bez_d(B, t, d1, d2);
            for (int q = 0; q < 3; ++q) e[q] = c[q] - x[q];
            double f = dot3(e, d1), fp = dot3(d1, d1) + dot3(e, d2);
            if (!(fp > 0.0)) break;
            t = fmin(1.0, fmax(0.0, t - f / fp));
            bez(B, t, c);
            best = fmin(best, dist3(c, x));
        }
        if (best > target) /* search all samples before giving up */
            for (int s = 0; s <= S; ++s) best = fmin(best, dist3(smp[s], x));
        ns = bs > 8 ? bs - 8 : 0;
        ev = fmax(ev, best);
        if (ev > target) return INFINITY;
    }
    return fmax(ev, es + move);
}

static void append(cj_sect_pieces *out, double B[4][3], double err) {
    if (out->count == out->cap) {
        int cap = out->cap ? 2 * out->cap : 64;
        double *c = realloc(out->ctrl, (size_t)cap * 12 * sizeof *c);
        if (!c) {
            out->nomem = 1;
            return;
        }
        out->ctrl = c;
        out->cap = cap;
    }
    memcpy(out->ctrl + 12 * out->count++, B, 12 * sizeof(double));
    out->worst = fmax(out->worst, err);
}

static void fit_range(const double *P, const double *T, int i, int j, double target, double margin,
                      cj_sect_pieces *out) {
    double B[4][3];
    fit_cubic(P, T, i, j, B);
    double err = piece_error(B, P, i, j, target - margin);
    if (err + margin <= target || j == i + 1) {
        if (j == i + 1 && !(err + margin <= target)) /* a straight piece: its own error */
            err = piece_error(B, P, i, j, INFINITY);
        append(out, B, err + margin);
        return;
    }
    int mid = i + (j - i) / 2;
    fit_range(P, T, i, mid, target, margin, out);
    fit_range(P, T, mid, j, target, margin, out);
}

void cj_sect_fit_run(const double *P, const double *T, int np, double target, double margin,
                     cj_sect_pieces *out) {
    if (np < 2) return;
    fit_range(P, T, 0, np - 1, target, margin, out);
}
