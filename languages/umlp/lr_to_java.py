"""LightRocks expressions and statements as the Java of a UML/P chart, with the brackets
Java's precedence needs. What Java lacks (units, named arguments, vector literals, other
statements) raises :class:`Refused` (LR2120) at its position.
"""

from __future__ import annotations

from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.literals import LR_NUMBER, java_string_literal
from lightrocks.languages.umlp.refusal import Refused
from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import PRECEDENCE

_ATOM = 9  # binds tighter than every operator: names, literals, member access, calls


def _precedence(node: ast.Expression) -> int:
    if isinstance(node, ast.Binary):
        return PRECEDENCE[node.operator]
    return _ATOM - 1 if isinstance(node, ast.Unary) else _ATOM


def _bracketed(node: ast.Expression, needed: bool) -> n.JExpression:
    converted = java_expression(node)
    return n.JBracket(converted, node.position) if needed else converted


def _number_text(node: ast.Quantity) -> str:
    """The magnitude of a unitless number as Java writes it."""
    text = node.text.lstrip("-") if node.text else ""
    if LR_NUMBER.fullmatch(text):
        return text
    value = abs(node.value)
    return str(int(value)) if value.is_integer() else repr(value)


def java_expression(node: ast.Expression) -> n.JExpression:
    """The Java expression of a LightRocks expression, with the brackets Java's precedence
    needs; raises :class:`Refused`."""
    where = node.position
    match node:
        case ast.Quantity(unit=unit, value=value, text=text) if not unit:
            literal = n.JLiteral("number", _number_text(node), where)
            if value < 0 or text.startswith("-"):
                return n.JPrefix("-", literal, where)
            return literal
        case ast.Quantity(text=text):
            raise Refused(where, f"the quantity {text} has a unit; Java numbers have none")
        case ast.BooleanLiteral(value=value):
            return n.JLiteral("boolean", "true" if value else "false", where)
        case ast.StringLiteral(value=value):
            return n.JLiteral("string", java_string_literal(value), where)
        case ast.Name(name=name):
            return n.JName(name, where)
        case ast.Member(target=target, name=name):
            return n.JFieldAccess(_bracketed(target, _precedence(target) < _ATOM), name, where)
        case ast.Index(target=target, index=index):
            return n.JArrayAccess(
                _bracketed(target, _precedence(target) < _ATOM), java_expression(index), where
            )
        case ast.Call(function=function, arguments=arguments):
            named = [a for a in arguments if a.name]
            if named:
                raise Refused(
                    named[0].position,
                    f"the named argument {named[0].name} = … has no Java counterpart",
                )
            values = tuple(java_expression(a.value) for a in arguments)
            return n.JCall(_bracketed(function, _precedence(function) < _ATOM), values, where)
        case ast.Unary(operator=operator, operand=operand):
            return n.JPrefix(operator, _bracketed(operand, _precedence(operand) < _ATOM), where)
        case ast.Binary(operator=operator, left=left, right=right):
            level = PRECEDENCE[operator]
            return n.JBinary(
                operator,
                _bracketed(left, _precedence(left) < level),
                _bracketed(right, _precedence(right) <= level),
                where,
            )
        case ast.VectorLiteral():
            raise Refused(where, "a vector literal has no Java counterpart in a UML/P chart")
    raise Refused(where, f"the LightRocks expression {type(node).__name__} has no Java counterpart")


def java_statement(node: ast.Statement) -> n.JStatement:
    """The Java statement of a LightRocks assignment or expression statement; raises
    :class:`Refused`."""
    where = node.position
    match node:
        case ast.Assignment(target=target, value=value):
            assignment = n.JAssignment("=", java_expression(target), java_expression(value), where)
            return n.JExpressionStatement(assignment, where)
        case ast.ExpressionStatement(expression=value):
            return n.JExpressionStatement(java_expression(value), where)
    raise Refused(where, f"the statement {type(node).__name__} has no Java counterpart")
