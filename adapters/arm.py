"""The robot at the current tick, as the controllers and the wrist sensing read it.

Each plant keeps one :class:`ArmState` current from its own physics: ``sense()`` once per
tick, after the step (``update()`` alone refreshes the kinematics and dynamics without the
wrist sensing). The MuJoCo plant reads what its step has already computed (see
``adapters.mujoco.arm``); the twin computes it with Pinocchio (:class:`PinocchioArm`). Both give
the same numbers to rounding (tests/adapters/test_robot_model.py), so the controllers do not
care which one they read.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
import pinocchio as pin

from lightrocks.adapters import kernels as k
from lightrocks.adapters.kernels import SLOW_EVERY
from lightrocks.adapters.robot_model import ARM_DOF, FT_SITE, NV, TCP_SITE
from lightrocks.adapters.vec import symmetrize_upper

_LOWER = np.tril_indices(ARM_DOF, -1)


class ArmState(ABC):
    """Kinematics and dynamics of the robot (arm joints, then the two fingers) at one tick.

    Everything per tick lives in one flat ``buffer`` (layout in adapters.kernels) that the
    native tick functions read; the attributes are views of it. ``jacobian`` is the TCP
    Jacobian of the arm joints, LOCAL_WORLD_ALIGNED: its rows are the linear velocity of the
    TCP point and the angular velocity, in world axes. ``bias`` holds the Coriolis,
    centrifugal and gravity torques of the arm joints. ``mass_inv`` and ``mass_diag`` are
    replaced (not modified) every SLOW_EVERY ticks, so that controllers can cache what they
    derive from them on identity. ``sensing`` is the wrist sensing's buffer
    (adapters.sensing), kept here so that one native call updates both.
    """

    def __init__(self) -> None:
        self.buffer = buffer = np.zeros(k.ARM_SIZE)
        self.state = buffer[k.STATE : k.STATE + 2 * NV]
        """Joint positions then velocities, one array so that a matrix can act on both."""
        self.q = self.state[:NV]
        self.v = self.state[NV:]
        self.position = buffer[k.POS : k.POS + 3]
        self.rotation = buffer[k.ROT : k.ROT + 9].reshape(3, 3)
        """TCP position and rotation, world axes."""
        self.ft_position = buffer[k.FT_POS : k.FT_POS + 3]
        self.ft_rotation = buffer[k.FT_ROT : k.FT_ROT + 9].reshape(3, 3)
        """Pose of the wrist force/torque site."""
        self.rotation[:] = np.eye(3)
        self.ft_rotation[:] = np.eye(3)
        self.jacobian = buffer[k.JAC : k.JAC + 6 * ARM_DOF].reshape(6, ARM_DOF)
        self.twist = buffer[k.TWIST : k.TWIST + 6]
        self.bias = buffer[k.BIAS : k.BIAS + ARM_DOF]
        self.mass_inv = np.eye(ARM_DOF)
        self.mass_diag = np.ones(ARM_DOF)
        self.sensing = np.zeros(k.SENSE_SIZE)
        self.raw = self.sensing[k.S_RAW : k.S_RAW + 6]
        """The raw wrist reading, which the plant writes after each step."""
        self._tick = 0

    @property
    def point(self) -> tuple[float, float, float]:
        """``position`` as floats."""
        x, y, z = self.position.tolist()
        return (x, y, z)

    @property
    def tcp(self) -> pin.SE3:
        """The TCP pose, a new SE3 on each access."""
        return pin.SE3(self.rotation, self.position)

    @abstractmethod
    def update(self) -> None:
        """Take the plant's state of this tick."""

    def sense(self) -> None:
        """``update()``, then the wrist sensing of ``raw`` (adapters.kernels.sense)."""
        self.update()
        k.sense(self.buffer, self.sensing)

    def _slow_tick(self) -> bool:
        """Whether this tick refreshes the mass matrix; counts the tick."""
        self._tick += 1
        return self._tick % SLOW_EVERY == 1

    def _set_mass(self, arm_mass: np.ndarray) -> None:
        """Take the (symmetric) mass matrix of the arm joints."""
        self.mass_inv = np.empty((ARM_DOF, ARM_DOF))
        k.spd_inverse(arm_mass, self.mass_inv)
        self.mass_diag = np.diag(arm_mass).copy()


class PinocchioArm(ArmState):
    """Computes the arm state with Pinocchio from joint arrays that the plant updates in
    place: one ``computeJointJacobians`` (which includes the forward kinematics) serves the
    TCP and ft placements and the TCP Jacobian."""

    def __init__(self, model: pin.Model, q: np.ndarray, v: np.ndarray) -> None:
        super().__init__()
        self.model = model
        self.data = model.createData()
        self._joint_q = q
        self._joint_v = v
        self._tcp_id = model.getFrameId(TCP_SITE)
        self._ft_id = model.getFrameId(FT_SITE)
        self._tcp = self.data.oMf[self._tcp_id]
        self._ft = self.data.oMf[self._ft_id]
        """References into ``data`` that every update moves."""

    def update(self) -> None:
        model, data = self.model, self.data
        self.q[:] = self._joint_q
        self.v[:] = self._joint_v
        pin.computeJointJacobians(model, data, self.q)
        pin.updateFramePlacement(model, data, self._tcp_id)
        pin.updateFramePlacement(model, data, self._ft_id)
        tcp, ft = self._tcp, self._ft
        self.position[:] = tcp.translation
        self.rotation[:] = tcp.rotation
        self.ft_position[:] = ft.translation
        self.ft_rotation[:] = ft.rotation
        jacobian = pin.getFrameJacobian(model, data, self._tcp_id, pin.LOCAL_WORLD_ALIGNED)
        self.jacobian[:] = jacobian[:, :ARM_DOF]
        np.matmul(jacobian, self.v, out=self.twist)
        self.bias[:] = pin.nonLinearEffects(model, data, self.q, self.v)[:ARM_DOF]
        if self._slow_tick():
            mass = pin.crba(model, data, self.q)[:ARM_DOF, :ARM_DOF]
            self._set_mass(symmetrize_upper(mass.copy(), _LOWER))
