"""The franka adapter against the protocol simulator: each elemental action as the arm runs
it, the sensors as stop conditions read them, and the limits checked before anything moves.

One simulator (the empty scene: a table and a block under the ready pose) serves the module;
the tests run in order, each starting where the previous one left the arm.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from importlib.metadata import entry_points
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pinocchio as pin
import pytest
from adapter_support import address, need_franka, simulator

from lightrocks.adapters.franka import link
from lightrocks.adapters.franka.limits import Limits
from lightrocks.runtime.contract import AdapterError, Command, StopCondition

ADDRESS = address(0)
MODELS = Path(__file__).parent / "models"
TOUCH = MODELS / "touch" / "Touch.lr"
READY_TCP = np.array([0.4893, 0.0, 0.3166])
"""Where the Panda's ready pose puts the TCP (the simulator starts there)."""
BLOCK_TOP = 0.15
"""The empty scene's block: its top face [m]."""
REACHED = StopCondition("reached", lambda s: s.robot.goalReached)
DONE = StopCondition("done", lambda s: s.gripper.done)


SIMULATED = pytest.mark.slow
"""The tests on the simulator: a minute or more on two loaded cores."""


@pytest.fixture(scope="module")
def arm() -> Iterator[object]:
    need_franka()
    from lightrocks.adapters.franka import FrankaAdapter

    with simulator("empty", ADDRESS):
        adapter = FrankaAdapter("empty", robot_ip=ADDRESS)
        try:
            assert adapter.fault == ""
            yield adapter
        finally:
            adapter.close()


def down(arm, distance: float, **args) -> Command:
    goal = pin.SE3(np.eye(3), np.array([0.0, 0.0, -distance])) * arm.snapshot().robot.tcp
    contact = StopCondition("contact", lambda s: s.robot.wrench.force.z > 5.0)
    return Command("robot", "moveCartesian", {"goal": goal, **args}, [contact, REACHED], 10.0)


def test_the_entry_point_names_the_adapter() -> None:
    found = {e.name: e.value for e in entry_points(group="lightrocks.adapters")}
    assert found["franka"] == "lightrocks.adapters.franka:FrankaAdapter"


def test_an_adapter_without_address_is_refused() -> None:
    need_franka()
    from lightrocks.adapters.franka import FrankaAdapter

    with pytest.raises(ValueError, match="--robot-ip ADDRESS"):
        FrankaAdapter("empty")
    with pytest.raises(ValueError, match="no Franka arm"):
        FrankaAdapter("empty", robot_ip=ADDRESS, robot="lwr")


@SIMULATED
def test_the_arm_starts_in_the_ready_pose_at_rest(arm) -> None:
    s = arm.snapshot()
    assert arm.devices() == {"robot": "Panda", "gripper": "ParallelGripper", "camera": "Camera"}
    assert np.allclose(s.robot.tcp.translation, READY_TCP, atol=2e-3)
    assert s.robot.wrench.force.norm() < 0.5
    assert s.gripper.done and not s.gripper.holding
    assert "block" in arm.objects()


@SIMULATED
def test_a_goal_outside_the_workspace_is_refused_before_anything_moves(arm) -> None:
    before = arm.snapshot().robot.q
    with pytest.raises(AdapterError, match="outside the workspace box"):
        arm.execute([down(arm, 0.5)])  # 18 cm below the table top
    with pytest.raises(AdapterError, match=r"stiffness\[2\] = 5000 N/m is above"):
        arm.execute([down(arm, 0.05, stiffness=[3000, 3000, 5000, 300, 300, 300])])
    with pytest.raises(AdapterError, match=r"speed 0\.500 m/s is above"):
        arm.execute([down(arm, 0.05, speed=0.5)])
    with pytest.raises(AdapterError, match=r"grasp force 100\.0 N is above"):
        arm.execute([Command("gripper", "close", {"force": 100.0}, [DONE], 5.0)])
    assert np.allclose(arm.snapshot().robot.q, before, atol=1e-4)


@SIMULATED
def test_a_cartesian_motion_reaches_its_goal_and_travels(arm) -> None:
    start = arm.snapshot().robot.tcp.translation
    (result,) = arm.execute([down(arm, 0.05, speed=0.1)])
    s = arm.snapshot()
    assert result.outcome == "reached"
    assert s.robot.tcp.translation[2] == pytest.approx(start[2] - 0.05, abs=1.5e-3)
    assert s.robot.travel.z == pytest.approx(-0.05, abs=1.5e-3)
    assert arm.stats.ticks > 500


@SIMULATED
def test_a_compliant_approach_stops_at_contact_with_the_block(arm) -> None:
    (result,) = arm.execute(
        [down(arm, 0.2, speed=0.05, stiffness=[2000, 2000, 1000, 150, 150, 150])]
    )
    s = arm.snapshot()
    assert result.outcome == "contact"
    assert s.robot.wrench.force.z > 5.0  # the block pushes up: the cell's sign
    assert s.robot.tcp.translation[2] == pytest.approx(BLOCK_TOP + 0.015, abs=6e-3)
    assert s.robot.peakForce >= s.robot.wrench.force.norm() - 1e-9


@SIMULATED
def test_a_joint_motion_reaches_its_configuration(arm) -> None:
    up = arm.snapshot().robot.q.copy()
    up[3] += 0.3  # the elbow opens: the hand lifts off the block
    (result,) = arm.execute([Command("robot", "moveJoint", {"q": up}, [REACHED], 10.0)])
    assert result.outcome == "reached"
    assert np.allclose(arm.snapshot().robot.q, up, atol=np.radians(0.5))


@SIMULATED
def test_the_hand_closes_empty_and_opens(arm) -> None:
    (closed,) = arm.execute([Command("gripper", "close", {"force": 20.0}, [DONE], 10.0)])
    s = arm.snapshot()
    assert closed.outcome == "done" and not s.gripper.holding and s.gripper.width < 2e-3
    (opened,) = arm.execute([Command("gripper", "open", {}, [DONE], 10.0)])
    assert opened.outcome == "done" and arm.snapshot().gripper.width > 0.07


@SIMULATED
def test_the_camera_reports_where_the_scene_places_an_object(arm) -> None:
    seen = StopCondition("seen", lambda s: s.camera.done)
    (result,) = arm.execute([Command("camera", "localize", {"target": "block"}, [seen], 1.0)])
    assert result.outcome == "seen"
    assert np.allclose(result.value.translation, [0.5, 0.0, 0.125], atol=1e-9)


@SIMULATED
def test_a_budget_spent_is_a_timeout_and_the_arm_holds(arm) -> None:
    (result,) = arm.execute([down(arm, 0.05, speed=0.01)])  # 5 s of motion
    assert result.outcome == "reached"  # settle first
    slow = down(arm, 0.05, speed=0.01)
    (result,) = arm.execute([Command(slow.device, slow.command, slow.args, slow.stop, 0.2)])
    assert result.outcome == "timeout"
    held = arm.snapshot().robot.tcp.translation
    arm.execute([Command("camera", "localize", {"target": "block"}, [], 0.3)])
    assert np.allclose(arm.snapshot().robot.tcp.translation, held, atol=2e-3)


@SIMULATED
def test_the_python_api_runs_a_chart_on_the_arm_as_on_mujoco() -> None:
    from lightrocks.app.pipeline import run_model

    where = address(1)
    with simulator("empty", where):
        franka = run_model(TOUCH, [MODELS], adapter="franka", robot_ip=where)
    mujoco = run_model(TOUCH, [MODELS], adapter="mujoco", robot="panda")
    assert franka.outcome == mujoco.outcome == "contact"
    assert franka.time == pytest.approx(mujoco.time, abs=0.3)
    assert franka.measurements == {} and franka.goal is None  # no ground truth on an arm


PANDA_RANGES = (
    np.array([-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973]),
    np.array([2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973]),
)
"""The Panda's joint ranges [rad], as its model gives them to the adapter."""


@pytest.mark.parametrize(
    ("mode", "words"),
    [
        ("Reflex", "is in mode Reflex, not Idle: a reflex stopped it"),
        ("UserStopped", "the user stop (emergency stop) is pressed"),
        ("Guiding", "being guided by hand"),
    ],
)
def test_the_start_check_names_a_robot_in_the_wrong_mode(mode: str, words: str) -> None:
    state = SimpleNamespace(robot_mode=SimpleNamespace(name=mode), current_errors=[], q=[0] * 7)
    with pytest.raises(AdapterError, match=re.escape(words)):
        link.check_start(state, "172.16.0.2", PANDA_RANGES)


def test_the_start_check_refuses_errors_and_joints_at_their_ends() -> None:
    ready = [0.0, -0.15, 0.0, -2.29, 0.0, 2.14, 0.6]
    errors = SimpleNamespace(robot_mode=SimpleNamespace(name="Idle"), current_errors=["x"], q=ready)
    with pytest.raises(AdapterError, match="reports errors"):
        link.check_start(errors, "172.16.0.2", PANDA_RANGES)
    stretched = SimpleNamespace(
        robot_mode=SimpleNamespace(name="Idle"), current_errors=[], q=[*ready[:5], 3.75, 0.6]
    )
    with pytest.raises(AdapterError, match=r"joint 6 at 214\.9 deg is not within"):
        link.check_start(stretched, "172.16.0.2", PANDA_RANGES)


def test_the_limits_set_the_robots_reflexes_above_the_adapters_own() -> None:
    joint, wrench = Limits(force=40.0, torque=8.0).collision_thresholds()
    assert wrench == [50.0] * 3 + [10.0] * 3
    assert len(joint) == 7 and min(joint) > 0


@SIMULATED
def test_a_contact_force_beyond_the_limit_ends_the_motion_and_the_arm_holds(arm) -> None:
    hard = down(arm, 0.2, speed=0.05, stiffness=[3000, 3000, 3000, 300, 300, 300])
    never = [StopCondition("crushed", lambda s: s.robot.wrench.force.z > 500.0)]
    command = Command(hard.device, hard.command, hard.args, never, 10.0)
    with pytest.raises(AdapterError, match=r"contact force \d+\.\d N is above the limit 60"):
        arm.execute([command])
    held = arm.snapshot().robot.tcp.translation
    (result,) = arm.execute([Command("camera", "localize", {"target": "block"}, [], 0.2)])
    assert result.outcome == "timeout"  # the arm took the next command
    assert np.allclose(arm.snapshot().robot.tcp.translation, held, atol=3e-3)


@SIMULATED
def test_two_runs_on_fresh_simulators_are_the_same_tick_for_tick() -> None:
    from lightrocks.adapters.franka import FrankaAdapter

    def once() -> list[tuple]:
        ticks: list[tuple] = []
        with simulator("empty", address(2)):
            adapter = FrankaAdapter("empty", robot_ip=address(2))
            try:
                adapter.execute(
                    [down(adapter, 0.2, speed=0.05, stiffness=[2000, 2000, 1000, 150, 150, 150])],
                    on_tick=lambda s: ticks.append(
                        (s.time, *s.robot.tcp.translation, s.robot.wrench.force.z)
                    ),
                )
            finally:
                adapter.close()
        return ticks

    first = once()
    assert len(first) > 1000 and first == once()


@pytest.mark.parametrize(
    ("options", "words"),
    [
        (["--robot-ip", "172.16.0.2"], "--robot-ip and --confirm are for a real arm"),
        (["--confirm"], "--robot-ip and --confirm are for a real arm"),
        (
            ["--adapter", "mujoco", "--robot", "panda", "--robot-ip", "172.16.0.2"],
            "adapter 'mujoco' has no option robot_ip; adapters that have it: franka",
        ),
        (["--adapter", "franka", "--robot-ip", "172.16.0.2", "--seeds", "2"], "one run at a time"),
        (["--adapter", "franka", "--robot-ip", "172.16.0.2", "--video", "v.mp4"], "cannot record"),
        (["--adapter", "franka"], "a real arm needs its address: --robot-ip ADDRESS"),
    ],
)
def test_the_run_commands_arm_options_are_checked(options, words, capsys) -> None:
    need_franka()
    from lightrocks.app.cli import main

    assert main(["run", str(TOUCH), "--path", str(MODELS), *options]) == 2
    error = capsys.readouterr().err
    assert words in error and "Traceback" not in error


def test_real_time_scheduling_is_required_but_for_a_simulator_on_this_machine() -> None:
    assert link.on_this_machine("127.0.0.1") and link.on_this_machine("127.40.3.9")
    assert link.on_this_machine("localhost")
    assert not link.on_this_machine("172.16.0.2")
    assert not link.on_this_machine("no-such-robot.invalid")
