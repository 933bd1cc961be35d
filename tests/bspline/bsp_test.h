/* Shared helpers of the B-spline tests: a failure counter that names the case, and a seeded
 * generator of random and adversarial B-splines. */
#ifndef CJ_TEST_BSP_TEST_H
#define CJ_TEST_BSP_TEST_H

#include "casteljau/bspline.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int bsp_failures;

#define BSP_CHECK(cond, ...)                                                                       \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++bsp_failures;                                                                        \
            if (bsp_failures <= 20) {                                                              \
                printf("FAIL %s:%d: ", __FILE__, __LINE__);                                        \
                printf(__VA_ARGS__);                                                               \
                printf("\n");                                                                      \
            }                                                                                      \
        }                                                                                          \
    } while (0)

#define BSP_MAXN 96

/* A generated curve owning its arrays. */
typedef struct bsp_case {
    int p, dim, n1, rational;
    double pts[BSP_MAXN * 8], w[BSP_MAXN], knots[BSP_MAXN + 70];
    char what[96];
} bsp_case;

static inline cj_bspline bsp_view(const bsp_case *c) {
    return cj_bspline_view(c->p, c->dim, c->n1, c->pts, c->rational ? c->w : NULL, c->knots);
}

/* Kinds of knot vectors and coordinates the generator draws. */
enum { BSP_KNOTS_RANDOM, BSP_KNOTS_REPEATED, BSP_KNOTS_TINY, BSP_KNOTS_UNIFORM, BSP_KNOTS_KINDS };
enum { BSP_COORDS_UNIT, BSP_COORDS_HUGE, BSP_COORDS_TINY, BSP_COORDS_MIXED, BSP_COORDS_KINDS };

/* Fills c with degree p, n1 points (n1 >= p+1, <= BSP_MAXN), dim, the given kinds. */
static inline void bsp_generate(cj_rng *r, bsp_case *c, int p, int n1, int dim, int rational,
                                int knot_kind, int coord_kind) {
    c->p = p;
    c->n1 = n1;
    c->dim = dim;
    c->rational = rational;
    const int nk = n1 + p + 1;
    const int clamped = cj_rng_int(r, 0, 1);
    double x = cj_rng_range(r, -4.0, 4.0);
    for (int i = 0; i < nk; ++i) {
        double step;
        switch (knot_kind) {
        case BSP_KNOTS_REPEATED:
            step = cj_rng_int(r, 0, 2) == 0 ? cj_rng_range(r, 0.1, 1.0) : 0.0;
            break;
        case BSP_KNOTS_TINY: /* spans of a few units in the last place next to ordinary ones */
            step =
                cj_rng_int(r, 0, 1) ? ldexp(cj_rng_int(r, 1, 8), -50) : cj_rng_range(r, 0.1, 1.0);
            break;
        case BSP_KNOTS_UNIFORM:
            step = 1.0;
            break;
        default:
            step = cj_rng_range(r, 0.0, 1.0);
            break;
        }
        if (i > 0) x += step;
        c->knots[i] = x;
    }
    if (clamped) {
        for (int i = 0; i < p; ++i) c->knots[i] = c->knots[p];
        for (int i = n1 + 1; i < nk; ++i) c->knots[i] = c->knots[n1];
    }
    /* Enforce multiplicity <= p+1 and a non-empty domain. */
    if (!(c->knots[p] < c->knots[n1]))
        for (int i = n1; i < nk; ++i) c->knots[i] = c->knots[p] + 1.0 + (i - n1);
    for (int i = 1; i < nk; ++i) {
        if (c->knots[i] < c->knots[i - 1]) c->knots[i] = c->knots[i - 1];
        if (i > p && c->knots[i] == c->knots[i - p - 1])
            c->knots[i] = nextafter(c->knots[i], INFINITY);
    }
    for (int i = 0; i < n1 * dim; ++i) {
        double v = cj_rng_range(r, -1.0, 1.0);
        switch (coord_kind) {
        case BSP_COORDS_HUGE:
            v *= 0x1p1000;
            break;
        case BSP_COORDS_TINY:
            v *= 0x1p-1060;
            break; /* subnormal territory */
        case BSP_COORDS_MIXED:
            v = ldexp(v, cj_rng_int(r, -200, 200));
            break;
        default:
            break;
        }
        c->pts[i] = v;
    }
    for (int i = 0; i < n1; ++i)
        c->w[i] = rational ? ldexp(cj_rng_range(r, 0.5, 1.0), cj_rng_int(r, -8, 8)) : 1.0;
    snprintf(c->what, sizeof c->what, "p=%d n=%d dim=%d %s knots=%d coords=%d%s", p, n1, dim,
             rational ? "NURBS" : "poly", knot_kind, coord_kind, clamped ? " clamped" : "");
}

/* A parameter in the domain: a knot, an end, or uniform in a random span. */
static inline double bsp_param(cj_rng *r, const bsp_case *c) {
    const double a = c->knots[c->p], b = c->knots[c->n1];
    switch (cj_rng_int(r, 0, 5)) {
    case 0:
        return a;
    case 1:
        return b;
    case 2: {
        const double k = c->knots[cj_rng_int(r, c->p, c->n1)];
        return k;
    }
    default: {
        double t = a + (b - a) * cj_rng_unit(r);
        return t < a ? a : (t > b ? b : t);
    }
    }
}

#endif
