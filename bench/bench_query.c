/* bench_query: the certified queries of issue 23 on random cubics in the unit square (seeded):
 * curve–curve intersection per pair, nearest point per query, offset per curve at a tolerance,
 * each the median over 7 repetitions of a batch, in thread CPU time. The same queries against
 * OpenCASCADE and kurbo in one process: bench_query_occt (docs/queries.md). */
#include "bench_clock.h"

#include "casteljau/intersect.h"
#include "casteljau/nearest.h"
#include "casteljau/offset.h"

#include <stdint.h>
#include <stdio.h>

#define NCURVES 2000
#define REPS    7

static uint64_t state = 0x9e3779b97f4a7c15u;
static double unit(void) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (double)(state >> 11) * 0x1p-53;
}

static double curves[NCURVES][8];
static cj_isect res[64];
static double pts[8 * 4096];

int main(void) {
    for (int i = 0; i < NCURVES; ++i)
        for (int k = 0; k < 8; ++k) curves[i][k] = unit();
    double times[REPS];
    long found = 0;
    for (int r = 0; r < REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        found = 0;
        for (int i = 0; i + 1 < NCURVES; i += 2) {
            cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL),
                       b = cj_bezier2_view(3, curves[i + 1], NULL);
            int n = 0;
            if (cj_intersect_curves(&a, &b, 1e-9, res, 64, &n) == CJ_OK) found += n;
        }
        times[r] = (cj_bench_thread_cpu() - t0) / (NCURVES / 2);
    }
    printf("intersect cubic pair (tol 1e-9, enclosures ~1e-15): %8.2f us per pair, %.2f "
           "intersections per pair\n",
           1e6 * cj_bench_median(times, REPS), (double)found / (NCURVES / 2));
    long pieces = 0;
    for (int r = 0; r < REPS; ++r) {
        double t0 = cj_bench_thread_cpu();
        pieces = 0;
        for (int i = 0; i < NCURVES; ++i) {
            cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL);
            double q[2] = {unit(), unit()};
            cj_nearest nr;
            if (cj_nearest_curve(&a, q, 1e-10, &nr) == CJ_OK) pieces += nr.pieces;
        }
        times[r] = (cj_bench_thread_cpu() - t0) / NCURVES;
    }
    printf("nearest point on a cubic (tol 1e-10, certified):    %8.2f us per query, %.1f pieces "
           "per query\n",
           1e6 * cj_bench_median(times, REPS), (double)pieces / NCURVES);
    int noff = 200;
    long npieces = 0, done = 0;
    for (int r = 0; r < 3; ++r) {
        double t0 = cj_bench_thread_cpu();
        npieces = done = 0;
        for (int i = 0; i < noff; ++i) {
            cj_bezier2 a = cj_bezier2_view(3, curves[i], NULL);
            int np = 0;
            double dev;
            if (cj_offset_curve(&a, 0.05, 1e-4, pts, NULL, 4096, &np, &dev, NULL) == CJ_OK)
                npieces += np, ++done;
        }
        times[r] = (cj_bench_thread_cpu() - t0) / noff;
    }
    printf("offset a cubic by 0.05 (tol 1e-4, proven):          %8.2f ms per curve, %.1f pieces "
           "per curve (%ld of %d offset; the others have a vanishing derivative)\n",
           1e3 * cj_bench_median(times, 3), done ? (double)npieces / done : 0.0, done, noff);
    return 0;
}
