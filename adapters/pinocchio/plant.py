"""The fast twin: Pinocchio rigid-body dynamics with penalty contacts against static boxes.

The arm is integrated with semi-implicit Euler at 1 kHz from ``M a = τ − h − damping·v + Jᵀf``
(joint damping from the MJCF; τ clamped to the motors' torque limits, as MuJoCo clamps it),
with the arm block of the whole robot's mass matrix (Pinocchio's CRBA) and its nonlinear
effects h (RNEA), the fingers where they are: the very terms the controllers read, computed
once per step at the state it reached. The fingers are a
first-order model: they move at the speed the finger damping of the MJCF gives the
grip force and stop when they would press into a box; their acceleration does not act on
the arm. Contacts are the corners of the hand and finger boxes against
the boxes welded to the world in the scene MJCF (spring-damper normal force, regularised
Coulomb friction); the arm links, the floor plane and moving scene bodies are not collided.
The wrist reading is quasi-static: the hand load's weight plus the contact forces.
Scenes with moving parts (screw, terminals) act through their analytic fixture twin from
their scene object (see adapters.scene): it is stepped with the TCP pose and returns the
wrench it exerts at the TCP; closing on a graspable part stops the fingers at GRASP_WIDTH.
"""

from __future__ import annotations

from typing import Any

import mujoco
import numpy as np
import pinocchio as pin

from lightrocks.adapters import kernels as k
from lightrocks.adapters.arm import PinocchioArm, address, carrier, in_joint
from lightrocks.adapters.robots.common import ARM_DOF, FINGER_TRAVEL, FT_SITE, NV, TCP_SITE
from lightrocks.adapters.scene import FixtureTwin
from lightrocks.adapters.scene_registry import load_model
from lightrocks.adapters.scene_registry import robot as registered_robot
from lightrocks.adapters.scene_registry import scene as registered
from lightrocks.adapters.vec import cross

CONTACT_STIFFNESS = 2e4
"""Normal penalty stiffness per contact point [N/m]."""
CONTACT_DAMPING = 200.0
FRICTION = 1.0
FRICTION_SLIP = 1e-3
"""Sliding speed [m/s] at which friction reaches the Coulomb limit (regularisation)."""
GRAVITY = np.array([0.0, 0.0, -9.81])
GRASP_WIDTH = 0.02
"""Width [m] at which the twin's fingers stop on a part of the scene's fixture twin."""
REACH = 0.2
"""Radius [m] around the hand origin that holds every contact point (broad phase)."""
_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)


def box_corners(model: mujoco.MjModel, body_name: str) -> np.ndarray:
    """The corners of a body's box geoms in the body frame (n x 3): its contact points."""
    body = model.body(body_name).id
    corners = []
    for g in range(model.ngeom):
        if model.geom_bodyid[g] == body and model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX:
            rotation = np.zeros(9)
            mujoco.mju_quat2Mat(rotation, model.geom_quat[g])
            local = _CORNERS * model.geom_size[g]
            corners.append(local @ rotation.reshape(3, 3).T + model.geom_pos[g])
    return np.vstack(corners)


class PinocchioPlant:
    """A scene with a robot (both by registered name; the scene read from the same MJCF)
    simulated with Pinocchio dynamics."""

    def __init__(self, scene: str, robot: str = "lwr") -> None:
        self._scene = registered(scene)
        self._robot = chosen = registered_robot(robot)
        self.model = load_model(scene, robot)
        self.data = mujoco.MjData(self.model)
        joints = [self.model.joint(name) for name in chosen.joints]
        self._qadr = np.array([j.qposadr[0] for j in joints])
        self.robot = chosen.model()
        self.arm = PinocchioArm(self.robot)
        self.q, self.v = self.arm.q, self.arm.v
        """The joint state is the arm state's, integrated in place."""
        self.q[:ARM_DOF], self.q[ARM_DOF:] = chosen.ready, FINGER_TRAVEL
        self.robot_data = self.arm.data
        """Pinocchio's data, shared with the arm state: its ``compute`` serves both."""
        self.arm.compute()
        self.sync()
        boxes = self._static_boxes()
        self._twin = twin = np.zeros(k.TWIN_SIZE + k.T_BOX * len(boxes))
        """Parameters, per-step forces and the static boxes (layout in adapters.kernels)."""
        damping = [self.model.dof_damping[j.dofadr[0]] for j in joints]
        twin[k.T_DAMPING : k.T_DAMPING + NV] = -np.array(damping)
        twin[k.T_TORQUE_LIMIT : k.T_TORQUE_LIMIT + ARM_DOF] = [
            self._torque_limit(name) for name in chosen.arm_joints
        ]
        self._generalized = twin[k.T_GENERALIZED : k.T_GENERALIZED + NV]
        hand = self.model.body(chosen.hand).id
        load_com = self._in_body(hand, self.data.subtree_com[hand])
        twin[k.T_LOAD : k.T_LOAD + 3] = float(self.model.body_subtreemass[hand]) * GRAVITY
        twin[k.T_LOAD_COM : k.T_LOAD_COM + 3] = load_com
        hand_frame = self.robot.getFrameId(chosen.hand, pin.BODY)
        if carrier(self.robot, (hand_frame,)) != self.arm.joint:
            raise ValueError(f"the hand body {chosen.hand!r} is not on the TCP's joint")
        twin[k.T_HAND : k.T_HAND + 12] = in_joint(self.robot, hand_frame)
        twin[k.T_STIFFNESS], twin[k.T_CONTACT_DAMPING] = CONTACT_STIFFNESS, CONTACT_DAMPING
        twin[k.T_FRICTION], twin[k.T_SLIP] = FRICTION, FRICTION_SLIP
        for row, (c, r, h) in zip(twin[k.T_BOXES :].reshape(-1, k.T_BOX), boxes, strict=True):
            reach = np.abs(r) @ h + REACH
            row[k.BOX_REACH : k.BOX_NEAR] = (*(c - reach), *(c + reach))
            row[k.BOX_CENTRE : k.BOX_ROT] = c
            row[k.BOX_ROT : k.BOX_HALF] = r.reshape(-1)
            row[k.BOX_HALF :] = h
        self._links, self._bodies = self._contact_bodies()
        self._contact = twin[k.T_CONTACT : k.T_CONTACT + 6]
        """Environment wrench on the hand subtree at the ft site, world axes."""
        self._tcp_id = self.robot.getFrameId(TCP_SITE)
        self._ft_id = self.robot.getFrameId(FT_SITE)
        self._fixture = self._scene.twin()
        self._grasp = 0.0
        """Finger position [m] where the fingers stop on a grasped fixture part (0: none)."""
        k.twin_wrist(self.arm.buffer, twin, self.arm.index, self.arm.frames)

    @property
    def fixture(self) -> FixtureTwin | None:
        """The scene's analytic fixture twin, if it has one."""
        return self._fixture

    def _torque_limit(self, joint: str) -> float:
        """The largest torque [Nm] of the motor that drives a joint (the MJCF's ``ctrlrange``;
        unlimited without one)."""
        motor = self.model.actuator(joint)
        if not self.model.actuator_ctrllimited[motor.id]:
            return np.inf
        return float(max(-motor.ctrlrange[0], motor.ctrlrange[1]))

    def _in_body(self, body: int, world_point: np.ndarray) -> np.ndarray:
        rotation = self.data.xmat[body].reshape(3, 3)
        return rotation.T @ (world_point - self.data.xpos[body])

    def _static_boxes(self) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """(centre, rotation, half sizes) of every box geom welded to the world."""
        m, d = self.model, self.data
        boxes = []
        for g in range(m.ngeom):
            welded = m.body_weldid[m.geom_bodyid[g]] == 0
            if m.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX and welded:
                boxes.append(
                    (d.geom_xpos[g].copy(), d.geom_xmat[g].reshape(3, 3).copy(), m.geom_size[g])
                )
        return boxes

    def _contact_bodies(self) -> tuple[np.ndarray, np.ndarray]:
        """The ``links`` and ``bodies`` arrays of the contact bodies, the robot's hand and
        fingers (adapters.kernels B_*):
        where Pinocchio keeps each body's joint placement, and the corners of its box geoms
        in its frame."""
        robot, bodies = self.robot, (self._robot.hand, *self._robot.fingers)
        links = np.zeros(k.B_INTS * len(bodies), dtype=np.int64)
        headers, points = [], []
        start = k.B_HEADER * len(bodies)
        for index, name in enumerate(bodies):
            frame = robot.getFrameId(name, pin.BODY)
            joint = robot.frames[frame].parentJoint
            moves = np.zeros(NV)
            moves[[robot.joints[j].idx_v for j in robot.supports[joint].tolist()[1:]]] = 1.0
            headers.append(np.concatenate([in_joint(robot, frame), moves]))
            points.append(box_corners(self.model, name).reshape(-1))
            placement = self.robot_data.oMi[joint]
            link = links[k.B_INTS * index : k.B_INTS * (index + 1)]
            link[k.B_ROT] = address(placement.rotation)
            link[k.B_POS] = address(placement.translation)
            link[k.B_START], link[k.B_COUNT] = start, len(points[-1]) // 3
            start += len(points[-1])
        return links, np.concatenate(headers + points)

    def step(self, tau: np.ndarray, grip: float) -> None:
        """One DT: contacts, arm dynamics, the first-order fingers; then Pinocchio's terms at
        the state reached."""
        arm = self.arm
        if tau is not arm.tau:
            arm.tau[:] = tau
        speed = grip / self._robot.finger_damping
        alone = self._fixture is None
        near = k.twin_step(arm.buffer, self._twin, arm.index, arm.frames, speed, self._grasp, alone)
        if near >= 0:
            self._interact(grip, speed, near > 0)
        arm.compute()

    def _interact(self, grip: float, finger_speed: float, near: bool) -> None:
        """The step ``near`` a static box or with a fixture twin: their forces, then the
        integration."""
        arm, twin = self.arm, self._twin
        blocked = 0
        if near:
            blocked = k.twin_contacts(
                arm.buffer, twin, arm.index, arm.frames, self._links, self._bodies
            )
        if self._fixture is not None:
            self._apply_fixture(self._generalized, grip)
        k.twin_integrate(
            arm.buffer, twin, arm.index, arm.frames,
            finger_speed, self._grasp, bool(blocked & 1), bool(blocked & 2),
        )  # fmt: skip

    def _apply_fixture(self, generalized: np.ndarray, grip: float) -> None:
        """Step the scene's fixture twin; add its wrench at the TCP to joints and wrist."""
        data = self.robot_data
        pin.updateFramePlacements(self.robot, data)
        tcp = data.oMf[self._tcp_id]
        if grip <= 0:
            self._grasp = 0.0
        elif self._grasp == 0.0 and self._fixture.graspable(tcp.translation):
            self._grasp = GRASP_WIDTH / 2
        closed_on_part = self._grasp > 0 and bool(np.all(self.q[ARM_DOF:] < self._grasp + 1e-3))
        wrench = self._fixture.step(k.DT, tcp.translation, tcp.rotation, closed_on_part)
        if not np.any(wrench):
            return
        jacobian = pin.getFrameJacobian(self.robot, data, self._tcp_id, pin.LOCAL_WORLD_ALIGNED)
        generalized += jacobian.T @ wrench
        ft = data.oMf[self._ft_id].translation
        self._contact[:3] += wrench[:3]
        self._contact[3:] += wrench[3:] + cross(tcp.translation - ft, wrench[:3])

    def wrist(self) -> np.ndarray:
        """The raw reading of the last step: the arm state's ``raw``, quasi-static: what link7
        must exert to hold the load against the contacts (the ft site pose and contacts of the
        step's start)."""
        return self.arm.raw

    def sync(self) -> None:
        """Copy the robot state into the MuJoCo data for ground truth and rendering."""
        self.data.qpos[self._qadr] = self.q
        mujoco.mj_kinematics(self.model, self.data)
        mujoco.mj_comPos(self.model, self.data)

    def measurements(self) -> dict[str, Any]:
        if self._fixture is not None:
            return dict(self._fixture.measurements())
        self.sync()
        return self._scene.measurements(self.model, self.data)
