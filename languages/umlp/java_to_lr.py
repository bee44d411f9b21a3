"""Java expressions and statements of a UML/P chart (guards, actions, invariants) as
LightRocks expressions and statements, where LightRocks has the construct: names, member
access, calls, indexing, the operators both languages share, literals, assignments,
``x++`` and ``x += e``. Anything else raises :class:`Refused` (LR2120) at its position.
"""

from __future__ import annotations

from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.literals import LR_NUMBER, java_string_value
from lightrocks.languages.umlp.printer import expression as java_text
from lightrocks.languages.umlp.printer import inline
from lightrocks.languages.umlp.refusal import Refused
from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import PRECEDENCE

_OPERATORS = tuple(PRECEDENCE)  # the binary operators both languages write alike
_COMPOUND = {"+=": "+", "-=": "-", "*=": "*", "/=": "/", "%=": "%"}


def lr_expression(node: n.JExpression) -> ast.Expression:
    """The LightRocks expression of a Java expression; raises :class:`Refused`."""
    where = node.position
    match node:
        case n.JLiteral(kind="boolean", text=text):
            return ast.BooleanLiteral(text == "true", where)
        case n.JLiteral(kind="number", text=text):
            if not LR_NUMBER.fullmatch(text):
                raise Refused(where, f"the number {text} has no LightRocks counterpart")
            return ast.Quantity(float(text), "", text, where)
        case n.JLiteral(kind="string", text=text):
            value = java_string_value(text)
            if value.endswith("\\"):
                raise Refused(where, f"the string {text} cannot be written in LightRocks")
            return ast.StringLiteral(value, where)
        case n.JLiteral(kind=kind, text=text):
            raise Refused(where, f"the {kind} literal {text} has no LightRocks counterpart")
        case n.JName(name=name):
            return ast.Name(name, where)
        case n.JFieldAccess(target=target, name=name):
            return ast.Member(lr_expression(target), name, where)
        case n.JCall(target=target, arguments=arguments):
            values = tuple(ast.Argument(lr_expression(a), "", a.position) for a in arguments)
            return ast.Call(lr_expression(target), values, where)
        case n.JArrayAccess(target=target, index=index):
            return ast.Index(lr_expression(target), lr_expression(index), where)
        case n.JBracket(expression=inner):
            return lr_expression(inner)
        case n.JPrefix(operator=operator, operand=operand) if operator in ("!", "+", "-"):
            operand_lr = lr_expression(operand)
            if operator == "-" and isinstance(operand_lr, ast.Quantity):
                text = "-" + operand_lr.text
                return ast.Quantity(-operand_lr.value, "", text, where)
            return ast.Unary(operator, operand_lr, where)
        case n.JBinary(operator=operator, left=left, right=right) if operator in _OPERATORS:
            return ast.Binary(operator, lr_expression(left), lr_expression(right), where)
    raise Refused(where, f"the Java expression '{java_text(node)}' has no LightRocks counterpart")


def _increment(target: n.JExpression, operator: str, where: ast.Position) -> ast.Assignment:
    value = lr_expression(target)
    one = ast.Quantity(1.0, "", "1", where)
    return ast.Assignment(value, ast.Binary(operator, value, one, where), where)


def _assignable(target: n.JExpression) -> bool:
    while isinstance(target, n.JFieldAccess | n.JArrayAccess):
        target = target.target
    return isinstance(target, n.JName)


def lr_statements(node: n.JStatement) -> list[ast.Statement]:
    """The LightRocks statements of a Java statement (a block's in order, an empty
    statement none); raises :class:`Refused`."""
    where = node.position
    match node:
        case n.JBlock(statements=statements):
            return [s for statement in statements for s in lr_statements(statement)]
        case n.JEmpty():
            return []
        case n.JExpressionStatement(expression=value):
            match value:
                case n.JAssignment(operator="=", target=target, value=assigned) if _assignable(
                    target
                ):
                    return [ast.Assignment(lr_expression(target), lr_expression(assigned), where)]
                case n.JAssignment(operator=operator, target=target, value=assigned) if (
                    operator in _COMPOUND and _assignable(target)
                ):
                    lr_target = lr_expression(target)
                    binary = ast.Binary(
                        _COMPOUND[operator], lr_target, lr_expression(assigned), where
                    )
                    return [ast.Assignment(lr_target, binary, where)]
                case (
                    n.JPostfix(operator=operator, operand=target)
                    | n.JPrefix(operator=operator, operand=target)
                ) if operator in ("++", "--") and _assignable(target):
                    return [_increment(target, operator[0], where)]
            return [ast.ExpressionStatement(lr_expression(value), where)]
    kind = {
        n.JLocalVariable: "local variable declaration",
        n.JIf: "if statement",
        n.JWhile: "while loop",
        n.JDoWhile: "do-while loop",
        n.JFor: "for loop",
        n.JForEach: "for loop",
        n.JSwitch: "switch statement",
        n.JJump: "jump statement",
        n.JReturn: "return statement",
    }.get(type(node), "statement")
    raise Refused(where, f"the Java {kind} '{inline(node)}' has no LightRocks counterpart")
