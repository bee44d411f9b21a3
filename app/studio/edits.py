"""Edits of a statechart as changes of its syntax tree, written back as canonical text.

An edit names a place in a chart (the states and regions down to the level it changes, as
the diagram's level keys do), changes the tree there and prints the whole file with the
language's pretty printer, keeping its comments. The printed text must parse back into the
changed tree, or the edit is refused: what lands on disk is always what the edit meant.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable, Iterator, Sequence
from dataclasses import fields, is_dataclass, replace
from typing import Any

from lightrocks.languages.lightrocks.model import LAYERS
from lightrocks.languages.lightrocks.printer import print_statechart
from lightrocks.languages.lightrocks.syntax import parse_literal, parse_statechart
from lightrocks.metamodel import ast
from lightrocks.metamodel.comments import Comment, Comments
from lightrocks.metamodel.grammar import SyntaxProblem

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
    parses back into the changed tree and keeps every comment of ``text``."""
    unit = parse_statechart(text, file)
    changed = change(unit)
    comments = _Comments(text, _fresh_blocks(unit, changed), _gone(unit, changed))
    placed = replace(changed, statechart=_placed(changed.statechart, comments.comments))
    printed = print_statechart(placed, comments)
    if parse_statechart(printed, file) != changed:
        raise EditError("the edit does not survive printing and parsing again")
    if Counter(c.text for c in Comments(printed).comments) != Counter(
        c.text for c in Comments(text).comments
    ):
        raise EditError("the edit would lose a comment of the file")
    return printed


class _Comments(Comments):
    """The comments of the source, for a tree some of whose elements are new. A new element
    (no position) and an element that has a block now but had none in the source have no
    closing brace in the source: no comment of the source belongs inside their block."""

    def __init__(self, text: str, fresh: set[ast.Position], gone: set[int]) -> None:
        super().__init__(text)
        self.fresh = fresh
        self.comments = tuple(
            replace(c, own_line=True) if c.line in gone and not c.own_line else c
            for c in self.comments
        )  # a comment at the end of a deleted element's line gets a line of its own

    def closing_brace(self, position: ast.Position) -> tuple[int, int]:
        if position.line <= 0:
            return (0, 0)
        if position in self.fresh or position.column == AFTER:
            return (position.line, position.column)
        return super().closing_brace(position)


AFTER = 10**9
"""The column of a new element's place: after everything on the line it is printed after."""


def _placed(node: Any, comments: Sequence[Comment]) -> Any:
    """``node`` with a place for each new element (one without a position) that follows
    an element with a comment at its end: after that comment, which stays with the element
    it ends (the printer puts comments before the element whose position follows them)."""
    changes = {}
    for name in ("elements", "body", "parameters"):
        items = getattr(node, name, None)
        if not isinstance(items, tuple):
            continue
        items = tuple(_placed(item, comments) for item in items)
        result = list(items)
        for index, item in enumerate(items):
            if getattr(item, "position", None) != ast.NOWHERE or index == 0:
                continue
            previous = result[index - 1].position
            later = [i.position for i in items[index + 1 :] if i.position.line > 0]
            limit = (later[0].line, later[0].column) if later else (AFTER, AFTER)
            ends = [
                c.line
                for c in comments
                if not c.own_line and (previous.line, previous.column) < c.start < limit
            ]
            if previous.line > 0 and ends:
                where = ast.Position(previous.file, max(ends), AFTER)
                result[index] = replace(item, position=where)
        changes[name] = tuple(result)
    return replace(node, **changes) if changes else node


def _has_block(node: object) -> bool:
    if isinstance(node, ast.Transition | ast.InternalTransition):
        return node.action is not None
    if isinstance(node, ast.State):
        return node.body is not None
    return isinstance(node, ast.Action) and node.block


def _nodes(node: object) -> Iterator[object]:
    """Every element, statement and block of a tree (not the expressions)."""
    yield node
    for item in getattr(node, "elements", None) or getattr(node, "body", None) or ():
        yield from _nodes(item)
    for item in getattr(node, "statements", None) or getattr(node, "action", None) or ():
        yield from _nodes(item)


def _lines(unit: ast.StatechartUnit) -> set[int]:
    found = set()
    for node in _nodes(unit.statechart):
        found.add(node.position.line)
        for item in getattr(node, "parameters", ()) or ():
            found.add(item.position.line)
    return found


def _gone(old: ast.StatechartUnit, new: ast.StatechartUnit) -> set[int]:
    """The lines on which an element started that the edit deleted."""
    return _lines(old) - _lines(new)


def _fresh_blocks(old: ast.StatechartUnit, new: ast.StatechartUnit) -> set[ast.Position]:
    """Positions of elements of ``new`` with a block where the source had none."""
    blocks = {n.position for n in _nodes(old.statechart) if _has_block(n)}
    return {
        n.position
        for n in _nodes(new.statechart)
        if _has_block(n) and n.position.line > 0 and n.position not in blocks
    }


def nowhere(node: Any) -> Any:
    """``node`` with every position dropped: a node parsed from a form's text belongs at no
    place of the file it is put into."""
    if isinstance(node, tuple):
        return tuple(nowhere(item) for item in node)
    if not is_dataclass(node) or isinstance(node, ast.Position):
        return node
    changes = {}
    for item in fields(node):
        if not item.init:
            continue
        value = getattr(node, item.name)
        changes[item.name] = ast.NOWHERE if isinstance(value, ast.Position) else nowhere(value)
    return replace(node, **changes)


def expression(text: str, what: str) -> ast.Expression:
    """One expression typed into a form, read by the language's own parser."""
    try:
        return nowhere(parse_literal(text.strip(), what))
    except SyntaxProblem as problem:
        raise EditError(f"{what}: {_problem(problem, text.strip())}") from None


def statements(text: str, what: str) -> tuple[ast.Statement, ...]:
    """Statements typed into a form (``a = b; c();``), read as the body of an action."""
    wrapped = f"statechart Form {{ entry / {{\n{text.strip()}\n}} }}\n"
    try:
        unit = parse_statechart(wrapped, what)
    except SyntaxProblem as problem:
        lines = text.strip().split("\n")
        if 2 <= problem.line <= len(lines) + 1:
            where = f"line {problem.line - 1}, column {problem.column}"
            raise EditError(f"{what}: {problem.message} ({where})") from None
        raise EditError(f"{what}: incomplete ({problem.message})") from None
    [action] = unit.statechart.elements
    return nowhere(action.statements)


def _problem(problem: SyntaxProblem, text: str) -> str:
    if problem.line == 1 and problem.column <= len(text):
        return f"{problem.message} (column {problem.column})"
    return problem.message


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


def add_transition(
    source: str, target: str, stimulus: str, guard: str = "", action: str = ""
) -> Callable[[Elements], Elements]:
    """``source -> target [guard] stimulus / { action };`` after the last transition."""
    transition = _transition(ast.Transition(source, target), stimulus, guard, action)

    def change(elements: Elements) -> Elements:
        for end in (source, target):
            if end not in names(elements):
                raise EditError(f"no state or condition '{end}' here")
        return _after_last(elements, (ast.Transition,), transition)

    return change


def _transition(old: ast.Transition, stimulus: str, guard: str, action: str) -> ast.Transition:
    """``old`` with the stimulus, guard and action typed into a form ('' for none)."""
    stimulus = stimulus.strip()
    if stimulus:
        identifier(stimulus, "stimulus")
    arguments = old.stimulus_arguments if stimulus == old.stimulus else ()
    return replace(
        old,
        stimulus=stimulus,
        stimulus_arguments=arguments,
        guard=expression(guard, "guard") if guard.strip() else None,
        action=statements(action, "action") if action.strip() else None,
    )


def set_transition(
    source: str, target: str, number: int, stimulus: str, guard: str, action: str
) -> Callable[[Elements], Elements]:
    """The ``number``-th transition from ``source`` to ``target`` (counted from 0, as the
    arrow lists them) with a new stimulus, guard and action."""

    def change(elements: Elements) -> Elements:
        found = [
            i
            for i, e in enumerate(elements)
            if isinstance(e, ast.Transition) and (e.source, e.target) == (source, target)
        ]
        if not 0 <= number < len(found):
            raise EditError(f"no transition {number + 1} from '{source}' to '{target}' here")
        index = found[number]
        new = _transition(elements[index], stimulus, guard, action)
        return (*elements[:index], new, *elements[index + 1 :])

    return change


def set_arguments(name: str, values: Sequence[tuple[str, str]]) -> Callable[[Elements], Elements]:
    """The arguments of the state ``name``: ``(parameter, value text)`` in the order given,
    an empty value leaving the parameter to its default."""
    arguments = tuple(
        ast.Argument(expression(text, f"argument '{key}'"), identifier(key, "parameter"))
        for key, text in values
        if text.strip()
    )
    if len({a.name for a in arguments}) < len(arguments):
        raise EditError("a parameter is given twice")

    def change(elements: Elements) -> Elements:
        for index, element in enumerate(elements):
            if isinstance(element, ast.State) and element.name == name:
                new = replace(element, arguments=arguments)
                return (*elements[:index], new, *elements[index + 1 :])
        raise EditError(f"no state '{name}' here")

    return change


TYPE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*\Z")


def set_parameters(rows: Sequence[tuple[str, str, str]]) -> Callable[[Elements], Elements]:
    """The chart's parameters: ``(type, name, default text)`` each, in this order; a
    parameter that keeps its name keeps its place for the comments around it."""
    for kind, _, _ in rows:
        if not TYPE.match(kind.strip()):
            raise EditError(f"type '{kind}' is not a type name")
    given = [
        ast.Parameter(
            kind.strip(),
            identifier(name.strip(), "parameter name"),
            expression(default, f"default of '{name.strip()}'") if default.strip() else None,
        )
        for kind, name, default in rows
    ]
    if len({p.name for p in given}) < len(given):
        raise EditError("two parameters have one name")

    def change(elements: Elements) -> Elements:
        blocks = [i for i, e in enumerate(elements) if isinstance(e, ast.ParameterBlock)]
        old = {p.name: p for i in blocks for p in elements[i].parameters}
        kept = tuple(
            replace(p, position=old[p.name].position) if p.name in old else p for p in given
        )
        rest = tuple(e for i, e in enumerate(elements) if i not in blocks[1:])
        if not blocks:
            return (ast.ParameterBlock(kept), *elements) if kept else elements
        index = blocks[0]
        if not kept:
            return (*rest[:index], *rest[index + 1 :])
        return (*rest[:index], replace(rest[index], parameters=kept), *rest[index + 1 :])

    return change


def add_condition(kind: str, name: str, condition: str = "") -> Callable[[Elements], Elements]:
    """``kind condition name [condition];`` after the conditions (before the states when
    there are none yet)."""
    if kind not in ("start", "end"):
        raise EditError(f"a condition is 'start' or 'end', not '{kind}'")
    identifier(name, "condition name")
    guard = expression(condition, f"condition '{name}'") if condition.strip() else None
    new = ast.Condition(kind, name, guard)

    def change(elements: Elements) -> Elements:
        if name in names(elements):
            raise EditError(f"'{name}' is taken here")
        conditions = [i for i, e in enumerate(elements) if isinstance(e, ast.Condition)]
        if conditions:
            index = conditions[-1] + 1
        else:
            heads = (ast.ParameterBlock, ast.EventBlock)
            index = sum(1 for _ in _leading(elements, heads))
        return (*elements[:index], new, *elements[index:])

    return change


def set_condition(name: str, condition: str) -> Callable[[Elements], Elements]:
    """The expression of the condition ``name`` ('' for none)."""
    guard = expression(condition, f"condition '{name}'") if condition.strip() else None

    def change(elements: Elements) -> Elements:
        for index, element in enumerate(elements):
            if isinstance(element, ast.Condition) and element.name == name:
                new = replace(element, expression=guard)
                return (*elements[:index], new, *elements[index + 1 :])
        raise EditError(f"no condition '{name}' here")

    return change


def _leading(elements: Elements, kinds: tuple[type, ...]) -> Iterator[object]:
    for element in elements:
        if not isinstance(element, kinds):
            return
        yield element


def new_chart(package: str, name: str, layer: str, imports: Sequence[str] = ()) -> str:
    """The text of a new, empty statechart: ``<<layer>> statechart name { }`` in
    ``package``, importing ``imports`` (a cell, say)."""
    identifier(name, "statechart name")
    if package and not TYPE.match(package):
        raise EditError(f"package '{package}' is not a package name")
    if layer and layer not in LAYERS:
        raise EditError(f"layer '{layer}' is none of {', '.join(LAYERS)}")
    for imported in imports:
        if not TYPE.match(imported):
            raise EditError(f"import '{imported}' is not a qualified name")
    stereotypes = (ast.Stereotype(layer),) if layer else ()
    unit = ast.StatechartUnit(
        package,
        tuple(ast.Import(i) for i in imports),
        ast.Statechart(name, (), stereotypes),
    )
    return print_statechart(unit)


def delete_state(name: str) -> Callable[[Elements], Elements]:
    """The state (or condition, or pseudostate) and every transition from or to it."""
    kinds = (ast.State, ast.Condition, ast.Pseudostate)

    def change(elements: Elements) -> Elements:
        if not any(isinstance(e, kinds) and e.name == name for e in elements):
            raise EditError(f"no state or condition '{name}' here")
        return tuple(
            e
            for e in elements
            if not (isinstance(e, kinds) and e.name == name)
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
