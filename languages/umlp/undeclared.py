"""Parameters for the variables a UML/P chart uses but does not declare (UML/P takes them
from the class the chart describes; a LightRocks chart declares them): their types are
guessed from their uses (assigned values, comparisons, conditions, ``x++``), and each
declared parameter is reported (LR2123).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.refusal import Findings
from lightrocks.languages.umlp.typing import JAVA_LANG_TYPES, type_of
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Severity

_DEFAULTS = {"Integer": "0", "Real": "0.0", "Boolean": "false", "String": '""'}
_JAVA = {"Integer": "int", "Real": "double", "Boolean": "boolean", "String": "String"}
_JavaPart = n.JStatement | tuple[n.JExpression, bool]  # a statement, or (condition, is Boolean)


def undeclared_parameters(
    elements: Sequence[n.SCElement], where: ast.Position, findings: Findings
) -> ast.ParameterBlock | None:
    """The parameters of the variables ``elements`` use without declaring them, declared at
    ``where``; None when there are none."""
    guesses = _TypeGuesses()
    guesses.infer(elements)
    return guesses.parameters(where, findings)


class _TypeGuesses:
    """The types the uses of each undeclared variable show."""

    def __init__(self) -> None:
        self.variables: dict[str, set[str]] = {}  # undeclared variable -> LightRocks types
        self.known: dict[str, str] = {}  # the guesses so far, as Java types

    def infer(self, elements: Sequence[n.SCElement]) -> None:
        """Guess the types of undeclared variables from their uses, again while a guess
        types more (``n = n + 1`` is an Integer once ``n = 0`` is)."""
        parts = list(_java_parts(elements))
        known: dict[str, str] = {}
        for _ in range(len(parts) + 1):
            for part in parts:
                if isinstance(part, tuple):  # (expression, needs a boolean)
                    self.condition(*part)
                else:
                    self.statement_types(part)
            guessed = {
                name: _JAVA[kind]
                for name, kinds in self.variables.items()
                if (kind := _joined(kinds)) is not None
            }
            if guessed == known:
                return
            known = self.known = guessed

    def note(self, name: str, kind: str | None) -> None:
        if kind is not None and name not in JAVA_LANG_TYPES:
            self.variables.setdefault(name, set()).add(kind)

    def condition(self, node: n.JExpression, boolean: bool) -> None:
        """Types shown by an expression in a condition (guard, invariant, postcondition)."""
        match node:
            case n.JName(name=name) if boolean:
                self.note(name, "Boolean")
            case n.JBracket(expression=inner):
                self.condition(inner, boolean)
            case n.JPrefix(operator="!", operand=operand):
                self.condition(operand, True)
            case n.JBinary(operator=operator, left=left, right=right):
                if operator in ("&&", "||"):
                    self.condition(left, True)
                    self.condition(right, True)
                else:
                    self.compared(left, right)
                    self.compared(right, left)
                    self.condition(left, False)
                    self.condition(right, False)

    def compared(self, name: n.JExpression, other: n.JExpression) -> None:
        if isinstance(name, n.JName):
            self.note(name.name, _lr_type(type_of(other, names=self.known)))

    def statement_types(self, node: n.JStatement) -> None:
        match node:
            case n.JBlock(statements=statements):
                for statement in statements:
                    self.statement_types(statement)
            case n.JExpressionStatement(expression=value):
                match value:
                    case n.JAssignment(operator=operator, target=n.JName(name=name), value=v):
                        kind = _lr_type(type_of(v, names=self.known))
                        self.note(name, kind if operator == "=" else kind or "Integer")
                    case (
                        n.JPostfix(operand=n.JName(name=name))
                        | n.JPrefix(operator="++" | "--", operand=n.JName(name=name))
                    ):
                        self.note(name, "Integer")

    def parameters(self, where: ast.Position, findings: Findings) -> ast.ParameterBlock | None:
        """A parameter for each variable whose uses agree on a type, each with a finding."""
        declared = []
        for name, kinds in self.variables.items():
            kind = _joined(kinds)
            if kind is None:
                continue
            default = _DEFAULTS[kind]
            declared.append(
                ast.Parameter(kind, name, _literal(kind, default), where),
            )
            findings.add(
                where,
                "LR2123",
                Severity.INFO,
                f"'{name}' is not declared in the UML/P chart (it belongs to the class the chart "
                f"describes): declared as parameter {kind} {name} = {default}",
            )
        return ast.ParameterBlock(tuple(declared), where) if declared else None


def _java_parts(elements: Sequence[n.SCElement]) -> Iterator[_JavaPart]:
    """Statements, and (condition, is Boolean) pairs, of every element at any depth."""
    for element in elements:
        match element:
            case n.SCState():
                if element.ante is not None:
                    yield n.JBlock(element.ante)
                if element.invariant is not None:
                    yield element.invariant, True
                yield from _java_parts(element.body or ())
            case n.SCTransition() | n.SCInternTransition():
                if element.pre is not None:
                    yield element.pre, True
                if element.action is not None:
                    if element.action.statement is not None:
                        yield element.action.statement
                    if element.action.post is not None:
                        yield element.action.post, True
            case n.SCAction(body=body):
                if body.statement is not None:
                    yield body.statement


def _lr_type(java: str) -> str | None:
    if java in ("int", "long", "short", "byte"):
        return "Integer"
    if java in ("double", "float"):
        return "Real"
    return {"boolean": "Boolean", "String": "String"}.get(java)


def _joined(kinds: set[str]) -> str | None:
    if len(kinds) == 1:
        return next(iter(kinds))
    if kinds == {"Integer", "Real"}:
        return "Real"
    return None


def _literal(kind: str, text: str) -> ast.Expression:
    if kind == "Boolean":
        return ast.BooleanLiteral(False)
    if kind == "String":
        return ast.StringLiteral("")
    return ast.Quantity(float(text), "", text)
