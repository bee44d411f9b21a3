"""Conditions as solver terms: the expression AST translated to z3, never evaluated.

Quantities are reals in SI, Integers integers, Booleans Booleans. What has no exact
counterpart here — frames, vectors, calls other than ``abs``/``min``/``max``, an ``Object``
parameter's attributes — becomes a fresh variable that may take any value: the solver then
judges the condition for every value it could have (a sound over-approximation). Two
mentions of the same value (``robot.tcp.x`` twice) share one variable.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import z3

from lightrocks.languages.lightrocks.access import names_of
from lightrocks.languages.lightrocks.behaviour.scope import Scope
from lightrocks.languages.lightrocks.behaviour.variables import Variable
from lightrocks.metamodel import ast

COMPARISONS = ("<", "<=", ">", ">=")


@dataclass
class Terms:
    """Translates the conditions of one region; remembers the variables they read."""

    scope: Scope
    read: dict[str, tuple[Variable, z3.ExprRef]] = field(default_factory=dict)
    _fresh: int = 0

    def condition(self, expression: ast.Expression) -> z3.BoolRef:
        return self._bool(self.term(expression), expression)

    def term(self, expression: ast.Expression) -> z3.ExprRef | None:
        """The term of ``expression``, or None where it has no translation."""
        match expression:
            case ast.Quantity():
                if expression.integral:
                    return z3.IntVal(int(expression.value))
                return z3.RealVal(exact(expression.value))
            case ast.BooleanLiteral():
                return z3.BoolVal(expression.value)
            case ast.Name() | ast.Member():
                return self._read(expression)
            case ast.Unary():
                return self._unary(expression)
            case ast.Binary():
                return self._binary(expression)
            case ast.Call(function=ast.Name(name=name)) if name in ("abs", "min", "max"):
                return self._function(name, expression)
        return None

    def variable_term(self, variable: Variable) -> z3.ExprRef:
        """The solver constant of a variable, with its range asserted where it is used."""
        key = variable.path
        if key in self.read and self.read[key][0].sort != variable.sort:
            key = f"{variable.path}:{variable.sort}"  # one path read both ways: kept apart
        if key not in self.read:
            make = {"Real": z3.Real, "Int": z3.Int, "Bool": z3.Bool}[variable.sort]
            self.read[key] = (variable, make(key))
        return self.read[key][1]

    def ranges(self) -> list[z3.BoolRef]:
        """The declared ranges of every variable read so far."""
        found = []
        for variable, term in self.read.values():
            if variable.low is not None:
                found.append(term >= exact(variable.low))
            if variable.high is not None:
                found.append(term <= exact(variable.high))
        return found

    # -- parts ----------------------------------------------------------------------------

    def _read(self, expression: ast.Expression) -> z3.ExprRef | None:
        variable = self.scope.variable(expression)
        return None if variable is None else self.variable_term(variable)

    def _unary(self, expression: ast.Unary) -> z3.ExprRef | None:
        operand = self.term(expression.operand)
        if expression.operator == "!":
            return z3.Not(self._bool(operand, expression.operand))
        if operand is None or z3.is_bool(operand):
            return None
        return -operand if expression.operator == "-" else operand

    def _binary(self, expression: ast.Binary) -> z3.ExprRef | None:
        operator = expression.operator
        if operator in ("&&", "||"):
            left = self._bool(self.term(expression.left), expression.left)
            right = self._bool(self.term(expression.right), expression.right)
            return z3.And(left, right) if operator == "&&" else z3.Or(left, right)
        left, right = self._operand(expression.left), self._operand(expression.right)
        if operator in ("==", "!="):
            if left is None or right is None or z3.is_bool(left) != z3.is_bool(right):
                return self._opaque_bool(expression)
            left, right = _common(left, right)
            return left == right if operator == "==" else left != right
        if left is None or right is None or z3.is_bool(left) or z3.is_bool(right):
            return self._opaque_bool(expression) if operator in COMPARISONS else None
        if operator in COMPARISONS:
            left, right = _common(left, right)
            return {"<": left < right, "<=": left <= right, ">": left > right}.get(
                operator, left >= right
            )
        return _arithmetic(operator, left, right)

    def _operand(self, expression: ast.Expression) -> z3.ExprRef | None:
        """A term; a name or member path without translation becomes a real read by path."""
        term = self.term(expression)
        chain = names_of(expression) if term is None else None
        if chain is not None:
            return self.variable_term(Variable(".".join(chain), "Real", kind="unknown"))
        return term

    def _function(self, name: str, call: ast.Call) -> z3.ExprRef | None:
        values = [self.term(a.value) for a in call.arguments]
        if any(v is None or z3.is_bool(v) for v in values):
            return None
        if name == "abs" and len(values) == 1:
            return z3.If(values[0] >= 0, values[0], -values[0])
        if name in ("min", "max") and len(values) == 2:
            left, right = _common(*values)
            smaller = left <= right if name == "min" else left >= right
            return z3.If(smaller, left, right)
        return None

    def _bool(self, term: z3.ExprRef | None, expression: ast.Expression) -> z3.BoolRef:
        if term is not None and z3.is_bool(term):
            return term
        return self._opaque_bool(expression)

    def _opaque_bool(self, expression: ast.Expression) -> z3.BoolRef:
        """A Boolean that may be true or false: shared by mentions of the same path."""
        chain = names_of(expression)
        if chain is not None:
            path = ".".join(chain)
            variable = Variable(path, "Bool", kind="unknown")
            return self.variable_term(variable)
        self._fresh += 1
        return z3.Bool(f"?{self._fresh}")


def _arithmetic(operator: str, left: z3.ExprRef, right: z3.ExprRef) -> z3.ExprRef | None:
    if operator == "/":
        return _real(left) / _real(right)
    if operator == "%":
        return left % right if z3.is_int(left) and z3.is_int(right) else None
    left, right = _common(left, right)
    return {"+": left + right, "-": left - right, "*": left * right}.get(operator)


def _common(left: z3.ExprRef, right: z3.ExprRef) -> tuple[z3.ExprRef, z3.ExprRef]:
    """Both sides as reals when either is one (an Integer widens to a Real)."""
    if z3.is_int(left) and z3.is_real(right):
        return z3.ToReal(left), right
    if z3.is_real(left) and z3.is_int(right):
        return left, z3.ToReal(right)
    return left, right


def _real(term: z3.ExprRef) -> z3.ExprRef:
    return z3.ToReal(term) if z3.is_int(term) else term


def exact(value: float) -> z3.RatNumRef:
    """A float as the exact rational it stands for in decimal (``0.1`` is 1/10)."""
    return z3.RealVal(repr(float(value))) if "e" not in repr(float(value)) else z3.RealVal(value)
