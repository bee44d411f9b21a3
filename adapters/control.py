"""Impedance controllers shared by both adapters, on the plant's ``ArmState``.

Runs at 1 kHz: the plant updates its arm state once per tick, then the active controller's
``torque`` reads it. The per-tick arithmetic is one native call (adapters.kernels) on the
controller's buffer; the operational-space inertia (for damping) and the null-space projector
are refreshed every ``SLOW_EVERY`` ticks only, because they change slowly with the
configuration.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from lightrocks.adapters import kernels as k
from lightrocks.adapters.arm import ArmState
from lightrocks.adapters.robots.common import ARM_DOF

JOINT_SPEED = 0.5
"""Speed [rad/s] of the fastest joint of a moveJoint interpolation."""
REACHED_POSITION = 1e-3
REACHED_ANGLE = np.deg2rad(0.5)
REST_LINEAR = 5e-3
REST_ANGULAR = 0.02
REST_JOINT = 0.02


class CartesianImpedance:
    """``τ = Jᵀ(K e − D ė) + bias + null-space posture term`` for a task frame on the hand.

    Stiffness and damping act along the axes of the task frame (so ``[.., .., .., .., .., 30]``
    is soft about the tool axis). Damping ratios become ``D = 2 ζ sqrt(K Λ)`` with the diagonal
    of the operational-space inertia Λ in task axes (a diagonal approximation of the full
    ``2 ζ sqrt`` factorisation, refreshed every SLOW_EVERY ticks). The set point moves on a
    straight line at ``speed`` while its orientation turns about a fixed axis at
    ``angular_speed``; both arrive together. Damping acts on the error velocity, so the set point
    velocity is fed forward. The per-tick work is one native call
    (adapters.kernels.cartesian_torque) on the controller's buffer, whose fields are views here.
    """

    def __init__(
        self,
        arm: ArmState,
        goal: pin.SE3,
        task: pin.SE3,
        stiffness: np.ndarray,
        damping: np.ndarray,
        speed: float,
        angular_speed: float,
    ) -> None:
        self.goal = goal
        self.task = task
        self.stiffness = np.asarray(stiffness, dtype=float)
        self.ratio = np.asarray(damping, dtype=float)
        self._buffer = b = np.zeros(k.CARTESIAN_SIZE)
        b[k.C_K : k.C_K + 6] = self.stiffness
        b[k.C_RATIO : k.C_RATIO + 6] = self.ratio
        self.damping = b[k.C_D : k.C_D + 6]
        b[k.C_POSTURE : k.C_POSTURE + ARM_DOF] = arm.q[:ARM_DOF]
        start = arm.tcp * task
        p0, r0 = start.translation, start.rotation
        dp = goal.translation - p0
        dr = pin.log3(r0.T @ goal.rotation)
        distance, angle = np.linalg.norm(dp), np.linalg.norm(dr)
        self.duration = max(distance / max(speed, 1e-9), angle / max(angular_speed, 1e-9))
        b[k.C_P0 : k.C_P0 + 3] = p0
        b[k.C_DP : k.C_DP + 3] = dp
        b[k.C_DR : k.C_DR + 3] = dr
        b[k.C_R0 : k.C_R0 + 9] = r0.reshape(9)
        b[k.C_RGOAL : k.C_RGOAL + 9] = goal.rotation.reshape(9)
        b[k.C_PGOAL : k.C_PGOAL + 3] = goal.translation
        if self.duration > 0:  # the set-point velocity (linear, angular; world axes)
            b[k.C_TWSET : k.C_TWSET + 3] = dp / self.duration
            b[k.C_TWSET + 3 : k.C_TWSET + 6] = r0 @ dr / self.duration
        b[k.C_DURATION] = self.duration
        b[k.C_MOVING] = 1.0
        b[k.C_OFFSET] = 0.0 if task.isIdentity() else 1.0
        b[k.C_TASK_R : k.C_TASK_R + 9] = task.rotation.reshape(9)
        b[k.C_TASK_P : k.C_TASK_P + 3] = task.translation
        self._local = b[k.C_LOCAL : k.C_LOCAL + 9].reshape(3, 3)
        """Position error, linear and angular error velocity (rows) in task axes."""
        self._e_rot = b[k.C_EROT : k.C_EROT + 3]

    @property
    def elapsed(self) -> float:
        """Seconds since the command started (one DT per tick)."""
        return float(self._buffer[k.C_ELAPSED])

    def torque(self, arm: ArmState) -> np.ndarray:
        """Joint torques of the arm for this tick (the arm state's ``tau``); advances the set
        point by one DT."""
        k.cartesian_torque(arm.buffer, self._buffer)
        return arm.tau

    def reached(self, arm: ArmState) -> bool:
        """Interpolation done, within 1 mm and 0.5° of the final goal and nearly at rest."""
        return (
            self._buffer[k.C_MOVING] == 0.0
            and math.sqrt(self._local[0] @ self._local[0]) < REACHED_POSITION
            and math.sqrt(self._e_rot @ self._e_rot) < REACHED_ANGLE
            and math.sqrt(arm.twist[:3] @ arm.twist[:3]) < REST_LINEAR
            and math.sqrt(arm.twist[3:] @ arm.twist[3:]) < REST_ANGULAR
        )


class JointImpedance:
    """``τ = K (q_set − q) − D q̇ + bias`` with ``D = 2 ζ sqrt(K M_ii)``.

    The set point moves linearly from the start configuration so that the fastest joint runs
    at JOINT_SPEED; damping acts on the error velocity. D follows the arm state's mass matrix,
    refreshed every SLOW_EVERY ticks. The per-tick work is one native call
    (adapters.kernels.joint_torque).
    """

    def __init__(
        self, arm: ArmState, goal: np.ndarray, stiffness: np.ndarray, damping: np.ndarray
    ) -> None:
        self.goal = np.asarray(goal, dtype=float)
        self.stiffness = np.asarray(stiffness, dtype=float)
        self.ratio = np.asarray(damping, dtype=float)
        self._buffer = b = np.zeros(k.JOINT_SIZE)
        q0 = arm.q[:ARM_DOF].copy()
        dq = self.goal - q0
        self.duration = float(np.max(np.abs(dq))) / JOINT_SPEED
        b[k.J_K : k.J_K + ARM_DOF] = self.stiffness
        b[k.J_RATIO : k.J_RATIO + ARM_DOF] = self.ratio
        b[k.J_Q0 : k.J_Q0 + ARM_DOF] = q0
        b[k.J_DQ : k.J_DQ + ARM_DOF] = dq
        if self.duration > 0:
            b[k.J_VSET : k.J_VSET + ARM_DOF] = dq / self.duration
        b[k.J_DURATION] = self.duration

    @property
    def elapsed(self) -> float:
        """Seconds since the command started (one DT per tick)."""
        return float(self._buffer[k.J_ELAPSED])

    def torque(self, arm: ArmState) -> np.ndarray:
        """Joint torques of the arm for this tick (the arm state's ``tau``)."""
        k.joint_torque(arm.buffer, self._buffer)
        return arm.tau

    def reached(self, arm: ArmState) -> bool:
        """Every joint within 0.5° of the goal and nearly at rest."""
        return (
            self.elapsed >= self.duration
            and float(np.max(np.abs(self.goal - arm.q[:ARM_DOF]))) < REACHED_ANGLE
            and float(np.max(np.abs(arm.v[:ARM_DOF]))) < REST_JOINT
        )
