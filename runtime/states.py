"""The state pattern of the LightRocks paper: states with a parent and a current child.

Generated code subclasses these classes and fills their class-level tables (children,
transitions, start and end conditions, invariants) with functions compiled from the model;
the :mod:`runtime.executor` interprets the tables. A table function takes the state that owns
it and the current sensor snapshot: ``guard(owner, s) -> bool``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from lightrocks.runtime import DEFAULT_BUDGET
from lightrocks.runtime.contract import Snapshot
from lightrocks.runtime.safety import SafeRange

Predicate = Callable[[Any, Snapshot], bool]
Effect = Callable[[Any, Snapshot], None]


@dataclass(frozen=True)
class Transition:
    """``source -> target [guard] stimulus / action [post]`` between children of one state.

    An internal transition has no target and stays in its state; ``delay`` makes it a time
    event ``after(delay)`` (seconds); ``history`` enters the target through its shallow or
    deep history.
    """

    source: str
    target: str
    stimulus: str = ""
    guard: Predicate | None = None
    action: Effect | None = None
    post: Predicate | None = None
    location: str = ""
    delay: Callable[[Any, Snapshot], float] | None = None
    history: str = ""  # "" | "shallow" | "deep"


@dataclass(frozen=True)
class Condition:
    """A start or end condition; without ``holds`` it is a pure entry/exit point."""

    name: str
    holds: Predicate | None = None
    location: str = ""


@dataclass(frozen=True)
class Invariant:
    holds: Predicate
    location: str = ""


class State:
    """A state: a name, a parent, entry/exit actions and invariants."""

    NAME: ClassVar[str] = ""
    LOCATION: ClassVar[str] = ""
    ENTRY_LOCATION: ClassVar[str] = ""
    EXIT_LOCATION: ClassVar[str] = ""
    """Where the entry and exit actions are written: where their faults are reported."""
    FINAL: ClassVar[bool] = False
    LAYER: ClassVar[str | None] = None
    OUTCOMES: ClassVar[tuple[str, ...]] = ()
    INVARIANTS: ClassVar[tuple[Invariant, ...]] = ()
    INTERNAL: ClassVar[tuple[Transition, ...]] = ()  # internal transitions, owned by the state
    env: Any  # the run's runtime.environment.Environment, shared by every state

    def __init__(self, parent: Composite | None = None, name: str | None = None) -> None:
        self.name = name or self.NAME
        self.parent = parent
        self.path: str = f"{parent.path}/{self.name}" if parent is not None else self.name

    def on_entry(self, s: Snapshot) -> None:
        """Entry action (generated when the model has one)."""

    def on_exit(self, s: Snapshot) -> None:
        """Exit action (generated when the model has one); μ of an elemental action."""

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.path}>"


class Composite(State):
    """A hierarchical state: children, transitions between them, start and end conditions."""

    CHILDREN: ClassVar[Mapping[str, type[State]]] = {}
    INITIAL: ClassVar[str | None] = None
    STARTS: ClassVar[tuple[Condition, ...]] = ()
    ENDS: ClassVar[tuple[Condition, ...]] = ()
    TRANSITIONS: ClassVar[tuple[Transition, ...]] = ()
    BINDINGS: ClassVar[Mapping[str, Callable[[Any, Snapshot], dict[str, Any]]]] = {}
    BUDGET: ClassVar[float | None] = None
    """Seconds of adapter time a skill or task may take (``<<timeout>>``), or no limit: once
    spent, what runs inside is left and the state ends with the outcome ``timeout``."""

    def __init__(self, parent: Composite | None = None, name: str | None = None) -> None:
        super().__init__(parent, name)
        self.current: State | None = None
        self.last: State | None = None  # the child active when it was last left (history)
        self.children: dict[str, State] = {n: c(self, n) for n, c in self.CHILDREN.items()}
        self.end_names = frozenset(c.name for c in self.ENDS)

    def transitions_from(self, source: str) -> tuple[Transition, ...]:
        """Transitions leaving ``source`` in declaration order (indexed once per class)."""
        index = type(self).__dict__.get("_index")
        if index is None:
            index = {}
            for transition in self.TRANSITIONS:
                index.setdefault(transition.source, []).append(transition)
            index = {k: tuple(v) for k, v in index.items()}
            type(self)._index = index
        return index.get(source, ())


class Parallel(Composite):
    """An orthogonal state: its children are regions (composites), all active together.

    It completes once every region rests in a final state, with the final state of its
    first region as the outcome; leaving it leaves every region.
    """

    def __init__(self, parent: Composite | None = None, name: str | None = None) -> None:
        super().__init__(parent, name)
        self.running: set[str] = set()  # names of the active regions

    def regions(self) -> list[State]:
        """The active regions in declaration order."""
        return [region for name, region in self.children.items() if name in self.running]


class Final(State):
    """A final state: entering it completes its parent with the final state's name."""

    FINAL = True


class Choice(State):
    """A choice pseudostate: left at once by the first branch whose guard holds."""


class Action(State):
    """An elemental action: one device command; its end conditions are the stop conditions."""

    DEVICE: ClassVar[str] = ""
    COMMAND: ClassVar[str] = ""
    BUDGET: ClassVar[float] = DEFAULT_BUDGET
    ENDS: ClassVar[tuple[Condition, ...]] = ()
    SENSORS: ClassVar[tuple[tuple[str, str], ...]] = ()
    RANGES: ClassVar[dict[str, SafeRange]] = {}
    """The declared safe range of every ranged argument, checked before the command is sent."""

    def arguments(self, s: Snapshot) -> dict[str, Any]:
        """The command's arguments by name, in SI (generated)."""
        return {}

    def store(self, value: Any) -> None:
        """Keep what the command returned (``do / obj.attr = dev.cmd(…)``; generated)."""
