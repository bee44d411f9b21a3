"""Check time of synthetic models from 1,000 to 10,000 states and transitions.

Prints the time per size (the least of three cold runs) and the exponent of a power-law fit
(1.0 = linear growth), each beside its goal: the 10,000-state model checked cold in under
2 s, growth at most slightly above linear (exponent <= 1.05 from 1,000 to 10,000). Then the
re-check of the unchanged 10,000-state workspace, goal < 0.3 s: in the same process
(findings cache in memory) and by a new `lightrocks check` (findings cache on disk), with
the start of that command on an empty folder for comparison. All times are CPU times (of
this process, or of the child), so that other jobs on the machine do not count.
Run: .venv/bin/python benchmarks/bench_check.py
"""

from __future__ import annotations

import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from lightrocks.workbench.check import check

SIZES = (1_000, 2_000, 5_000, 10_000)
GOAL_SECONDS = 2.0
GOAL_EXPONENT = 1.05
GOAL_RECHECK_SECONDS = 0.3


def synthetic(states: int, run: int = 0) -> str:
    """A ring of states; each transition has a guard with a unit and an outcome-like event.
    ``run`` changes a comment only, so that each run is parsed and checked anew."""
    lines = [
        f"// run {run}",
        "package big;",
        "",
        "statechart Big {",
        "  parameters {",
        "    Length x = 0 mm;",
        "  }",
    ]
    lines.append("  initial state S0;")
    lines += [f"  state S{i};" for i in range(1, states)]
    lines += [f"  S{i} -> S{(i + 1) % states} [x < {i} mm] step;" for i in range(states)]
    lines.append("}")
    return "\n".join(lines) + "\n"


def measure(states: int, folder: Path, run: int = 0) -> float:
    package = folder / "big"
    package.mkdir(exist_ok=True)
    (package / "Big.lr").write_text(synthetic(states, run), encoding="utf-8")
    start = time.process_time()
    context = check([folder])
    elapsed = time.process_time() - start
    assert not context.diagnostics.has_errors, context.diagnostics.items[:3]
    return elapsed


def cli_seconds(folder: Path, cache: Path) -> float:
    """CPU time of one `lightrocks check` of ``folder`` in a new process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(
        [sys.executable, "-m", "lightrocks.app.cli", "check", str(folder)],
        env={**os.environ, "XDG_CACHE_HOME": str(cache)},
        check=True,
        stdout=subprocess.DEVNULL,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def verdict(value: float, goal: float) -> str:
    return "met" if value <= goal else "NOT met"


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        measure(100, Path(tmp))  # warm-up: grammar construction happens once per process
        # The least of three cold runs per size: other work on the machine only adds time.
        times = [(n, min(measure(n, Path(tmp), run) for run in range(1, 4))) for n in SIZES]
        in_process = min(measure(SIZES[-1], Path(tmp)) for _ in range(3))
        cache = Path(tmp) / "cache"
        cli_cold = cli_seconds(Path(tmp), cache)
        cli_warm = min(cli_seconds(Path(tmp), cache) for _ in range(3))
        (Path(tmp) / "empty").mkdir()
        startup = min(cli_seconds(Path(tmp) / "empty", cache) for _ in range(3))
    for n, seconds in times:
        print(f"{n:>6} states + {n:>6} transitions: {seconds:6.2f} s")
    xs = [math.log(n) for n, _ in times]
    ys = [math.log(t) for _, t in times]
    mean_x, mean_y = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mean_x) * (y - mean_y) for x, y in zip(xs, ys, strict=True)) / sum(
        (x - mean_x) ** 2 for x in xs
    )
    largest = times[-1][1]
    print(f"fitted exponent: {slope:.2f} (1.00 = linear; goal <= {GOAL_EXPONENT:.2f}: "
          f"{'met' if slope <= GOAL_EXPONENT else 'NOT met'})")  # fmt: skip
    print(f"10,000-state check: {largest:.2f} s (goal < {GOAL_SECONDS:.0f} s: "
          f"{verdict(largest, GOAL_SECONDS)})")  # fmt: skip
    print(f"re-check, unchanged, same process: {in_process:.3f} s, {largest / in_process:.0f}x "
          f"less than cold (goal < {GOAL_RECHECK_SECONDS} s: "
          f"{verdict(in_process, GOAL_RECHECK_SECONDS)})")  # fmt: skip
    print(f"re-check, unchanged, new `lightrocks check`: {cli_warm:.2f} s against {cli_cold:.2f} s "
          f"cold, {cli_cold / cli_warm:.0f}x less (goal < {GOAL_RECHECK_SECONDS} s: "
          f"{verdict(cli_warm, GOAL_RECHECK_SECONDS)}); of it, starting the command on an "
          f"empty folder: {startup:.2f} s")  # fmt: skip


if __name__ == "__main__":
    main()
