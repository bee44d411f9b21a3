"""Cartesian and joint impedance control reach their goals in both adapters."""

import numpy as np
import pinocchio as pin

from lightrocks.runtime.contract import Command, StopCondition

REACHED = [StopCondition("reached", lambda s: s.robot.goalReached)]


def test_cartesian_goal_10cm_30deg_reached_within_3s(adapter):
    start = adapter.snapshot().robot.tcp
    offset = np.array([0.06, 0.05, 0.06])
    offset *= 0.1 / np.linalg.norm(offset)
    goal = start * pin.SE3(pin.exp3(np.array([0.0, 0.0, np.deg2rad(30)])), offset)
    t0 = adapter.time
    result = adapter.execute(
        [
            Command(
                "robot",
                "moveCartesian",
                {"goal": goal, "stiffness": [1000, 1000, 1000, 100, 100, 100]},
                REACHED,
                3.0,
            )
        ]
    )[0]
    assert result.outcome == "reached"
    assert adapter.time - t0 < 3.0
    tcp = adapter.snapshot().robot.tcp
    assert np.linalg.norm(tcp.translation - goal.translation) < 1e-3
    assert np.linalg.norm(pin.log3(tcp.rotation.T @ goal.rotation)) < np.deg2rad(0.5)
    snap = adapter.snapshot()
    assert abs(snap.robot.turned - np.deg2rad(30)) < np.deg2rad(0.5)
    assert np.allclose(snap.robot.travel.array(), goal.translation - start.translation, atol=1e-3)


def test_task_frame_offset_is_the_controlled_frame(adapter):
    task = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.05]))
    start = adapter.snapshot().robot.tcp * task
    goal = start * pin.SE3(pin.exp3(np.array([0.3, 0.0, 0.0])), np.zeros(3))
    result = adapter.execute(
        [Command("robot", "moveCartesian", {"goal": goal, "task": task}, REACHED, 3.0)]
    )[0]
    assert result.outcome == "reached"
    frame = adapter.snapshot().robot.tcp * task
    assert np.linalg.norm(frame.translation - goal.translation) < 1e-3


def test_joint_goal_reached(adapter):
    goal = adapter.snapshot().robot.q + np.deg2rad([10, -5, 10, 5, -10, 5, 20])
    result = adapter.execute([Command("robot", "moveJoint", {"q": goal}, REACHED, 3.0)])[0]
    assert result.outcome == "reached"
    assert np.max(np.abs(adapter.snapshot().robot.q - goal)) < np.deg2rad(0.5)
