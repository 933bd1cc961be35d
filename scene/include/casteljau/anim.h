/* casteljau: keyframe channels (seed 16.2) — values of dimension 1..4 or unit quaternions at
 * key times, interpolated by the library's cubic splines.
 *
 * A channel holds N >= 1 keys (time t_j, value v_j) with strictly increasing finite times
 * (negative times are refused: an animation starts at 0). Every vector interpolation becomes
 * N−1 CUBIC BÉZIER SEGMENTS built by the curve core (casteljau/catmull_rom.h) and evaluated by
 * de Casteljau (casteljau/bezier.h): segment j covers [t_j, t_{j+1}], traversed linearly in time,
 *
 *     v(t) = c_j(u),   u = (t − t_j)/(t_{j+1} − t_j),   c_j(u) = Σ b_{j,i} B_i^3(u).
 *
 * Control points b_{j,0..3} per interpolation (Δ_j = t_{j+1} − t_j):
 *   STEP         v_j, v_j, v_j, v_j (v(t) = v_j on [t_j, t_{j+1}); t_{N−1} and later: v_{N−1})
 *   LINEAR       v_j, (2v_j + v_{j+1})/3, (v_j + 2v_{j+1})/3, v_{j+1}
 *   CATMULL_ROM  cj_catmull_rom() on the values with tension κ (seed eq. 126): the spline is the
 *                seed's uniform one (one key = one knot), so it is C¹ in time only where the keys
 *                are evenly spaced; CENTRIPETAL likewise with knots |Δv|^½ (α = ½, no cusps).
 *   KOCHANEK_BARTELS   cj_catmull_rom() with tension T, continuity C and bias B.
 *   HERMITE      cj_hermite_spline() with the given tangents dv/dt at the key times:
 *                v_j, v_j + Δ_j m_j/3, v_{j+1} − Δ_j m_{j+1}/3, v_{j+1} (C¹ in time).
 *   BEZIER_AUTO  Blender-style auto-clamped handles, per coordinate: the slope at an interior
 *                key is the three-point estimate m_j = (Δ_j s_{j−1} + Δ_{j−1} s_j)/(Δ_{j−1} + Δ_j)
 *                of the secants s_j = (v_{j+1} − v_j)/Δ_j, set to 0 at a local extremum
 *                (s_{j−1} s_j <= 0) and at the two end keys, and clamped to
 *                |m_j| <= 3 min(|s_{j−1}|, |s_j|), so that both handles of a segment lie between
 *                its end values: by the convex-hull property the curve NEVER OVERSHOOTS its keys
 *                (each segment stays within [min, max] of its two end values, and is monotone).
 *   GLTF_CUBIC   glTF 2.0 CUBICSPLINE: per key an in-tangent a_j and out-tangent b_j (given in
 *                `tangents` as 2·N·dim numbers: a_0, b_0, a_1, b_1, ...), segment
 *                v_j, v_j + Δ_j b_j/3, v_{j+1} − Δ_j a_{j+1}/3, v_{j+1}, which is the
 *                specification's Hermite form p(s) = (2s³−3s²+1)v_j + (s³−2s²+s)Δ_j b_j +
 *                (−2s³+3s²)v_{j+1} + (s³−s²)Δ_j a_{j+1}.
 * Outside [t_0, t_{N−1}] the value is clamped to the first/last key (as glTF players do).
 *
 * QUATERNION channels (rotations; keys (w, x, y, z), normalised on creation, a zero quaternion is
 * refused). Consecutive keys are sign-aligned on creation (q_{j+1} := −q_{j+1} when q_j·q_{j+1} <
 * 0) so every interpolation takes the SHORTEST ARC. STEP holds q_j; LINEAR is slerp (cj_quat_slerp,
 * the glTF LINEAR rotation sampler); SQUAD is Shoemake's spherical cubic with the inner
 * quadrangle points s_j = q_j exp(−(log(q_j⁻¹q_{j+1}) + log(q_j⁻¹q_{j−1}))/4) (ends: s_j = q_j);
 * GLTF_CUBIC is the component-wise cubic above followed by normalisation (glTF 2.0 text).
 * Results are unit quaternions.
 *
 * EULER angles: a dimension-3 vector channel of angles in radians whose `euler_order` says how to
 * compose them; cj_channel_eval_quat() converts (cj_quat_from_euler).
 *
 * OWNERSHIP: cj_channel_create() copies the keys and builds the segments (one allocation,
 * through the optional allocator); cj_channel_eval() allocates nothing and is safe to call from
 * several threads on the same channel.
 *
 * Errors (nothing created): a time that is NaN/Inf, negative, or not strictly after the previous
 * key's: CJ_ERR_NONFINITE / CJ_ERR_RANGE / CJ_ERR_ARGUMENT with a message naming the key
 * ("key 3: time 0.5 is not after key 2's time 0.75"); a non-finite value or tangent:
 * CJ_ERR_NONFINITE naming the key and coordinate; N = 0: CJ_ERR_EMPTY; dimension outside 1..4
 * (4 for quaternions, 3 for Euler): CJ_ERR_DIMENSION; tangents missing where required, an
 * interpolation that does not apply to the kind (centripetal on quaternions), a zero
 * quaternion: CJ_ERR_ARGUMENT; CENTRIPETAL with two equal consecutive values:
 * CJ_ERR_DEGENERATE (its knot spacing would vanish). Evaluation at a NaN time: CJ_ERR_NONFINITE.
 */
#ifndef CASTELJAU_ANIM_H
#define CASTELJAU_ANIM_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CJ_CHANNEL_MAX_DIM 4

typedef enum cj_interp {
    CJ_INTERP_STEP = 0,
    CJ_INTERP_LINEAR,           /* vectors: lerp; quaternions: slerp */
    CJ_INTERP_CATMULL_ROM,      /* tension κ */
    CJ_INTERP_CENTRIPETAL,      /* tension κ, knots |Δv|^½ */
    CJ_INTERP_KOCHANEK_BARTELS, /* T, C, B */
    CJ_INTERP_HERMITE,          /* given tangents dv/dt, N·dim numbers */
    CJ_INTERP_BEZIER_AUTO,      /* auto-clamped handles, no overshoot */
    CJ_INTERP_GLTF_CUBIC,       /* glTF CUBICSPLINE, in/out tangents 2·N·dim numbers */
    CJ_INTERP_SQUAD             /* quaternions only */
} cj_interp;

typedef enum cj_channel_kind {
    CJ_CHANNEL_VECTOR = 0, /* dim 1..4 */
    CJ_CHANNEL_QUATERNION, /* dim 4: (w, x, y, z) */
    CJ_CHANNEL_EULER       /* dim 3: angles (radians) about the axes named by euler_order */
} cj_channel_kind;

/* The order in which Euler angles are applied: CJ_EULER_XYZ rotates about x first, then y, then
 * z (fixed world axes), i.e. R = Rz(a2) Ry(a1) Rx(a0) with angles (a0, a1, a2) = (x, y, z). */
typedef enum cj_euler_order {
    CJ_EULER_XYZ = 0,
    CJ_EULER_XZY,
    CJ_EULER_YXZ,
    CJ_EULER_YZX,
    CJ_EULER_ZXY,
    CJ_EULER_ZYX
} cj_euler_order;

typedef struct cj_channel_desc {
    cj_channel_kind kind;
    cj_interp interp;
    int dim;                /* 1..4 (vectors), 4 (quaternions), 3 (Euler) */
    size_t count;           /* keys */
    const double *times;    /* count strictly increasing times >= 0 */
    const double *values;   /* count × dim, key-major */
    const double *tangents; /* HERMITE: count × dim; GLTF_CUBIC: count × 2 × dim (in, out) */
    double tension;         /* κ (CATMULL_ROM, CENTRIPETAL; 0.5 classic) or T (KB) */
    double continuity;      /* C (KB) */
    double bias;            /* B (KB) */
    cj_euler_order euler_order;
} cj_channel_desc;

/* A zeroed description with tension 0.5 and the given kind, interpolation and dimension. */
cj_channel_desc cj_channel_desc_make(cj_channel_kind kind, cj_interp interp, int dim);

typedef struct cj_channel cj_channel;

/* Validates the description, copies the keys and builds the segments (errors: see above). */
cj_status cj_channel_create(const cj_channel_desc *desc, const cj_allocator *alloc,
                            cj_channel **out);
void cj_channel_destroy(cj_channel *ch);

int cj_channel_dim(const cj_channel *ch);
cj_channel_kind cj_channel_kind_of(const cj_channel *ch);
/* First and last key times. */
void cj_channel_range(const cj_channel *ch, double *t0, double *t1);

/* The value at time t into out[dim] (quaternion channels: a unit (w, x, y, z); Euler channels:
 * the three angles). NaN/Inf t: CJ_ERR_NONFINITE, out untouched. */
cj_status cj_channel_eval(const cj_channel *ch, double t, double *out);

/* Rotation channels as a unit quaternion: quaternion channels as cj_channel_eval, Euler channels
 * converted with their order. Other channels: CJ_ERR_ARGUMENT. */
cj_status cj_channel_eval_quat(const cj_channel *ch, double t, double q[4]);

/* Vector channels: the Bézier segments (count−1 of them, 4·dim doubles each, as
 * casteljau/catmull_rom.h lays them out), so that a caller can flatten or draw the curve.
 * *nsegs receives count − 1 (0 for a one-key channel, whose value is constant). Quaternion
 * channels other than GLTF_CUBIC have no segments (NULL, 0). */
const double *cj_channel_segments(const cj_channel *ch, size_t *nsegs);

/* ---- quaternions: (w, x, y, z), Hamilton product, rotation of v is q v q* ------------------ */

/* q = a b (apply b first, then a). */
void cj_quat_mul(const double a[4], const double b[4], double out[4]);
/* The unit quaternion of the rotation by `angle` radians about `axis` (normalised here; a
 * zero or non-finite axis is CJ_ERR_DEGENERATE / CJ_ERR_NONFINITE). */
cj_status cj_quat_from_axis_angle(const double axis[3], double angle, double out[4]);
/* Rotation of v by the unit quaternion q. */
void cj_quat_rotate(const double q[4], const double v[3], double out[3]);
/* Spherical linear interpolation of unit quaternions along the SHORTER arc (b is negated first
 * when a·b < 0), t in [0,1] (other t extrapolate along the great circle):
 *     slerp(a, b, t) = sin((1−t)θ)/sin θ a + sin(tθ)/sin θ b,   θ = angle between a and ±b,
 * with θ computed as 2 atan2(|a − b|, |a + b|) (accurate for every θ, unlike acos of the dot) and
 * the weights written as (1−t) sinc((1−t)θ)/sinc θ and t sinc(tθ)/sinc θ with a series sinc near
 * 0, so that identical or nearly identical keys interpolate smoothly with no division by ~0.
 * The result is renormalised. */
void cj_quat_slerp(const double a[4], const double b[4], double t, double out[4]);
/* The quaternion of Euler angles (radians) applied in the given order (see cj_euler_order). */
void cj_quat_from_euler(const double angles[3], cj_euler_order order, double out[4]);

#ifdef __cplusplus
}
#endif
#endif
