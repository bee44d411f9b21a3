"""Guards, start and end conditions of one region, judged by the SMT solver.

Transitions leaving one source are compared on each stimulus they react to, in declaration
order (the first whose guard holds fires): a guard that never holds, one that always holds,
one whose every case an earlier transition takes first (shadowed), and two whose guards
hold together for different effects (overlap, with a witness). An action's end conditions
are a priority list: one that never holds, one that always holds or holds when its command
starts, and one that an earlier one always pre-empts. Parameters may take any value when
something is proved for every case; an overlap is shown only for the values the models give
them (see :mod:`.parameters`).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import z3

from lightrocks.languages.lightrocks.access import access
from lightrocks.languages.lightrocks.behaviour.judge import Judge, show
from lightrocks.languages.lightrocks.behaviour.parameters import ParameterValues
from lightrocks.languages.lightrocks.behaviour.scope import Scope
from lightrocks.languages.lightrocks.behaviour.terms import COMPARISONS, Terms, exact
from lightrocks.languages.lightrocks.model import Component, Region
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast


@dataclass(frozen=True)
class Finding:
    code: str
    position: ast.Position
    message: str
    hint: str = ""


class Conditions:
    """The findings about the conditions of one region written in its component's file."""

    def __init__(
        self, typing: Typing, values: ParameterValues, component: Component, region: Region
    ) -> None:
        self.component = component
        self.region = region
        self.values = values
        self.scope = Scope(typing, region)
        self.terms = Terms(self.scope)
        self.judge = Judge(self.terms)
        self._file = region.loaded.unit.package_position.file
        self._guards: dict[int, z3.BoolRef] = {}

    def findings(self) -> Iterator[Finding]:
        for source, leaving in self._leaving().items():
            yield from self._transitions(source, leaving)
        if self.component.layer == "action" and self.region.parent is None:
            yield from self._ordered(self.region.end_conditions, "end")
        yield from self._ordered(self.region.start_conditions, "start")
        yield from self._equalities()

    # -- transitions ----------------------------------------------------------------------

    def _leaving(self) -> dict[str, list[ast.Transition]]:
        leaving: dict[str, list[ast.Transition]] = {}
        for transition in self.region.transitions:
            leaving.setdefault(transition.source, []).append(transition)
        return leaving

    def keys(self, source: str, transition: ast.Transition) -> list[str]:
        """What a transition reacts to: its stimulus, or every declared outcome of a child
        when it has none (a completion transition), or the delay of a time event."""
        if transition.delay is not None:
            return [f"after@{transition.stimulus_position}"]
        info = self.region.states.get(source)
        outcomes = info.outcomes if info is not None else None
        if transition.stimulus or outcomes is None:
            return [transition.stimulus]
        return list(outcomes)  # a completion takes declared outcomes, never timeout or error

    def _transitions(self, source: str, leaving: list[ast.Transition]) -> Iterator[Finding]:
        candidates: dict[str, list[ast.Transition]] = {}
        if len(leaving) > 1:
            for transition in leaving:
                for key in self.keys(source, transition):
                    candidates.setdefault(key, []).append(transition)
        alone = all(len(c) == 1 for c in candidates.values())
        for transition in leaving:
            if transition.position.file != self._file:
                continue  # inherited through <<extends>>: judged in its own file
            guard = transition.guard
            if guard is not None:
                trivial = alone and self._open(guard)  # may hold, may not: nothing to ask
                verdict = None if trivial else self._judge_alone(guard, "guard")
                if verdict is not None:
                    yield verdict
                    if verdict.code == "LR0601":
                        continue
            if alone:
                continue
            earlier = {
                k: c[: c.index(transition)] for k, c in candidates.items() if transition in c
            }
            hidden = list(self._shadowed(transition, earlier))
            yield from hidden
            if not hidden and source not in self.region.pseudostates:
                yield from self._overlaps(transition, earlier)  # a choice is a priority list

    def _open(self, expression: ast.Expression) -> bool:
        """Decided without the solver: a guard that compares one value without a declared
        range with something that does not read it (or a Boolean read as it is) may hold
        and may not."""
        if isinstance(expression, ast.Unary) and expression.operator == "!":
            return self._open(expression.operand)
        variable = self.scope.variable(expression)
        if variable is not None:
            return variable.sort == "Bool" and variable.start is None
        if not (isinstance(expression, ast.Binary) and expression.operator in COMPARISONS):
            return False
        for side, other in (
            (expression.left, expression.right),
            (expression.right, expression.left),
        ):
            variable = self.scope.variable(side)
            if (
                variable is not None
                and variable.sort != "Bool"
                and variable.low is None
                and variable.high is None
                and not _reads_path(other, variable.path)
            ):
                return True
        return False

    def _judge_alone(self, expression: ast.Expression, what: str) -> Finding | None:
        term = self.guard_term(expression)
        if self.judge.never(term):
            return Finding(
                "LR0601",
                start_of(expression),
                f"this {what} never holds: {_text(self.judge, term)}",
                "the transition never fires; correct the comparison or the range it reads",
            )
        trivial = isinstance(expression, ast.BooleanLiteral)
        if not trivial and self.judge.always(term):
            return Finding(
                "LR0602",
                start_of(expression),
                f"this {what} always holds",
                "drop it, or compare with what was meant",
            )
        return None

    def _at(self, position: ast.Position) -> str:
        """A position in the same file as line:column, elsewhere with its file."""
        if position.file == self._file:
            return f"{position.line}:{position.column}"
        return str(position)

    def guard_term(self, expression: ast.Expression) -> z3.BoolRef:
        key = id(expression)
        if key not in self._guards:
            self._guards[key] = self.terms.condition(expression)
        return self._guards[key]

    def _term(self, transition: ast.Transition) -> z3.BoolRef:
        return z3.BoolVal(True) if transition.guard is None else self.guard_term(transition.guard)

    def _shadowed(
        self, transition: ast.Transition, earlier: dict[str, list[ast.Transition]]
    ) -> Iterator[Finding]:
        if transition.guard is None and any(
            t.guard is None for before in earlier.values() for t in before
        ):
            return  # an unguarded duplicate: LR0211 reports it
        own = self._term(transition)
        takers: list[ast.Transition] = []
        for before in earlier.values():
            if not before:
                return
            covered = z3.Or(*(self._term(t) for t in before))
            if not self.judge.never(own, z3.Not(covered)):
                return
            takers += [t for t in before if t not in takers]
        where = ", ".join(self._at(t.position) for t in takers)
        yield Finding(
            "LR0604",
            start_of(transition.guard) if transition.guard else transition.position,
            f"never fires: the transition{'s' if len(takers) > 1 else ''} at {where} "
            f"take{'' if len(takers) > 1 else 's'} every case it would take, first",
            "order it before them, or narrow their guards",
        )

    def _overlaps(
        self, transition: ast.Transition, earlier: dict[str, list[ast.Transition]]
    ) -> Iterator[Finding]:
        if transition.guard is None:
            return  # the last, unguarded branch takes what the others leave: an else
        seen: set[int] = set()
        for key, before in earlier.items():
            for other in before:
                if other.guard is None or id(other) in seen or _same_effect(other, transition):
                    continue
                seen.add(id(other))
                both = z3.And(self._term(other), self._term(transition))
                model = self.judge.possible(both, *self.parameter_values(both))
                if isinstance(model, bool):
                    continue
                stimulus = f" on '{key}'" if key and not key.startswith("after@") else ""
                yield Finding(
                    "LR0605",
                    start_of(transition.guard),
                    f"overlaps the transition at {self._at(other.position)}{stimulus}: "
                    f"both guards hold when {self.judge.witness(model, both) or 'any value'}; "
                    "the earlier one fires",
                    "make the guards exclude each other",
                )

    def parameter_values(self, formula: z3.BoolRef) -> list[z3.BoolRef]:
        """The values the models give the component's parameters read by ``formula``."""
        facts = []
        own = self.component.region.parameters
        for path, (variable, term) in self.terms.read.items():
            if variable.kind != "parameter" or path not in own or not _reads(formula, path):
                continue
            values = self.values.of(self.component, path)
            if values is None:
                continue
            options = [
                term == (z3.BoolVal(v) if isinstance(v, bool) else _value(term, v)) for v in values
            ]
            facts.append(z3.Or(*options) if options else z3.BoolVal(False))
        return facts

    # -- start and end conditions ---------------------------------------------------------

    def _ordered(self, conditions: list[ast.Condition], kind: str) -> Iterator[Finding]:
        judged: list[ast.Condition] = []
        for condition in conditions:
            expression = condition.expression
            if expression is None:
                continue
            own = condition.position.file == self._file
            term = self.guard_term(expression)
            if own and self.judge.never(term):
                yield Finding(
                    "LR0601",
                    start_of(expression),
                    f"{kind} condition '{condition.name}' never holds: {_text(self.judge, term)}",
                    "correct the comparison or the range it reads",
                )
                continue
            if own and kind == "end":
                yield from self._at_once(condition, term)
            if own and judged:
                covered = z3.Or(*(self.guard_term(c.expression) for c in judged))
                if self.judge.never(term, z3.Not(covered)):
                    takers = [
                        c
                        for c in judged
                        if not self.judge.never(term, self.guard_term(c.expression))
                    ]
                    names = " or ".join(f"'{c.name}'" for c in takers or judged)
                    yield Finding(
                        "LR0604",
                        start_of(expression),
                        f"{kind} condition '{condition.name}' is never the one that holds "
                        f"first: whenever it holds, {names} holds too",
                        "declare it before them, or narrow them",
                    )
            judged.append(condition)

    def _at_once(self, condition: ast.Condition, term: z3.BoolRef) -> Iterator[Finding]:
        if self.judge.always(term):
            yield Finding(
                "LR0602",
                start_of(condition.expression),
                f"end condition '{condition.name}' always holds: the command ends as soon "
                "as it starts",
                "compare with what was meant",
            )
            return
        start = self._start_values(term)
        if start and self.judge.always(term, *start, *self.parameter_values(term)):
            yield Finding(
                "LR0603",
                start_of(condition.expression),
                f"end condition '{condition.name}' already holds when the command starts "
                f"({_start_text(self, term)}): the command ends at once",
                "compare with the value the sensor reaches, mind the sign",
            )

    def implied_by_start(self) -> Iterator[Finding]:
        """End conditions of an action that its start conditions imply (LR0613): whenever
        the command may start, it ends at once."""
        starts = [c.expression for c in self.region.start_conditions if c.expression]
        if not starts or self.component.layer != "action" or self.region.parent is not None:
            return
        given = [self.guard_term(e) for e in starts]
        if self.judge.never(*given):
            return  # start conditions that never hold: LR0601
        for condition in self.region.end_conditions:
            expression = condition.expression
            if expression is None or condition.position.file != self._file:
                continue
            term = self.guard_term(expression)
            if self.judge.always(term) or self.judge.never(term):
                continue  # LR0601, LR0602
            facts = self.parameter_values(z3.And(term, *given))
            if self.judge.always(term, *given, *facts):
                names = ", ".join(f"'{c.name}'" for c in self.region.start_conditions)
                yield Finding(
                    "LR0613",
                    start_of(expression),
                    f"end condition '{condition.name}' holds whenever the start condition "
                    f"{names} does: the command ends as soon as it starts",
                    "end on what the command changes, not on what must hold before it",
                )

    def _start_values(self, term: z3.BoolRef) -> list[z3.BoolRef]:
        """What the commanded device's sensors read when its command starts."""
        instance = commanded_instance(self.region)
        facts = []
        for path, (variable, constant) in self.terms.read.items():
            if (
                variable.kind == "sensor"
                and variable.start is not None
                and path.startswith(f"{instance}.")
                and _reads(term, path)
            ):
                value = variable.start
                start = z3.BoolVal(value) if isinstance(value, bool) else _value(constant, value)
                facts.append(constant == start)
        return facts

    # -- equality on measured values ------------------------------------------------------

    def _equalities(self) -> Iterator[Finding]:
        expressions = [t.guard for t in self.region.transitions if t.guard is not None]
        expressions += [c.expression for c in self.region.conditions.values() if c.expression]
        for expression in expressions:
            if expression.position.file != self._file:
                continue
            for node in _equalities(expression):
                if node.operator in ("==", "!="):
                    measured = self._measured(node)
                    if measured:
                        yield Finding(
                            "LR0606",
                            start_of(node),
                            f"'{node.operator}' on the measured value {measured}: a sensor "
                            "reading is almost never exactly equal to a number",
                            f"compare with a tolerance, e.g. abs({measured} - value) < tolerance",
                        )

    def _measured(self, binary: ast.Binary) -> str:
        for node in ast.walk((binary.left, binary.right)):
            if isinstance(node, ast.Name | ast.Member):
                variable = self.scope.variable(node)
                if variable is not None and variable.measured:
                    return variable.path
        return ""


def commanded_instance(region: Region) -> str:
    """The device instance an action's ``do`` command calls ('' when there is none)."""
    for action in region.actions:
        for statement in action.statements if action.kind == "do" else ():
            call = statement.value if isinstance(statement, ast.Assignment) else None
            call = call or getattr(statement, "expression", None)
            function = getattr(call, "function", None)
            if isinstance(function, ast.Member) and isinstance(function.target, ast.Name):
                return function.target.name
    return ""


def start_of(expression: ast.Expression) -> ast.Position:
    """Where an expression's text begins (a member access is positioned at its dot)."""
    while True:
        match expression:
            case ast.Member(target=inner) | ast.Index(target=inner) | ast.Binary(left=inner):
                expression = inner
            case ast.Call(function=inner):
                expression = inner
            case _:
                return expression.position


def _equalities(expression: ast.Expression) -> list[ast.Binary]:
    """The binary operations of a condition, through operators and call arguments only
    (a generic walk over every node costs a hundredfold on large models)."""
    found = []
    pending = [expression]
    while pending:
        node = pending.pop()
        if isinstance(node, ast.Binary):
            found.append(node)
            pending += [node.left, node.right]
        elif isinstance(node, ast.Unary):
            pending.append(node.operand)
        elif isinstance(node, ast.Call):
            pending += [a.value for a in node.arguments]
    return found


def _same_effect(one: ast.Transition, other: ast.Transition) -> bool:
    return (one.target, one.target_history, one.action) == (
        other.target,
        other.target_history,
        other.action,
    )


def _reads_path(expression: ast.Expression, path: str) -> bool:
    """Whether an expression reads ``path``, a part of it, or something inside it."""
    return any(
        read == path or path.startswith(f"{read}.") or read.startswith(f"{path}.")
        for read in access(expression).reads
    )


def _reads(formula: z3.ExprRef, path: str) -> bool:
    pending, seen = [formula], set()
    while pending:
        term = pending.pop()
        if term.get_id() in seen:
            continue
        seen.add(term.get_id())
        if z3.is_const(term) and str(term) == path:
            return True
        pending.extend(term.children())
    return False


def _value(term: z3.ExprRef, value: float) -> z3.ExprRef:
    return z3.IntVal(int(value)) if z3.is_int(term) else exact(value)


def _text(judge: Judge, term: z3.BoolRef) -> str:
    ranged = [
        f"{v.path} in {_bound(v, v.low)} .. {_bound(v, v.high)}"
        for v, _ in judge.terms.read.values()
        if (v.low is not None or v.high is not None) and _reads(term, v.path)
    ]
    return "no value satisfies it" + (f" ({', '.join(ranged)})" if ranged else "")


def _bound(variable: object, value: float | None) -> str:
    return "" if value is None else show(variable, exact(value))


def _start_text(conditions: Conditions, term: z3.BoolRef) -> str:
    parts = []
    for path, (variable, _) in conditions.terms.read.items():
        if variable.start is not None and _reads(term, path):
            value = variable.start
            shown = str(value).lower() if isinstance(value, bool) else _bound(variable, value)
            parts.append(f"{path} = {shown}")
    return ", ".join(parts)
