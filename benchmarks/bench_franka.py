"""The franka adapter's control loop beside the MuJoCo adapter's, on the same task.

Run: ``.venv/bin/python benchmarks/bench_franka.py [rounds]`` (needs ``lightrocks[franka]``).
The task is the compliant approach of the pick-and-place: from the Panda's ready pose straight
down at 5 cm/s, 1000 N/m along z, until the block of the empty scene pushes up with more than
5 N. The franka adapter runs it against the protocol simulator (``lightrocks franka-sim``, in
a process of its own on a loopback address, stepped in lock-step with the client); the MuJoCo
adapter runs it with ``--robot panda``. Each runs ``rounds`` times (default 3), each time on a
fresh simulator or cell; the medians are printed.

Figures: the loop rate (control ticks per wall-clock second), the missed cycles (robot states
that came more than 1.5 ms after the previous one, counted in 1 ms cycles; the lock-step
simulator waits for the client, so these are the client's and the network's), the control
step (the adapter's work from a robot state's arrival to its torque command's departure:
median and p99; for MuJoCo, one whole tick including the physics step), wall-clock seconds
per simulated second, and where the approach stopped.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time

import numpy as np
import pinocchio as pin

from lightrocks.runtime.contract import Command, StopCondition

ADDRESS = "127.0.77.1"
STIFFNESS = [2000.0, 2000.0, 1000.0, 150.0, 150.0, 150.0]
STOPS = [
    StopCondition("contact", lambda s: s.robot.wrench.force.z > 5.0),
    StopCondition("missed", lambda s: s.robot.goalReached),
]
SERVE = (
    "import sys\n"
    "from lightrocks.app.franka_sim import FrankaSim\n"
    "sim = FrankaSim('empty', address=sys.argv[1]); sim.start()\n"
    "print('ready', flush=True); sim.serve()\n"
)


def approach(adapter, ticks: list[float]) -> tuple[str, float, float, float]:
    """Run the approach; outcome, simulated seconds, wall seconds, contact height [m]."""
    tcp = adapter.snapshot().robot.tcp
    goal = pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.25])) * tcp
    args = {"goal": goal, "speed": 0.05, "stiffness": STIFFNESS}
    command = Command("robot", "moveCartesian", args, STOPS, 10.0)
    began, wall = adapter.time, time.perf_counter()
    (result,) = adapter.execute([command], on_tick=lambda _: ticks.append(time.perf_counter()))
    wall = time.perf_counter() - wall
    height = float(adapter.snapshot().robot.tcp.translation[2])
    return result.outcome, adapter.time - began, wall, height


def franka_round() -> dict[str, float | str]:
    from lightrocks.adapters.franka import FrankaAdapter

    server = subprocess.Popen(
        [sys.executable, "-c", SERVE, ADDRESS], stdout=subprocess.PIPE, text=True
    )
    try:
        assert server.stdout is not None and "ready" in server.stdout.readline()
        adapter = FrankaAdapter("empty", robot_ip=ADDRESS)
        if adapter.fault:
            raise SystemExit(f"bench_franka: {adapter.fault}")
        try:
            outcome, simulated, wall, height = approach(adapter, [])
            stats = adapter.stats
            steps = np.array(stats.steps) * 1e6
            return {
                "outcome": outcome,
                "rate": stats.ticks / wall,
                "missed": stats.missed,
                "median": float(np.median(steps)),
                "p99": float(np.percentile(steps, 99)),
                "per_second": wall / simulated,
                "height": height,
            }
        finally:
            adapter.close()
    finally:
        server.terminate()
        server.wait(30)


def mujoco_round() -> dict[str, float | str]:
    from lightrocks.adapters.mujoco import MujocoAdapter

    adapter = MujocoAdapter("empty", robot="panda")
    ticks: list[float] = []
    outcome, simulated, wall, height = approach(adapter, ticks)
    steps = np.diff(ticks) * 1e6
    return {
        "outcome": outcome,
        "rate": round(simulated / 0.001) / wall,
        "missed": 0,
        "median": float(np.median(steps)),
        "p99": float(np.percentile(steps, 99)),
        "per_second": wall / simulated,
        "height": height,
    }


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    rows = {"franka (franky-sim)": franka_round, "mujoco --robot panda": mujoco_round}
    print(f"compliant approach onto the empty scene's block, median of {rounds} rounds")
    print(
        f"{'adapter':22} {'outcome':8} {'loop Hz':>8} {'missed':>6} {'step med µs':>11} "
        f"{'step p99 µs':>11} {'wall s/sim s':>12} {'stop z m':>8}"
    )
    for name, measure in rows.items():
        results = [measure() for _ in range(rounds)]

        def median(key: str, results=results) -> float:
            return statistics.median(float(r[key]) for r in results)

        outcomes = ",".join(sorted({str(r["outcome"]) for r in results}))
        print(
            f"{name:22} {outcomes:8} {median('rate'):8.0f} {median('missed'):6.0f} "
            f"{median('median'):11.0f} {median('p99'):11.0f} {median('per_second'):12.2f} "
            f"{median('height'):8.4f}"
        )


if __name__ == "__main__":
    main()
