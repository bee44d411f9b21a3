"""Durations of one region judged against zero and against the budget that encloses them.

A time event ``after(d)`` waits ``d``; its duration is the solver term of ``d`` with the
parameters it reads at the values the loaded models give them (their defaults and the
constants bound where the chart is used) and everything else in its declared range. A
duration that is never positive fires at once; one that is never shorter than the
statechart's ``<<timeout>>`` never fires, since the budget ends the chart first. A child
statechart whose own budget is longer than the one of the chart it runs in is cut off by
the outer one before its own can ever be spent.
"""

from __future__ import annotations

from collections.abc import Iterator
from fractions import Fraction

import z3

from lightrocks.languages.lightrocks.behaviour.conditions import Conditions, Finding, start_of
from lightrocks.languages.lightrocks.behaviour.terms import exact
from lightrocks.metamodel import ast


def seconds_text(value: float) -> str:
    """A duration in seconds as a model writes it (``300 ms``, ``2 s``)."""
    if value != 0 and abs(value) < 1:
        return f"{value * 1000:g} ms"
    return f"{value:g} s"


class Durations:
    """The findings about the ``after(...)`` durations of one region (LR0611, LR0612)."""

    def __init__(self, conditions: Conditions) -> None:
        self.conditions = conditions
        self.judge = conditions.judge
        self.budget = conditions.component.time_budget
        self.stereotype = conditions.component.budget

    def findings(self) -> Iterator[Finding]:
        region = self.conditions.region
        file = region.loaded.unit.package_position.file
        for transition in [*region.transitions, *region.internal]:
            delay = transition.delay
            if delay is None or transition.position.file != file:
                continue
            yield from self._delay(delay)

    def _delay(self, delay: ast.Expression) -> Iterator[Finding]:
        term = self.conditions.terms.term(delay)
        if term is None or z3.is_bool(term):
            return
        term = z3.ToReal(term) if z3.is_int(term) else term
        given = self.conditions.parameter_values(term == term)
        if self.judge.always(term <= 0, *given):
            yield Finding(
                "LR0611",
                start_of(delay),
                f"after({_source(delay)}) waits {self._value(term, given)}: a duration is "
                "never positive here, the time event fires at once",
                "wait a positive duration, e.g. after(2 s), or leave on the event meant",
            )
            return
        if self.budget is None or self.budget <= 0 or self.stereotype is None:
            return  # no budget, or one of no time (LR0611)
        if self.judge.always(term >= exact(self.budget), *given):
            yield Finding(
                "LR0612",
                start_of(delay),
                f"after({_source(delay)}) waits {self._value(term, given)}, not less than the "
                f"budget {seconds_text(self.budget)} of the <<timeout>> at "
                f"{self.stereotype.position}: the timeout always ends the chart first, "
                "the transition never fires",
                "wait less than the budget, or raise the <<timeout>>",
            )

    def _value(self, term: z3.ExprRef, given: list[z3.BoolRef]) -> str:
        model = self.judge.possible(*given) if given else self.judge.possible(term == term)
        if isinstance(model, bool):
            return "this duration"
        value = model.evaluate(term, model_completion=True)
        if not z3.is_rational_value(value):
            return "this duration"
        return seconds_text(float(Fraction(value.as_fraction())))


def nested_budgets(conditions: Conditions) -> Iterator[Finding]:
    """Children run by ``<<import>>`` whose own budget is longer than the enclosing one."""
    outer = conditions.component.time_budget
    stereotype = conditions.component.budget
    if outer is None or stereotype is None:
        return
    region = conditions.region
    file = region.loaded.unit.package_position.file
    for info in region.states.values():
        child = info.imported
        inner = child.time_budget if child is not None else None
        if inner is None or inner <= outer or info.state.position.file != file:
            continue
        written = ast.stereotype(info.state.stereotypes, "import")
        yield Finding(
            "LR0612",
            written.position if written is not None else info.state.position,
            f"'{child.qualified_name}' has the budget {seconds_text(inner)}, longer than "
            f"the enclosing budget {seconds_text(outer)} at {stereotype.position}: the "
            "outer timeout ends it first, its own is never spent",
            "shorten the child's <<timeout>>, or raise the enclosing one",
        )


def zero_budget(stereotype: ast.Stereotype, seconds: float | None) -> Finding | None:
    """A ``<<timeout>>`` of no time: every run ends in ``timeout`` at once."""
    if seconds is None or seconds > 0:
        return None
    return Finding(
        "LR0611",
        stereotype.position,
        f"timeout '{stereotype.value}' is no time: every run ends in 'timeout' at once",
        'give the budget a positive duration, e.g. <<timeout="5 s">>',
    )


def _source(expression: ast.Expression) -> str:
    match expression:
        case ast.Quantity():
            return expression.text or f"{expression.value:g} {expression.unit}".strip()
        case ast.Name():
            return expression.name
        case ast.Unary():
            return f"{expression.operator}{_source(expression.operand)}"
    return "…"
