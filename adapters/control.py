"""Impedance controllers shared by both adapters, on the plant's ``ArmState``.

Runs at 1 kHz: the plant updates its arm state once per tick, then the active controller's
``torque`` reads it. Everything here is the hot path, so the per-tick work is a few small
NumPy products and Pinocchio's ``exp3``/``log3``; the operational-space inertia (for damping)
and the null-space projector are refreshed every ``SLOW_EVERY`` ticks only, because they change
slowly with the configuration.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from lightrocks.adapters.arm import SLOW_EVERY, ArmState
from lightrocks.adapters.robot_model import ARM_DOF, NV

DT = 0.001
NULLSPACE_STIFFNESS = 10.0
"""Posture stiffness [Nm/rad] pulling the elbow towards the configuration at command start."""
NULLSPACE_DAMPING = 2.0
JOINT_SPEED = 0.5
"""Speed [rad/s] of the fastest joint of a moveJoint interpolation."""
REACHED_POSITION = 1e-3
REACHED_ANGLE = np.deg2rad(0.5)
REST_LINEAR = 5e-3
REST_ANGULAR = 0.02
REST_JOINT = 0.02


def _block_rotate(rotation: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """``Rᵀ A R`` with R = diag(rotation, rotation): a 6x6 matrix from world to local axes."""
    r6 = np.zeros((6, 6))
    r6[:3, :3] = rotation
    r6[3:, 3:] = rotation
    return r6.T @ matrix @ r6


class CartesianImpedance:
    """``τ = Jᵀ(K e − D ė) + bias + null-space posture term`` for a task frame on the hand.

    Stiffness and damping act along the axes of the task frame (so ``[.., .., .., .., .., 30]``
    is soft about the tool axis). Damping ratios become ``D = 2 ζ sqrt(K Λ)`` with the diagonal
    of the operational-space inertia Λ in task axes (a diagonal approximation of the full
    ``2 ζ sqrt`` factorisation, refreshed every SLOW_EVERY ticks). The set point moves on a
    straight line at ``speed`` while its orientation turns about a fixed axis at
    ``angular_speed``; both arrive together. Damping acts on the error velocity, so the set point
    velocity is fed forward. The per-tick work is a dozen small NumPy calls on preallocated
    arrays (each costs ~0.5 µs whatever its size, so fewer, larger products win).
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
        self.damping = np.zeros(6)
        self._k = tuple(self.stiffness.tolist())
        self._d = (0.0,) * 6
        """Stiffness and damping as floats for the per-tick wrench."""
        self.posture = arm.q[:ARM_DOF].copy()
        start = arm.tcp * task
        self._p0 = start.translation.copy()
        self._r0 = start.rotation.copy()
        self._p_goal = goal.translation.copy()
        self._r_goal = goal.rotation.copy()
        self._dp = self._p_goal - self._p0
        self._line = (*self._p0.tolist(), *self._dp.tolist())
        """Start and direction of the set point's straight line, as floats."""
        self._dr = pin.log3(self._r0.T @ self._r_goal)
        distance, angle = np.linalg.norm(self._dp), np.linalg.norm(self._dr)
        self.duration = max(distance / max(speed, 1e-9), angle / max(angular_speed, 1e-9))
        self._twist_set = np.zeros(6)
        """Set-point velocity (linear, angular; world axes) while moving."""
        if self.duration > 0:
            self._twist_set[:3] = self._dp / self.duration
            self._twist_set[3:] = self._r0 @ self._dr / self.duration
        self.elapsed = 0.0
        self._moving = True
        self._slow_tick = 0
        self._offset = not task.isIdentity()
        self._errors = np.zeros((3, 3))
        """Rows: position error, linear and angular error velocity, world axes."""
        self._local = np.zeros((3, 3))
        """The rows of ``_errors`` in task axes."""
        self._position_error, self._rate_errors = self._errors[0], self._errors[1:].reshape(6)
        """Views of the rows, made once: a view costs a NumPy call too."""
        self._wrench = np.zeros((2, 3))
        """Task wrench in task axes (force row, torque row); ``_world`` in world axes."""
        self._world = np.zeros((2, 3))
        self._world_flat = self._world.reshape(6)
        self._e_rot = np.zeros(3)
        self._nullspace_posture = np.zeros(ARM_DOF)
        self._nullspace_state = np.zeros((ARM_DOF, 2 * NV))
        """Null-space posture torque = ``_nullspace_posture + _nullspace_state @ arm.state``."""

    def _refresh_slow_terms(self, arm: ArmState, jac: np.ndarray, rotation: np.ndarray) -> None:
        """Damping from Λ and the dynamically consistent null-space projector N.

        ``N (K_ns (q₀ − q) − D_ns q̇)`` is split into a constant and a matrix acting on the
        joint state, so that each tick needs one product for it.
        """
        lam_inv = jac @ arm.mass_inv @ jac.T
        lam = np.linalg.inv(lam_inv + 1e-6 * np.eye(6))
        lam_local = np.diag(_block_rotate(rotation, lam))
        self.damping = 2.0 * self.ratio * np.sqrt(self.stiffness * np.maximum(lam_local, 0.0))
        self._d = tuple(self.damping.tolist())
        jbar = arm.mass_inv @ jac.T @ lam
        nullspace = np.eye(ARM_DOF) - jac.T @ jbar.T
        self._nullspace_posture = NULLSPACE_STIFFNESS * (nullspace @ self.posture)
        self._nullspace_state[:, :ARM_DOF] = -NULLSPACE_STIFFNESS * nullspace
        self._nullspace_state[:, NV : NV + ARM_DOF] = -NULLSPACE_DAMPING * nullspace

    def torque(self, arm: ArmState) -> np.ndarray:
        """Joint torques of the arm for this tick; advances the set point by one DT."""
        s = 1.0 if self.duration <= 0 else min(self.elapsed / self.duration, 1.0)
        self.elapsed += DT
        self._moving = moving = s < 1.0

        if self._offset:
            frame = arm.tcp * self.task
            rot, pos = frame.rotation, frame.translation
            jac = arm.jacobian.copy()
            jac[:3] -= pin.skew(pos - arm.position) @ jac[3:]
            twist = jac @ arm.v[:ARM_DOF]
        else:
            rot, pos, jac, twist = arm.rotation, arm.position, arm.jacobian, arm.twist
        if self._slow_tick % SLOW_EVERY == 0:
            self._refresh_slow_terms(arm, jac, rot)
        self._slow_tick += 1

        if moving:
            x0, y0, z0, dx, dy, dz = self._line
            x, y, z = pos.tolist() if self._offset else arm.point
            self._position_error[:] = (x0 + s * dx - x, y0 + s * dy - y, z0 + s * dz - z)
            np.subtract(self._twist_set, twist, out=self._rate_errors)
            r_set = self._r0 @ pin.exp3(s * self._dr)
        else:
            np.subtract(self._p_goal, pos, out=self._position_error)
            np.negative(twist, out=self._rate_errors)
            r_set = self._r_goal
        np.matmul(self._errors, rot, out=self._local)  # row i: Rᵀ errors[i]
        rot_t = rot.T
        self._e_rot = e_rot = pin.log3(rot_t @ r_set)
        (px, py, pz), (vx, vy, vz), (wx, wy, wz) = self._local.tolist()
        ex, ey, ez = e_rot.tolist()
        k0, k1, k2, k3, k4, k5 = self._k
        d0, d1, d2, d3, d4, d5 = self._d
        self._wrench[:] = (
            (k0 * px + d0 * vx, k1 * py + d1 * vy, k2 * pz + d2 * vz),
            (k3 * ex + d3 * wx, k4 * ey + d4 * wy, k5 * ez + d5 * wz),
        )  # K e + D ė elementwise, as NumPy computes it
        np.matmul(self._wrench, rot_t, out=self._world)  # back to world axes
        tau = jac.T @ self._world_flat
        tau += arm.bias
        tau += self._nullspace_posture
        tau += self._nullspace_state @ arm.state
        return tau

    def reached(self, arm: ArmState) -> bool:
        """Interpolation done, within 1 mm and 0.5° of the final goal and nearly at rest."""
        return (
            not self._moving
            and math.sqrt(self._local[0] @ self._local[0]) < REACHED_POSITION
            and math.sqrt(self._e_rot @ self._e_rot) < REACHED_ANGLE
            and math.sqrt(arm.twist[:3] @ arm.twist[:3]) < REST_LINEAR
            and math.sqrt(arm.twist[3:] @ arm.twist[3:]) < REST_ANGULAR
        )


class JointImpedance:
    """``τ = K (q_set − q) − D q̇ + bias`` with ``D = 2 ζ sqrt(K M_ii)``.

    The set point moves linearly from the start configuration so that the fastest joint runs
    at JOINT_SPEED; damping acts on the error velocity. D is recomputed only when the arm
    state refreshes its mass matrix.
    """

    def __init__(
        self, arm: ArmState, goal: np.ndarray, stiffness: np.ndarray, damping: np.ndarray
    ) -> None:
        self.goal = np.asarray(goal, dtype=float)
        self.stiffness = np.asarray(stiffness, dtype=float)
        self.ratio = np.asarray(damping, dtype=float)
        self._q0 = arm.q[:ARM_DOF].copy()
        self._dq = self.goal - self._q0
        self.duration = float(np.max(np.abs(self._dq))) / JOINT_SPEED
        self._v_set = self._dq / self.duration if self.duration > 0 else np.zeros(ARM_DOF)
        self.elapsed = 0.0
        self._mass_diag: np.ndarray | None = None
        self._damping = np.zeros(ARM_DOF)

    def torque(self, arm: ArmState) -> np.ndarray:
        s = 1.0 if self.duration <= 0 else min(self.elapsed / self.duration, 1.0)
        self.elapsed += DT
        q, v = arm.q[:ARM_DOF], arm.v[:ARM_DOF]
        if arm.mass_diag is not self._mass_diag:
            self._mass_diag = arm.mass_diag
            self._damping = 2.0 * self.ratio * np.sqrt(self.stiffness * arm.mass_diag)
        v_set = self._v_set if s < 1.0 else 0.0
        return (
            self.stiffness * (self._q0 + s * self._dq - q) + self._damping * (v_set - v) + arm.bias
        )

    def reached(self, arm: ArmState) -> bool:
        """Every joint within 0.5° of the goal and nearly at rest."""
        return (
            self.elapsed >= self.duration
            and float(np.max(np.abs(self.goal - arm.q[:ARM_DOF]))) < REACHED_ANGLE
            and float(np.max(np.abs(arm.v[:ARM_DOF]))) < REST_JOINT
        )
