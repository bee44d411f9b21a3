"""The values the model checker tracks exactly, and guards decided against them.

Integer, Real and Boolean attributes of scene objects (and parameters) are tracked while
their value is known: a constant default, a constant assigned, a counter incremented. A value
computed from a sensor, or one that outgrows :data:`LIMIT` or :data:`DIGITS`, becomes
unknown: any value. A guard is then decided by the solver with the known values put in and the
unknown ones free, so each branch the real system could take is a branch here (a sound
over-approximation).
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import z3

from lightrocks.languages.lightrocks.access import names_of
from lightrocks.languages.lightrocks.behaviour.judge import Judge, constants
from lightrocks.languages.lightrocks.behaviour.scope import Scope
from lightrocks.languages.lightrocks.behaviour.terms import Terms
from lightrocks.languages.lightrocks.model import Region
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import fold

LIMIT = 10**6
DIGITS = 40
"""A rational whose numerator or denominator has more digits becomes unknown as well: a
recurrence such as ``r = r + c / r`` doubles them at every step."""
Value = int | tuple[int, int] | bool
"""A Boolean, an Integer, or a rational as (numerator, denominator): hashed fast."""
Store = tuple[tuple[str, Value], ...]
"""Known values by path (``screw.cycles``), sorted: a configuration's data part."""


@dataclass(frozen=True)
class Frame:
    """One instance of a statechart: its parameters' values (None: unknown) and the scene
    objects its ``Object`` parameters stand for."""

    values: tuple[tuple[str, Value | None], ...] = ()
    objects: tuple[tuple[str, str], ...] = ()

    def value(self, name: str) -> Value | None:
        return dict(self.values).get(name)

    def object(self, name: str) -> str | None:
        return dict(self.objects).get(name)


class Evaluator:
    """Guards and assignments of one region, decided under a frame and a store."""

    def __init__(self, typing: Typing, region: Region) -> None:
        self.region = region
        self.terms = Terms(Scope(typing, region))
        self.judge = Judge(self.terms)
        self._terms: dict[int, z3.ExprRef | None] = {}
        self._answers: dict[tuple, list[int | None]] = {}
        self._read: dict[int, frozenset[str]] = {}
        self._values: dict[tuple, Value | None] = {}

    def first_enabled(
        self, guards: list[ast.Expression | None], frame: Frame, store: Store
    ) -> list[int | None]:
        """Which of the guards can be the first to hold (index), and whether none can
        (``None``): the choices the real system has."""
        terms = [z3.BoolVal(True) if g is None else self._condition(g) for g in guards]
        paths = set().union(*(self._reads(g) for g in guards if g is not None))
        shown = self._shown(paths, frame, store)
        key = (tuple(term.get_id() for term in terms), shown)  # by structure: solved once
        if key in self._answers:
            return self._answers[key]
        known = [self.terms.read[p][1] == _constant(self.terms.read[p][1], v) for p, v in shown]
        found: list[int | None] = []
        earlier: list[z3.BoolRef] = []
        for index, term in enumerate(terms):
            if self.judge.possible(term, *earlier, *known) is not False:
                found.append(index)
            earlier.append(z3.Not(term))
            if z3.is_true(term):
                break
        else:
            if self.judge.possible(*earlier, *known) is not False:
                found.append(None)
        self._answers[key] = found
        return found

    def _shown(self, paths: set[str], frame: Frame, store: Store) -> tuple:
        """The known values of ``paths``, sorted: what a decision depends on."""
        if not paths:
            return ()
        values = dict(store)
        shown = []
        for path in sorted(paths):
            value = self._known(path, self.terms.read[path][0].kind, frame, values)
            if value is not None:
                shown.append((path, value))
        return tuple(shown)

    def _reads(self, expression: ast.Expression) -> frozenset[str]:
        """The variables an expression's term reads, found once."""
        key = id(expression)
        if key not in self._read:
            term = self._terms.get(key)
            names = {str(c) for c in constants(term)} if term is not None else set()
            self._read[key] = frozenset(p for p in self.terms.read if p in names)
        return self._read[key]

    def _known(self, path: str, kind: str, frame: Frame, values: dict[str, Value]) -> Value | None:
        if kind == "parameter" and "." not in path:
            return frame.value(path)
        return values.get(resolve(path, frame))

    def _condition(self, expression: ast.Expression) -> z3.BoolRef:
        if id(expression) not in self._terms:
            self._terms[id(expression)] = self.terms.condition(expression)
        return self._terms[id(expression)]

    def value(self, expression: ast.Expression, frame: Frame, store: Store) -> Value | None:
        """The value of an expression when every value it reads is known, else None."""
        if id(expression) not in self._terms:
            self._terms[id(expression)] = self.terms.term(expression)
        term = self._terms[id(expression)]
        if term is None:
            return None
        values = dict(store)
        known = []
        for path in sorted(self._reads(expression)):
            variable, _ = self.terms.read[path]
            value = self._known(path, variable.kind, frame, values)
            if value is None:
                return None
            known.append((path, value))
        key = (id(expression), tuple(known))
        if key not in self._values:
            pairs = [(self.terms.read[p][1], _constant(self.terms.read[p][1], v)) for p, v in known]
            simple = z3.simplify(z3.substitute(term, *pairs) if pairs else term)
            self._values[key] = _numeral(simple)
        return self._values[key]

    def assign(self, statement: ast.Statement, frame: Frame, store: Store) -> Store:
        """The store after an assignment (a command call changes no tracked value)."""
        if not isinstance(statement, ast.Assignment):
            return store
        chain = names_of(statement.target)
        if chain is None:
            return store
        path = resolve(".".join(chain), frame)
        value = self.value(statement.value, frame, store)
        values = dict(store)
        values.pop(path, None)
        if value is not None and _bounded(value):
            values[path] = value
        return tuple(sorted(values.items()))


def _bounded(value: Value) -> bool:
    if isinstance(value, tuple):
        return abs(value[0]) <= LIMIT * value[1]
    return isinstance(value, bool) or abs(value) <= LIMIT


def resolve(path: str, frame: Frame) -> str:
    """A path with an ``Object`` parameter replaced by the scene object it stands for."""
    head, dot, rest = path.partition(".")
    bound = frame.object(head)
    return f"{bound}{dot}{rest}" if bound and dot else path


def _constant(term: z3.ExprRef, value: Value) -> z3.ExprRef:
    if isinstance(value, bool):
        return z3.BoolVal(value)
    if isinstance(value, tuple):
        return z3.Q(*value)
    return z3.IntVal(value) if z3.is_int(term) else z3.RealVal(value)


def _numeral(term: z3.ExprRef) -> Value | None:
    if z3.is_true(term) or z3.is_false(term):
        return z3.is_true(term)
    if z3.is_int_value(term):
        digits = term.as_string()
        return int(digits) if len(digits) <= DIGITS else None
    if z3.is_rational_value(term):
        numerator, denominator = term.numerator().as_string(), term.denominator().as_string()
        if max(len(numerator), len(denominator)) > DIGITS:
            return None
        return _rational(Fraction(int(numerator), int(denominator)))
    return None


def _rational(value: Fraction) -> int | tuple[int, int]:
    """A whole number as an int, any other as (numerator, denominator): configurations are
    hashed often, Fractions slowly."""
    return value.numerator if value.denominator == 1 else (value.numerator, value.denominator)


def fold_value(expression: ast.Expression | None, declared: str) -> Value | None:
    """A constant default as a tracked value; an attribute without default starts at zero."""
    if expression is None:
        return False if declared == "Boolean" else 0
    value = fold(expression)
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        return _rational(Fraction(repr(value)) if "e" not in repr(value) else Fraction(value))
    return None
