"""Edits of a statechart as changes of its syntax tree, written back as canonical text.

An edit names a place in a chart (the states and regions down to the level it changes, as
the diagram's level keys do), changes the tree there and prints the whole file with the
language's pretty printer, keeping its comments. The printed text must parse back into the
changed tree, or the edit is refused: what lands on disk is always what the edit meant.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import replace

from lightrocks.languages.lightrocks.printer import print_statechart
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.comments import Comments

IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")

Elements = tuple


class EditError(ValueError):
    """An edit that does not fit the chart (a taken name, a state that is not there, …)."""


def identifier(text: str, what: str) -> str:
    if not IDENTIFIER.match(text):
        raise EditError(f"{what} '{text}' is not a name (letters, digits and _)")
    return text


def edited(text: str, file: str, change: Callable[[ast.StatechartUnit], ast.StatechartUnit]) -> str:
    """The canonical text of the chart in ``text`` after ``change``; refused unless the text
    parses back into the changed tree."""
    unit = parse_statechart(text, file)
    changed = change(unit)
    printed = print_statechart(changed, Comments(text))
    if parse_statechart(printed, file) != changed:
        raise EditError("the edit does not survive printing and parsing again")
    return printed


def at(place: Sequence[str], change: Callable[[Elements], Elements]) -> Callable:
    """A change of the elements of the statechart, or of the composite state or region that
    ``place`` names below it (``["PressOn", "Arm"]``)."""

    def apply(unit: ast.StatechartUnit) -> ast.StatechartUnit:
        chart = unit.statechart
        return replace(unit, statechart=replace(chart, elements=_inside(chart.elements, place)))

    def _inside(elements: Elements, rest: Sequence[str]) -> Elements:
        if not rest:
            return change(elements)
        name, below = rest[0], rest[1:]
        for index, element in enumerate(elements):
            if isinstance(element, ast.State) and element.name == name and element.body:
                inner = replace(element, body=_inside(element.body, below))
            elif isinstance(element, ast.Region) and element.name == name:
                inner = replace(element, elements=_inside(element.elements, below))
            else:
                continue
            return (*elements[:index], inner, *elements[index + 1 :])
        raise EditError(f"no composite state or region '{name}' here")

    return apply


def names(elements: Elements) -> set[str]:
    kinds = (ast.State, ast.Condition, ast.Pseudostate, ast.Region)
    return {e.name for e in elements if isinstance(e, kinds)}


def add_state(name: str, imported: str) -> Callable[[Elements], Elements]:
    """``<<import="imported">> state name;`` after the last state."""
    identifier(name, "state name")

    def change(elements: Elements) -> Elements:
        if name in names(elements):
            raise EditError(f"'{name}' is taken here")
        state = ast.State(name, stereotypes=(ast.Stereotype("import", imported),))
        return _after_last(elements, (ast.State, ast.Region), state)

    return change


def add_transition(source: str, target: str, stimulus: str) -> Callable[[Elements], Elements]:
    """``source -> target stimulus;`` after the last transition."""
    if stimulus:
        identifier(stimulus, "stimulus")

    def change(elements: Elements) -> Elements:
        for end in (source, target):
            if end not in names(elements):
                raise EditError(f"no state or condition '{end}' here")
        transition = ast.Transition(source, target, stimulus=stimulus)
        return _after_last(elements, (ast.Transition,), transition)

    return change


def delete_state(name: str) -> Callable[[Elements], Elements]:
    """The state and every transition from or to it."""

    def change(elements: Elements) -> Elements:
        if not any(isinstance(e, ast.State) and e.name == name for e in elements):
            raise EditError(f"no state '{name}' here")
        return tuple(
            e
            for e in elements
            if not (isinstance(e, ast.State) and e.name == name)
            and not (isinstance(e, ast.Transition) and name in (e.source, e.target))
        )

    return change


def delete_transitions(source: str, target: str) -> Callable[[Elements], Elements]:
    """Every transition from ``source`` to ``target`` (the diagram draws them as one arrow)."""

    def change(elements: Elements) -> Elements:
        kept = tuple(
            e
            for e in elements
            if not (isinstance(e, ast.Transition) and (e.source, e.target) == (source, target))
        )
        if len(kept) == len(elements):
            raise EditError(f"no transition from '{source}' to '{target}' here")
        return kept

    return change


def chain(elements: Elements) -> list[ast.Transition]:
    """The links of the level's chain: from its start condition, each state's only
    transition to a state not yet in the chain, until one leads elsewhere."""
    states = {e.name for e in elements if isinstance(e, ast.State)}
    transitions = [e for e in elements if isinstance(e, ast.Transition)]
    starts = {e.name for e in elements if isinstance(e, ast.Condition) and e.kind == "start"}
    links: list[ast.Transition] = []
    current = next((t.source for t in transitions if t.source in starts), None)
    visited: set[str] = set()
    while current is not None:
        forward = [t for t in transitions if t.source == current and t.target in states]
        forward = [t for t in forward if t.target not in visited and t.target != current]
        if len(forward) != 1:
            break
        links.append(forward[0])
        visited.add(current)
        current = forward[0].target
    return links


def move_in_chain(name: str, steps: int) -> Callable[[Elements], Elements]:
    """Move the state ``steps`` places along the chain (negative: towards its start). Every
    state keeps its own transition into the chain (its outcome), which now leads to its new
    successor; the one that ends up last leads to the chain's end condition."""

    def change(elements: Elements) -> Elements:
        links = chain(elements)
        order = [link.target for link in links]
        if name not in order:
            raise EditError(f"'{name}' is not in a chain from a start condition here")
        last = end_link(elements, order[-1])
        if last is None:
            raise EditError(f"the chain's last state '{order[-1]}' leads to no end condition")
        own = {link.source: link for link in links} | {order[-1]: last}
        index = order.index(name)
        moved = min(max(index + steps, 0), len(order) - 1)
        if moved == index:
            raise EditError(f"'{name}' is already at that end of the chain")
        order.insert(moved, order.pop(index))
        sources, targets = [links[0].source, *order], [*order, last.target]
        relinked = [replace(own[s], target=t) for s, t in zip(sources, targets, strict=True)]
        slots = sorted(i for i, e in enumerate(elements) if any(e is o for o in own.values()))
        result = list(elements)  # the chain's transitions, in its new order, in their slots
        for slot, transition in zip(slots, relinked, strict=True):
            result[slot] = transition
        return tuple(result)

    return change


def end_link(elements: Elements, source: str) -> ast.Transition | None:
    """The first transition from ``source`` to an end condition."""
    ends = {e.name for e in elements if isinstance(e, ast.Condition) and e.kind == "end"}
    found = (e for e in elements if isinstance(e, ast.Transition) and e.source == source)
    return next((e for e in found if e.target in ends), None)


def with_import(unit: ast.StatechartUnit, qualified: str) -> tuple[ast.StatechartUnit, str]:
    """The unit importing the chart ``qualified`` where it does not yet, and the name the
    chart has in it."""
    package, _, simple = qualified.rpartition(".")
    imported = {i.name for i in unit.imports if not i.wildcard}
    wildcards = {i.name for i in unit.imports if i.wildcard}
    if package == unit.package or qualified in imported or package in wildcards:
        return unit, simple
    return replace(unit, imports=(*unit.imports, ast.Import(qualified))), simple


def _after_last(elements: Elements, kinds: tuple[type, ...], new: object) -> Elements:
    positions = [i for i, e in enumerate(elements) if isinstance(e, kinds)]
    if positions:
        index = positions[-1] + 1
    else:
        later = [i for i, e in enumerate(elements) if isinstance(e, ast.Transition)]
        index = later[0] if later else len(elements)
    return (*elements[:index], new, *elements[index:])
