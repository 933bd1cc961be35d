/* bench_geometry: cost of the Bézier geometry operations by degree (microseconds per call,
 * median of 5 repetitions over a batch of random 2D curves with coordinates in [-1,1]), and of
 * transforming control-point arrays. Prints tables; asserts nothing. */
#define _POSIX_C_SOURCE 199309L
#include "casteljau/bezier.h"
#include "casteljau/transform.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "bench_clock.h"

#define BATCH 64
#define REPS  5

static uint64_t rng_state = 0x2545F4914F6CDD1Dull;
static double urand(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * 0x1p-53 * 2.0 - 1.0;
}

static double pts[BATCH][(CJ_BEZIER_MAX_DEGREE + 1) * 2];
static double out[(CJ_BEZIER_MAX_DEGREE + 2) * 2];
static volatile double sink;

enum op { OP_BBOX, OP_HULL, OP_LEN6, OP_LEN10, OP_TANGENT, OP_CURV, OP_SUB, OP_ELEV, OP_COUNT };
static const char *names[OP_COUNT] = {"bbox",    "hull2d",    "arclen 1e-6", "arclen 1e-10",
                                      "tangent", "curvature", "subcurve",    "elevate+1"};

static double run(enum op o, int n, double *extra) {
    double times[REPS];
    double esum = 0;
    const int batch = n >= 100 ? BATCH / 8 : BATCH; /* keep the whole run to a minute or so */
    for (int r = 0; r < REPS; ++r) {
        const double t0 = cj_bench_wall();
        for (int b = 0; b < batch; ++b) {
            cj_bezier c = cj_bezier_view(n, 2, pts[b]);
            double lo[2], hi[2], len, err, v[2], k;
            int idx[CJ_BEZIER_MAX_DEGREE + 1], cnt;
            switch (o) {
            case OP_BBOX:
                cj_bezier_bbox(&c, lo, hi);
                sink = hi[0];
                break;
            case OP_HULL:
                cj_bezier_hull2d(&c, idx, &cnt);
                sink = cnt;
                break;
            case OP_LEN6:
            case OP_LEN10:
                cj_bezier_arclength(&c, 0, 1, o == OP_LEN6 ? 1e-6 : 1e-10, &len, &err);
                sink = len;
                esum += err;
                break;
            case OP_TANGENT:
                cj_bezier_tangent(&c, 0.3, v, NULL);
                sink = v[0];
                break;
            case OP_CURV:
                cj_bezier_curvature(&c, 0.3, &k);
                sink = k;
                break;
            case OP_SUB:
                cj_bezier_subcurve(&c, 0.2, 0.7, out);
                sink = out[0];
                break;
            case OP_ELEV:
            default:
                if (n < CJ_BEZIER_MAX_DEGREE) cj_bezier_elevate(&c, 1, out);
                sink = out[0];
                break;
            }
        }
        times[r] = (cj_bench_wall() - t0) / batch * 1e6;
    }
    qsort(times, REPS, sizeof times[0], cj_bench_cmp_double);
    if (extra) *extra = esum / (REPS * batch);
    return times[REPS / 2];
}

int main(void) {
    for (int b = 0; b < BATCH; ++b)
        for (int i = 0; i < (CJ_BEZIER_MAX_DEGREE + 1) * 2; ++i) pts[b][i] = urand();
    const int degrees[] = {3, 5, 10, 20, 50, 100, 255};
    const int nd = (int)(sizeof degrees / sizeof degrees[0]);
    printf("bench_geometry: microseconds per call (median of %d runs over %d random 2D curves, "
           "%d from degree 100)\n",
           REPS, BATCH, BATCH / 8);
    printf("%-14s", "degree");
    for (int j = 0; j < nd; ++j) printf("%10d", degrees[j]);
    printf("\n");
    for (int o = 0; o < OP_COUNT; ++o) {
        printf("%-14s", names[o]);
        for (int j = 0; j < nd; ++j) {
            if (o == OP_ELEV && degrees[j] >= CJ_BEZIER_MAX_DEGREE)
                printf("%10s", "n/a"); /* already at the degree limit */
            else
                printf("%10.2f", run((enum op)o, degrees[j], NULL));
        }
        printf("\n");
    }
    printf("%-14s", "  mean est.");
    for (int j = 0; j < nd; ++j) {
        double e;
        run(OP_LEN10, degrees[j], &e);
        printf("%10.1e", e);
    }
    printf("   (arc length error estimate reached at tol 1e-10)\n");

    /* Transforms: points per microsecond through cj_xform3_apply_points. */
    enum { NP = 1 << 16 };
    static double cloud[NP * 3];
    for (int i = 0; i < NP * 3; ++i) cloud[i] = urand();
    cj_xform3 m;
    cj_xform3_rotate_axis(cj_v3(1, 2, 3), 0.7, &m);
    cj_xform3 t = cj_xform3_translate(1, 2, 3);
    m = cj_xform3_compose(&t, &m);
    double times[REPS];
    for (int r = 0; r < REPS; ++r) {
        const double t0 = cj_bench_wall();
        cj_xform3_apply_points(&m, cloud, NP, cloud);
        times[r] = cj_bench_wall() - t0;
    }
    qsort(times, REPS, sizeof times[0], cj_bench_cmp_double);
    printf("cj_xform3_apply_points: %.1f million points/s (in place, %d points, validated)\n",
           NP / times[REPS / 2] * 1e-6, NP);
    return 0;
}
