"""LightRocks expressions compiled to Structured Text: data in, text out, never evaluated."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from lightrocks.languages.domain.types import FRAME, DeviceT, Type
from lightrocks.metamodel import ast

OPERATORS = {"&&": "AND", "||": "OR", "==": "=", "!=": "<>", "%": "MOD"}
FUNCTIONS = {
    "abs": "ABS",
    "min": "MIN",
    "max": "MAX",
    "rotX": "ROT_X",
    "rotY": "ROT_Y",
    "rotZ": "ROT_Z",
    "transl": "TRANSL",
}


ESCAPES = {"$": "$$", "'": "$'", "\n": "$N", "\r": "$R", "\t": "$T", "\f": "$P"}


def string_literal(value: str) -> str:
    """A single-byte IEC 61131-3 STRING: ``$`` escapes, ``$hh`` for any other character
    outside printable ASCII (as UTF-8 bytes)."""
    parts = []
    for character in value:
        if character in ESCAPES:
            parts.append(ESCAPES[character])
        elif " " <= character <= "~":
            parts.append(character)
        else:
            parts.append("".join(f"${byte:02X}" for byte in character.encode("utf-8")))
    return "'" + "".join(parts) + "'"


def real(value: float) -> str:
    """An ST REAL literal: always with a point, exponent as ``E``."""
    text = repr(float(value))
    if "e" in text:
        mantissa, exponent = text.split("e")
        mantissa = mantissa if "." in mantissa else f"{mantissa}.0"
        return f"{mantissa}E{int(exponent)}"
    return text


def time_literal(seconds: float) -> str:
    """``T#30s`` or ``T#500ms``."""
    milliseconds = round(seconds * 1000)
    if milliseconds % 1000 == 0:
        return f"T#{milliseconds // 1000}s"
    return f"T#{milliseconds}ms"


def literal(expression: ast.Expression) -> str | None:
    """The ST text of a constant (usable as an initial value), or None if not constant."""
    match expression:
        case ast.Quantity(value=value, unit=unit, text=text):
            if not unit and float(value).is_integer() and "." not in text:
                return str(int(value))
            return real(value)
        case ast.BooleanLiteral(value=value):
            return "TRUE" if value else "FALSE"
        case ast.StringLiteral(value=value):
            return string_literal(value)
        case ast.Unary(operator="-", operand=operand):
            inner = literal(operand)
            return None if inner is None else (inner[1:] if inner[0] == "-" else f"-{inner}")
        case ast.VectorLiteral(elements=elements):
            parts = [literal(e) for e in elements]
            return None if None in parts else "[" + ", ".join(parts) + "]"
    return None


@dataclass
class Scope:
    """How names of one LightRocks scope read in ST, and how to type an expression there."""

    names: dict[str, str]
    infer: Callable[[ast.Expression], Type]
    sensor: Callable[[DeviceT, str], str]
    field: Callable[[str], str]

    def compile(self, expression: ast.Expression) -> str:
        constant = literal(expression)
        if constant is not None and not isinstance(expression, ast.VectorLiteral):
            return constant
        match expression:
            case ast.Name(name=name):
                return self.names.get(name, name)
            case ast.Member(target=target, name=name):
                owner = self.infer(target)
                member = self.sensor(owner, name) if isinstance(owner, DeviceT) else None
                return f"{self.compile(target)}.{member or self.field(name)}"
            case ast.Index(target=target, index=index):
                return f"{self.compile(target)}[{self.compile(index)}]"
            case ast.Call(function=ast.Name(name=function), arguments=arguments):
                inner = ", ".join(self.compile(a.value) for a in arguments)
                return f"{FUNCTIONS.get(function, function)}({inner})"
            case ast.Unary(operator=operator, operand=operand):
                text = "NOT " if operator == "!" else operator
                return f"{text}{self._operand(operand)}"
            case ast.Binary(operator="*", left=left, right=right) if self.infer(left) == FRAME:
                return f"FRAME_MUL({self.compile(left)}, {self.compile(right)})"
            case ast.Binary(operator=operator, left=left, right=right):
                symbol = OPERATORS.get(operator, operator)
                return f"{self._operand(left)} {symbol} {self._operand(right)}"
        raise ValueError(f"cannot compile {type(expression).__name__} to Structured Text")

    def _operand(self, expression: ast.Expression) -> str:
        text = self.compile(expression)
        return f"({text})" if isinstance(expression, ast.Binary | ast.Unary) else text

    def assign(self, target: ast.Expression, value: ast.Expression) -> list[str]:
        """ST statements for ``target = value``; a vector literal is assigned element-wise."""
        left = self.compile(target)
        if isinstance(value, ast.VectorLiteral):
            return [f"{left}[{i}] := {self.compile(e)};" for i, e in enumerate(value.elements)]
        return [f"{left} := {self.compile(value)};"]
