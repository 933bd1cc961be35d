/* Ray–torus: the quartic along the ray, roots isolated through the critical points of its
 * derivatives (see ray.h) and refined by safeguarded Newton–bisection. */
#include "casteljau/ray.h"

#include <math.h>

static const double two_pi = 6.283185307179586476925286766559;

typedef struct torus_ray {
    cj_vec3 o, d;        /* local frame, origin moved near the centre, |d| = 1 */
    double R2, rho2, mr; /* R², ρ², 4R² */
    double c[5];         /* g(s) = Σ c_k s^k */
} torus_ray;

/* g in the geometric form, and a bound on its rounding error. */
static double g_eval(const torus_ray *tr, double s, double *err, double *dg) {
    cj_vec3 w = cj_v3_add(tr->o, cj_v3_scale(tr->d, s));
    double w2 = cj_v3_dot(w, w), h = w.x * w.x + w.y * w.y;
    double G = w2 + (tr->R2 - tr->rho2);
    double g = G * G - tr->mr * h;
    if (err) {
        double Gm = w2 + tr->R2 + tr->rho2;
        *err = cj_gamma(12) * (Gm * Gm + tr->mr * h) +
               4.0 * Gm * cj_gamma(4) * (fabs(tr->o.x) + fabs(tr->o.y) + fabs(tr->o.z) + fabs(s)) *
                   sqrt(w2);
    }
    if (dg) *dg = 4.0 * G * cj_v3_dot(w, tr->d) - 2.0 * tr->mr * (w.x * tr->d.x + w.y * tr->d.y);
    return g;
}

static double dpoly(const double *c, double s) { /* g'(s) */
    return ((4.0 * s + 3.0 * c[3]) * s + 2.0 * c[2]) * s + c[1];
}
static double ddpoly(const double *c, double s) { /* g''(s) */
    return (12.0 * s + 6.0 * c[3]) * s + 2.0 * c[2];
}

/* A root of a function with a sign change on [a, b] (fa, fb of opposite signs), by Newton
 * steps kept inside the shrinking bracket, bisection when a step leaves it or stalls. */
static double bracket_root(const torus_ray *tr, int deriv, double a, double b, double fa) {
    for (int it = 0; it < 200; it++) {
        double m = 0.5 * (a + b);
        if (!(m > a && m < b)) break; /* a and b adjacent doubles */
        double f, df;
        if (deriv) {
            f = dpoly(tr->c, m);
            df = ddpoly(tr->c, m);
        } else {
            f = g_eval(tr, m, NULL, &df);
        }
        if (f == 0.0) return m;
        if ((f < 0.0) == (fa < 0.0)) {
            a = m;
            fa = f;
        } else {
            b = m;
        }
        /* Try a Newton step from the midpoint; take it when it lands inside the bracket. */
        if (df != 0.0) {
            double n = m - f / df;
            if (n > a && n < b) {
                double fn = deriv ? dpoly(tr->c, n) : g_eval(tr, n, NULL, NULL);
                if (fn == 0.0) return n;
                if ((fn < 0.0) == (fa < 0.0)) {
                    a = n;
                    fa = fn;
                } else {
                    b = n;
                }
            }
        }
    }
    return 0.5 * (a + b);
}

/* Sorted roots of g' in (lo, hi), each a critical point of g (at most 3). */
static int critical_points(const torus_ray *tr, double lo, double hi, double *out) {
    /* g''(s) = 12 s² + 6 c3 s + 2 c2: its roots split [lo, hi] where g' is monotone. */
    double A = 12.0, B = 6.0 * tr->c[3], C = 2.0 * tr->c[2];
    double pts[4];
    int np = 0;
    pts[np++] = lo;
    double disc = B * B - 4.0 * A * C;
    if (disc > 0.0) {
        double q = -0.5 * (B + copysign(sqrt(disc), B));
        double r0 = q / A, r1 = q != 0.0 ? C / q : r0;
        if (r1 < r0) {
            double s = r0;
            r0 = r1;
            r1 = s;
        }
        if (r0 > lo && r0 < hi) pts[np++] = r0;
        if (r1 > lo && r1 < hi && r1 != r0) pts[np++] = r1;
    }
    pts[np++] = hi;
    int n = 0;
    for (int i = 0; i + 1 < np; i++) {
        double fa = dpoly(tr->c, pts[i]), fb = dpoly(tr->c, pts[i + 1]);
        if (fa == 0.0) {
            if (pts[i] > lo) out[n++] = pts[i];
            continue;
        }
        if ((fa < 0.0) != (fb < 0.0) && fb != 0.0)
            out[n++] = bracket_root(tr, 1, pts[i], pts[i + 1], fa);
    }
    return n;
}

int cj_ray_torus(const cj_ray *ray, const cj_torus *to, cj_hit *hit) {
    cj_vec3 w0 = cj_v3_sub(ray->org, to->center);
    cj_vec3 ol = cj_v3(cj_v3_dot(w0, to->e1), cj_v3_dot(w0, to->e2), cj_v3_dot(w0, to->a));
    cj_vec3 dl =
        cj_v3(cj_v3_dot(ray->dir, to->e1), cj_v3_dot(ray->dir, to->e2), cj_v3_dot(ray->dir, to->a));
    double k = cj_v3_norm(dl);
    if (!(k > 0.0)) return 0;
    dl = cj_v3_scale(dl, 1.0 / k);
    double s0 = -cj_v3_dot(ol, dl);
    torus_ray tr;
    tr.o = cj_v3_add(ol, cj_v3_scale(dl, s0));
    tr.d = dl;
    double R = to->major, rho = to->minor;
    tr.R2 = R * R;
    tr.rho2 = rho * rho;
    tr.mr = 4.0 * tr.R2;
    /* The part of the ray inside the bounding sphere |w| <= R + ρ (slightly enlarged). */
    double Rb = (R + rho) * (1.0 + 1e-9);
    double oo = cj_v3_dot(tr.o, tr.o);
    if (oo > Rb * Rb) return 0;
    double h = sqrt(Rb * Rb - oo);
    double lo = -h, hi = h;
    double smin = ray->tmin * k - s0, smax = ray->tmax * k - s0;
    if (smin > lo) lo = smin;
    if (smax < hi) hi = smax;
    if (!(lo <= hi)) return 0;
    /* Coefficients at the moved origin (β = o·d ≈ 0 there). */
    double beta = cj_v3_dot(tr.o, dl), gc = oo + tr.R2 - tr.rho2;
    double a2 = dl.x * dl.x + dl.y * dl.y, b2 = tr.o.x * dl.x + tr.o.y * dl.y;
    double g2 = tr.o.x * tr.o.x + tr.o.y * tr.o.y;
    tr.c[4] = 1.0;
    tr.c[3] = 4.0 * beta;
    tr.c[2] = 4.0 * beta * beta + 2.0 * gc - tr.mr * a2;
    tr.c[1] = 4.0 * beta * gc - 2.0 * tr.mr * b2;
    tr.c[0] = gc * gc - tr.mr * g2;

    double crit[3];
    int nc = critical_points(&tr, lo, hi, crit);
    /* Walk lo = x_0 < crit... < x_last = hi; g is monotone between consecutive points. */
    double xs[5];
    int nx = 0;
    xs[nx++] = lo;
    for (int i = 0; i < nc; i++)
        if (crit[i] > xs[nx - 1] && crit[i] < hi) xs[nx++] = crit[i];
    xs[nx++] = hi;
    double root = NAN;
    double err;
    double fprev = g_eval(&tr, xs[0], &err, NULL);
    if (fprev == 0.0) root = xs[0];
    for (int i = 0; i + 1 < nx && isnan(root); i++) {
        double ferr, f = g_eval(&tr, xs[i + 1], &ferr, NULL);
        if (fprev != 0.0 && f != 0.0 && (fprev < 0.0) != (f < 0.0)) {
            root = bracket_root(&tr, 0, xs[i], xs[i + 1], fprev);
            break;
        }
        if (f == 0.0) {
            root = xs[i + 1];
            break;
        }
        /* A critical point where g vanishes to rounding: a tangent (grazing) hit. */
        if (i + 1 < nx - 1 && fabs(f) <= ferr) {
            root = xs[i + 1];
            break;
        }
        fprev = f;
    }
    if (isnan(root)) return 0;
    double t = (s0 + root) / k;
    if (!(t >= ray->tmin && t <= ray->tmax)) return 0;

    cj_vec3 w = cj_v3_add(tr.o, cj_v3_scale(dl, root));
    double gerr, dg, g = g_eval(&tr, root, &gerr, &dg);
    double w2 = cj_v3_dot(w, w), G = w2 + tr.R2 - tr.rho2;
    cj_vec3 grad =
        cj_v3(4.0 * G * w.x - 2.0 * tr.mr * w.x, 4.0 * G * w.y - 2.0 * tr.mr * w.y, 4.0 * G * w.z);
    double gn = cj_v3_norm(grad);
    double e =
        (gn > 0.0 ? 2.0 * (fabs(g) + gerr) / gn : rho * 1e-8) +
        cj_gamma(8) * (cj_v3_norm(w0) + fabs(t) * cj_v3_norm(ray->dir) + cj_v3_norm(to->center));
    cj_vec3 nl = gn > 0.0 ? cj_v3_scale(grad, 1.0 / gn) : cj_v3(0.0, 0.0, 1.0);
    cj_vec3 n = cj_v3_add(cj_v3_add(cj_v3_scale(to->e1, nl.x), cj_v3_scale(to->e2, nl.y)),
                          cj_v3_scale(to->a, nl.z));
    n = cj_v3_normalize(n);
    hit->t = t;
    hit->p = cj_v3_add(ray->org, cj_v3_scale(ray->dir, t));
    hit->p_err = cj_v3(e, e, e);
    hit->n = n;
    hit->ng = n;
    double u = atan2(w.y, w.x), v = atan2(w.z, hypot(w.x, w.y) - R);
    hit->u = u < 0.0 ? u + two_pi : u;
    hit->v = v < 0.0 ? v + two_pi : v;
    hit->err = 0.0;
    return 1;
}
