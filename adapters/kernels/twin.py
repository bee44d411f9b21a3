"""The Pinocchio twin's step as native code: damping and torques, the broad phase around the
hand, the penalty contacts of the hand and finger corners against the boxes near, the
integration by a Cholesky solve with the arm block of the mass matrix, and the wrist
reading."""

from __future__ import annotations

import math

import numpy as np
from numba import carray

from lightrocks.adapters.kernels.control import finger_push
from lightrocks.adapters.kernels.foreign import doubles_at
from lightrocks.adapters.kernels.jit import kernel
from lightrocks.adapters.kernels.layout import (
    ARM_DOF,
    B_COUNT,
    B_HEADER,
    B_INTS,
    B_PLACEMENT,
    B_POS,
    B_ROT,
    B_START,
    B_SUPPORT,
    BOX_CENTRE,
    BOX_HALF,
    BOX_NEAR,
    BOX_ROT,
    DT,
    F_FT,
    NV,
    P_J,
    P_M,
    P_NLE,
    S_RAW,
    SENSING,
    STATE,
    T_ACCELERATION,
    T_BODY,
    T_BOX,
    T_BOXES,
    T_CONTACT,
    T_CONTACT_DAMPING,
    T_DAMPING,
    T_FRICTION,
    T_GENERALIZED,
    T_HAND,
    T_LOAD,
    T_LOAD_COM,
    T_LOW,
    T_PLACEMENT,
    T_SLIP,
    T_STIFFNESS,
    T_TORQUE_LIMIT,
    TAU,
)
from lightrocks.adapters.kernels.linalg import cholesky, cholesky_solve
from lightrocks.adapters.kernels.pinocchio_tick import (
    frame_placement,
    pinocchio_array,
    place_on_joint,
)


@kernel
def twin_step(
    arm: np.ndarray,
    twin: np.ndarray,
    index: np.ndarray,
    frames: np.ndarray,
    finger_speed: float,
    grasp: float,
    alone: bool,
) -> int:
    """A twin step as far as native code goes: generalized forces ``−damping q̇ + τ`` (τ
    clamped to the motors' torque limits), no contact yet, and the static boxes whose reach
    holds the hand origin flagged. With none and the arm ``alone`` (no fixture twin to step),
    the whole step (``twin_integrate``), and returns -1; otherwise returns how many boxes are
    near, and the caller adds the interactions and integrates."""
    for j in range(NV):
        twin[T_GENERALIZED + j] = twin[T_DAMPING + j] * arm[STATE + NV + j]
    for j in range(ARM_DOF):
        limit = twin[T_TORQUE_LIMIT + j]
        twin[T_GENERALIZED + j] += min(max(arm[TAU + j], -limit), limit)
    for i in range(6):
        twin[T_CONTACT + i] = 0.0
    frame_placement(index, twin, T_HAND, twin, T_PLACEMENT, T_PLACEMENT + 9)
    x, y, z = twin[T_PLACEMENT + 9], twin[T_PLACEMENT + 10], twin[T_PLACEMENT + 11]
    near = 0
    for b in range(T_BOXES, twin.shape[0], T_BOX):
        inside = twin[b] < x < twin[b + 3] and twin[b + 1] < y < twin[b + 4]
        inside = inside and twin[b + 2] < z < twin[b + 5]
        twin[b + BOX_NEAR] = 1.0 if inside else 0.0
        near += inside
    if near or not alone:
        return near
    twin_integrate(arm, twin, index, frames, finger_speed, grasp, False, False)
    return -1


@kernel
def twin_contacts(
    arm: np.ndarray,
    twin: np.ndarray,
    index: np.ndarray,
    frames: np.ndarray,
    links: np.ndarray,
    bodies: np.ndarray,
) -> int:
    """Penalty contacts of the contact bodies' points against the static boxes flagged near:
    a point inside a box is pushed out through the nearest face (spring-damper) with
    regularised Coulomb friction; the forces go into the generalized forces (through the
    point's Jacobian) and the contact wrench at the ft site. Returns which fingers touch a box
    (bit 0: the first, bit 1: the second)."""
    joints = pinocchio_array(index, P_J, 6 * NV)
    frame_placement(index, frames, F_FT, twin, T_PLACEMENT, T_PLACEMENT + 9)
    ft = twin[T_PLACEMENT + 9 : T_PLACEMENT + 12]
    stiffness, damping = twin[T_STIFFNESS], twin[T_CONTACT_DAMPING]
    friction, slip_full = twin[T_FRICTION], twin[T_SLIP]
    place = twin[T_BODY : T_BODY + 12]
    jac = np.empty((3, NV))
    blocked = 0
    for body in range(links.shape[0] // B_INTS):
        link = links[B_INTS * body : B_INTS * body + B_INTS]
        joint_rot = carray(doubles_at(link[B_ROT]), 9)
        joint_pos = carray(doubles_at(link[B_POS]), 3)
        place_on_joint(
            joint_rot, joint_pos, bodies, B_HEADER * body + B_PLACEMENT, twin, T_BODY, T_BODY + 9
        )
        support = B_HEADER * body + B_SUPPORT
        for b in range(T_BOXES, twin.shape[0], T_BOX):
            if twin[b + BOX_NEAR] == 0.0:
                continue
            box_rot, centre, half = b + BOX_ROT, b + BOX_CENTRE, b + BOX_HALF
            for point in range(link[B_COUNT]):
                at = link[B_START] + 3 * point
                lx, ly, lz = bodies[at], bodies[at + 1], bodies[at + 2]
                wx = place[0] * lx + place[1] * ly + place[2] * lz + place[9]
                wy = place[3] * lx + place[4] * ly + place[5] * lz + place[10]
                wz = place[6] * lx + place[7] * ly + place[8] * lz + place[11]
                ex, ey, ez = wx - twin[centre], wy - twin[centre + 1], wz - twin[centre + 2]
                inside = (
                    twin[box_rot] * ex + twin[box_rot + 3] * ey + twin[box_rot + 6] * ez,
                    twin[box_rot + 1] * ex + twin[box_rot + 4] * ey + twin[box_rot + 7] * ez,
                    twin[box_rot + 2] * ex + twin[box_rot + 5] * ey + twin[box_rot + 8] * ez,
                )
                depth = (
                    twin[half] - abs(inside[0]),
                    twin[half + 1] - abs(inside[1]),
                    twin[half + 2] - abs(inside[2]),
                )
                if depth[0] <= 0 or depth[1] <= 0 or depth[2] <= 0:
                    continue
                axis = 0
                for i in range(1, 3):
                    if depth[i] < depth[axis]:
                        axis = i
                side = 1.0 if inside[axis] > 0 else (-1.0 if inside[axis] < 0 else 0.0)
                normal = np.empty(3)
                for i in range(3):
                    normal[i] = twin[box_rot + 3 * i + axis] * side
                velocity = np.zeros(3)
                for c in range(NV):  # the point's Jacobian: v + ω × point, moving columns
                    col = 6 * c
                    ox, oy, oz = joints[col + 3], joints[col + 4], joints[col + 5]
                    move = bodies[support + c]
                    jac[0, c] = move * (joints[col] + oy * wz - oz * wy)
                    jac[1, c] = move * (joints[col + 1] + oz * wx - ox * wz)
                    jac[2, c] = move * (joints[col + 2] + ox * wy - oy * wx)
                    for i in range(3):
                        velocity[i] += jac[i, c] * arm[STATE + NV + c]
                normal_speed = normal[0] * velocity[0]
                normal_speed += normal[1] * velocity[1] + normal[2] * velocity[2]
                pressure = max(stiffness * depth[axis] - damping * normal_speed, 0.0)
                slip = np.empty(3)
                for i in range(3):
                    slip[i] = velocity[i] - normal_speed * normal[i]
                slip_speed = math.sqrt(slip[0] ** 2 + slip[1] ** 2 + slip[2] ** 2)
                scale = 0.0
                if slip_speed > 0:
                    scale = -friction * pressure * min(slip_speed / slip_full, 1.0) / slip_speed
                force = np.empty(3)
                for i in range(3):
                    force[i] = pressure * normal[i] + scale * slip[i]
                for c in range(NV):
                    total = 0.0
                    for i in range(3):
                        total += jac[i, c] * force[i]
                    twin[T_GENERALIZED + c] += total
                dx, dy, dz = wx - ft[0], wy - ft[1], wz - ft[2]
                fx, fy, fz = force[0], force[1], force[2]
                twin[T_CONTACT] += fx
                twin[T_CONTACT + 1] += fy
                twin[T_CONTACT + 2] += fz
                twin[T_CONTACT + 3] += dy * fz - dz * fy
                twin[T_CONTACT + 4] += dz * fx - dx * fz
                twin[T_CONTACT + 5] += dx * fy - dy * fx
                if body > 0:
                    blocked |= 1 << (body - 1)
    return blocked


@kernel
def twin_integrate(
    arm: np.ndarray,
    twin: np.ndarray,
    index: np.ndarray,
    frames: np.ndarray,
    finger_speed: float,
    grasp: float,
    left_blocked: bool,
    right_blocked: bool,
) -> None:
    """End of a twin step: the arm's accelerations from ``M a = forces − h`` (the arm block of
    Pinocchio's mass matrix and its nonlinear effects, of the step's start), semi-implicit Euler
    of the arm joints, the first-order fingers (``finger_speed`` = grip force / finger damping;
    a blocked finger does not close), and ``twin_wrist`` (ft pose of the step's start)."""
    mass = pinocchio_array(index, P_M, NV * NV)
    nle = pinocchio_array(index, P_NLE, NV)
    low = twin[T_LOW:T_ACCELERATION].reshape(ARM_DOF, ARM_DOF)
    for i in range(ARM_DOF):  # the lower triangle, from Pinocchio's upper one
        for j in range(i + 1):
            low[i, j] = mass[j + NV * i]
    cholesky(low, low)
    acceleration = twin[T_ACCELERATION:T_PLACEMENT]
    for j in range(ARM_DOF):
        acceleration[j] = twin[T_GENERALIZED + j] - nle[j]
    cholesky_solve(low, acceleration)
    for j in range(ARM_DOF):
        arm[STATE + NV + j] += DT * acceleration[j]
        arm[STATE + j] += DT * arm[STATE + NV + j]
    left, right = finger_push(finger_speed, arm[STATE + ARM_DOF], arm[STATE + ARM_DOF + 1], grasp)
    if left_blocked and left < 0:
        left = 0.0
    if right_blocked and right < 0:
        right = 0.0
    arm[STATE + NV + ARM_DOF], arm[STATE + NV + ARM_DOF + 1] = left, right
    arm[STATE + ARM_DOF] += DT * left
    arm[STATE + ARM_DOF + 1] += DT * right
    twin_wrist(arm, twin, index, frames)


@kernel
def twin_wrist(arm: np.ndarray, twin: np.ndarray, index: np.ndarray, frames: np.ndarray) -> None:
    """The twin's quasi-static wrist reading into the arm state's sensing: what link7 must
    exert to hold the load against the contacts, at the ft pose in Pinocchio's data."""
    s = arm[SENSING:]
    frame_placement(index, frames, F_FT, twin, T_PLACEMENT, T_PLACEMENT + 9)
    ft = twin[T_PLACEMENT : T_PLACEMENT + 9]
    com = twin[T_LOAD_COM : T_LOAD_COM + 3]
    lx = ft[0] * com[0] + ft[1] * com[1] + ft[2] * com[2]
    ly = ft[3] * com[0] + ft[4] * com[1] + ft[5] * com[2]
    lz = ft[6] * com[0] + ft[7] * com[1] + ft[8] * com[2]
    wx, wy, wz = twin[T_LOAD], twin[T_LOAD + 1], twin[T_LOAD + 2]
    c = twin[T_CONTACT : T_CONTACT + 6]
    s[S_RAW] = -c[0] - wx
    s[S_RAW + 1] = -c[1] - wy
    s[S_RAW + 2] = -c[2] - wz
    s[S_RAW + 3] = -c[3] - (ly * wz - lz * wy)
    s[S_RAW + 4] = -c[4] - (lz * wx - lx * wz)
    s[S_RAW + 5] = -c[5] - (lx * wy - ly * wx)
