"""One run of a generated statechart: bind it to an adapter, drive it, summarize it.

``run_once`` takes picklable inputs only, so that a worker process can do it on its own.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lightrocks.app.adapter_factory import adapter_for, adapter_options, scene_of
from lightrocks.app.errors import ModelError, RunError
from lightrocks.app.loading import load_component
from lightrocks.app.script import Script
from lightrocks.app.values import Noise, parameters, parse_delay


def success_outcome(cls: type, chosen: str | None = None) -> str | None:
    """The outcome that counts as success: ``chosen``, else the first declared end condition
    (final states come after end conditions in ``OUTCOMES``)."""
    if chosen is None:
        return cls.OUTCOMES[0] if cls.OUTCOMES else None
    if chosen not in cls.OUTCOMES:
        known = ", ".join(cls.OUTCOMES) or "none"
        raise RunError(f"{cls.NAME} has no outcome '{chosen}'; outcomes: {known}")
    return chosen


@dataclass
class Summary:
    outcome: str | None
    time: float
    skills: list[tuple[str, float]]
    fault: str


def summarize(chart: Any) -> Summary:
    """Outcome, run time and the time spent in every skill (from the trace)."""
    entered: dict[str, float] = {}
    skills: list[tuple[str, float]] = []
    for record in chart.trace:
        if record["kind"] == "enter" and record.get("layer") == "skill":
            entered[record["state"]] = record["time"]
        elif record["kind"] == "exit" and record["state"] in entered:
            skills.append((record["state"], record["time"] - entered.pop(record["state"])))
    fault = chart.fault
    described = ""
    if fault is not None and chart.outcome == "error":
        described = f"{fault.message} at {fault.location or '?'} via {' <- '.join(fault.origin)}"
    return Summary(
        chart.outcome,
        chart.trace[-1]["time"] if chart.trace else 0.0,
        skills,
        described,
    )


def drive(
    cls: type,
    params: dict[str, Any],
    adapter: Any,
    events: Sequence[str],
    trace: Path | None,
    progress: Callable[[dict[str, Any]], None] | None = None,
    watch: Any = None,
    header: Mapping[str, Any] | None = None,
) -> Any:
    """Create, bind and run the chart; send the events once it rests.

    The binding is checked before the trace file is opened, so a run that cannot start
    leaves no file behind. A cell that does not fit the adapter is the model's mistake.
    """
    from lightrocks.runtime import BindingError, Trace
    from lightrocks.runtime.binding import bind
    from lightrocks.runtime.sampling import Sampler

    chart = cls(**params)
    steps = [parse_delay(e) if e.startswith("+") else e for e in events]
    if adapter is not None and any(not isinstance(step, str) for step in steps):
        raise RunError("+<time> advances the virtual clock of a run without adapter only")
    unknown = [e for e in steps if isinstance(e, str) and e not in chart.events]
    if unknown:
        known = ", ".join(sorted(chart.events)) or "none"
        raise RunError(f"unknown event '{unknown[0]}'; {cls.NAME} accepts: {known}")
    try:
        if adapter is not None:
            bind(adapter, cls.CELL)
    except BindingError as error:
        raise ModelError(f"error: {error}") from None
    try:
        recorder = Trace(trace)
    except OSError as error:
        raise RunError(f"--trace: cannot write {trace}: {error.strerror or error}") from None
    if header:
        recorder.write(0.0, "run", **header)
    if progress is not None:
        recorder.listeners.append(progress)
    if watch is not None:
        watch.attach(recorder)  # first: a paused tick is sampled once the run goes on
    if adapter is not None:
        Sampler(recorder, adapter.devices()).attach()
    try:
        chart.start(adapter, trace=recorder)
        for step in steps:
            if chart.finished:
                break
            if isinstance(step, str):
                chart.send(step)
            else:
                chart.advance(step)
    finally:
        recorder.close()
    if recorder.failure is not None:
        trace.unlink(missing_ok=True)  # never leave a cut-off trace behind
        reason = recorder.failure.strerror or recorder.failure
        raise RunError(f"--trace: cannot write {trace}: {reason} (the run went on without it)")
    return chart


@dataclass
class RunResult:
    """What one run gives a report or a benchmark; plain data, so it crosses processes."""

    seed: int
    outcome: str | None
    success: bool
    time: float
    skills: list[tuple[str, float]]
    measurements: dict[str, float | bool]
    fault: str
    active: tuple[str, ...]
    """The paths of the innermost active states when the run did not finish (one per
    active orthogonal region)."""
    video: str = ""
    """Where the adapter's video went."""


def run_component(
    cls: type,
    params: Sequence[str],
    adapter: str | None,
    seed: int = 0,
    noise: Noise = (0.0, 0.0),
    trace: Path | None = None,
    video: str | None = None,
    *,
    events: Sequence[str] = (),
    success: str | None = None,
    progress: Callable[[dict[str, Any]], None] | None = None,
    script: Script | None = None,
    watch: Any = None,
    header: Mapping[str, Any] | None = None,
) -> RunResult:
    """One run of a loaded chart; the measurements are read before the adapter is closed,
    because closing ends its simulation."""
    wanted = success_outcome(cls, success)
    values = parameters(cls, params)
    options = adapter_options(adapter, seed, noise, video, script)
    device = None if adapter is None else adapter_for(adapter, scene_of(cls), **options)
    try:
        chart = drive(cls, values, device, events, trace, progress, watch, header)
        measure = getattr(device, "measurements", None)
        measured = dict(measure()) if measure is not None else {}
        if watch is not None:
            watch.finish(measured)
    finally:
        if device is not None:
            device.close()
    summary = summarize(chart)
    video_written = getattr(device, "video_written", "")
    # a plain chart without final state succeeds by resting without error
    succeeded = summary.outcome != "error" if wanted is None else summary.outcome == wanted
    return RunResult(
        seed,
        summary.outcome,
        succeeded,
        summary.time,
        summary.skills,
        measured,
        summary.fault,
        () if chart.finished else _innermost(chart.active_paths),
        video_written,
    )


def _innermost(paths: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(p for p in paths if not any(q.startswith(p + "/") for q in paths))


def run_once(
    model: Path,
    search_path: Sequence[Path],
    params: Sequence[str],
    adapter: str | None,
    seed: int = 0,
    noise: Noise = (0.0, 0.0),
    trace: Path | None = None,
    video: str | None = None,
    *,
    events: Sequence[str] = (),
    success: str | None = None,
    script: Script | None = None,
) -> RunResult:
    """One run from picklable inputs only, so that a worker process can do it on its own:
    the generated code is imported again from the cache, never pickled."""
    cls = load_component(model, search_path)
    return run_component(
        cls,
        params,
        adapter,
        seed,
        noise,
        trace,
        video,
        events=events,
        success=success,
        script=script,
        header=run_header(model, search_path),
    )


def run_header(model: Path, search_path: Sequence[Path]) -> dict[str, Any]:
    """The first record of a trace file: the model it ran, so that a replay can draw it."""
    return {"model": str(model.resolve()), "path": [str(p.resolve()) for p in search_path]}
