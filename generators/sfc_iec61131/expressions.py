"""LightRocks expressions compiled to Structured Text: data in, text out, never evaluated.

Integers are DINT, every other quantity is REAL, and IEC 61131-3 converts neither into the
other by itself. Numbers therefore meet as they do at run time: an Integer operand that
meets a REAL one, or that stands where a REAL is declared, becomes REAL (``DINT_TO_REAL``,
or a REAL literal); ``/`` divides as REAL, as Python's true division does; ``%`` is the
floored remainder of Python, whose sign follows the divisor.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass

from lightrocks.languages.domain.types import (
    FRAME,
    NUMBER,
    DeviceT,
    ObjectT,
    QuantityT,
    StructT,
    Type,
    VectorT,
)
from lightrocks.metamodel import ast
from lightrocks.metamodel.constants import Value, fold
from lightrocks.workbench.generators import GenerationError

OPERATORS = {"&&": "AND", "||": "OR", "==": "=", "!=": "<>"}  # "%": see _modulo
ARITHMETIC = ("+", "-", "*", "/", "%")
COMPARISONS = ("==", "!=", "<", "<=", ">", ">=")
FUNCTIONS = {
    "abs": "ABS",
    "min": "MIN",
    "max": "MAX",
    "rotX": "ROT_X",
    "rotY": "ROT_Y",
    "rotZ": "ROT_Z",
    "transl": "TRANSL",
}
FRAME_BUILDERS = ("rotX", "rotY", "rotZ", "transl")  # their arguments are REAL
DINT, REAL = "DINT", "REAL"
DECLARED = {DINT: QuantityT("Integer"), REAL: NUMBER}  # a LightRocks type of each


STRING_LENGTH = 254  # bytes of a STRING without declared length (MatIEC)
ESCAPES = {"$": "$$", "'": "$'", "\n": "$N", "\r": "$R", "\t": "$T", "\f": "$P"}


def string_literal(value: str) -> str:
    """A single-byte IEC 61131-3 STRING: ``$`` escapes, ``$hh`` for any other character
    outside printable ASCII (as UTF-8 bytes), and for the ``(`` of ``(*`` and the ``*`` of
    ``*)``: MatIEC's forward-reference pass (``-p``) reads those as comment delimiters even
    inside a string."""
    parts = []
    for character, following in zip(value, [*value[1:], ""], strict=True):
        if character in ESCAPES:
            parts.append(ESCAPES[character])
        elif (character, following) in (("(", "*"), ("*", ")")):
            parts.append(f"${ord(character):02X}")
        elif " " <= character <= "~":
            parts.append(character)
        else:
            parts.append("".join(f"${byte:02X}" for byte in character.encode("utf-8")))
    return "'" + "".join(parts) + "'"


def outside_strings(text: str) -> Iterator[tuple[int, str]]:
    """Index and character of every character of ST ``text`` outside its string literals
    (``'…'`` and ``"…"``, with ``$`` escapes): what may be structure, never data."""
    quote = ""
    escaped = False
    for index, character in enumerate(text):
        if escaped:
            escaped = False
        elif quote:
            escaped = character == "$"
            quote = "" if character == quote else quote
        elif character in "'\"":
            quote = character
        else:
            yield index, character


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


def number_type(declared: Type | None) -> str | None:
    """DINT for an Integer, REAL for any other quantity, None for what is no number."""
    if isinstance(declared, QuantityT):
        return DINT if declared.name == "Integer" else REAL
    return None


def convert(text: str, have: str | None, want: str | None, position: ast.Position) -> str:
    """``text``, a value of ST type ``have``, as one of ``want``: an Integer widens to REAL;
    a REAL has no place in a DINT (at run time it would keep its fraction)."""
    if want is None or have is None or have == want:
        return text
    if want == REAL:
        return f"DINT_TO_REAL({text})"
    raise GenerationError(
        f"{position}: a Real value where an Integer is declared: "
        "the SFC target keeps Integers as DINT"
    )


def literal(expression: ast.Expression, declared: Type | None = None) -> str | None:
    """The ST text of a constant expression (usable as an initial value), folded as the
    runtime computes it, or None if not constant; a number is written as the ST type of
    ``declared`` when given."""
    return _literal_of(fold(expression), declared, expression.position)


def initial_value(default: ast.Expression | None, declared: Type | None, what: str) -> str:
    """A declaration's initial value: the default folded to a constant ("" without one)."""
    if default is None:
        return ""
    initial = literal(default, declared)
    if initial is None:
        raise GenerationError(
            f"{default.position}: the SFC target needs a constant default for {what}"
        )
    return initial


def _literal_of(value: Value | None, declared: Type | None, position: ast.Position) -> str | None:
    match value:
        case bool():
            return "TRUE" if value else "FALSE"
        case str():
            if len(value.encode("utf-8")) > STRING_LENGTH:
                raise GenerationError(
                    f"{position}: a string of {len(value.encode('utf-8'))} bytes: an IEC 61131-3 "
                    f"STRING holds {STRING_LENGTH} (MatIEC's default length)"
                )
            return string_literal(value)
        case tuple():
            element = _element(declared)
            return "[" + ", ".join(_literal_of(v, element, position) for v in value) + "]"
        case int() | float():
            have = DINT if isinstance(value, int) else REAL
            want = number_type(declared) or have
            if want == DINT and float(value).is_integer():
                return str(int(value))
            if want == REAL:
                return real(value)
            return convert(real(value), have, want, position)
    return None


def _element(declared: Type | None) -> Type | None:
    """The declared type of a vector's elements: that of its ST array (the first one's)."""
    return declared.elements[0] if isinstance(declared, VectorT) and declared.elements else None


def _element_of(vector: ast.Expression, index: int) -> ast.Expression:
    """Element ``index`` of a vector expression: of a literal as written, else indexed."""
    if isinstance(vector, ast.VectorLiteral):
        return vector.elements[index]
    number = ast.Quantity(index, text=str(index), position=vector.position)
    return ast.Index(vector, number, position=vector.position)


@dataclass
class Scope:
    """How names of one LightRocks scope read in ST, and how to type an expression there."""

    names: dict[str, str]
    infer: Callable[[ast.Expression], Type]
    sensor: Callable[[DeviceT, str], str]
    field: Callable[[str], str]
    extension: Callable[[ast.ExtensionNode, Scope], str] | None = None
    """The ST text of an expression a language extension adds (see ``.extensions``)."""

    def compile(self, expression: ast.Expression, declared: Type | None = None) -> str:
        """The ST text of ``expression``; as the ST number type of ``declared`` when given."""
        return self._as(expression, number_type(declared))[0]

    def number(self, expression: ast.Expression) -> str | None:
        """The ST number type of ``expression`` as the compiled text computes it, or None."""
        match expression:
            case ast.Quantity():
                return DINT if expression.integral else REAL
            case ast.Unary(operator="-", operand=operand):
                return self.number(operand)
            case ast.Binary(operator=operator, left=left, right=right) if operator in ARITHMETIC:
                kinds = {self.number(left), self.number(right)}
                if None in kinds:
                    return None
                return REAL if operator == "/" or REAL in kinds else DINT
            case ast.Binary():
                return None
            case ast.Call(function=ast.Name(name="abs" | "min" | "max"), arguments=arguments):
                kinds = {self.number(a.value) for a in arguments}
                return REAL if REAL in kinds else (DINT if kinds == {DINT} else None)
        return number_type(self.infer(expression))

    def _as(self, expression: ast.Expression, want: str | None) -> tuple[str, bool]:
        """The text of ``expression`` as a value of ST type ``want`` (None: as it is), and
        whether that text needs parentheses to be an operand."""
        have = self.number(expression)
        if want is not None and have is not None and have != want:
            constant = literal(expression, DECLARED[want])
            if constant is not None:
                return constant, constant.startswith("-")
            text = self._text(expression)
            return convert(text, have, want, expression.position), False
        text = self._text(expression)
        return text, isinstance(expression, ast.Binary | ast.Unary) or text.startswith("-")

    def _text(self, expression: ast.Expression) -> str:
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
                position = self.compile(index)
                if self.number(index) == REAL:  # Python's int(): toward zero
                    position = f"TRUNC({position})"
                return f"{self.compile(target)}[{position}]"
            case ast.Call(function=ast.Name(name=function), arguments=arguments):
                kinds = {self.number(a.value) for a in arguments}
                want = REAL if function in FRAME_BUILDERS or REAL in kinds else None
                inner = ", ".join(self._as(a.value, want)[0] for a in arguments)
                return f"{FUNCTIONS.get(function, function)}({inner})"
            case ast.Unary(operator=operator, operand=operand):
                text = "NOT " if operator == "!" else operator
                return f"{text}{self._operand(operand)}"
            case ast.Binary(operator="*", left=left, right=right) if self.infer(left) == FRAME:
                return f"FRAME_MUL({self.compile(left)}, {self.compile(right)})"
            case ast.Binary(operator=operator, left=left, right=right):
                return self._binary(operator, left, right)
            case ast.ExtensionNode() if self.extension is not None:
                return self.extension(expression, self)
            case ast.VectorLiteral():
                raise GenerationError(
                    f"{expression.position}: the SFC target writes a vector literal where it "
                    "is assigned, passed or compared: ST has array literals as initial values only"
                )
        raise ValueError(f"cannot compile {type(expression).__name__} to Structured Text")

    def _binary(self, operator: str, left: ast.Expression, right: ast.Expression) -> str:
        """Numbers of both types meet as REAL; ``/`` always divides REALs; vectors are equal
        element by element."""
        if operator in ("==", "!="):
            compared = [self.infer(left), self.infer(right)]
            vectors = [t for t in compared if isinstance(t, VectorT)]
            if vectors:
                return self._equal_vectors(operator, left, right, len(vectors[0].elements))
            if any(t == FRAME or isinstance(t, StructT | ObjectT) for t in compared):
                raise GenerationError(
                    f"{left.position}: the SFC target compares numbers, Booleans, strings and "
                    "vectors, not frames, structures or objects"
                )
        kinds = {self.number(left), self.number(right)}
        numeric = operator in ARITHMETIC + COMPARISONS and None not in kinds
        want = REAL if numeric and (operator == "/" or REAL in kinds) else None
        first, second = self._operand(left, want), self._operand(right, want)
        if operator == "%":
            return _modulo(first, second, want == REAL)
        return f"{first} {OPERATORS.get(operator, operator)} {second}"

    def _equal_vectors(
        self, operator: str, left: ast.Expression, right: ast.Expression, size: int
    ) -> str:
        """``==`` and ``!=`` of two vectors: ST compares no arrays, so element by element."""
        equal = " AND ".join(
            f"({self._binary('==', _element_of(left, i), _element_of(right, i))})"
            for i in range(size)
        )
        return equal if operator == "==" else f"NOT ({equal})"

    def _operand(self, expression: ast.Expression, want: str | None = None) -> str:
        text, loose = self._as(expression, want)
        return f"({text})" if loose else text

    def assign(
        self, target: ast.Expression, value: ast.Expression, declared: Type | None = None
    ) -> list[str]:
        """ST statements for ``target = value`` (``declared``: the target's type when the
        scope does not know it); a vector literal is assigned element-wise."""
        declared = declared or self.infer(target)
        left = self.compile(target)
        if isinstance(value, ast.VectorLiteral):
            return self.elements(left, value, declared)
        return [f"{left} := {self.compile(value, declared)};"]

    def elements(self, target: str, vector: ast.VectorLiteral, declared: Type | None) -> list[str]:
        """``target := vector`` element by element: ST has array literals as initial values
        only."""
        element = _element(declared)
        return [
            f"{target}[{i}] := {self.compile(e, element)};" for i, e in enumerate(vector.elements)
        ]


def _modulo(left: str, right: str, real_operands: bool) -> str:
    """Python's floored remainder from ST's truncated one: ``((a MOD b) + b) MOD b``. ST has
    MOD for integers only; for REALs the truncated remainder is ``a - b * TRUNC(a / b)``."""

    def truncated(a: str) -> str:
        if real_operands:
            return f"{a} - {right} * DINT_TO_REAL(TRUNC({a} / {right}))"
        return f"{a} MOD {right}"

    return truncated(f"({truncated(left)} + {right})")
