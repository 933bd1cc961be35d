/* Keyframe channels: glTF 2.0 sampler formulas written out independently (STEP, LINEAR, slerp,
 * CUBICSPLINE), the seed's Catmull-Rom matrix, Hermite basis functions, no-overshoot of the
 * auto-clamped handles, squad through its keys, Euler angles against matrix products, and bad
 * keys refused with a message naming the key. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/anim.h"
#include "casteljau/transform.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAXK 24

static double g_worst;

static void make_keys(cj_rng *r, size_t n, int dim, double *t, double *v) {
    double tt = cj_rng_range(r, 0.0, 2.0);
    for (size_t j = 0; j < n; ++j) {
        t[j] = tt;
        tt += cj_rng_range(r, 0.05, 1.5);
        for (int k = 0; k < dim; ++k) v[j * dim + k] = cj_rng_range(r, -5, 5);
    }
}

static cj_channel *make(const cj_channel_desc *d) {
    cj_channel *ch = NULL;
    cj_status st = cj_channel_create(d, NULL, &ch);
    if (st != CJ_OK) fail_msg("create: %s", cj_last_error());
    return ch;
}

/* glTF 2.0 spec, Appendix C (interpolation): k with t_k <= t < t_{k+1}, t_d = t_{k+1} − t_k,
 * s = (t − t_k)/t_d. */
static size_t gltf_k(const double *t, size_t n, double tc) {
    size_t k = 0;
    while (k + 2 < n && t[k + 1] <= tc) ++k;
    return k;
}

static void check_close(const double *a, const double *b, int dim, double tol, const char *what,
                        int cas, double t) {
    for (int k = 0; k < dim; ++k) {
        const double e = fabs(a[k] - b[k]);
        if (e > g_worst) g_worst = e;
        if (e > tol)
            fail_msg("%s case %d t=%.17g coord %d: %.17g vs %.17g", what, cas, t, k, a[k], b[k]);
    }
}

static void test_gltf_vector_samplers(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_channels/gltf", 1601));
    g_worst = 0;
    int evals = 0;
    for (int cas = 0; cas < 300; ++cas) {
        const int dim = cj_rng_int(&r, 1, 4);
        const size_t n = (size_t)cj_rng_int(&r, 2, MAXK);
        double t[MAXK], v[MAXK * 4], tan[MAXK * 8];
        make_keys(&r, n, dim, t, v);
        for (size_t i = 0; i < 2 * n * (size_t)dim; ++i) tan[i] = cj_rng_range(&r, -4, 4);
        cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_VECTOR, CJ_INTERP_STEP, dim);
        d.count = n;
        d.times = t;
        d.values = v;
        cj_channel *step = make(&d);
        d.interp = CJ_INTERP_LINEAR;
        cj_channel *lin = make(&d);
        d.interp = CJ_INTERP_GLTF_CUBIC;
        d.tangents = tan;
        cj_channel *cub = make(&d);
        for (int q = 0; q < 60; ++q) {
            double tc = cj_rng_range(&r, t[0] - 0.5, t[n - 1] + 0.5);
            if (q < (int)n) tc = t[q]; /* the keys themselves */
            double a[4], e[4];
            const size_t k = gltf_k(t, n, tc);
            /* outside the keys: the first / last value */
            const int before = tc <= t[0], after = tc >= t[n - 1];
            const double td = t[k + 1] - t[k], s = (tc - t[k]) / td;
            for (int c = 0; c < dim; ++c) {
                const double vk = v[k * dim + c];
                if (before)
                    e[c] = v[c];
                else if (after)
                    e[c] = v[(n - 1) * dim + c];
                else
                    e[c] = vk;
            }
            assert_int_equal(cj_channel_eval(step, tc, a), CJ_OK);
            check_close(a, e, dim, 0.0, "STEP", cas, tc); /* exact: a key value */
            for (int c = 0; c < dim; ++c)
                if (!before && !after) e[c] = (1 - s) * v[k * dim + c] + s * v[(k + 1) * dim + c];
            assert_int_equal(cj_channel_eval(lin, tc, a), CJ_OK);
            check_close(a, e, dim, 1e-14 * 5, "LINEAR", cas, tc);
            for (int c = 0; c < dim; ++c)
                if (!before && !after) {
                    const double s2 = s * s, s3 = s2 * s;
                    const double bk = tan[(2 * k + 1) * dim + c],
                                 ak1 = tan[(2 * (k + 1)) * dim + c];
                    e[c] = (2 * s3 - 3 * s2 + 1) * v[k * dim + c] + td * (s3 - 2 * s2 + s) * bk +
                           (-2 * s3 + 3 * s2) * v[(k + 1) * dim + c] + td * (s3 - s2) * ak1;
                }
            assert_int_equal(cj_channel_eval(cub, tc, a), CJ_OK);
            check_close(a, e, dim, 1e-13, "CUBICSPLINE", cas, tc);
            ++evals;
        }
        cj_channel_destroy(step);
        cj_channel_destroy(lin);
        cj_channel_destroy(cub);
    }
    printf("glTF STEP (exact) / LINEAR / CUBICSPLINE vs the spec formulas: %d times x 3 samplers, "
           "worst |diff| %.3g (values ~5, tangents ~4 x key interval <= 1.5)\n",
           evals, g_worst);
}

static void rand_quat(cj_rng *r, double q[4]) {
    double n;
    do {
        for (int k = 0; k < 4; ++k) q[k] = cj_rng_range(r, -1, 1);
        n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    } while (n < 0.1 || n > 1);
    for (int k = 0; k < 4; ++k) q[k] /= n;
}

/* The glTF spec's slerp (Appendix C), in long double: flip on negative dot, then the acos form. */
static void spec_slerp(const double *a, const double *b, double t, double *out) {
    long double d = 0, bb[4];
    for (int k = 0; k < 4; ++k) d += (long double)a[k] * b[k];
    for (int k = 0; k < 4; ++k) bb[k] = d < 0 ? -(long double)b[k] : b[k];
    d = fabsl(d);
    const long double ang = acosl(d > 1 ? 1 : d), s = sinl(ang);
    for (int k = 0; k < 4; ++k)
        out[k] = (double)(s > 0 ? (sinl(ang * (1 - t)) / s) * a[k] + (sinl(ang * t) / s) * bb[k]
                                : (1 - t) * a[k] + t * bb[k]);
}

static void test_gltf_rotation_linear(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_channels/slerp", 1602));
    g_worst = 0;
    int evals = 0;
    for (int cas = 0; cas < 200; ++cas) {
        const size_t n = (size_t)cj_rng_int(&r, 2, 10);
        double t[MAXK], v[MAXK * 4], dummy[MAXK * 4];
        make_keys(&r, n, 4, t, dummy);
        for (size_t j = 0; j < n; ++j) rand_quat(&r, v + 4 * j);
        cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_QUATERNION, CJ_INTERP_LINEAR, 4);
        d.count = n;
        d.times = t;
        d.values = v;
        cj_channel *ch = make(&d);
        for (int q = 0; q < 40; ++q) {
            const double tc = cj_rng_range(&r, t[0], t[n - 1]);
            const size_t k = gltf_k(t, n, tc);
            const double s = (tc - t[k]) / (t[k + 1] - t[k]);
            double a[4], e[4];
            spec_slerp(v + 4 * k, v + 4 * (k + 1), s, e);
            assert_int_equal(cj_channel_eval(ch, tc, a), CJ_OK);
            check_close(a, e, 4, 1e-13, "slerp", cas, tc);
            ++evals;
        }
        cj_channel_destroy(ch);
    }
    printf("glTF LINEAR rotation = spec slerp (shortest arc, long double acos form): %d times, "
           "worst %.3g\n",
           evals, g_worst);
    /* Nearly identical keys (angle 1e-9) and keys pi/2 apart in quaternion space (a half turn). */
    const double tiny = 1e-9;
    const double qa[4] = {1, 0, 0, 0}, qb[4] = {cos(tiny / 2), sin(tiny / 2), 0, 0};
    double m[4];
    cj_quat_slerp(qa, qb, 0.25, m);
    const double want = tiny * 0.25 / 2; /* half-angle of the quarter rotation */
    assert_true(fabs(m[1] - sin(want)) <= 1e-24 + 1e-15 * want);
    assert_true(fabs(m[0] * m[0] + m[1] * m[1] - 1) < 4e-16);
    const double tiny_rel = fabs(m[1] - sin(want)) / want;
    const double qh[4] = {0, 0, 0, 1}; /* half turn about z */
    cj_quat_slerp(qa, qh, 0.5, m);
    assert_true(fabs(m[0] - cos(M_PI / 4)) < 1e-15 && fabs(m[3] - sin(M_PI / 4)) < 1e-15);
    const double qhn[4] = {-1e-17, 0, 0, -1}; /* same half turn, opposite sign, dot ~ -0 */
    cj_quat_slerp(qa, qhn, 0.5, m);
    assert_true(fabs(fabs(m[3]) - sin(M_PI / 4)) < 1e-15 && isfinite(m[0]));
    printf("slerp of keys 1e-9 rad apart: relative error %.2g; half-turn keys (dot 0, either "
           "sign): a quarter turn at t = 1/2\n",
           tiny_rel);
}

/* The seed's Catmull-Rom matrix (eq. 126) for evenly spaced keys. */
static void test_catmull_rom_and_kb(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_channels/catmull_rom", 1603));
    g_worst = 0;
    for (int cas = 0; cas < 100; ++cas) {
        const int dim = cj_rng_int(&r, 1, 4);
        const size_t n = (size_t)cj_rng_int(&r, 4, 12);
        double t[MAXK], v[MAXK * 4];
        make_keys(&r, n, dim, t, v);
        const double h = cj_rng_range(&r, 0.1, 2);
        for (size_t j = 0; j < n; ++j) t[j] = 1 + h * (double)j;
        cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_VECTOR, CJ_INTERP_CATMULL_ROM, dim);
        d.count = n;
        d.times = t;
        d.values = v;
        d.tension = cj_rng_range(&r, 0, 1);
        cj_channel *cr = make(&d);
        const double kap = d.tension;
        d.interp = CJ_INTERP_KOCHANEK_BARTELS;
        d.tension = 1 - 2 * kap; /* κ = (1 − T)/2 */
        cj_channel *kb = make(&d);
        const double M[4][4] = {{-kap, 2 - kap, kap - 2, kap},
                                {2 * kap, kap - 3, 3 - 2 * kap, -kap},
                                {-kap, 0, kap, 0},
                                {0, 1, 0, 0}};
        for (size_t j = 1; j + 2 < n; ++j)
            for (int q = 0; q < 8; ++q) {
                const double u = q / 8.0, tc = t[j] + u * h;
                const double U[4] = {u * u * u, u * u, u, 1};
                double e[4], a[4];
                for (int c = 0; c < dim; ++c) {
                    double s = 0;
                    for (int rr = 0; rr < 4; ++rr)
                        for (int cc = 0; cc < 4; ++cc)
                            s += U[rr] * M[rr][cc] * v[(j - 1 + cc) * dim + c];
                    e[c] = s;
                }
                assert_int_equal(cj_channel_eval(cr, tc, a), CJ_OK);
                check_close(a, e, dim, 1e-12, "Catmull-Rom", cas, tc);
                assert_int_equal(cj_channel_eval(kb, tc, a), CJ_OK);
                check_close(a, e, dim, 1e-12, "Kochanek-Bartels(C=B=0)", cas, tc);
            }
        cj_channel_destroy(cr);
        cj_channel_destroy(kb);
    }
    printf("Catmull-Rom (random tension) and Kochanek-Bartels with T = 1-2k, C = B = 0 on evenly "
           "spaced keys = the seed's matrix form: worst %.3g\n",
           g_worst);
}

static void test_hermite_and_auto(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_channels/hermite", 1604));
    g_worst = 0;
    int overshoot_checks = 0;
    double max_violation = 0;
    for (int cas = 0; cas < 200; ++cas) {
        const int dim = cj_rng_int(&r, 1, 4);
        const size_t n = (size_t)cj_rng_int(&r, 2, MAXK);
        double t[MAXK], v[MAXK * 4], m[MAXK * 4];
        make_keys(&r, n, dim, t, v);
        if (cas % 4 == 0) /* plateaus and repeated values: the hard case for overshoot */
            for (size_t j = 1; j < n; ++j)
                if (cj_rng_unit(&r) < 0.4)
                    for (int c = 0; c < dim; ++c) v[j * dim + c] = v[(j - 1) * dim + c];
        for (size_t i = 0; i < n * (size_t)dim; ++i) m[i] = cj_rng_range(&r, -3, 3);
        cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_VECTOR, CJ_INTERP_HERMITE, dim);
        d.count = n;
        d.times = t;
        d.values = v;
        d.tangents = m;
        cj_channel *he = make(&d);
        d.interp = CJ_INTERP_BEZIER_AUTO;
        d.tangents = NULL;
        cj_channel *au = make(&d);
        for (size_t j = 0; j + 1 < n; ++j) {
            const double dt = t[j + 1] - t[j];
            double prev[4];
            for (int q = 0; q <= 32; ++q) {
                const double s = q / 32.0, tc = q == 32 ? t[j + 1] : t[j] + s * dt;
                const double s2 = s * s, s3 = s2 * s;
                double e[4], a[4];
                for (int c = 0; c < dim; ++c)
                    e[c] = (2 * s3 - 3 * s2 + 1) * v[j * dim + c] +
                           (s3 - 2 * s2 + s) * dt * m[j * dim + c] +
                           (-2 * s3 + 3 * s2) * v[(j + 1) * dim + c] +
                           (s3 - s2) * dt * m[(j + 1) * dim + c];
                assert_int_equal(cj_channel_eval(he, tc, a), CJ_OK);
                check_close(a, e, dim, 1e-12, "Hermite", cas, tc);
                assert_int_equal(cj_channel_eval(au, tc, a), CJ_OK);
                for (int c = 0; c < dim; ++c) {
                    const double lo = fmin(v[j * dim + c], v[(j + 1) * dim + c]);
                    const double hi = fmax(v[j * dim + c], v[(j + 1) * dim + c]);
                    const double viol = fmax(lo - a[c], a[c] - hi);
                    if (viol > max_violation) max_violation = viol;
                    if (viol > 1e-14 * (1 + fabs(hi)))
                        fail_msg(
                            "auto-clamped overshoot case %d segment %zu s=%g: %g outside [%g, %g]",
                            cas, j, s, a[c], lo, hi);
                    /* monotone within the segment */
                    if (q > 0) {
                        const double dir = v[(j + 1) * dim + c] - v[j * dim + c];
                        if ((a[c] - prev[c]) * dir < -1e-13)
                            fail_msg("auto-clamped not monotone: case %d segment %zu", cas, j);
                    }
                    prev[c] = a[c];
                }
                ++overshoot_checks;
            }
        }
        cj_channel_destroy(he);
        cj_channel_destroy(au);
    }
    printf("Hermite = basis-function form (worst %.3g); auto-clamped handles: %d samples, never "
           "outside their segment's key values (worst excursion %.3g) and monotone\n",
           g_worst, overshoot_checks, max_violation);
}

static void test_squad(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_channels/squad", 1605));
    double worst_key = 0, worst_kink = 0, worst_unit = 0;
    for (int cas = 0; cas < 50; ++cas) {
        const size_t n = (size_t)cj_rng_int(&r, 3, 8);
        double t[MAXK], v[MAXK * 4], dummy[MAXK * 4];
        make_keys(&r, n, 4, t, dummy);
        /* keys a moderate rotation apart so the curve is smooth enough to differentiate */
        rand_quat(&r, v);
        for (size_t j = 1; j < n; ++j) {
            double ax[3] = {cj_rng_range(&r, -1, 1), cj_rng_range(&r, -1, 1),
                            cj_rng_range(&r, -1, 1)},
                   dq[4];
            assert_int_equal(cj_quat_from_axis_angle(ax, cj_rng_range(&r, 0.2, 1.5), dq), CJ_OK);
            cj_quat_mul(dq, v + 4 * (j - 1), v + 4 * j);
            if (cj_rng_unit(&r) < 0.5)
                for (int k = 0; k < 4; ++k) v[4 * j + k] = -v[4 * j + k]; /* same rotation */
        }
        cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_QUATERNION, CJ_INTERP_SQUAD, 4);
        d.count = n;
        d.times = t;
        d.values = v;
        cj_channel *ch = make(&d);
        for (size_t j = 0; j < n; ++j) {
            double a[4];
            assert_int_equal(cj_channel_eval(ch, t[j], a), CJ_OK);
            double dot = 0;
            for (int k = 0; k < 4; ++k) dot += a[k] * v[4 * j + k];
            worst_key = fmax(worst_key, 1 - fabs(dot));
            if (j == 0 || j + 1 == n) continue;
            /* Angular velocity per unit SEGMENT parameter is continuous at interior keys. */
            const double h = 1e-6;
            double l1[4], l0[4], r0[4], r1[4];
            assert_int_equal(cj_channel_eval(ch, t[j] - 2 * h * (t[j] - t[j - 1]), l1), CJ_OK);
            assert_int_equal(cj_channel_eval(ch, t[j] - h * (t[j] - t[j - 1]), l0), CJ_OK);
            assert_int_equal(cj_channel_eval(ch, t[j] + h * (t[j + 1] - t[j]), r0), CJ_OK);
            assert_int_equal(cj_channel_eval(ch, t[j] + 2 * h * (t[j + 1] - t[j]), r1), CJ_OK);
            double sgn = 0;
            for (int k = 0; k < 4; ++k) sgn += a[k] * l0[k];
            for (int k = 0; k < 4; ++k) {
                const double dl =
                    (3 * a[k] - 4 * (sgn < 0 ? -l0[k] : l0[k]) + (sgn < 0 ? -l1[k] : l1[k])) /
                    (2 * h);
                double sr = 0;
                for (int kk = 0; kk < 4; ++kk) sr += a[kk] * r0[kk];
                const double dr =
                    (-3 * a[k] + 4 * (sr < 0 ? -r0[k] : r0[k]) - (sr < 0 ? -r1[k] : r1[k])) /
                    (2 * h);
                worst_kink = fmax(worst_kink, fabs(dl - dr));
            }
        }
        for (int q = 0; q < 50; ++q) {
            double a[4];
            assert_int_equal(cj_channel_eval(ch, cj_rng_range(&r, t[0], t[n - 1]), a), CJ_OK);
            worst_unit =
                fmax(worst_unit, fabs(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3] - 1));
        }
        cj_channel_destroy(ch);
    }
    printf("squad: passes through its keys (1-|dot| <= %.2g), unit (%.2g), C1 in the segment "
           "parameter at interior keys (one-sided derivatives differ by <= %.2g)\n",
           worst_key, worst_unit, worst_kink);
    assert_true(worst_key < 1e-14);
    assert_true(worst_unit < 1e-14);
    assert_true(worst_kink < 1e-5);
}

static void test_euler(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_channels/euler", 1606));
    static const int seq[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    double worst = 0;
    for (int cas = 0; cas < 600; ++cas) {
        const int order = cas % 6;
        const double ang[3] = {cj_rng_range(&r, -4, 4), cj_rng_range(&r, -4, 4),
                               cj_rng_range(&r, -4, 4)};
        cj_xform3 m = cj_xform3_identity();
        for (int i = 0; i < 3; ++i) {
            const int ax = seq[order][i];
            cj_xform3 rr = ax == 0   ? cj_xform3_rotate_x(ang[0])
                           : ax == 1 ? cj_xform3_rotate_y(ang[1])
                                     : cj_xform3_rotate_z(ang[2]);
            m = cj_xform3_compose(&rr, &m);
        }
        double q[4];
        cj_quat_from_euler(ang, (cj_euler_order)order, q);
        const double p[3] = {cj_rng_range(&r, -1, 1), cj_rng_range(&r, -1, 1),
                             cj_rng_range(&r, -1, 1)};
        double a[3];
        cj_quat_rotate(q, p, a);
        cj_vec3 b;
        assert_int_equal(cj_xform3_apply_vector(&m, cj_v3(p[0], p[1], p[2]), &b), CJ_OK);
        worst = fmax(worst, fmax(fabs(a[0] - b.x), fmax(fabs(a[1] - b.y), fabs(a[2] - b.z))));
    }
    printf("Euler angles (6 orders) as quaternions rotate vectors as the products of "
           "cj_xform3_rotate_x/y/z: worst %.3g\n",
           worst);
    assert_true(worst < 1e-14);
    /* An Euler channel interpolates angles, then converts. */
    const double t[2] = {0, 1}, v[6] = {0, 0, 0, 0, 0, 2};
    cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_EULER, CJ_INTERP_LINEAR, 3);
    d.count = 2;
    d.times = t;
    d.values = v;
    d.euler_order = CJ_EULER_ZYX;
    cj_channel *ch = make(&d);
    double q[4];
    assert_int_equal(cj_channel_eval_quat(ch, 0.5, q), CJ_OK);
    assert_true(fabs(q[0] - cos(0.5)) < 1e-15 && fabs(q[3] - sin(0.5)) < 1e-15);
    cj_channel_destroy(ch);
}

static void expect_fail(cj_channel_desc *d, cj_status want, const char *needle) {
    cj_channel *ch = NULL;
    const cj_status st = cj_channel_create(d, NULL, &ch);
    if (st != want || !strstr(cj_last_error(), needle))
        fail_msg("expected status %d mentioning '%s', got %d: '%s'", (int)want, needle, (int)st,
                 cj_last_error());
    assert_null(ch);
    printf("  refused: %s\n", cj_last_error());
}

static void test_bad_keys(void **state) {
    (void)state;
    double t[4] = {0, 1, 0.5, 2}, v[8] = {0, 0, 1, 1, 2, 2, 3, 3};
    cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_VECTOR, CJ_INTERP_CATMULL_ROM, 2);
    d.count = 4;
    d.times = t;
    d.values = v;
    printf("bad keys:\n");
    expect_fail(&d, CJ_ERR_ARGUMENT, "key 2");
    t[2] = NAN;
    expect_fail(&d, CJ_ERR_NONFINITE, "key 2");
    t[2] = 1.5;
    t[0] = -1;
    expect_fail(&d, CJ_ERR_RANGE, "key 0");
    t[0] = 0;
    v[7] = NAN;
    expect_fail(&d, CJ_ERR_NONFINITE, "key 3");
    v[7] = 3;
    t[1] = 0;
    expect_fail(&d, CJ_ERR_ARGUMENT, "key 1");
    t[1] = 1;
    d.interp = CJ_INTERP_HERMITE;
    expect_fail(&d, CJ_ERR_ARGUMENT, "tangents");
    d.interp = CJ_INTERP_SQUAD;
    expect_fail(&d, CJ_ERR_ARGUMENT, "quaternion");
    d.count = 0;
    d.interp = CJ_INTERP_LINEAR;
    expect_fail(&d, CJ_ERR_EMPTY, "no keys");
    double qv[8] = {1, 0, 0, 0, 0, 0, 0, 0};
    cj_channel_desc q = cj_channel_desc_make(CJ_CHANNEL_QUATERNION, CJ_INTERP_LINEAR, 4);
    q.count = 2;
    q.times = t;
    q.values = qv;
    expect_fail(&q, CJ_ERR_ARGUMENT, "key 1: zero quaternion");
    d.count = 4;
    d.interp = CJ_INTERP_LINEAR;
    cj_channel *ch = make(&d);
    double out[2] = {7, 7};
    assert_int_equal(cj_channel_eval(ch, NAN, out), CJ_ERR_NONFINITE);
    assert_true(out[0] == 7 && out[1] == 7);
    cj_channel_destroy(ch);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gltf_vector_samplers),
        cmocka_unit_test(test_gltf_rotation_linear),
        cmocka_unit_test(test_catmull_rom_and_kb),
        cmocka_unit_test(test_hermite_and_auto),
        cmocka_unit_test(test_squad),
        cmocka_unit_test(test_euler),
        cmocka_unit_test(test_bad_keys),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
