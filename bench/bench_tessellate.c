/* bench_tessellate: the Utah teapot at tolerances 1e-2, 1e-3, 1e-4 of its size (the diagonal
 * of its control-point box), uniform (the smallest K whose proven bound meets the tolerance)
 * against adaptive: triangle count, proven bound, measured deviation (barycentric lattice of
 * step 1/4 on every triangle), microseconds per patch (best of several runs, without the
 * measurement). Goal to measure against: adaptive needs at most half the triangles of uniform.
 * Usage: bench_tessellate [path/to/teapot.bpt] */
#define _POSIX_C_SOURCE 199309L
#include "casteljau/patchset.h"
#include "casteljau/tessellate.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "bench_clock.h"

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

typedef struct run {
    cj_tess_report rep;
    double us_per_patch;
    double measured;
} run;

static int tessellate(const cj_patchset *set, cj_mesh *mesh, double tol, int uniform, int reps,
                      run *out) {
    double best = 1e300;
    for (int r = 0; r < reps; ++r) {
        cj_mesh_clear(mesh);
        cj_tess_options opt = {tol, uniform, 0, 0};
        const double t0 = (1e6 * cj_bench_wall());
        cj_status st = cj_tessellate_patches(set->patches, set->count, &opt, mesh, &out->rep);
        const double t1 = (1e6 * cj_bench_wall());
        if (st) {
            fprintf(stderr, "bench_tessellate: %s\n", cj_last_error());
            return -1;
        }
        if (t1 - t0 < best) best = t1 - t0;
    }
    out->us_per_patch = best / (double)set->count;
    cj_mesh_clear(mesh);
    cj_tess_options opt = {tol, uniform, 4, 0};
    cj_tess_report rep;
    if (cj_tessellate_patches(set->patches, set->count, &opt, mesh, &rep)) return -1;
    out->measured = rep.measured;
    return 0;
}

/* Proven bound of the uniform K x K tessellation. */
static double uniform_bound(const cj_patchset *set, cj_mesh *mesh, int K) {
    cj_mesh_clear(mesh);
    cj_tess_options opt = {0.0, K, 0, 0};
    cj_tess_report rep;
    if (cj_tessellate_patches(set->patches, set->count, &opt, mesh, &rep)) return -1.0;
    return rep.bound;
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : CJ_TEAPOT_PATH;
    cj_patchset *set;
    if (cj_patchset_load_bpt(path, NULL, &set)) {
        fprintf(stderr, "bench_tessellate: %s\n", cj_last_error());
        return 1;
    }
    double lo[3], hi[3], size;
    cj_patchset_bbox(set, lo, hi, &size);
    cj_mesh *mesh;
    if (cj_mesh_create(NULL, &mesh)) return 1;
    printf("Utah teapot, %zu bicubic patches, size (control box diagonal) %.6g\n", set->count,
           size);
    printf("%-8s %-9s %-9s %10s %12s %12s %10s\n", "tol/size", "method", "grid", "triangles",
           "bound", "measured", "us/patch");
    const double rels[3] = {1e-2, 1e-3, 1e-4};
    for (int t = 0; t < 3; ++t) {
        const double tol = rels[t] * size;
        /* smallest K with bound <= tol: doubling, then bisection */
        int lo_k = 0, hi_k = 1;
        while (uniform_bound(set, mesh, hi_k) > tol) {
            lo_k = hi_k;
            hi_k *= 2;
        }
        while (hi_k - lo_k > 1) {
            const int mid = (lo_k + hi_k) / 2;
            if (uniform_bound(set, mesh, mid) > tol)
                lo_k = mid;
            else
                hi_k = mid;
        }
        const int reps = t == 2 ? 3 : 10;
        run u, a;
        if (tessellate(set, mesh, tol, hi_k, reps, &u) || tessellate(set, mesh, tol, 0, reps, &a))
            return 1;
        char grid[32];
        snprintf(grid, sizeof grid, "K=%d", hi_k);
        printf("%-8.0e %-9s %-9s %10zu %12.4e %12.4e %10.1f\n", rels[t], "uniform", grid,
               u.rep.triangles, u.rep.bound, u.measured, u.us_per_patch);
        snprintf(grid, sizeof grid, "<=%dx%d", a.rep.max_nu, a.rep.max_nv);
        printf("%-8.0e %-9s %-9s %10zu %12.4e %12.4e %10.1f\n", rels[t], "adaptive", grid,
               a.rep.triangles, a.rep.bound, a.measured, a.us_per_patch);
        printf("         adaptive/uniform triangles: %.3f (goal <= 0.5)\n",
               (double)a.rep.triangles / (double)u.rep.triangles);
    }
    cj_mesh_destroy(mesh);
    cj_patchset_destroy(set);
    return 0;
}
