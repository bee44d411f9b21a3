"""The MuJoCo plant's arm state, read from MuJoCo's step, equals the one Pinocchio computes.

The MuJoCo plant does not recompute kinematics and dynamics: it runs each step in two halves
so that MuJoCo has already computed them for the state just reached. These tests pin both
halves of that claim: the values agree with Pinocchio's for the same joint state, also after
steps (so they describe the state reached, not the one before), and in a scene whose robot
joints do not start at address 0.
"""

import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters import kernels as k
from lightrocks.adapters.arm import PinocchioArm, carrier
from lightrocks.adapters.kernels import SLOW_EVERY
from lightrocks.adapters.mujoco.data_view import data_view
from lightrocks.adapters.mujoco.plant import MujocoPlant
from lightrocks.adapters.pinocchio.plant import PinocchioPlant, box_corners
from lightrocks.adapters.robots.common import ARM_DOF, NV
from lightrocks.adapters.robots.lwr import ROBOT as LWR

TOLERANCE = 1e-9
FIELDS = ("q", "v", "position", "rotation", "ft_position", "ft_rotation", "jacobian", "twist")


def _twin_of(plant: MujocoPlant) -> PinocchioArm:
    """A Pinocchio arm state that reads the MuJoCo plant's joint arrays (on ``compute``)."""
    return PinocchioArm(LWR.model(), plant.q, plant.v)


def _assert_same(mujoco_arm, pinocchio_arm) -> None:
    for name in FIELDS:
        mine, theirs = getattr(mujoco_arm, name), getattr(pinocchio_arm, name)
        assert np.allclose(mine, theirs, atol=TOLERANCE), name
    assert np.allclose(mujoco_arm.bias, pinocchio_arm.bias, atol=TOLERANCE)
    assert np.allclose(mujoco_arm.mass_inv, pinocchio_arm.mass_inv, atol=TOLERANCE)
    assert mujoco_arm.point == pytest.approx(pinocchio_arm.point, abs=TOLERANCE)
    tcp, twin_tcp = mujoco_arm.tcp, pinocchio_arm.tcp
    assert np.allclose(tcp.homogeneous, twin_tcp.homogeneous, atol=TOLERANCE)


@pytest.mark.parametrize("scene", ["empty", "screwing"])
def test_arm_states_agree_while_stepping(scene: str) -> None:
    plant = MujocoPlant(scene)
    twin = _twin_of(plant)
    rng = np.random.default_rng(11)
    for _ in range(2 * SLOW_EVERY + 3):
        plant.step(rng.normal(0.0, 20.0, ARM_DOF), grip=10.0)
        plant.arm.update()
        twin.compute()
        twin.update()
        _assert_same(plant.arm, twin)
    assert np.any(plant.v != 0.0)


def test_the_arm_state_describes_the_state_reached_by_the_step() -> None:
    plant = MujocoPlant("empty")
    plant.step(np.full(ARM_DOF, 30.0), grip=0.0)
    plant.arm.update()
    before = plant.arm.position.copy()
    plant.step(np.full(ARM_DOF, 30.0), grip=0.0)
    plant.arm.update()
    twin = _twin_of(plant)
    twin.compute()
    twin.update()
    assert not np.allclose(before, plant.arm.position, atol=1e-12)
    assert np.allclose(plant.arm.position, twin.position, atol=TOLERANCE)


def test_arm_states_agree_on_random_configurations() -> None:
    plant = MujocoPlant("screwing")
    twin = _twin_of(plant)
    rng = np.random.default_rng(5)
    for _ in range(5):
        plant.q[:ARM_DOF] = rng.uniform(-2.0, 2.0, ARM_DOF)
        plant.v[:] = rng.normal(size=NV)
        plant.step(np.zeros(ARM_DOF), grip=0.0)
        twin.compute()
        for _ in range(SLOW_EVERY):  # a fresh mass matrix for the new configuration
            plant.arm.update()
            twin.update()
        _assert_same(plant.arm, twin)


def test_the_flat_view_of_the_data_reads_and_writes_mujocos_arrays() -> None:
    plant = MujocoPlant("screwing")
    names = ("qpos", "ctrl", "site_xmat", "sensordata")
    view, at = data_view(plant.data, names)
    for name in names:
        array = getattr(plant.data, name).reshape(-1)
        assert np.array_equal(view[at[name] : at[name] + array.size], array), name
    view[at["ctrl"] + 2] = 12.5
    assert plant.data.ctrl[2] == 12.5


@pytest.mark.parametrize("kind", ["mujoco", "twin"])
def test_update_takes_the_state_without_advancing_the_wrist_sensing(kind: str) -> None:
    """``sense()`` filters the wrist reading once per tick; ``update()`` leaves it alone."""
    plant = MujocoPlant("empty") if kind == "mujoco" else PinocchioPlant("empty")
    filtered = slice(k.S_VALUES, k.S_R0)
    plant.arm.sensing[k.S_ALPHA] = 0.5  # as a WristSensor sets it
    plant.step(np.full(ARM_DOF, 5.0), grip=0.0)
    plant.arm.sense()
    after_sense = plant.arm.sensing[filtered].copy()
    plant.step(np.full(ARM_DOF, 5.0), grip=0.0)
    plant.arm.update()
    assert np.array_equal(plant.arm.sensing[filtered], after_sense)
    plant.arm.sense()
    assert not np.array_equal(plant.arm.sensing[filtered], after_sense)


def test_a_twin_step_follows_pinocchios_forward_dynamics_with_the_fingers_where_they_are() -> None:
    """The twin's arm accelerations are ABA's for the arm with the fingers locked at their
    current opening (no grip force: the fingers rest), whatever the opening."""
    plant = PinocchioPlant("empty")
    robot, rng = LWR.model(), np.random.default_rng(3)
    fingers = [robot.getJointId(name) for name in LWR.finger_joints]
    damping = -plant._twin[k.T_DAMPING : k.T_DAMPING + ARM_DOF]
    for opening in (0.0, 0.015, 0.04):
        plant.q[:ARM_DOF] = rng.uniform(-1.5, 1.5, ARM_DOF)
        plant.q[ARM_DOF:] = opening
        plant.v[:ARM_DOF], plant.v[ARM_DOF:] = rng.normal(size=ARM_DOF), 0.0
        plant.arm.compute()
        q, v, tau = plant.q.copy(), plant.v.copy(), rng.normal(0.0, 20.0, ARM_DOF)
        arm = pin.buildReducedModel(robot, fingers, q)
        expected = pin.aba(
            arm, arm.createData(), q[:ARM_DOF], v[:ARM_DOF], tau - damping * v[:ARM_DOF]
        )
        plant.step(tau, grip=0.0)
        assert np.allclose((plant.v[:ARM_DOF] - v[:ARM_DOF]) / k.DT, expected, atol=1e-8)
        assert np.allclose(plant.q[:ARM_DOF], q[:ARM_DOF] + k.DT * plant.v[:ARM_DOF], atol=1e-15)
        assert np.array_equal(plant.q[ARM_DOF:], q[ARM_DOF:])


def test_the_twin_clamps_the_torques_to_the_motors_limits_as_mujoco_does() -> None:
    """Torques beyond the motors' ranges act as the limits themselves (MuJoCo clamps a motor's
    control to its ctrlrange): the twin's step with 10 kNm equals ABA's with the limits."""
    plant = PinocchioPlant("empty")
    robot = LWR.model()
    fingers = [robot.getJointId(name) for name in LWR.finger_joints]
    limits = plant.model.actuator_ctrlrange[:ARM_DOF, 1]
    assert list(limits) == [320, 320, 176, 176, 110, 40, 40]
    damping = -plant._twin[k.T_DAMPING : k.T_DAMPING + ARM_DOF]
    q, v = plant.q.copy(), plant.v.copy()
    tau = np.array([1e4, -1e4, 1e4, -1e4, 1e4, -1e4, 1e4])
    arm = pin.buildReducedModel(robot, fingers, q)
    expected = pin.aba(
        arm,
        arm.createData(),
        q[:ARM_DOF],
        v[:ARM_DOF],
        np.sign(tau) * limits - damping * v[:ARM_DOF],
    )
    plant.step(tau, grip=0.0)
    assert np.allclose((plant.v[:ARM_DOF] - v[:ARM_DOF]) / k.DT, expected, atol=1e-8)


def test_the_native_reads_need_the_frames_on_one_joint_that_the_arm_joints_move() -> None:
    robot = LWR.model()

    def body(name: str) -> int:
        return robot.getFrameId(name, pin.BODY)

    tcp, ft = robot.getFrameId("tcp"), robot.getFrameId("ft")
    assert carrier(robot, (tcp, ft, body("hand"))) == robot.getJointId("j7")
    with pytest.raises(ValueError, match="tcp, link1 are not on one joint"):
        carrier(robot, (tcp, body("link1")))
    for name in ("finger_left", "link3"):
        with pytest.raises(ValueError, match="not moved by the arm joints alone"):
            carrier(robot, (body(name),))


def test_the_twins_native_contacts_equal_the_penalty_law_computed_with_numpy() -> None:
    """A box placed over the hand and the left finger: every box-geom corner inside it is
    pushed out through its nearest face, with friction against its velocity, through the
    point's Jacobian (Pinocchio's ``getFrameJacobian``), and adds to the wrench at the ft
    site; the left finger is reported blocked, the right one not."""
    plant = PinocchioPlant("empty")
    robot, data = plant.robot, plant.robot_data
    rng = np.random.default_rng(4)
    plant.v[:] = rng.normal(0.0, 0.2, NV)
    plant.arm.compute()
    pin.updateFramePlacements(robot, data)
    hand = data.oMf[robot.getFrameId("hand", pin.BODY)]
    centre = hand.translation + hand.rotation @ np.array([0.0, 0.05, 0.1])
    rotation, half = pin.exp3(np.array([0.1, -0.2, 0.3])), np.array([0.05, 0.04, 0.03])
    twin = plant._twin
    boxes = twin[k.T_BOXES :].reshape(-1, k.T_BOX)
    boxes[:, k.BOX_NEAR] = 0.0
    boxes[0, k.BOX_NEAR], boxes[0, k.BOX_CENTRE : k.BOX_ROT] = 1.0, centre
    boxes[0, k.BOX_ROT : k.BOX_HALF], boxes[0, k.BOX_HALF :] = rotation.reshape(-1), half
    twin[k.T_GENERALIZED : k.T_GENERALIZED + NV] = 0.0
    twin[k.T_CONTACT : k.T_CONTACT + 6] = 0.0
    arm = plant.arm
    blocked = k.twin_contacts(arm.buffer, twin, arm.index, arm.frames, plant._links, plant._bodies)

    generalized, wrench, touching = np.zeros(NV), np.zeros(6), []
    ft = data.oMf[robot.getFrameId("ft")].translation
    for name in (LWR.hand, *LWR.fingers):
        frame = robot.getFrameId(name, pin.BODY)
        placement = data.oMf[frame]
        jacobian = pin.getFrameJacobian(robot, data, frame, pin.LOCAL_WORLD_ALIGNED)
        hits = 0
        for corner in box_corners(plant.model, name):
            point = placement.act(corner)
            inside = rotation.T @ (point - centre)
            depth = half - np.abs(inside)
            if np.any(depth <= 0):
                continue
            hits += 1
            axis = int(np.argmin(depth))
            normal = rotation[:, axis] * np.sign(inside[axis])
            j_point = jacobian[:3] - pin.skew(point - placement.translation) @ jacobian[3:]
            velocity = j_point @ plant.v
            pressure = max(2e4 * depth[axis] - 200.0 * normal @ velocity, 0.0)
            slip = velocity - (normal @ velocity) * normal
            speed = np.linalg.norm(slip)
            force = pressure * normal - pressure * min(speed / 1e-3, 1.0) * slip / speed
            generalized += j_point.T @ force
            wrench += np.concatenate([force, np.cross(point - ft, force)])
        touching.append(hits > 0)
    assert touching[0] and touching[1] and not touching[2]
    assert blocked == 1
    assert np.allclose(twin[k.T_GENERALIZED : k.T_GENERALIZED + NV], generalized, atol=1e-9)
    assert np.allclose(twin[k.T_CONTACT : k.T_CONTACT + 6], wrench, atol=1e-9)
    assert np.abs(wrench).max() > 1.0
