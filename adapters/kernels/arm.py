"""The arm state after a step, shared by both plants: the mass terms every SLOW_EVERY ticks
and the wrist sensing with the motion sensors (``peakForce``, ``turned``)."""

from __future__ import annotations

import math

import numpy as np

from lightrocks.adapters.kernels.jit import kernel
from lightrocks.adapters.kernels.layout import (
    ARM_DOF,
    FT_POS,
    FT_ROT,
    MASS_DIAG,
    MASS_INV,
    POS,
    ROT,
    S_ALPHA,
    S_LOAD_COM,
    S_OFFSET,
    S_PEAK,
    S_R0,
    S_RAW,
    S_TURNED,
    S_VALUES,
    S_WEIGHT,
    S_YAW,
    SLOW_EVERY,
    TICKS,
)
from lightrocks.adapters.kernels.linalg import spd_inverse


@kernel
def take_mass(arm: np.ndarray, mass: np.ndarray, first: int, upper: bool) -> None:
    """The arm block (at dof ``first``) of a mass matrix: its inverse and diagonal into the arm
    state; with ``upper``, only the upper triangle of ``mass`` is filled (Pinocchio's crba)."""
    block = np.empty((ARM_DOF, ARM_DOF))
    for i in range(ARM_DOF):
        for j in range(ARM_DOF):
            low, high = (j, i) if upper and i > j else (i, j)
            block[i, j] = mass[first + low, first + high]
        arm[MASS_DIAG + i] = block[i, i]
    spd_inverse(block, arm[MASS_INV : MASS_INV + ARM_DOF * ARM_DOF].reshape(ARM_DOF, ARM_DOF))


@kernel
def sense(arm: np.ndarray, s: np.ndarray) -> None:
    """Wrist sensing (adapters.sensing) of the raw reading in ``s``, then the peak force and
    the TCP's turn about its own z since command start (unwrapped)."""
    com, r = S_LOAD_COM, FT_ROT  # the load's lever: ft rotation @ centre of mass
    lx = arm[r] * s[com] + arm[r + 1] * s[com + 1] + arm[r + 2] * s[com + 2]
    ly = arm[r + 3] * s[com] + arm[r + 4] * s[com + 1] + arm[r + 5] * s[com + 2]
    lz = arm[r + 6] * s[com] + arm[r + 7] * s[com + 1] + arm[r + 8] * s[com + 2]
    wx, wy, wz = s[S_WEIGHT], s[S_WEIGHT + 1], s[S_WEIGHT + 2]
    fx = -s[S_RAW] - s[S_OFFSET] - wx
    fy = -s[S_RAW + 1] - s[S_OFFSET + 1] - wy
    fz = -s[S_RAW + 2] - s[S_OFFSET + 2] - wz
    tx = -s[S_RAW + 3] - s[S_OFFSET + 3] - (ly * wz - lz * wy)
    ty = -s[S_RAW + 4] - s[S_OFFSET + 4] - (lz * wx - lx * wz)
    tz = -s[S_RAW + 5] - s[S_OFFSET + 5] - (lx * wy - ly * wx)
    dx, dy, dz = (
        arm[FT_POS] - arm[POS],
        arm[FT_POS + 1] - arm[POS + 1],
        arm[FT_POS + 2] - arm[POS + 2],
    )
    tx += dy * fz - dz * fy
    ty += dz * fx - dx * fz
    tz += dx * fy - dy * fx
    a = s[S_ALPHA]
    new = (fx, fy, fz, tx, ty, tz)
    for i in range(6):
        s[S_VALUES + i] = s[S_VALUES + i] + (new[i] - s[S_VALUES + i]) * a
    vx, vy, vz = s[S_VALUES], s[S_VALUES + 1], s[S_VALUES + 2]
    s[S_PEAK] = max(s[S_PEAK], math.sqrt(vx * vx + vy * vy + vz * vz))
    c0, c1, c2 = arm[ROT], arm[ROT + 3], arm[ROT + 6]
    cos = c0 * s[S_R0] + c1 * s[S_R0 + 3] + c2 * s[S_R0 + 6]  # first column of R₀ᵀ R
    sin = c0 * s[S_R0 + 1] + c1 * s[S_R0 + 4] + c2 * s[S_R0 + 7]
    yaw = math.atan2(sin, cos)
    s[S_TURNED] += (yaw - s[S_YAW] + math.pi) % (2 * math.pi) - math.pi
    s[S_YAW] = yaw


@kernel
def slow_tick(arm: np.ndarray) -> bool:
    """Counts a read of the plant's state; whether it refreshes the mass terms."""
    ticks = arm[TICKS] + 1.0
    arm[TICKS] = ticks
    return ticks % SLOW_EVERY == 1
