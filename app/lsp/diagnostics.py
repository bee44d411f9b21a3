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
    """The finding over the word it points at (an empty range where no word starts)."""
    offset = text.offset(finding.line - 1, finding.column - 1)
    return lsp.Diagnostic(
        range=text.word_range(offset),
        message=finding.message + (f" ({finding.hint})" if finding.hint else ""),
        severity=SEVERITIES[finding.severity],
        code=finding.code,
        source="lightrocks",
        data={"hint": finding.hint} if finding.hint else None,
    )


def quick_fixes(
    uri: str, diagnostics: list[lsp.Diagnostic], unit: ast.StatechartUnit | None = None
) -> list[lsp.CodeAction]:
    """One fix per name a diagnostic's hint suggests, replacing the name it was reported at;
    and, in the parsed ``unit`` of the document, the transition an unhandled outcome's hint
    names."""
    actions = []
    for item in diagnostics:
        hint = item.data.get("hint", "") if isinstance(item.data, dict) else ""
        handler = HANDLER.search(hint) if item.code == "LR0209" else None
        if handler is not None and unit is not None:
            actions += _transition_fix(uri, item, unit, handler["source"], handler["text"])
            continue
        if not hint.startswith("did you mean"):
            continue
        for name in SUGGESTION.findall(hint):
            edit = lsp.TextEdit(item.range, name)
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
    uri: str, item: lsp.Diagnostic, unit: ast.StatechartUnit, source: str, transition: str
) -> list[lsp.CodeAction]:
    """Insert ``transition`` on a line of its own before the first transition leaving
    ``source`` in the body that declares the state the diagnostic points at (or before its
    first transition): a statement boundary, wherever the statements span lines. Outcomes
    exclude each other, so the new transition's place among them changes nothing."""
    start = item.range.start
    for node in ast.walk(unit):
        elements = getattr(node, "elements", None) or getattr(node, "body", None) or ()
        if not isinstance(node, ast.Statechart | ast.Region | ast.State):
            continue
        declared = any(
            isinstance(e, ast.State)
            and e.name == source
            and (e.position.line - 1, e.position.column - 1) == (start.line, start.character)
            for e in elements
        )
        transitions = [e for e in elements if isinstance(e, ast.Transition)]
        if not declared or not transitions:
            continue
        before = next((t for t in transitions if t.source == source), transitions[0]).position
        at = lsp.Position(before.line - 1, before.column - 1)
        indent = " " * (before.column - 1)
        edit = lsp.TextEdit(lsp.Range(at, at), f"{transition}\n{indent}")
        return [
            lsp.CodeAction(
                title=f"Add '{transition}'",
                kind=lsp.CodeActionKind.QuickFix,
                diagnostics=[item],
                edit=lsp.WorkspaceEdit(changes={uri: [edit]}),
            )
        ]
    return []
