/* Helpers shared by the tessellation test programs (tessellate_test.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/tessellate.h"
#include "tessellate_test.h"

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
