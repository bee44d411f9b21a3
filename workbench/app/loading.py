"""Check → generate → cache → import: the generated class of a model's statechart.

The cache folder is named by a hash of every loaded model's text, so an unchanged model is
generated once. Generated modules are imported with importlib from that folder; model text
itself is never executed.
"""

from __future__ import annotations

import hashlib
import importlib
import importlib.util
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType

from lightrocks.generators.python import GENERATOR
from lightrocks.generators.python.generator import module_path
from lightrocks.generators.python.names import identifier
from lightrocks.languages.domain.types import UNKNOWN, DeviceT, Type
from lightrocks.languages.lightrocks.analysis import analysis
from lightrocks.languages.lightrocks.cocos_safety import constant_values
from lightrocks.runtime.safety import Bounds, Ranges
from lightrocks.workbench import report
from lightrocks.workbench.app.errors import ModelError
from lightrocks.workbench.app.values import DECLARED_TYPES, SAFE_RANGES
from lightrocks.workbench.check import CheckContext, all_cocos, check
from lightrocks.workbench.generators import GenerationRequest, write_all


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


def load_component(model: Path, search_path: Sequence[Path]) -> type:
    """Check the model, generate it (once per content) and import the class of its chart."""
    context = check([model], list(search_path))
    if context.diagnostics.has_errors:
        raise ModelError(report.text(context.diagnostics.items, all_cocos()))
    unit = next(u.unit for u in context.workspace.loaded_units() if u.path == model.resolve())
    name = f"{unit.package}.{unit.statechart.name}" if unit.package else unit.statechart.name
    package = generated_package(context, [model.resolve()], cache_root())
    cls = component_class(package, name)
    setattr(cls, DECLARED_TYPES, declared_types(context, name))
    setattr(cls, SAFE_RANGES, safe_ranges(context, name))
    return cls


def safe_ranges(context: CheckContext, qualified_name: str) -> Ranges:
    """Every constant safe range of the commands the statechart's devices offer."""
    found = analysis(context)
    component = found.models.component(qualified_name)
    if component is None:
        return {}
    ranges: dict[str, dict[str, dict[str, Bounds]]] = {}
    for name, kind in found.typing.environment(component.region).items():
        if not isinstance(kind, DeviceT) or kind.device is None:
            continue
        for command in kind.device.commands:
            for parameter in command.parameters:
                low, high = constant_values(parameter.low), constant_values(parameter.high)
                if low or high:
                    bounds = (tuple(low) if low else None, tuple(high) if high else None)
                    ranges.setdefault(name, {}).setdefault(command.name, {})[parameter.name] = (
                        bounds
                    )
    return ranges


def declared_types(context: CheckContext, qualified_name: str) -> dict[str, Type]:
    """The declared type of every parameter of a checked statechart, for run values."""
    found = analysis(context)
    component = found.models.component(qualified_name)
    if component is None:
        return {}
    region = component.region
    return {
        name: found.typing.types.resolve(region.loaded, parameter.type) or UNKNOWN
        for name, parameter in region.parameters.items()
    }
