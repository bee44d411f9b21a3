"""The one path every front door takes: check → generate → load → run.

The command line, textX's commands, the monitor, sweeps and tests build a spec
(:mod:`app.specs`) and hand it here; nothing else checks, generates or runs on its own, so
option and error rules are written once.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from lightrocks.app.adapter_factory import adapter_for, scene_of
from lightrocks.app.errors import ModelError
from lightrocks.app.ground_truth import ground_truth
from lightrocks.app.loading import load_component
from lightrocks.app.robots import RobotChoice, choose
from lightrocks.app.run import RunResult, drive, summarize
from lightrocks.app.specs import GenerateSpec, RunSpec, run_spec
from lightrocks.workbench import report
from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.generators import GenerationRequest, load_generator, run_generator
from lightrocks.workbench.languages import extensions
from lightrocks.workbench.modelpath import model_files


def checked(paths: Sequence[Path], search_path: Sequence[Path]) -> CheckContext:
    """The checked models; their errors, shown as ``check`` shows them, are a ``ModelError``."""
    context = check(list(paths), list(search_path))
    if context.diagnostics.has_errors:
        raise ModelError(report.text(context.diagnostics.items))
    return context


def generate(spec: GenerateSpec) -> dict[str, str | bytes]:
    """The files ``spec.target`` generates from the checked models, by relative path."""
    generator = load_generator(spec.target)
    context = checked(spec.models, spec.search_path)
    files = [f.resolve() for p in spec.models for f in model_files(p, extensions())]
    request = GenerationRequest(context, files, dict(spec.options), spec.templates)
    return run_generator(generator, request)


def load(model: Path, search_path: Sequence[Path], robot: RobotChoice | None = None) -> type:
    """The generated class of the statechart in ``model`` (checked, generated once per
    content, imported); with ``robot``, for that robot in the cell's robot slot."""
    return load_component(model, search_path, robot)


def run(
    spec: RunSpec,
    cls: type | None = None,
    *,
    progress: Callable[[dict[str, Any]], None] | None = None,
    watch: Any = None,
) -> RunResult:
    """One run; ``cls`` is the loaded class of ``spec.model`` where the caller has it. The
    measurements are read, and judged by the scene's ``goal_met``, before the adapter is
    closed, because closing ends its simulation."""
    cls = cls or load(spec.model, spec.search_path, spec.robot)
    wanted = spec.success
    scene = scene_of(cls)
    device = (
        None
        if spec.adapter is None
        else adapter_for(spec.adapter, scene, spec.seed, **spec.adapter_options)
    )
    try:
        chart = drive(
            cls, dict(spec.params), device, spec.events, spec.trace, progress, watch, spec.header
        )
        truth = ground_truth(device, scene)
        if watch is not None:
            watch.finish(truth.measurements)
    finally:
        if device is not None:
            device.close()
    summary = summarize(chart)
    # a plain chart without final state succeeds by resting without error
    succeeded = summary.outcome != "error" if wanted is None else summary.outcome == wanted
    return RunResult(
        spec.seed,
        summary.outcome,
        succeeded,
        summary.time,
        summary.skills,
        truth.measurements,
        summary.fault,
        () if chart.finished else _innermost(chart.active_paths),
        getattr(device, "video_written", ""),
        truth.goal,
        truth.fault,
    )


def _innermost(paths: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(p for p in paths if not any(q.startswith(p + "/") for q in paths))


def spec_for(
    model: Path,
    search_path: Sequence[Path],
    params: Sequence[str] = (),
    adapter: str | None = None,
    *,
    robot: str | None = None,
    **options: Any,
) -> RunSpec:
    """The spec of a run of ``model`` from its user's words (see :func:`specs.run_spec` for
    the ``options``; ``robot`` names a registered robot): for callers that have no loaded
    class yet."""
    chosen = choose(robot) if robot is not None else None
    cls = load(model, search_path, chosen)
    return run_spec(cls, model, search_path, params, adapter, robot=chosen, **options)


def run_model(
    model: Path,
    search_path: Sequence[Path],
    params: Sequence[str] = (),
    adapter: str | None = None,
    **options: Any,
) -> RunResult:
    """One run of ``model`` from its user's words, as ``lightrocks run`` does it."""
    return run(spec_for(model, search_path, params, adapter, **options))
