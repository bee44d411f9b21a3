"""One run of a generated statechart: bind it to an adapter, drive it, summarize it (the
pipeline's last stage, :func:`app.pipeline.run`)."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lightrocks.app.errors import ModelError, RunError


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
    events: Sequence[str | float],
    trace: Path | None,
    progress: Callable[[dict[str, Any]], None] | None = None,
    watch: Any = None,
    header: Mapping[str, Any] | None = None,
) -> Any:
    """Create, bind and run the chart; send the events once it rests.

    The chart's ``start`` checks the binding before its first step; a run that cannot start
    leaves no trace file behind. A cell that does not fit the adapter is the model's mistake.
    A run stopped by Ctrl-C ends its trace with ``interrupted`` and ``finished``.
    """
    from lightrocks.runtime import BindingError, Trace
    from lightrocks.runtime.faults import INTERRUPTED
    from lightrocks.runtime.sampling import Sampler

    chart = cls(**params)
    steps = list(events)
    if adapter is not None and any(not isinstance(step, str) for step in steps):
        raise RunError("+<time> advances the virtual clock of a run without adapter only")
    unknown = [e for e in steps if isinstance(e, str) and e not in chart.events]
    if unknown:
        known = ", ".join(sorted(chart.events)) or "none"
        raise RunError(f"unknown event '{unknown[0]}'; {cls.NAME} accepts: {known}")
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
        Sampler(recorder, adapter).attach()
    misfit: BindingError | None = None
    try:
        chart.start(adapter, trace=recorder)
        for step in steps:
            if chart.finished:
                break
            if isinstance(step, str):
                chart.send(step)
            else:
                chart.advance(step)
    except BindingError as error:
        misfit = error
    except KeyboardInterrupt:
        if chart.outcome == INTERRUPTED:  # the arm holds; the trace says how the run ended
            recorder.write(recorder.time, "finished", outcome=INTERRUPTED)
        raise
    finally:
        recorder.close()
    if misfit is not None:
        if trace is not None:
            trace.unlink(missing_ok=True)
        raise ModelError(f"error: {misfit}") from None
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
    goal: bool | None = None
    """Whether the scene's ground truth shows its goal met (``Scene.goal_met`` on the
    measurements); ``None`` without adapter, scene or goal. Beside ``success``, which only
    says whether the chart ended with the success outcome."""
    scene_fault: str = ""
    """What a hook of the scene raised (``measurements()``, ``goal_met``), if one did."""
