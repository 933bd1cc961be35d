/* The surface tests' generator and oracle gap (bsp_surf.h). */
#include "bsp_surf.h"

#include "oracle_bspline.h"

#include <math.h>
#include <stdio.h>

cj_bspline_surface bsp_surf_view(const bsp_surf *s) {
    cj_bspline_surface v = {s->p,  s->q, s->nu, s->nv, s->pts, s->rational ? s->w : NULL,
                            s->ku, s->kv};
    return v;
}

void bsp_surf_generate(cj_rng *r, bsp_surf *s, int rep, bsp_knot_rule knots) {
    s->p = cj_rng_int(r, 1, 4);
    s->q = cj_rng_int(r, 1, 4);
    s->nu = s->p + 1 + cj_rng_int(r, 0, BSP_SURF_MAXN - 1 - s->p);
    s->nv = s->q + 1 + cj_rng_int(r, 0, BSP_SURF_MAXN - 1 - s->q);
    s->rational = rep % 2;
    knots(r, s->ku, s->nu, s->p, rep % 3 != 0);
    knots(r, s->kv, s->nv, s->q, rep % 4 != 0);
    for (int i = 0; i < 3 * s->nu * s->nv; ++i) s->pts[i] = cj_rng_range(r, -1, 1);
    for (int i = 0; i < s->nu * s->nv; ++i) s->w[i] = s->rational ? cj_rng_range(r, 0.3, 3) : 1.0;
    snprintf(s->what, sizeof s->what, "(%d,%d) %dx%d %s", s->p, s->q, s->nu, s->nv,
             s->rational ? "NURBS" : "poly");
}

double bsp_surf_gap_exact(const bsp_surf *s, const mpfr_t u, const mpfr_t v, const double *x,
                          double *gaps) {
    mpfr_t Nu[BSP_SURF_CAP], Nv[BSP_SURF_CAP], num[3], den, t, z;
    for (int i = 0; i < s->nu; ++i) mpfr_init2(Nu[i], 64);
    for (int j = 0; j < s->nv; ++j) mpfr_init2(Nv[j], 64);
    mpfr_inits2(CJ_ORACLE_BSP_PREC, num[0], num[1], num[2], den, t, z, (mpfr_ptr)0);
    cj_obsp_basis(s->ku, s->nu, s->p, u, Nu);
    cj_obsp_basis(s->kv, s->nv, s->q, v, Nv);
    for (int c = 0; c < 3; ++c) mpfr_set_ui(num[c], 0, MPFR_RNDN);
    mpfr_set_ui(den, 0, MPFR_RNDN);
    for (int j = 0; j < s->nv; ++j)
        for (int i = 0; i < s->nu; ++i) {
            mpfr_mul(t, Nu[i], Nv[j], MPFR_RNDN);
            mpfr_mul_d(t, t, s->rational ? s->w[j * s->nu + i] : 1.0, MPFR_RNDN);
            mpfr_add(den, den, t, MPFR_RNDN);
            for (int c = 0; c < 3; ++c) {
                mpfr_mul_d(z, t, s->pts[3 * (j * s->nu + i) + c], MPFR_RNDN);
                mpfr_add(num[c], num[c], z, MPFR_RNDN);
            }
        }
    double g = 0;
    for (int c = 0; c < 3; ++c) {
        mpfr_div(num[c], num[c], den, MPFR_RNDN);
        mpfr_sub_d(num[c], num[c], x[c], MPFR_RNDN);
        const double gc = fabs(mpfr_get_d(num[c], MPFR_RNDU));
        if (gaps) gaps[c] = gc;
        g = fmax(g, gc);
    }
    for (int i = 0; i < s->nu; ++i) mpfr_clear(Nu[i]);
    for (int j = 0; j < s->nv; ++j) mpfr_clear(Nv[j]);
    mpfr_clears(num[0], num[1], num[2], den, t, z, (mpfr_ptr)0);
    return g;
}

double bsp_surf_gap(const bsp_surf *s, double u, double v, const double *x, double *gaps) {
    mpfr_t mu, mv;
    mpfr_inits2(64, mu, mv, (mpfr_ptr)0);
    mpfr_set_d(mu, u, MPFR_RNDN);
    mpfr_set_d(mv, v, MPFR_RNDN);
    const double g = bsp_surf_gap_exact(s, mu, mv, x, gaps);
    mpfr_clears(mu, mv, (mpfr_ptr)0);
    return g;
}
