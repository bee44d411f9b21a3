"""Sweeps: every combination of parameter values and perception noise levels, each run over
the same seeds on a Dask cluster, summarised per grid point with its success rate."""

from __future__ import annotations

import csv
import io
import itertools
import logging
import math
import signal
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass
from typing import Any

from lightrocks.app.errors import RunError
from lightrocks.app.pipeline import run
from lightrocks.app.run import RunResult
from lightrocks.app.seeds import wilson
from lightrocks.app.specs import RunSpec
from lightrocks.app.values import Noise


@dataclass(frozen=True)
class GridPoint:
    """One combination: parameter values as given (``name=value``) and one noise level."""

    params: tuple[str, ...]
    noise: Noise


@dataclass(frozen=True)
class PointSummary:
    point: GridPoint
    runs: int
    successes: int
    complete: bool = True
    """Whether every planned run of the point finished (not so in a sweep stopped early)."""

    @property
    def rate(self) -> float:
        return self.successes / self.runs if self.runs else 0.0

    @property
    def interval(self) -> tuple[float, float]:
        return wilson(self.successes, self.runs)


def split_values(text: str) -> list[str]:
    """``10mm,[1 mm, 2 mm]`` -> the two values: commas inside brackets belong to a vector."""
    values, depth, current = [], 0, ""
    for character in text:
        depth += {"[": 1, "]": -1}.get(character, 0)
        if character == "," and depth == 0:
            values.append(current.strip())
            current = ""
        else:
            current += character
    values.append(current.strip())
    if depth != 0 or not all(values):
        raise RunError(f"'{text}' is not a comma-separated list of values")
    return values


def parse_grid(items: Sequence[str]) -> list[tuple[str, list[str]]]:
    """``--grid name=v1,v2`` options -> (name, values) in the order given, names unique."""
    grid: dict[str, list[str]] = {}
    for item in items:
        name, separator, text = item.partition("=")
        name = name.strip()
        if not separator or not name:
            raise RunError(f"--grid '{item}' is not NAME=VALUE,VALUE,…")
        if name in grid:
            raise RunError(f"--grid names '{name}' twice")
        grid[name] = split_values(text)
    return list(grid.items())


def grid_points(
    grid: Sequence[tuple[str, Sequence[str]]], noises: Sequence[Noise]
) -> list[GridPoint]:
    """Every combination, noise varying fastest, so that a parameter's rows stay together."""
    names = [name for name, _ in grid]
    combinations = itertools.product(*(values for _, values in grid))
    return [
        GridPoint(tuple(f"{n}={v}" for n, v in zip(names, values, strict=True)), noise)
        for values in combinations
        for noise in noises
    ]


@contextmanager
def dask_client(scheduler: str | None, workers: int | None) -> Iterator[Any]:
    """A client of the cluster at ``scheduler``, else of a local cluster of worker
    processes (one per core by default, one thread each: a simulation is single-threaded).

    Ctrl-C is held back while the cluster starts: a cluster interrupted half-made cannot be
    closed cleanly. It takes effect as soon as the cluster is there to be closed. The local
    cluster logs only what is critical: a failed run reaches the sweep through its future,
    and a worker that loses the scheduler while the cluster closes (after Ctrl-C) would
    otherwise print tracebacks of that race between the progress line and the summary.
    """
    from distributed import Client, LocalCluster

    with ExitStack() as stack:
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            if scheduler is not None:
                client = stack.enter_context(_connect(Client, scheduler))
            else:
                cluster = LocalCluster(
                    n_workers=workers,
                    threads_per_worker=1,
                    processes=True,
                    dashboard_address=":0",  # any free port: several clusters may run at once
                    silence_logs=logging.CRITICAL,
                )
                stack.enter_context(cluster)
                client = stack.enter_context(Client(cluster))
        finally:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
        yield client


def _connect(client_type: type, scheduler: str) -> Any:
    try:
        return client_type(scheduler, timeout="10s")
    except OSError as error:
        raise RunError(f"--scheduler {scheduler}: {error}") from None


def sweep(
    client: Any,
    points: Sequence[GridPoint],
    specs: Sequence[RunSpec],
    seeds: Sequence[int],
    *,
    done: Callable[[GridPoint, RunResult], None] | None = None,
    finished: Mapping[tuple[int, int], RunResult] | None = None,
) -> list[tuple[GridPoint, RunResult]]:
    """Run every grid point (its parsed run ``specs``, in the same order) over ``seeds`` on
    the cluster; results in grid and seed order. Runs in ``finished`` (by index of the
    point and seed: a sweep resumed) are not run again; ``done`` hears of every other one
    as it finishes.

    Each run is a pickled spec, deterministic per seed, so the scheduler may run a task
    again on another worker when its worker is lost. Ctrl-C cancels what has not finished.
    """
    from distributed import as_completed

    results = dict(finished or {})
    jobs = [(i, seed) for i in range(len(points)) for seed in seeds]
    todo = [job for job in jobs if job not in results]
    futures = [client.submit(run, specs[i].for_seed(seed), pure=False) for i, seed in todo]
    index = {future.key: job for future, job in zip(futures, todo, strict=True)}
    try:
        for future in as_completed(futures):
            job = index[future.key]
            results[job] = future.result()
            if done is not None:
                done(points[job[0]], results[job])
    except BaseException:
        client.cancel(futures)
        raise
    return [(points[i], results[i, seed]) for i, seed in jobs]


def summarize(
    points: Sequence[GridPoint],
    results: Sequence[tuple[GridPoint, RunResult]],
    planned: int | None = None,
) -> list[PointSummary]:
    """The runs and successes of every point; ``planned`` runs per point make it complete
    (without it, every point is)."""
    summaries = []
    for point in points:
        runs = sum(p == point for p, _ in results)
        successes = sum(p == point and r.success for p, r in results)
        complete = planned is None or runs >= planned
        summaries.append(PointSummary(point, runs, successes, complete))
    return summaries


def _noise_columns(noise: Noise) -> dict[str, float]:
    return {
        "noise_length_mm": round(noise[0] * 1e3, 9),
        "noise_angle_deg": round(math.degrees(noise[1]), 9),
    }


def point_rows(summaries: Sequence[PointSummary]) -> list[dict[str, Any]]:
    """One row per grid point: the parameter values, the noise, the runs and the rate."""
    rows = []
    for summary in summaries:
        low, high = summary.interval
        values = dict(p.split("=", 1) for p in summary.point.params)
        rows.append(
            {
                **values,
                **_noise_columns(summary.point.noise),
                "runs": summary.runs,
                "successes": summary.successes,
                "success_rate": summary.rate,
                "wilson_low": low,
                "wilson_high": high,
                "complete": summary.complete,
            }
        )
    return rows


def run_rows(results: Sequence[tuple[GridPoint, RunResult]]) -> list[dict[str, Any]]:
    """One row per run, so that nothing of the sweep is lost beyond the summary; ``success``
    is the outcome's, ``goal_met`` the scene's ground truth (empty where it judges none)."""
    return [
        {
            **dict(p.split("=", 1) for p in point.params),
            **_noise_columns(point.noise),
            "seed": result.seed,
            "outcome": result.outcome or "not finished",
            "success": result.success,
            "goal_met": result.goal,
            "time_s": result.time,
            "fault": result.fault,
        }
        for point, result in results
    ]


def csv_text(rows: Sequence[dict[str, Any]]) -> str:
    stream = io.StringIO()
    writer = csv.DictWriter(stream, fieldnames=list(rows[0]), lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return stream.getvalue()


def parquet_bytes(rows: Sequence[dict[str, Any]]) -> bytes:
    import pyarrow as pa
    import pyarrow.parquet as pq

    sink = pa.BufferOutputStream()
    pq.write_table(pa.Table.from_pylist(list(rows)), sink)
    return sink.getvalue().to_pybytes()


def plot_png(name: str, summaries: Sequence[PointSummary]) -> bytes:
    """Success against noise with the Wilson interval, one line per parameter combination."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot

    levels = list(dict.fromkeys(s.point.noise for s in summaries))
    labels = [f"{n[0] * 1e3:g} mm\n{math.degrees(n[1]):g}°" for n in levels]
    figure, axes = pyplot.subplots(figsize=(7, 4.5), dpi=100)
    for params in dict.fromkeys(s.point.params for s in summaries):
        line = [s for s in summaries if s.point.params == params]
        rates = [s.rate * 100 for s in line]
        errors = [  # rounding may put a bound a hair beyond the rate
            [max(0.0, s.rate - s.interval[0]) * 100 for s in line],
            [max(0.0, s.interval[1] - s.rate) * 100 for s in line],
        ]
        positions = [levels.index(s.point.noise) for s in line]
        label = ", ".join(params) or name
        axes.errorbar(positions, rates, yerr=errors, marker="o", capsize=4, label=label)
    axes.set_xticks(range(len(levels)), labels)
    axes.set_xlabel("perception noise (σ position, σ rotation)")
    axes.set_ylabel("success [%] (95 % Wilson interval)")
    axes.set_ylim(-2, 102)
    axes.set_title(f"{name}: success against perception noise")
    axes.grid(alpha=0.3)
    axes.legend(loc="lower left", fontsize="small")
    figure.tight_layout()
    stream = io.BytesIO()
    figure.savefig(stream, format="png", metadata={"Software": None})
    pyplot.close(figure)
    return stream.getvalue()


def result_files(
    name: str, summaries: Sequence[PointSummary], results: Sequence[tuple[GridPoint, RunResult]]
) -> dict[str, str | bytes]:
    """The files a sweep writes into its output folder."""
    points = point_rows(summaries)
    runs = run_rows(results)
    return {
        "results.csv": csv_text(points),
        "results.parquet": parquet_bytes(points),
        "runs.csv": csv_text(runs),
        "runs.parquet": parquet_bytes(runs),
        "success.png": plot_png(name, summaries),
    }
