"""The Franka Research 3 (robot ``fr3``, the URDF franky-sim ships): its joint ranges from
the model, MuJoCo and Pinocchio agreeing on it, a Cartesian move to its goal in both
adapters, and a clear error where franky-sim (``lightrocks[franka]``) is not installed."""

from importlib.metadata import PackageNotFoundError

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.franka.adapter import FRANKA_ROBOTS
from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.robots import fr3
from lightrocks.adapters.robots.robot import RobotDataMissing
from lightrocks.app.cli import main
from lightrocks.runtime.contract import AdapterError, Command, StopCondition

LOWER = (-2.9007, -1.8361, -2.9007, -3.077, -2.8763, 0.4398, -3.0508)
UPPER = (2.9007, 1.8361, 2.9007, -0.1169, 2.8763, 4.6216, 3.0508)
"""The FR3's joint ranges [rad] as its URDF gives them (joints 4 and 6 unlike the Panda's)."""


def test_both_simulators_read_the_fr3_ranges_and_agree_on_its_kinematics(installed):
    robot = installed("fr3")
    model = mujoco.MjModel.from_xml_string(robot.mjcf().decode())
    twin = robot.model()
    assert robot.device_type == "Panda" and "fr3" in FRANKA_ROBOTS
    assert np.allclose(model.jnt_range[:7], np.column_stack([LOWER, UPPER]))
    assert np.allclose(twin.lowerPositionLimit[:7], LOWER)
    assert np.allclose(twin.upperPositionLimit[:7], UPPER)
    data, frames = mujoco.MjData(model), twin.createData()
    for q in (
        np.array([*robot.ready, 0.04, 0.04]),
        np.array([0.3, 0.5, -0.4, -1.2, 0.6, 1.9, -1.0, 0.01, 0.02]),
    ):
        data.qpos[:] = q
        mujoco.mj_forward(model, data)
        pin.framesForwardKinematics(twin, frames, q)
        for site in ("tcp", "ft"):
            placement = frames.oMf[twin.getFrameId(site)]
            assert np.allclose(placement.translation, data.site(site).xpos, atol=1e-9)
            assert np.allclose(placement.rotation, data.site(site).xmat.reshape(3, 3), atol=1e-9)


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_a_cartesian_move_on_the_fr3_reaches_its_goal(kind, installed):
    """From the ready pose 5 cm down and 5 cm sideways: the goal is reached and the TCP is
    within a millimetre of it."""
    installed("fr3")
    arm = kind("empty", robot="fr3")
    goal = arm.arm.tcp.copy()
    goal.translation += np.array([0.0, 0.05, -0.05])
    reached = StopCondition("reached", lambda s: s.robot.goalReached)
    (result,) = arm.execute([Command("robot", "moveCartesian", {"goal": goal}, [reached], 5.0)])
    assert result.outcome == "reached"
    assert np.linalg.norm(arm.arm.tcp.translation - goal.translation) < 1e-3
    arm.close()


def test_lightrocks_list_robots_shows_the_fr3(capsys):
    assert main(["list", "robots"]) == 0
    rows = [line.split("  ")[:2] for line in capsys.readouterr().out.splitlines()]
    assert ["fr3", "Panda"] in rows


def test_without_franky_sim_the_fr3_says_what_to_install(monkeypatch):
    def absent(name: str):
        raise PackageNotFoundError(name)

    monkeypatch.setattr(fr3, "distribution", absent)
    with pytest.raises(RobotDataMissing, match=r"franky-sim: pip install 'lightrocks\[franka\]'"):
        fr3.urdf()


def test_the_franka_adapter_checks_goals_in_the_fr3s_own_joint_ranges(installed):
    """Joint 6 at 0.3 rad is inside the Panda's range and outside the FR3's: the adapter's
    check takes the ranges from the robot's model."""
    from lightrocks.adapters.franka.limits import Limits

    twin = installed("fr3").model()
    ranges = (twin.lowerPositionLimit[:7], twin.upperPositionLimit[:7])
    goal = np.array([0.0, -0.15, 0.0, -2.29, 0.0, 0.3, 0.6])
    with pytest.raises(AdapterError, match=r"goal: joint 6 at 17\.2 deg is not within"):
        Limits().check_joint(goal, np.full(7, 100.0), ranges)
    panda = installed("panda").model()
    Limits().check_joint(
        goal, np.full(7, 100.0), (panda.lowerPositionLimit[:7], panda.upperPositionLimit[:7])
    )
