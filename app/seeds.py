"""Repeated runs over seeds in worker processes, and the statistics of their success."""

from __future__ import annotations

import math
import multiprocessing
import os
import signal
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed

from lightrocks.app.pipeline import run
from lightrocks.app.run import RunResult
from lightrocks.app.specs import RunSpec


def _ignore_interrupt() -> None:
    """Ctrl-C is the parent's to handle: it cancels the runs that have not started."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_seeds(
    spec: RunSpec,
    seeds: Sequence[int],
    *,
    workers: int | None = None,
    done: Callable[[RunResult], None] | None = None,
) -> list[RunResult]:
    """``spec`` once per seed in worker processes (default: one per core); results in seed
    order, ``done`` is called in this process as each run ends. The workers receive the
    parsed spec and import the generated code again from the cache; they read no user text.

    Workers are spawned, not forked: the parent may run a progress thread and have MuJoCo
    loaded, neither of which survives a fork reliably.
    """
    if not seeds:
        return []
    count = min(workers or os.cpu_count() or 1, len(seeds))
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(count, mp_context=context, initializer=_ignore_interrupt) as pool:
        futures = [pool.submit(run, spec.for_seed(seed)) for seed in seeds]
        try:
            for future in as_completed(futures):
                result = future.result()
                if done is not None:
                    done(result)
        except BaseException:
            pool.shutdown(cancel_futures=True)
            raise
    return [future.result() for future in futures]


def wilson(successes: int, runs: int, z: float = 1.959963984540054) -> tuple[float, float]:
    """The 95 % Wilson score interval of a success rate; unlike p ± z·σ it stays inside
    [0, 1] and is not empty for 0 or N successes out of few runs."""
    if runs == 0:
        return 0.0, 1.0
    rate = successes / runs
    scale = 1 + z * z / runs
    centre = (rate + z * z / (2 * runs)) / scale
    half = z * math.sqrt(rate * (1 - rate) / runs + z * z / (4 * runs * runs)) / scale
    return max(0.0, centre - half), min(1.0, centre + half)
