"""``lightrocks run``: check, generate Python into a content-keyed cache, import and run.

The cache folder is named by a hash of every loaded model's text, so an unchanged model is
generated once. Generated modules are imported with importlib from that folder; model text
itself is never executed, and ``--param`` values go through the expression parser.
Repeated runs (``--seeds``) happen in worker processes that get only picklable inputs and
import the generated code again from the cache.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import inspect
import math
import multiprocessing
import os
import signal
import statistics
import sys
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from importlib.metadata import entry_points
from pathlib import Path
from types import ModuleType
from typing import Any

from generators.python import GENERATOR
from generators.python.generator import module_path
from generators.python.names import identifier
from languages.lightrocks.syntax import parse_statechart
from metamodel import ast
from metamodel.grammar import SyntaxProblem
from metamodel.units import ANGLE, LENGTH, Dimension, UnitError, lookup
from workbench import report
from workbench.check import CheckContext, all_cocos, check
from workbench.generators import GenerationRequest, write_all

Noise = tuple[float, float]
"""Perception noise: position sigma [m], rotation sigma [rad]."""


class RunError(Exception):
    """A problem the user can fix: unknown adapter, parameter or value."""


def cache_root() -> Path:
    xdg = os.environ.get("XDG_CACHE_HOME")
    return Path(xdg) / "lightrocks" if xdg else Path.cwd() / ".lightrocks-cache"


def content_key(context: CheckContext) -> str:
    digest = hashlib.sha256()
    for loaded in sorted(context.workspace.loaded_units(), key=lambda u: str(u.path)):
        digest.update(str(loaded.path).encode() + b"\0" + loaded.path.read_bytes() + b"\0")
    return digest.hexdigest()[:16]


def generated_package(context: CheckContext, files: list[Path], root: Path) -> ModuleType:
    """Generate (once per content) and import the package of every loaded statechart."""
    key = content_key(context)
    folder = root / key
    if not (folder / "__init__.py").exists():
        folder.mkdir(parents=True, exist_ok=True)
        write_all(folder, GENERATOR.generate(GenerationRequest(context, files)))
    name = f"lightrocks_{key}"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(
            name, folder / "__init__.py", submodule_search_locations=[str(folder)]
        )
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


def component_class(package: ModuleType, qualified_name: str) -> type:
    """The generated class of a statechart, by its qualified model name."""
    dotted = module_path(qualified_name).removesuffix(".py").replace("/", ".")
    module = importlib.import_module(f"{package.__name__}.{dotted}")
    return getattr(module, identifier(qualified_name.rpartition(".")[2]))


def _literal(text: str) -> Any:
    """The expression of ``text`` parsed as a parameter default, so units and signs work."""
    wrapper = f"statechart P {{ parameters {{ Real p = {text}; }} }}"
    try:
        unit = parse_statechart(wrapper, "<param>")
    except SyntaxProblem:
        raise RunError(f"'{text}' is not a literal value") from None
    (block,) = unit.statechart.elements
    return block.parameters[0].default if len(block.parameters) == 1 else None


def _dimension(quantity: ast.Quantity) -> Dimension:
    """The parser keeps an unknown unit's number as it is, so a typo must fail here."""
    try:
        return lookup(quantity.unit).dimension
    except UnitError as error:
        hint = f" (did you mean {' or '.join(error.suggestions)}?)" if error.suggestions else ""
        raise RunError(f"'{quantity.text}': {error}{hint}") from None


def parse_value(text: str) -> Any:
    """A ``--param`` value as a LightRocks literal: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``."""
    value = _literal(text)
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if isinstance(literal, ast.Quantity):
        _dimension(literal)
        number = -literal.value if negative else literal.value
        plain = not literal.unit and not any(c in literal.text for c in ".eE")
        return int(number) if plain and float(number).is_integer() else float(number)
    if isinstance(literal, ast.BooleanLiteral | ast.StringLiteral) and not negative:
        return literal.value
    if isinstance(literal, ast.VectorLiteral) and not negative:
        for element in literal.elements:
            if isinstance(element, ast.Quantity):
                _dimension(element)
        return tuple(e.value for e in literal.elements if isinstance(e, ast.Quantity))
    raise RunError(f"'{text}' is not a literal value")


def parse_noise(text: str) -> Noise:
    """``--perception-noise 2mm,2deg``: the camera's position and rotation sigmas in SI."""
    usage = f"--perception-noise '{text}' is not LENGTH,ANGLE such as 2mm,2deg"
    parts = text.split(",")
    if len(parts) != 2:
        raise RunError(usage)
    sigmas = []
    for part, dimension in zip(parts, (LENGTH, ANGLE), strict=True):
        literal = _literal(part.strip())
        if not isinstance(literal, ast.Quantity) or _dimension(literal) != dimension:
            raise RunError(usage)
        if literal.value < 0:
            raise RunError(f"--perception-noise '{text}': a sigma cannot be negative")
        sigmas.append(literal.value)
    return sigmas[0], sigmas[1]


def parameters(cls: type, given: Sequence[str]) -> dict[str, Any]:
    """``name=value`` pairs to Python attributes of the component, checked by name."""
    bound = {}
    for item in given:
        name, separator, text = item.partition("=")
        if not separator:
            raise RunError(f"--param '{item}' is not name=value")
        if name.strip() not in cls.PARAMETERS:
            known = ", ".join(cls.PARAMETERS) or "none"
            raise RunError(f"{cls.NAME} has no parameter '{name.strip()}'; parameters: {known}")
        bound[cls.PARAMETERS[name.strip()]] = parse_value(text.strip())
    return bound


def adapter_factory(name: str) -> Callable[..., Any]:
    found = {e.name: e for e in entry_points(group="lightrocks.adapters")}
    if name not in found:
        raise RunError(f"unknown adapter '{name}'; known: {', '.join(sorted(found))}")
    return found[name].load()


def adapter_options(
    name: str | None, seed: int = 0, noise: Noise = (0.0, 0.0), video: str | None = None
) -> dict[str, Any]:
    """Keyword arguments for the adapter, read off its signature so that nothing it cannot
    honour (noise, a video) is silently dropped; the seed only matters to adapters that
    draw random numbers."""
    if name is None:
        if any(noise) or video is not None:
            raise RunError("perception noise and video need an adapter (--adapter)")
        return {}
    accepted = inspect.signature(adapter_factory(name)).parameters
    options: dict[str, Any] = {"seed": seed} if "seed" in accepted else {}
    if any(noise):
        if "perception_noise" not in accepted:
            raise RunError(f"adapter '{name}' has no perception noise")
        options["perception_noise"] = noise
    if video is not None:
        if "video" not in accepted:
            raise RunError(f"adapter '{name}' cannot record a video")
        options["video"] = video
    return options


def adapter_for(name: str, scene: str | None, **options: Any) -> Any:
    return adapter_factory(name)(scene=scene, **options)


def scene_of(cls: type) -> str | None:
    return cls.CELL.SCENE if cls.CELL is not None else None


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
) -> Any:
    """Create, bind and run the chart; send the events once it rests.

    The binding is checked before the trace file is opened, so a run that cannot start
    leaves no file behind.
    """
    from runtime import BindingError, Trace
    from runtime.binding import bind

    chart = cls(**params)
    try:
        if adapter is not None:
            bind(adapter, cls.CELL)
    except BindingError as error:
        raise RunError(str(error)) from None
    recorder = Trace(trace)
    if progress is not None:
        recorder.listeners.append(progress)
    try:
        chart.start(adapter, trace=recorder)
        for event in events:
            if chart.finished:
                break
            chart.send(event)
    finally:
        recorder.close()
    return chart


class ModelError(Exception):
    """The model has check errors; the argument is the report."""


def load_component(model: Path, search_path: Sequence[Path]) -> type:
    """Check the model, generate it (once per content) and import the class of its chart."""
    context = check([model], list(search_path))
    if context.diagnostics.has_errors:
        raise ModelError(report.text(context.diagnostics.items, all_cocos()))
    unit = next(u.unit for u in context.workspace.loaded_units() if u.path == model.resolve())
    name = f"{unit.package}.{unit.statechart.name}" if unit.package else unit.statechart.name
    package = generated_package(context, [model.resolve()], cache_root())
    return component_class(package, name)


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
    """The active configuration when the run did not finish."""


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
) -> RunResult:
    """One run of a loaded chart; the measurements are read before the adapter is closed,
    because closing ends its simulation."""
    wanted = success_outcome(cls, success)
    values = parameters(cls, params)
    options = adapter_options(adapter, seed, noise, video)
    device = None if adapter is None else adapter_for(adapter, scene_of(cls), **options)
    try:
        chart = drive(cls, values, device, events, trace, progress)
        measure = getattr(device, "measurements", None)
        measured = dict(measure()) if measure is not None else {}
    finally:
        if device is not None:
            device.close()
    summary = summarize(chart)
    if wanted is None:
        succeeded = chart.finished and summary.outcome != "error"
    else:
        succeeded = summary.outcome == wanted
    return RunResult(
        seed,
        summary.outcome,
        succeeded,
        summary.time,
        summary.skills,
        measured,
        summary.fault,
        () if chart.finished else chart.active_configuration,
    )


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
) -> RunResult:
    """One run from picklable inputs only, so that a worker process can do it on its own:
    the generated code is imported again from the cache, never pickled."""
    cls = load_component(model, search_path)
    return run_component(
        cls, params, adapter, seed, noise, trace, video, events=events, success=success
    )


def seed_trace(trace: Path | None, seed: int) -> Path | None:
    """``run.jsonl`` -> ``run.seed3.jsonl``: one trace per seed."""
    return None if trace is None else trace.with_name(f"{trace.stem}.seed{seed}{trace.suffix}")


def _ignore_interrupt() -> None:
    """Ctrl-C is the parent's to handle: it cancels the runs that have not started."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_seeds(
    model: Path,
    search_path: Sequence[Path],
    params: Sequence[str],
    adapter: str | None,
    seeds: Sequence[int],
    noise: Noise = (0.0, 0.0),
    trace: Path | None = None,
    *,
    events: Sequence[str] = (),
    success: str | None = None,
    workers: int | None = None,
    done: Callable[[RunResult], None] | None = None,
) -> list[RunResult]:
    """``run_once`` per seed in worker processes (default: one per core); results in seed
    order, ``done`` is called in this process as each run ends.

    Workers are spawned, not forked: the parent may run a progress thread and have MuJoCo
    loaded, neither of which survives a fork reliably.
    """
    if not seeds:
        return []
    count = min(workers or os.cpu_count() or 1, len(seeds))
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(count, mp_context=context, initializer=_ignore_interrupt) as pool:
        futures = [
            pool.submit(
                run_once,
                model,
                list(search_path),
                list(params),
                adapter,
                seed,
                noise,
                seed_trace(trace, seed),
                events=list(events),
                success=success,
            )
            for seed in seeds
        ]
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


_SCALES = {
    "_depth": (1e3, "mm", 1),
    "_height": (1e3, "mm", 1),
    "_angle": (180 / math.pi, "deg", 1),
    "_torque": (1.0, "Nm", 3),
}
"""Measurement key suffix -> factor from SI, unit, decimals."""


def measurement_label(key: str) -> str:
    return key.replace("_", " ")


def key_measurements(measured: dict[str, float | bool]) -> dict[str, float | bool]:
    """What a per-seed row shows: the yes/no results and the depths."""
    return {k: v for k, v in measured.items() if isinstance(v, bool) or k.endswith("_depth")}


def format_measurement(key: str, value: float | bool | str) -> str:
    """Readable value: metres as millimetres, radians as degrees, booleans as yes/no."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if not isinstance(value, int | float):
        return str(value)
    for suffix, (factor, unit, decimals) in _SCALES.items():
        if key.endswith(suffix):
            return f"{value * factor:.{decimals}f} {unit}"
    return f"{value:g}"


def show(name: str, run: Callable[..., RunResult]) -> int:
    """Call ``run(progress=…)`` with a live status line on stderr (simulated time, active
    state path) and print the summary on stdout; 0 when it ended with the success outcome."""
    from rich.console import Console
    from rich.table import Table

    with Console(stderr=True, highlight=False, markup=False).status("starting") as status:
        path = ""

        def progress(record: dict[str, Any]) -> None:
            nonlocal path
            if record["kind"] == "enter":
                path = record["state"]
            elif record["kind"] == "exit":
                path = record["state"].rpartition("/")[0]
            status.update(f"{record['time']:8.3f} s  {path}")

        result = run(progress=progress)
    console = Console(highlight=False, markup=False)
    outcome = result.outcome or "not finished"
    if result.skills:
        table = Table(title=f"{name}: {outcome}", title_justify="left")
        table.add_column("skill")
        table.add_column("time [s]", justify="right")
        for skill, seconds in result.skills:
            table.add_row(skill, f"{seconds:.3f}")
        console.print(table)
    if result.measurements:
        table = Table()
        table.add_column("measurement")
        table.add_column("value", justify="right")
        for key, value in result.measurements.items():
            table.add_row(measurement_label(key), format_measurement(key, value))
        console.print(table)
    print(f"outcome: {outcome} after {result.time:.3f} s")
    if result.active:
        print("active: " + " / ".join(result.active))
    if result.fault:
        print(f"error: {result.fault}")
    return 0 if result.success else 1


def show_seeds(
    name: str, wanted: str | None, runs: int, run: Callable[..., list[RunResult]]
) -> int:
    """Call ``run(done=…)`` with a progress bar on stderr; print a row per seed, the success
    rate with its 95 % Wilson interval and the spread of the simulated time on stdout.
    0 when every run ended with the success outcome."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn
    from rich.table import Table

    columns = (
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("{task.fields[succeeded]} succeeded"),
        TimeElapsedColumn(),
    )
    with Progress(*columns, console=Console(stderr=True, highlight=False)) as bar:
        task = bar.add_task(name, total=runs, succeeded=0)
        succeeded = 0

        def done(result: RunResult) -> None:
            nonlocal succeeded
            succeeded += result.success
            bar.update(task, advance=1, succeeded=succeeded)

        results = run(done=done)
    keys = list(dict.fromkeys(k for r in results for k in key_measurements(r.measurements)))
    table = Table(title=f"{name}: {len(results)} runs", title_justify="left")
    table.add_column("seed", justify="right")
    table.add_column("outcome")
    table.add_column("time [s]", justify="right")
    for key in keys:
        table.add_column(measurement_label(key), justify="right")
    for result in results:
        measured = result.measurements
        cells = [format_measurement(k, measured[k]) if k in measured else "" for k in keys]
        table.add_row(
            str(result.seed), result.outcome or "not finished", f"{result.time:.3f}", *cells
        )
    Console(highlight=False, markup=False).print(table)
    for result in results:
        if result.fault:
            print(f"seed {result.seed}: error: {result.fault}")
    count = sum(r.success for r in results)
    low, high = wilson(count, len(results))
    label = wanted or "finished without error"
    print(
        f"success ({label}): {count}/{len(results)} = {count / len(results):.0%}, "
        f"95% Wilson interval {low:.0%}–{high:.0%}"
    )
    times = [r.time for r in results]
    spread = statistics.stdev(times) if len(times) > 1 else 0.0
    print(
        f"simulated time: {statistics.fmean(times):.3f} ± {spread:.3f} s, "
        f"min {min(times):.3f} s, max {max(times):.3f} s"
    )
    return 0 if count == len(results) else 1
