/* Random tensor-product B-spline and NURBS surfaces for the surface tests (test_bspline_surface,
 * test_bspline_surface_ops) and their exact values: the generator draws degrees 1..4 and
 * 2..BSP_SURF_MAXN control points a direction from a seeded rng, the caller's knot rule spaces
 * the knots, and the gap to the MPFR oracle (products of Cox–de Boor basis functions at
 * CJ_ORACLE_BSP_PREC bits) measures a computed point. */
#ifndef CJ_TEST_BSP_SURF_H
#define CJ_TEST_BSP_SURF_H

#include "casteljau/bspline_surface.h"
#include "rng.h"

#include <mpfr.h>

enum {
    BSP_SURF_MAXN = 12, /* control points a direction that bsp_surf_generate draws */
    BSP_SURF_CAP = 64   /* room a direction, for the results of the operations under test */
};

typedef struct bsp_surf {
    int p, q, nu, nv, rational;
    double pts[3 * BSP_SURF_CAP * BSP_SURF_CAP], w[BSP_SURF_CAP * BSP_SURF_CAP];
    double ku[BSP_SURF_CAP + 40], kv[BSP_SURF_CAP + 40];
    char what[80]; /* "(p,q) nu x nv NURBS|poly", for messages */
} bsp_surf;

/* The library's view of s (weights only when s->rational). */
cj_bspline_surface bsp_surf_view(const bsp_surf *s);

/* n + p + 1 knots of degree p into k, clamped (p + 1 equal end knots) or not. */
typedef void (*bsp_knot_rule)(cj_rng *r, double *k, int n, int p, int clamped);

/* A random surface: rep % 2 makes it rational, rep % 3 and rep % 4 clamp u and v. */
void bsp_surf_generate(cj_rng *r, bsp_surf *s, int rep, bsp_knot_rule knots);

/* |S_k(u, v) − x_k| per coordinate, S exact, rounded up, into gaps (may be NULL); returns the
 * largest. (u, v) is in the domain: exact parameters (mpfr values), or doubles. */
double bsp_surf_gap_exact(const bsp_surf *s, const mpfr_t u, const mpfr_t v, const double *x,
                          double *gaps);
double bsp_surf_gap(const bsp_surf *s, double u, double v, const double *x, double *gaps);

#endif
