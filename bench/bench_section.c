/* bench_section (issue 23): model sections as joined cubic curves (the teapot), stroke outlines
 * of cubics, and the certified nearest point on an equidistant patch. Thread CPU, medians of
 * repetitions. */
#include "bench_clock.h"

#include "casteljau/offset.h"
#include "casteljau/patch_nearest.h"
#include "casteljau/patch_section.h"
#include "casteljau/patchset.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static double section_polylines(const cj_patchset *set, double tol, long *pts) {
    const double n[3] = {0, 0, 1};
    double t0 = cj_bench_thread_cpu();
    *pts = 0;
    for (size_t i = 0; i < set->count; ++i) {
        cj_patch_section s;
        if (cj_patch_section_plane(&set->patches[i], n, 1.5, 0.25 * tol, &s) == CJ_OK)
            *pts += s.npts;
        cj_patch_section_free(&s);
    }
    return cj_bench_thread_cpu() - t0;
}

int main(void) {
    cj_patchset *set = NULL;
    if (cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set) != CJ_OK) {
        fprintf(stderr, "bench_section: %s\n", cj_last_error());
        return 1;
    }
    const double n[3] = {0, 0, 1}, tols[3] = {8e-3, 2e-3, 5e-4};
    for (int k = 0; k < 3; ++k) {
        double t[5], tp[5];
        cj_section_curves s = {0};
        long pts = 0;
        for (int r = 0; r < 5; ++r) {
            cj_section_curves_free(&s);
            double t0 = cj_bench_thread_cpu();
            if (cj_patches_section_curves(set->patches, set->count, n, 1.5, tols[k], &s) != CJ_OK) {
                fprintf(stderr, "bench_section: %s\n", cj_last_error());
                return 1;
            }
            t[r] = cj_bench_thread_cpu() - t0;
            tp[r] = section_polylines(set, tols[k], &pts);
        }
        printf("teapot z = 1.5, tol %g: %.1f ms (polylines alone %.1f ms), %d curves, %d cubic "
               "pieces for %d polyline vertices, deviation %.3g\n",
               tols[k], 1e3 * cj_bench_median(t, 5), 1e3 * cj_bench_median(tp, 5), s.nchains,
               s.npieces, s.npts, s.deviation);
        cj_section_curves_free(&s);
    }
    cj_patchset_destroy(set);

    /* outlines of random cubics in the unit square, half-width 0.05, tol 1e-4 */
    enum { NC = 200, CAP = 4096 };
    static double buf[8 * CAP];
    srand(7);
    double tr[NC], to[NC], pieces = 0;
    int ok = 0;
    for (int i = 0; i < NC; ++i) {
        double P[8];
        for (int k = 0; k < 8; ++k) P[k] = rand() / (double)RAND_MAX;
        cj_bezier2 c = cj_bezier2_view(3, P, NULL);
        int np = 0, cusps;
        double dev, t0 = cj_bench_thread_cpu();
        cj_status st = cj_offset_outline(&c, 0.05, 1e-4, CJ_OFFSET_CAP_ROUND, buf, NULL, CAP, &np,
                                         &dev, &cusps);
        to[ok] = cj_bench_thread_cpu() - t0;
        t0 = cj_bench_thread_cpu();
        int n1 = 0, n2 = 0;
        cj_status s1 = cj_offset_curve(&c, 0.05, 1e-4, buf, NULL, CAP, &n1, &dev, NULL);
        cj_status s2 = cj_offset_curve(&c, -0.05, 1e-4, buf, NULL, CAP, &n2, &dev, NULL);
        tr[ok] = cj_bench_thread_cpu() - t0;
        if (st == CJ_OK && s1 == CJ_OK && s2 == CJ_OK) pieces += np, ++ok;
    }
    printf("outline, round caps, w 0.05, tol 1e-4: %.3f ms per cubic (both raw offsets %.3f ms), "
           "%.1f pieces; %d of %d cubics\n",
           1e3 * cj_bench_median(to, (size_t)ok), 1e3 * cj_bench_median(tr, (size_t)ok),
           pieces / ok, ok, NC);

    /* the rational sphere octant seen from its centre: every point at distance 1 */
    const double c = sqrt(0.5), a[3][2] = {{1, 0}, {1, 1}, {0, 1}}, wa[3] = {1, c, 1};
    double sp[27], sw[9];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            int idx = j * 3 + i;
            sp[3 * idx] = a[j][0] * a[i][0];
            sp[3 * idx + 1] = a[j][0] * a[i][1];
            sp[3 * idx + 2] = a[j][1];
            sw[idx] = wa[i] * wa[j];
        }
    cj_patch S = cj_patch_view(2, 2, sp, sw);
    double tn[101];
    cj_patch_nearest_result r;
    for (int k = 0; k < 101; ++k) {
        double t0 = cj_bench_thread_cpu();
        cj_patch_nearest(&S, (double[]){0, 0, 0}, 1e-9, &r);
        tn[k] = cj_bench_thread_cpu() - t0;
    }
    printf("nearest on the sphere octant from its centre, tol 1e-9: %.1f us, %ld sub-patches, "
           "distance %.17g, lower %.17g\n",
           1e6 * cj_bench_median(tn, 101), r.pieces, r.distance, r.lower);
    return 0;
}
