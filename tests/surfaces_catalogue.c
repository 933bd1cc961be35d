/* test_surfaces, the catalogue (surfaces_catalogue.h): the analytic test surfaces built in the
 * group setup, with the exact circle profiles they are made from (independent of the Bézier
 * code), and the sampling and on-surface helpers. */
#include "surfaces_catalogue.h"

static const double PI = 3.14159265358979323846;

uint64_t seed;

/* ---- exact circle profiles (independent of the Bézier code) ---------------------------- */

static cj_status circle_cb(const void *data, double t, cj_vec2 d[3]) {
    const circle2 *c = data;
    double ct = cos(t), st = sin(t);
    d[0] = cj_v2(c->cx + c->r * ct, c->cy + c->r * st);
    d[1] = cj_v2(-c->r * st, c->r * ct);
    d[2] = cj_v2(-c->r * ct, -c->r * st);
    return CJ_OK;
}

/* ---- the catalogue of test surfaces ----------------------------------------------------- */

cj_quadric q_ell, q_h1, q_h2u, q_h2l, q_cone, q_cone_neg, q_par, q_hp, q_sph;
cj_torus torus, torus_tilted;
static cj_cylinder cyl;
static cj_planar_patch ppatch;
cj_bilinear bil, bil_tri;
static cj_gen_cylinder gcyl_circle, gcyl_bez;
cj_revolution rev_sphere, rev_torus, rev_bez;
circle2 semi = {0, 0, 1.5}, ring = {3.0, 0.0, 1.0}, dir_circle = {0, 0, 0.8};
cj_curve2 semi_curve, ring_curve, dir_curve, bez_profile_curve, bez_dir_curve;
static const double bez_profile_pts[] = {0, -1, 1.3, -1, 1.3, 1, 0, 1};
static const double bez_dir_pts[] = {0, 0, 1, 2, 3, -1, 4, 1};
static cj_bezier bez_profile, bez_dir;
static cj_cylinder cyl_for_gcyl;
static double arc_pts[6], arc_w[3];
static cj_rbezier arc;
static cj_curve2 arc_curve;
static cj_revolution rev_hemi;

tcase cases[NCASES];
int ncases;

static void add_case(const char *name, cj_param_surface ps, const cj_implicit_surface *is,
                     cj_vec3 center, int outward) {
    tcase *t = &cases[ncases++];
    t->name = name;
    t->ps = ps;
    t->has_implicit = is != NULL;
    if (is) t->is = *is;
    t->center = center;
    t->outward = outward;
}

int setup(void **state) {
    (void)state;
    cj_vec3 o = cj_v3(0, 0, 0);
    cj_param_surface ps;
    cj_implicit_surface is;
    ncases = 0;
    assert_int_equal(cj_quadric_ellipsoid(&q_ell, 2.0, 1.0, 0.5), CJ_OK);
    assert_int_equal(cj_quadric_ellipsoid(&q_sph, 1.5, 1.5, 1.5), CJ_OK);
    assert_int_equal(cj_quadric_hyperboloid1(&q_h1, 1.0, 2.0, 0.7, -1.5, 1.2), CJ_OK);
    assert_int_equal(cj_quadric_hyperboloid2(&q_h2u, 1.0, 0.5, 2.0, 0, 1.5), CJ_OK);
    assert_int_equal(cj_quadric_hyperboloid2(&q_h2l, 1.0, 0.5, 2.0, 1, 1.5), CJ_OK);
    assert_int_equal(cj_quadric_cone(&q_cone, 1.0, 2.0, 1.5, 0.0, 2.0), CJ_OK);
    assert_int_equal(cj_quadric_cone(&q_cone_neg, 1.0, 2.0, 1.5, -2.0, 0.0), CJ_OK);
    assert_int_equal(cj_quadric_paraboloid(&q_par, 1.0, 3.0, 1.5), CJ_OK);
    assert_int_equal(cj_quadric_hyperbolic_paraboloid(&q_hp, 2.0, 1.0, -1, 1.5, -2, 1), CJ_OK);
    const cj_quadric *qs[] = {&q_ell, &q_h1, &q_h2u, &q_h2l, &q_cone, &q_cone_neg, &q_par, &q_hp};
    const char *qn[] = {"ellipsoid", "hyperboloid1", "hyperboloid2 upper", "hyperboloid2 lower",
                        "cone v>=0", "cone v<=0",    "paraboloid",         "hyperbolic paraboloid"};
    for (int i = 0; i < 8; ++i) {
        cj_quadric_surface(qs[i], &ps);
        cj_quadric_implicit(qs[i], &is);
        add_case(qn[i], ps, &is, o, i == 0);
    }
    assert_int_equal(cj_torus_init(&torus, o, cj_v3(0, 0, 1), 3.0, 1.0), CJ_OK);
    cj_torus_surface(&torus, &ps);
    cj_torus_implicit(&torus, &is);
    add_case("torus", ps, &is, o, 0);
    assert_int_equal(cj_torus_init(&torus_tilted, cj_v3(1, -2, 0.5), cj_v3(1, 2, -0.5), 2.0, 0.5),
                     CJ_OK);
    cj_torus_surface(&torus_tilted, &ps);
    cj_torus_implicit(&torus_tilted, &is);
    add_case("tilted torus", ps, &is, o, 0);
    assert_int_equal(cj_cylinder_init(&cyl, cj_v3(1, 1, 0), cj_v3(0.3, -1, 2), 0.75, -1, 2), CJ_OK);
    cj_cylinder_surface(&cyl, &ps);
    cj_cylinder_implicit(&cyl, &is);
    add_case("cylinder", ps, &is, o, 0);
    assert_int_equal(
        cj_planar_patch_init(&ppatch, cj_v3(1, 2, 3), cj_v3(1, 0.5, 0), cj_v3(-0.2, 1, 0.7)),
        CJ_OK);
    cj_planar_patch_surface(&ppatch, &ps);
    cj_planar_patch_implicit(&ppatch, &is);
    add_case("planar patch", ps, &is, o, 0);
    assert_int_equal(
        cj_bilinear_init(&bil, cj_v3(0, 0, 0), cj_v3(2, 0, 1), cj_v3(0, 1, 1), cj_v3(2, 2, -1)),
        CJ_OK);
    cj_bilinear_surface(&bil, &ps);
    add_case("bilinear patch", ps, NULL, o, 0);
    /* Sphere of radius 1.5 as a surface of revolution of an exact half circle. */
    semi_curve = (cj_curve2){circle_cb, &semi, -0.5 * PI, 0.5 * PI, 0};
    assert_int_equal(cj_revolution_init(&rev_sphere, &semi_curve, o, cj_v3(0, 0, 1)), CJ_OK);
    cj_revolution_surface(&rev_sphere, &ps);
    cj_quadric_implicit(&q_sph, &is);
    add_case("sphere of revolution", ps, &is, o, 1);
    /* Torus R = 3, rho = 1 as a surface of revolution of a full circle. */
    ring_curve = (cj_curve2){circle_cb, &ring, 0.0, 2.0 * PI, 1};
    assert_int_equal(cj_revolution_init(&rev_torus, &ring_curve, o, cj_v3(0, 0, 1)), CJ_OK);
    cj_revolution_surface(&rev_torus, &ps);
    cj_torus_implicit(&torus, &is);
    add_case("torus of revolution", ps, &is, o, 0);
    /* Bézier profile from the south pole to the north pole. */
    bez_profile = cj_bezier_view(3, 2, bez_profile_pts);
    assert_int_equal(cj_curve2_from_bezier(&bez_profile, &bez_profile_curve), CJ_OK);
    assert_int_equal(cj_revolution_init(&rev_bez, &bez_profile_curve, o, cj_v3(0, 0, 1)), CJ_OK);
    cj_revolution_surface(&rev_bez, &ps);
    add_case("Bezier revolution", ps, NULL, o, 1);
    /* A general cylinder on an exact circle equals a right circular cylinder. */
    dir_curve = (cj_curve2){circle_cb, &dir_circle, 0.0, 2.0 * PI, 1};
    cj_vec3 e1, e2, ax = cj_v3(0, 0.6, 0.8);
    cj_frame_from_axis(ax, &e1, &e2);
    assert_int_equal(
        cj_gen_cylinder_init(&gcyl_circle, &dir_curve, cj_v3(0, 1, 0), e1, e2, ax, -1.0, 1.0),
        CJ_OK);
    assert_int_equal(cj_cylinder_init(&cyl_for_gcyl, cj_v3(0, 1, 0), ax, 0.8, -1.0, 1.0), CJ_OK);
    cj_gen_cylinder_surface(&gcyl_circle, &ps);
    cj_cylinder_implicit(&cyl_for_gcyl, &is);
    add_case("general cylinder (circle)", ps, &is, o, 0);
    bez_dir = cj_bezier_view(3, 2, bez_dir_pts);
    assert_int_equal(cj_curve2_from_bezier(&bez_dir, &bez_dir_curve), CJ_OK);
    assert_int_equal(cj_gen_cylinder_init(&gcyl_bez, &bez_dir_curve, cj_v3(0, 0, 0), cj_v3(1, 0, 0),
                                          cj_v3(0.2, 1, 0), cj_v3(0.3, 0.1, 1.0), 0.0, 2.0),
                     CJ_OK);
    cj_gen_cylinder_surface(&gcyl_bez, &ps);
    add_case("general cylinder (Bezier)", ps, NULL, o, 0);
    /* Upper hemisphere of radius 1.5: revolution of an exact rational quarter circle from
     * (r, z) = (1.5, 0) to (0, 1.5). */
    assert_int_equal(cj_rbezier_ellipse_arc(0, 0, 1.5, 1.5, 0, 0, 0.5 * PI, arc_pts, arc_w), CJ_OK);
    arc = cj_rbezier_view(2, 2, arc_pts, arc_w);
    assert_int_equal(cj_curve2_from_rbezier(&arc, &arc_curve), CJ_OK);
    assert_int_equal(cj_revolution_init(&rev_hemi, &arc_curve, o, cj_v3(0, 0, 1)), CJ_OK);
    assert_true(rev_hemi.flags == (CJ_SURF_PERIODIC_U | CJ_SURF_COLLAPSED_V1));
    cj_revolution_surface(&rev_hemi, &ps);
    cj_quadric_implicit(&q_sph, &is);
    add_case("rational hemisphere of revolution", ps, &is, o, 1);
    seed = cj_test_seed("test_surfaces", 20261121);
    return 0;
}

double rnd(cj_rng *r, double a, double b) {
    return cj_rng_range(r, a, b);
}

/* A random parameter pair inside the domain shrunk by `margin` (relative). A quarter of the
 * draws are snapped to a domain edge (margin permitting), where poles live. */
void draw_uv(cj_rng *r, const cj_param_surface *s, double margin, double *u, double *v) {
    double du = margin * (s->u1 - s->u0), dv = margin * (s->v1 - s->v0);
    *u = rnd(r, s->u0 + du, s->u1 - du);
    *v = rnd(r, s->v0 + dv, s->v1 - dv);
    if (margin == 0.0 && cj_rng_int(r, 0, 3) == 0) *v = cj_rng_int(r, 0, 1) ? s->v0 : s->v1;
    if (margin == 0.0 && cj_rng_int(r, 0, 7) == 0) *u = cj_rng_int(r, 0, 1) ? s->u0 : s->u1;
}

/* |f(S(u,v))| <= 1e-14 (|grad f| (|x| + 1) + 1): a point displaced by delta along the normal
 * has |f| ~ |grad f| delta, so this certifies distance <~ 1e-14 (|x| + 1) from the implicit
 * surface (rounding in S and f is a few ulps, ~1e-15 relative, observed worst ~6e-2 of the
 * tolerance). A point displaced by 1e-11 (|x| + 1) must fail the check. */
int on_surface(const tcase *t, cj_vec3 x, double *rel) {
    double f;
    cj_vec3 g;
    assert_int_equal(cj_implicit_eval(&t->is, x, &f, &g), CJ_OK);
    double tol = 1e-14 * (cj_v3_norm(g) * (cj_v3_norm(x) + 1.0) + 1.0);
    *rel = fabs(f) / tol;
    return fabs(f) <= tol;
}
