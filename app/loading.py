"""Check → generate → cache → import: the generated class of a model's statechart.

Generated packages live in the run cache (:mod:`app.cache`), so an unchanged model
is generated once. Each entry is verified before it is imported with importlib, all its
modules at once and without writing bytecode beside them; model text itself is never
executed. A run on another robot than its cell names checks and generates the model with
the cell's robot slot re-bound (:mod:`app.rebinding`).
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
import threading
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType

from lightrocks.app import cache
from lightrocks.app.cachedir import cache_root
from lightrocks.app.errors import ModelError, RunError
from lightrocks.app.rebinding import rebinding
from lightrocks.app.robots import RobotChoice
from lightrocks.generators.python import GENERATOR
from lightrocks.metamodel import ast
from lightrocks.workbench import report
from lightrocks.workbench.check import CheckContext, check
from lightrocks.workbench.generators import GenerationRequest, run_generator

# A package is in sys.modules while its modules are still being executed; threads that load
# models at once (a pool of runs, a server) wait here rather than see it half-imported.
_IMPORTING = threading.Lock()


def generator_inputs(
    context: CheckContext, files: list[Path], rebound: str | None = None
) -> list[tuple[str, bytes]]:
    """Every loaded model (path and text), the files generation was asked for, and the
    re-binding of the cell's robot slot the models were checked with."""
    units = sorted(context.workspace.loaded_units(), key=lambda u: str(u.path))
    inputs = [(str(unit.path), unit.path.read_bytes()) for unit in units]
    inputs += [(str(file), b"requested") for file in sorted(files)]
    return inputs + ([("rebound", rebound.encode())] if rebound is not None else [])


def generated_package(
    context: CheckContext, files: list[Path], root: Path, rebound: str | None = None
) -> ModuleType:
    """Generate (once per input) and import the package of every loaded statechart."""
    key = cache.cache_key(GENERATOR.name, generator_inputs(context, files, rebound))
    name = f"lightrocks_{key}"
    with _IMPORTING:
        if name not in sys.modules:
            folder = cache.entry(
                root, key, lambda: run_generator(GENERATOR, GenerationRequest(context, files))
            )
            _import_all(name, folder)
        return sys.modules[name]


def _import_all(name: str, folder: Path) -> None:
    """Import the package and every module in it now, while the entry is known good."""
    spec = importlib.util.spec_from_file_location(
        name, folder / "__init__.py", submodule_search_locations=[str(folder)]
    )
    module = importlib.util.module_from_spec(spec)
    writes_bytecode, sys.dont_write_bytecode = sys.dont_write_bytecode, True
    try:
        sys.modules[name] = module
        spec.loader.exec_module(module)
        for path in sorted(folder.rglob("*.py")):
            parts = path.relative_to(folder).with_suffix("").parts
            if parts[-1] == "__init__":
                parts = parts[:-1]
            if parts:
                importlib.import_module(".".join([name, *parts]))
    except BaseException:
        for loaded in [m for m in sys.modules if m == name or m.startswith(name + ".")]:
            del sys.modules[loaded]
        raise
    finally:
        sys.dont_write_bytecode = writes_bytecode


def component_class(package: ModuleType, qualified_name: str) -> type:
    """The generated class of a statechart, by its qualified model name, as the generated
    package exports it."""
    return package.component(qualified_name)


def load_component(
    model: Path, search_path: Sequence[Path], robot: RobotChoice | None = None
) -> type:
    """Check the model, generate it (once per content) and import the class of its chart;
    with ``robot``, with the robot in the cell's robot slot."""
    rebound = rebinding(model, search_path, robot) if robot is not None else None
    substituted = rebound.substituted if rebound is not None else None
    context = check([model], list(search_path), substituted=substituted)
    if context.diagnostics.has_errors:
        found = report.text(context.diagnostics.items)
        raise ModelError(f"checked with {rebound.description}\n{found}" if rebound else found)
    units = [u.unit for u in context.workspace.loaded_units() if u.path == model.resolve()]
    if not units or not isinstance(units[0], ast.StatechartUnit):
        raise RunError(f"{model} holds no statechart")
    unit = units[0]
    name = f"{unit.package}.{unit.statechart.name}" if unit.package else unit.statechart.name
    described = rebound.description if rebound is not None else None
    package = generated_package(context, [model.resolve()], cache_root(), described)
    return component_class(package, name)
