"""Speed of both adapters: time per 1 kHz control tick with stop predicates every tick.

Run: ``.venv/bin/python benchmarks/bench_adapters.py [seconds] [rounds]``. Each adapter executes
a slow Cartesian motion (goal 10 cm and 30° away) in the empty scene for the given simulated
time with three stop predicates that never hold, evaluated on every tick. The reference is a
bare ``mujoco.mj_step`` loop on the same scene in the same run. The three run in turn for
``rounds`` rounds (default 5) and the median of each is reported. Times are CPU seconds of
this process: the loop is single-threaded, and on a machine shared with other work the wall
clock also counts the time the process waits for a core.

Goals: the MuJoCo adapter at most 2x a bare ``mj_step`` per tick; the Pinocchio twin at least
100x real time.
"""

from __future__ import annotations

import statistics
import sys
import time

import mujoco
import numpy as np
import pinocchio as pin

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.scene_registry import load_model
from lightrocks.runtime.contract import Command, StopCondition

STOPS = [
    StopCondition("force", lambda s: abs(s.robot.wrench.force.z) > 1e3),
    StopCondition("torque", lambda s: abs(s.robot.wrench.torque.z) > 1e3),
    StopCondition("far", lambda s: s.robot.travel.norm() > 10.0),
]
GOAL_MUJOCO = 2.0
"""MuJoCo adapter time per tick over a bare mj_step's, at most."""
GOAL_TWIN = 100.0
"""Pinocchio twin simulated seconds per CPU second, at least."""


def bare_step_seconds(ticks: int) -> float:
    """CPU seconds per bare mj_step of the empty scene."""
    model = load_model("empty")
    model.opt.timestep = 0.001
    data = mujoco.MjData(model)
    start = time.process_time()
    for _ in range(ticks):
        mujoco.mj_step(model, data)
    return (time.process_time() - start) / ticks


def adapter_seconds(kind: type, seconds: float) -> float:
    """CPU seconds per control tick of one adapter."""
    adapter = kind()
    tcp = adapter.snapshot().robot.tcp
    goal = tcp * pin.SE3(pin.exp3(np.array([0.0, 0.0, np.deg2rad(30)])), np.array([0, 0.1, 0]))
    args = {"goal": goal, "speed": 0.02, "angular_speed": 0.1}
    start = time.process_time()
    adapter.execute([Command("robot", "moveCartesian", args, STOPS, seconds)])
    spent = time.process_time() - start
    adapter.close()
    return spent / round(seconds * 1000)


def main() -> None:
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 5.0
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    kinds = (MujocoAdapter, PinocchioAdapter)
    bares: list[float] = []
    ticks: dict[type, list[float]] = {kind: [] for kind in kinds}
    for _ in range(rounds):
        bares.append(bare_step_seconds(round(seconds * 1000)))
        for kind in kinds:
            ticks[kind].append(adapter_seconds(kind, seconds))
    bare = statistics.median(bares)
    print(f"median of {rounds} rounds, {seconds:g} s simulated each, CPU time")
    print(f"bare mj_step: {bare * 1e6:.1f} us/tick ({1e-3 / bare:.0f}x real time)")
    for kind, spent in ticks.items():
        tick = statistics.median(spent)
        print(
            f"{kind.__name__}: {tick * 1e6:.1f} us/tick, {1e-3 / tick:.1f}x real time, "
            f"{tick / bare:.1f}x a bare mj_step"
        )
    mujoco_ratio = statistics.median(ticks[MujocoAdapter]) / bare
    twin_speed = 1e-3 / statistics.median(ticks[PinocchioAdapter])
    verdict = "met" if mujoco_ratio <= GOAL_MUJOCO else "NOT met"
    print(f"goal: MujocoAdapter <= {GOAL_MUJOCO:.0f}x a bare mj_step; "
          f"{mujoco_ratio:.1f}x ({verdict})")  # fmt: skip
    verdict = "met" if twin_speed >= GOAL_TWIN else "NOT met"
    print(f"goal: PinocchioAdapter >= {GOAL_TWIN:.0f}x real time; {twin_speed:.1f}x ({verdict})")


if __name__ == "__main__":
    main()
