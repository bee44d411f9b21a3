"""The value of a constant expression, computed on the AST as every target computes it.

A target that needs a value before anything runs (an initial value on a PLC, a bound checked
by a CoCo) folds the expression here; the text of the model is never evaluated. Numbers are
SI values; Integers stay ``int`` under ``+ - * %`` (``%`` is floored, its sign follows the
divisor) and ``/`` divides as a Real, as in the Python runtime and on the SFC target.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable

from lightrocks.metamodel import ast
from lightrocks.metamodel.printer import expression

Value = bool | int | float | str | tuple
"""A Boolean, an Integer, a Real (SI), a String, or a vector of numbers."""

_ARITHMETIC: dict[str, Callable[[float, float], float]] = {
    "+": operator.add,
    "-": operator.sub,
    "*": operator.mul,
    "/": operator.truediv,
    "%": operator.mod,
}
_COMPARISONS: dict[str, Callable[[float, float], bool]] = {
    "<": operator.lt,
    "<=": operator.le,
    ">": operator.gt,
    ">=": operator.ge,
}
_FUNCTIONS: dict[str, Callable[..., float]] = {"abs": abs, "min": min, "max": max}


def fold(expression: ast.Expression | None) -> Value | None:
    """The value of ``expression``, or None when it is not constant: it reads a name, calls
    something other than abs/min/max, divides by zero, or mixes what does not mix."""
    match expression:
        case ast.Quantity(value=value):
            return int(value) if expression.integral else float(value)
        case ast.BooleanLiteral(value=value) | ast.StringLiteral(value=value):
            return value
        case ast.VectorLiteral(elements=elements):
            parts = tuple(fold(e) for e in elements)
            return parts if all(_is_number(p) for p in parts) else None
        case ast.Unary(operator=sign, operand=operand):
            return _unary(sign, fold(operand))
        case ast.Binary(operator=op, left=left, right=right):
            return _binary(op, fold(left), fold(right))
        case ast.Call(function=ast.Name(name=name), arguments=arguments) if name in _FUNCTIONS:
            values = [fold(a.value) for a in arguments if not a.name]
            if len(values) != len(arguments) or not values or not all(map(_is_number, values)):
                return None
            if name == "abs" and len(values) != 1:
                return None
            return _finite(_FUNCTIONS[name](*values))
    return None


def overflow(expression: ast.Expression | None) -> float | None:
    """What an arithmetic operation on constants computes when that is beyond a Real (``inf``
    or ``nan``; a whole number too large for a Real is ``inf``): its operands fold to finite
    numbers, it does not. ``None`` for anything else (a literal beyond a Real is no
    operation; an operation on such a value, or on names, is not judged here). Every target
    computes the same operation in IEEE doubles, so this is the value it would run with."""
    if not isinstance(expression, ast.Binary) or expression.operator not in ("+", "-", "*", "/"):
        return None
    left, right = fold(expression.left), fold(expression.right)
    if not all(_is_number(v) and _finite(v) is not None for v in (left, right)):
        return None  # not constant, or a literal beyond a Real already (reported as such)
    if expression.operator == "/" and right == 0:
        return None
    try:
        exact = _ARITHMETIC[expression.operator](left, right)
        result = float(exact)
    except OverflowError:  # whole numbers whose result is beyond a Real
        sign = left * right if expression.operator in ("*", "/") else exact
        return math.inf if sign >= 0 else -math.inf
    return None if math.isfinite(result) else result


def beyond_a_real(binary: ast.Binary, value: float) -> str:
    """The finding of an operation on constants whose result no Real holds (its text cut
    short when it is long)."""
    text = expression(binary)
    if len(text) > 60:
        text = text[:57] + "..."
    return (
        f"'{text}' computes {value}: beyond the largest number a Real holds "
        "(about 1.8e308 in SI units)"
    )


def _is_number(value: Value | None) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _finite(value: float) -> Value | None:
    try:
        return value if math.isfinite(value) else None
    except OverflowError:  # a whole number beyond a Real
        return None


def _unary(sign: str, value: Value | None) -> Value | None:
    if sign == "!":
        return (not value) if isinstance(value, bool) else None
    if not _is_number(value):
        return None
    return -value if sign == "-" else value


def _binary(op: str, left: Value | None, right: Value | None) -> Value | None:
    if op in ("&&", "||"):
        if not (isinstance(left, bool) and isinstance(right, bool)):
            return None
        return (left and right) if op == "&&" else (left or right)
    if op in ("==", "!="):
        if left is None or right is None or _is_number(left) != _is_number(right):
            return None
        return (left == right) == (op == "==")
    if not (_is_number(left) and _is_number(right)):
        return None
    if op in _COMPARISONS:
        return _COMPARISONS[op](left, right)
    if op in ("/", "%") and right == 0:
        return None
    return _finite(_ARITHMETIC[op](left, right)) if op in _ARITHMETIC else None
