"""Rendering of findings: text for people, JSON for tools, SARIF for code scanning, and
GitHub workflow annotations. Model text (file names, quoted source) is neutralised first, so
it can neither drive a terminal nor add a workflow command."""

from __future__ import annotations

import json
import unicodedata
from collections.abc import Callable, Sequence
from importlib.metadata import version

from lightrocks.workbench.cocos import Code
from lightrocks.workbench.diagnostics import Diagnostic, Severity

SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
_SARIF_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
_GITHUB_LEVEL = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}


_UNSAFE = {"Cc", "Cf", "Cs", "Zl", "Zp"}
"""Controls, format (bidi), lone surrogates (no terminal can show them; encoding them
fails) and line or paragraph separators."""


def printable(text: str) -> str:
    """``text`` for a terminal: control and format characters (escape sequences, BEL, line
    breaks, bidi overrides) are shown as Python escapes (``\\x1b``) instead of acting."""
    return "".join(repr(c)[1:-1] if unicodedata.category(c) in _UNSAFE else c for c in text)


def text(diagnostics: Sequence[Diagnostic]) -> str:
    lines = [printable(str(d)) for d in diagnostics]
    errors = sum(d.severity is Severity.ERROR for d in diagnostics)
    warnings = sum(d.severity is Severity.WARNING for d in diagnostics)
    lines.append(f"{errors} error(s), {warnings} warning(s)")
    return "\n".join(lines)


def as_json(diagnostics: Sequence[Diagnostic]) -> str:
    items = [
        {
            "file": d.file,
            "line": d.line,
            "column": d.column,
            "code": d.code,
            "severity": d.severity.value,
            "message": d.message,
            "hint": d.hint,
        }
        for d in diagnostics
    ]
    return json.dumps(items, indent=2)


def sarif(diagnostics: Sequence[Diagnostic], cocos: Sequence[Code]) -> str:
    rules = {c.code: c for c in cocos}
    used = sorted({d.code for d in diagnostics})
    document = {
        "$schema": SARIF_SCHEMA,
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "lightrocks",
                        "version": version("lightrocks"),
                        "rules": [
                            {
                                "id": code,
                                "shortDescription": {
                                    "text": rules[code].summary if code in rules else code
                                },
                            }
                            for code in used
                        ],
                    }
                },
                "results": [
                    {
                        "ruleId": d.code,
                        "level": _SARIF_LEVEL[d.severity],
                        "message": {"text": f"{d.message} ({d.hint})" if d.hint else d.message},
                        "locations": [
                            {
                                "physicalLocation": {
                                    "artifactLocation": {"uri": d.file},
                                    "region": _region(d),
                                }
                            }
                        ],
                    }
                    for d in diagnostics
                ],
            }
        ],
    }
    return json.dumps(document, indent=2)


def _region(d: Diagnostic) -> dict[str, int]:
    """A finding's region: its start, and its end where the element's end is known (SARIF's
    end column, like ours, is the column just after the region)."""
    region = {"startLine": d.line, "startColumn": d.column}
    if d.end_line > 0:
        region |= {"endLine": d.end_line, "endColumn": d.end_column}
    return region


def github(diagnostics: Sequence[Diagnostic]) -> str:
    return "\n".join(
        f"::{_GITHUB_LEVEL[d.severity]} file={_property(d.file)},line={d.line},col={d.column},"
        f"title={_property(d.code)}::{_data(d.message + (f' ({d.hint})' if d.hint else ''))}"
        for d in diagnostics
    )


def _data(value: str) -> str:
    """A workflow command's message: one line, no terminal controls."""
    return printable(value.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A"))


def _property(value: str) -> str:
    """A workflow command's property value: also no ``:`` or ``,`` that end it."""
    return _data(value).replace(":", "%3A").replace(",", "%2C")


_PLAIN: dict[str, Callable[[Sequence[Diagnostic]], str]] = {
    "text": text,
    "json": as_json,
    "github": github,
}
FORMATS = (*_PLAIN, "sarif")


def render(
    form: str, diagnostics: Sequence[Diagnostic], cocos: Callable[[], Sequence[Code]]
) -> str:
    """The findings in one of :data:`FORMATS`. Only SARIF describes the rules it reports, so
    only it asks ``cocos`` for them (loading every CoCo takes a while)."""
    if form == "sarif":
        return sarif(diagnostics, cocos())
    return _PLAIN[form](diagnostics)
