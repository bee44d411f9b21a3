"""Syntax of language extensions in the SFC and PLCopen targets (one mapping for both).

A node an extension adds is rendered through the template ``sfc/<Node>.jinja`` of its
extension (or of ``--templates``), as the Python target renders ``python/<Node>.jinja``:

- an expression's template writes one ST expression; it sees ``node``, ``code(e)`` for the
  ST text of a sub-expression (``code(e, like=x)``: as the ST number type of expression
  ``x``, so that an Integer meets a Real as REAL) and ``target(e)`` for an assignable one;
- a statement's template writes ST statements, one per line, with the same helpers;
- an element's template (a declaration such as ``requirement``) writes lines of the
  documentation of its chart's block, and sees the elements of its type as
  ``extension.elements``: the SFC target puts them in the block's comment, PLCopen in the
  POU's ``documentation``.

Model text reaches code only through ``code``, ``target`` and the filter ``string`` (an ST
string literal); documentation lines lose their comment delimiters. A node without a
template is refused where it stands: leaving it out would generate something the model
does not say.
"""

from __future__ import annotations

import textwrap
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import jinja2

from lightrocks.generators.sfc_iec61131.expressions import Scope, string_literal
from lightrocks.metamodel import ast
from lightrocks.workbench.extensions import template_name
from lightrocks.workbench.generators import GenerationError

TARGET = "sfc"


def comment_text(text: str) -> str:
    """``text`` inside an ST comment: no comment delimiter, which would end the comment early
    or, where comments nest, open another."""
    return str(text).replace("(*", "( *").replace("*)", "* )")


@dataclass
class Elements:
    """What an element's template sees as ``extension``: the elements of one type."""

    elements: list[Any]


class Extensions:
    """Renders extension nodes through the templates of ``environment``; without one, maps
    none (every extension node is refused)."""

    def __init__(self, environment: jinja2.Environment | None = None) -> None:
        self.environment = environment
        if environment is not None:
            environment.filters["string"] = string_literal

    def _template(self, node: Any) -> jinja2.Template | None:
        if self.environment is None:
            return None
        try:
            return self.environment.get_template(template_name(TARGET, node))
        except jinja2.TemplateNotFound:
            return None

    def _mapping(self, node: Any) -> jinja2.Template:
        """The template of ``node``; without one, the node is refused where it stands."""
        template = self._template(node)
        if template is None:
            raise GenerationError(
                f"{node.position}: the SFC target does not map '{type(node).__name__}', "
                f"which a language extension adds (no template {template_name(TARGET, node)})"
            )
        return template

    def refuse_unmapped(self, unit: Any) -> None:
        """Stop at the first extension node of ``unit`` that no template maps, before any
        output: an action's nodes are met only when its statements are compiled."""
        for node in ast.walk(unit):
            if ast.is_extension(node):
                self._mapping(node)

    def _render(self, node: ast.ExtensionNode, scope: Scope) -> str:
        template = self._mapping(node)

        def code(part: ast.Expression, like: ast.Expression | None = None) -> str:
            return scope.compile(part, scope.infer(like) if like is not None else None)

        def target(part: ast.Expression) -> str:
            if not isinstance(part, ast.Name | ast.Member):
                raise GenerationError(f"{part.position}: cannot assign to this expression")
            return scope.compile(part)

        return template.render(node=node, code=code, target=target)

    def expression(self, node: ast.ExtensionNode, scope: Scope) -> str:
        """The ST text of an extension expression, parenthesized as one operand."""
        return f"({self._render(node, scope).strip()})"

    def statement(self, node: ast.ExtensionNode, scope: Scope) -> list[str]:
        """The ST statements of an extension statement."""
        text = textwrap.dedent(self._render(node, scope))
        return [line.rstrip() for line in text.splitlines() if line.strip()]

    def documentation(self, elements: Iterable[Any]) -> list[str]:
        """Documentation lines of a chart's extension elements, grouped by type in order of
        first appearance."""
        groups: dict[type, list[Any]] = {}
        for element in elements:
            groups.setdefault(type(element), []).append(element)
        lines: list[str] = []
        for group in groups.values():
            text = self._mapping(group[0]).render(extension=Elements(group))
            lines += [comment_text(line.rstrip()) for line in text.splitlines() if line.strip()]
        return lines
