"""What a robot is: its MuJoCo model (MJCF text that scenes include as ``robot.xml``), its
Pinocchio model, the names the adapters look up in both, its ready pose and its gains, as one
object that a ``lightrocks.robots`` entry point registers (see adapters.scene_registry).

Adapters ask the robot object and never switch on a robot's name. What every robot shares is
in adapters.robots.common: ARM_DOF arm joints and two finger slides of FINGER_TRAVEL each (the
native tick is compiled for them), sites ``tcp`` and ``ft`` on the hand, and the wrist's
force and torque sensors ``ft_force``, ``ft_torque`` at ``ft``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from pathlib import Path

import pinocchio as pin

from lightrocks.adapters.robots.common import ARM_DOF, FINGER_TRAVEL


class RobotDataMissing(ValueError):
    """A registered robot whose model files are not installed; the message says what to
    install."""


@dataclass(frozen=True)
class Robot(ABC):
    """A robot arm with a parallel gripper, as both adapters need it.

    In both models the robot's joints are the arm joints, then the two finger joints, with
    the same names; MuJoCo's motors carry the names of the joints they drive.
    """

    device_type: str
    """The device type a cell's ``robot`` slot binds to (``LWR``)."""
    description: str
    """One line for ``lightrocks list robots``."""
    arm_joints: tuple[str, ...]
    finger_joints: tuple[str, str]
    """The slides of the two fingers: the first opens along the hand's y axis, the second
    against it."""
    root: str
    """The root body: every body below it belongs to the robot, not to the scene."""
    hand: str
    """The body that carries the ``ft`` site (at its origin, in its axes) and ``tcp``: its
    subtree is the wrist sensor's load, and its box geoms touch the scene in the twin."""
    fingers: tuple[str, str]
    """The finger bodies, moved by ``finger_joints``; their box geoms touch the scene."""
    ready: tuple[float, ...]
    """Ready pose [rad]: the TCP pointing straight down over the table, where every adapter
    starts."""
    joint_stiffness: tuple[float, ...]
    """Joint impedance [Nm/rad] that holds the ready pose at start-up; ``moveJoint``'s
    default."""
    cartesian_stiffness: tuple[float, ...]
    """``moveCartesian``'s default stiffness (3 × N/m, 3 × Nm/rad)."""
    finger_damping: float
    """Joint damping [N s/m] of each finger in the MJCF: a grip force F moves a finger at
    F / finger_damping (the twin's first-order fingers use it too)."""

    def __post_init__(self) -> None:
        for name in ("arm_joints", "ready", "joint_stiffness"):
            if len(getattr(self, name)) != ARM_DOF:
                raise ValueError(f"robot {self.device_type}: {name} must have {ARM_DOF} entries")
        if len(self.cartesian_stiffness) != 6:
            raise ValueError(f"robot {self.device_type}: cartesian_stiffness must have 6 entries")

    @property
    def joints(self) -> tuple[str, ...]:
        """Arm joints, then finger joints: the order of ``q`` in both adapters."""
        return (*self.arm_joints, *self.finger_joints)

    @abstractmethod
    def mjcf(self) -> bytes:
        """The robot's MJCF, standalone and includable by a scene (no ``<compiler>`` or
        ``<option>``, angles in degrees, mesh files by absolute path)."""

    @abstractmethod
    def model(self) -> pin.Model:
        """A new Pinocchio model of the robot with frames ``tcp`` and ``ft``; its joints in
        the order of ``joints``."""


@dataclass(frozen=True)
class MjcfRobot(Robot):
    """A robot written as an MJCF file, which MuJoCo includes and Pinocchio reads."""

    path: Path

    def mjcf(self) -> bytes:
        return self.path.read_bytes()

    def model(self) -> pin.Model:
        """Pinocchio 4.1 converts slide-joint ranges as if they were angles (degrees), so the
        finger limits are set here from FINGER_TRAVEL."""
        model = pin.buildModelFromMJCF(str(self.path))
        model.lowerPositionLimit[ARM_DOF:] = 0.0
        model.upperPositionLimit[ARM_DOF:] = FINGER_TRAVEL
        return model
