"""MuJoCo physics under the device layer: one MuJoCo step per 1 kHz control tick.

The step runs in its two halves, ``mj_step2`` with the tick's torques and then ``mj_step1`` of
the next step, so that between ticks the data holds the kinematics and dynamics of the state
just reached (for ``MujocoArm``). For the Euler integrator the halves are exactly ``mj_step``.
"""

from __future__ import annotations

from typing import Any

import mujoco
import numpy as np

from lightrocks.adapters import kernels as k
from lightrocks.adapters.arm import ArmState
from lightrocks.adapters.kernels import DT
from lightrocks.adapters.mujoco.arm import MujocoArm
from lightrocks.adapters.mujoco.data_view import data_view, function_address
from lightrocks.adapters.robots.common import (
    ARM_DOF,
    FINGER_TRAVEL,
    FORCE_SENSOR,
    FT_SITE,
    NV,
    TCP_SITE,
    TORQUE_SENSOR,
)
from lightrocks.adapters.scene import hook_fault
from lightrocks.adapters.scene_registry import load_model
from lightrocks.adapters.scene_registry import robot as registered_robot
from lightrocks.adapters.scene_registry import scene as registered

_ARRAYS = ("qpos", "qvel", "site_xpos", "site_xmat", "qfrc_bias", "ctrl", "sensordata")
"""The arrays of ``data`` a tick reads or writes."""


class MujocoPlant:
    """A scene with a robot (both by registered name) simulated by MuJoCo with the timestep
    forced to the control period."""

    def __init__(self, scene: str, robot: str = "lwr") -> None:
        self._robot = registered_robot(robot)
        self.model = load_model(scene, robot)
        self.model.opt.timestep = DT
        self.data = mujoco.MjData(self.model)
        joints = [self.model.joint(name) for name in self._robot.joints]
        self._qadr = np.array([j.qposadr[0] for j in joints])
        self._vadr = np.array([j.dofadr[0] for j in joints])
        if not (np.all(np.diff(self._qadr) == 1) and np.all(np.diff(self._vadr) == 1)):
            raise ValueError(f"robot joints of scene {scene!r} are not contiguous")
        qa, va = int(self._qadr[0]), int(self._vadr[0])
        actuators = [self.model.actuator(name).id for name in self._robot.joints]
        self._ctrl = int(actuators[0])
        if actuators != list(range(self._ctrl, self._ctrl + NV)):
            raise ValueError(f"robot actuators of scene {scene!r} are not contiguous")
        self.q = self.data.qpos[qa : qa + NV]
        self.v = self.data.qvel[va : va + NV]
        self.q[:ARM_DOF] = self._robot.ready
        self.q[ARM_DOF:] = FINGER_TRAVEL
        mujoco.mj_forward(self.model, self.data)
        sensor = self.model.sensor
        self._force = int(sensor(FORCE_SENSOR).adr[0])
        if int(sensor(TORQUE_SENSOR).adr[0]) != self._force + 3:
            raise ValueError(f"sensor {TORQUE_SENSOR} must follow {FORCE_SENSOR} in the robot")
        tcp, ft = self.model.site(TCP_SITE).id, self.model.site(FT_SITE).id
        self._mj, at = data_view(self.data, _ARRAYS)
        """``data`` as one array (see data_view), with the offsets of ``index``."""
        index = np.zeros(k.M_SIZE, dtype=np.int64)
        index[k.M_QPOS], index[k.M_QVEL] = at["qpos"] + qa, at["qvel"] + va
        index[k.M_TCP_XPOS], index[k.M_FT_XPOS] = (
            at["site_xpos"] + 3 * tcp,
            at["site_xpos"] + 3 * ft,
        )
        index[k.M_TCP_XMAT], index[k.M_FT_XMAT] = (
            at["site_xmat"] + 9 * tcp,
            at["site_xmat"] + 9 * ft,
        )
        index[k.M_BIAS], index[k.M_CTRL] = at["qfrc_bias"] + va, at["ctrl"] + self._ctrl
        index[k.M_FORCE], index[k.M_VADR] = at["sensordata"] + self._force, va
        index[k.M_MODEL], index[k.M_DATA] = self.model._address, self.data._address
        index[k.M_TCP], index[k.M_NV] = tcp, self.model.nv
        index[k.M_JAC_SITE] = function_address("mj_jacSite")
        index[k.M_FULL_M] = function_address("mj_fullM")
        self._index = index
        self._scene_name = scene
        self._scene = registered(scene)
        self._scene_step = self._scene.step
        self.arm: ArmState = MujocoArm(self.model, self.data, self._mj, self._index)
        self.arm.sensing[k.S_SENSOR_ROT : k.S_SENSOR_ROT + 9] = self.data.site_xmat[ft]
        try:
            self._scene_step(self.model, self.data)
        except Exception as error:
            raise hook_fault(scene, "step", error) from error
        mujoco.mj_step1(self.model, self.data)

    def step(self, tau: np.ndarray, grip: float) -> None:
        """Arm torques straight to the motors; each finger pushes with the grip force; then
        the second half of this step, the scene's hook (a raise is the scene's fault) and the
        first half of the next step.
        The arm state rotates the wrist reading into world axes with the site pose the step
        computed it at (see adapters.kernels.mujoco_actuate).

        The finger joint damping sets the finger speed; the force fades out within
        GRIPPER_BAND of the end of travel (see robot_model).
        """
        model, data = self.model, self.data
        arm = self.arm
        if tau is not arm.tau:
            arm.tau[:] = tau
        k.mujoco_actuate(self._mj, arm.buffer, grip, self._index)
        mujoco.mj_step2(model, data)
        try:  # costs nothing until the hook raises
            self._scene_step(model, data)
        except Exception as error:
            raise hook_fault(self._scene_name, "step", error) from error
        mujoco.mj_step1(model, data)

    def wrist(self) -> np.ndarray:
        """The force/torque sensors (site frame) in world axes: the arm state's ``raw``,
        which its ``sense()``/``update()`` after every step rewrites."""
        return self.arm.raw

    def sync(self) -> None:
        """``data`` is the simulation itself: always current."""

    def measurements(self) -> dict[str, Any]:
        return self._scene.measurements(self.model, self.data)
