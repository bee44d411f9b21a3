"""Physics of the screwing cell (adapters/models/screwing.xml) and its analytic twin.

Fixture tests drive the screw directly: placed by hand, or turned through the thread's hinge
with a stiff PD "test hand" (no arm control); the arm is held up by gravity compensation so that
it stays out of the way.
"""

from __future__ import annotations

import itertools
import math

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.scene_registry import load_model
from lightrocks.adapters.scenes import screwing
from lightrocks.runtime.contract import Command, CommandResult, StopCondition

HALF_TURN = math.pi
HOLE = np.array([*screwing.SCREW_AXIS_XY, screwing.CUBE_TOP_Z])
"""The hole's mouth on the cube top."""


def one(adapter, device: str, command: str, args: dict, stop: list, budget: float) -> CommandResult:
    """One command alone, as an action runs it."""
    return adapter.execute([Command(device, command, args, stop, budget)])[0]


class Cell:
    """The screwing scene with a PD drive on the thread's hinge."""

    def __init__(self) -> None:
        self.model = load_model("screwing")
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
        return screwing.SCENE.measurements(self.model, self.data)

    def step(self, hinge_torque: float = 0.0, steps: int = 1) -> None:
        d = self.data
        for _ in range(steps):
            d.qfrc_applied[self.arm_dofs] = d.qfrc_bias[self.arm_dofs]
            d.qfrc_applied[self.hinge_v] = hinge_torque
            screwing.SCENE.step(self.model, d)
            mujoco.mj_step(self.model, d)

    def hand_start(self) -> None:
        """Put the screw into the hole's mouth, axial, just past the catch: the thread holds."""
        tip = HOLE - [0.0, 0.0, screwing.CATCH_DEPTH + 1e-5]
        screwing.place_screw(self.model, self.data, tip)
        self.step()
        assert self.values()["thread_caught"]

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
    for body in ("table", "cube", "holder", "screw", "thread", "hand", "finger_left"):
        assert m.body(body).id >= 0
    assert m.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC
    assert m.opt.impratio >= 10
    assert m.geom("screw_head").condim >= 4
    assert not cell.data.eq_active[m.equality("thread_catch").id]


def test_screw_stands_upright_in_its_holder_and_has_not_caught() -> None:
    cell = Cell()
    cell.step(steps=1000)
    values = cell.values()
    assert not values["thread_caught"]
    assert abs(values["screw_depth"]) < 1e-6
    assert [values["screw_x"], values["screw_y"], values["screw_z"]] == pytest.approx(
        screwing.SCREW_START, abs=3e-4
    )
    assert values["screw_tilt"] < math.radians(1.5)


def lower_into_hole(cell: Cell, offset: float, tilt: float, steps: int = 1500) -> None:
    """Hold the screw like a soft hand (position and orientation springs) with its tip over
    the hole + ``offset`` (x), leaning by ``tilt``, and press it down with 2 N."""
    screw = cell.model.body("screw").id
    free = int(cell.model.joint("screw_free").dofadr[0])
    target = HOLE[:2] + np.array([offset, 0.0])
    screwing.place_screw(cell.model, cell.data, [*target, HOLE[2] + 0.002], tilt)
    upright = np.array([math.cos(tilt / 2), math.sin(tilt / 2), 0.0, 0.0])
    for _ in range(steps):
        d = cell.data
        error = np.zeros(3)
        mujoco.mju_subQuat(error, upright, d.xquat[screw])
        v = d.qvel[free : free + 6]
        push = np.zeros(6)
        push[:2] = 500.0 * (target - d.xpos[screw][:2]) - 5.0 * v[:2]
        push[2] = -2.0 + float(cell.model.body_subtreemass[screw]) * 9.81
        push[3:] = 0.2 * error - 0.002 * v[3:]
        d.xfrc_applied[screw] = push
        cell.step()
    cell.data.xfrc_applied[screw] = 0.0


def test_an_axial_screw_entering_the_hole_catches_the_thread_at_depth_zero() -> None:
    cell = Cell()
    lower_into_hole(cell, offset=0.0005, tilt=0.0)
    values = cell.values()
    assert values["thread_caught"]
    assert values["screw_depth"] == pytest.approx(0.0, abs=3e-4)
    assert math.hypot(values["screw_x"] - HOLE[0], values["screw_y"] - HOLE[1]) < 1e-4
    assert values["screw_tilt"] < math.radians(0.2)  # drawn onto the axis by the thread


def test_a_tilted_screw_slides_into_the_hole_without_catching() -> None:
    cell = Cell()
    lower_into_hole(cell, offset=0.0, tilt=math.radians(5.0))
    values = cell.values()
    assert not values["thread_caught"]
    assert values["screw_z"] < HOLE[2] - screwing.CATCH_WINDOW  # it went in, past the catch
    assert abs(values["screw_depth"]) < 1e-6


def test_a_screw_beside_the_hole_rests_on_the_cube() -> None:
    cell = Cell()
    lower_into_hole(cell, offset=0.006, tilt=0.0, steps=800)
    values = cell.values()
    assert not values["thread_caught"]
    assert values["screw_z"] == pytest.approx(HOLE[2], abs=4e-4)  # the wood gives a little


@pytest.mark.parametrize(
    ("tip", "axis_z", "caught"),
    [
        ((0.55, 0.0, 0.1490), 1.0, True),
        ((0.55, 0.0, 0.1495), 1.0, False),  # not in far enough
        ((0.55, 0.0, 0.1470), 1.0, False),  # past the first turn
        ((0.5515, 0.0, 0.1490), 1.0, False),  # off the axis
        ((0.55, 0.0, 0.1490), math.cos(math.radians(2.9)), True),  # within the tolerance
        ((0.55, 0.0, 0.1490), math.cos(math.radians(3.1)), False),  # tilted
    ],
)
def test_catch_rule(tip, axis_z, caught) -> None:
    assert (screwing.catch_depth(np.array(tip), axis_z) is not None) is caught


def test_screw_is_held_by_the_thread() -> None:
    cell = Cell()
    cell.hand_start()
    screw = cell.model.body("screw").id
    start = cell.values()["screw_depth"]
    cell.step(steps=500)
    cell.data.xfrc_applied[screw, 2] = -5.0  # press down on the head: self-locking thread
    cell.step(steps=500)
    assert abs(cell.values()["screw_depth"] - start) < 5e-5
    cell.data.xfrc_applied[screw, 2] = 5.0  # and pull: the thread holds too
    cell.step(steps=500)
    assert abs(cell.values()["screw_depth"] - start) < 5e-5


def test_half_turn_advances_by_half_the_pitch() -> None:
    cell = Cell()
    cell.hand_start()
    start = cell.values()
    cell.turn(HALF_TURN)
    values = cell.values()
    assert values["screw_angle"] - start["screw_angle"] == pytest.approx(HALF_TURN, abs=0.02)
    advance = values["screw_depth"] - start["screw_depth"]
    assert advance == pytest.approx(screwing.SCREW_PITCH / 2, abs=5e-5)
    assert values["screw_z"] == pytest.approx(start["screw_z"] - advance, abs=5e-5)
    assert not values["screw_bottomed"]


@pytest.mark.slow
def test_torque_grows_with_depth_and_bottom_out_stops_the_screw() -> None:
    cell = Cell()
    cell.hand_start()
    means = []
    for _ in range(8):
        torques = cell.turn(HALF_TURN, duration=0.5)
        means.append(float(np.median(torques[100:450])))  # steady part of the turn
    print("median drive torque per half-turn [Nm]:", np.round(means, 3))
    assert means[0] == pytest.approx(screwing.THREAD_TORQUE_START, abs=0.02)
    assert means[-1] == pytest.approx(screwing.THREAD_TORQUE_END, abs=0.03)
    assert all(b > a for a, b in itertools.pairwise(means))
    assert max(means) < 0.32  # the turn-until-0.32-Nm condition fires only at bottom-out
    values = cell.values()
    assert values["screw_depth"] == pytest.approx(screwing.SCREW_TARGET_DEPTH, abs=2e-4)
    assert values["screw_bottomed"]
    # one more half-turn: the screw stays put and the torque needed exceeds 0.32 Nm at once
    torques = cell.turn(HALF_TURN, duration=0.5)
    values = cell.values()
    assert values["screw_depth"] == pytest.approx(screwing.SCREW_TARGET_DEPTH, abs=2e-4)
    assert np.argmax(np.abs(torques) > 0.32) < 50
    assert np.max(np.abs(torques)) > 1.0


DOWN = np.diag([1.0, -1.0, -1.0])
"""A gripper pointing down."""


def test_screw_twin_is_carried_meets_the_cube_and_catches_only_on_the_axis() -> None:
    twin = screwing.ScrewTwin()
    start = np.array(screwing.SCREW_START)
    grasp = start + np.array([0.0, 0.0, screwing.SCREW_LENGTH])
    assert twin.graspable(grasp)
    assert not twin.step(0.001, grasp, DOWN, holding=True).any()
    # carried 4 mm beside the hole, the tip 1 mm into the cube top: pushed up
    beside = HOLE + np.array([0.004, 0.0, screwing.SCREW_LENGTH - 0.001])
    wrench = twin.step(0.001, beside, DOWN, holding=True)
    assert wrench[2] == pytest.approx(twin.contact_stiffness * 0.001)
    assert not twin.caught
    # leaning 3 deg over the hole: not caught
    leaning = DOWN @ pin.utils.rotate("x", math.radians(3.0))
    tip_in = HOLE[2] - screwing.CATCH_DEPTH - 0.0002
    tcp = np.array([*HOLE[:2], tip_in]) - leaning @ [0.0, 0.0, -screwing.SCREW_LENGTH]
    twin.step(0.001, tcp, leaning, holding=True)
    assert not twin.caught
    # axial over the hole: caught at depth 0
    twin.step(0.001, np.array([*HOLE[:2], tip_in + screwing.SCREW_LENGTH]), DOWN, holding=True)
    assert twin.caught
    assert twin.depth == pytest.approx(0.0002)


def test_screw_twin_advances_and_bottoms_out() -> None:
    twin = screwing.ScrewTwin()
    grasp = np.array(screwing.SCREW_START) + np.array([0.0, 0.0, screwing.SCREW_LENGTH])
    twin.step(0.001, grasp, DOWN, holding=True)
    top = HOLE[2] - screwing.CATCH_DEPTH - 1e-6 + screwing.SCREW_LENGTH
    tcp = np.array([*HOLE[:2], top])
    twin.step(0.001, tcp, DOWN, holding=True)
    assert twin.caught and twin.depth == pytest.approx(0.0, abs=1e-5)
    tcp[2] += 0.001  # pulling up: the thread holds the hand down
    assert twin.step(0.001, tcp, DOWN, holding=True)[2] < -10.0
    dt, yaw, torques = 0.001, 0.0, []
    for _ in range(9):  # one half-turn more than needed
        for _ in range(500):
            yaw += HALF_TURN / 500  # tightening: about the TCP z = world -z
            c, s = math.cos(yaw), math.sin(yaw)
            rot = DOWN @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
            tcp[2] = top - twin.depth
            torques.append(twin.step(dt, tcp, rot, holding=True)[5])
        assert twin.step(dt, tcp, rot, holding=False)[5] == 0.0  # release, turn back
        yaw -= HALF_TURN
    values = twin.measurements()
    assert values["screw_bottomed"]
    assert values["screw_depth"] == pytest.approx(screwing.SCREW_TARGET_DEPTH)
    assert 0.04 < torques[250] < 0.07
    assert 0.18 < torques[7 * 500 + 250] < 0.22
    assert max(torques) > 0.32


# --- robot level: the LightRocks screwing skill on the MuJoCo adapter ---------------------

TURN = math.radians(179.5)
"""Just under 180 deg: at exactly 180 deg the controller's log3 picks the turning direction
from rounding noise (either way is the same rotation)."""
TURN_STIFFNESS = [2000.0, 2000.0, 800.0, 150.0, 150.0, 30.0]
TIGHT = 0.32
GRASP_Z = screwing.SCREW_HEAD_TOP_Z - 0.003
"""TCP height for the grasp: fingertips 4 mm above the head's underside."""


def hand_start(adapter) -> None:
    """Start with the screw in the hole and its thread caught, as a worker would leave it."""
    plant = adapter.plant
    if isinstance(adapter, MujocoAdapter):
        tip = HOLE - [0.0, 0.0, screwing.CATCH_DEPTH + 1e-5]
        screwing.place_screw(plant.model, plant.data, tip)
    else:
        plant.fixture.hand_start()


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
    x, y = screwing.SCREW_AXIS_XY
    assert one(adapter, "gripper", "open", {}, settled, 2.0).outcome == "done"
    for z, speed in ((GRASP_Z + 0.05, 0.2), (GRASP_Z, 0.05)):
        goal = pin.SE3(down, np.array([x, y, z]))
        outcome = one(adapter, "robot", "moveCartesian", {"goal": goal, "speed": speed}, reached, 5)
        assert outcome.outcome == "done"
    assert one(adapter, "gripper", "close", {"force": 20.0}, grip, 2.0).outcome == "holding"

    log = []
    advance = screwing.SCREW_PITCH * TURN / (2 * math.pi)  # a screw motion: turn and follow
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
        outcome = one(adapter, "robot", "moveCartesian", args, stop, 6.0).outcome
        log.append((outcome, adapter.measurements()["screw_depth"], peak[0]))
        if outcome != "done":
            break
        assert one(adapter, "gripper", "open", {}, settled, 2.0).outcome == "done"
        back = adapter.snapshot().robot.tcp * pin.SE3(
            pin.rpy.rpyToMatrix(0.0, 0.0, -TURN), np.zeros(3)
        )
        args = {"goal": back, "angular_speed": 1.5}
        assert one(adapter, "robot", "moveCartesian", args, reached, 6.0).outcome == "done"
        assert one(adapter, "gripper", "close", {"force": 20.0}, grip, 2.0).outcome == "holding"
    return log, adapter.measurements()["screw_depth"]


@pytest.mark.slow
@pytest.mark.parametrize("adapter_class", [MujocoAdapter, PinocchioAdapter])
def test_robot_screws_in_until_the_thread_tightens(adapter_class) -> None:
    """MuJoCo: the scene's physics; Pinocchio: the arm with the analytic ScrewTwin."""
    adapter = adapter_class("screwing")
    try:
        hand_start(adapter)
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
    assert depth == pytest.approx(screwing.SCREW_TARGET_DEPTH, abs=2e-4)
    assert values["screw_bottomed"]
