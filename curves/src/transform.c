/* Homogeneous 2D (3x3) and 3D (4x4) transforms. The dimension-generic kernels work on flat
 * row-major arrays of size N*N with N = 3 or 4. */
#include "casteljau/transform.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- generic kernels ----------------------------------------------------------------- */

static void mat_identity(double *m, int nn) {
    memset(m, 0, sizeof(double) * (size_t)(nn * nn));
    for (int i = 0; i < nn; ++i) m[i * nn + i] = 1.0;
}

static void mat_mul(const double *a, const double *b, double *out, int nn) {
    double r[16];
    for (int i = 0; i < nn; ++i)
        for (int j = 0; j < nn; ++j) {
            double s = 0.0;
            for (int k = 0; k < nn; ++k) s += a[i * nn + k] * b[k * nn + j];
            r[i * nn + j] = s;
        }
    memcpy(out, r, sizeof(double) * (size_t)(nn * nn));
}

static cj_status mat_check(const double *m, int nn, const char *what) {
    for (int i = 0; i < nn; ++i)
        for (int j = 0; j < nn; ++j)
            if (!isfinite(m[i * nn + j]))
                return cj_fail(CJ_ERR_NONFINITE, "%s entry [%d][%d] is %s", what, i, j,
                               isnan(m[i * nn + j]) ? "NaN" : "infinite");
    return CJ_OK;
}

/* Gauss–Jordan with partial pivoting on an nn x nn (nn <= 4) matrix. */
static cj_status mat_inverse(const double *m, double *inv, int nn, const char *what) {
    double a[16], r[16];
    memcpy(a, m, sizeof(double) * (size_t)(nn * nn));
    mat_identity(r, nn);
    double big = 0.0;
    for (int i = 0; i < nn * nn; ++i) big = fmax(big, fabs(a[i]));
    const double floor_ = 16.0 * 0x1p-53 * big;
    for (int col = 0; col < nn; ++col) {
        int piv = col;
        for (int i = col + 1; i < nn; ++i)
            if (fabs(a[i * nn + col]) > fabs(a[piv * nn + col])) piv = i;
        if (!(fabs(a[piv * nn + col]) > floor_))
            return cj_fail(CJ_ERR_SINGULAR,
                           "%s is singular to working precision (pivot %.3g in column %d)", what,
                           a[piv * nn + col], col);
        if (piv != col)
            for (int j = 0; j < nn; ++j) {
                double t = a[col * nn + j];
                a[col * nn + j] = a[piv * nn + j];
                a[piv * nn + j] = t;
                t = r[col * nn + j];
                r[col * nn + j] = r[piv * nn + j];
                r[piv * nn + j] = t;
            }
        const double p = a[col * nn + col];
        for (int j = 0; j < nn; ++j) {
            a[col * nn + j] /= p;
            r[col * nn + j] /= p;
        }
        for (int i = 0; i < nn; ++i) {
            if (i == col) continue;
            const double f = a[i * nn + col];
            if (f == 0.0) continue;
            for (int j = 0; j < nn; ++j) {
                a[i * nn + j] -= f * a[col * nn + j];
                r[i * nn + j] -= f * r[col * nn + j];
            }
        }
    }
    memcpy(inv, r, sizeof(double) * (size_t)(nn * nn));
    return CJ_OK;
}

/* Homogeneous point map: x has nn-1 coordinates. */
static cj_status map_point(const double *m, int nn, const double *x, double *out) {
    const int d = nn - 1;
    double h[4];
    for (int i = 0; i < nn; ++i) {
        double s = m[i * nn + d];
        for (int k = 0; k < d; ++k) s += m[i * nn + k] * x[k];
        h[i] = s;
    }
    const double w = h[d];
    if (w == 0.0) return cj_fail(CJ_ERR_DEGENERATE, "point maps to infinity (w' = 0)");
    for (int k = 0; k < d; ++k) {
        out[k] = w == 1.0 ? h[k] : h[k] / w;
        if (!isfinite(out[k]))
            return cj_fail(CJ_ERR_NONFINITE, "transformed point coordinate %d overflows", k);
    }
    return CJ_OK;
}

static void map_vector(const double *m, int nn, const double *v, double *out) {
    const int d = nn - 1;
    double r[3];
    for (int i = 0; i < d; ++i) {
        double s = 0.0;
        for (int k = 0; k < d; ++k) s += m[i * nn + k] * v[k];
        r[i] = s;
    }
    memcpy(out, r, sizeof(double) * (size_t)d);
}

/* L^-T n, L the linear block. */
static cj_status map_normal(const double *m, int nn, const double *n, double *out) {
    const int d = nn - 1;
    double l[9], li[9];
    for (int i = 0; i < d; ++i)
        for (int k = 0; k < d; ++k) l[i * d + k] = m[i * nn + k];
    cj_status st = mat_inverse(l, li, d, "linear part of the transform");
    if (st) return st;
    double r[3];
    for (int i = 0; i < d; ++i) {
        double s = 0.0;
        for (int k = 0; k < d; ++k) s += li[k * d + i] * n[k]; /* transpose */
        r[i] = s;
    }
    memcpy(out, r, sizeof(double) * (size_t)d);
    return CJ_OK;
}

static cj_status check_vec(const double *v, int d, const char *what) {
    for (int k = 0; k < d; ++k)
        if (!isfinite(v[k]))
            return cj_fail(CJ_ERR_NONFINITE, "%s coordinate %d is %s", what, k,
                           isnan(v[k]) ? "NaN" : "infinite");
    return CJ_OK;
}

static cj_status map_points(const double *m, int nn, const double *in, size_t count, double *out) {
    const int d = nn - 1;
    cj_status st = mat_check(m, nn, "transform");
    if (st) return st;
    st = cj_check_points(in, count, d, "point");
    if (st) return st;
    /* Validate every image first so that a failure leaves out (which may be in) untouched. */
    for (size_t i = 0; i < count; ++i) {
        double tmp[3];
        if (map_point(m, nn, in + i * (size_t)d, tmp) != CJ_OK) {
            char why[256];
            snprintf(why, sizeof why, "%s", cj_last_error());
            return cj_fail(map_point(m, nn, in + i * (size_t)d, tmp), "point %zu: %s", i, why);
        }
    }
    for (size_t i = 0; i < count; ++i) {
        double tmp[3];
        (void)map_point(m, nn, in + i * (size_t)d, tmp);
        memcpy(out + i * (size_t)d, tmp, sizeof(double) * (size_t)d);
    }
    return CJ_OK;
}

/* ---- 2D ------------------------------------------------------------------------------ */

cj_xform2 cj_xform2_identity(void) {
    cj_xform2 r;
    mat_identity(&r.m[0][0], 3);
    return r;
}

cj_xform2 cj_xform2_translate(double tx, double ty) {
    cj_xform2 r = cj_xform2_identity();
    r.m[0][2] = tx;
    r.m[1][2] = ty;
    return r;
}

cj_xform2 cj_xform2_rotate(double angle) {
    cj_xform2 r = cj_xform2_identity();
    const double c = cos(angle), s = sin(angle);
    r.m[0][0] = c;
    r.m[0][1] = -s;
    r.m[1][0] = s;
    r.m[1][1] = c;
    return r;
}

cj_xform2 cj_xform2_scale(double sx, double sy) {
    cj_xform2 r = cj_xform2_identity();
    r.m[0][0] = sx;
    r.m[1][1] = sy;
    return r;
}

cj_xform2 cj_xform2_shear(double shx, double shy) {
    cj_xform2 r = cj_xform2_identity();
    r.m[0][1] = shx;
    r.m[1][0] = shy;
    return r;
}

cj_status cj_xform2_reflect(cj_vec2 dir, cj_xform2 *out) {
    assert(out != NULL);
    const double v[2] = {dir.x, dir.y};
    cj_status st = check_vec(v, 2, "reflection line direction");
    if (st) return st;
    const double len = hypot(dir.x, dir.y);
    if (len == 0.0) return cj_fail(CJ_ERR_DEGENERATE, "reflection line direction is zero");
    const double nx = -dir.y / len, ny = dir.x / len;
    cj_xform2 r = cj_xform2_identity();
    r.m[0][0] = 1.0 - 2.0 * nx * nx;
    r.m[0][1] = -2.0 * nx * ny;
    r.m[1][0] = -2.0 * nx * ny;
    r.m[1][1] = 1.0 - 2.0 * ny * ny;
    *out = r;
    return CJ_OK;
}

cj_xform2 cj_xform2_compose(const cj_xform2 *a, const cj_xform2 *b) {
    assert(a != NULL && b != NULL);
    cj_xform2 r;
    mat_mul(&a->m[0][0], &b->m[0][0], &r.m[0][0], 3);
    return r;
}

cj_status cj_xform2_inverse(const cj_xform2 *m, cj_xform2 *inv) {
    assert(m != NULL && inv != NULL);
    cj_status st = mat_check(&m->m[0][0], 3, "transform");
    if (st) return st;
    cj_xform2 r;
    if ((st = mat_inverse(&m->m[0][0], &r.m[0][0], 3, "transform"))) return st;
    *inv = r;
    return CJ_OK;
}

int cj_xform2_is_affine(const cj_xform2 *m) {
    assert(m != NULL);
    return m->m[2][0] == 0.0 && m->m[2][1] == 0.0 && m->m[2][2] == 1.0;
}

cj_status cj_xform2_apply_point(const cj_xform2 *m, cj_vec2 p, cj_vec2 *out) {
    assert(m != NULL && out != NULL);
    const double x[2] = {p.x, p.y};
    double r[2];
    cj_status st = mat_check(&m->m[0][0], 3, "transform");
    if (st || (st = check_vec(x, 2, "point")) || (st = map_point(&m->m[0][0], 3, x, r))) return st;
    *out = cj_v2(r[0], r[1]);
    return CJ_OK;
}

cj_status cj_xform2_apply_vector(const cj_xform2 *m, cj_vec2 v, cj_vec2 *out) {
    assert(m != NULL && out != NULL);
    const double x[2] = {v.x, v.y};
    double r[2];
    cj_status st = mat_check(&m->m[0][0], 3, "transform");
    if (st || (st = check_vec(x, 2, "vector"))) return st;
    map_vector(&m->m[0][0], 3, x, r);
    *out = cj_v2(r[0], r[1]);
    return CJ_OK;
}

cj_status cj_xform2_apply_normal(const cj_xform2 *m, cj_vec2 n, cj_vec2 *out) {
    assert(m != NULL && out != NULL);
    const double x[2] = {n.x, n.y};
    double r[2];
    cj_status st = mat_check(&m->m[0][0], 3, "transform");
    if (st || (st = check_vec(x, 2, "normal")) || (st = map_normal(&m->m[0][0], 3, x, r)))
        return st;
    *out = cj_v2(r[0], r[1]);
    return CJ_OK;
}

cj_status cj_xform2_apply_points(const cj_xform2 *m, const double *in, size_t count, double *out) {
    assert(m != NULL && (count == 0 || (in != NULL && out != NULL)));
    return map_points(&m->m[0][0], 3, in, count, out);
}

/* ---- 3D ------------------------------------------------------------------------------ */

cj_xform3 cj_xform3_identity(void) {
    cj_xform3 r;
    mat_identity(&r.m[0][0], 4);
    return r;
}

cj_xform3 cj_xform3_translate(double tx, double ty, double tz) {
    cj_xform3 r = cj_xform3_identity();
    r.m[0][3] = tx;
    r.m[1][3] = ty;
    r.m[2][3] = tz;
    return r;
}

/* Rotation in the plane of axes (i, j), taking axis i towards axis j. */
static cj_xform3 plane_rotation(int i, int j, double angle) {
    cj_xform3 r = cj_xform3_identity();
    const double c = cos(angle), s = sin(angle);
    r.m[i][i] = c;
    r.m[i][j] = -s;
    r.m[j][i] = s;
    r.m[j][j] = c;
    return r;
}

cj_xform3 cj_xform3_rotate_x(double angle) {
    return plane_rotation(1, 2, angle);
}
cj_xform3 cj_xform3_rotate_y(double angle) {
    return plane_rotation(2, 0, angle);
}
cj_xform3 cj_xform3_rotate_z(double angle) {
    return plane_rotation(0, 1, angle);
}

cj_status cj_xform3_rotate_axis(cj_vec3 axis, double angle, cj_xform3 *out) {
    assert(out != NULL);
    const double v[3] = {axis.x, axis.y, axis.z};
    cj_status st = check_vec(v, 3, "rotation axis");
    if (st) return st;
    if (!isfinite(angle)) return cj_fail(CJ_ERR_NONFINITE, "rotation angle is not finite");
    const double big = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (big == 0.0) return cj_fail(CJ_ERR_DEGENERATE, "rotation axis is the zero vector");
    double k[3] = {v[0] / big, v[1] / big, v[2] / big};
    const double len = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
    for (int i = 0; i < 3; ++i) k[i] /= len;
    const double c = cos(angle), s = sin(angle), omc = 1.0 - c;
    /* R = c I + s [k]x + (1-c) k k^T, the expanded form of Rodrigues' formula. */
    cj_xform3 r = cj_xform3_identity();
    r.m[0][0] = c + omc * k[0] * k[0];
    r.m[0][1] = omc * k[0] * k[1] - s * k[2];
    r.m[0][2] = omc * k[0] * k[2] + s * k[1];
    r.m[1][0] = omc * k[1] * k[0] + s * k[2];
    r.m[1][1] = c + omc * k[1] * k[1];
    r.m[1][2] = omc * k[1] * k[2] - s * k[0];
    r.m[2][0] = omc * k[2] * k[0] - s * k[1];
    r.m[2][1] = omc * k[2] * k[1] + s * k[0];
    r.m[2][2] = c + omc * k[2] * k[2];
    *out = r;
    return CJ_OK;
}

cj_xform3 cj_xform3_scale(double sx, double sy, double sz) {
    cj_xform3 r = cj_xform3_identity();
    r.m[0][0] = sx;
    r.m[1][1] = sy;
    r.m[2][2] = sz;
    return r;
}

cj_xform3 cj_xform3_shear(double xy, double xz, double yx, double yz, double zx, double zy) {
    cj_xform3 r = cj_xform3_identity();
    r.m[0][1] = xy;
    r.m[0][2] = xz;
    r.m[1][0] = yx;
    r.m[1][2] = yz;
    r.m[2][0] = zx;
    r.m[2][1] = zy;
    return r;
}

cj_status cj_xform3_reflect(cj_vec3 normal, cj_xform3 *out) {
    assert(out != NULL);
    const double v[3] = {normal.x, normal.y, normal.z};
    cj_status st = check_vec(v, 3, "reflection plane normal");
    if (st) return st;
    const double big = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    if (big == 0.0) return cj_fail(CJ_ERR_DEGENERATE, "reflection plane normal is zero");
    double n[3] = {v[0] / big, v[1] / big, v[2] / big};
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; ++i) n[i] /= len;
    cj_xform3 r = cj_xform3_identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.m[i][j] = (i == j ? 1.0 : 0.0) - 2.0 * n[i] * n[j];
    *out = r;
    return CJ_OK;
}

cj_xform3 cj_xform3_compose(const cj_xform3 *a, const cj_xform3 *b) {
    assert(a != NULL && b != NULL);
    cj_xform3 r;
    mat_mul(&a->m[0][0], &b->m[0][0], &r.m[0][0], 4);
    return r;
}

cj_status cj_xform3_inverse(const cj_xform3 *m, cj_xform3 *inv) {
    assert(m != NULL && inv != NULL);
    cj_status st = mat_check(&m->m[0][0], 4, "transform");
    if (st) return st;
    cj_xform3 r;
    if ((st = mat_inverse(&m->m[0][0], &r.m[0][0], 4, "transform"))) return st;
    *inv = r;
    return CJ_OK;
}

int cj_xform3_is_affine(const cj_xform3 *m) {
    assert(m != NULL);
    return m->m[3][0] == 0.0 && m->m[3][1] == 0.0 && m->m[3][2] == 0.0 && m->m[3][3] == 1.0;
}

cj_status cj_xform3_apply_point(const cj_xform3 *m, cj_vec3 p, cj_vec3 *out) {
    assert(m != NULL && out != NULL);
    const double x[3] = {p.x, p.y, p.z};
    double r[3];
    cj_status st = mat_check(&m->m[0][0], 4, "transform");
    if (st || (st = check_vec(x, 3, "point")) || (st = map_point(&m->m[0][0], 4, x, r))) return st;
    *out = cj_v3(r[0], r[1], r[2]);
    return CJ_OK;
}

cj_status cj_xform3_apply_vector(const cj_xform3 *m, cj_vec3 v, cj_vec3 *out) {
    assert(m != NULL && out != NULL);
    const double x[3] = {v.x, v.y, v.z};
    double r[3];
    cj_status st = mat_check(&m->m[0][0], 4, "transform");
    if (st || (st = check_vec(x, 3, "vector"))) return st;
    map_vector(&m->m[0][0], 4, x, r);
    *out = cj_v3(r[0], r[1], r[2]);
    return CJ_OK;
}

cj_status cj_xform3_apply_normal(const cj_xform3 *m, cj_vec3 n, cj_vec3 *out) {
    assert(m != NULL && out != NULL);
    const double x[3] = {n.x, n.y, n.z};
    double r[3];
    cj_status st = mat_check(&m->m[0][0], 4, "transform");
    if (st || (st = check_vec(x, 3, "normal")) || (st = map_normal(&m->m[0][0], 4, x, r)))
        return st;
    *out = cj_v3(r[0], r[1], r[2]);
    return CJ_OK;
}

cj_status cj_xform3_apply_points(const cj_xform3 *m, const double *in, size_t count, double *out) {
    assert(m != NULL && (count == 0 || (in != NULL && out != NULL)));
    return map_points(&m->m[0][0], 4, in, count, out);
}
