"""The robot at the current tick, as the controllers and the wrist sensing read it.

Each plant keeps one :class:`ArmState` current from its own physics: ``sense()`` once per
tick, after the step (``update()`` takes the state without advancing the wrist sensing). The
MuJoCo plant reads what its step has already computed (see ``adapters.mujoco.arm``); the twin
computes it with Pinocchio (:class:`PinocchioArm`). Both give the same numbers to rounding
(tests/adapters/test_robot_model.py), so the controllers do not care which one they read.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
import pinocchio as pin

from lightrocks.adapters import kernels as k
from lightrocks.adapters.kernels import SLOW_EVERY
from lightrocks.adapters.robot_model import ARM_DOF, FT_SITE, NV, TCP_SITE


class ArmState(ABC):
    """Kinematics and dynamics of the robot (arm joints, then the two fingers) at one tick.

    Everything per tick lives in one flat ``buffer`` (layout in adapters.kernels) that the
    native tick functions read; the attributes are views of it. ``jacobian`` is the TCP
    Jacobian of the arm joints, LOCAL_WORLD_ALIGNED: its rows are the linear velocity of the
    TCP point and the angular velocity, in world axes. ``bias`` holds the Coriolis,
    centrifugal and gravity torques of the arm joints. ``mass_inv`` and ``mass_diag`` (of the
    arm block of the mass matrix) are refreshed in place every SLOW_EVERY ticks. ``tau``
    receives the controller's torques.
    ``sensing`` is the wrist sensing's block (adapters.sensing), kept in the same buffer so that
    one native call updates both.
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
        self.mass_inv = buffer[k.MASS_INV : k.MASS_INV + ARM_DOF * ARM_DOF].reshape(ARM_DOF, -1)
        self.mass_inv[:] = np.eye(ARM_DOF)
        self.tau = buffer[k.TAU : k.TAU + ARM_DOF]
        self.mass_diag = buffer[k.MASS_DIAG : k.MASS_DIAG + ARM_DOF]
        self.mass_diag[:] = 1.0
        self.sensing = buffer[k.SENSING :]
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
        """Take the plant's state of this tick (the wrist sensing is left alone)."""

    @abstractmethod
    def sense(self) -> None:
        """Take the plant's state of this tick, then the wrist sensing of ``raw``
        (adapters.kernels.sense), in one native call."""

    def _slow_tick(self) -> bool:
        """Whether this tick refreshes the mass matrix; counts the tick."""
        self._tick += 1
        return self._tick % SLOW_EVERY == 1


class PinocchioArm(ArmState):
    """Computes the arm state with Pinocchio: one ``computeJointJacobians`` (which includes
    the forward kinematics) serves the TCP and ft placements and the TCP Jacobian; one native
    call copies Pinocchio's results (read through views of its data made once) and does the
    wrist sensing.

    The joint state is ``q``/``v`` of this arm state, which the twin's plant integrates in
    place; given ``q`` and ``v`` arrays of another owner, each update copies them first.
    """

    def __init__(
        self, model: pin.Model, q: np.ndarray | None = None, v: np.ndarray | None = None
    ) -> None:
        super().__init__()
        self.model = model
        self.data = data = model.createData()
        self._joints = None if q is None or v is None else (q, v)
        self._tcp_id = model.getFrameId(TCP_SITE)
        self._ft_id = model.getFrameId(FT_SITE)
        tcp, ft = data.oMf[self._tcp_id], data.oMf[self._ft_id]
        self._results = (tcp.rotation, tcp.translation, ft.rotation, ft.translation)
        """Views into ``data`` that every update rewrites."""
        self._nle, self._mass = data.nle, data.M

    def update(self) -> None:
        self._read(False)

    def sense(self) -> None:
        self._read(True)

    def _read(self, wrist: bool) -> None:
        model, data, q, v = self.model, self.data, self.q, self.v
        if self._joints is not None:
            q[:], v[:] = self._joints
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacement(model, data, self._tcp_id)
        pin.updateFramePlacement(model, data, self._ft_id)
        jacobian = pin.getFrameJacobian(model, data, self._tcp_id, pin.LOCAL_WORLD_ALIGNED)
        pin.nonLinearEffects(model, data, q, v)
        slow = self._slow_tick()
        if slow:
            pin.crba(model, data, q)  # the upper triangle of data.M
        results, nle, mass = self._results, self._nle, self._mass
        k.pinocchio_sense(self.buffer, *results, jacobian, nle, mass, wrist, slow)
