"""LightRocks expressions as the Python of python-statemachine's SCXML data model.

python-statemachine 3.x reads SCXML with a Python data model and evaluates ``cond`` and
``expr`` with a restricted evaluator by default: names, literals, ``and``/``or``/``not``,
comparisons, ``+ - * / % **``, unary ``-``/``+`` and ``In('state')`` — no other call, no
conditional expression. So the translation writes each LightRocks construct with those
alone, fully parenthesised, from the AST (never from the model's text):

- ``&&``, ``||``, ``!`` become ``and``, ``or``, ``not``; the other operators are Python's
  with the same meaning (``/`` divides as a Real, ``%`` is floored, as in the runtime);
- numbers are their SI values (``2 mm`` is ``0.002``), whole numbers without unit ``int``;
- ``abs(x)`` is ``x * ((x > 0) - (x < 0))``, ``min(a, b)`` is ``a * (a <= b) + b * (b < a)``
  and ``max(a, b)`` is ``a * (a >= b) + b * (b > a)``: a comparison is a ``bool``, which
  multiplies as 0 or 1, so the type follows the operands as in LightRocks;
- strings in conditions escape every character but letters, digits and spaces (``\\x26``),
  and the letters ``t``, ``f`` and ``n``: python-statemachine unescapes XML entities in a
  condition and rewrites ``true``, ``false``, ``null``, ``&&`` and ``||`` in it, also inside a
  string, so only an escaped string reaches it unchanged.

Anything else (a scene object's attribute, a vector, a device command, a call of
``rotX``…, a language extension's expression) has no counterpart in this data model and is
refused with its position.
"""

from __future__ import annotations

from collections.abc import Mapping

from lightrocks.generators.scxml.names import Names
from lightrocks.metamodel import ast

_OPERATORS = {"&&": "and", "||": "or"}
_ARITHMETIC = {"+", "-", "*", "/", "%"}
_COMPARISON = {"==", "!=", "<", "<=", ">", ">="}


class Untranslatable(Exception):
    """A construct the data model cannot express, at its position."""

    def __init__(self, position: ast.Position, message: str) -> None:
        super().__init__(message)
        self.position = position
        self.message = message


def string(value: str, strict: bool) -> str:
    """A Python string literal of ``value``; ``strict`` for conditions (see the module)."""
    out = []
    for c in value:
        keep = c.isascii() and (c.isalnum() or c == " ") if strict else c.isprintable()
        if strict and c in "tfn":
            keep = False
        if keep and c not in "\\'":
            out.append(c)
        elif ord(c) < 0x100:
            out.append(f"\\x{ord(c):02x}")
        elif ord(c) < 0x10000:
            out.append(f"\\u{ord(c):04x}")
        else:
            out.append(f"\\U{ord(c):08x}")
    return "'" + "".join(out) + "'"


def number(node: ast.Quantity) -> str:
    """The SI value: an ``int`` where LightRocks has an Integer, else the shortest float."""
    if node.integral:
        return str(int(node.value))
    return repr(float(node.value))


class Translator:
    """Expressions of one chart; ``names`` maps its parameters to data-model variables."""

    def __init__(self, names: Names, parameters: Mapping[str, ast.Parameter]) -> None:
        self.names = names
        self.parameters = parameters

    def cond(self, node: ast.Expression, values: Mapping[str, str] | None = None) -> str:
        """A ``cond``; ``values`` replaces parameters by expressions (a guard evaluated after
        exit actions that the SCXML engine runs later)."""
        return self._text(node, values or {}, strict=True)

    def value(self, node: ast.Expression) -> str:
        """An ``expr`` (assigned, or the initial value of a variable)."""
        return self._text(node, {}, strict=False)

    def variable(self, node: ast.Expression) -> str:
        """The ``location`` an assignment writes."""
        if isinstance(node, ast.Name) and node.name in self.parameters:
            return self.names.data(node.name)
        raise Untranslatable(
            node.position, "only a parameter can be assigned in SCXML's data model here"
        )

    def _text(self, node: ast.Expression, values: Mapping[str, str], strict: bool) -> str:
        def text(inner: ast.Expression) -> str:
            return self._text(inner, values, strict)

        match node:
            case ast.Binary(operator=operator, left=left, right=right):
                if operator in _OPERATORS:
                    return f"({text(left)} {_OPERATORS[operator]} {text(right)})"
                if operator in _ARITHMETIC | _COMPARISON:
                    return f"({text(left)} {operator} {text(right)})"
            case ast.Unary(operator="!", operand=operand):
                return f"(not {text(operand)})"
            case ast.Unary(operator=("-" | "+") as sign, operand=operand):
                return f"({sign}{text(operand)})"
            case ast.Quantity():
                return number(node)
            case ast.BooleanLiteral(value=value):
                return "True" if value else "False"
            case ast.StringLiteral(value=value):
                return string(value, strict)
            case ast.Name(name=name) if name in self.parameters:
                return values.get(name) or self.names.data(name)
            case ast.Name(name=name):
                raise Untranslatable(
                    node.position,
                    f"'{name}' is no parameter of the chart: SCXML's data model holds only "
                    "the parameters (a scene object or a device has no counterpart there)",
                )
            case ast.Member():
                raise Untranslatable(
                    node.position,
                    "a member access (a scene object's attribute, a sensor) has no counterpart "
                    "in SCXML's data model: declare the value as a parameter",
                )
            case ast.Call(function=ast.Name(name=name), arguments=arguments):
                return self._call(node, name, arguments, text)
        raise Untranslatable(
            getattr(node, "position", ast.NOWHERE),
            f"{_described(node)} has no counterpart in python-statemachine's restricted "
            "Python data model (numbers, Booleans, strings and their operators)",
        )

    @staticmethod
    def _call(node: ast.Call, name: str, arguments: tuple[ast.Argument, ...], text) -> str:
        positional = [a.value for a in arguments if not a.name]
        if len(positional) != len(arguments):
            raise Untranslatable(node.position, f"'{name}' takes no named arguments here")
        if name == "abs" and len(positional) == 1:
            x = text(positional[0])
            return f"({x} * (({x} > 0) - ({x} < 0)))"
        if name in ("min", "max") and len(positional) == 2:
            a, b = (text(p) for p in positional)
            first, second = ("<=", "<") if name == "min" else (">=", ">")
            return f"(({a} * ({a} {first} {b})) + ({b} * ({b} {second} {a})))"
        raise Untranslatable(
            node.position,
            f"a call of '{name}': python-statemachine's restricted evaluator calls no "
            "function but In(); only abs(x), min(a, b) and max(a, b) are written out as "
            "arithmetic",
        )


def _described(node: object) -> str:
    if isinstance(node, ast.VectorLiteral | ast.Index):
        return "a vector"
    if ast.is_extension(node):
        return f"'{type(node).__name__}' (syntax of a language extension)"
    return f"'{type(node).__name__}'"
