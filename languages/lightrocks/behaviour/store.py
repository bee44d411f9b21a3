"""The values the model checker tracks exactly, and guards decided against them.

Integer, Real and Boolean attributes of scene objects (and parameters) are tracked while
their value is known: a constant default, a constant assigned, a counter incremented. A value
computed from a sensor, or one that outgrows :data:`LIMIT` or :data:`DIGITS`, becomes
unknown: any value. A guard is then decided by the solver with the known values put in and the
unknown ones free, so each branch the real system could take is a branch here (a sound
over-approximation).

A counter (a value computed from itself) is exact within :data:`WINDOW`; past it only its
side is kept (:class:`Beyond`), within its declared range: a loop over a counter of range
0..10⁶ has a window's configurations, not a million. Each step records how it moved such a
counter and which guards that fired bound it (:data:`MOVED`, :data:`BOUNDED`), so that a
cycle through them is judged by whether the counter must leave it (:mod:`.checker`).
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
WINDOW = 1000
"""A counter is exact while its magnitude is at most this."""
FAR = 10**12
"""A counter a guard or its range bounds on one side stays short of this on that side."""
STEP = z3.Q(1, 10**6)
"""The least move that counts as one: a counter that always moves by this is not Zeno."""
MOVED, BOUNDED = "~", "^"
"""Marks a step leaves in the store: ``~path`` how it moved a counter beyond the window
(+1 up, -1 down, 0 otherwise), ``^path`` the side a fired guard or the range bounds it on."""
DIGITS = 40
"""A rational whose numerator or denominator has more digits becomes unknown as well: a
recurrence such as ``r = r + c / r`` doubles them at every step."""


@dataclass(frozen=True)
class Beyond:
    """A number past :data:`WINDOW` on one side (``sign`` +1: above it, -1: below minus it)."""

    sign: int

    def fact(self, term: z3.ExprRef) -> z3.BoolRef:
        return term > WINDOW if self.sign > 0 else term < -WINDOW


Value = int | tuple[int, int] | bool | Beyond
"""A Boolean, an Integer, a rational as (numerator, denominator), or a counter past the
window: hashed fast."""
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
        self._guard_lists: dict[tuple, tuple] = {}  # the guards kept: their ids stay theirs

    def first_enabled(
        self, guards: list[ast.Expression | None], frame: Frame, store: Store
    ) -> list[int | None]:
        """Which of the guards can be the first to hold (index), and whether none can
        (``None``): the choices the real system has."""
        terms, paths, ids = self._guards(guards)
        shown = self._shown(paths, frame, store)
        key = (ids, shown)  # by structure: solved once
        if key in self._answers:
            return self._answers[key]
        found = self._decided(terms, shown) if len(shown) == len(paths) else None
        if found is not None:
            self._answers[key] = found
            return found
        known = [fact(self.terms.read[p][1], v) for p, v in shown]
        found = []
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

    def _guards(self, guards: list[ast.Expression | None]) -> tuple[list, set[str], tuple]:
        """The terms of a list of guards, what they read and their structure, found once."""
        key = tuple(id(g) for g in guards)
        if key not in self._guard_lists:
            terms = [z3.BoolVal(True) if g is None else self._condition(g) for g in guards]
            paths = set().union(*(self._reads(g) for g in guards if g is not None))
            self._guard_lists[key] = (terms, paths, tuple(t.get_id() for t in terms), guards)
        return self._guard_lists[key][:3]

    def _decided(self, terms: list[z3.BoolRef], shown: tuple) -> list[int | None] | None:
        """The first guard that holds, when every value they read is known exactly: the
        terms then fold to true or false without the solver (a counter's thousand values
        are a thousand substitutions, not a thousand solver calls)."""
        if any(isinstance(v, Beyond) for _, v in shown):
            return None
        pairs = [(self.terms.read[p][1], constant(self.terms.read[p][1], v)) for p, v in shown]
        for index, term in enumerate(terms):
            folded = z3.simplify(z3.substitute(term, *pairs) if pairs else term)
            if z3.is_true(folded):
                return [index]
            if not z3.is_false(folded):
                return None
        return [None]

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
        """The value of an expression when every value it reads is known, else None; past
        the window only its side, where a value it reads is past it."""
        term = self._term(expression)
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
            self._values[key] = self._evaluate(term, known)
        return self._values[key]

    def _evaluate(self, term: z3.ExprRef, known: list[tuple[str, Value]]) -> Value | None:
        exact = [(p, v) for p, v in known if not isinstance(v, Beyond)]
        pairs = [(self.terms.read[p][1], constant(self.terms.read[p][1], v)) for p, v in exact]
        simple = z3.simplify(z3.substitute(term, *pairs) if pairs else term)
        far = [v.fact(self.terms.read[p][1]) for p, v in known if isinstance(v, Beyond)]
        if not far:
            return _numeral(simple)
        if z3.is_bool(simple):
            return None
        for side in (Beyond(1), Beyond(-1)):
            if self.judge.always(side.fact(simple), *far):
                return side
        return None

    def _term(self, expression: ast.Expression) -> z3.ExprRef | None:
        if id(expression) not in self._terms:
            self._terms[id(expression)] = self.terms.term(expression)
        return self._terms[id(expression)]

    def assign(self, statement: ast.Statement, frame: Frame, store: Store) -> Store:
        """The store after an assignment (a command call changes no tracked value); a
        counter past the window keeps its side, and the move is marked."""
        if not isinstance(statement, ast.Assignment):
            return store
        chain = names_of(statement.target)
        if chain is None:
            return store
        path = resolve(".".join(chain), frame)
        value = self.value(statement.value, frame, store)
        recurrent = ".".join(chain) in self._reads(statement.value)
        if recurrent and not isinstance(value, bool | Beyond | None) and _sign(value, WINDOW):
            value = Beyond(_sign(value, WINDOW))
        values = dict(store)
        old = values.pop(path, None)
        if isinstance(value, Beyond) or isinstance(old, Beyond):
            move = self._move(statement, frame, store) if recurrent else 0
            values[MOVED + path] = move if values.get(MOVED + path, move) == move else 0
            if isinstance(value, Beyond) and self._ranged(path, value, frame):
                values[BOUNDED + path] = value.sign
        if isinstance(value, Beyond) or (value is not None and _sign(value, LIMIT) == 0):
            values[path] = value
        return tuple(sorted(values.items()))

    def _move(self, statement: ast.Assignment, frame: Frame, store: Store) -> int:
        """+1 where the assignment always raises its target by a step or more, -1 where it
        always lowers it so, else 0."""
        term = self._term(statement.value)
        target = ".".join(names_of(statement.target) or ())
        if term is None or z3.is_bool(term) or target not in self.terms.read:
            return 0
        old = self.terms.read[target][1]
        given = [
            fact(self.terms.read[p][1], v)
            for p, v in self._shown(self._reads(statement.value), frame, store)
        ]
        for sign in (1, -1):
            if self.judge.always(term * sign >= old * sign + STEP, *given):
                return sign
        return 0

    def _ranged(self, path: str, side: Beyond, frame: Frame) -> bool:
        """The declared range bounds the value on the side it went past the window."""
        for read, (_, term) in self.terms.read.items():
            if resolve(read, frame) == path:
                return self.judge.never(term * side.sign > FAR)
        return False

    def bound(self, guard: ast.Expression, frame: Frame, store: Store) -> Store:
        """The store with the counters past the window that ``guard``, as it fired, bounds
        on their side marked."""
        term = self._condition(guard)
        shown = self._shown(self._reads(guard), frame, store)
        far = [(p, v) for p, v in shown if isinstance(v, Beyond)]
        if not far:
            return store
        given = [fact(self.terms.read[p][1], v) for p, v in shown]
        values = dict(store)
        for path, side in far:
            if self.judge.never(term, *given, self.terms.read[path][1] * side.sign > FAR):
                values[BOUNDED + resolve(path, frame)] = side.sign
        return tuple(sorted(values.items()))


def fact(term: z3.ExprRef, value: Value) -> z3.BoolRef:
    """What a known value says of the variable ``term``."""
    if isinstance(value, Beyond):
        return value.fact(term)
    return term == constant(term, value)


def _sign(value: int | tuple[int, int] | bool | Beyond, limit: int) -> int:
    """0 for a value within ``limit``, else the side it is past it on (+1 or -1)."""
    if isinstance(value, Beyond):
        return value.sign
    if isinstance(value, bool):
        return 0
    numerator, denominator = value if isinstance(value, tuple) else (value, 1)
    if abs(numerator) <= limit * denominator:
        return 0
    return 1 if numerator > 0 else -1


def resolve(path: str, frame: Frame) -> str:
    """A path with an ``Object`` parameter replaced by the scene object it stands for."""
    head, dot, rest = path.partition(".")
    bound = frame.object(head)
    return f"{bound}{dot}{rest}" if bound and dot else path


def constant(term: z3.ExprRef, value: Value) -> z3.ExprRef:
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
