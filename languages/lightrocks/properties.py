"""What the predicates of a property (``property name: formula;``) may name besides the
values of the statechart: its own states (true while active) and its outcomes (true at the
moment the run ends with it, ``error`` included). Typing reads these names as Booleans; the
model checker (:mod:`.behaviour.properties`) evaluates them on the configurations it
explored.
"""

from __future__ import annotations

from lightrocks.languages.domain.types import BOOLEAN, Type
from lightrocks.languages.lightrocks.model import Region

KINDS = {
    "ensures": "contract on the outcome",
    "always": "invariant",
    "never": "absence",
    "after": "response",
    "reachable": "reachability",
    "exclusive": "mutual exclusion",
}
"""Each formula keyword and the kind of property it states."""


def top(region: Region) -> Region:
    """The statechart's region around ``region``: a property speaks of the whole chart."""
    while region.parent is not None:
        region = region.parent
    return region


def state_names(region: Region) -> dict[str, int]:
    """Each name of a state (or orthogonal region) of the chart's own hierarchy, not of the
    statecharts it imports, with how many states bear it."""
    counts: dict[str, int] = {}
    for inner in region.regions():
        for name in inner.states:
            counts[name] = counts.get(name, 0) + 1
    return counts


def predicate_names(region: Region) -> dict[str, Type]:
    """The states and outcomes of the chart of ``region``, as the Booleans a predicate reads."""
    chart = top(region)
    names = dict.fromkeys(state_names(chart), BOOLEAN)
    names.update(dict.fromkeys(outcome_names(chart), BOOLEAN))
    return names


def outcome_names(region: Region) -> tuple[str, ...]:
    """The outcomes a run of the chart may end with: its own, and ``error``."""
    return (*region.outcomes, "error")
