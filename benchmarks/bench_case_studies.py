"""Robustness of the case studies under perception noise, in MuJoCo: the envelope.

Run: ``.venv/bin/python benchmarks/bench_case_studies.py [--seeds N] [--seed-offset S]
[--noise 0mm,0deg 2mm,2deg ...] [--case din_rail ...] [--workers K] [--plot FILE.png]``
(default: 20 seeds from 0, 2 mm / 2 deg, every case study, one worker per core).

Each case study runs once per seed and noise level (Gaussian camera noise, per axis and about a
random axis) in worker processes. A run succeeds when the task ends in its success outcome and
the scene's ground truth agrees (screw seated; all three terminals latched). Per case study and
level the script prints the successes with their 95 % Wilson interval, the simulated time and
the wall time per simulated second, and the seeds that failed. ``--plot`` draws success
against noise, one line per case study, with the sweep's plot. Measure on seeds that were not
used while tuning the models (e.g. ``--seed-offset 1000``).
"""

from __future__ import annotations

import argparse
import csv
import math
import signal
import statistics
import time
from pathlib import Path

from lightrocks.app.errors import RunError
from lightrocks.app.pipeline import spec_for
from lightrocks.app.run import RunResult
from lightrocks.app.seeds import run_seeds, wilson
from lightrocks.app.sweep import GridPoint, PointSummary, plot_png
from lightrocks.app.values import Noise, parse_noise

ROOT = Path(__file__).resolve().parents[1]
GOALS = ((2e-3, math.radians(2), 0.99), (3e-3, math.radians(3), 0.95))
"""Share of runs that must succeed up to each noise level (position, angle, share)."""


def goal(noise: Noise) -> float | None:
    """The success goal at a noise level: that of the lowest goal level it does not exceed."""
    return next((share for p, a, share in GOALS if noise[0] <= p and noise[1] <= a + 1e-12), None)


def verdict(wins: int, runs: int, low: float, noise: Noise) -> str:
    """The rate against the goal, and whether the interval's lower bound shows it."""
    share = goal(noise)
    if share is None:
        return "no goal at this level"
    rate = "met" if wins >= share * runs else "NOT met"
    shown = "shown" if low >= share else "not shown by the interval"
    return f"goal >= {share:.0%}: {rate}, {shown}"


CASE_STUDIES = {  # name: task
    "screwing": ROOT / "examples/screwing/tasks/ScrewTask.lr",
    "din_rail": ROOT / "examples/din_rail/tasks/AssembleRail.lr",
    "din_rail_ahead": ROOT / "examples/din_rail_ahead/tasks/AssembleRailAhead.lr",
}


def succeeded(result: RunResult) -> bool:
    """The task says so and the scene's ground truth, judged by the run, agrees."""
    return result.success and result.goal is True


def label(noise: Noise) -> str:
    return f"{noise[0] * 1e3:g} mm / {math.degrees(noise[1]):g} deg"


def measure(name: str, seeds: range, noise: Noise, workers: int | None) -> PointSummary:
    """Run one case study at one noise level over ``seeds`` and print its figures. Ended
    early (Ctrl-C, SIGTERM), it reports the runs that finished and raises KeyboardInterrupt."""
    model = CASE_STUDIES[name]
    start = time.perf_counter()
    results: list[RunResult] = []

    def report(result: RunResult) -> None:  # as each run ends: a long sweep shows its progress
        results.append(result)
        verdict = "ok" if succeeded(result) else "FAILED"
        print(f"  seed {result.seed}: {result.outcome} {verdict}", flush=True)

    interrupted = False
    try:
        spec = spec_for(model, [], adapter="mujoco", noise=noise)
        run_seeds(spec, seeds, workers=workers, done=report)
    except KeyboardInterrupt:
        interrupted = True
        print(f"  ended early: {len(results)} of {len(seeds)} runs finished")
    if not results:
        raise KeyboardInterrupt
    wall = time.perf_counter() - start
    wins = sum(succeeded(r) for r in results)
    low, high = wilson(wins, len(results))
    times = [r.time for r in results]
    print(
        f"{name:15} {label(noise):17} {wins:4}/{len(results):<4} "
        f"{wins / len(results):6.1%}  [{low:6.1%}, {high:6.1%}]  "
        f"sim {statistics.mean(times):5.1f} ± {statistics.pstdev(times):4.1f} s  "
        f"wall {wall / sum(times):.3f} s per sim s  "
        f"{verdict(wins, len(results), low, noise)}",
        flush=True,
    )
    believed = sum(r.success for r in results)
    if believed != wins:
        print(f"  the task believed it succeeded {believed} times")
    failures = [f"{r.seed}: {r.outcome}" for r in results if not succeeded(r)]
    if failures:
        print("  failed seeds " + "; ".join(sorted(failures)), flush=True)
    summary = PointSummary(GridPoint((name,), noise), len(results), wins)
    if interrupted:
        raise PartialRun(summary)
    return summary


class PartialRun(KeyboardInterrupt):
    """A sweep ended early, with the summary of the runs that finished."""

    def __init__(self, summary: PointSummary) -> None:
        super().__init__()
        self.summary = summary


def record(table: Path, seeds: range, summaries: list[PointSummary]) -> list[PointSummary]:
    """Append the summaries to a CSV table and return every summary it holds, the runs at
    one case and level added up: runs of this script in parallel (say one per noise level,
    or one per range of seeds) add up to one picture."""
    fields = ["case", "noise_m", "noise_rad", "first_seed", "runs", "successes"]
    new = not table.exists()
    with table.open("a", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        if new:
            writer.writerow(fields)
        for s in summaries:
            writer.writerow([s.point.params[0], *s.point.noise, seeds.start, s.runs, s.successes])
    with table.open(newline="", encoding="utf-8") as stream:
        rows = list(csv.DictReader(stream))
    totals: dict[tuple[str, float, float], tuple[int, int]] = {}
    for row in rows:
        key = (row["case"], float(row["noise_m"]), float(row["noise_rad"]))
        runs, successes = totals.get(key, (0, 0))
        totals[key] = (runs + int(row["runs"]), successes + int(row["successes"]))
    return [
        PointSummary(GridPoint((case,), (length, angle)), runs, successes)
        for (case, length, angle), (runs, successes) in sorted(totals.items())
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, default=20, help="runs per case study and level")
    parser.add_argument("--seed-offset", type=int, default=0, help="the first seed")
    parser.add_argument(
        "--noise", nargs="+", default=["2mm,2deg"], metavar="LENGTH,ANGLE", help="noise levels"
    )
    parser.add_argument("--case", nargs="+", choices=list(CASE_STUDIES), default=None)
    parser.add_argument("--workers", type=int, help="processes (default: one per core)")
    parser.add_argument("--plot", type=Path, help="write success against noise as PNG here")
    parser.add_argument(
        "--table", type=Path, help="append the figures to this CSV; --plot then draws all of it"
    )
    args = parser.parse_args()
    if args.seeds < 1:
        parser.error("--seeds must be at least 1")
    try:
        levels = [parse_noise(text) for text in args.noise]
    except RunError as error:
        parser.error(str(error))
    cases = [c for c in args.case or CASE_STUDIES if CASE_STUDIES[c].is_file()]
    seeds = range(args.seed_offset, args.seed_offset + args.seeds)
    print(
        f"seeds {seeds.start}..{seeds.stop - 1}, MuJoCo; success, 95 % Wilson interval",
        flush=True,
    )
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # ends early like Ctrl-C
    summaries: list[PointSummary] = []
    try:
        for name in cases:
            for noise in levels:
                summaries.append(measure(name, seeds, noise, args.workers))
    except PartialRun as partial:
        summaries.append(partial.summary)
    except KeyboardInterrupt:
        pass
    if args.table:
        summaries = record(args.table, seeds, summaries)
    if args.plot and summaries:
        args.plot.write_bytes(plot_png("case studies", summaries))
        print(f"plot written to {args.plot}")


if __name__ == "__main__":
    main()
