"""What the real arm may be asked to do, checked before anything is sent to it.

The model's declared safe ranges (``in a .. b`` of the domain library) are checked by the
runtime before a command reaches any adapter; the adapter does not see them. What a real
Franka arm needs on top of them is this table: a workspace box the TCP stays in, speed,
stiffness and force limits, and the joint ranges of the arm. The defaults are Franka's
published limits where a simulation would forgive exceeding them, kept well below the
maximum where a skill never needs more (docs/adapters.md, "A real Franka arm").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightrocks.runtime.contract import AdapterError

JointRanges = tuple[np.ndarray, np.ndarray]
"""The lower and upper ends [rad] of the arm's joints, from the robot's own model (the
Panda's and the FR3's differ on joints 4 and 6)."""
JOINT_MARGIN = math.radians(2.0)
"""A moveJoint goal or a start configuration this close to a joint's end is refused."""


@dataclass(frozen=True)
class Limits:
    """The real arm's limits, in SI units and the world frame of the cell."""

    workspace: tuple[tuple[float, float, float], tuple[float, float, float]] = (
        (0.15, -0.6, -0.02),
        (0.85, 0.6, 0.9),
    )
    """Lower and upper corner of the box [m] every Cartesian goal and the TCP stay in."""
    workspace_slack: float = 0.03
    """How far [m] the TCP may leave the box while moving (compliance, contact) before the
    run ends with an error."""
    speed: float = 0.25
    """Largest Cartesian set-point speed [m/s] (Franka: 1.7 m/s, kept well below)."""
    angular_speed: float = 1.0
    """Largest Cartesian set-point angular speed [rad/s] (Franka: 2.5 rad/s)."""
    stiffness: tuple[float, ...] = (3000.0, 3000.0, 3000.0, 300.0, 300.0, 300.0)
    """Largest Cartesian stiffness per axis [N/m, Nm/rad] (libfranka's Cartesian impedance)."""
    joint_stiffness: tuple[float, ...] = (3000.0, 3000.0, 3000.0, 2500.0, 2500.0, 2000.0, 2000.0)
    """Largest joint stiffness [Nm/rad] (libfranka's joint impedance)."""
    force: float = 60.0
    """Largest contact force [N] at the TCP: beyond it the run ends with an error, and the
    robot's own collision reflex is set just above it."""
    torque: float = 10.0
    """Largest contact torque [Nm] at the TCP, likewise."""
    grip_force: float = 70.0
    """Largest grasp force [N] (the Franka Hand's continuous force)."""

    def collision_thresholds(self) -> tuple[list[float], list[float]]:
        """The robot's collision reflex (joint torques [Nm], Cartesian wrench [N, Nm]): a
        quarter above the adapter's own force limits, so that the adapter's check, with its
        clear message, comes first and the robot's reflex stays the backstop."""
        joint = [1.25 * t for t in (40.0, 40.0, 36.0, 36.0, 32.0, 28.0, 24.0)]
        wrench = [1.25 * self.force] * 3 + [1.25 * self.torque] * 3
        return joint, wrench

    def check_cartesian(
        self, goal: np.ndarray, stiffness: np.ndarray, speed: float, angular_speed: float
    ) -> None:
        """Refuse a Cartesian motion beyond the limits: its goal position (world frame) must
        lie in the workspace box; the straight path there does too, the box being convex."""
        low, high = self.workspace
        for axis, name in enumerate("xyz"):
            if not low[axis] <= goal[axis] <= high[axis]:
                raise AdapterError(
                    f"goal {name} = {goal[axis]:.3f} m is outside the workspace box "
                    f"[{low[axis]:.3f}, {high[axis]:.3f}] m"
                )
        _at_most("stiffness", stiffness, self.stiffness, ("N/m",) * 3 + ("Nm/rad",) * 3)
        if speed > self.speed:
            raise AdapterError(f"speed {speed:.3f} m/s is above the limit {self.speed} m/s")
        if angular_speed > self.angular_speed:
            raise AdapterError(
                f"angular_speed {angular_speed:.3f} rad/s is above the limit "
                f"{self.angular_speed} rad/s"
            )

    def check_joint(self, q: np.ndarray, stiffness: np.ndarray, ranges: JointRanges) -> None:
        """Refuse a joint motion to a goal near or beyond a joint's end."""
        joints_in_range(q, "goal", ranges)
        _at_most("stiffness", stiffness, self.joint_stiffness, ("Nm/rad",) * len(q))

    def check_grip(self, force: float) -> None:
        if force > self.grip_force:
            raise AdapterError(f"grasp force {force:.1f} N is above the limit {self.grip_force} N")

    def check_tcp(self, position: np.ndarray) -> None:
        """While moving: the TCP within the box and its slack."""
        low, high = self.workspace
        slack = self.workspace_slack
        for axis, name in enumerate("xyz"):
            if not low[axis] - slack <= position[axis] <= high[axis] + slack:
                raise AdapterError(
                    f"the TCP left the workspace box: {name} = {position[axis]:.3f} m "
                    f"(box [{low[axis]:.3f}, {high[axis]:.3f}] m)"
                )

    def check_wrench(self, force: float, torque: float) -> None:
        """While moving: the contact force and torque at the TCP below the limits."""
        if force > self.force:
            raise AdapterError(f"contact force {force:.1f} N is above the limit {self.force} N")
        if torque > self.torque:
            raise AdapterError(
                f"contact torque {torque:.2f} Nm is above the limit {self.torque} Nm"
            )


def joints_in_range(q: np.ndarray, what: str, ranges: JointRanges) -> None:
    """Every joint at least JOINT_MARGIN inside its range."""
    lower, upper = ranges
    for i, (value, low, high) in enumerate(zip(q, lower, upper, strict=True)):
        if not low + JOINT_MARGIN <= value <= high - JOINT_MARGIN:
            raise AdapterError(
                f"{what}: joint {i + 1} at {math.degrees(value):.1f} deg is not within "
                f"[{math.degrees(low):.1f}, {math.degrees(high):.1f}] deg "
                f"by {math.degrees(JOINT_MARGIN):.0f} deg"
            )


def _at_most(name: str, values: np.ndarray, limits: tuple[float, ...], units: tuple) -> None:
    for i, (value, limit, unit) in enumerate(zip(values, limits, units, strict=True)):
        if value > limit:
            raise AdapterError(f"{name}[{i}] = {value:g} {unit} is above the limit {limit:g}")
