"""Findings of the check as LSP diagnostics, and quick fixes for their hints: a name a "did
you mean" hint suggests, and a transition an LR0209 hint names."""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from lightrocks.app.lsp.text import Text
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Diagnostic, Severity

SEVERITIES = {
    Severity.ERROR: lsp.DiagnosticSeverity.Error,
    Severity.WARNING: lsp.DiagnosticSeverity.Warning,
    Severity.INFO: lsp.DiagnosticSeverity.Information,
}
SUGGESTION = re.compile(r"'([^']+)'")
HANDLER = re.compile(r"add the transition '(?P<text>(?P<source>\w+) -> [^']+)'")


def diagnostic(finding: Diagnostic, text: Text) -> lsp.Diagnostic:
    """The finding over the element it is reported at, as far as that element's first line
    (a composite state is marked on its header, not over its whole body); over the word at
    its start where its end is unknown (a syntax error, an empty range where no word
    starts)."""
    start = text.model_offset(finding.line, finding.column)
    return lsp.Diagnostic(
        range=_extent(finding, text, start),
        message=finding.message + (f" ({finding.hint})" if finding.hint else ""),
        severity=SEVERITIES[finding.severity],
        code=finding.code,
        source="lightrocks",
        data={"hint": finding.hint} if finding.hint else None,
    )


def _extent(finding: Diagnostic, text: Text, start: int) -> lsp.Range:
    if finding.end_line <= 0:
        return text.word_range(start)
    if finding.end_line > finding.line:  # as far as the end of its first line
        end = text.model_offset(finding.line, len(text.lines[finding.line - 1]) + 1)
    else:
        end = text.model_offset(finding.end_line, finding.end_column)
    return text.range(start, max(start, end))


def quick_fixes(
    uri: str,
    diagnostics: list[lsp.Diagnostic],
    text: Text,
    unit: ast.StatechartUnit | None = None,
) -> list[lsp.CodeAction]:
    """One fix per name a diagnostic's hint suggests, replacing the name it was reported at
    (the word at the diagnostic's start in ``text``); and, in the parsed ``unit`` of the
    document, the transition an unhandled outcome's hint names."""
    actions = []
    for item in diagnostics:
        hint = item.data.get("hint", "") if isinstance(item.data, dict) else ""
        handler = HANDLER.search(hint) if item.code == "LR0209" else None
        if handler is not None and unit is not None:
            actions += _transition_fix(uri, item, text, unit, handler)
            continue
        if not hint.startswith("did you mean"):
            continue
        written = text.word_range(text.at(item.range.start))
        for name in SUGGESTION.findall(hint):
            edit = lsp.TextEdit(written, name)
            actions.append(
                lsp.CodeAction(
                    title=f"Change to '{name}'",
                    kind=lsp.CodeActionKind.QuickFix,
                    diagnostics=[item],
                    edit=lsp.WorkspaceEdit(changes={uri: [edit]}),
                )
            )
    return actions


def _transition_fix(
    uri: str, item: lsp.Diagnostic, text: Text, unit: ast.StatechartUnit, handler: re.Match[str]
) -> list[lsp.CodeAction]:
    """Insert ``transition`` on a line of its own before the first transition leaving
    ``source`` in the body that declares the state the diagnostic points at (or before its
    first transition): a statement boundary, wherever the statements span lines. Outcomes
    exclude each other, so the new transition's place among them changes nothing."""
    source, transition = handler["source"], handler["text"]

    def at(where: ast.Position) -> lsp.Position:
        return text.position(text.model_offset(where.line, where.column))

    for node in ast.walk(unit):
        elements = getattr(node, "elements", None) or getattr(node, "body", None) or ()
        if not isinstance(node, ast.Statechart | ast.Region | ast.State):
            continue
        declared = any(
            isinstance(e, ast.State) and e.name == source and at(e.position) == item.range.start
            for e in elements
        )
        transitions = [e for e in elements if isinstance(e, ast.Transition)]
        if not declared or not transitions:
            continue
        before = next((t for t in transitions if t.source == source), transitions[0]).position
        indent = " " * (before.column - 1)
        edit = lsp.TextEdit(lsp.Range(at(before), at(before)), f"{transition}\n{indent}")
        return [
            lsp.CodeAction(
                title=f"Add '{transition}'",
                kind=lsp.CodeActionKind.QuickFix,
                diagnostics=[item],
                edit=lsp.WorkspaceEdit(changes={uri: [edit]}),
            )
        ]
    return []
