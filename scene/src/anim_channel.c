/* Keyframe channels: keys validated once, turned into cubic Bézier segments by the curve core
 * (catmull_rom.h), evaluated by de Casteljau; quaternion channels by slerp / squad. */
#include "casteljau/anim.h"

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct cj_channel {
    cj_allocator alloc;
    int has_alloc;
    cj_channel_kind kind;
    cj_interp interp;
    cj_euler_order order;
    int dim;
    size_t count;
    double *times;  /* count */
    double *values; /* count × dim (quaternions normalised) */
    double *segs;   /* (count − 1) × 4 × dim, or NULL */
    double *qa;     /* SQUAD: sign-aligned keys, count × 4 */
    double *qs;     /* SQUAD: inner quadrangle points, count × 4 */
};

cj_channel_desc cj_channel_desc_make(cj_channel_kind kind, cj_interp interp, int dim) {
    cj_channel_desc d;
    memset(&d, 0, sizeof d);
    d.kind = kind;
    d.interp = interp;
    d.dim = dim;
    d.tension = 0.5;
    d.euler_order = CJ_EULER_XYZ;
    return d;
}

static cj_status check_desc(const cj_channel_desc *d) {
    if (d->count == 0) return cj_fail(CJ_ERR_EMPTY, "channel has no keys");
    if (d->kind == CJ_CHANNEL_VECTOR && (d->dim < 1 || d->dim > CJ_CHANNEL_MAX_DIM))
        return cj_fail(CJ_ERR_DIMENSION, "channel dimension %d outside 1..4", d->dim);
    if (d->kind == CJ_CHANNEL_QUATERNION && d->dim != 4)
        return cj_fail(CJ_ERR_DIMENSION, "quaternion channel dimension %d, must be 4", d->dim);
    if (d->kind == CJ_CHANNEL_EULER && d->dim != 3)
        return cj_fail(CJ_ERR_DIMENSION, "Euler channel dimension %d, must be 3", d->dim);
    if ((int)d->interp < 0 || d->interp > CJ_INTERP_SQUAD)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown interpolation %d", (int)d->interp);
    if ((int)d->euler_order < 0 || d->euler_order > CJ_EULER_ZYX)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown Euler order %d", (int)d->euler_order);
    if (d->kind == CJ_CHANNEL_QUATERNION) {
        if (d->interp != CJ_INTERP_STEP && d->interp != CJ_INTERP_LINEAR &&
            d->interp != CJ_INTERP_SQUAD && d->interp != CJ_INTERP_GLTF_CUBIC)
            return cj_fail(CJ_ERR_ARGUMENT,
                           "quaternion channels take step, linear, squad or glTF cubic");
    } else if (d->interp == CJ_INTERP_SQUAD) {
        return cj_fail(CJ_ERR_ARGUMENT, "squad applies to quaternion channels only");
    }
    for (size_t j = 0; j < d->count; ++j) {
        const double t = d->times[j];
        if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "key %zu: time is %g", j, t);
        if (t < 0.0) return cj_fail(CJ_ERR_RANGE, "key %zu: negative time %g", j, t);
        if (j > 0 && !(t > d->times[j - 1]))
            return cj_fail(CJ_ERR_ARGUMENT, "key %zu: time %g is not after key %zu's time %g", j, t,
                           j - 1, d->times[j - 1]);
        for (int k = 0; k < d->dim; ++k)
            if (!isfinite(d->values[j * (size_t)d->dim + (size_t)k]))
                return cj_fail(CJ_ERR_NONFINITE, "key %zu: value coordinate %d is not finite", j,
                               k);
    }
    size_t ntan = 0;
    if (d->interp == CJ_INTERP_HERMITE) ntan = d->count * (size_t)d->dim;
    if (d->interp == CJ_INTERP_GLTF_CUBIC) ntan = 2 * d->count * (size_t)d->dim;
    if (ntan) {
        if (!d->tangents) return cj_fail(CJ_ERR_ARGUMENT, "interpolation needs tangents");
        for (size_t i = 0; i < ntan; ++i)
            if (!isfinite(d->tangents[i]))
                return cj_fail(CJ_ERR_NONFINITE, "key %zu: tangent coordinate %zu is not finite",
                               d->interp == CJ_INTERP_HERMITE ? i / (size_t)d->dim
                                                              : i / (2 * (size_t)d->dim),
                               i % (size_t)d->dim);
    }
    if (d->kind == CJ_CHANNEL_QUATERNION)
        for (size_t j = 0; j < d->count; ++j) {
            const double *q = d->values + 4 * j;
            if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "key %zu: zero quaternion", j);
        }
    return CJ_OK;
}

/* Auto-clamped slopes per coordinate (header: BEZIER_AUTO). */
static void auto_clamped_slopes(const double *t, const double *v, size_t n, int dim, double *m) {
    for (size_t j = 0; j < n; ++j)
        for (int k = 0; k < dim; ++k) {
            double mj = 0.0;
            if (j > 0 && j + 1 < n) {
                const double d0 = t[j] - t[j - 1], d1 = t[j + 1] - t[j];
                const double s0 = (v[j * dim + k] - v[(j - 1) * dim + k]) / d0;
                const double s1 = (v[(j + 1) * dim + k] - v[j * dim + k]) / d1;
                if (s0 * s1 > 0.0) {
                    mj = (d1 * s0 + d0 * s1) / (d0 + d1);
                    const double cap = 3.0 * fmin(fabs(s0), fabs(s1));
                    if (fabs(mj) > cap) mj = copysign(cap, mj);
                }
            }
            m[j * dim + k] = mj;
        }
}

static void *ch_alloc(const cj_allocator *a, size_t bytes) {
    return a ? a->alloc(a->user, bytes) : malloc(bytes);
}

static void ch_free(const cj_allocator *a, void *p) {
    if (a)
        a->free(a->user, p);
    else
        free(p);
}

static cj_status build_segments(cj_channel *ch, const cj_channel_desc *d) {
    const size_t n = ch->count, nseg = n - 1;
    const int dim = ch->dim;
    const double *v = ch->values;
    double *s = ch->segs;
    switch (d->interp) {
    case CJ_INTERP_STEP:
    case CJ_INTERP_LINEAR:
        for (size_t j = 0; j < nseg; ++j)
            for (int k = 0; k < dim; ++k) {
                const double a = v[j * dim + k], b = v[(j + 1) * dim + k];
                const int lin = d->interp == CJ_INTERP_LINEAR;
                s[(4 * j + 0) * dim + k] = a;
                s[(4 * j + 1) * dim + k] = lin ? (2.0 * a + b) / 3.0 : a;
                s[(4 * j + 2) * dim + k] = lin ? (a + 2.0 * b) / 3.0 : a;
                s[(4 * j + 3) * dim + k] = lin ? b : a;
            }
        return CJ_OK;
    case CJ_INTERP_CATMULL_ROM:
    case CJ_INTERP_CENTRIPETAL:
    case CJ_INTERP_KOCHANEK_BARTELS: {
        cj_spline_options o = cj_spline_defaults();
        o.kind = d->interp == CJ_INTERP_CATMULL_ROM   ? CJ_SPLINE_CATMULL_ROM
                 : d->interp == CJ_INTERP_CENTRIPETAL ? CJ_SPLINE_CENTRIPETAL
                                                      : CJ_SPLINE_KOCHANEK_BARTELS;
        o.tension = d->tension;
        o.continuity = d->continuity;
        o.bias = d->bias;
        if (!isfinite(o.tension) || !isfinite(o.continuity) || !isfinite(o.bias))
            return cj_fail(CJ_ERR_NONFINITE, "channel tension/continuity/bias not finite");
        return cj_catmull_rom(v, n, dim, &o, s, nseg, NULL, NULL);
    }
    case CJ_INTERP_HERMITE:
        return cj_hermite_spline(v, d->tangents, ch->times, n, dim, s, nseg, NULL);
    case CJ_INTERP_BEZIER_AUTO: {
        double *m = ch_alloc(ch->has_alloc ? &ch->alloc : NULL, sizeof(double) * n * (size_t)dim);
        if (!m) return cj_fail(CJ_ERR_NOMEM, "channel: no memory for handle slopes");
        auto_clamped_slopes(ch->times, v, n, dim, m);
        cj_status st = cj_hermite_spline(v, m, ch->times, n, dim, s, nseg, NULL);
        ch_free(ch->has_alloc ? &ch->alloc : NULL, m);
        return st;
    }
    case CJ_INTERP_GLTF_CUBIC:
        for (size_t j = 0; j < nseg; ++j) {
            const double dt = ch->times[j + 1] - ch->times[j];
            double v0[CJ_CHANNEL_MAX_DIM], v1[CJ_CHANNEL_MAX_DIM];
            for (int k = 0; k < dim; ++k) {
                v0[k] = dt * d->tangents[(2 * j + 1) * dim + k];   /* out-tangent b_j */
                v1[k] = dt * d->tangents[(2 * (j + 1)) * dim + k]; /* in-tangent a_{j+1} */
            }
            cj_status st = cj_hermite_segment(v + j * dim, v0, v + (j + 1) * dim, v1, dim,
                                              s + 4 * j * (size_t)dim);
            if (st != CJ_OK) return st;
        }
        return CJ_OK;
    default:
        return cj_fail(CJ_ERR_ARGUMENT, "interpolation %d has no segments", (int)d->interp);
    }
}

/* log of a unit quaternion with w >= 0: (0, u φ), u the unit axis, φ = half angle. */
static void quat_log(const double q[4], double out[3]) {
    const double vn = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double phi = atan2(vn, q[0]);
    const double f = vn > 0.0 ? phi / vn : 1.0;
    for (int k = 0; k < 3; ++k) out[k] = q[1 + k] * f;
}

static void quat_exp(const double v[3], double out[4]) {
    const double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double f = n > 1e-8 ? sin(n) / n : 1.0 - n * n / 6.0;
    out[0] = cos(n);
    for (int k = 0; k < 3; ++k) out[1 + k] = v[k] * f;
}

static void build_squad(cj_channel *ch) {
    const size_t n = ch->count;
    memcpy(ch->qa, ch->values, sizeof(double) * 4 * n);
    for (size_t j = 1; j < n; ++j) {
        const double *p = ch->qa + 4 * (j - 1);
        double *q = ch->qa + 4 * j;
        if (p[0] * q[0] + p[1] * q[1] + p[2] * q[2] + p[3] * q[3] < 0.0)
            for (int k = 0; k < 4; ++k) q[k] = -q[k];
    }
    for (size_t j = 0; j < n; ++j) {
        double *s = ch->qs + 4 * j;
        const double *q = ch->qa + 4 * j;
        if (j == 0 || j + 1 == n) {
            memcpy(s, q, sizeof(double) * 4);
            continue;
        }
        const double qi[4] = {q[0], -q[1], -q[2], -q[3]};
        double a[4], b[4], la[3], lb[3], e[3], ex[4];
        cj_quat_mul(qi, ch->qa + 4 * (j + 1), a);
        cj_quat_mul(qi, ch->qa + 4 * (j - 1), b);
        quat_log(a, la);
        quat_log(b, lb);
        for (int k = 0; k < 3; ++k) e[k] = -0.25 * (la[k] + lb[k]);
        quat_exp(e, ex);
        cj_quat_mul(q, ex, s);
    }
}

cj_status cj_channel_create(const cj_channel_desc *desc, const cj_allocator *alloc,
                            cj_channel **out) {
    assert(desc && out);
    assert(desc->times && desc->values);
    cj_status st = check_desc(desc);
    if (st != CJ_OK) return st;
    const size_t n = desc->count, dim = (size_t)desc->dim;
    const int need_segs =
        desc->kind != CJ_CHANNEL_QUATERNION || desc->interp == CJ_INTERP_GLTF_CUBIC;
    const int need_squad = desc->interp == CJ_INTERP_SQUAD;
    const size_t nd = n + n * dim + (need_segs ? (n - 1) * 4 * dim : 0) + (need_squad ? 8 * n : 0);
    const size_t bytes = sizeof(cj_channel) + sizeof(double) * nd;
    cj_channel *ch = ch_alloc(alloc, bytes);
    if (!ch) return cj_fail(CJ_ERR_NOMEM, "channel: no memory for %zu keys", n);
    memset(ch, 0, sizeof *ch);
    if (alloc) {
        ch->alloc = *alloc;
        ch->has_alloc = 1;
    }
    ch->kind = desc->kind;
    ch->interp = desc->interp;
    ch->order = desc->euler_order;
    ch->dim = desc->dim;
    ch->count = n;
    double *p = (double *)(ch + 1);
    ch->times = p;
    p += n;
    ch->values = p;
    p += n * dim;
    if (need_segs) {
        ch->segs = p;
        p += (n - 1) * 4 * dim;
    }
    if (need_squad) {
        ch->qa = p;
        ch->qs = p + 4 * n;
    }
    memcpy(ch->times, desc->times, sizeof(double) * n);
    memcpy(ch->values, desc->values, sizeof(double) * n * dim);
    if (ch->kind == CJ_CHANNEL_QUATERNION)
        for (size_t j = 0; j < n; ++j) {
            double *q = ch->values + 4 * j;
            const double nn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            for (int k = 0; k < 4; ++k) q[k] /= nn;
        }
    if (need_segs && n > 1) st = build_segments(ch, desc);
    if (need_squad) build_squad(ch);
    if (st != CJ_OK) {
        cj_channel_destroy(ch);
        return st;
    }
    *out = ch;
    return CJ_OK;
}

void cj_channel_destroy(cj_channel *ch) {
    if (!ch) return;
    ch_free(ch->has_alloc ? &ch->alloc : NULL, ch);
}

int cj_channel_dim(const cj_channel *ch) {
    return ch->dim;
}
cj_channel_kind cj_channel_kind_of(const cj_channel *ch) {
    return ch->kind;
}

void cj_channel_range(const cj_channel *ch, double *t0, double *t1) {
    if (t0) *t0 = ch->times[0];
    if (t1) *t1 = ch->times[ch->count - 1];
}

const double *cj_channel_segments(const cj_channel *ch, size_t *nsegs) {
    if (nsegs) *nsegs = ch->segs ? ch->count - 1 : 0;
    return ch->segs;
}

/* Segment j with t_j <= t < t_{j+1} (t strictly inside the key range), and its parameter. */
static size_t locate(const cj_channel *ch, double t, double *u) {
    size_t lo = 0, hi = ch->count - 1; /* t_lo <= t < t_hi */
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (ch->times[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    *u = (t - ch->times[lo]) / (ch->times[lo + 1] - ch->times[lo]);
    return lo;
}

cj_status cj_channel_eval(const cj_channel *ch, double t, double *out) {
    assert(ch && out);
    if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "channel evaluated at time %g", t);
    const size_t dim = (size_t)ch->dim, n = ch->count;
    if (n == 1 || t <= ch->times[0]) {
        memcpy(out, ch->values, sizeof(double) * dim);
        return CJ_OK;
    }
    if (t >= ch->times[n - 1]) {
        memcpy(out, ch->values + (n - 1) * dim, sizeof(double) * dim);
        return CJ_OK;
    }
    double u;
    const size_t j = locate(ch, t, &u);
    if (ch->interp == CJ_INTERP_STEP) {
        memcpy(out, ch->values + j * dim, sizeof(double) * dim);
        return CJ_OK;
    }
    if (ch->kind == CJ_CHANNEL_QUATERNION && ch->interp == CJ_INTERP_LINEAR) {
        cj_quat_slerp(ch->values + 4 * j, ch->values + 4 * (j + 1), u, out);
        return CJ_OK;
    }
    if (ch->kind == CJ_CHANNEL_QUATERNION && ch->interp == CJ_INTERP_SQUAD) {
        double a[4], b[4];
        cj_quat_slerp(ch->qa + 4 * j, ch->qa + 4 * (j + 1), u, a);
        cj_quat_slerp(ch->qs + 4 * j, ch->qs + 4 * (j + 1), u, b);
        cj_quat_slerp(a, b, 2.0 * u * (1.0 - u), out);
        return CJ_OK;
    }
    const cj_bezier c = cj_bezier_view(3, ch->dim, ch->segs + 4 * j * dim);
    double tmp[CJ_CHANNEL_MAX_DIM];
    cj_status st = cj_bezier_eval_decasteljau(&c, u, tmp);
    if (st != CJ_OK) return st;
    if (ch->kind == CJ_CHANNEL_QUATERNION) {
        const double nn =
            sqrt(tmp[0] * tmp[0] + tmp[1] * tmp[1] + tmp[2] * tmp[2] + tmp[3] * tmp[3]);
        if (!(nn > 0.0))
            return cj_fail(CJ_ERR_DEGENERATE, "glTF cubic rotation vanishes at time %g", t);
        for (int k = 0; k < 4; ++k) tmp[k] /= nn;
    }
    memcpy(out, tmp, sizeof(double) * dim);
    return CJ_OK;
}

cj_status cj_channel_eval_quat(const cj_channel *ch, double t, double q[4]) {
    if (ch->kind == CJ_CHANNEL_VECTOR)
        return cj_fail(CJ_ERR_ARGUMENT, "a vector channel is not a rotation");
    if (ch->kind == CJ_CHANNEL_QUATERNION) return cj_channel_eval(ch, t, q);
    double a[3];
    cj_status st = cj_channel_eval(ch, t, a);
    if (st != CJ_OK) return st;
    cj_quat_from_euler(a, ch->order, q);
    return CJ_OK;
}
