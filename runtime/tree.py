"""The shape of a state tree, computed once per run or asked on every step: the events it
accepts, the transitions an event or a time event may take from each state, and the states
above and the active states below a state."""

from __future__ import annotations

from lightrocks.runtime.contract import TIMEOUT
from lightrocks.runtime.faults import ERROR, PREEMPTED
from lightrocks.runtime.states import Action, Composite, Parallel, State, Transition

BUDGET_SPENT = Transition(source="", target="", stimulus=TIMEOUT,
                          delay=lambda state, _: state.BUDGET)  # fmt: skip
"""The time event of a composite's ``BUDGET``: it ends the composite with ``timeout``."""


def known_events(top: State) -> frozenset[str]:
    """Every event the state tree can take: declared ones and the stimuli that are no
    outcome of their source."""
    found: set[str] = set(getattr(top, "EVENTS", None) or ())
    internal = [t.stimulus for t in top.INTERNAL if t.delay is None]
    found.update(internal)
    if isinstance(top, Composite):
        for transition in top.TRANSITIONS:
            source = top.children.get(transition.source)
            if source is None or transition.delay is not None or not transition.stimulus:
                continue
            if transition.stimulus not in completions(source):
                found.add(transition.stimulus)
        for child in top.children.values():
            found |= known_events(child)
    return frozenset(found)


def states_below(top: State) -> list[State]:
    """Every state of the tree below ``top``, ``top`` first."""
    found, pending = [], [top]
    while pending:
        state = pending.pop()
        found.append(state)
        pending += getattr(state, "children", {}).values()
    return found


def reactions(state: State) -> dict[str, tuple[tuple[State, Transition], ...]]:
    """The transitions an event may take from ``state``, by event, each with the state its
    guard belongs to: its internal transitions, then those leaving it (unless the event is
    one of its completions, which only its completion fires)."""
    found: dict[str, list[tuple[State, Transition]]] = {}
    for transition in state.INTERNAL:
        found.setdefault(transition.stimulus, []).append((state, transition))
    parent = state.parent
    if parent is not None:
        own = completions(state)
        for transition in parent.transitions_from(state.name):
            if transition.stimulus not in own:
                found.setdefault(transition.stimulus, []).append((parent, transition))
    return {event: tuple(candidates) for event, candidates in found.items()}


def timed_events(state: State) -> tuple[tuple[State, Transition], ...]:
    """The time events armed on entering ``state``: its own, then those leaving it (the order
    in which they fire at one deadline); each with the state its delay belongs to."""
    parent = state.parent
    leaving = parent.transitions_from(state.name) if parent is not None else ()
    # a composite's budget is a time event; an action's BUDGET is its command's own
    spends = isinstance(state, Composite) and state.BUDGET is not None
    budget = [(state, BUDGET_SPENT)] if spends else []
    return tuple(
        [(state, t) for t in state.INTERNAL if t.delay is not None]
        + budget
        + [(parent, t) for t in leaving if t.delay is not None]
    )


def active_children(state: State) -> list[State]:
    """The active children of ``state``. The executor's ``_select`` and ``_exit``, on the path
    of every event, test the two cases in place: a list per call made dispatch 20 % slower."""
    if isinstance(state, Parallel):
        return state.regions()
    if isinstance(state, Composite) and state.current is not None:
        return [state.current]
    return []


def owners(state: State) -> list[State]:
    """The states that enclose ``state``, innermost first."""
    found = []
    while state.parent is not None:
        state = state.parent
        found.append(state)
    return found


def completions(state: State) -> tuple[str, ...]:
    """Outcomes ``state`` ends with: they fire only on completion, never as external events."""
    if isinstance(state, Action | Composite):
        return (*state.OUTCOMES, ERROR, TIMEOUT, PREEMPTED)
    return (ERROR,)  # a violated invariant ends even a simple state


def matches(transition: Transition, outcome: str, child: State) -> bool:
    """The stimulus names the outcome, or is empty and the outcome is a declared one."""
    stimulus = transition.stimulus
    return stimulus == outcome or (not stimulus and outcome in child.OUTCOMES)
