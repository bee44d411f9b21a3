"""LightRocks expressions and statements compiled to Python source, from the AST.

Nothing of the model text is copied into code: numbers are printed from their SI values,
strings through ``repr``, names through :mod:`generators.python.names`. Sensors read the
snapshot ``s``, scene objects the environment ``self.env``, parameters the state that
declares them (``self.parent.depth`` one level up). Parentheses follow Python's precedence,
and comparisons never chain.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from lightrocks.generators.python.names import attribute, identifier
from lightrocks.languages.domain.types import FRAME, DeviceT, FunctionT, ObjectT, StructT, Type
from lightrocks.languages.lightrocks.model import Region
from lightrocks.languages.lightrocks.typing import Typing
from lightrocks.metamodel import ast

OR, AND, NOT, COMPARE, ADD, MULTIPLY, UNARY, ATOM = 1, 2, 3, 4, 6, 7, 8, 10
BINARY = {
    "||": ("or", OR),
    "&&": ("and", AND),
    "==": ("==", COMPARE),
    "!=": ("!=", COMPARE),
    "<": ("<", COMPARE),
    "<=": ("<=", COMPARE),
    ">": (">", COMPARE),
    ">=": (">=", COMPARE),
    "+": ("+", ADD),
    "-": ("-", ADD),
    "*": ("*", MULTIPLY),
    "/": ("/", MULTIPLY),
    "%": ("%", MULTIPLY),
}
RUNTIME_FUNCTIONS = {"rotX", "rotY", "rotZ", "transl"}
AXES = {"x": 0, "y": 1, "z": 2}


class CompileError(Exception):
    """A construct the Python target cannot express (reported with its model location)."""


@dataclass
class Scope:
    """Where compiled code runs: ``self`` is the state of ``region``'s state ``offset`` up."""

    typing: Typing | None
    region: Region | None
    offset: int = 0
    extension: Callable[[ast.ExtensionNode, Scope], str] | None = None
    """Renders a node of a language extension through that extension's template."""

    def __post_init__(self) -> None:
        self.env: dict[str, Type] = (
            self.typing.environment(self.region) if self.typing and self.region else {}
        )

    def type_of(self, expression: ast.Expression) -> Type | None:
        if self.typing is None:
            return None
        return self.typing.infer(expression, self.env)


def number(literal: ast.Quantity) -> str:
    """The SI value; integers stay integers when written as such (``3``, not ``3 mm``)."""
    if literal.integral:
        return str(int(literal.value))
    return repr(float(literal.value))


def expression(node: ast.Expression, scope: Scope) -> str:
    return _compile(node, scope)[0]


def _wrap(compiled: tuple[str, int], minimum: int) -> str:
    code, level = compiled
    return code if level >= minimum else f"({code})"


def _compile(node: ast.Expression, scope: Scope) -> tuple[str, int]:
    match node:
        case ast.Quantity():
            code = number(node)
            return code, (UNARY if code.startswith("-") else ATOM)
        case ast.BooleanLiteral():
            return ("True" if node.value else "False"), ATOM
        case ast.StringLiteral():
            return repr(node.value), ATOM
        case ast.VectorLiteral():
            items = [_wrap(_compile(e, scope), OR) for e in node.elements]
            return ("(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"), ATOM
        case ast.Name():
            return _name(node, scope), ATOM
        case ast.Member():
            return _member(node, scope), ATOM
        case ast.Index():
            target = _wrap(_compile(node.target, scope), ATOM)
            index = node.index
            if isinstance(index, ast.Quantity) and number(index).isdigit():
                return f"{target}[{number(index)}]", ATOM
            return f"{target}[int({expression(index, scope)})]", ATOM
        case ast.Call():
            return _call(node, scope), ATOM
        case ast.Unary():
            if node.operator == "!":
                return f"not {_wrap(_compile(node.operand, scope), NOT)}", NOT
            return f"{node.operator}{_wrap(_compile(node.operand, scope), UNARY)}", UNARY
        case ast.Binary():
            operator, level = BINARY[node.operator]
            left_min = COMPARE + 1 if level == COMPARE else level
            left = _wrap(_compile(node.left, scope), left_min)
            right = _wrap(_compile(node.right, scope), level + 1)
            return f"{left} {operator} {right}", level
        case ast.ExtensionNode() if scope.extension is not None:
            return f"({scope.extension(node, scope)})", ATOM
    raise CompileError(f"{node.position}: cannot compile {type(node).__name__}")


def _name(node: ast.Name, scope: Scope) -> str:
    hops, region = scope.offset, scope.region
    while region is not None:
        if node.name in region.parameters:
            return "self" + ".parent" * hops + "." + identifier(node.name)
        region, hops = region.parent, hops + 1
    kind = scope.env.get(node.name)
    if isinstance(kind, DeviceT):
        return attribute("s", node.name)
    if isinstance(kind, ObjectT):
        return f"self.env.{identifier(node.name)}"
    raise CompileError(f"{node.position}: unknown name '{node.name}'")


def _member(node: ast.Member, scope: Scope) -> str:
    owner = scope.type_of(node.target)
    target = _wrap(_compile(node.target, scope), ATOM)
    if owner == FRAME and node.name in AXES:
        return f"rt.coordinate({target}, {AXES[node.name]})"
    if isinstance(owner, DeviceT | StructT):
        return attribute(target, node.name)
    return f"{target}.{identifier(node.name)}"


def _call(node: ast.Call, scope: Scope) -> str:
    function = node.function
    known = isinstance(function, ast.Name) and isinstance(scope.env.get(function.name), FunctionT)
    if not known:
        raise CompileError(f"{node.position}: only built-in functions can be called here")
    arguments = ", ".join(_wrap(_compile(a.value, scope), OR) for a in node.arguments)
    prefix = "rt." if function.name in RUNTIME_FUNCTIONS else ""
    return f"{prefix}{function.name}({arguments})"


def target(node: ast.Expression, scope: Scope) -> str:
    """An assignment target: a parameter or an attribute of a scene object."""
    if isinstance(node, ast.Name | ast.Member):
        return expression(node, scope)
    raise CompileError(f"{node.position}: cannot assign to this expression")


def statements(body: tuple[ast.Statement, ...], scope: Scope) -> list[str]:
    lines = []
    for statement in body:
        if isinstance(statement, ast.ExtensionNode) and scope.extension is not None:
            lines += scope.extension(statement, scope).splitlines()
        elif isinstance(statement, ast.Assignment):
            value = expression(statement.value, scope)
            lines.append(f"{target(statement.target, scope)} = {value}")
        else:
            lines.append(expression(statement.expression, scope))
    return lines
