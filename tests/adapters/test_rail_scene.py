"""Physics of the top-hat rail cell (adapters/models/din_rail.xml) and its analytic twin.

Fixture tests push a terminal with a "virtual gripper": a wrench on the terminal body that
keeps it centred and upright (like the arm's Cartesian impedance) and pushes it down with a
force ramp. The arm is held up by gravity compensation so that it stays out of the way.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.scene_registry import load_model
from lightrocks.adapters.scenes import din_rail
from lightrocks.runtime.contract import Command, CommandResult, StopCondition


def one(adapter, device: str, command: str, args: dict, stop: list, budget: float) -> CommandResult:
    """One command alone, as an action runs it."""
    return adapter.execute([Command(device, command, args, stop, budget)])[0]


class Cell:
    """The rail scene with a virtual gripper on one terminal."""

    def __init__(self, terminal: str = "terminal2") -> None:
        self.model = load_model("din_rail")
        self.data = mujoco.MjData(self.model)
        self.terminal = terminal
        self.body = self.model.body(terminal).id
        free = self.model.joint(terminal)
        self.qadr, self.vadr = int(free.qposadr[0]), int(free.dofadr[0])
        self.arm_dofs = [int(self.model.joint(f"j{i}").dofadr[0]) for i in range(1, 8)]
        mujoco.mj_forward(self.model, self.data)

    def place_over_rail(self, height: float = 0.0028) -> None:
        """Put the terminal upright over its rail slot, ``height`` above the latched pose."""
        y = din_rail.TERMINAL_Y[din_rail.TERMINALS.index(self.terminal)]
        self.data.qpos[self.qadr : self.qadr + 7] = [
            din_rail.RAIL_X,
            y,
            din_rail.RAIL_LIP_TOP_Z + height,
            1,
            0,
            0,
            0,
        ]
        self.target = np.array([din_rail.RAIL_X, y])
        mujoco.mj_forward(self.model, self.data)

    @property
    def height(self) -> float:
        return float(self.data.xpos[self.body][2]) - din_rail.RAIL_LIP_TOP_Z

    def values(self) -> dict[str, float | bool]:
        return din_rail.SCENE.measurements(self.model, self.data)

    def step(self, push: float | None = None) -> None:
        """One step; ``push`` [N, down positive] holds and pushes, None lets go."""
        d = self.data
        d.qfrc_applied[self.arm_dofs] = d.qfrc_bias[self.arm_dofs]
        wrench = np.zeros(6)
        if push is not None:
            pos, vel = d.xpos[self.body], d.qvel[self.vadr : self.vadr + 6]
            wrench[:2] = 2000.0 * (self.target - pos[:2]) - 14.0 * vel[:2]
            wrench[2] = -push
            tilt = np.zeros(3)
            mujoco.mju_quat2Vel(tilt, d.xquat[self.body], 1.0)
            spin = d.xmat[self.body].reshape(3, 3) @ vel[3:]
            wrench[3:] = -0.5 * tilt - 0.004 * spin
        d.xfrc_applied[self.body] = wrench
        din_rail.SCENE.step(self.model, d)
        mujoco.mj_step(self.model, d)

    def ramp(self, rate: float, until: float) -> float | None:
        """Push with a force rising at ``rate`` N/s up to ``until`` N; the force at the snap."""
        snap = None
        for i in range(round(until / rate / self.model.opt.timestep)):
            force = rate * i * self.model.opt.timestep
            self.step(force)
            if snap is None and self.height < 0.0002:
                snap = force
        return snap


def test_scene_loads_with_named_bodies_and_terminals_rest_in_the_tray() -> None:
    cell = Cell()
    for body in ("table", "rail", "tray", *din_rail.TERMINALS):
        assert cell.model.body(body).id >= 0
    start = np.array([cell.data.body(t).xpos.copy() for t in din_rail.TERMINALS])
    for _ in range(500):
        cell.step()
    end = np.array([cell.data.body(t).xpos.copy() for t in din_rail.TERMINALS])
    assert np.max(np.abs(end - start)) < 5e-4
    assert all(cell.data.body(t).xmat[8] > 0.999 for t in din_rail.TERMINALS)
    assert start[:, 2] == pytest.approx(din_rail.TERMINAL_TRAY_Z, abs=5e-4)
    assert cell.values()["terminals_latched"] == 0


def test_terminal_snaps_on_near_the_design_force_and_stays_latched() -> None:
    cell = Cell()
    cell.place_over_rail()
    snap = cell.ramp(rate=40.0, until=45.0)
    print(f"snap-through force: {snap:.1f} N")
    assert snap is not None
    assert snap == pytest.approx(din_rail.SNAP_FORCE, rel=0.15)
    assert 28.0 <= snap <= 40.0
    for _ in range(500):  # let go
        cell.step()
    values = cell.values()
    assert values["terminal2_latched"]
    assert not values["terminal1_latched"] and not values["terminal3_latched"]
    assert abs(values["terminal2_height"]) < 3e-4
    cell.data.xfrc_applied[cell.body, 2] = 15.0  # pull up moderately: the catches hold
    for _ in range(500):
        cell.data.qfrc_applied[cell.arm_dofs] = cell.data.qfrc_bias[cell.arm_dofs]
        mujoco.mj_step(cell.model, cell.data)
    assert cell.values()["terminal2_latched"]
    assert cell.height < 3e-4


def test_terminal_pushed_below_the_snap_force_does_not_latch() -> None:
    cell = Cell("terminal1")
    cell.place_over_rail()
    cell.ramp(rate=40.0, until=20.0)
    for _ in range(300):
        cell.step(20.0)
    assert not cell.values()["terminal1_latched"]
    assert cell.height > 0.001  # still riding on the ramps
    for _ in range(500):
        cell.step()
    assert not cell.values()["terminal1_latched"]


def test_rail_twin_snaps_and_holds() -> None:
    twin = din_rail.RailTwin()
    down = np.diag([1.0, -1.0, -1.0])
    grasp = np.array([din_rail.TRAY_X, 0.0, din_rail.TERMINAL_TRAY_Z + 0.025])
    assert twin.graspable(grasp)
    twin.step(0.001, grasp, down, holding=True)
    over = np.array([din_rail.RAIL_X, 0.0, din_rail.RAIL_LIP_TOP_Z + 0.004 + 0.025])
    twin.step(0.001, over, down, holding=True)
    forces = []
    for i in range(500):  # move down 5 mm
        tcp = over - np.array([0.0, 0.0, 1e-5 * i])
        forces.append(twin.step(0.001, tcp, down, holding=True)[2])
    assert max(forces[:390]) == pytest.approx(din_rail.SNAP_FORCE, rel=0.05)
    assert twin.measurements()["terminal2_latched"]
    twin.step(0.001, tcp, down, holding=False)
    assert twin.measurements()["terminal2_latched"]
    assert twin.measurements()["terminals_latched"] == 1


@pytest.mark.parametrize(("across", "latches"), [(0.005, True), (-0.005, True), (0.007, False)])
def test_rail_twin_leads_a_terminal_within_6mm_onto_the_centre_line(
    across: float, latches: bool
) -> None:
    twin = din_rail.RailTwin()
    down = np.diag([1.0, -1.0, -1.0])
    grasp = np.array([din_rail.TRAY_X, 0.0, din_rail.TERMINAL_TRAY_Z + 0.025])
    twin.step(0.001, grasp, down, holding=True)
    over = np.array([din_rail.RAIL_X + across, 0.0, din_rail.RAIL_LIP_TOP_Z + 0.008 + 0.025])
    for i in range(900):  # down 9 mm
        twin.step(0.001, over - np.array([0.0, 0.0, 1e-5 * i]), down, holding=True)
    assert twin.measurements()["terminal2_latched"] is latches
    if latches:
        assert twin.terminals["terminal2"].position[0] == din_rail.RAIL_X


@pytest.mark.parametrize("across", [0.008, -0.008])
def test_rail_twin_terminal_beyond_the_lead_in_stands_on_a_lip_and_twists_the_wrist(
    across: float,
) -> None:
    """The wedge's end on the lip, 23.5 mm from the terminal's centre, pushes up there: about
    the TCP above the centre that is a twist about y of 23.5 mm times the force, its sign
    telling the side."""
    twin = din_rail.RailTwin()
    down = np.diag([1.0, -1.0, -1.0])
    grasp = np.array([din_rail.TRAY_X, 0.0, din_rail.TERMINAL_TRAY_Z + 0.025])
    twin.step(0.001, grasp, down, holding=True)
    standing = din_rail.RAIL_LIP_TOP_Z + din_rail.RAMP_BOTTOM + 0.025
    tcp = np.array([din_rail.RAIL_X + across, 0.0, standing + 0.001])
    assert not twin.step(0.001, tcp, down, holding=True).any()
    wrench = twin.step(0.001, tcp - np.array([0.0, 0.0, 0.0011]), down, holding=True)
    assert wrench[2] == pytest.approx(twin.seat_stiffness * 1e-4)
    assert wrench[4] == pytest.approx(math.copysign(0.0235, across) * wrench[2])
    assert not twin.measurements()["terminal2_latched"]
    assert twin.measurements()["terminal2_height"] == pytest.approx(din_rail.RAMP_BOTTOM)


# --- robot level: pick a terminal from the tray and snap it onto the rail ---------------------

GRASP_HEIGHT = 0.028
"""TCP above a terminal's underside when grasping: fingertips 13 mm above it."""


class ClickDetector:
    """Stop predicate: the force along the push rises to a peak, drops sharply (the click),
    and rises again as the housing seats on the rail. Records the force trace."""

    def __init__(self) -> None:
        self.trace: list[float] = []
        self.peak = 0.0
        self.clicked = False

    def __call__(self, snap) -> bool:
        force = snap.robot.wrench.force.z  # the rail pushes the tool up
        self.trace.append(force)
        if not self.clicked:
            self.peak = max(self.peak, force)
            self.clicked = self.peak > 15.0 and force < 0.6 * self.peak
            return False
        return force > 0.9 * self.peak


def _snap_on(adapter, terminal: str) -> ClickDetector:
    """Pick ``terminal`` from the tray, push it onto its rail slot until the click, let go."""
    down = adapter.snapshot().robot.tcp.rotation
    reached = [StopCondition("done", lambda s: s.robot.goalReached)]
    settled = [StopCondition("done", lambda s: s.gripper.done)]
    grip = [
        StopCondition("holding", lambda s: s.gripper.holding),
        StopCondition("empty", lambda s: s.gripper.done),
    ]
    y = din_rail.TERMINAL_Y[din_rail.TERMINALS.index(terminal)]

    def move(x: float, z: float, speed: float) -> None:
        args = {"goal": pin.SE3(down, np.array([x, y, z])), "speed": speed}
        assert one(adapter, "robot", "moveCartesian", args, reached, 5.0).outcome == "done"

    assert one(adapter, "gripper", "open", {}, settled, 2.0).outcome == "done"
    move(din_rail.TRAY_X, 0.20, 0.2)
    move(din_rail.TRAY_X, din_rail.TERMINAL_TRAY_Z + GRASP_HEIGHT, 0.05)
    assert one(adapter, "gripper", "close", {"force": 20.0}, grip, 2.0).outcome == "holding"
    move(din_rail.TRAY_X, 0.20, 0.1)
    move(din_rail.RAIL_X, 0.20, 0.2)
    move(din_rail.RAIL_X, din_rail.RAIL_LIP_TOP_Z + 0.004 + GRASP_HEIGHT, 0.05)
    click = ClickDetector()
    press = pin.SE3(down, np.array([din_rail.RAIL_X, y, din_rail.RAIL_LIP_TOP_Z - 0.03]))
    stop = [
        StopCondition("clicked", click),
        StopCondition("tooHard", lambda s: s.robot.wrench.force.z > 45.0),
        StopCondition("done", lambda s: s.robot.goalReached),
    ]
    args = {"goal": press, "speed": 0.005}
    assert one(adapter, "robot", "moveCartesian", args, stop, 6.0).outcome == "clicked"
    assert one(adapter, "gripper", "open", {}, settled, 2.0).outcome == "done"
    move(din_rail.RAIL_X, 0.20, 0.1)
    return click


@pytest.mark.slow
@pytest.mark.parametrize("adapter_class", [MujocoAdapter, PinocchioAdapter])
def test_robot_snaps_a_terminal_on_and_hears_the_click(adapter_class) -> None:
    """MuJoCo: the scene's physics; Pinocchio: the arm with the analytic RailTwin."""
    adapter = adapter_class("din_rail")
    try:
        click = _snap_on(adapter, "terminal2")
        values = adapter.measurements()
    finally:
        adapter.close()
    trace = np.array(click.trace)
    top = int(np.argmax(trace >= click.peak))  # the peak before the click
    low = float(np.min(trace[top : top + 50]))
    print(f"peak {trace[top]:.1f} N, then {low:.1f} N within 50 ms; {values}")
    assert trace[top] == pytest.approx(din_rail.SNAP_FORCE, rel=0.2)
    assert low < 0.5 * trace[top]  # the click: a sharp drop right after the peak
    assert values["terminal2_latched"]
    assert not values["terminal1_latched"] and not values["terminal3_latched"]


@pytest.mark.slow
def test_robot_fills_the_rail_with_all_three_terminals() -> None:
    adapter = MujocoAdapter("din_rail")
    try:
        for terminal in din_rail.TERMINALS:
            _snap_on(adapter, terminal)
        values = adapter.measurements()
    finally:
        adapter.close()
    assert values["terminals_latched"] == 3
