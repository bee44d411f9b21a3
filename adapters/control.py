"""Impedance controllers shared by both adapters; kinematics and dynamics come from Pinocchio.

Runs at 1 kHz: ``ArmState.update`` once per tick, then the active controller's ``torque``.
Everything here is the hot path, so the per-tick work is a handful of Pinocchio calls and small
NumPy products; the operational-space inertia (for damping) and the null-space projector are
refreshed every ``SLOW_EVERY`` ticks only, because they change slowly with the configuration.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from adapters.robot_model import ARM_DOF, NV, TCP_SITE
from adapters.vec import symmetrize_upper

DT = 0.001
SLOW_EVERY = 10
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

_ZEROS = np.zeros(NV)
_LOWER = np.tril_indices(ARM_DOF, -1)


class ArmState:
    """Kinematics and dynamics of the robot at the current tick, computed with Pinocchio."""

    def __init__(self, model: pin.Model) -> None:
        self.model = model
        self.data = model.createData()
        self.tcp_id = model.getFrameId(TCP_SITE)
        self.q = np.zeros(NV)
        self.v = np.zeros(NV)
        self.tcp = pin.SE3.Identity()
        self.jacobian = np.zeros((6, ARM_DOF))
        """TCP Jacobian of the arm joints, LOCAL_WORLD_ALIGNED: rows are v, ω in world axes."""
        self.twist = np.zeros(6)
        self.bias = np.zeros(ARM_DOF)
        """Coriolis, centrifugal and gravity torques of the arm joints."""
        self.mass_inv = np.eye(ARM_DOF)
        self.mass_diag = np.ones(ARM_DOF)
        self._tick = 0

    def update(self, q: np.ndarray, v: np.ndarray) -> None:
        """Recompute everything for joint positions and velocities ``q``, ``v`` (length NV)."""
        model, data = self.model, self.data
        self.q[:] = q
        self.v[:] = v
        pin.computeJointJacobians(model, data, self.q)
        pin.updateFramePlacement(model, data, self.tcp_id)
        self.tcp = data.oMf[self.tcp_id]
        self.jacobian = pin.getFrameJacobian(model, data, self.tcp_id, pin.LOCAL_WORLD_ALIGNED)[
            :, :ARM_DOF
        ]
        self.twist = self.jacobian @ self.v[:ARM_DOF]
        self.bias = pin.rnea(model, data, self.q, self.v, _ZEROS)[:ARM_DOF]
        if self._tick % SLOW_EVERY == 0:
            mass = pin.crba(model, data, self.q)[:ARM_DOF, :ARM_DOF]
            mass = symmetrize_upper(mass.copy(), _LOWER)
            self.mass_inv = np.linalg.inv(mass)
            self.mass_diag = np.diag(mass).copy()
        self._tick += 1


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
    velocity is fed forward.
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
        self.posture = arm.q[:ARM_DOF].copy()
        self.nullspace = np.eye(ARM_DOF)
        start = arm.tcp * task
        self._p0 = start.translation.copy()
        self._r0 = start.rotation.copy()
        self._dp = goal.translation - self._p0
        self._dr = pin.log3(self._r0.T @ goal.rotation)
        distance, angle = np.linalg.norm(self._dp), np.linalg.norm(self._dr)
        self.duration = max(distance / max(speed, 1e-9), angle / max(angular_speed, 1e-9))
        self._v_set = np.zeros(3)
        self._w_set = np.zeros(3)
        if self.duration > 0:
            self._v_set = self._dp / self.duration
            self._w_set = self._r0 @ self._dr / self.duration
        self.elapsed = 0.0
        self.final_error = (np.inf, np.inf)
        self._slow_tick = 0
        self._offset = not task.isIdentity()
        self._world = np.zeros((3, 3))
        self._wrench_local = np.zeros((3, 2))

    def _refresh_slow_terms(self, arm: ArmState, jac: np.ndarray, rotation: np.ndarray) -> None:
        """Damping from Λ and the dynamically consistent null-space projector."""
        lam_inv = jac @ arm.mass_inv @ jac.T
        lam = np.linalg.inv(lam_inv + 1e-6 * np.eye(6))
        lam_local = np.diag(_block_rotate(rotation, lam))
        self.damping = 2.0 * self.ratio * np.sqrt(self.stiffness * np.maximum(lam_local, 0.0))
        jbar = arm.mass_inv @ jac.T @ lam
        self.nullspace = np.eye(ARM_DOF) - jac.T @ jbar.T

    def torque(self, arm: ArmState) -> np.ndarray:
        """Joint torques of the arm for this tick; advances the set point by one DT."""
        s = 1.0 if self.duration <= 0 else min(self.elapsed / self.duration, 1.0)
        self.elapsed += DT
        moving = s < 1.0
        r_set = self._r0 @ pin.exp3(s * self._dr) if moving else self.goal.rotation

        if self._offset:
            frame = arm.tcp * self.task
            rot, pos = frame.rotation, frame.translation
            jac = arm.jacobian.copy()
            jac[:3] -= pin.skew(pos - arm.tcp.translation) @ jac[3:]
            twist = jac @ arm.v[:ARM_DOF]
        else:
            rot, pos = arm.tcp.rotation, arm.tcp.translation
            jac, twist = arm.jacobian, arm.twist
        if self._slow_tick % SLOW_EVERY == 0:
            self._refresh_slow_terms(arm, jac, rot)
        self._slow_tick += 1

        # columns: position error, linear and angular error velocity; rotated to task axes
        world = self._world
        world[:, 0] = self._p0 + s * self._dp - pos
        world[:, 1] = -twist[:3]
        world[:, 2] = -twist[3:]
        if moving:
            world[:, 1] += self._v_set
            world[:, 2] += self._w_set
        local = rot.T @ world
        e_rot = pin.log3(rot.T @ r_set)
        if moving:
            self.final_error = (np.inf, np.inf)
        else:
            self.final_error = (float(np.linalg.norm(local[:, 0])), float(np.linalg.norm(e_rot)))
        k, d = self.stiffness, self.damping
        wrench_local = self._wrench_local
        wrench_local[:, 0] = k[:3] * local[:, 0] + d[:3] * local[:, 1]
        wrench_local[:, 1] = k[3:] * e_rot + d[3:] * local[:, 2]
        wrench = (rot @ wrench_local).T.ravel()
        posture = NULLSPACE_STIFFNESS * (self.posture - arm.q[:ARM_DOF])
        posture -= NULLSPACE_DAMPING * arm.v[:ARM_DOF]
        return jac.T @ wrench + arm.bias + self.nullspace @ posture

    def reached(self, arm: ArmState) -> bool:
        """Within 1 mm and 0.5° of the final goal and nearly at rest."""
        e_pos, e_rot = self.final_error
        return (
            e_pos < REACHED_POSITION
            and e_rot < REACHED_ANGLE
            and np.linalg.norm(arm.twist[:3]) < REST_LINEAR
            and np.linalg.norm(arm.twist[3:]) < REST_ANGULAR
        )


class JointImpedance:
    """``τ = K (q_set − q) − D q̇ + bias`` with ``D = 2 ζ sqrt(K M_ii)``.

    The set point moves linearly from the start configuration so that the fastest joint runs
    at JOINT_SPEED; damping acts on the error velocity.
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

    def torque(self, arm: ArmState) -> np.ndarray:
        s = 1.0 if self.duration <= 0 else min(self.elapsed / self.duration, 1.0)
        self.elapsed += DT
        q, v = arm.q[:ARM_DOF], arm.v[:ARM_DOF]
        damping = 2.0 * self.ratio * np.sqrt(self.stiffness * arm.mass_diag)
        v_set = self._v_set if s < 1.0 else 0.0
        return self.stiffness * (self._q0 + s * self._dq - q) + damping * (v_set - v) + arm.bias

    def reached(self, arm: ArmState) -> bool:
        """Every joint within 0.5° of the goal and nearly at rest."""
        return (
            self.elapsed >= self.duration
            and float(np.max(np.abs(self.goal - arm.q[:ARM_DOF]))) < REACHED_ANGLE
            and float(np.max(np.abs(arm.v[:ARM_DOF]))) < REST_JOINT
        )
