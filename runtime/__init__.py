"""The LightRocks state runtime: what generated code imports (as ``import runtime as rt``).

It depends on the standard library, numpy and pinocchio only, never on the workbench.
"""

from runtime.binding import BindingError, bind, problems
from runtime.component import ActionComponent, Cell, Component, CompositeComponent
from runtime.contract import (
    TIMEOUT,
    Adapter,
    AdapterError,
    CommandResult,
    Snapshot,
    StopCondition,
    Vector3,
    Wrench,
)
from runtime.environment import Environment, SceneObject, object_name
from runtime.executor import ERROR, PREEMPTED, Executor, Fault
from runtime.frames import Frame, coordinate, rotX, rotY, rotZ, transl
from runtime.states import Action, Composite, Condition, Final, Invariant, State, Transition
from runtime.trace import Trace, to_json

DEFAULT_BUDGET = 30.0  # seconds, when neither the action nor its device names a timeout

__all__ = [
    "DEFAULT_BUDGET",
    "ERROR",
    "PREEMPTED",
    "TIMEOUT",
    "Action",
    "ActionComponent",
    "Adapter",
    "AdapterError",
    "BindingError",
    "Cell",
    "CommandResult",
    "Component",
    "Composite",
    "CompositeComponent",
    "Condition",
    "Environment",
    "Executor",
    "Fault",
    "Final",
    "Frame",
    "Invariant",
    "SceneObject",
    "Snapshot",
    "State",
    "StopCondition",
    "Trace",
    "Transition",
    "Vector3",
    "Wrench",
    "bind",
    "coordinate",
    "object_name",
    "problems",
    "rotX",
    "rotY",
    "rotZ",
    "to_json",
    "transl",
]
