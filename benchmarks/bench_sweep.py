"""Speed-up of a sweep on a Dask LocalCluster of two workers over one worker.

Run: ``.venv/bin/python benchmarks/bench_sweep.py [seeds] [adapter]`` (default 12 seeds of the
rail task on the ``pinocchio`` twin at two noise levels; the ``dryrun`` adapter has no camera
noise and runs without). The same sweep runs first on one
worker, the baseline, then on two; each cluster is started before its clock starts. The
script prints both wall times, the runs per minute and the speed-up, and checks that both
sweeps gave the same outcome for every run (runs are deterministic per seed). The goal: two
workers at least 1.5x as fast as one (ideal 2x; the machine's other load takes its share).
"""

from __future__ import annotations

import logging
import math
import sys
import time
from pathlib import Path

from distributed import Client, LocalCluster

from lightrocks.app.pipeline import load
from lightrocks.app.specs import run_spec
from lightrocks.app.sweep import grid_points, sweep

ROOT = Path(__file__).resolve().parents[1]
MODEL = ROOT / "examples/din_rail/tasks/AssembleRail.lr"
NOISES = [(0.0, 0.0), (0.002, math.radians(2.0))]


GOAL = 1.5
"""Speed-up of two workers over one."""


def timed_sweep(workers: int, adapter: str, seeds: range) -> tuple[float, list]:
    noises = NOISES[:1] if adapter == "dryrun" else NOISES
    with (
        LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            dashboard_address=":0",  # any free port: several clusters may run at once
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        client.wait_for_workers(workers)
        search_path = [ROOT / "examples"]
        cls = load(MODEL, search_path)
        points = grid_points([], noises)
        specs = [run_spec(cls, MODEL, search_path, [], adapter, noise=p.noise) for p in points]
        start = time.perf_counter()
        results = sweep(client, points, specs, seeds)
        return time.perf_counter() - start, results


def main() -> None:
    seeds = range(int(sys.argv[1]) if len(sys.argv) > 1 else 12)
    adapter = sys.argv[2] if len(sys.argv) > 2 else "pinocchio"
    one, baseline = timed_sweep(1, adapter, seeds)
    two, results = timed_sweep(2, adapter, seeds)
    runs = len(results)
    same = [r.outcome for _, r in baseline] == [r.outcome for _, r in results]
    print(f"sweep of {runs} runs of {MODEL.stem} on {adapter}")
    print(f"  1 worker  (baseline): {one:7.1f} s   {runs / one * 60:6.1f} runs/min")
    print(f"  2 workers           : {two:7.1f} s   {runs / two * 60:6.1f} runs/min")
    verdict = "met" if one / two >= GOAL else "NOT met"
    print(f"  speed-up: {one / two:.2f}x (ideal 2.00x; goal >= {GOAL:.1f}x: {verdict}); "
          f"same outcomes per run: {same}")  # fmt: skip


if __name__ == "__main__":
    main()
