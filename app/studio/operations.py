"""The edits the page asks for, one typed request each (checked on arrival, see
:mod:`lightrocks.app.web.schema`), and the change of the chart each one makes through
:mod:`.edits`. What the schema cannot say (a name that is not a name, a transition across
regions) is refused here, as an :class:`~.edits.EditError`.

An element is named as on its level: ``Arm/Snap`` on an orthogonal state's level is the
state ``Snap`` of its region ``Arm``.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

from lightrocks.app.studio import edits
from lightrocks.app.web.schema import one_of
from lightrocks.metamodel import ast

Change = Callable[[ast.StatechartUnit], ast.StatechartUnit]


@dataclass(frozen=True)
class Operation:
    """One edit of a chart's level; ``OP`` names it in the request."""

    OP: ClassVar[str] = ""
    SUBJECT: ClassVar[str] = ""
    """The field that names what the edit changes, in its label ('': none)."""

    @property
    def label(self) -> str:
        """The edit as undo and redo name it."""
        subject = getattr(self, self.SUBJECT) if self.SUBJECT else ""
        return f"{self.OP} {subject}".strip()

    def change(self, place: list[str]) -> Change:
        """The change of the chart, made on the level that ``place`` names below it."""
        raise NotImplementedError


def _inside(place: list[str], element: str) -> tuple[list[str], str]:
    """``Arm/Snap`` on the level ``place``: the place of region ``Arm``, state ``Snap``."""
    *regions, name = element.split("/")
    return place + regions, name


@dataclass(frozen=True)
class AddState(Operation):
    OP: ClassVar[str] = "add-state"
    SUBJECT: ClassVar[str] = "name"
    name: str
    imports: str

    def change(self, place: list[str]) -> Change:
        where, name = _inside(place, self.name)
        imported = self.imports
        if not edits.TYPE.match(imported):
            raise edits.EditError(f"imports '{imported}' is not a qualified chart name")

        def add(unit: ast.StatechartUnit) -> ast.StatechartUnit:
            unit, simple = edits.with_import(unit, imported)
            return edits.at(where, edits.add_state(name, simple))(unit)

        return add


@dataclass(frozen=True)
class _Transition(Operation):
    """An edit of a transition from ``source`` to ``target`` with the texts of its form."""

    source: str
    target: str
    stimulus: str = ""
    guard: str = ""
    action: str = ""

    @property
    def label(self) -> str:
        return f"{self.OP} {self.source} -> {self.target}"


@dataclass(frozen=True)
class AddTransition(_Transition):
    OP: ClassVar[str] = "add-transition"

    def change(self, place: list[str]) -> Change:
        where, source = _inside(place, self.source)
        there, target = _inside(place, self.target)
        if where != there:
            raise edits.EditError("a transition joins two states of one region")
        made = edits.add_transition(source, target, self.stimulus, self.guard, self.action)
        return edits.at(where, made)


@dataclass(frozen=True)
class SetTransition(_Transition):
    """The ``number``-th transition of an arrow (from 0, as the arrow lists them)."""

    OP: ClassVar[str] = "set-transition"
    number: int = 0

    def change(self, place: list[str]) -> Change:
        where, source = _inside(place, self.source)
        _, target = _inside(place, self.target)
        fields = (self.stimulus, self.guard, self.action)
        return edits.at(where, edits.set_transition(source, target, self.number, *fields))


@dataclass(frozen=True)
class SetArguments(Operation):
    """``[parameter, value text]`` for the state's parameters, an empty value leaving one to
    its default."""

    OP: ClassVar[str] = "set-arguments"
    SUBJECT: ClassVar[str] = "state"
    state: str
    arguments: tuple[tuple[str, str], ...]

    def change(self, place: list[str]) -> Change:
        where, name = _inside(place, self.state)
        return edits.at(where, edits.set_arguments(name, self.arguments))


@dataclass(frozen=True)
class SetParameters(Operation):
    """The chart's parameters, ``[type, name, default text]`` each."""

    OP: ClassVar[str] = "set-parameters"
    parameters: tuple[tuple[str, str, str], ...]

    def change(self, place: list[str]) -> Change:
        if place:
            raise edits.EditError("parameters belong to the chart's own level")
        return edits.at([], edits.set_parameters(self.parameters))


@dataclass(frozen=True)
class AddCondition(Operation):
    OP: ClassVar[str] = "add-condition"
    SUBJECT: ClassVar[str] = "name"
    kind: str
    name: str
    expression: str = ""

    def change(self, place: list[str]) -> Change:
        where, name = _inside(place, self.name)
        return edits.at(where, edits.add_condition(self.kind, name, self.expression))


@dataclass(frozen=True)
class SetCondition(Operation):
    OP: ClassVar[str] = "set-condition"
    SUBJECT: ClassVar[str] = "name"
    name: str
    expression: str = ""

    def change(self, place: list[str]) -> Change:
        where, name = _inside(place, self.name)
        return edits.at(where, edits.set_condition(name, self.expression))


@dataclass(frozen=True)
class Delete(Operation):
    """A state or condition with its transitions, or (``source->target``) an arrow."""

    OP: ClassVar[str] = "delete"
    SUBJECT: ClassVar[str] = "element"
    element: str

    def change(self, place: list[str]) -> Change:
        if "->" in self.element:
            source, _, target = self.element.partition("->")
            where, source = _inside(place, source)
            _, target = _inside(place, target)
            return edits.at(where, edits.delete_transitions(source, target))
        where, name = _inside(place, self.element)
        return edits.at(where, edits.delete_state(name))


@dataclass(frozen=True)
class Move(Operation):
    """A state ``steps`` places later (earlier: below 0) in its chain of transitions."""

    OP: ClassVar[str] = "move"
    SUBJECT: ClassVar[str] = "state"
    state: str
    steps: int

    def change(self, place: list[str]) -> Change:
        where, name = _inside(place, self.state)
        return edits.at(where, edits.move_in_chain(name, self.steps))


OPERATIONS: dict[str, type[Operation]] = {
    kind.OP: kind
    for kind in (
        AddState,
        AddTransition,
        SetTransition,
        SetArguments,
        SetParameters,
        AddCondition,
        SetCondition,
        Delete,
        Move,
    )
}
"""Every edit by the ``op`` that names it (a rename has a request of its own)."""


def operation(request: Mapping[str, Any]) -> Operation:
    """The edit a request's ``op`` names, checked against its schema."""
    return one_of(OPERATIONS, request, "op", "edit")
