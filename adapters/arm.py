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
from lightrocks.adapters.robots.common import ARM_DOF, FT_SITE, NV, TCP_SITE


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


class PinocchioArm(ArmState):
    """Computes the arm state with Pinocchio: ``compute`` runs ``crba`` in the world convention
    (whose by-products are the joint placements and the joint Jacobians, as
    ``computeJointJacobians`` gives them) and ``nonLinearEffects`` at ``q``, ``v``;
    ``update``/``sense`` read the results in place in one native call (``index`` holds the
    addresses of Pinocchio's arrays, ``frames`` the TCP and ft placements in their joint), which
    derives the TCP and ft placements and the TCP Jacobian and does the wrist sensing.

    Whoever changes ``q`` and ``v`` calls ``compute`` before the next read: the twin's plant
    after each step, which reads the mass matrix and nonlinear effects too. Given ``q`` and ``v``
    arrays of another owner, ``compute`` copies them first.
    """

    def __init__(
        self, model: pin.Model, q: np.ndarray | None = None, v: np.ndarray | None = None
    ) -> None:
        super().__init__()
        self.model = model
        self.data = data = model.createData()
        self._joints = None if q is None or v is None else (q, v)
        frames = (model.getFrameId(TCP_SITE), model.getFrameId(FT_SITE))
        self.joint = carrier(model, frames)
        """The joint that carries the TCP and the ft site."""
        self.frames = np.concatenate([in_joint(model, frame) for frame in frames])
        placement = data.oMi[self.joint]
        arrays = (data.J, data.nle, data.M, placement.rotation, placement.translation)
        self.index = np.array([address(a) for a in arrays], dtype=np.int64)
        """Addresses of Pinocchio's arrays (P_* in adapters.kernels): Eigen allocates them once
        with ``data``, which this arm state keeps."""

    def compute(self) -> None:
        """Pinocchio's kinematics, Jacobians, nonlinear effects and mass matrix at ``q``,
        ``v``."""
        model, data, q = self.model, self.data, self.q
        if self._joints is not None:
            q[:], self.v[:] = self._joints
        pin.crba(model, data, q, pin.Convention.WORLD)
        pin.nonLinearEffects(model, data, q, self.v)

    def update(self) -> None:
        k.pinocchio_sense(self.buffer, self.index, self.frames, False)

    def sense(self) -> None:
        k.pinocchio_sense(self.buffer, self.index, self.frames, True)


def address(array: np.ndarray) -> int:
    """Where an array of Pinocchio's data starts, for native code to read it in place; they
    are column-major float64 (Eigen's default)."""
    if not (array.flags.f_contiguous and array.dtype == np.float64):
        raise ValueError("Pinocchio's data arrays are not column-major float64")
    return array.ctypes.data


def carrier(model: pin.Model, frames: tuple[int, ...]) -> int:
    """The joint that carries all the frames (ids), which the arm joints (the first ARM_DOF
    velocities) move: the native reads take their placements and the TCP Jacobian from it."""
    joints = {model.frames[frame].parentJoint for frame in frames}
    names = ", ".join(model.frames[frame].name for frame in frames)
    if len(joints) != 1:
        raise ValueError(f"frames {names} are not on one joint")
    joint = joints.pop()
    moved_by = [model.joints[j].idx_v for j in model.supports[joint].tolist()[1:]]
    if moved_by != list(range(ARM_DOF)):
        raise ValueError(f"frames {names} are not moved by the arm joints alone")
    return joint


def in_joint(model: pin.Model, frame: int) -> np.ndarray:
    """A frame's placement in its joint: rotation (row-major), then translation."""
    placement = model.frames[frame].placement
    return np.concatenate([placement.rotation.reshape(-1), placement.translation])
