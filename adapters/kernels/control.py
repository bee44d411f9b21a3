"""The controllers' tick as native code: Cartesian impedance (the controlled frame, the slow
terms every SLOW_EVERY ticks, the torque), joint impedance, and the fingers' drive."""

from __future__ import annotations

import math

import numpy as np

from lightrocks.adapters.kernels.jit import kernel
from lightrocks.adapters.kernels.layout import (
    ARM_DOF,
    BIAS,
    C_D,
    C_DP,
    C_DR,
    C_DURATION,
    C_ELAPSED,
    C_EROT,
    C_ERRORS,
    C_FRAME_JAC,
    C_FRAME_POS,
    C_FRAME_ROT,
    C_FRAME_TWIST,
    C_K,
    C_LOCAL,
    C_MOVING,
    C_NS_POSTURE,
    C_NS_STATE,
    C_OFFSET,
    C_P0,
    C_PGOAL,
    C_POSTURE,
    C_R0,
    C_RATIO,
    C_RGOAL,
    C_SCRATCH,
    C_TASK_P,
    C_TASK_R,
    C_TICKS,
    C_TWSET,
    DT,
    FINGER_TRAVEL,
    GRIPPER_BAND,
    J_DQ,
    J_DURATION,
    J_ELAPSED,
    J_K,
    J_Q0,
    J_RATIO,
    J_VSET,
    JAC,
    LAMBDA_REGULARISATION,
    MASS_DIAG,
    MASS_INV,
    NULLSPACE_DAMPING,
    NULLSPACE_STIFFNESS,
    NV,
    POS,
    ROT,
    SLOW_EVERY,
    STATE,
    TAU,
    TWIST,
)
from lightrocks.adapters.kernels.linalg import exp3, log3, spd_inverse


@kernel
def finger_push(grip: float, left: float, right: float, closed: float) -> tuple[float, float]:
    """Signed drive (> 0 opens) of each finger at positions ``left``, ``right``: ``|grip|``
    fading out linearly within GRIPPER_BAND of the target, ``closed`` if ``grip`` > 0 else
    fully open."""
    target = closed if grip > 0 else FINGER_TRAVEL
    size = abs(grip)
    return (
        size * min(max((target - left) / GRIPPER_BAND, -1.0), 1.0),
        size * min(max((target - right) / GRIPPER_BAND, -1.0), 1.0),
    )


@kernel
def cartesian_refresh(
    mass_inv: np.ndarray, jac: np.ndarray, rot: np.ndarray, c: np.ndarray
) -> None:
    """The slow terms of Cartesian impedance from the controlled frame's Jacobian and rotation
    and the inverse arm mass matrix: the damping ``D = 2 ζ sqrt(K Λ_ii)``
    with the diagonal of the operational-space inertia Λ = (J M⁻¹ Jᵀ)⁻¹ in task axes, and the
    dynamically consistent null-space projector ``N = I − Jᵀ J̄ᵀ``, ``J̄ = M⁻¹ Jᵀ Λ``, split into
    a constant posture torque and a matrix acting on the joint state."""
    mj = np.zeros((ARM_DOF, 6))  # M⁻¹ Jᵀ
    for i in range(ARM_DOF):
        for j in range(6):
            total = 0.0
            for m in range(ARM_DOF):
                total += mass_inv[i, m] * jac[j, m]
            mj[i, j] = total
    lam_inv = np.zeros((6, 6))
    for i in range(6):
        for j in range(6):
            total = 0.0
            for m in range(ARM_DOF):
                total += jac[i, m] * mj[m, j]
            lam_inv[i, j] = total
        lam_inv[i, i] += LAMBDA_REGULARISATION
    lam = np.zeros((6, 6))
    spd_inverse(lam_inv, lam)
    for b in range(2):  # the diagonal of diag(R, R)ᵀ Λ diag(R, R)
        for i in range(3):
            total = 0.0
            for m in range(3):
                for n in range(3):
                    total += rot[m, i] * lam[3 * b + m, 3 * b + n] * rot[n, i]
            axis = 3 * b + i
            c[C_D + axis] = 2.0 * c[C_RATIO + axis] * math.sqrt(c[C_K + axis] * max(total, 0.0))
    jbar = np.zeros((ARM_DOF, 6))
    for i in range(ARM_DOF):
        for j in range(6):
            total = 0.0
            for m in range(6):
                total += mj[i, m] * lam[m, j]
            jbar[i, j] = total
    ns = c[C_NS_STATE : C_NS_STATE + ARM_DOF * 2 * NV].reshape(ARM_DOF, 2 * NV)
    for i in range(ARM_DOF):
        posture = 0.0
        for j in range(ARM_DOF):
            total = 0.0
            for m in range(6):
                total += jac[m, i] * jbar[j, m]
            projector = (1.0 if i == j else 0.0) - total
            posture += projector * c[C_POSTURE + j]
            ns[i, j] = -NULLSPACE_STIFFNESS * projector
            ns[i, NV + j] = -NULLSPACE_DAMPING * projector
        c[C_NS_POSTURE + i] = NULLSPACE_STIFFNESS * posture


@kernel
def cartesian_frame(arm: np.ndarray, c: np.ndarray) -> None:
    """Pose, Jacobian and twist of the controlled frame ``tcp * task`` into ``c``, when the task
    frame is not the TCP (else the controller reads the arm state's). Flat row-major indexing
    throughout: a reshape costs a numba call."""
    for i in range(3):
        for j in range(3):
            total = 0.0
            for m in range(3):
                total += arm[ROT + 3 * i + m] * c[C_TASK_R + 3 * m + j]
            c[C_FRAME_ROT + 3 * i + j] = total
        total = 0.0
        for m in range(3):
            total += arm[ROT + 3 * i + m] * c[C_TASK_P + m]
        c[C_FRAME_POS + i] = total + arm[POS + i]
    dx = c[C_FRAME_POS] - arm[POS]
    dy = c[C_FRAME_POS + 1] - arm[POS + 1]
    dz = c[C_FRAME_POS + 2] - arm[POS + 2]
    jac, fjac = JAC, C_FRAME_JAC
    for j in range(ARM_DOF):  # linear rows -= skew(d) @ angular rows
        wx, wy, wz = arm[jac + 21 + j], arm[jac + 28 + j], arm[jac + 35 + j]
        c[fjac + j] = arm[jac + j] - (dy * wz - dz * wy)
        c[fjac + 7 + j] = arm[jac + 7 + j] - (dz * wx - dx * wz)
        c[fjac + 14 + j] = arm[jac + 14 + j] - (dx * wy - dy * wx)
        c[fjac + 21 + j], c[fjac + 28 + j], c[fjac + 35 + j] = wx, wy, wz
    for i in range(6):
        total = 0.0
        for j in range(ARM_DOF):
            total += c[fjac + ARM_DOF * i + j] * arm[STATE + NV + j]
        c[C_FRAME_TWIST + i] = total


@kernel
def cartesian_torque(arm: np.ndarray, c: np.ndarray) -> None:
    """One tick of Cartesian impedance (see adapters.control.CartesianImpedance) into the arm
    state's TAU; advances the set point by DT and refreshes the slow terms every SLOW_EVERY
    ticks."""
    duration, elapsed = c[C_DURATION], c[C_ELAPSED]
    s = 1.0 if duration <= 0 else min(elapsed / duration, 1.0)
    c[C_ELAPSED] = elapsed + DT
    moving = s < 1.0
    c[C_MOVING] = 1.0 if moving else 0.0
    if c[C_OFFSET] == 0.0:  # the controlled frame: the TCP, or computed into c
        f, rot, pos, jac, twist = arm, ROT, POS, JAC, TWIST
    else:
        cartesian_frame(arm, c)
        f, rot, pos = c, C_FRAME_ROT, C_FRAME_POS
        jac, twist = C_FRAME_JAC, C_FRAME_TWIST
    if c[C_TICKS] % SLOW_EVERY == 0:
        mass_inv = arm[MASS_INV : MASS_INV + ARM_DOF * ARM_DOF].reshape(ARM_DOF, ARM_DOF)
        jacobian = f[jac : jac + 6 * ARM_DOF].reshape(6, ARM_DOF)
        cartesian_refresh(mass_inv, jacobian, f[rot : rot + 9].reshape(3, 3), c)
    c[C_TICKS] += 1
    e, sc = C_ERRORS, C_SCRATCH  # errors: rows position, linear and angular velocity
    r_set, turn, error, normed, wrench, world = sc, sc + 9, sc + 18, sc + 27, sc + 36, sc + 42
    if moving:
        for i in range(3):
            c[e + i] = c[C_P0 + i] + s * c[C_DP + i] - f[pos + i]
        for i in range(6):
            c[e + 3 + i] = c[C_TWSET + i] - f[twist + i]
        exp3(s * c[C_DR], s * c[C_DR + 1], s * c[C_DR + 2], c[turn : turn + 9])
        for i in range(3):
            for j in range(3):
                total = 0.0
                for m in range(3):
                    total += c[C_R0 + 3 * i + m] * c[turn + 3 * m + j]
                c[r_set + 3 * i + j] = total
    else:
        for i in range(3):
            c[e + i] = c[C_PGOAL + i] - f[pos + i]
        for i in range(6):
            c[e + 3 + i] = -f[twist + i]
        for i in range(9):
            c[r_set + i] = c[C_RGOAL + i]
    for i in range(3):
        for j in range(3):
            total = 0.0  # row i of the errors in task axes: Rᵀ errors[i]
            for m in range(3):
                total += c[e + 3 * i + m] * f[rot + 3 * m + j]
            c[C_LOCAL + 3 * i + j] = total
            total = 0.0  # Rᵀ R_set
            for m in range(3):
                total += f[rot + 3 * m + i] * c[r_set + 3 * m + j]
            c[error + 3 * i + j] = total
    log3(c[error : error + 9], c[C_EROT : C_EROT + 3], c[normed : normed + 9])
    for i in range(3):  # K e + D ė in task axes, force then torque
        c[wrench + i] = c[C_K + i] * c[C_LOCAL + i] + c[C_D + i] * c[C_LOCAL + 3 + i]
        c[wrench + 3 + i] = c[C_K + 3 + i] * c[C_EROT + i] + c[C_D + 3 + i] * c[C_LOCAL + 6 + i]
    for b in range(2):  # back to world axes, per 3-block
        for i in range(3):
            total = 0.0
            for m in range(3):
                total += c[wrench + 3 * b + m] * f[rot + 3 * i + m]
            c[world + 3 * b + i] = total
    for j in range(ARM_DOF):
        total = 0.0
        for i in range(6):
            total += f[jac + ARM_DOF * i + j] * c[world + i]
        posture = 0.0
        for m in range(2 * NV):
            posture += c[C_NS_STATE + 2 * NV * j + m] * arm[STATE + m]
        arm[TAU + j] = total + arm[BIAS + j] + c[C_NS_POSTURE + j] + posture


@kernel
def joint_torque(arm: np.ndarray, c: np.ndarray) -> None:
    """One tick of joint impedance (see adapters.control.JointImpedance) into the arm state's
    TAU, with the damping ``2 ζ sqrt(K M_ii)`` of the current mass matrix."""
    duration, elapsed = c[J_DURATION], c[J_ELAPSED]
    s = 1.0 if duration <= 0 else min(elapsed / duration, 1.0)
    c[J_ELAPSED] = elapsed + DT
    for j in range(ARM_DOF):
        v_set = c[J_VSET + j] if s < 1.0 else 0.0
        error = c[J_Q0 + j] + s * c[J_DQ + j] - arm[STATE + j]
        damping = 2.0 * c[J_RATIO + j] * math.sqrt(c[J_K + j] * arm[MASS_DIAG + j])
        arm[TAU + j] = c[J_K + j] * error + damping * (v_set - arm[STATE + NV + j]) + arm[BIAS + j]
