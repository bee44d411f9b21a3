"""Abstract syntax of UML/P statecharts, LightRocks components and domain interfaces.

The textX parse tree is converted into these frozen dataclasses so that every later stage
(symbols, CoCos, printers, generators) works on plain, comparable values. Source positions
take no part in equality: a model printed and parsed again compares equal to the original.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, fields, is_dataclass
from functools import cache
from typing import Any


@dataclass(frozen=True)
class Position:
    """Where a node starts in its file (1-based line and column) and where it ends: the
    line and column just after its last character, as the parse tree records them (0 where
    no end is known: built-in names, whole-file findings). Positions are told apart by their
    start only, so a node's findings stay one finding whatever its extent."""

    file: str
    line: int
    column: int
    end_line: int = field(default=0, compare=False)
    end_column: int = field(default=0, compare=False)

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"

    @property
    def has_end(self) -> bool:
        return self.end_line > 0

    def through(self, last: Position) -> Position:
        """From this start to the end of ``last`` (a node made of several parts)."""
        return Position(self.file, self.line, self.column, last.end_line, last.end_column)


NOWHERE = Position("<builtin>", 0, 0)


def _position() -> Position:
    return field(default=NOWHERE, compare=False, repr=False)


# --- expressions -------------------------------------------------------------------------


@dataclass(frozen=True)
class Quantity:
    """A number with an optional unit; ``value`` is already converted to SI."""

    value: float
    unit: str = ""
    text: str = field(default="", compare=False)
    position: Position = _position()

    @property
    def integral(self) -> bool:
        """Written as a whole number without unit (``3``, not ``3.0``, ``1e3`` or ``3 mm``):
        an Integer, as every target keeps it."""
        whole = not any(c in self.text for c in ".eE") and float(self.value).is_integer()
        return not self.unit and whole


@dataclass(frozen=True)
class BooleanLiteral:
    value: bool
    position: Position = _position()


@dataclass(frozen=True)
class StringLiteral:
    value: str
    position: Position = _position()


@dataclass(frozen=True)
class VectorLiteral:
    elements: tuple[Expression, ...]
    position: Position = _position()


@dataclass(frozen=True)
class Name:
    name: str
    position: Position = _position()


@dataclass(frozen=True)
class Member:
    target: Expression
    name: str
    position: Position = _position()


@dataclass(frozen=True)
class Argument:
    """A call argument; ``name`` is empty for positional arguments."""

    value: Expression
    name: str = ""
    position: Position = _position()


@dataclass(frozen=True)
class Call:
    function: Expression
    arguments: tuple[Argument, ...]
    position: Position = _position()


@dataclass(frozen=True)
class Index:
    target: Expression
    index: Expression
    position: Position = _position()


@dataclass(frozen=True)
class Unary:
    operator: str
    operand: Expression
    position: Position = _position()


@dataclass(frozen=True)
class Binary:
    operator: str
    left: Expression
    right: Expression
    position: Position = _position()


class ExtensionNode(ABC):
    """An expression or a statement that a language extension adds through the grammar hooks
    ``ExpressionExtension`` and ``StatementExtension``.

    Subclasses are frozen dataclasses with a ``position``. Every stage that meets one asks
    the node itself: the printer for its text, typing for its type; generators render it
    through the extension's templates, or refuse it with its position.
    """

    position: Position

    @abstractmethod
    def text(self, expression: Callable[[Expression], str]) -> str:
        """The node as model text (a statement with its ``;``), given the text of each
        sub-expression."""

    @abstractmethod
    def infer(self, infer: Callable[[Expression], Any]) -> Any:
        """The node's type given the type of each sub-expression (types of
        ``languages.domain.types``); a statement types its parts and returns ``None``."""


Expression = (
    (Quantity | BooleanLiteral | StringLiteral | VectorLiteral | Name | Member | Call | Index)
    | Unary
    | Binary
    | ExtensionNode
)


# --- statements --------------------------------------------------------------------------


@dataclass(frozen=True)
class Assignment:
    target: Expression
    value: Expression
    position: Position = _position()


@dataclass(frozen=True)
class ExpressionStatement:
    expression: Expression
    position: Position = _position()


Statement = Assignment | ExpressionStatement | ExtensionNode


def evaluated(statement: Statement) -> Expression | None:
    """What a statement evaluates: an assignment's value, an expression statement's
    expression; None for a statement of a language extension, which has its own fields."""
    if isinstance(statement, Assignment):
        return statement.value
    return statement.expression if isinstance(statement, ExpressionStatement) else None


# --- statecharts -------------------------------------------------------------------------


@dataclass(frozen=True)
class Stereotype:
    """``<<name>>`` or ``<<name="value">>``; ``value`` is None when no value is given."""

    name: str
    value: str | None = None
    position: Position = _position()


@dataclass(frozen=True)
class Parameter:
    """A parameter, or an attribute of a scene object (which may declare the range of values
    it takes, ``low .. high``)."""

    type: str
    name: str
    default: Expression | None = None
    position: Position = _position()
    low: Expression | None = None
    high: Expression | None = None


@dataclass(frozen=True)
class Condition:
    """A named start or end condition; without an expression it is a pure entry/exit point."""

    kind: str  # "start" | "end"
    name: str
    expression: Expression | None = None
    position: Position = _position()


@dataclass(frozen=True)
class Property:
    """``property name: formula;`` — what every run of the statechart guarantees, proved or
    refuted by ``lightrocks verify``. ``kind`` is the formula's keyword; ``expressions`` are
    its bracketed predicates in order (``after [p] eventually [q]``: p, q); ``outcome`` is
    the end named by ``outcome ensures [p]``."""

    name: str
    kind: str  # "always" | "never" | "reachable" | "after" | "exclusive" | "ensures"
    expressions: tuple[Expression, ...]
    outcome: str = ""
    position: Position = _position()
    outcome_position: Position = _position()


@dataclass(frozen=True)
class Action:
    """``entry /``, ``exit /`` or ``do /`` with its statements."""

    kind: str  # "entry" | "exit" | "do"
    statements: tuple[Statement, ...]
    block: bool = True
    position: Position = _position()


@dataclass(frozen=True)
class Invariant:
    expression: Expression
    position: Position = _position()


@dataclass(frozen=True)
class Transition:
    source: str
    target: str
    guard: Expression | None = None
    stimulus: str = ""
    stimulus_arguments: tuple[Expression, ...] = ()
    action: tuple[Statement, ...] | None = None
    postcondition: Expression | None = None
    position: Position = _position()
    source_position: Position = _position()
    target_position: Position = _position()
    stimulus_position: Position = _position()
    target_history: str = ""  # ``Target.H``: enter Target through its history pseudostate H

    delay = property(lambda self: _delay(self))


@dataclass(frozen=True)
class InternalTransition:
    """``internal [guard] stimulus / { action };``: reacts without leaving its state."""

    stimulus: str
    guard: Expression | None = None
    stimulus_arguments: tuple[Expression, ...] = ()
    action: tuple[Statement, ...] | None = None
    position: Position = _position()
    stimulus_position: Position = _position()

    delay = property(lambda self: _delay(self))


def _delay(transition: Transition | InternalTransition) -> Expression | None:
    """The duration of a time event ``after(d)``, or None for any other stimulus."""
    if transition.stimulus == "after" and len(transition.stimulus_arguments) == 1:
        return transition.stimulus_arguments[0]
    return None


@dataclass(frozen=True)
class Pseudostate:
    """``choice C;``, ``history H;`` or ``deep history H;`` in a region."""

    kind: str  # "choice" | "history" | "deep history"
    name: str
    position: Position = _position()


@dataclass(frozen=True)
class Event:
    name: str
    position: Position = _position()


@dataclass(frozen=True)
class EventBlock:
    """``events { … }``: the external events a statechart accepts."""

    events: tuple[Event, ...]
    position: Position = _position()


@dataclass(frozen=True)
class State:
    name: str
    stereotypes: tuple[Stereotype, ...] = ()
    modifiers: tuple[str, ...] = ()  # "initial", "final"
    arguments: tuple[Argument, ...] = ()
    invariant: Expression | None = None
    body: tuple[Element, ...] | None = None
    position: Position = _position()

    @property
    def is_initial(self) -> bool:
        return "initial" in self.modifiers

    @property
    def is_final(self) -> bool:
        return "final" in self.modifiers


@dataclass(frozen=True)
class Region:
    """``region Name { … }``: one orthogonal region of a statechart or composite state."""

    name: str
    elements: tuple[Element, ...]
    position: Position = _position()


Element = (
    Parameter
    | Condition
    | Property
    | Action
    | Invariant
    | State
    | Pseudostate
    | Transition
    | InternalTransition
    | Region
)


@dataclass(frozen=True)
class ParameterBlock:
    """``parameters { … }`` — kept as a block so printing reproduces it."""

    parameters: tuple[Parameter, ...]
    position: Position = _position()


@dataclass(frozen=True)
class Statechart:
    name: str
    elements: tuple[Element | ParameterBlock | EventBlock, ...]
    stereotypes: tuple[Stereotype, ...] = ()
    position: Position = _position()


@dataclass(frozen=True)
class Import:
    name: str
    wildcard: bool = False
    position: Position = _position()


@dataclass(frozen=True)
class StatechartUnit:
    """One ``.lr`` file: a package, its imports and exactly one statechart."""

    package: str
    imports: tuple[Import, ...]
    statechart: Statechart
    file: str = field(default="", compare=False)
    package_position: Position = _position()


# --- domain interfaces -------------------------------------------------------------------


@dataclass(frozen=True)
class QuantityType:
    """A scalar quantity; ``unit`` is empty for dimensionless numbers."""

    name: str
    unit: str = ""
    position: Position = _position()


@dataclass(frozen=True)
class VectorType:
    """A fixed-size vector: either ``of`` one element type or one unit per element."""

    name: str
    element_type: str = ""
    size: int = 0
    units: tuple[str, ...] = ()
    position: Position = _position()


@dataclass(frozen=True)
class Field:
    type: str
    name: str
    position: Position = _position()


@dataclass(frozen=True)
class StructureType:
    name: str
    fields: tuple[Field, ...]
    position: Position = _position()


@dataclass(frozen=True)
class CommandParameter:
    type: str
    name: str
    default: Expression | None = None
    low: Expression | None = None
    high: Expression | None = None
    position: Position = _position()


@dataclass(frozen=True)
class Command:
    name: str
    parameters: tuple[CommandParameter, ...]
    returns: str = ""
    position: Position = _position()


@dataclass(frozen=True)
class Sensor:
    """A sensor; ``start`` is its value when a command of its device starts, ``low .. high``
    the range of values it reports (both optional)."""

    type: str
    name: str
    position: Position = _position()
    start: Expression | None = None
    low: Expression | None = None
    high: Expression | None = None


@dataclass(frozen=True)
class Device:
    name: str
    members: tuple[Command | Sensor, ...]
    stereotypes: tuple[Stereotype, ...] = ()
    position: Position = _position()

    @property
    def commands(self) -> tuple[Command, ...]:
        return tuple(m for m in self.members if isinstance(m, Command))

    @property
    def sensors(self) -> tuple[Sensor, ...]:
        return tuple(m for m in self.members if isinstance(m, Sensor))


@dataclass(frozen=True)
class DeviceInstance:
    name: str
    type: str
    position: Position = _position()


@dataclass(frozen=True)
class SceneObject:
    name: str
    attributes: tuple[Parameter, ...] = ()
    position: Position = _position()


@dataclass(frozen=True)
class Cell:
    name: str
    members: tuple[DeviceInstance | SceneObject, ...]
    stereotypes: tuple[Stereotype, ...] = ()
    position: Position = _position()

    @property
    def devices(self) -> tuple[DeviceInstance, ...]:
        return tuple(m for m in self.members if isinstance(m, DeviceInstance))

    @property
    def objects(self) -> tuple[SceneObject, ...]:
        return tuple(m for m in self.members if isinstance(m, SceneObject))


Declaration = QuantityType | VectorType | StructureType | Device | Cell


@dataclass(frozen=True)
class DomainUnit:
    """One ``.lrd`` file: a package, its imports and its declarations."""

    package: str
    imports: tuple[Import, ...]
    declarations: tuple[Declaration, ...]
    file: str = field(default="", compare=False)
    package_position: Position = _position()


Unit = StatechartUnit | DomainUnit


def stereotype(stereotypes: tuple[Stereotype, ...], name: str) -> Stereotype | None:
    """The stereotype called ``name``, if present."""
    return next((s for s in stereotypes if s.name == name), None)


@cache
def field_names(cls: type) -> tuple[str, ...]:
    """The field names of a node class, looked up once per class: the walks over whole
    models (storing, depth) meet every node of a large model."""
    return tuple(f.name for f in fields(cls))


def walk(node: Any) -> Iterator[Any]:
    """Every node at or below ``node``, parents before children, in source order of fields."""
    if isinstance(node, tuple | list):
        for item in node:
            yield from walk(item)
    elif is_dataclass(node) and not isinstance(node, Position):
        yield node
        for item in fields(node):
            if item.name != "position":
                yield from walk(getattr(node, item.name))


def is_extension(node: Any) -> bool:
    """A node a language extension contributed: every built-in node is defined here."""
    return is_dataclass(node) and type(node).__module__ != __name__
