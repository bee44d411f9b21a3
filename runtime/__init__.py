"""The LightRocks state runtime: what generated code imports (as ``import runtime as rt``).

It depends on the standard library, numpy and pinocchio only, never on the workbench.
"""

from lightrocks.runtime.binding import BindingError, bind, problems
from lightrocks.runtime.component import (
    ActionComponent,
    Cell,
    Component,
    CompositeComponent,
    ParallelComponent,
)
from lightrocks.runtime.contract import (
    TIMEOUT,
    Adapter,
    AdapterError,
    Command,
    CommandResult,
    Snapshot,
    StopCondition,
    Vector3,
    Wrench,
)
from lightrocks.runtime.environment import Environment, SceneObject, object_name
from lightrocks.runtime.executor import Executor
from lightrocks.runtime.faults import ERROR, PREEMPTED, Abort, Fault, UnknownEvent
from lightrocks.runtime.frames import Frame, coordinate, rotX, rotY, rotZ, transl
from lightrocks.runtime.safety import Bound, SafeRange
from lightrocks.runtime.sampling import Sampler
from lightrocks.runtime.states import (
    Action,
    Choice,
    Composite,
    Condition,
    Final,
    Invariant,
    Parallel,
    State,
    Transition,
)
from lightrocks.runtime.trace import Trace, to_json

DEFAULT_BUDGET = 30.0  # seconds, when neither the action nor its device names a timeout

__all__ = [
    "DEFAULT_BUDGET",
    "ERROR",
    "PREEMPTED",
    "TIMEOUT",
    "Abort",
    "Action",
    "ActionComponent",
    "Adapter",
    "AdapterError",
    "BindingError",
    "Bound",
    "Cell",
    "Choice",
    "Command",
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
    "Parallel",
    "ParallelComponent",
    "SafeRange",
    "Sampler",
    "SceneObject",
    "Snapshot",
    "State",
    "StopCondition",
    "Trace",
    "Transition",
    "UnknownEvent",
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
