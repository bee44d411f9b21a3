"""Speed of both adapters: simulated seconds per wall second with stop predicates every tick.

Run: ``.venv/bin/python benchmarks/bench_adapters.py [seconds] [rounds]``. Each adapter executes
a slow Cartesian motion (goal 10 cm and 30° away) in the empty scene for the given simulated
time with three stop predicates that never hold, evaluated on every 1 kHz tick. The reference
is a bare ``mujoco.mj_step`` loop on the same scene in the same run; the ratio is the
adapter's wall time per tick over the bare step's. The three run in turn for ``rounds`` rounds
(default 3) and the best time of each is reported, because other load on a shared machine only
ever makes a run slower.
"""

from __future__ import annotations

import math
import sys
import time

import mujoco
import numpy as np
import pinocchio as pin

from lightrocks.adapters.mujoco import MujocoAdapter
from lightrocks.adapters.pinocchio import PinocchioAdapter
from lightrocks.adapters.scene_registry import load_model
from lightrocks.runtime.contract import StopCondition

STOPS = [
    StopCondition("force", lambda s: abs(s.robot.wrench.force.z) > 1e3),
    StopCondition("torque", lambda s: abs(s.robot.wrench.torque.z) > 1e3),
    StopCondition("far", lambda s: s.robot.travel.norm() > 10.0),
]


def bare_step_seconds(ticks: int) -> float:
    """Wall seconds per bare mj_step of the empty scene."""
    model = load_model("empty")
    model.opt.timestep = 0.001
    data = mujoco.MjData(model)
    start = time.perf_counter()
    for _ in range(ticks):
        mujoco.mj_step(model, data)
    return (time.perf_counter() - start) / ticks


def adapter_seconds(kind: type, seconds: float) -> float:
    """Wall seconds per control tick of one adapter."""
    adapter = kind()
    tcp = adapter.snapshot().robot.tcp
    goal = tcp * pin.SE3(pin.exp3(np.array([0.0, 0.0, np.deg2rad(30)])), np.array([0, 0.1, 0]))
    args = {"goal": goal, "speed": 0.02, "angular_speed": 0.1}
    start = time.perf_counter()
    adapter.execute("robot", "moveCartesian", args, STOPS, budget=seconds)
    wall = time.perf_counter() - start
    adapter.close()
    return wall / round(seconds * 1000)


def main() -> None:
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 5.0
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    kinds = (MujocoAdapter, PinocchioAdapter)
    bare, ticks = math.inf, dict.fromkeys(kinds, math.inf)
    for _ in range(rounds):
        bare = min(bare, bare_step_seconds(round(seconds * 1000)))
        for kind in kinds:
            ticks[kind] = min(ticks[kind], adapter_seconds(kind, seconds))
    print(f"bare mj_step: {bare * 1e6:.1f} us/tick ({1e-3 / bare:.0f}x real time)")
    for kind, tick in ticks.items():
        print(
            f"{kind.__name__}: {tick * 1e6:.1f} us/tick, {1e-3 / tick:.1f}x real time, "
            f"{tick / bare:.1f}x a bare mj_step"
        )


if __name__ == "__main__":
    main()
