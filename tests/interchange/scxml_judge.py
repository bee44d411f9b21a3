"""python-statemachine as the judge of the SCXML target: it loads a generated document with its
own SCXML reader (secure default: the restricted evaluator, no ``eval``), runs it on simulated
time, and reports what LightRocks' runtime reports after each step: the active states by
their LightRocks paths and the values of the parameters.

python-statemachine takes delayed events off its queue on the wall clock and, while one is
pending, its synchronous loop waits for it. :func:`simulated` lets the machine read a clock
of its own instead and makes the loop return once nothing is due, so that
:meth:`Machine.advance` fires each delayed event at its own deadline, as
``chart.advance()`` does in LightRocks.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass

import statemachine.engines.sync as sync_engine
import statemachine.event_data as event_data
from statemachine.engines.base import BaseEngine
from statemachine.engines.sync import SyncEngine
from statemachine.io import load

from lightrocks.generators.python.names import identifier
from lightrocks.generators.scxml.writer import Document
from lightrocks.languages.scxml.markup import event_name

EPSILON = 1e-9

Observation = tuple[tuple[str, ...], tuple | None]


class Clock:
    now = 0.0


CLOCK = Clock()


def _take_due_external_event(self, first_result):
    """python-statemachine's own step, on :data:`CLOCK`; nothing due ends the loop."""
    if self.external_queue.is_empty():
        return False, first_result
    self.clear_cache()
    external_event = self.external_queue.pop_due(CLOCK.now + EPSILON)
    if external_event is None:
        return False, first_result
    self._macrostep_count += 1
    self._microstep_count = 0
    result = self._take_external_event(external_event)
    if first_result is self._sentinel:
        first_result = result
    return True, first_result


RESTORED: list[str] = []
"""Ids of final states of regions that a deep history entered again (see
:func:`_add_history_states_to_enter`)."""


def _region_final(state) -> bool:
    region = state.parent
    return bool(state.final and region is not None and region.parent and region.parent.parallel)


_ORIGINAL_HISTORY = BaseEngine._add_history_states_to_enter


def _add_history_states_to_enter(self, info, state, *args):
    """python-statemachine's own, noting the final states of regions it enters again."""
    if state.type.is_deep:
        remembered = self.sm.history_values.get(state.id, ())
        RESTORED.extend(s.id for s in remembered if _region_final(s))
    return _ORIGINAL_HISTORY(self, info, state, *args)


@contextmanager
def simulated() -> Iterator[Clock]:
    """Runs python-statemachine on :data:`CLOCK` while the context lasts."""
    saved = (sync_engine.monotonic, event_data.monotonic, SyncEngine._take_due_external_event)
    sync_engine.monotonic = event_data.monotonic = lambda: CLOCK.now
    SyncEngine._take_due_external_event = _take_due_external_event
    BaseEngine._add_history_states_to_enter = _add_history_states_to_enter
    CLOCK.now = 0.0
    try:
        yield CLOCK
    finally:
        sync_engine.monotonic, event_data.monotonic, SyncEngine._take_due_external_event = saved
        BaseEngine._add_history_states_to_enter = _ORIGINAL_HISTORY


@dataclass
class Machine:
    """A generated document running in python-statemachine (inside :func:`simulated`)."""

    document: Document
    variables: Sequence[str]

    def __post_init__(self) -> None:
        self.sm = load(self.document.text, format="scxml")()

    def send(self, event: str) -> None:
        self.sm.send(event_name(event))

    def advance(self, seconds: float) -> None:
        until = CLOCK.now + seconds
        while not self.sm.is_terminated:
            due = [t for t in self._pending() if t.execution_time <= until + EPSILON]
            if not due:
                break
            CLOCK.now = max(CLOCK.now, min(t.execution_time for t in due))
            self.sm._engine.processing_loop()
        CLOCK.now = until

    def _pending(self) -> list:
        queue = self.sm._engine.external_queue.queue
        with queue.mutex:
            return [t for t in queue.queue if not t.cancelled]

    def pending_deadlines(self) -> list[tuple[float, str]]:
        """The delayed events waiting, with their deadlines."""
        return sorted((t.execution_time, str(t.event)) for t in self._pending())

    def restored_finals(self) -> set[str]:
        """Paths of the final states of regions that deep history entered again since the
        last call: python-statemachine enters them, LightRocks enters those regions at their
        initial state (docs/language.md, the SCXML differences)."""
        found = {"/".join(self.document.paths.get(i, (i,))) for i in RESTORED}
        RESTORED.clear()
        return found

    def observation(self) -> Observation:
        if self.sm.is_terminated:
            return (), None
        paths = self.document.paths
        active = sorted("/".join(paths.get(s.id, (s.id,))) for s in self.sm.configuration)
        model = self.sm.model
        values = tuple(getattr(model, self.document.variables[v]) for v in self.variables)
        return tuple(active), values


def lightrocks_observation(chart, variables: Sequence[str]) -> Observation:
    values = None if chart.outcome else tuple(getattr(chart, identifier(v)) for v in variables)
    return tuple(sorted(chart.active_paths)), values


STEP_PREFIX = "+"


def run_both(cls: type, document: Document, variables: Sequence[str], events: Sequence[str]):
    """Both runs on ``events`` (an item ``+0.25`` advances the clocks): the observations
    after the start and after each item, LightRocks' chart, and python-statemachine's
    machine (whose ``restored`` lists :meth:`Machine.restored_finals` of the start and of
    each item)."""
    chart = cls().start()
    mine = [lightrocks_observation(chart, variables)]
    with simulated():
        RESTORED.clear()
        machine = Machine(document, variables)
        theirs = [machine.observation()]
        machine.restored = [machine.restored_finals()]
        for event in events:
            if event.startswith(STEP_PREFIX):
                seconds = float(event[1:])
                chart.advance(seconds)
                machine.advance(seconds)
            else:
                chart.send(event)
                machine.send(event)
            mine.append(lightrocks_observation(chart, variables))
            theirs.append(machine.observation())
            machine.restored.append(machine.restored_finals())
    return mine, theirs, chart, machine


def same(mine: Observation, theirs: Observation) -> bool:
    """Equal configurations, and equal values while the LightRocks run goes on."""
    return mine[0] == theirs[0] and (mine[1] is None or mine[1] == theirs[1])


DEEP_HISTORY_OVER_A_FINAL = "deep history over a region resting in a final state"


def documented(step: int, mine: Sequence[Observation], theirs: Sequence[Observation], machine):
    """The documented difference that explains the first disagreement, at ``step``, or None:
    python-statemachine entered a region's final state that a deep history remembered,
    where LightRocks entered the region at its initial state."""
    restored = machine.restored[step]
    entered = set(theirs[step][0]) - set(mine[step][0])
    return DEEP_HISTORY_OVER_A_FINAL if restored & entered else None
