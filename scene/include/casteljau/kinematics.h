/* casteljau: articulated chains and trees (seed 16.3) — forward kinematics and inverse
 * kinematics for one or more end effectors by damped least squares or the Jacobian transpose.
 *
 * A chain is up to CJ_CHAIN_MAX_JOINTS joints, each with one degree of freedom q_j:
 *   REVOLUTE   rotation by q_j (radians) about `axis` through the joint's origin;
 *   PRISMATIC  translation by q_j along `axis`.
 * Joint j's origin sits at `offset` in its parent's frame (the base frame for parent −1); a
 * parent must come earlier. Frames (R_j, p_j) in world coordinates, with (R_P, p_P) the
 * parent's (identity and the base position for the root):
 *   revolute:  R_j = R_P Rot(axis_j, q_j),  p_j = p_P + R_P offset_j
 *   prismatic: R_j = R_P,                   p_j = p_P + R_P (offset_j + q_j axis_j)
 * An end effector is a point `local` fixed in joint j's frame: x = p_j + R_j local.
 *
 * INVERSE KINEMATICS drives effectors e_i to targets g_i. With the stacked error
 * e = (g_i − x_i) ∈ R^{3m} and the Jacobian J (3m × n, column of joint k for effector i:
 * a_k × (x_i − p_k) for a revolute joint with world axis a_k = R_P axis_k, a_k for a prismatic
 * joint, 0 if k is not on the effector's path to the root), each iteration takes
 *   DLS        Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e           (LAPACKE dposv; λ = options.damping)
 *   TRANSPOSE  Δq = α Jᵀ e,  α = (e·J Jᵀ e)/|J Jᵀ e|²  (Buss's step for the transpose method)
 * scaled down to at most `max_step` (radians or lengths, in max-norm), then clamps q to the
 * joint limits [lo, hi]. A step that does not lower |e| is rejected and retried with λ² × 16
 * (DLS) or half the step (TRANSPOSE); an accepted one divides λ² by 9, down to 1e-12 of
 * damping² (Levenberg–Marquardt): far from the target or near a singular pose the damping
 * keeps steps bounded, near the solution it fades so the convergence is fast to `tol`. It stops
 * when |e| <= tol (REACHED), when the step no longer reduces |e| by a relative 1e-12 over
 * `stall_window` iterations (STALLED: the closest pose the method finds — an unreachable target
 * ends with the arm stretched towards it, never a NaN), or after max_iterations. Result: the
 * residual |e| (Euclidean, all effectors), the iterations, and the outcome. Status: CJ_OK when
 * reached; CJ_ERR_CAP when stalled or out of iterations (the closest pose found IS written to q and
 * result says which); bad input (nothing written): CJ_ERR_NONFINITE (a NaN target, offset, axis or
 * value, named), CJ_ERR_DEGENERATE (a zero axis, named), CJ_ERR_ARGUMENT (a parent that is not an
 * earlier joint, an effector on a joint that does not exist, more than CJ_IK_MAX_EFFECTORS
 * effectors, lo > hi, a value outside its limits), CJ_ERR_SINGULAR (DLS with damping 0 on a
 * singular pose).
 *
 * Everything is on the stack: no allocation.
 */
#ifndef CASTELJAU_KINEMATICS_H
#define CASTELJAU_KINEMATICS_H

#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CJ_CHAIN_MAX_JOINTS 64
#define CJ_IK_MAX_EFFECTORS 8

typedef enum cj_joint_kind { CJ_JOINT_REVOLUTE = 0, CJ_JOINT_PRISMATIC } cj_joint_kind;

typedef struct cj_joint {
    int parent; /* an earlier joint, or −1 */
    cj_joint_kind kind;
    double offset[3]; /* origin in the parent's frame */
    double axis[3];   /* rotation / translation axis in the parent's frame (normalised on use) */
    double lo, hi;    /* limits (may be ±INFINITY), lo <= hi */
} cj_joint;

typedef struct cj_chain {
    int count;
    double base[3]; /* world position of the root frame */
    cj_joint joints[CJ_CHAIN_MAX_JOINTS];
} cj_chain;

/* World frames of every joint: rotation R (row-major 3×3) and origin p. */
typedef struct cj_chain_pose {
    double R[CJ_CHAIN_MAX_JOINTS][9];
    double p[CJ_CHAIN_MAX_JOINTS][3];
} cj_chain_pose;

/* Validates the chain (see errors above) and the values q[count] (finite, within limits). */
cj_status cj_chain_check(const cj_chain *chain, const double *q);

/* Forward kinematics: the frames of every joint for the values q. */
cj_status cj_chain_fk(const cj_chain *chain, const double *q, cj_chain_pose *pose);

/* The world position of a point fixed in joint j's frame. */
void cj_chain_point(const cj_chain_pose *pose, int joint, const double local[3], double out[3]);

typedef struct cj_ik_effector {
    int joint;        /* the joint whose frame carries the effector */
    double local[3];  /* the effector point in that frame */
    double target[3]; /* where it should go (world) */
} cj_ik_effector;

typedef enum cj_ik_method { CJ_IK_DLS = 0, CJ_IK_TRANSPOSE } cj_ik_method;

typedef struct cj_ik_options {
    cj_ik_method method;
    double damping;     /* initial λ for DLS, a length (default 0.05) */
    double tol;         /* residual at which the target counts as reached (default 1e-10) */
    double max_step;    /* largest |Δq_k| per iteration (default 0.5) */
    int max_iterations; /* default 1000 (DLS), use ~1e5 for TRANSPOSE */
    int stall_window;   /* default 20 */
} cj_ik_options;

typedef enum cj_ik_outcome { CJ_IK_REACHED = 0, CJ_IK_STALLED, CJ_IK_MAX_ITERATIONS } cj_ik_outcome;

typedef struct cj_ik_result {
    cj_ik_outcome outcome;
    int iterations;
    double residual; /* |e| at the returned pose */
} cj_ik_result;

/* Defaults for a method (damping 0.05, tol 1e-10, max_step 0.5, 1000 or 100000 iterations,
 * stall window 20). */
cj_ik_options cj_ik_defaults(cj_ik_method method);

/* Solves from the values in q (the starting pose), writing the final pose back into q. */
cj_status cj_ik_solve(const cj_chain *chain, double *q, const cj_ik_effector *effectors,
                      size_t count, const cj_ik_options *options, cj_ik_result *result);

#ifdef __cplusplus
}
#endif
#endif
