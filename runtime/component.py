"""Statecharts as components: parameters, the cell they run in, and the public API.

A generated statechart class is a :class:`CompositeComponent` or an :class:`ActionComponent`.
The same class serves as the top of a run (``ScrewTask(depth=0.012).start(adapter)``) and as
an ``<<import>>`` state inside another statechart (the parent binds its parameters).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import IO, Any, ClassVar, Self

from lightrocks.runtime.binding import bind
from lightrocks.runtime.contract import Adapter, Snapshot
from lightrocks.runtime.environment import Environment
from lightrocks.runtime.executor import Executor
from lightrocks.runtime.faults import Fault
from lightrocks.runtime.states import Action, Composite, Parallel
from lightrocks.runtime.trace import Record, Trace
from lightrocks.runtime.tree import known_events


class Cell:
    """A cell of the domain interface: device instances, scene objects and the scene name."""

    SCENE: ClassVar[str | None] = None
    DEVICES: ClassVar[Mapping[str, type]] = {}
    OBJECTS: ClassVar[Mapping[str, Mapping[str, Any]]] = {}


class Component:
    """Parameters, the cell, and start/send/trace for a statechart run on its own."""

    NAME: ClassVar[str]
    CELL: ClassVar[type[Cell] | None] = None
    PARAMETERS: ClassVar[Mapping[str, str]] = {}  # model name -> Python attribute
    EVENTS: ClassVar[tuple[str, ...] | None] = None  # declared events, if the model has any

    def __init__(self, parent: Composite | None = None, name: str | None = None, **params: Any):
        super().__init__(parent, name)  # type: ignore[call-arg]
        unknown = sorted(set(params) - set(self.PARAMETERS.values()))
        if unknown:
            known = ", ".join(self.PARAMETERS) or "none"
            raise TypeError(f"{self.NAME} has no parameter(s) {unknown}; parameters: {known}")
        self.given: dict[str, Any] = dict(params)
        self._executor: Executor | None = None

    def defaults(self, s: Snapshot) -> None:
        """Set every parameter to its default (generated)."""

    def initialize(self, s: Snapshot) -> None:
        """On entry: defaults first, then the values given by the user or the parent."""
        self.defaults(s)
        for attribute, value in self.given.items():
            setattr(self, attribute, value)

    # -- running on its own ---------------------------------------------------------------

    def start(
        self, adapter: Adapter | None = None, *, trace: Trace | str | Path | IO[str] | None = None
    ) -> Self:
        """Bind the adapter (conformance checked first) and run the first step."""
        if self.parent is not None:  # type: ignore[attr-defined]
            raise RuntimeError(f"{self!r} is a state of another statechart: start that one")
        if self._executor is not None:
            raise RuntimeError(f"{self!r} was started already")
        if adapter is not None:
            bind(adapter, self.CELL)
        objects = self.CELL.OBJECTS if self.CELL is not None else {}
        recorder = trace if isinstance(trace, Trace) else Trace(trace)
        self._executor = Executor(self, adapter, recorder, Environment(objects))  # type: ignore[arg-type]
        _share_environment(self, self._executor.env)
        self._executor.start()
        return self

    def send(self, event: str) -> bool:
        """Dispatch one event; True when a transition took it. An event the statechart does
        not know raises :class:`runtime.faults.UnknownEvent`."""
        return self._running.send(event)

    def advance(self, seconds: float) -> None:
        """Move the virtual clock of a run without adapter; due ``after(…)`` events fire."""
        self._running.advance(seconds)

    @property
    def events(self) -> frozenset[str]:
        """The events this statechart accepts."""
        return known_events(self)  # type: ignore[arg-type]

    @property
    def _running(self) -> Executor:
        if self._executor is None:
            raise RuntimeError(f"{self!r} has not been started")
        return self._executor

    @property
    def active_configuration(self) -> tuple[str, ...]:
        """Names of the active states, outermost first."""
        return tuple(state.name for state in self._running.active())

    @property
    def active_paths(self) -> tuple[str, ...]:
        """Paths of the active states (``Chart/Composite/Child``): with orthogonal regions
        the configuration is a tree, which names alone do not show."""
        return tuple(state.path for state in self._running.active())

    @property
    def trace(self) -> list[Record]:
        return self._running.trace.records

    @property
    def finished(self) -> bool:
        return self._running.finished

    @property
    def outcome(self) -> str | None:
        return self._running.outcome

    @property
    def fault(self) -> Fault | None:
        return self._running.fault

    def close(self) -> None:
        """Flush the trace file."""
        self._running.trace.close()


class CompositeComponent(Component, Composite):
    """A task, skill or plain statechart."""


class ParallelComponent(Component, Parallel):
    """A task, skill or plain statechart whose body is made of orthogonal regions."""


class ActionComponent(Component, Action):
    """An elemental action."""


def _share_environment(state: Any, env: Environment) -> None:
    """Every state of the run reads and updates the one environment model."""
    state.env = env
    for child in getattr(state, "children", {}).values():
        _share_environment(child, env)
