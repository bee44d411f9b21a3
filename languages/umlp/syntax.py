"""Concrete syntax of UML/P statecharts (``.sc``): the textX grammar ``umlp.tx`` and the
conversion of its parse trees into the syntax tree of :mod:`languages.umlp.nodes`."""

from __future__ import annotations

import bisect
import re
from pathlib import Path
from typing import Any

from lightrocks.languages.umlp import nodes as n
from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import SyntaxProblem, parse, paused_gc
from lightrocks.workbench.depth import (
    MAX_DEPTH,
    TOO_DEEP_EXPRESSION,
    TOO_DEEP_STATES,
    deepest,
    deepest_node,
)

GRAMMAR = Path(__file__).with_name("umlp.tx")

PRECEDENCE = {
    "||": 1,
    "&&": 2,
    "|": 3,
    "^": 4,
    "&": 5,
    "==": 6,
    "!=": 6,
    "<": 7,
    ">": 7,
    "<=": 7,
    ">=": 7,
    "<<": 8,
    ">>": 8,
    ">>>": 8,
    "+": 9,
    "-": 9,
    "*": 10,
    "/": 10,
    "%": 10,
}
"""Java's binary operators by precedence; a higher number binds tighter."""


class UMLPConverter:
    """Turns textX objects of ``umlp.tx`` into nodes; one method ``rule_<Rule>`` per rule."""

    def __init__(self, text: str, file: str) -> None:
        self.file = file
        self._line_starts = [0, *(m.end() for m in re.finditer("\n", text))]

    def position(self, node: Any) -> ast.Position:
        """Where ``node`` starts and ends (the parse tree's offsets as lines and columns)."""
        line, column = self._line_column(getattr(node, "_tx_position", 0))
        end = getattr(node, "_tx_position_end", None)
        if end is None:
            return ast.Position(self.file, line, column)
        return ast.Position(self.file, line, column, *self._line_column(end))

    def _line_column(self, offset: int) -> tuple[int, int]:
        line = bisect.bisect_right(self._line_starts, offset)
        return line, offset - self._line_starts[line - 1] + 1

    def convert(self, node: Any) -> Any:
        return getattr(self, f"rule_{type(node).__name__}")(node)

    def optional(self, node: Any) -> Any:
        return None if node is None or node == "" else self.convert(node)

    def many(self, nodes: list[Any]) -> tuple[Any, ...]:
        return tuple(self.convert(item) for item in nodes)

    # -- artifact and statechart ------------------------------------------------------------

    def rule_SCArtifact(self, node: Any) -> n.SCArtifact:
        package = node.package.name if node.package else ""
        where = self.position(node.package) if package else ast.Position(self.file, 1, 1)
        return n.artifact(
            package, self.many(node.imports), self.convert(node.statechart), self.file, where
        )

    def rule_MCImportStatement(self, node: Any) -> n.MCImportStatement:
        return n.MCImportStatement(node.name, bool(node.star), self.position(node))

    def rule_Statechart(self, node: Any) -> n.SCStatechart:
        return n.SCStatechart(
            node.name or "",
            self.many(node.elements),
            self.stereotype(node.stereotype),
            node.keyword,
            self.position(node),
        )

    def stereotype(self, node: Any) -> tuple[n.StereoValue, ...]:
        if not node:
            return ()
        return tuple(
            n.StereoValue(v.name, v.content or None, self.position(v)) for v in node.values
        )

    # -- states -------------------------------------------------------------------------

    def rule_SCState(self, node: Any) -> n.SCState:
        body = node.body
        ante = node.ante
        return n.SCState(
            node.name,
            "initial" in node.modifiers,
            "final" in node.modifiers,
            self.stereotype(node.stereotype),
            self.many(ante.statements) if ante else None,
            self.optional(node.invariant),
            self.many(body.elements) if body else None,
            self.position(node),
            self.position(node),
            self.position(body) if body else ast.NOWHERE,
            self.position(ante) if ante else ast.NOWHERE,
        )

    def rule_SCTransition(self, node: Any) -> n.SCTransition:
        pre, event, action = self.transition_body(node.body)
        where = self.position(node)
        return n.SCTransition(
            node.source,
            node.target,
            pre,
            event,
            action,
            self.stereotype(node.stereotype),
            where,
            where,
            where,
        )

    def rule_SCInternTransition(self, node: Any) -> n.SCInternTransition:
        pre, event, action = self.transition_body(node.body)
        return n.SCInternTransition(
            pre, event, action, self.stereotype(node.stereotype), self.position(node)
        )

    def transition_body(self, body: Any) -> tuple[Any, Any, Any]:
        if not body:  # textX makes no object of a rule that matched nothing
            return None, None, None
        action = self.action_body(body.action, body) if body.slash else None
        return self.optional(body.pre), self.optional(body.event), action

    def action_body(self, node: Any, parent: Any) -> n.SCActionBody:
        if not node:
            return n.SCActionBody(None, None, self.position(parent))
        return n.SCActionBody(
            self.optional(node.statement), self.optional(node.post), self.position(node)
        )

    def rule_SCUMLEvent(self, node: Any) -> n.SCEvent:
        arguments = None if not node.arguments else self.many(node.arguments.arguments)
        return n.SCEvent(node.name, arguments, self.position(node))

    def rule_SCAction(self, node: Any) -> n.SCAction:
        return n.SCAction(node.kind, self.action_body(node.body, node), self.position(node))

    def rule_SCCompleteness(self, node: Any) -> n.SCCompleteness:
        return n.SCCompleteness(node.marker == "(c)", self.position(node))

    def rule_SCFuncEventDef(self, node: Any) -> n.SCFuncEventDef:
        return n.SCFuncEventDef(
            node.name,
            self.optional(node.returnType),
            self.many(node.parameters),
            self.position(node),
        )

    def rule_SCFuncEventParameter(self, node: Any) -> n.SCFuncEventParameter:
        return n.SCFuncEventParameter(self.convert(node.type), node.name, self.position(node))

    # -- types ----------------------------------------------------------------------------

    def rule_MCVoidType(self, node: Any) -> n.MCType:
        return n.MCType("void", (), 0, self.position(node))

    def rule_MCType(self, node: Any) -> n.MCType:
        return n.MCType(
            node.name, self.many(node.arguments), len(node.dimensions), self.position(node)
        )

    def rule_MCWildcard(self, node: Any) -> n.MCType:
        return n.MCType("?", (), 0, self.position(node))

    # -- statements -----------------------------------------------------------------------

    def rule_JBlock(self, node: Any) -> n.JBlock:
        return n.JBlock(self.many(node.statements), self.position(node))

    def rule_JIfStatement(self, node: Any) -> n.JIf:
        return n.JIf(
            self.convert(node.condition),
            self.convert(node.then),
            self.optional(node.otherwise),
            self.position(node),
        )

    def rule_JWhileStatement(self, node: Any) -> n.JWhile:
        return n.JWhile(self.convert(node.condition), self.convert(node.body), self.position(node))

    def rule_JDoWhileStatement(self, node: Any) -> n.JDoWhile:
        return n.JDoWhile(
            self.convert(node.body), self.convert(node.condition), self.position(node)
        )

    def rule_JForStatement(self, node: Any) -> n.JFor | n.JForEach:
        control = node.control
        body = self.convert(node.body)
        if type(control).__name__ == "JEnhancedForControl":
            return n.JForEach(
                tuple(control.modifiers),
                self.convert(control.type),
                control.name,
                self.convert(control.iterable),
                body,
                self.position(node),
            )
        init = control.init
        if init is None or init == "":
            converted = None
        elif type(init).__name__ == "JForInitByExpressions":
            converted = self.many(init.expressions)
        else:
            converted = self.convert(init)
        return n.JFor(
            converted,
            self.optional(control.condition),
            self.many(control.updates),
            body,
            self.position(node),
        )

    def rule_JSwitchStatement(self, node: Any) -> n.JSwitch:
        return n.JSwitch(
            self.convert(node.value),
            self.many(node.groups),
            self.many(node.labels),
            self.position(node),
        )

    def rule_JSwitchGroup(self, node: Any) -> n.JSwitchGroup:
        return n.JSwitchGroup(
            self.many(node.labels), self.many(node.statements), self.position(node)
        )

    def rule_JCaseLabel(self, node: Any) -> n.JSwitchLabel:
        return n.JSwitchLabel(self.convert(node.value), self.position(node))

    def rule_JDefaultLabel(self, node: Any) -> n.JSwitchLabel:
        return n.JSwitchLabel(None, self.position(node))

    def rule_JBreakStatement(self, node: Any) -> n.JJump:
        return n.JJump("break", self.position(node))

    def rule_JContinueStatement(self, node: Any) -> n.JJump:
        return n.JJump("continue", self.position(node))

    def rule_JReturnStatement(self, node: Any) -> n.JReturn:
        return n.JReturn(self.optional(node.value), self.position(node))

    def rule_JEmptyStatement(self, node: Any) -> n.JEmpty:
        return n.JEmpty(self.position(node))

    def rule_JLocalVariableDeclarationStatement(self, node: Any) -> n.JLocalVariable:
        return self.convert(node.declaration)

    def rule_JLocalVariableDeclaration(self, node: Any) -> n.JLocalVariable:
        return n.JLocalVariable(
            tuple(node.modifiers),
            self.convert(node.type),
            self.many(node.declarators),
            self.position(node),
        )

    def rule_JVariableDeclarator(self, node: Any) -> n.JDeclarator:
        return n.JDeclarator(
            node.name, len(node.dimensions), self.optional(node.init), self.position(node)
        )

    def rule_JArrayInit(self, node: Any) -> n.JArrayInit:
        return n.JArrayInit(self.many(node.values), bool(node.trailing), self.position(node))

    def rule_JExpressionStatement(self, node: Any) -> n.JExpressionStatement:
        return n.JExpressionStatement(self.convert(node.expression), self.position(node))

    # -- expressions ----------------------------------------------------------------------

    def rule_JAssignmentExpression(self, node: Any) -> n.JExpression:
        target = self.convert(node.target)
        if not node.operator:
            return target
        return n.JAssignment(node.operator, target, self.convert(node.value), self.position(node))

    def rule_JConditionalExpression(self, node: Any) -> n.JExpression:
        condition = self.convert(node.condition)
        if node.then is None or node.then == "":
            return condition
        return n.JConditional(
            condition,
            self.convert(node.then),
            self.convert(node.otherwise),
            self.position(node),
        )

    def rule_JBinaryExpression(self, node: Any) -> n.JExpression:
        """Java's precedence over the flat list of operands and operators, left-associative
        (precedence climbing)."""
        operands = [self.convert(operand) for operand in node.operands]
        operators = list(node.operators)
        if not operators:
            return operands[0]
        where = self.position(node)
        pending = list(zip(operators, operands[1:], strict=True))
        pending.reverse()

        def climb(left: n.JExpression, minimum: int) -> n.JExpression:
            while pending and PRECEDENCE[pending[-1][0]] >= minimum:
                operator, right = pending.pop()
                level = PRECEDENCE[operator]
                while pending and PRECEDENCE[pending[-1][0]] > level:
                    right = climb(right, level + 1)
                left = n.JBinary(operator, left, right, where.through(right.position))
            return left

        return climb(operands[0], 0)

    def rule_JPrefixExpression(self, node: Any) -> n.JPrefix:
        return n.JPrefix(node.operator, self.convert(node.operand), self.position(node))

    def rule_JPostfixExpression(self, node: Any) -> n.JExpression:
        result = self.convert(node.primary)
        for suffix in node.suffixes:
            kind = type(suffix).__name__
            where = self.position(suffix)
            if kind == "JFieldAccess":
                result = n.JFieldAccess(result, suffix.name, where)
            elif kind == "JArguments":
                arguments = self.many(suffix.arguments)
                result = n.JCall(result, arguments, result.position.through(where))
            elif kind == "JArrayAccess":
                result = n.JArrayAccess(result, self.convert(suffix.index), where)
            else:
                result = n.JPostfix(suffix.operator, result, result.position.through(where))
        return result

    def rule_JBracketExpression(self, node: Any) -> n.JBracket:
        return n.JBracket(self.convert(node.expression), self.position(node))

    def rule_JNameExpression(self, node: Any) -> n.JName:
        return n.JName(node.name, self.position(node))

    def rule_JNullLiteral(self, node: Any) -> n.JLiteral:
        return n.JLiteral("null", node.text, self.position(node))

    def rule_JBooleanLiteral(self, node: Any) -> n.JLiteral:
        return n.JLiteral("boolean", node.text, self.position(node))

    def rule_JCharLiteral(self, node: Any) -> n.JLiteral:
        return n.JLiteral("char", node.text, self.position(node))

    def rule_JStringLiteral(self, node: Any) -> n.JLiteral:
        return n.JLiteral("string", node.text, self.position(node))

    def rule_JNumberLiteral(self, node: Any) -> n.JLiteral:
        return n.JLiteral("number", node.text, self.position(node))


def parse_sc(text: str, file: str) -> n.SCArtifact:
    """Parse one ``.sc`` text; raises ``metamodel.grammar.SyntaxProblem``, also for a text
    nested deeper than the parser or the later passes walk (``workbench.depth``)."""
    try:
        with paused_gc():
            tree = parse(GRAMMAR, (), text, file)
            unit = UMLPConverter(text, file).convert(tree)
    except RecursionError:
        where, message = deepest(text, file)
        raise SyntaxProblem(message, where.line, where.column) from None
    found = deepest_node(unit)
    if found is not None:
        where, _ = found  # its message counts LightRocks' expression nodes, not Java's
        states = _state_depth(unit.statechart.elements) > MAX_DEPTH
        message = TOO_DEEP_STATES if states else TOO_DEEP_EXPRESSION
        raise SyntaxProblem(message, where.line, where.column)
    return unit


def _state_depth(elements: tuple[n.SCElement, ...] | None) -> int:
    """How deep states nest in ``elements``, without recursion."""
    deepest_level, pending = 0, [(elements or (), 0)]
    while pending:
        items, level = pending.pop()
        deepest_level = max(deepest_level, level)
        pending += [(e.body, level + 1) for e in items if isinstance(e, n.SCState) and e.body]
    return deepest_level
