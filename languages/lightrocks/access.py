"""Reads and writes of the variables per element of a statechart: which names a guard,
an action, a condition, a state's arguments and invariant read, and which an assignment
writes.

A variable is named by its path as written: a parameter or a plain statechart's variable
(``depth``), an attribute of a scene object (``screw.depth``), a device's sensor down to the
leaf read (``robot.wrench.force.z``). A call's function is no read (built-in functions and
device commands are not variables); its arguments are. Every analysis that needs to know
what an element touches (the behaviour checker's liveness and guard shortcuts, the
parameters that vary, the SCXML target's time events) asks here, so the answer is one;
:class:`Accesses` keeps each element's answer for its component (``Component.access``).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, is_dataclass
from typing import Any

from lightrocks.metamodel import ast


@dataclass(frozen=True)
class Access:
    """The variables an element reads and those it writes, each a dotted path."""

    reads: frozenset[str] = frozenset()
    writes: frozenset[str] = frozenset()


NONE = Access()
_NO_READS = (ast.Position, ast.Quantity, ast.BooleanLiteral, ast.StringLiteral)


def access(element: Any) -> Access:
    """What ``element`` reads and writes: an expression, a statement (or a tuple of them), a
    transition (guard, stimulus arguments, action, postcondition), a start or end condition,
    an entry/exit/do action, an invariant, or a state (its arguments, its invariant and the
    actions of its own body; the states and transitions inside are elements of their own)."""
    match element:
        case None:
            return NONE
        case tuple() | list():
            return _union(access(item) for item in element)
        case ast.Assignment(target=target, value=value):
            written, read = _written(target)
            return Access(_reads(value) | read, written)
        case ast.ExpressionStatement(expression=expression):
            return Access(_reads(expression))
        case ast.Transition() | ast.InternalTransition():
            post = getattr(element, "postcondition", None)
            parts = (element.guard, element.stimulus_arguments, element.action, post)
            return access(parts)
        case ast.Condition(expression=expression) | ast.Invariant(expression=expression):
            return access(expression)
        case ast.Action(statements=statements):
            return access(statements)
        case ast.State(arguments=arguments, invariant=invariant, body=body):
            own = [e for e in body or () if isinstance(e, ast.Action)]
            return access(([a.value for a in arguments], invariant, own))
        case _:
            return Access(_reads(element))


def assigned(statechart: ast.Statechart) -> frozenset[str]:
    """The parameters (a plain statechart's variables) some assignment of the chart writes:
    they are not constant."""
    return frozenset(
        path
        for node in ast.walk(statechart)
        if isinstance(node, ast.Assignment)
        for path in access(node).writes
        if "." not in path
    )


def names_of(expression: Any) -> list[str] | None:
    """``a.b.c`` as ``["a", "b", "c"]``; None for anything but names and members."""
    names: list[str] = []
    while isinstance(expression, ast.Member):
        names.append(expression.name)
        expression = expression.target
    if not isinstance(expression, ast.Name):
        return None
    names.append(expression.name)
    return names[::-1]


class Accesses:
    """The reads and writes of one component's elements, each computed once."""

    def __init__(self) -> None:
        self._found: dict[int, tuple[Any, Access]] = {}

    def __call__(self, element: Any) -> Access:
        found = self._found.get(id(element))
        if found is None:
            found = self._found[id(element)] = (element, access(element))
        return found[1]


def _reads(node: Any) -> frozenset[str]:
    found: set[str] = set()
    _collect(node, found)
    return frozenset(found)


def _collect(node: Any, found: set[str]) -> None:
    """Every variable ``node`` reads into ``found``: the longest name chain counts, a call's
    function does not. The usual nodes are taken apart by hand (a generic walk costs many
    times as much on large models), the rest (a language extension's nodes) field by field."""
    chain = names_of(node)
    if chain is not None:
        found.add(".".join(chain))
    elif isinstance(node, ast.Binary):
        _collect(node.left, found)
        _collect(node.right, found)
    elif isinstance(node, ast.Unary):
        _collect(node.operand, found)
    elif isinstance(node, ast.Call):
        for argument in node.arguments:
            _collect(argument.value, found)
    elif isinstance(node, ast.Member):
        _collect(node.target, found)
    elif isinstance(node, ast.Index):
        _collect(node.target, found)
        _collect(node.index, found)
    elif isinstance(node, ast.VectorLiteral | tuple | list):
        for item in node.elements if isinstance(node, ast.VectorLiteral) else node:
            _collect(item, found)
    elif is_dataclass(node) and not isinstance(node, _NO_READS):
        for item in fields(node):
            if item.name != "position":
                _collect(getattr(node, item.name), found)


def _written(target: Any) -> tuple[frozenset[str], frozenset[str]]:
    """The variable an assignment's target writes; a target that is none (only names and
    attributes can be assigned, LR0306) writes nothing and reads what it reads."""
    chain = names_of(target)
    if chain is None:
        return frozenset(), _reads(target)
    return frozenset({".".join(chain)}), frozenset()


def _union(accesses: Any) -> Access:
    reads: set[str] = set()
    writes: set[str] = set()
    for found in accesses:
        reads |= found.reads
        writes |= found.writes
    return Access(frozenset(reads), frozenset(writes))
