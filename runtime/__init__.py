"""The LightRocks state runtime: what generated code imports (as ``import runtime as rt``).

It depends on the standard library, numpy and pinocchio only, never on the workbench. Its
names load on first use (PEP 562): the language's checks import ``safety`` alone and do not
pay for the physics libraries the components bring.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

DEFAULT_BUDGET = 30.0  # seconds, when neither the action nor its device names a timeout

_HOMES = {
    "binding": ("BindingError", "bind", "problems"),
    "component": (
        "ActionComponent",
        "Cell",
        "Component",
        "CompositeComponent",
        "ParallelComponent",
    ),
    "contract": (
        "Adapter",
        "AdapterError",
        "Command",
        "CommandResult",
        "Snapshot",
        "StopCondition",
        "TIMEOUT",
        "Vector3",
        "Wrench",
    ),
    "environment": ("Environment", "SceneObject", "object_name"),
    "executor": ("Executor",),
    "faults": ("Abort", "ERROR", "Fault", "PREEMPTED", "UnknownEvent"),
    "frames": ("Frame", "coordinate", "rotX", "rotY", "rotZ", "transl"),
    "safety": ("Bound", "SafeRange"),
    "sampling": ("Sampler",),
    "states": (
        "Action",
        "Choice",
        "Composite",
        "Condition",
        "Final",
        "Invariant",
        "Parallel",
        "State",
        "Transition",
    ),
    "trace": ("Trace", "to_json"),
}
"""Each submodule and the names it exports."""

_MODULE_OF = {name: module for module, names in _HOMES.items() for name in names}

__all__ = ["DEFAULT_BUDGET", *sorted(_MODULE_OF)]


def __getattr__(name: str) -> Any:
    module = _MODULE_OF.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
