"""Questions to the SMT solver about conditions, and witnesses in the model's own units.

Every question is asked under the declared ranges of the variables read. A question the
solver cannot answer in time counts as "may hold", so that no finding rests on a guess.
"""

from __future__ import annotations

import threading
from fractions import Fraction

import z3

from lightrocks.languages.lightrocks.behaviour.terms import Terms
from lightrocks.languages.lightrocks.behaviour.variables import Variable
from lightrocks.metamodel.units import lookup

TIMEOUT_MS = 500
SOLVER_TURN = threading.RLock()
"""z3's terms live in one global context that is not thread-safe: checks running in several
threads (a thread pool, a server) build and solve their terms one at a time."""
MAX_ANSWERS = 50_000
_ANSWERS: dict[tuple[int, ...], tuple[z3.ModelRef | bool, list[z3.BoolRef]]] = {}


class Judge:
    def __init__(self, terms: Terms) -> None:
        self.terms = terms

    def possible(self, *facts: z3.BoolRef) -> z3.ModelRef | bool:
        """A model where all ``facts`` hold, False when none exists, True when unknown.

        Answers are kept by the question: the solver's terms are shared by structure, so a
        guard written a thousand times over the same values is solved once. The question's
        terms are kept with the answer, so their ids are never reused."""
        assertions = [*self.terms.ranges(), *facts]
        key = tuple(sorted(a.get_id() for a in assertions))
        if key in _ANSWERS:
            return _ANSWERS[key][0]
        solver = z3.Solver()
        solver.set("timeout", TIMEOUT_MS)
        solver.add(*assertions)
        answer = solver.check()
        found = solver.model() if answer == z3.sat else answer != z3.unsat
        if len(_ANSWERS) >= MAX_ANSWERS:  # a language server runs for hours: start afresh
            _ANSWERS.clear()
        _ANSWERS[key] = (found, assertions)
        return found

    def never(self, *facts: z3.BoolRef) -> bool:
        """The facts can never hold together (proved)."""
        return self.possible(*facts) is False

    def always(self, fact: z3.BoolRef, *given: z3.BoolRef) -> bool:
        """``fact`` holds whenever ``given`` do (proved)."""
        return self.never(*given, z3.Not(fact))

    def witness(self, model: z3.ModelRef, formula: z3.ExprRef) -> str:
        """The values of the model's variables that ``formula`` reads, as the model reads."""
        names = {str(c) for c in constants(formula)}
        parts = []
        for path, (variable, term) in sorted(self.terms.read.items()):
            if path not in names or variable.kind == "unknown":
                continue
            parts.append(f"{path} = {show(variable, model.evaluate(term, model_completion=True))}")
        return ", ".join(parts)


def show(variable: Variable, value: z3.ExprRef) -> str:
    """A solver value in the unit the variable is declared in (SI symbol otherwise)."""
    if z3.is_true(value) or z3.is_false(value):
        return "true" if z3.is_true(value) else "false"
    if z3.is_int_value(value):
        return str(value.as_long())
    if z3.is_rational_value(value):
        number = float(Fraction(value.numerator_as_long(), value.denominator_as_long()))
    elif z3.is_algebraic_value(value):
        number = float(value.approx(6).as_fraction())
    else:
        return str(value)
    if variable.sort == "Int":
        return f"{number:g}"
    unit = variable.unit
    if not unit:
        return f"{number:g}"
    return f"{number / lookup(unit).factor:g} {unit}"


def constants(formula: z3.ExprRef) -> list[z3.ExprRef]:
    found, seen, pending = [], set(), [formula]
    while pending:
        term = pending.pop()
        if term.get_id() in seen:
            continue
        seen.add(term.get_id())
        if z3.is_const(term) and term.decl().kind() == z3.Z3_OP_UNINTERPRETED:
            found.append(term)
        pending.extend(term.children())
    return found
