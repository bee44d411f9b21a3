"""The arm state read from MuJoCo's own computation of the current state.

The plant runs each step in two halves (``mj_step2``, then ``mj_step1`` of the next step), so
after a tick MuJoCo has already computed the kinematics, the mass matrix and the bias forces
of the state it just reached. Reading them costs a Jacobian and a few copies; computing them
again with Pinocchio cost a dozen library calls per tick.
"""

from __future__ import annotations

import mujoco
import numpy as np

from lightrocks.adapters.arm import ArmState
from lightrocks.adapters.robot_model import ARM_DOF, FT_SITE, NV, TCP_SITE


class MujocoArm(ArmState):
    """The robot's joints at ``qadr``/``vadr`` (arm, then fingers, contiguous) in ``data``."""

    def __init__(self, model: mujoco.MjModel, data: mujoco.MjData, qadr: int, vadr: int) -> None:
        super().__init__()
        self._model, self._data = model, data
        self._joint_q = data.qpos[qadr : qadr + NV]
        self._joint_v = data.qvel[vadr : vadr + NV]
        tcp, ft = model.site(TCP_SITE).id, model.site(FT_SITE).id
        self._tcp = tcp
        self.position = data.site_xpos[tcp]
        self.rotation = data.site_xmat[tcp].reshape(3, 3)
        self.ft_position = data.site_xpos[ft]
        self.ft_rotation = data.site_xmat[ft].reshape(3, 3)
        self.bias = data.qfrc_bias[vadr : vadr + ARM_DOF]
        """Views into ``data``: MuJoCo rewrites them in place every step."""
        self._jacobians = np.zeros((6, model.nv))
        self._linear, self._angular = self._jacobians[:3], self._jacobians[3:]
        self._robot_columns = self._jacobians[:, vadr : vadr + NV]
        self.jacobian = self._jacobians[:, vadr : vadr + ARM_DOF]
        self._mass = np.zeros((model.nv, model.nv))
        self._arm_mass = self._mass[vadr : vadr + ARM_DOF, vadr : vadr + ARM_DOF]

    def update(self) -> None:
        model, data = self._model, self._data
        self.q[:] = self._joint_q
        self.v[:] = self._joint_v
        self.point = tuple(self.position.tolist())
        mujoco.mj_jacSite(model, data, self._linear, self._angular, self._tcp)
        np.matmul(self._robot_columns, self.v, out=self.twist)
        if self._slow_tick():
            mujoco.mj_fullM(model, data, self._mass)
            self._set_mass(self._arm_mass)
