"""Both adapters implement runtime.contract.Adapter and reject bad input with clear errors."""

import dataclasses

import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.runtime.contract import (
    Adapter,
    AdapterError,
    Command,
    StopCondition,
    Vector3,
    Wrench,
)

DONE = StopCondition("done", lambda s: s.gripper.done)


def test_is_an_adapter(adapter):
    assert isinstance(adapter, Adapter)
    assert adapter.devices() == {"robot": "LWR", "gripper": "ParallelGripper", "camera": "Camera"}


def test_snapshot_has_every_sensor(adapter):
    snap = adapter.snapshot()
    assert snap.time == pytest.approx(adapter.time)
    assert isinstance(snap.robot.tcp, pin.SE3)
    assert isinstance(snap.robot.wrench, Wrench)
    assert isinstance(snap.robot.wrench.torque.z, float)
    assert snap.robot.q.shape == (7,)
    assert isinstance(snap.robot.travel, Vector3)
    assert isinstance(snap.robot.turned, float)
    assert isinstance(snap.robot.goalReached, bool)
    assert snap.gripper.width == pytest.approx(0.08, abs=1e-3)
    assert snap.gripper.holding is False
    assert snap.camera.done is False


@pytest.mark.parametrize(
    ("device", "command", "args", "message"),
    [
        ("arm", "moveCartesian", {}, "unknown device"),
        ("robot", "fly", {}, "no command"),
        ("robot", "moveJoint", {}, "needs the argument 'q'"),
        ("robot", "moveJoint", {"q": [0.0] * 6}, "7 finite numbers"),
        ("robot", "moveJoint", {"q": "up"}, "7"),
        ("robot", "moveJoint", {"q": [0.0] * 7, "speed": 1}, "no parameter"),
        ("robot", "moveCartesian", {"goal": [0, 0, 0]}, "pinocchio.SE3"),
        ("robot", "moveCartesian", {"goal": pin.SE3.Identity(), "stiffness": [1] * 5}, "6"),
        ("robot", "moveCartesian", {"goal": pin.SE3.Identity(), "speed": -1}, "positive"),
        ("robot", "moveCartesian", {"goal": pin.SE3.Identity(), "ref": "nothing"}, "no object"),
        ("gripper", "close", {"force": "hard"}, "number"),
        ("camera", "localize", {"target": "unicorn"}, "no object"),
    ],
)
def test_bad_commands_raise_adapter_errors(adapter, device, command, args, message):
    before = adapter.snapshot().robot.q
    with pytest.raises(AdapterError, match=message):
        adapter.execute([Command(device, command, args, [], 1.0)])
    assert np.allclose(adapter.snapshot().robot.q, before, atol=1e-3)


def test_failing_stop_predicate_is_an_adapter_error(adapter):
    broken = StopCondition("broken", lambda s: s.robot.nonsense > 0)
    with pytest.raises(AdapterError, match="stop condition"):
        adapter.execute(
            [Command("robot", "moveJoint", {"q": adapter.snapshot().robot.q}, [broken], 1.0)]
        )


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_unknown_scene_is_a_value_error(kind):
    with pytest.raises(ValueError, match="unknown scene"):
        kind("atlantis")


@pytest.mark.parametrize("kind", [MujocoAdapter, PinocchioAdapter])
def test_unknown_robot_is_a_value_error_naming_the_known_ones(kind):
    with pytest.raises(ValueError, match=r"unknown robot 'r2d2'; known robots: .*lwr"):
        kind("empty", robot="r2d2")


def test_timeout_leaves_the_robot_holding_still(adapter):
    tcp = adapter.snapshot().robot.tcp
    goal = pin.SE3(tcp.rotation, tcp.translation + np.array([0.0, 0.2, 0.0]))
    t0 = adapter.time
    result = adapter.execute([Command("robot", "moveCartesian", {"goal": goal}, [], 0.5)])[0]
    assert result.outcome == "timeout"
    assert adapter.time - t0 == pytest.approx(0.5, abs=1.5e-3)
    here = adapter.snapshot().robot.tcp.translation
    adapter.execute(
        [Command("robot", "moveCartesian", {"goal": adapter.snapshot().robot.tcp}, [], 0.5)]
    )
    assert np.linalg.norm(adapter.snapshot().robot.tcp.translation - here) < 0.01


def test_first_condition_in_order_wins(adapter):
    stop = [StopCondition("first", lambda s: True), StopCondition("second", lambda s: True)]
    result = adapter.execute(
        [Command("robot", "moveJoint", {"q": adapter.snapshot().robot.q}, stop, 1.0)]
    )[0]
    assert result.outcome == "first"


def test_goal_relative_to_a_scene_object(adapter):
    block = adapter.scene_pose("block")
    above = pin.SE3(adapter.snapshot().robot.tcp.rotation, np.array([0.0, 0.02, 0.2]))
    reached = StopCondition("reached", lambda s: s.robot.goalReached)
    result = adapter.execute(
        [Command("robot", "moveCartesian", {"goal": above, "ref": "block"}, [reached], 3.0)]
    )[0]
    assert result.outcome == "reached"
    expected = (block * above).translation
    assert np.linalg.norm(adapter.snapshot().robot.tcp.translation - expected) < 1e-3


def test_gripper_closes_empty_and_opens(adapter):
    assert adapter.execute([Command("gripper", "close", {}, [DONE], 2.0)])[0].outcome == "done"
    snap = adapter.snapshot()
    assert snap.gripper.width < 0.002
    assert snap.gripper.holding is False
    assert adapter.execute([Command("gripper", "open", {}, [DONE], 2.0)])[0].outcome == "done"
    assert adapter.snapshot().gripper.width == pytest.approx(0.08, abs=1e-3)


def test_ticks_are_told_where_the_stop_conditions_hold_none(adapter):
    ticks: list[int] = []
    t0 = adapter.time
    later = StopCondition("later", lambda s: s.time - t0 > 0.0495)
    q = adapter.snapshot().robot.q
    (result,) = adapter.execute(
        [Command("robot", "moveJoint", {"q": q}, [later], 1.0)],
        lambda s: ticks.append(round((s.time - t0) * 1000)),
    )
    assert result.outcome == "later"
    assert ticks == list(range(1, 50))  # in milliseconds; not the 50th, where it held


def test_a_gripper_command_tells_its_ticks_once_it_has_settled(adapter):
    ticks: list[tuple[float, bool]] = []
    t0 = adapter.time
    after = StopCondition("after", lambda s: s.time - t0 > 0.6)
    adapter.execute(
        [Command("gripper", "close", {}, [after], 1.0)],
        lambda s: ticks.append((s.time - t0, s.gripper.done)),
    )
    assert ticks and all(done for _, done in ticks)
    assert 0.3 < ticks[0][0] < 0.6


def test_commands_of_two_devices_run_in_one_loop_that_tells_each_tick_once(adapter):
    ticks: list[int] = []
    t0 = adapter.time
    q = adapter.snapshot().robot.q
    soon = StopCondition("soon", lambda s: s.time - t0 > 0.0995)
    commands = [
        Command("robot", "moveJoint", {"q": q}, [soon], 1.0),
        Command("gripper", "close", {}, [DONE], 1.0),
    ]
    robot, gripper = adapter.execute(commands, lambda s: ticks.append(round((s.time - t0) * 1000)))
    assert (robot.outcome, gripper.outcome) == ("soon", "done")
    assert adapter.time - t0 > 0.3, "the gripper closed on after the arm's command ended"
    assert ticks == list(range(1, 100)), "the closing gripper checks nothing until it settles"


def test_measurements_is_a_dict(adapter):
    assert isinstance(adapter.measurements(), dict)


def test_value_objects_built_from_floats_equal_the_dataclass_ones():
    """The adapters' fast constructors make the same frozen values as the dataclasses."""
    vector = Vector3.of_floats(1.0, -2.0, 3.5)
    assert vector == Vector3(1.0, -2.0, 3.5) and hash(vector) == hash(Vector3(1.0, -2.0, 3.5))
    assert repr(vector) == repr(Vector3(1.0, -2.0, 3.5))
    wrench = Wrench.of_floats(1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
    assert wrench == Wrench(Vector3(1.0, 2.0, 3.0), Vector3(4.0, 5.0, 6.0))
    with pytest.raises(dataclasses.FrozenInstanceError):
        vector.x = 0.0  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        wrench.force = vector  # type: ignore[misc]
