"""The arm state read from MuJoCo's own computation of the current state.

The plant runs each step in two halves (``mj_step2``, then ``mj_step1`` of the next step), so
after a tick MuJoCo has already computed the kinematics, the mass matrix and the bias forces
of the state it just reached. Reading them is one native call (adapters.kernels.mujoco_sense):
it calls MuJoCo's ``mj_jacSite`` (and ``mj_fullM`` every SLOW_EVERY ticks) at their addresses,
copies the results into the arm state and does the wrist sensing; computing them again with
Pinocchio cost a dozen library calls per tick.
"""

from __future__ import annotations

import mujoco
import numpy as np

from lightrocks.adapters import kernels as k
from lightrocks.adapters.arm import ArmState


class MujocoArm(ArmState):
    """The robot's joints (arm, then fingers, contiguous) in ``data``, read through the
    plant's flat view ``mj`` of it at the offsets ``index`` (adapters.kernels.M_*)."""

    def __init__(
        self, model: mujoco.MjModel, data: mujoco.MjData, mj: np.ndarray, index: np.ndarray
    ) -> None:
        super().__init__()
        self._mj, self._index = mj, index
        self._scratch = np.zeros(6 * model.nv + model.nv * model.nv)
        """Room for MuJoCo's TCP Jacobians and full mass matrix."""
        k.warm_up_mujoco(mj, self._scratch, index)

    def update(self) -> None:
        k.mujoco_sense(self._mj, self._scratch, self._index, self.buffer, False)

    def sense(self) -> None:
        k.mujoco_sense(self._mj, self._scratch, self._index, self.buffer, True)
