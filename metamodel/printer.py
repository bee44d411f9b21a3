"""Pretty printing shared by the languages: expressions, statements, blocks and a line writer.

Printing is the inverse of parsing: for every AST the parser can produce, parsing the printed
text gives an equal AST. Expressions get the fewest parentheses the PRECEDENCE table of the
converter allows (operators are left-associative). :class:`Writer` lays out lines with
two-space indentation and canonical blank lines, and re-attaches the comments of the source.

Comment attachment (textX drops comments; :mod:`metamodel.comments` finds them again): the
printers visit the elements in source order and tell the writer where each one starts
(:meth:`Writer.item`) and where each block ends (:meth:`Writer.close`). Before an element,
the writer emits every comment that precedes it in the source, in source order:

* a comment after code on its line is appended to the last printed line, when that line
  came from the comment's source line or an earlier one (a trailing comment stays trailing,
  also when it trailed a later line of an element that spans several lines);
* any other comment goes on a line of its own, indented like the element that follows it,
  or like the elements of the block when it stands before a closing brace or at file end.

So no comment is ever dropped and their order never changes. A comment on a line of its own
inside an element (say, between two arguments) ends up on its own line after that element.
"""

from __future__ import annotations

import math
import re
import sys
from collections import deque
from collections.abc import Sequence

from lightrocks.metamodel import ast
from lightrocks.metamodel.comments import Comment, Comments
from lightrocks.metamodel.convert import PRECEDENCE
from lightrocks.metamodel.units import UnitError, lookup

LINE_WIDTH = 100
INDENT = "  "
_ATOM = max(PRECEDENCE.values()) + 1  # binds tighter than every binary operator

# --- expressions -------------------------------------------------------------------------


def expression(node: ast.Expression) -> str:
    """The text of an expression with minimal parentheses."""
    match node:
        case ast.Binary(operator=operator, left=left, right=right):
            level = PRECEDENCE[operator]
            left_text = _wrapped(left, _precedence(left) < level)
            right_text = _wrapped(right, _precedence(right) <= level)
            return f"{left_text} {operator} {right_text}"
        case ast.Unary(operator=operator, operand=operand):
            text = expression(operand)
            # the grammar allows one unary operator before a postfix expression only
            return operator + _parenthesized(text, _precedence(operand) < _ATOM or text[0] == "-")
        case ast.Quantity():
            return quantity(node)
        case ast.BooleanLiteral(value=value):
            return "true" if value else "false"
        case ast.StringLiteral(value=value):
            return string(value)
        case ast.VectorLiteral(elements=elements):
            return "[" + ", ".join(expression(e) for e in elements) + "]"
        case ast.Name(name=name):
            return name
        case ast.Member(target=target, name=name):
            return f"{_postfix_target(target)}.{name}"
        case ast.Call(function=function, arguments=args):
            return f"{_postfix_target(function)}({', '.join(arguments(args))})"
        case ast.Index(target=target, index=index):
            return f"{_postfix_target(target)}[{expression(index)}]"
    if isinstance(node, ast.ExtensionNode):
        return node.text(expression)
    raise TypeError(f"not an expression: {node!r}")


def _precedence(node: ast.Expression) -> int:
    if isinstance(node, ast.Binary):
        return PRECEDENCE[node.operator]
    return _ATOM - 1 if isinstance(node, ast.Unary) else _ATOM


def _parenthesized(text: str, needed: bool) -> str:
    return f"({text})" if needed else text


def _wrapped(node: ast.Expression, needed: bool) -> str:
    return _parenthesized(expression(node), needed)


def _postfix_target(node: ast.Expression) -> str:
    """A member, call or index target; literals with a number or operator get parentheses."""
    return _wrapped(node, isinstance(node, ast.Binary | ast.Unary | ast.Quantity))


def arguments(args: Sequence[ast.Argument]) -> list[str]:
    """Each argument as ``name = value`` or, when positional, ``value``."""
    return [f"{a.name} = {expression(a.value)}" if a.name else expression(a.value) for a in args]


def argument_parts(args: Sequence[ast.Argument]) -> list[list[str]]:
    """Each argument split before the operators of its top level, for :func:`fit`."""
    result = []
    for argument in args:
        parts = expression_parts(argument.value)
        if argument.name:
            parts[0] = f"{argument.name} = {parts[0]}"
        result.append(parts)
    return result


def expression_parts(node: ast.Expression) -> list[str]:
    """The text of ``node`` split before each operator of its top precedence level."""
    if not isinstance(node, ast.Binary):
        return [expression(node)]
    level = PRECEDENCE[node.operator]
    if _precedence(node.left) == level:
        left = expression_parts(node.left)
    else:
        left = [_wrapped(node.left, _precedence(node.left) < level)]
    return [*left, f"{node.operator} {_wrapped(node.right, _precedence(node.right) <= level)}"]


def quantity(node: ast.Quantity) -> str:
    """The literal as written when known, else the SI value converted back to its unit."""
    if node.text:
        return node.text
    number = _number(node.value, node.unit)
    return f"{number} {node.unit}" if node.unit else number


def _number(value: float, unit: str) -> str:
    """The shortest decimal that the converter turns back into exactly ``value`` (in SI)."""
    try:
        factor = lookup(unit).factor
    except UnitError:
        factor = 1.0  # the converter keeps the number as it is for unknown units
    guess = value / factor
    candidates = [guess]
    for direction in (math.inf, -math.inf):
        step = guess
        for _ in range(4):
            step = math.nextafter(step, direction)
            candidates.append(step)
    exact = [c for c in candidates if float(repr(c)) * factor == value] or [guess]
    text = min((repr(c) for c in exact), key=len)
    return text.removesuffix(".0")


def string(value: str) -> str:
    """A double-quoted literal that textX reads back as ``value``.

    textX only turns ``\\"`` into ``"`` and then ``\\'`` into ``'``; backslashes are never
    unescaped. So every ``"`` gets a backslash, and a ``'`` after a backslash gets another
    one. A value ending in a backslash cannot be written in this grammar at all.
    """
    return '"' + re.sub(r"\\'", r"\\\\'", value).replace('"', '\\"') + '"'


def stereotypes(items: Sequence[ast.Stereotype]) -> str:
    """``<<a, b="x">>``, or the empty string when there are none."""
    if not items:
        return ""
    texts = [s.name if s.value is None else f"{s.name}={string(s.value)}" for s in items]
    return f"<<{', '.join(texts)}>>"


def parameter(node: ast.Parameter) -> str:
    """``Type name = default;`` of a statechart parameter or a scene object attribute."""
    default = f" = {expression(node.default)}" if node.default is not None else ""
    return f"{node.type} {node.name}{default};"


# --- statements and line breaking --------------------------------------------------------


def fit(head: str, items: Sequence[str | Sequence[str]], tail: str, width: int) -> list[str]:
    """``head`` + items + ``tail`` on one line, or one item per line aligned after ``head``.

    An item given as parts (``["goal = a", "* b", "* c"]``) that is still too long on its
    own line continues with as many parts per line as fit, two columns deeper.
    """
    pieces = [[item] if isinstance(item, str) else list(item) for item in items]
    line = head + ", ".join(" ".join(parts) for parts in pieces) + tail
    if len(line) <= width or not pieces:
        return [line]
    hanging = " " * len(head)
    lines = []
    for index, parts in enumerate(pieces):
        start = head if index == 0 else hanging
        end = tail if index == len(pieces) - 1 else ","
        current = start + parts[0]
        for number, part in enumerate(parts[1:], 2):
            last = end if number == len(parts) else ""
            if len(f"{current} {part}{last}") <= width:
                current += f" {part}"
            else:
                lines.append(current)
                current = f"{hanging}  {part}"
        lines.append(current + end)
    return lines


def statement(node: ast.Statement, prefix: str = "", width: int = LINE_WIDTH) -> list[str]:
    """A statement after ``prefix``; the arguments of a call at its top break when too long."""
    if isinstance(node, ast.ExtensionNode):
        return [f"{prefix}{node.text(expression)}"]
    if isinstance(node, ast.Assignment):
        prefix += f"{expression(node.target)} = "
        value = node.value
    else:
        value = node.expression
    if isinstance(value, ast.Call):
        head = f"{prefix}{_postfix_target(value.function)}("
        return fit(head, argument_parts(value.arguments), ");", width)
    return [f"{prefix}{expression(value)};"]


def block(
    writer: Writer,
    head: str,
    statements: Sequence[ast.Statement],
    position: ast.Position,
    tail: str = "",
) -> None:
    """``head { s; } tail`` on one line for one statement, else one statement per line."""
    inner = "".join(f" {statement(s, width=sys.maxsize)[0]}" for s in statements)
    one_line = f"{head} {{{inner} }}{tail}"
    short = len(statements) <= 1 and len(one_line) <= writer.width
    if short and not writer.comments_within(position):
        writer.line([one_line], position.line)
        return
    writer.open([f"{head} {{"], position.line)
    for node in statements:
        writer.item(node.position, "statement")
        writer.line(statement(node, width=writer.width), node.position.line)
    writer.close(position, tail)


# --- layout ------------------------------------------------------------------------------


class Writer:
    """Printed lines with indentation, canonical blank lines and the source's comments."""

    def __init__(self, comments: Comments | None = None) -> None:
        self._source = comments
        self._pending: deque[Comment] = deque(comments.comments if comments else ())
        self._lines: list[str] = []
        self._origins: list[int] = []  # the source line each printed line came from, or 0
        self._code_widths: dict[int, int] = {}  # line index -> width before its trailing comment
        self._depth = 0
        self._fresh = True  # nothing printed yet in the current block
        self._previous: list[tuple[str, bool] | None] = [None]  # last sibling per depth

    @property
    def width(self) -> int:
        """Characters left on a line at the current indentation."""
        return LINE_WIDTH - len(INDENT) * self._depth

    def item(self, position: ast.Position, kind: str, spaced: bool = False) -> None:
        """Start an element: comments before it, then a blank line between groups.

        Siblings of different kinds are separated by a blank line, a ``spaced`` element
        (one that spans several lines) by one on each side, and a blank line of the source
        between siblings is kept.
        """
        previous = self._previous[-1]
        separate = previous is not None and (previous != (kind, spaced) or spaced)
        self._previous[-1] = (kind, spaced)
        separate = self._comments_before((position.line, position.column), separate)
        if separate or self._source_blank_before(position.line):
            self._blank()

    def line(self, texts: Sequence[str], origin: int) -> None:
        """Print lines of one element that starts on source line ``origin``."""
        for text in texts:
            self._emit(text, origin)

    def open(self, texts: Sequence[str], origin: int) -> None:
        """Print the head of a block, ending in ``{``, and indent what follows."""
        self.line(texts, origin)
        self._depth += 1
        self._fresh = True
        self._previous.append(None)

    def close(self, position: ast.Position, tail: str = "") -> None:
        """End the block opened for the element at ``position`` with ``}`` and ``tail``."""
        brace = self._source.closing_brace(position) if self._source else (0, 0)
        self._comments_before(brace, separate=False)
        self._depth -= 1
        self._previous.pop()
        self._emit("}" + tail, brace[0])

    def comments_within(self, position: ast.Position) -> bool:
        """Whether a comment lies between ``position`` and the end of the block it opens."""
        if not self._source or not self._pending:
            return False
        return self._pending[0].start < self._source.closing_brace(position)

    def finish(self) -> str:
        """The printed text with the comments at the end of the file."""
        self._comments_before((math.inf, math.inf), separate=False)
        self._align_trailing_comments()
        return "\n".join(self._lines) + "\n"

    def _align_trailing_comments(self) -> None:
        """Start the trailing comments of adjacent lines in one column, as people do."""
        run: list[int] = []
        for index in [*sorted(self._code_widths), -1]:
            if run and index != run[-1] + 1:
                column = max(self._code_widths[i] for i in run)
                for i in run:
                    code = self._code_widths[i]
                    self._lines[i] = (
                        self._lines[i][:code] + " " * (column - code) + self._lines[i][code:]
                    )
                run = []
            run.append(index)

    def _comments_before(self, limit: tuple[float, float], separate: bool) -> bool:
        """Print the comments before ``limit``; whether the blank of ``separate`` is still due."""
        while self._pending and self._pending[0].start < limit:
            comment = self._pending.popleft()
            if not comment.own_line and 0 < self._last_origin() <= comment.line:
                self._code_widths.setdefault(len(self._lines) - 1, len(self._lines[-1]))
                self._lines[-1] += " " + comment.text
                continue
            if separate or self._source_blank_before(comment.line):
                self._blank()
            separate = False
            self._emit(comment.text, comment.end_line)
        return separate

    def _last_origin(self) -> int:
        return self._origins[-1] if self._origins else 0

    def _source_blank_before(self, line: int) -> bool:
        """Whether the source has a blank line right before ``line``, after what is printed."""
        last = self._last_origin()
        return bool(self._source) and line - 1 > last and self._source.blank(line - 1)

    def _blank(self) -> None:
        if not self._fresh and self._lines[-1]:
            self._lines.append("")
            self._origins.append(0)

    def _emit(self, text: str, origin: int) -> None:
        self._lines.append(INDENT * self._depth + text)
        self._origins.append(origin)
        self._fresh = False


def header(writer: Writer, unit: ast.StatechartUnit | ast.DomainUnit) -> None:
    """Print the ``package`` and ``import`` lines that open every model file."""
    if unit.package:
        writer.item(unit.package_position, "package")
        writer.line([f"package {unit.package};"], unit.package_position.line)
    for node in unit.imports:
        writer.item(node.position, "import")
        writer.line([f"import {node.name}{'.*' if node.wildcard else ''};"], node.position.line)
