"""Physics of the screwing cell (adapters/models/screwing.xml) and its analytic twin.

Fixture tests drive the screw hinge directly with a stiff PD "test hand" (no arm control); the
arm is held up by gravity compensation so that it stays out of the way.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters import scenes
from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.runtime.contract import StopCondition

SCENE = Path(scenes.__file__).parent / "models" / "screwing.xml"
HALF_TURN = math.pi


class Cell:
    """The screwing scene with a PD drive on the screw hinge."""

    def __init__(self) -> None:
        self.model = mujoco.MjModel.from_xml_path(str(SCENE))
        self.data = mujoco.MjData(self.model)
        hinge = self.model.joint("screw_hinge")
        self.hinge_q = int(hinge.qposadr[0])
        self.hinge_v = int(hinge.dofadr[0])
        self.arm_dofs = [int(self.model.joint(f"j{i}").dofadr[0]) for i in range(1, 8)]
        mujoco.mj_forward(self.model, self.data)

    @property
    def angle(self) -> float:
        return float(self.data.qpos[self.hinge_q])

    def values(self) -> dict[str, float | bool]:
        return scenes.measurements("screwing", self.model, self.data)

    def step(self, hinge_torque: float = 0.0) -> None:
        d = self.data
        d.qfrc_applied[self.arm_dofs] = d.qfrc_bias[self.arm_dofs]
        d.qfrc_applied[self.hinge_v] = hinge_torque
        scenes.scene_step("screwing", self.model, d)
        mujoco.mj_step(self.model, d)

    def turn(self, angle: float, duration: float = 1.0) -> np.ndarray:
        """Turn the screw by ``angle`` following a ramp; return the drive torque per step."""
        start, steps = self.angle, round(duration / self.model.opt.timestep)
        torques = np.empty(steps + 200)
        for i in range(len(torques)):
            ref = start + angle * min(i / steps, 1.0)
            rate = angle / duration if i < steps else 0.0
            tau = 5.0 * (ref - self.angle) + 0.05 * (rate - self.data.qvel[self.hinge_v])
            torques[i] = tau
            self.step(tau)
        return torques


def test_scene_loads_with_named_bodies_and_options() -> None:
    cell = Cell()
    m = cell.model
    for body in ("table", "cube", "screw", "hand", "finger_left"):
        assert m.body(body).id >= 0
    assert m.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC
    assert m.opt.impratio >= 10
    assert m.geom("screw_head").condim >= 4
    screw = cell.data.body("screw").xpos
    assert 0.45 <= math.hypot(screw[0], screw[1]) <= 0.6


def test_screw_is_held_by_the_thread() -> None:
    cell = Cell()
    screw = cell.model.body("screw").id
    for _ in range(500):
        cell.step()
    cell.data.xfrc_applied[screw, 2] = -5.0  # press down on the head: self-locking thread
    for _ in range(500):
        cell.step()
    assert abs(cell.values()["screw_depth"]) < 5e-5
    assert abs(cell.angle) < 0.01


def test_half_turn_advances_by_half_the_pitch() -> None:
    cell = Cell()
    cell.turn(HALF_TURN)
    values = cell.values()
    assert values["screw_angle"] == pytest.approx(HALF_TURN, abs=0.02)
    assert values["screw_depth"] == pytest.approx(scenes.SCREW_PITCH / 2, abs=5e-5)
    assert not values["screw_bottomed"]


@pytest.mark.slow
def test_torque_grows_with_depth_and_bottom_out_stops_the_screw() -> None:
    cell = Cell()
    means = []
    for _ in range(8):
        torques = cell.turn(HALF_TURN, duration=0.5)
        means.append(float(np.median(torques[100:450])))  # steady part of the turn
    print("median drive torque per half-turn [Nm]:", np.round(means, 3))
    assert means[0] == pytest.approx(scenes.THREAD_TORQUE_START, abs=0.02)
    assert means[-1] == pytest.approx(scenes.THREAD_TORQUE_END, abs=0.03)
    assert all(b > a for a, b in itertools.pairwise(means))
    assert max(means) < 0.32  # the turn-until-0.32-Nm condition fires only at bottom-out
    values = cell.values()
    assert values["screw_depth"] == pytest.approx(scenes.SCREW_TARGET_DEPTH, abs=2e-4)
    assert values["screw_bottomed"]
    # one more half-turn: the screw stays put and the torque needed exceeds 0.32 Nm at once
    torques = cell.turn(HALF_TURN, duration=0.5)
    values = cell.values()
    assert values["screw_depth"] == pytest.approx(scenes.SCREW_TARGET_DEPTH, abs=2e-4)
    assert np.argmax(np.abs(torques) > 0.32) < 50
    assert np.max(np.abs(torques)) > 1.0


def test_screw_twin_advances_and_bottoms_out() -> None:
    twin = scenes.ScrewTwin()
    tcp = np.array([scenes.SCREW_AXIS_XY[0], scenes.SCREW_AXIS_XY[1], 0.181])
    down = np.diag([1.0, -1.0, -1.0])  # gripper pointing down
    assert twin.graspable(tcp)
    dt, yaw, torques = 0.001, 0.0, []
    for _ in range(9):  # one half-turn more than needed
        for _ in range(500):
            yaw += HALF_TURN / 500  # tightening: about the TCP z = world -z
            c, s = math.cos(yaw), math.sin(yaw)
            rot = down @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
            tcp[2] = 0.181 - twin.depth
            torques.append(twin.step(dt, tcp, rot, holding=True)[5])
        assert twin.step(dt, tcp, rot, holding=False)[5] == 0.0  # release, turn back
        yaw -= HALF_TURN
    values = twin.measurements()
    assert values["screw_bottomed"]
    assert values["screw_depth"] == pytest.approx(scenes.SCREW_TARGET_DEPTH)
    assert 0.04 < torques[250] < 0.07
    assert 0.18 < torques[7 * 500 + 250] < 0.22
    assert max(torques) > 0.32


# --- robot level: the LightRocks screwing skill on the MuJoCo adapter ---------------------

TURN = math.radians(179.5)
"""Just under 180 deg: at exactly 180 deg the controller's log3 picks the turning direction
from rounding noise (either way is the same rotation)."""
TURN_STIFFNESS = [2000.0, 2000.0, 800.0, 150.0, 150.0, 30.0]
TIGHT = 0.32
GRASP_Z = scenes.SCREW_HEAD_TOP_Z - 0.003
"""TCP height for the grasp: fingertips 4 mm above the head's underside."""


def _screw_in(adapter, *, turns: int = 12) -> tuple[list[tuple[str, float, float]], float]:
    """Grasp the screw and run Turn/Release/TurnBack/Regrasp until the 0.32 Nm condition.

    Returns per turn (outcome, depth after it, peak |torque z|) and the final depth.
    """
    down = adapter.snapshot().robot.tcp.rotation
    reached = [StopCondition("done", lambda s: s.robot.goalReached)]
    settled = [StopCondition("done", lambda s: s.gripper.done)]
    grip = [
        StopCondition("holding", lambda s: s.gripper.holding),
        StopCondition("empty", lambda s: s.gripper.done),
    ]
    x, y = scenes.SCREW_AXIS_XY
    assert adapter.execute("gripper", "open", {}, settled, 2.0).outcome == "done"
    for z, speed in ((GRASP_Z + 0.05, 0.2), (GRASP_Z, 0.05)):
        goal = pin.SE3(down, np.array([x, y, z]))
        outcome = adapter.execute(
            "robot", "moveCartesian", {"goal": goal, "speed": speed}, reached, 5
        )
        assert outcome.outcome == "done"
    assert adapter.execute("gripper", "close", {"force": 20.0}, grip, 2.0).outcome == "holding"

    log = []
    advance = scenes.SCREW_PITCH * TURN / (2 * math.pi)  # a screw motion: turn and follow
    for _ in range(turns):
        peak = [0.0]

        def tight(snap, peak=peak) -> bool:
            torque = abs(snap.robot.wrench.torque.z)
            peak[0] = max(peak[0], torque)
            return torque > TIGHT

        turn = pin.SE3(pin.rpy.rpyToMatrix(0.0, 0.0, TURN), np.array([0.0, 0.0, advance]))
        args = {
            "goal": adapter.snapshot().robot.tcp * turn,
            "stiffness": TURN_STIFFNESS,
            "damping": [0.7] * 6,
            "angular_speed": 1.0,
        }
        stop = [
            StopCondition("torqueLimit", tight),
            StopCondition("done", lambda s: s.robot.goalReached),
        ]
        outcome = adapter.execute("robot", "moveCartesian", args, stop, 6.0).outcome
        log.append((outcome, adapter.measurements()["screw_depth"], peak[0]))
        if outcome != "done":
            break
        assert adapter.execute("gripper", "open", {}, settled, 2.0).outcome == "done"
        back = adapter.snapshot().robot.tcp * pin.SE3(
            pin.rpy.rpyToMatrix(0.0, 0.0, -TURN), np.zeros(3)
        )
        args = {"goal": back, "angular_speed": 1.5}
        assert adapter.execute("robot", "moveCartesian", args, reached, 6.0).outcome == "done"
        assert adapter.execute("gripper", "close", {"force": 20.0}, grip, 2.0).outcome == "holding"
    return log, adapter.measurements()["screw_depth"]


@pytest.mark.slow
@pytest.mark.parametrize("adapter_class", [MujocoAdapter, PinocchioAdapter])
def test_robot_screws_in_until_the_thread_tightens(adapter_class) -> None:
    """MuJoCo: the scene's physics; Pinocchio: the arm with the analytic ScrewTwin."""
    adapter = adapter_class("screwing")
    try:
        log, depth = _screw_in(adapter)
        values = adapter.measurements()
    finally:
        adapter.close()
    for outcome, d, peak in log:
        print(f"{outcome:12s} depth {d * 1e3:5.2f} mm  peak |torque z| {peak:.3f} Nm")
    outcomes = [outcome for outcome, _, _ in log]
    # half-turns advance the screw by 1.5 mm each while the torque stays under 0.32 Nm ...
    assert outcomes[:-1] == ["done"] * (len(log) - 1)
    assert 6 <= len(log) <= 10
    depths = [d for _, d, _ in log]
    assert all(b - a == pytest.approx(0.0015, abs=3e-4) for a, b in itertools.pairwise(depths[:-1]))
    peaks = [p for _, _, p in log[:-1]]
    assert max(peaks) < TIGHT and peaks[-1] > peaks[0] + 0.05  # the thread gets tighter
    # ... until the head seats: then the turn stops on the 0.32 Nm condition at target depth
    assert outcomes[-1] == "torqueLimit"
    assert depth == pytest.approx(scenes.SCREW_TARGET_DEPTH, abs=2e-4)
    assert values["screw_bottomed"]
