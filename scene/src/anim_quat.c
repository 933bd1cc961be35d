/* Unit quaternions for rotation channels: product, axis-angle, slerp with a stable angle,
 * Euler angles. */
#include "casteljau/anim.h"

#include "error_internal.h"

#include <math.h>

void cj_quat_mul(const double a[4], const double b[4], double out[4]) {
    const double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    const double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    const double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    const double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    out[0] = w;
    out[1] = x;
    out[2] = y;
    out[3] = z;
}

cj_status cj_quat_from_axis_angle(const double axis[3], double angle, double out[4]) {
    if (!isfinite(axis[0]) || !isfinite(axis[1]) || !isfinite(axis[2]) || !isfinite(angle))
        return cj_fail(CJ_ERR_NONFINITE, "quaternion from axis-angle: non-finite axis or angle");
    const double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(n > 0.0)) return cj_fail(CJ_ERR_DEGENERATE, "quaternion from axis-angle: zero axis");
    const double s = sin(0.5 * angle) / n;
    out[0] = cos(0.5 * angle);
    out[1] = axis[0] * s;
    out[2] = axis[1] * s;
    out[3] = axis[2] * s;
    return CJ_OK;
}

void cj_quat_rotate(const double q[4], const double v[3], double out[3]) {
    /* v' = v + 2w (u×v) + 2 u×(u×v), u the vector part: no full products needed. */
    const double ux = q[1], uy = q[2], uz = q[3], w = q[0];
    const double cx = uy * v[2] - uz * v[1], cy = uz * v[0] - ux * v[2], cz = ux * v[1] - uy * v[0];
    const double dx = uy * cz - uz * cy, dy = uz * cx - ux * cz, dz = ux * cy - uy * cx;
    out[0] = v[0] + 2.0 * (w * cx + dx);
    out[1] = v[1] + 2.0 * (w * cy + dy);
    out[2] = v[2] + 2.0 * (w * cz + dz);
}

/* sin(x)/x, by its series where the quotient would lose digits. */
static double sinc(double x) {
    const double x2 = x * x;
    if (fabs(x) < 1e-3) return 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0));
    return sin(x) / x;
}

static void normalize4(double q[4]) {
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (n > 0.0)
        for (int k = 0; k < 4; ++k) q[k] /= n;
}

void cj_quat_slerp(const double a[4], const double b_in[4], double t, double out[4]) {
    double b[4];
    const double dot = a[0] * b_in[0] + a[1] * b_in[1] + a[2] * b_in[2] + a[3] * b_in[3];
    const double sgn = dot < 0.0 ? -1.0 : 1.0;
    for (int k = 0; k < 4; ++k) b[k] = sgn * b_in[k];
    /* The angle from the chord lengths: acos(dot) loses half the digits near 0. */
    double dm = 0.0, dp = 0.0;
    for (int k = 0; k < 4; ++k) {
        dm += (a[k] - b[k]) * (a[k] - b[k]);
        dp += (a[k] + b[k]) * (a[k] + b[k]);
    }
    const double theta = 2.0 * atan2(sqrt(dm), sqrt(dp)); /* in [0, pi/2] after the flip */
    const double st = sinc(theta);
    const double wa = (1.0 - t) * sinc((1.0 - t) * theta) / st;
    const double wb = t * sinc(t * theta) / st;
    for (int k = 0; k < 4; ++k) out[k] = wa * a[k] + wb * b[k];
    normalize4(out);
}

void cj_quat_from_euler(const double angles[3], cj_euler_order order, double out[4]) {
    static const int seq[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    double q[4] = {1, 0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        const int ax = seq[order][i];
        double r[4] = {cos(0.5 * angles[ax]), 0, 0, 0};
        r[1 + ax] = sin(0.5 * angles[ax]);
        double tmp[4];
        cj_quat_mul(r, q, tmp); /* later rotations multiply on the left */
        for (int k = 0; k < 4; ++k) q[k] = tmp[k];
    }
    for (int k = 0; k < 4; ++k) out[k] = q[k];
}
