/* test_surfaces' catalogue of analytic test surfaces (surfaces_catalogue.c): the surfaces with
 * their implicit forms where they have one, the profiles they are built from, the seed, and the
 * sampling and on-surface helpers the checks in test_surfaces.c share. */
#ifndef CJ_TEST_SURFACES_CATALOGUE_H
#define CJ_TEST_SURFACES_CATALOGUE_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/analytic.h"
#include "casteljau/bezier.h"
#include "casteljau/quadric.h"
#include "casteljau/rational.h"
#include "casteljau/surface.h"
#include "casteljau/transform.h"
#include "rng.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <stdint.h>

extern uint64_t seed;

typedef struct circle2 {
    double cx, cy, r;
} circle2;

typedef struct tcase {
    const char *name;
    cj_param_surface ps;
    cj_implicit_surface is; /* eval == NULL: no implicit form */
    int has_implicit;
    cj_vec3 center; /* for the outward test on closed surfaces */
    int outward;    /* 1: n.(p - center) > 0 expected (star-shaped about center) */
} tcase;

extern cj_quadric q_ell, q_h1, q_h2u, q_h2l, q_cone, q_cone_neg, q_par, q_hp, q_sph;
extern cj_torus torus, torus_tilted;
extern cj_bilinear bil, bil_tri;
extern cj_revolution rev_sphere, rev_torus, rev_bez;
extern circle2 semi;
extern cj_curve2 semi_curve, dir_curve;

#define NCASES 24
extern tcase cases[NCASES];
extern int ncases;

/* Fills the catalogue (cmocka group setup) and draws the seed. */
int setup(void **state);
double rnd(cj_rng *r, double a, double b);
/* A random parameter pair inside the domain shrunk by `margin` (relative). A quarter of the
 * draws are snapped to a domain edge (margin permitting), where poles live. */
void draw_uv(cj_rng *r, const cj_param_surface *s, double margin, double *u, double *v);
/* |f(S(u,v))| within the tolerance explained in surfaces_catalogue.c; rel = |f| / tol. */
int on_surface(const tcase *t, cj_vec3 x, double *rel);

#endif
