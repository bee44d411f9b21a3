"""MuJoCo's side of a tick as native code: the motor commands before the step, and after it
the arm state read from MuJoCo's data (one flat view of ``mjData``) with MuJoCo's own
``mj_jacSite`` and ``mj_fullM`` called at their addresses."""

from __future__ import annotations

import numpy as np

from lightrocks.adapters.kernels.arm import sense, slow_tick, take_mass
from lightrocks.adapters.kernels.control import finger_push
from lightrocks.adapters.kernels.foreign import c_call
from lightrocks.adapters.kernels.jit import kernel
from lightrocks.adapters.kernels.layout import (
    ARM_DOF,
    BIAS,
    FT_POS,
    FT_ROT,
    JAC,
    M_BIAS,
    M_CTRL,
    M_DATA,
    M_FORCE,
    M_FT_XMAT,
    M_FT_XPOS,
    M_FULL_M,
    M_JAC_SITE,
    M_MODEL,
    M_NV,
    M_QPOS,
    M_QVEL,
    M_TCP,
    M_TCP_XMAT,
    M_TCP_XPOS,
    M_VADR,
    NV,
    POS,
    ROT,
    S_RAW,
    S_SENSOR_ROT,
    SENSING,
    STATE,
    TAU,
    TWIST,
)


@kernel
def mujoco_actuate(mj: np.ndarray, arm: np.ndarray, grip: float, index: np.ndarray) -> None:
    """Before a step: arm torques to the arm motors, each finger motor pushes with the grip
    force; and the ft site's rotation, at which the step computes the wrist sensors, is kept
    (the next ``mj_step1`` moves the site)."""
    ctrl, qpos, s = index[M_CTRL], index[M_QPOS], arm[SENSING:]
    for j in range(ARM_DOF):
        mj[ctrl + j] = arm[TAU + j]
    left, right = finger_push(grip, mj[qpos + ARM_DOF], mj[qpos + ARM_DOF + 1], 0.0)
    mj[ctrl + ARM_DOF], mj[ctrl + ARM_DOF + 1] = left, right
    for i in range(9):
        s[S_SENSOR_ROT + i] = mj[index[M_FT_XMAT] + i]


@kernel
def mujoco_sense(
    mj: np.ndarray,
    scratch: np.ndarray,
    index: np.ndarray,
    arm: np.ndarray,
    wrist: bool,
) -> None:
    """The arm state from MuJoCo's data after a step, with MuJoCo's ``mj_jacSite`` of the TCP
    (into ``scratch``, 6 x nv) and, on a ``slow_tick``, ``mj_fullM`` (into ``scratch`` after the
    Jacobians, nv x nv) for the mass terms; with ``wrist``, the raw wrist reading (see
    ``mujoco_actuate``) and ``sense``. MuJoCo's functions are called at their addresses in
    ``index``: one native call for all, where each call through the Python bindings costs
    ~0.5 µs. Neither can fail for valid ids (no allocation, no MuJoCo error)."""
    qpos, qvel, bias, va = index[M_QPOS], index[M_QVEL], index[M_BIAS], index[M_VADR]
    model, data = index[M_MODEL], index[M_DATA]
    nv = index[M_NV]
    jacobians = scratch[: 6 * nv].reshape(6, nv)
    at = scratch.ctypes.data
    c_call(index[M_JAC_SITE], (model, data, at, at + 8 * 3 * nv, index[M_TCP]))
    if slow_tick(arm):
        c_call(index[M_FULL_M], (model, data, at + 8 * 6 * nv))
        take_mass(arm, scratch[6 * nv :].reshape(nv, nv), va, False)
    for j in range(NV):
        arm[STATE + j] = mj[qpos + j]
        arm[STATE + NV + j] = mj[qvel + j]
    for i in range(3):
        arm[POS + i] = mj[index[M_TCP_XPOS] + i]
        arm[FT_POS + i] = mj[index[M_FT_XPOS] + i]
    for i in range(9):
        arm[ROT + i] = mj[index[M_TCP_XMAT] + i]
        arm[FT_ROT + i] = mj[index[M_FT_XMAT] + i]
    for j in range(ARM_DOF):
        arm[BIAS + j] = mj[bias + j]
    for i in range(6):
        total = 0.0
        for j in range(NV):
            total += jacobians[i, va + j] * arm[STATE + NV + j]
        arm[TWIST + i] = total
        for j in range(ARM_DOF):
            arm[JAC + i * ARM_DOF + j] = jacobians[i, va + j]
    if not wrist:
        return
    s, force = arm[SENSING:], index[M_FORCE]  # the wrist sensors (site frame) into world axes
    for b in range(2):
        for i in range(3):
            total = 0.0
            for m in range(3):
                total += mj[force + 3 * b + m] * s[S_SENSOR_ROT + 3 * i + m]
            s[S_RAW + 3 * b + i] = total
    sense(arm, s)
