"""Robustness of both case studies under perception noise, in MuJoCo.

Run: ``.venv/bin/python benchmarks/bench_case_studies.py [seeds] [workers]`` (default 20 seeds,
one worker per core). Each case study first runs once without noise in this process: the
baseline. Then it runs once per seed with 2 mm / 2 deg camera noise (Gaussian, per axis and
about a random axis) in worker processes. A run succeeds when the task ends in its success
outcome and the scene's ground truth agrees (screw seated; all three terminals latched). The
script prints, per case study, the successes with their 95 % Wilson interval, the simulated
time of the noisy runs against the baseline's, and the wall time per simulated second. The
goal: at least 95 % of the noisy runs succeed.
"""

from __future__ import annotations

import math
import statistics
import sys
import time
from pathlib import Path

from lightrocks.adapters.scenes import goal_met
from lightrocks.workbench.app.run import RunResult, run_once
from lightrocks.workbench.app.seeds import run_seeds, wilson

ROOT = Path(__file__).resolve().parents[1]
NOISE = (0.002, math.radians(2.0))
GOAL = 0.95
"""Share of noisy runs that must succeed."""


CASE_STUDIES = [  # (name, scene, task)
    ("screwing", "screwing", ROOT / "examples/screwing/tasks/ScrewTask.lr"),
    ("din_rail", "din_rail", ROOT / "examples/din_rail/tasks/AssembleRail.lr"),
    ("din_rail_ahead", "din_rail", ROOT / "examples/din_rail_ahead/tasks/AssembleRailAhead.lr"),
]


def succeeded(scene: str, result: RunResult) -> bool:
    """The task says so and the scene's ground truth agrees."""
    return result.success and goal_met(scene, result.measurements)


def main() -> None:
    seeds = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    workers = int(sys.argv[2]) if len(sys.argv) > 2 else None
    print(f"{seeds} seeds per case study, perception noise 2 mm / 2 deg, MuJoCo")
    for name, scene, model in CASE_STUDIES:
        start = time.perf_counter()
        baseline = run_once(model, [], [], "mujoco")
        baseline_wall = time.perf_counter() - start
        start = time.perf_counter()
        results = run_seeds(model, [], [], "mujoco", range(seeds), NOISE, workers=workers)
        wall = time.perf_counter() - start
        wins = sum(succeeded(scene, r) for r in results)
        believed = sum(r.success for r in results)
        low, high = wilson(wins, seeds)
        times = [r.time for r in results]
        failures = [f"seed {r.seed}: {r.outcome}" for r in results if not succeeded(scene, r)]
        verdict = "met" if wins >= GOAL * seeds else "NOT met"
        print(f"\n{name}: {wins}/{seeds} succeeded (95 % interval {low:.0%}-{high:.0%}; "
              f"goal >= {GOAL:.0%}: {verdict})")  # fmt: skip
        print(f"  task outcome says success: {believed}/{seeds}")
        print(f"  baseline (no noise): {baseline.outcome}, {baseline.time:.1f} s simulated")
        print(
            f"  simulated time {statistics.mean(times):.1f} ± {statistics.pstdev(times):.1f} s "
            f"(min {min(times):.1f}, max {max(times):.1f}), "
            f"{statistics.mean(times) / baseline.time:.2f}x the baseline"
        )
        print(
            f"  wall time: baseline {baseline_wall / baseline.time:.3f} s per simulated s; "
            f"{seeds} seeds in {wall:.1f} s"
        )
        if failures:
            print("  failed: " + "; ".join(failures))


if __name__ == "__main__":
    main()
