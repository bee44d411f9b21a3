"""Terminal display of runs: a live status line or progress bar on stderr, the summary
tables on stdout."""

from __future__ import annotations

import math
import statistics
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from lightrocks.app.run import RunResult
from lightrocks.app.seeds import wilson
from lightrocks.workbench.report import printable

_SCALES = {
    "_depth": (1e3, "mm", 1),
    "_height": (1e3, "mm", 1),
    "_angle": (180 / math.pi, "deg", 1),
    "_tilt": (180 / math.pi, "deg", 1),
    "_x": (1e3, "mm", 1),
    "_y": (1e3, "mm", 1),
    "_z": (1e3, "mm", 1),
    "_offset": (1e3, "mm", 1),
    "_distance": (1e3, "mm", 1),
    "_torque": (1.0, "Nm", 3),
}
"""Measurement key suffix -> factor from SI, unit, decimals."""


def measurement_label(key: str) -> str:
    return printable(key.replace("_", " "))


def key_measurements(measured: dict[str, float | bool]) -> dict[str, float | bool]:
    """What a per-seed row shows: the yes/no results and the depths."""
    return {k: v for k, v in measured.items() if isinstance(v, bool) or k.endswith("_depth")}


def format_measurement(key: str, value: float | bool | str) -> str:
    """Readable value: metres as millimetres, radians as degrees, booleans as yes/no."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if not isinstance(value, int | float):
        return printable(str(value))
    for suffix, (factor, unit, decimals) in _SCALES.items():
        if key.endswith(suffix):
            return f"{value * factor:.{decimals}f} {unit}"
    return f"{value:g}"


@contextmanager
def live_status() -> Iterator[Callable[[dict[str, Any]], None]]:
    """A live status line on stderr (simulated time, active state path); yields the trace
    listener that updates it."""
    from rich.console import Console

    with Console(stderr=True, highlight=False, markup=False).status("starting") as status:
        path = ""

        def progress(record: dict[str, Any]) -> None:
            nonlocal path
            if record["kind"] == "enter":
                path = record["state"]
            elif record["kind"] == "exit":
                path = record["state"].rpartition("/")[0]
            status.update(f"{record['time']:8.3f} s  {printable(path)}")

        yield progress


def show(name: str, result: RunResult) -> int:
    """The summary of one run on stdout, with the scene's judgement of its goal where it has
    one; 0 when it ended with the success outcome and no hook of the scene raised."""
    from rich.console import Console
    from rich.table import Table

    console = Console(highlight=False, markup=False)
    outcome = printable(result.outcome or "not finished")
    if result.skills:
        table = Table(title=f"{printable(name)}: {outcome}", title_justify="left")
        table.add_column("skill")
        table.add_column("time [s]", justify="right")
        for skill, seconds in result.skills:
            table.add_row(printable(skill), f"{seconds:.3f}")
        console.print(table)
    if result.measurements:
        table = Table()
        table.add_column("measurement")
        table.add_column("value", justify="right")
        for key, value in result.measurements.items():
            table.add_row(measurement_label(key), format_measurement(key, value))
        console.print(table)
    if result.goal is not None:
        print(f"goal: {'met' if result.goal else 'not met'} (the scene's ground truth)")
    print(f"outcome: {outcome} after {result.time:.3f} s")
    if result.active:
        active = " | ".join(path.replace("/", " / ") for path in result.active)
        print(f"active: {printable(active)}")
    if result.fault:
        print(f"error: {printable(result.fault)}")
    if result.scene_fault:
        print(f"error: {printable(result.scene_fault)}")
    if result.video:
        print(printable(result.video))
    return 0 if result.success and not result.scene_fault else 1


@contextmanager
def progress_bar(name: str, runs: int) -> Iterator[Callable[[bool], None]]:
    """A progress bar on stderr counting runs and successes; yields ``advance(succeeded)``."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("{task.fields[succeeded]} succeeded"),
        TimeElapsedColumn(),
    )
    with Progress(*columns, console=Console(stderr=True, highlight=False)) as bar:
        task = bar.add_task(printable(name), total=runs, succeeded=0)
        succeeded = 0

        def advance(success: bool) -> None:
            nonlocal succeeded
            succeeded += success
            bar.update(task, advance=1, succeeded=succeeded)

        yield advance


def show_seeds(name: str, wanted: str | None, results: list[RunResult]) -> int:
    """A row per seed, the success rate with its 95 % Wilson interval (and how many runs the
    scene's ground truth shows at the goal, where it judges one) and the spread of the
    simulated time on stdout; 0 when every run ended with the success outcome and no hook of
    the scene raised."""
    from rich.console import Console
    from rich.table import Table

    keys = list(dict.fromkeys(k for r in results for k in key_measurements(r.measurements)))
    judged = any(r.goal is not None for r in results)
    table = Table(title=f"{printable(name)}: {len(results)} runs", title_justify="left")
    table.add_column("seed", justify="right")
    table.add_column("outcome")
    if judged:
        table.add_column("goal")
    table.add_column("time [s]", justify="right")
    for key in keys:
        table.add_column(measurement_label(key), justify="right")
    for result in results:
        measured = result.measurements
        cells = [format_measurement(k, measured[k]) if k in measured else "" for k in keys]
        goal = [_yes_no(result.goal)] if judged else []
        table.add_row(
            str(result.seed),
            printable(result.outcome or "not finished"),
            *goal,
            f"{result.time:.3f}",
            *cells,
        )
    Console(highlight=False, markup=False).print(table)
    for result in results:
        for fault in (result.fault, result.scene_fault):
            if fault:
                print(f"seed {result.seed}: error: {printable(fault)}")
    count = sum(r.success for r in results)
    low, high = wilson(count, len(results))
    label = printable(wanted or "finished without error")
    rate = (
        f"success ({label}): {count}/{len(results)} = {count / len(results):.0%}, "
        f"95% Wilson interval {low:.0%}–{high:.0%}"
    )
    if judged:
        met = sum(r.goal is True for r in results)
        rate += f"; goal met (the scene's ground truth): {met}/{len(results)}"
    print(rate)
    times = [r.time for r in results]
    spread = statistics.stdev(times) if len(times) > 1 else 0.0
    print(
        f"simulated time: {statistics.fmean(times):.3f} ± {spread:.3f} s, "
        f"min {min(times):.3f} s, max {max(times):.3f} s"
    )
    return 0 if count == len(results) and not any(r.scene_fault for r in results) else 1


def _yes_no(value: bool | None) -> str:
    return "" if value is None else "yes" if value else "no"


_RATE_COLUMNS = ("runs", "successes", "success_rate", "wilson_low", "wilson_high", "complete")


def show_sweep(name: str, wanted: str | None, rows: list[dict[str, Any]], output: str) -> None:
    """The sweep's table on stdout: a row per grid point with its rate and Wilson interval;
    the points of a sweep stopped early that did not run every seed are marked."""
    from rich.console import Console
    from rich.table import Table

    label = printable(wanted or "finished without error")
    incomplete = "" if all(row["complete"] for row in rows) else " (incomplete)"
    title = f"{printable(name)}: success ({label}) per grid point{incomplete}"
    table = Table(title=title, title_justify="left")
    given = [column for column in rows[0] if column not in _RATE_COLUMNS]
    for column in [*given, "success", "95% Wilson"]:
        table.add_column(printable(column.replace("_", " ")), justify="right")
    for row in rows:
        cells = [f"{row[c]:g}" if isinstance(row[c], float) else printable(row[c]) for c in given]
        rate = f"{row['successes']}/{row['runs']} = {row['success_rate']:.0%}"
        rate += "" if row["complete"] else " (incomplete)"
        interval = f"{row['wilson_low']:.0%}–{row['wilson_high']:.0%}"
        table.add_row(*cells, rate, interval)
    Console(highlight=False, markup=False).print(table)
    print(f"results: {printable(output)}")
