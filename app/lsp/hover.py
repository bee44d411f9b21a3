"""Hover: the declaration behind a name, with its type's unit, signature or outcomes."""

from __future__ import annotations

import re
from typing import Any

from lsprotocol import types as lsp

from lightrocks.app.lsp.index import Declared, FileIndex, Index, Occurrence
from lightrocks.app.lsp.text import Text
from lightrocks.languages.domain.types import Types, describe
from lightrocks.metamodel import ast, printer
from lightrocks.metamodel.units import UnitError, lookup
from lightrocks.workbench.workspace import Workspace

QUANTITY = re.compile(
    r"(?<![\w.])(\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)\s*([A-Za-z]\w*(?:/[A-Za-z]\w*)?)"
)


def hover(index: Index, occurrence: Occurrence, workspace: Workspace) -> lsp.Hover | None:
    declared = index.declared.get(occurrence.key)
    if declared is None:
        return None
    text = describe_declared(declared, workspace)
    return lsp.Hover(
        lsp.MarkupContent(lsp.MarkupKind.Markdown, f"```lightrocks\n{text}\n```"),
        occurrence.range,
    )


def quantity_hover(text: Text, position: lsp.Position) -> lsp.Hover | None:
    """A literal with a unit under the cursor: its value in SI and its dimension."""
    line = text.lines[position.line] if position.line < len(text.lines) else ""
    column = text.column(position.line, position.character)
    for match in QUANTITY.finditer(line):
        if match.start() <= column <= match.end():
            try:
                info = lookup(match.group(2))
            except UnitError:
                return None
            si = float(match.group(1)) * info.factor
            shown = f"{match.group()} = {si:g} [{info.dimension}]"
            where = text.range(*(text.starts[position.line] + at for at in match.span()))
            return lsp.Hover(lsp.MarkupContent(lsp.MarkupKind.Markdown, f"`{shown}`"), where)
    return None


def expression_hover(file: FileIndex | None, position: lsp.Position) -> lsp.Hover | None:
    """The type of the innermost expression under the cursor: an operator, a member, a call."""
    found = file.expression_at(position) if file is not None else None
    if found is None:
        return None
    where, shown = found
    return lsp.Hover(lsp.MarkupContent(lsp.MarkupKind.Markdown, f"`{shown}`"), where)


def describe_declared(declared: Declared, workspace: Workspace) -> str:
    node, loaded = declared.node, declared.loaded
    types = Types(workspace)

    def typed(type_name: str) -> str:
        found = types.resolve(loaded, type_name)
        return f"  // {describe(found)}" if found is not None else ""

    if isinstance(node, ast.Statechart):
        return signature(node)
    if isinstance(node, ast.State):
        imported = next((s.value for s in node.stereotypes if s.name == "import"), None)
        symbol = workspace.resolve(loaded, imported) if imported else None
        if symbol is not None and isinstance(symbol.node, ast.Statechart):
            return f"state {node.name}  <<import>>\n{signature(symbol.node)}"
        return " ".join((*node.modifiers, "state", node.name))
    if isinstance(node, ast.Parameter | ast.CommandParameter):
        default = f" = {printer.expression(node.default)}" if node.default else ""
        return f"{node.type} {node.name}{default}{typed(node.type)}"
    if isinstance(node, ast.Sensor):
        return f"sensor {node.type} {node.name}{typed(node.type)}"
    if isinstance(node, ast.Command):
        return command_signature(node)
    if isinstance(node, ast.Condition):
        return f"{node.kind} condition {node.name}"
    if isinstance(node, ast.DeviceInstance):
        return f"{node.name} : {node.type}"
    return f"{declared.kind} {getattr(node, 'name', '')}"


def signature(chart: ast.Statechart) -> str:
    """``statechart Name(parameters)`` with its start and end conditions."""
    elements = [
        p for e in chart.elements for p in (e.parameters if hasattr(e, "parameters") else (e,))
    ]
    parameters = ", ".join(_parameter(p) for p in elements if isinstance(p, ast.Parameter))
    conditions = [e for e in elements if isinstance(e, ast.Condition)]
    starts = ", ".join(c.name for c in conditions if c.kind == "start") or "-"
    outcomes = ", ".join(c.name for c in conditions if c.kind == "end") or "-"
    return f"statechart {chart.name}({parameters})\n// start: {starts}\n// outcomes: {outcomes}"


def command_signature(command: ast.Command) -> str:
    parameters = ", ".join(_parameter(p) for p in command.parameters)
    returns = f" : {command.returns}" if command.returns else ""
    return f"command {command.name}({parameters}){returns}"


def _parameter(node: Any) -> str:
    default = f" = {printer.expression(node.default)}" if node.default else ""
    return f"{node.type} {node.name}{default}"
