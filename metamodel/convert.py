"""Conversion of textX parse trees into the AST of :mod:`metamodel.ast`.

Each grammar rule ``R`` is handled by a method ``rule_R``; a language subclasses
:class:`Converter` to add the rules of its own fragment, and the rules of grammar extensions
come as functions ``(converter, node) -> AST node`` in ``extension_rules``. Positions come
from the character offsets textX records, turned into line and column by
:class:`metamodel.lines.Lines`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.lines import Lines
from lightrocks.metamodel.units import UnitError, lookup

SHORT = 256
"""A node no longer than this many characters (most are) has its end found by looking for a
line break in it, not by counting lines."""


class Converter:
    def __init__(
        self,
        text: str,
        file: str,
        extension_rules: Mapping[str, Callable[[Converter, Any], Any]] | None = None,
    ) -> None:
        self.file = file
        self.extension_rules = extension_rules or {}
        self._lines = Lines(text)

    # -- infrastructure -------------------------------------------------------------------

    def position(self, node: Any) -> ast.Position:
        """Where ``node`` starts and ends (the parse tree's offsets as lines and columns)."""
        start = getattr(node, "_tx_position", 0)
        line, column = self._lines.line_column(start)
        end = getattr(node, "_tx_position_end", None)
        if end is None:
            return ast.Position(self.file, line, column)
        if end - start <= SHORT and self._lines.text.find("\n", start, end) < 0:
            return ast.Position(self.file, line, column, line, column + end - start)
        return ast.Position(self.file, line, column, *self._lines.line_column(end))

    def convert(self, node: Any) -> Any:
        rule = type(node).__name__
        method = getattr(self, f"rule_{rule}", None)
        if method is None:
            return self.extension_rules[rule](self, node)
        return method(node)

    def optional(self, node: Any) -> Any:
        return None if node is None or node == "" else self.convert(node)

    def many(self, nodes: list[Any]) -> tuple[Any, ...]:
        return tuple(self.convert(n) for n in nodes)

    # -- common ---------------------------------------------------------------------------

    def stereotypes(self, node: Any) -> tuple[ast.Stereotype, ...]:
        if not node:
            return ()
        return tuple(
            ast.Stereotype(item.name, item.value if item.value != "" else None, self.position(item))
            for item in node.items
        )

    def imports(self, nodes: list[Any]) -> tuple[ast.Import, ...]:
        return tuple(ast.Import(n.name, bool(n.wildcard), self.position(n)) for n in nodes)

    def package(self, node: Any) -> tuple[str, ast.Position]:
        if not node:
            return "", ast.Position(self.file, 1, 1)
        return node.name, self.position(node)

    # -- expressions ----------------------------------------------------------------------

    def rule_Expression(self, node: Any) -> ast.Expression:
        operands = [self.convert(operand) for operand in node.operands]
        operators = list(node.operators)
        if not operators:
            return operands[0]
        return _climb(operands, operators, self.position(node))

    def rule_UnaryExpression(self, node: Any) -> ast.Expression:
        operand = self.convert(node.operand)
        if not node.operator:
            return operand
        if node.operator == "-" and isinstance(operand, ast.Quantity):
            where = self.position(node)  # at the sign: the negative literal begins there
            return ast.Quantity(-operand.value, operand.unit, "-" + operand.text, where)
        return ast.Unary(node.operator, operand, self.position(node))

    def rule_PostfixExpression(self, node: Any) -> ast.Expression:
        result = self.convert(node.primary)
        for suffix in node.suffixes:
            where = self.position(suffix)
            kind = type(suffix).__name__
            if kind == "MemberSuffix":
                result = ast.Member(result, suffix.name, where)
            elif kind == "CallSuffix":
                arguments = self.many(suffix.arguments)
                result = ast.Call(result, arguments, result.position.through(where))
            else:
                result = ast.Index(result, self.convert(suffix.index), where)
        return result

    def rule_Argument(self, node: Any) -> ast.Argument:
        return ast.Argument(self.convert(node.value), node.name or "", self.position(node))

    def rule_QuantityLiteral(self, node: Any) -> ast.Quantity:
        number = float(node.number)
        unit = node.unit or ""
        try:
            value = number * lookup(unit).factor
        except UnitError:
            value = number
        text = f"{node.number} {unit}" if unit else node.number
        return ast.Quantity(value, unit, text, self.position(node))

    def rule_BooleanLiteral(self, node: Any) -> ast.BooleanLiteral:
        return ast.BooleanLiteral(node.value == "true", self.position(node))

    def rule_StringLiteral(self, node: Any) -> ast.StringLiteral:
        return ast.StringLiteral(node.value, self.position(node))

    def rule_VectorLiteral(self, node: Any) -> ast.VectorLiteral:
        return ast.VectorLiteral(self.many(node.elements), self.position(node))

    def rule_ParenthesizedExpression(self, node: Any) -> ast.Expression:
        return self.convert(node.expression)

    def rule_NameExpression(self, node: Any) -> ast.Name:
        return ast.Name(node.name, self.position(node))

    # -- statements -----------------------------------------------------------------------

    def rule_Assignment(self, node: Any) -> ast.Assignment:
        return ast.Assignment(
            self.convert(node.target), self.convert(node.value), self.position(node)
        )

    def rule_ExpressionStatement(self, node: Any) -> ast.ExpressionStatement:
        return ast.ExpressionStatement(self.convert(node.expression), self.position(node))

    def rule_Block(self, node: Any) -> tuple[ast.Statement, ...]:
        return self.many(node.statements)

    # -- statecharts ----------------------------------------------------------------------

    def rule_Statechart(self, node: Any) -> ast.Statechart:
        return ast.Statechart(
            node.name,
            self.many(node.elements),
            self.stereotypes(node.stereotypes),
            self.position(node),
        )

    def rule_State(self, node: Any) -> ast.State:
        return ast.State(
            node.name,
            self.stereotypes(node.stereotypes),
            tuple(node.modifiers),
            self.many(node.arguments),
            self.optional(node.invariant),
            self.many(node.body.elements) if node.body else None,
            self.position(node),
        )

    def rule_Action(self, node: Any) -> ast.Action:
        if node.block:
            return ast.Action(node.kind, self.convert(node.block), True, self.position(node))
        return ast.Action(node.kind, (self.convert(node.statement),), False, self.position(node))

    def rule_Invariant(self, node: Any) -> ast.Invariant:
        return ast.Invariant(self.convert(node.expression), self.position(node))

    def rule_EventBlock(self, node: Any) -> ast.EventBlock:
        events = tuple(ast.Event(e.name, self.position(e)) for e in node.events)
        return ast.EventBlock(events, self.position(node))

    def rule_ChoiceState(self, node: Any) -> ast.Pseudostate:
        return ast.Pseudostate("choice", node.name, self.position(node))

    def rule_HistoryState(self, node: Any) -> ast.Pseudostate:
        kind = "deep history" if node.deep else "history"
        return ast.Pseudostate(kind, node.name, self.position(node))

    def rule_Region(self, node: Any) -> ast.Region:
        return ast.Region(node.name, self.many(node.elements), self.position(node))

    def rule_InternalTransition(self, node: Any) -> ast.InternalTransition:
        stimulus = node.stimulus
        return ast.InternalTransition(
            stimulus.name,
            self.optional(node.guard),
            self.many(stimulus.arguments),
            self.convert(node.action) if node.action else None,
            self.position(node),
            self.position(stimulus),
        )

    def rule_Transition(self, node: Any) -> ast.Transition:
        stimulus = node.stimulus
        return ast.Transition(
            node.source.name,
            node.target.name,
            self.optional(node.guard),
            stimulus.name if stimulus else "",
            self.many(stimulus.arguments) if stimulus else (),
            self.convert(node.action) if node.action else None,
            self.optional(node.postcondition),
            self.position(node),
            self.position(node.source),
            self.position(node.target),
            self.position(stimulus) if stimulus else ast.NOWHERE,
            node.target.history or "",
        )


PRECEDENCE = {
    "||": 1,
    "&&": 2,
    "==": 3,
    "!=": 3,
    "<": 4,
    "<=": 4,
    ">": 4,
    ">=": 4,
    "+": 5,
    "-": 5,
    "*": 6,
    "/": 6,
    "%": 6,
}


def _climb(
    operands: list[ast.Expression], operators: list[str], position: ast.Position
) -> ast.Expression:
    """Fold a flat operand/operator list into a left-associative tree by precedence."""
    operands = list(operands)
    operators = list(operators)

    def parse(minimum: int) -> ast.Expression:
        left = operands.pop(0)
        while operators and PRECEDENCE[operators[0]] >= minimum:
            operator = operators.pop(0)
            right = parse(PRECEDENCE[operator] + 1)
            start, last = getattr(left, "position", position), getattr(right, "position", position)
            left = ast.Binary(operator, left, right, start.through(last))
        return left

    return parse(1)
