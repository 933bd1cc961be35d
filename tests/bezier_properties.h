/* Shared by the files of test_bezier_properties (test_bezier_properties.c holds the helpers,
 * the basic properties and main; bezier_properties_geometry.c the bounding box, arc length and
 * frames): the random curves, the evaluation helpers and the failure message. */
#ifndef CJ_TEST_BEZIER_PROPERTIES_H
#define CJ_TEST_BEZIER_PROPERTIES_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "rng.h"

#include <inttypes.h>
#include <stdint.h>

#define CASES  1000
#define MAXDEG 20
#define MAXPTS (MAXDEG + 8)
#define U      0x1p-53

extern uint64_t g_seed; /* the suite's seed (printed; CJ_SEED=<n> replays) */

#define PFAIL(prop, cs, fmt, ...)                                                                  \
    fail_msg("property '%s' failed: seed %" PRIu64 " case %d: " fmt, prop, g_seed, cs, __VA_ARGS__)

typedef struct rcurve {
    int n, d;
    double p[MAXPTS * 3];
    cj_bezier c;
    double mag; /* max |coordinate| */
} rcurve;

void rng_for(cj_rng *r, int property);
/* Random curve: degree 1..20, dim 2 or 3 (or forced), coordinates in [-s, s] with s a random
 * power of ten between 1e-3 and 1e3. */
void random_curve(cj_rng *r, rcurve *rc, int dim);
void ev(const cj_bezier *c, double t, double *out);
void bnd(const cj_bezier *c, double t, double *out);
double maxabs(const double *v, int m);
/* A dyadic parameter k/2^10 in [0,1]: products and 1-t are then exact. */
double dyadic(cj_rng *r);

void prop_bbox(void **state);
void prop_arclength(void **state);
void prop_frames(void **state);

#endif
