"""Findings of the check as LSP diagnostics, and quick fixes for their "did you mean" hints."""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from lightrocks.app.lsp.text import Text
from lightrocks.workbench.diagnostics import Diagnostic, Severity

SEVERITIES = {
    Severity.ERROR: lsp.DiagnosticSeverity.Error,
    Severity.WARNING: lsp.DiagnosticSeverity.Warning,
    Severity.INFO: lsp.DiagnosticSeverity.Information,
}
SUGGESTION = re.compile(r"'([^']+)'")


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


def quick_fixes(uri: str, diagnostics: list[lsp.Diagnostic]) -> list[lsp.CodeAction]:
    """One fix per name a diagnostic's hint suggests, replacing the name it was reported at."""
    actions = []
    for item in diagnostics:
        hint = item.data.get("hint", "") if isinstance(item.data, dict) else ""
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
