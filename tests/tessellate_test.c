/* Helpers shared by the tessellation test programs (tessellate_test.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/tessellate.h"
#include "tessellate_test.h"

#include <math.h>

double tess_binom(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

/* The smallest K whose uniform K x K tessellation has a proven bound <= tol, and its triangle
 * count. */
int tess_smallest_uniform(const cj_patch *p, size_t np, double tol, size_t *tris) {
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    int K = 1;
    for (;; ++K) {
        assert_true(K <= 400);
        cj_mesh_clear(mesh);
        cj_tess_options opt = {0.0, K, 0, 0};
        cj_tess_report rep;
        assert_int_equal(cj_tessellate_patches(p, np, &opt, mesh, &rep), CJ_OK);
        if (rep.bound <= tol) {
            *tris = rep.triangles;
            break;
        }
    }
    cj_mesh_destroy(mesh);
    return K;
}

void tess_random_point(cj_rng *r, int m, int n, int q, double p[3]) {
    p[0] = (double)(q % (m + 1)) / m + cj_rng_range(r, -0.4, 0.4);
    p[1] = (double)(q / (m + 1)) / n + cj_rng_range(r, -0.4, 0.4);
    p[2] = cj_rng_range(r, -0.8, 0.8);
}

/* Independent evaluation: the Bernstein sum (polynomial or rational). */
void bern_eval(const cj_patch *p, double u, double v, double out[3]) {
    const int m = p->deg_u, n = p->deg_v;
    double bu[CJ_PATCH_MAX_DEGREE + 1], bv[CJ_PATCH_MAX_DEGREE + 1];
    /* B_i^m(u) = C(m,i) u^i (1-u)^(m-i), powers by repeated products */
    double pu[CJ_PATCH_MAX_DEGREE + 1], qu[CJ_PATCH_MAX_DEGREE + 1];
    pu[0] = qu[0] = 1.0;
    for (int i = 1; i <= m; ++i) pu[i] = pu[i - 1] * u, qu[i] = qu[i - 1] * (1 - u);
    for (int i = 0; i <= m; ++i) bu[i] = tess_binom(m, i) * pu[i] * qu[m - i];
    pu[0] = qu[0] = 1.0;
    for (int j = 1; j <= n; ++j) pu[j] = pu[j - 1] * v, qu[j] = qu[j - 1] * (1 - v);
    for (int j = 0; j <= n; ++j) bv[j] = tess_binom(n, j) * pu[j] * qu[n - j];
    double num[3] = {0, 0, 0}, den = 0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const int q = j * (m + 1) + i;
            const double w = bu[i] * bv[j] * (p->weights ? p->weights[q] : 1.0);
            den += w;
            for (int k = 0; k < 3; ++k) num[k] += w * p->pts[3 * q + k];
        }
    for (int k = 0; k < 3; ++k) out[k] = p->weights ? num[k] / den : num[k];
}

/* max over triangles of max over the barycentric lattice (step 1/L) of |S(x) - L(x)|, with
 * S evaluated by the oracle at the interpolated (u,v). Also checks every vertex lies on its
 * patch (within 1e-12 of the size). */
double sample_deviation(const cj_mesh *mesh, const cj_patch *patches, int L, double size) {
    double worst = 0.0;
    for (size_t t = 0; t < mesh->triangle_count; ++t) {
        const cj_patch *p = &patches[mesh->triangle_patch[t]];
        const uint32_t *v = mesh->triangles + 3 * t;
        const double *uv[3], *P[3];
        for (int k = 0; k < 3; ++k) {
            uv[k] = mesh->uvs + 2 * (size_t)v[k];
            P[k] = mesh->positions + 3 * (size_t)v[k];
            double s[3];
            bern_eval(p, uv[k][0], uv[k][1], s);
            for (int c = 0; c < 3; ++c)
                if (fabs(s[c] - P[k][c]) > 1e-12 * size)
                    fail_msg("triangle %zu vertex %d is not on patch %d", t, k,
                             (int)mesh->triangle_patch[t]);
        }
        for (int i = 0; i <= L; ++i)
            for (int j = 0; i + j <= L; ++j) {
                const double a = (double)i / L, b = (double)j / L, c = 1.0 - a - b;
                double s[3], d2 = 0.0;
                bern_eval(p, a * uv[0][0] + b * uv[1][0] + c * uv[2][0],
                          a * uv[0][1] + b * uv[1][1] + c * uv[2][1], s);
                for (int k = 0; k < 3; ++k) {
                    const double x = s[k] - (a * P[0][k] + b * P[1][k] + c * P[2][k]);
                    d2 += x * x;
                }
                worst = fmax(worst, sqrt(d2));
            }
    }
    return worst;
}

int cmp3(const void *a, const void *b) {
    const double *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}
