/* Tessellation of rational patches (split from test_tessellate.c): random rational patches
 * (degrees 1..4, weights in [0.2, 5]) and exact sphere octants, torus pieces and a quarter
 * cylinder, adaptive and uniform. The distance from the surface (independent homogeneous
 * Bernstein sums) to its mesh points L(x) (linear) and Q(x) (homogeneous linear) and to its
 * triangle, and the exact distance of the mesh to the sphere/torus/cylinder, stay within the
 * proven bound (<= tol in adaptive mode); the closed ones are crack-free manifolds. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/analytic.h"
#include "casteljau/patchset.h"
#include "casteljau/quadric.h"
#include "casteljau/tessellate.h"
#include "rng.h"
#include "tessellate_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define SQRT1_2 0.70710678118654752440

static uint64_t seed;

/* ---- rational patches -------------------------------------------------------------------- */

/* Independent homogeneous evaluation: numerator and denominator Bernstein sums. */
static void bern_eval_h(const cj_patch *p, double u, double v, double num[3], double *den) {
    const int m = p->deg_u, n = p->deg_v;
    double bu[CJ_PATCH_MAX_DEGREE + 1], bv[CJ_PATCH_MAX_DEGREE + 1];
    double pu[CJ_PATCH_MAX_DEGREE + 1], qu[CJ_PATCH_MAX_DEGREE + 1];
    pu[0] = qu[0] = 1.0;
    for (int i = 1; i <= m; ++i) pu[i] = pu[i - 1] * u, qu[i] = qu[i - 1] * (1 - u);
    for (int i = 0; i <= m; ++i) bu[i] = tess_binom(m, i) * pu[i] * qu[m - i];
    pu[0] = qu[0] = 1.0;
    for (int j = 1; j <= n; ++j) pu[j] = pu[j - 1] * v, qu[j] = qu[j - 1] * (1 - v);
    for (int j = 0; j <= n; ++j) bv[j] = tess_binom(n, j) * pu[j] * qu[n - j];
    num[0] = num[1] = num[2] = *den = 0.0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const int q = j * (m + 1) + i;
            const double w = bu[i] * bv[j] * (p->weights ? p->weights[q] : 1.0);
            *den += w;
            for (int k = 0; k < 3; ++k) num[k] += w * p->pts[3 * q + k];
        }
}

static double dist3(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* Distance from point x to triangle (a, b, c): minimum over the plane projection when it falls
 * inside, else over the three edges (closest point on a segment). */
static double point_triangle_distance(const double *x, const double *a, const double *b,
                                      const double *c) {
    double e0[3], e1[3], d[3], nrm[3];
    for (int k = 0; k < 3; ++k) e0[k] = b[k] - a[k], e1[k] = c[k] - a[k], d[k] = x[k] - a[k];
    nrm[0] = e0[1] * e1[2] - e0[2] * e1[1];
    nrm[1] = e0[2] * e1[0] - e0[0] * e1[2];
    nrm[2] = e0[0] * e1[1] - e0[1] * e1[0];
    const double nn = nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2];
    if (nn > 0.0) {
        /* barycentric of the projection by sub-areas */
        const double *P3[3] = {a, b, c};
        const double t = (d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2]) / nn;
        double y[3];
        for (int k = 0; k < 3; ++k) y[k] = x[k] - t * nrm[k];
        int inside = 1;
        for (int e = 0; e < 3 && inside; ++e) {
            const double *p0 = P3[e], *p1 = P3[(e + 1) % 3];
            double f[3], g[3];
            for (int k = 0; k < 3; ++k) f[k] = p1[k] - p0[k], g[k] = y[k] - p0[k];
            const double cr[3] = {f[1] * g[2] - f[2] * g[1], f[2] * g[0] - f[0] * g[2],
                                  f[0] * g[1] - f[1] * g[0]};
            if (cr[0] * nrm[0] + cr[1] * nrm[1] + cr[2] * nrm[2] < 0.0) inside = 0;
        }
        if (inside) return fabs(t) * sqrt(nn);
    }
    double best = INFINITY;
    const double *P3[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) {
        const double *p0 = P3[e], *p1 = P3[(e + 1) % 3];
        double f[3], ff = 0.0, fg = 0.0;
        for (int k = 0; k < 3; ++k) {
            f[k] = p1[k] - p0[k];
            ff += f[k] * f[k];
            fg += f[k] * (x[k] - p0[k]);
        }
        double t = ff > 0.0 ? fg / ff : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        double q[3];
        for (int k = 0; k < 3; ++k) q[k] = p0[k] + t * f[k];
        best = fmin(best, dist3(x, q));
    }
    return best;
}

typedef double (*exact_dist_fn)(const double *x); /* distance to an exact surface */

typedef struct rat_stats {
    double dev;        /* max of min(|S(x) - L(x)|, |S(x) - Q(x)|) */
    double tri_dist;   /* max distance from S(x) to its triangle */
    double mesh_exact; /* max distance of the mesh points L(x) to the exact surface */
    double surf_exact; /* max distance of the oracle's S(x) to the exact surface */
} rat_stats;

/* Samples every triangle on the barycentric lattice of step 1/L with the independent oracle:
 * S(x) at the interpolated (u,v); the mesh points L(x) = Σ λ_i V_i and Q(x) = Σ λ_i w_i V_i /
 * Σ λ_i w_i (w_i the oracle's weight at vertex i), the deviation being the smaller of
 * |S - L| and |S - Q| (the quantity the rational bound bounds); the distance from S(x) to the
 * triangle, which must not exceed it; with `exact`, the distances of S(x) and L(x) to the
 * exact surface. Also checks every vertex lies on its patch (within 1e-12 of the size). */
static rat_stats rational_deviation(const cj_mesh *mesh, const cj_patch *patches, int L,
                                    double size, exact_dist_fn exact) {
    rat_stats st = {0.0, 0.0, 0.0, 0.0};
    for (size_t t = 0; t < mesh->triangle_count; ++t) {
        const cj_patch *p = &patches[mesh->triangle_patch[t]];
        const uint32_t *vi = mesh->triangles + 3 * t;
        const double *uv[3], *V[3];
        double w[3];
        for (int k = 0; k < 3; ++k) {
            uv[k] = mesh->uvs + 2 * (size_t)vi[k];
            V[k] = mesh->positions + 3 * (size_t)vi[k];
            double num[3], s[3];
            bern_eval_h(p, uv[k][0], uv[k][1], num, &w[k]);
            for (int c = 0; c < 3; ++c) s[c] = num[c] / w[k];
            if (dist3(s, V[k]) > 1e-12 * size)
                fail_msg("seed %llu: triangle %zu vertex %d is not on patch %d",
                         (unsigned long long)seed, t, k, (int)mesh->triangle_patch[t]);
        }
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const double l[3] = {(double)i / L, (double)j / L,
                                     1.0 - (double)i / L - (double)j / L};
                double num[3], den, s[3], q[3] = {0, 0, 0};
                bern_eval_h(p, l[0] * uv[0][0] + l[1] * uv[1][0] + l[2] * uv[2][0],
                            l[0] * uv[0][1] + l[1] * uv[1][1] + l[2] * uv[2][1], num, &den);
                for (int c = 0; c < 3; ++c) s[c] = num[c] / den;
                double qh[3] = {0, 0, 0};
                const double sw = l[0] * w[0] + l[1] * w[1] + l[2] * w[2];
                for (int k = 0; k < 3; ++k)
                    for (int c = 0; c < 3; ++c) {
                        q[c] += l[k] * V[k][c];
                        qh[c] += l[k] * w[k] / sw * V[k][c];
                    }
                const double dev = fmin(dist3(s, q), dist3(s, qh));
                const double td = point_triangle_distance(s, V[0], V[1], V[2]);
                if (td > dev + 1e-13 * size)
                    fail_msg("seed %llu: triangle %zu: distance to the triangle %.6g exceeds the "
                             "distance %.6g to one of its points",
                             (unsigned long long)seed, t, td, dev);
                st.dev = fmax(st.dev, dev);
                st.tri_dist = fmax(st.tri_dist, td);
                if (exact) {
                    st.mesh_exact = fmax(st.mesh_exact, exact(q));
                    st.surf_exact = fmax(st.surf_exact, exact(s));
                }
            }
    }
    return st;
}

static void test_rational_random(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x9e3779b97f4a7c15ull);
    int cases = 0;
    double worst_ratio = 0.0, best_ratio = 1.0;
    size_t tris[2] = {0, 0}, uni_tris = 0, ada6 = 0;
    for (int c = 0; c < 12; ++c) {
        const int m = cj_rng_int(&r, 1, 4), n = cj_rng_int(&r, 1, 4);
        double pts[25 * 3], w[25], w3[25];
        for (int q = 0; q < (m + 1) * (n + 1); ++q) {
            tess_random_point(&r, m, n, q, pts + 3 * q);
            w[q] = exp(cj_rng_range(&r, log(0.2), log(5.0))); /* in [0.2, 5] */
            w3[q] = 3.0 * w[q];
        }
        cj_patch p = cj_patch_view(m, n, pts, w);
        double size;
        cj_patch_size(&p, &size);
        const double tol = (c % 2 ? 1e-2 : 4e-3) * size;
        for (int mode = 0; mode < 2; ++mode) {
            cj_mesh *mesh;
            assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
            cj_tess_options opt = {tol, mode ? 9 : 0, 3, 0};
            cj_tess_report rep;
            const cj_status st = cj_tessellate_patches(&p, 1, &opt, mesh, &rep);
            if (st != CJ_OK)
                fail_msg("seed %llu rational case %d mode %d (deg %d,%d): %s",
                         (unsigned long long)seed, c, mode, m, n, cj_last_error());
            const rat_stats rs = rational_deviation(mesh, &p, 4, size, NULL);
            if (!isfinite(rep.bound) || rs.dev > rep.bound || rep.measured > rep.bound)
                fail_msg("seed %llu rational case %d mode %d: sampled deviation %.6g (library "
                         "%.6g) > proven bound %.6g",
                         (unsigned long long)seed, c, mode, rs.dev, rep.measured, rep.bound);
            if (mode == 0 && rep.bound > tol)
                fail_msg("seed %llu rational case %d: bound %.6g > tol %.6g",
                         (unsigned long long)seed, c, rep.bound, tol);
            if (mode == 0 && c < 4) { /* (a linear search: the first cases only) */
                size_t uni;
                const int K = tess_smallest_uniform(&p, 1, tol, &uni);
                if (rep.triangles > uni)
                    fail_msg("seed %llu rational case %d: adaptive %zu triangles > uniform K=%d "
                             "%zu triangles",
                             (unsigned long long)seed, c, rep.triangles, K, uni);
                uni_tris += uni;
                ada6 += rep.triangles;
            }
            if (mode == 1) {
                /* the surface does not change when every weight is scaled: nor does the bound
                 * (up to rounding) */
                cj_patch p3 = cj_patch_view(m, n, pts, w3);
                cj_tess_report rep3;
                cj_mesh_clear(mesh);
                assert_int_equal(cj_tessellate_patches(&p3, 1, &opt, mesh, &rep3), CJ_OK);
                if (fabs(rep3.bound - rep.bound) > 1e-9 * rep.bound)
                    fail_msg("seed %llu rational case %d: bound %.17g changes to %.17g when the "
                             "weights are scaled by 3",
                             (unsigned long long)seed, c, rep.bound, rep3.bound);
            }
            worst_ratio = fmax(worst_ratio, rs.dev / rep.bound);
            best_ratio = fmin(best_ratio, rs.dev / rep.bound);
            tris[mode] += rep.triangles;
            cj_mesh_destroy(mesh);
            ++cases;
        }
    }
    printf("random rational patches (deg 1..4, weights in [0.2,5]): %d tessellations, sampled "
           "deviation min(|S-L|,|S-Q|) <= proven bound (<= tol adaptive, finite uniform), "
           "deviation/bound in "
           "[%.3f, %.3f]; adaptive %zu triangles (first 4 cases %zu <= %zu of the smallest "
           "uniform grids meeting tol), uniform 9x9 %zu; bound invariant under weight scaling\n",
           cases, best_ratio, worst_ratio, tris[0], ada6, uni_tris, tris[1]);
}

/* Exact rational nets: the tensor product of two rational quadratic quarter circles. */
static const double QC[3][2] = {{1, 0}, {1, 1}, {0, 1}};
static const double QW[3] = {1, SQRT1_2, 1};

/* Rotates (x, y) by k quarter turns (exact). */
static void quarter_turn(int k, double x, double y, double *ox, double *oy) {
    for (int i = 0; i < (k & 3); ++i) {
        const double t = x;
        x = -y;
        y = t;
    }
    *ox = x;
    *oy = y;
}

/* Sphere octant k (0..3 around z), north (hemi = 0) or south (1): S = (C(u) r(v), z(v)) with
 * C the quarter circle from angle k 90deg (reversed in the south so the normal points out) and
 * (r, z) the quarter circle from the equator to the pole. Unit sphere; the pole row collapses
 * (identical points, weights 1, 1/sqrt2, 1). */
static void sphere_octant(int k, int hemi, double *pts, double *w) {
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const int ii = hemi ? 2 - i : i;
            double x, y;
            quarter_turn(k, QC[ii][0], QC[ii][1], &x, &y);
            const int q = j * 3 + i;
            pts[3 * q] = x * QC[j][0];
            pts[3 * q + 1] = y * QC[j][0];
            pts[3 * q + 2] = hemi ? -QC[j][1] : QC[j][1];
            w[q] = QW[ii] * QW[j];
        }
}

/* Torus piece (a, b): R = 2, tube r = 0.5, around z by quarter a, around the tube by quarter
 * b: S = ((R + r cos phi) C(u), r sin phi). */
static void torus_piece(int a, int b, double *pts, double *w) {
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            double x, y, cphi, sphi;
            quarter_turn(a, QC[i][0], QC[i][1], &x, &y);
            quarter_turn(b, QC[j][0], QC[j][1], &cphi, &sphi);
            const int q = j * 3 + i;
            pts[3 * q] = x * (2.0 + 0.5 * cphi);
            pts[3 * q + 1] = y * (2.0 + 0.5 * cphi);
            pts[3 * q + 2] = 0.5 * sphi;
            w[q] = QW[i] * QW[j];
        }
}

static double sphere_dist(const double *x) {
    return fabs(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1.0);
}
static double torus_dist(const double *x) {
    return fabs(hypot(hypot(x[0], x[1]) - 2.0, x[2]) - 0.5);
}

/* One closed rational model at one setting: bound/tol, oracle deviation <= bound, exact
 * distances <= bound, closed manifold of the given Euler characteristic after identifying
 * equal positions (zero cracks). */
static void exact_model(const char *name, const cj_patch *pp, size_t np, exact_dist_fn exact,
                        long euler, double tol, int uniform, int L) {
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    cj_tess_options opt = {tol, uniform, 0, 0};
    cj_tess_report rep;
    if (cj_tessellate_patches(pp, np, &opt, mesh, &rep) != CJ_OK)
        fail_msg("%s tol %g uniform %d: %s", name, tol, uniform, cj_last_error());
    const rat_stats rs = rational_deviation(mesh, pp, L, 4.0, exact);
    if (!(rep.bound < INFINITY) || (!uniform && rep.bound > tol) || rs.dev > rep.bound ||
        rs.mesh_exact > rep.bound || rs.tri_dist > rep.bound || rs.surf_exact > 1e-14)
        fail_msg("%s tol %g uniform %d: bound %.6g, deviation %.6g, to triangle %.6g, mesh to "
                 "exact surface %.6g, oracle off the surface by %.3g",
                 name, tol, uniform, rep.bound, rs.dev, rs.tri_dist, rs.mesh_exact, rs.surf_exact);
    cj_mesh_topology t;
    assert_int_equal(cj_mesh_topology_compute(mesh, &t), CJ_OK);
    if (t.boundary_edges || t.nonmanifold_edges || t.misoriented_edges || t.euler != euler)
        fail_msg("%s tol %g uniform %d: %zu boundary, %zu non-manifold, %zu misoriented edges, "
                 "Euler %ld (want %ld)",
                 name, tol, uniform, t.boundary_edges, t.nonmanifold_edges, t.misoriented_edges,
                 t.euler, euler);
    char what[32];
    if (uniform)
        snprintf(what, sizeof what, "uniform K %d", uniform);
    else
        snprintf(what, sizeof what, "tol %g", tol);
    printf("  %-6s %-12s %7zu triangles, bound %.4g, deviation min(|S-L|,|S-Q|) %.4g, surface to "
           "triangle %.4g, mesh to exact surface %.4g (ratio %.2f)\n",
           name, what, rep.triangles, rep.bound, rs.dev, rs.tri_dist, rs.mesh_exact,
           rs.dev / rep.bound);
    cj_mesh_destroy(mesh);
}

static void test_rational_exact(void **state) {
    (void)state;
    double sp[8][27], sw[8][9], tp[16][27], tw[16][9];
    cj_patch sphere[8], torus[16];
    for (int k = 0; k < 8; ++k) {
        sphere_octant(k % 4, k / 4, sp[k], sw[k]);
        sphere[k] = cj_patch_view(2, 2, sp[k], sw[k]);
    }
    for (int k = 0; k < 16; ++k) {
        torus_piece(k % 4, k / 4, tp[k], tw[k]);
        torus[k] = cj_patch_view(2, 2, tp[k], tw[k]);
    }
    /* the nets are exact: the oracle's points lie on the quadric / torus */
    printf("exact rational patches (sphere: 8 biquadratic octants, torus R=2 r=0.5: 16 "
           "biquadratic pieces), closed manifold meshes, every distance <= proven bound:\n");
    const double tols[3] = {1e-2, 1e-3, 3e-4};
    for (int i = 0; i < 3; ++i) {
        exact_model("sphere", sphere, 8, sphere_dist, 2, tols[i], 0, i == 2 ? 2 : 4);
        if (i < 2) exact_model("torus", torus, 16, torus_dist, 0, tols[i], 0, 4);
    }
    exact_model("sphere", sphere, 8, sphere_dist, 2, 0.0, 8, 5);
    exact_model("torus", torus, 16, torus_dist, 0, 0.0, 8, 5);
}

int main(void) {
    seed = cj_test_seed("test_tessellate_rational", 5905);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rational_random),
        cmocka_unit_test(test_rational_exact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
