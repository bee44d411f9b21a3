"""The Franka Emika Panda: its names, limits and gains, its ready pose in both adapters, and a
clear error where its model files (``lightrocks[panda]``) are not installed."""

import dataclasses
from importlib.metadata import PackageNotFoundError
from types import SimpleNamespace

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters import scene_registry
from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.robots import panda
from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.adapters.scene_registry import robot
from lightrocks.runtime.contract import Command, StopCondition

INSTALL = "pip install 'lightrocks[panda]'"


@pytest.fixture(scope="module")
def robot_model(installed) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(installed("panda").mjcf().decode())


def test_the_panda_is_registered_with_its_names_and_gains():
    found = robot("panda")
    assert (found.device_type, found.root, found.hand) == ("Panda", "panda_link0", "panda_hand")
    assert found.joints == (
        *(f"panda_joint{i}" for i in range(1, 8)),
        "panda_finger_joint1",
        "panda_finger_joint2",
    )
    assert found.fingers == ("panda_leftfinger", "panda_rightfinger")
    assert found.joint_stiffness == (600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0)
    assert found.cartesian_stiffness == (3000.0,) * 3 + (300.0,) * 3
    assert "Panda" in found.description


def test_its_motors_have_the_panda_effort_limits(robot_model):
    limits = [float(robot_model.actuator_ctrlrange[i, 1]) for i in range(robot_model.nu)]
    assert limits == [87.0] * 4 + [12.0] * 3 + [100.0] * 2
    assert np.all(robot_model.actuator_ctrlrange[:, 0] == -robot_model.actuator_ctrlrange[:, 1])


def test_the_hand_touches_with_one_box_and_the_fingers_with_their_urdf_boxes(robot_model):
    """MuJoCo's contacts and the twin's box corners are one geometry: the hand's mesh only
    shows, every geom that touches the scene on the hand and fingers is a box."""
    for body in ("panda_hand", "panda_leftfinger", "panda_rightfinger"):
        geoms = [
            g
            for g in range(robot_model.ngeom)
            if robot_model.geom_bodyid[g] == robot_model.body(body).id
        ]
        touching = [
            g for g in geoms if robot_model.geom_contype[g] or robot_model.geom_conaffinity[g]
        ]
        assert touching
        assert all(robot_model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX for g in touching)
        assert all(
            (robot_model.geom_contype[g], robot_model.geom_conaffinity[g]) == (2, 1)
            for g in touching
        )


def test_the_tcp_is_15_mm_above_the_fingertips(robot_model):
    """As on the LWR, so that the skills' grasp heights hold: the lowest point of the finger
    boxes is 15 mm below the TCP along the tool axis."""
    data = mujoco.MjData(robot_model)
    mujoco.mj_forward(robot_model, data)
    tcp = robot_model.site("tcp").id
    axis, origin = data.site_xmat[tcp].reshape(3, 3)[:, 2], data.site_xpos[tcp]
    finger = robot_model.body("panda_leftfinger").id
    lowest = 0.0
    for g in range(robot_model.ngeom):
        if robot_model.geom_bodyid[g] != finger:
            continue
        rotation = data.geom_xmat[g].reshape(3, 3)
        for corner in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).T.reshape(-1, 3):
            point = data.geom_xpos[g] + rotation @ (corner * robot_model.geom_size[g])
            lowest = max(lowest, float(axis @ (point - origin)))
    assert lowest == pytest.approx(0.015, abs=1e-4)


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_the_panda_starts_where_the_lwr_does_and_holds_still(kind, installed):
    """The ready TCP is where the LWR's is, pointing down, turned 10° further about the world
    z axis (so that a turn to the grasp orientation of the rail, 180° from the LWR's ready
    one, goes the way joint 7 has room for); held for a second it moves less than a
    micrometre."""
    installed("panda")
    lwr, arm = kind("empty"), kind("empty", robot="panda")
    assert arm.devices()["robot"] == "Panda"
    assert np.allclose(arm.arm.tcp.translation, lwr.arm.tcp.translation, atol=1e-9)
    turn = lwr.arm.tcp.rotation.T @ arm.arm.tcp.rotation
    assert np.allclose(pin.log3(turn), [0.0, 0.0, -np.radians(10)], atol=1e-9)
    start = arm.arm.tcp
    never = StopCondition("never", lambda s: False)
    (result,) = arm.execute([Command("robot", "moveCartesian", {"goal": start}, [never], 1.0)])
    assert result.outcome == "timeout"
    assert np.linalg.norm(arm.arm.tcp.translation - start.translation) < 1e-6
    assert np.linalg.norm(pin.log3(start.rotation.T @ arm.arm.tcp.rotation)) < 1e-6
    assert arm.snapshot().robot.wrench.force.norm() < 0.05
    lwr.close()
    arm.close()


def test_without_example_robot_data_the_panda_says_what_to_install(monkeypatch):
    def absent(name: str):
        raise PackageNotFoundError(name)

    monkeypatch.setattr(panda, "distribution", absent)
    with pytest.raises(
        RobotDataMissing, match=r"example-robot-data: pip install 'lightrocks\[panda\]'"
    ):
        panda.urdf()
    assert issubclass(RobotDataMissing, ValueError)
    assert robot("panda").device_type == "Panda"  # listing robots reads no model files


def test_example_robot_data_without_the_panda_urdf_is_an_error_too(monkeypatch):
    empty = SimpleNamespace(files=[])
    monkeypatch.setattr(panda, "distribution", lambda name: empty)
    with pytest.raises(RobotDataMissing, match=r"without .*panda\.urdf"):
        panda.urdf()


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_an_adapter_on_a_robot_without_its_files_raises_a_value_error(kind, monkeypatch):
    def absent():
        raise RobotDataMissing(f"robot 'panda' needs the package example-robot-data: {INSTALL}")

    missing_files = dataclasses.replace(panda.ROBOT, locate=absent)
    monkeypatch.setattr(scene_registry, "robots", lambda: {"panda": missing_files})
    with pytest.raises(ValueError, match=r"pip install 'lightrocks\[panda\]'"):
        kind("empty", robot="panda")
