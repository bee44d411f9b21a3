"""``lightrocks run``: check, generate Python into a content-keyed cache, import and run.

The cache folder is named by a hash of every loaded model's text, so an unchanged model is
generated once. Generated modules are imported with importlib from that folder; model text
itself is never executed, and ``--param`` values go through the expression parser.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import os
import sys
from collections.abc import Callable, Sequence
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
from workbench.check import CheckContext
from workbench.generators import GenerationRequest, write_all


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


def parse_value(text: str) -> Any:
    """A ``--param`` value as a LightRocks literal: ``12mm``, ``0.32 Nm``, ``true``, ``"a"``."""
    wrapper = f"statechart P {{ parameters {{ Real p = {text}; }} }}"
    try:
        unit = parse_statechart(wrapper, "<param>")
    except SyntaxProblem:
        raise RunError(f"'{text}' is not a literal value") from None
    (block,) = unit.statechart.elements
    value = block.parameters[0].default if len(block.parameters) == 1 else None
    negative = isinstance(value, ast.Unary) and value.operator == "-"
    literal = value.operand if negative else value
    if isinstance(literal, ast.Quantity):
        number = -literal.value if negative else literal.value
        plain = not literal.unit and not any(c in literal.text for c in ".eE")
        return int(number) if plain and float(number).is_integer() else float(number)
    if isinstance(literal, ast.BooleanLiteral | ast.StringLiteral) and not negative:
        return literal.value
    if isinstance(literal, ast.VectorLiteral) and not negative:
        return tuple(e.value for e in literal.elements if isinstance(e, ast.Quantity))
    raise RunError(f"'{text}' is not a literal value")


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


def adapter_for(name: str, scene: str | None) -> Any:
    found = {e.name: e for e in entry_points(group="lightrocks.adapters")}
    if name not in found:
        raise RunError(f"unknown adapter '{name}'; known: {', '.join(sorted(found))}")
    return found[name].load()(scene=scene)


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


def run_chart(
    cls: type,
    params: dict[str, Any],
    adapter_name: str | None,
    events: Sequence[str],
    trace: Path | None,
    progress: Callable[[dict[str, Any]], None] | None = None,
) -> Any:
    """Create, bind and run the chart; send the events once it rests."""
    chart = cls(**params)
    adapter = None
    if adapter_name is not None:
        cell = cls.CELL
        adapter = adapter_for(adapter_name, cell.SCENE if cell is not None else None)
    from runtime import Trace

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
        if adapter is not None:
            adapter.close()
    return chart


def show(
    cls: type, params: dict[str, Any], adapter: str | None, events: list[str], trace: str | None
) -> int:
    """Run with a live status line (state path, simulated time) and print the summary."""
    from rich.console import Console
    from rich.table import Table

    from runtime import BindingError

    console = Console(stderr=True, highlight=False)
    with console.status("starting") as status:

        def progress(record: dict[str, Any]) -> None:
            if record["kind"] == "enter":
                status.update(f"{record['time']:8.3f} s  {record['state']}")

        try:
            chart = run_chart(
                cls, params, adapter, events, Path(trace) if trace else None, progress
            )
        except BindingError as error:
            raise RunError(str(error)) from None
    summary = summarize(chart)
    table = Table(title=f"{cls.NAME}: {summary.outcome or 'not finished'}", title_justify="left")
    table.add_column("skill")
    table.add_column("time [s]", justify="right")
    for path, seconds in summary.skills:
        table.add_row(path, f"{seconds:.3f}")
    Console(highlight=False).print(table)
    print(f"outcome: {summary.outcome or 'not finished'} after {summary.time:.3f} s")
    if not chart.finished:
        print("active: " + " / ".join(chart.active_configuration))
    if summary.fault:
        print(f"error: {summary.fault}")
    return 0 if chart.finished and summary.outcome != "error" else 1
