"""The arm state read in place from Pinocchio's data after ``crba`` and ``nonLinearEffects``:
the arrays at their addresses, the frame placements derived from the joint that carries
them."""

from __future__ import annotations

import numpy as np
from numba import carray, farray

from lightrocks.adapters.kernels.arm import sense, slow_tick, take_mass
from lightrocks.adapters.kernels.foreign import doubles_at
from lightrocks.adapters.kernels.jit import kernel
from lightrocks.adapters.kernels.layout import (
    ARM_DOF,
    BIAS,
    F_FT,
    F_TCP,
    FT_POS,
    FT_ROT,
    JAC,
    NV,
    P_J,
    P_JOINT_POS,
    P_JOINT_ROT,
    P_M,
    P_NLE,
    POS,
    ROT,
    SENSING,
    STATE,
    TWIST,
)


@kernel
def pinocchio_array(index: np.ndarray, what: int, size: int) -> np.ndarray:
    """One of Pinocchio's arrays (``index`` offsets P_*) in place, flat, column-major."""
    return carray(doubles_at(index[what]), size)


@kernel
def place_on_joint(
    joint_rot: np.ndarray,
    joint_pos: np.ndarray,
    placements: np.ndarray,
    f: int,
    out: np.ndarray,
    rot: int,
    pos: int,
) -> None:
    """World placement of a frame (its placement in its joint at ``placements[f:]``, as F_TCP)
    on its joint's placement (Pinocchio's: rotation column-major): rotation (row-major) into
    ``out[rot:]``, translation into ``out[pos:]``."""
    for r in range(3):
        total = 0.0
        for m in range(3):
            total += joint_rot[r + 3 * m] * placements[f + 9 + m]
        out[pos + r] = total + joint_pos[r]
        for c in range(3):
            total = 0.0
            for m in range(3):
                total += joint_rot[r + 3 * m] * placements[f + 3 * m + c]
            out[rot + 3 * r + c] = total


@kernel
def frame_placement(
    index: np.ndarray, frames: np.ndarray, f: int, out: np.ndarray, rot: int, pos: int
) -> None:
    """``place_on_joint`` for a frame on the joint at P_JOINT_ROT (``frames[f:]``, or the twin's
    T_HAND)."""
    joint_rot, joint_pos = (
        pinocchio_array(index, P_JOINT_ROT, 9),
        pinocchio_array(index, P_JOINT_POS, 3),
    )
    place_on_joint(joint_rot, joint_pos, frames, f, out, rot, pos)


@kernel
def pinocchio_sense(arm: np.ndarray, index: np.ndarray, frames: np.ndarray, wrist: bool) -> None:
    """The arm state from Pinocchio's results, read in place (``index``): the TCP and ft
    placements, the TCP's LOCAL_WORLD_ALIGNED Jacobian from the world-frame joint Jacobians
    (the arm joints carry the TCP), the nonlinear effects and on a ``slow_tick`` the mass terms;
    then with ``wrist`` the wrist sensing."""
    if slow_tick(arm):
        take_mass(arm, farray(doubles_at(index[P_M]), (NV, NV)), 0, True)
    frame_placement(index, frames, F_TCP, arm, ROT, POS)
    frame_placement(index, frames, F_FT, arm, FT_ROT, FT_POS)
    nle = pinocchio_array(index, P_NLE, NV)
    for j in range(ARM_DOF):
        arm[BIAS + j] = nle[j]
    joints = pinocchio_array(index, P_J, 6 * NV)
    px, py, pz = arm[POS], arm[POS + 1], arm[POS + 2]
    for c in range(ARM_DOF):  # the velocity of the TCP point: v + ω × p
        at = 6 * c
        wx, wy, wz = joints[at + 3], joints[at + 4], joints[at + 5]
        arm[JAC + c] = joints[at] + wy * pz - wz * py
        arm[JAC + ARM_DOF + c] = joints[at + 1] + wz * px - wx * pz
        arm[JAC + 2 * ARM_DOF + c] = joints[at + 2] + wx * py - wy * px
        arm[JAC + 3 * ARM_DOF + c] = wx
        arm[JAC + 4 * ARM_DOF + c] = wy
        arm[JAC + 5 * ARM_DOF + c] = wz
    for i in range(6):
        total = 0.0
        for c in range(ARM_DOF):
            total += arm[JAC + i * ARM_DOF + c] * arm[STATE + NV + c]
        arm[TWIST + i] = total
    if wrist:
        sense(arm, arm[SENSING:])
