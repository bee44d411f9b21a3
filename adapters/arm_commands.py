"""The arm's commands under the cell's impedance controllers, for every adapter that runs
them itself: the simulated cells (MuJoCo, the Pinocchio twin) and the real Franka arm.

What a command does to the arm — a Cartesian or joint impedance target, the per-command
sensing (``travel``, ``turned``, ``peakForce``) zeroed at its start, the pose held with the
last command's impedance when it ends — is the same whoever applies the torques, so it is
written once here; an adapter supplies the arm state, where a scene object is
(``_goal``), and when the arm may be held (``hold``).
"""

from __future__ import annotations

import pinocchio as pin

from lightrocks.adapters.arm import ArmState
from lightrocks.adapters.control import CartesianImpedance, JointImpedance
from lightrocks.adapters.kernels import S_PEAK, S_R0, S_TURNED, S_YAW
from lightrocks.adapters.robots.common import ARM_DOF
from lightrocks.runtime.contract import Command
from lightrocks.runtime.control_loop import Started, always, nothing


class ArmCommands:
    """``robot.moveCartesian`` and ``robot.moveJoint`` on ``arm`` through ``controller``."""

    arm: ArmState
    controller: CartesianImpedance | JointImpedance
    travel_origin: tuple[float, float, float]

    def hold(self) -> None:
        """Stop every command: the arm holds where it is."""
        self.hold_arm()

    def hold_arm(self) -> None:
        """Hold the current pose (or configuration) with the impedance of the last command."""
        c = self.controller
        if isinstance(c, CartesianImpedance):
            here = self.arm.tcp * c.task
            self.controller = CartesianImpedance(
                self.arm, here, c.task, c.stiffness, c.ratio, 0.1, 1.0
            )
        else:
            self.controller = JointImpedance(self.arm, self.arm.q[:ARM_DOF], c.stiffness, c.ratio)

    def ended(self, command: Command) -> None:
        """The arm holds as soon as its command has ended; the other commands go on."""
        if command.device == "robot":
            self.hold()

    @property
    def turned(self) -> float:
        """Signed rotation [rad] of the TCP about its own z since command start."""
        return float(self.arm.sensing[S_TURNED])

    @property
    def peak_force(self) -> float:
        """Largest magnitude [N] of the wrist force since command start."""
        return float(self.arm.sensing[S_PEAK])

    def _goal(self, goal: pin.SE3, ref: str | None) -> pin.SE3:
        """``goal`` in the world frame: relative to the scene object ``ref`` where named."""
        raise NotImplementedError

    def _robot_moveCartesian(
        self, c: Command, goal, task, stiffness, damping, speed, angular_speed, ref
    ) -> Started:
        goal = self._goal(goal, ref)
        task = pin.SE3.Identity() if task is None else task
        self.controller = CartesianImpedance(
            self.arm, goal, task, stiffness, damping, speed, angular_speed
        )
        self._start_command()
        return Started(always, nothing, c.stop)

    def _robot_moveJoint(self, c: Command, q, stiffness, damping) -> Started:
        self.controller = JointImpedance(self.arm, q, stiffness, damping)
        self._start_command()
        return Started(always, nothing, c.stop)

    def _start_command(self) -> None:
        """Zero the per-command sensing: travel, turn and peak force count from here."""
        self.travel_origin = self.arm.point
        sensing = self.arm.sensing
        sensing[S_TURNED] = sensing[S_PEAK] = sensing[S_YAW] = 0.0
        sensing[S_R0 : S_R0 + 9] = self.arm.rotation.reshape(9)
