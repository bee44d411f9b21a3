"""The arithmetic of the 1 kHz tick as native code (numba), one call per phase of a tick.

In Python every NumPy or Pinocchio call costs a fixed ~0.5 µs whatever the size of its
arrays, and the controller, the arm state and the wrist sensing needed about 40 of them per
tick, four times the cost of the physics step itself. Here each phase is one compiled
function over preallocated flat buffers: the controller (``cartesian_torque``,
``joint_torque``), the motor commands (``mujoco_actuate``) and the state and sensing after a
step (``mujoco_sense``, ``pinocchio_sense``; the twin's ``twin_step``, ``twin_contacts`` and
``twin_integrate``). Each buffer has a fixed layout (``layout``); the Python objects
that own a buffer expose named views of it, so everything outside the tick reads arrays as
before.

This module is the kernels' one namespace (``from lightrocks.adapters import kernels as k``;
``k.POS``, ``k.cartesian_torque``) over the modules that hold them by job: ``layout``,
``linalg``, ``control``, ``arm``, ``mujoco_tick``, ``pinocchio_tick``,
``twin``, ``foreign``; ``jit`` caches them, keyed on all of them. A cold
start compiles for ~10 s; later starts load in ~0.2 s (``warm_up``).
"""

from __future__ import annotations

import numpy as np

from lightrocks.adapters.kernels.arm import sense as sense
from lightrocks.adapters.kernels.arm import slow_tick as slow_tick
from lightrocks.adapters.kernels.arm import take_mass as take_mass
from lightrocks.adapters.kernels.control import cartesian_frame as cartesian_frame
from lightrocks.adapters.kernels.control import cartesian_refresh as cartesian_refresh
from lightrocks.adapters.kernels.control import cartesian_torque as cartesian_torque
from lightrocks.adapters.kernels.control import finger_push as finger_push
from lightrocks.adapters.kernels.control import joint_torque as joint_torque
from lightrocks.adapters.kernels.layout import *  # noqa: F403 (the buffer layouts, as k.POS)
from lightrocks.adapters.kernels.layout import (
    ARM_SIZE,
    CARTESIAN_SIZE,
    FRAMES_SIZE,
    JOINT_SIZE,
    M_SIZE,
    NV,
    T_BOX,
    TWIN_SIZE,
)
from lightrocks.adapters.kernels.linalg import cholesky as cholesky
from lightrocks.adapters.kernels.linalg import cholesky_solve as cholesky_solve
from lightrocks.adapters.kernels.linalg import exp3 as exp3
from lightrocks.adapters.kernels.linalg import log3 as log3
from lightrocks.adapters.kernels.linalg import spd_inverse as spd_inverse
from lightrocks.adapters.kernels.mujoco_tick import mujoco_actuate as mujoco_actuate
from lightrocks.adapters.kernels.mujoco_tick import mujoco_sense as mujoco_sense
from lightrocks.adapters.kernels.pinocchio_tick import pinocchio_sense as pinocchio_sense
from lightrocks.adapters.kernels.twin import twin_contacts as twin_contacts
from lightrocks.adapters.kernels.twin import twin_integrate as twin_integrate
from lightrocks.adapters.kernels.twin import twin_step as twin_step
from lightrocks.adapters.kernels.twin import twin_wrist as twin_wrist


def warm_up() -> None:
    """Compile (or load from the cache) every kernel now, on scratch buffers, so that the
    first command does not pay for it inside its control loop."""
    arm, cartesian = np.zeros(ARM_SIZE), np.zeros(CARTESIAN_SIZE)
    cartesian_torque(arm, cartesian)
    joint_torque(arm, np.zeros(JOINT_SIZE))
    mj, index = np.zeros(4 * NV), np.zeros(M_SIZE, dtype=np.int64)
    mujoco_actuate(mj, arm, 1.0, index)
    # stand-ins for Pinocchio's data (P_J … P_JOINT_POS), alive while the functions read them
    stand_ins = (np.zeros(6 * NV), np.zeros(NV), np.eye(NV).reshape(-1), np.eye(3).reshape(-1))
    stand_ins += (np.zeros(3),)
    index = np.array([a.ctypes.data for a in stand_ins], dtype=np.int64)
    frames = np.zeros(FRAMES_SIZE)
    pinocchio_sense(arm, index, frames, True)
    twin = np.zeros(TWIN_SIZE + T_BOX)
    twin_step(arm, twin, index, frames, 0.1, 0.0, True)
    twin_contacts(arm, twin, index, frames, np.zeros(0, dtype=np.int64), np.zeros(0))


def warm_up_mujoco(mj: np.ndarray, scratch: np.ndarray, index: np.ndarray) -> None:
    """Compile (or load) ``mujoco_sense``, which calls MuJoCo: on a plant's real arguments,
    whose arm state it leaves alone (a scratch arm buffer)."""
    mujoco_sense(mj, scratch, index, np.zeros(ARM_SIZE), True)
