"""The arm state read from MuJoCo's own computation of the current state.

The plant runs each step in two halves (``mj_step2``, then ``mj_step1`` of the next step), so
after a tick MuJoCo has already computed the kinematics, the mass matrix and the bias forces
of the state it just reached. Reading them costs a Jacobian (``mj_jacSite``) and one native
call (adapters.kernels.mujoco_sense) that copies them into the arm state and does the wrist
sensing; computing them again with Pinocchio cost a dozen library calls per tick.
"""

from __future__ import annotations

import mujoco
import numpy as np

from lightrocks.adapters import kernels as k
from lightrocks.adapters.arm import ArmState
from lightrocks.adapters.robot_model import ARM_DOF, TCP_SITE


class MujocoArm(ArmState):
    """The robot's joints (arm, then fingers, contiguous) in ``data``, read through the
    plant's flat view ``mj`` of it at the offsets ``index`` (adapters.kernels.M_*)."""

    def __init__(
        self, model: mujoco.MjModel, data: mujoco.MjData, mj: np.ndarray, index: np.ndarray
    ) -> None:
        super().__init__()
        self._model, self._data, self._mj, self._index = model, data, mj, index
        self._tcp = model.site(TCP_SITE).id
        va = int(index[k.M_VADR])
        self._jacobians = np.zeros((6, model.nv))
        self._linear, self._angular = self._jacobians[:3], self._jacobians[3:]
        self._mass = np.zeros((model.nv, model.nv))
        self._arm_mass = self._mass[va : va + ARM_DOF, va : va + ARM_DOF]

    def update(self) -> None:
        self._read(False)

    def sense(self) -> None:
        self._read(True)

    def _read(self, wrist: bool) -> None:
        """One ``mj_jacSite`` and one native call: the arm state, then with ``wrist`` the wrist
        sensing."""
        model, data = self._model, self._data
        mujoco.mj_jacSite(model, data, self._linear, self._angular, self._tcp)
        k.mujoco_sense(self._mj, self._jacobians, self._index, self.buffer, wrist)
        if self._slow_tick():
            mujoco.mj_fullM(model, data, self._mass)
            self._set_mass(self._arm_mass)
