"""The findings cache on disk: the findings of a check and what it read, as JSON.

Entries are data only and are checked field by field when read: a planted or corrupt entry
is a miss. They are written whole and renamed into place (``put_json``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from lightrocks.app.cachedir import cache_root, put_json
from lightrocks.workbench.diagnostics import Diagnostic, Severity
from lightrocks.workbench.reads import Reads

_TYPES = (str, int, int, str, str, str, str)
"""Types of a stored finding's fields, in the order of :class:`Diagnostic`."""


class DiskStore:
    """Findings below ``folder`` (default: ``<user cache>/lightrocks/check``)."""

    def __init__(self, folder: Path | None = None) -> None:
        self.folder = folder or cache_root() / "check"

    def get(self, key: str) -> tuple[Reads, list[Diagnostic]] | None:
        try:
            data = json.loads((self.folder / key[:2] / key).read_text(encoding="utf-8"))
            if not isinstance(data, dict) or set(data) != {"reads", "findings"}:
                return None
            return Reads.from_json(data["reads"]), [_finding(f) for f in data["findings"]]
        except (OSError, ValueError, TypeError, RecursionError):
            return None

    def put(self, key: str, reads: Reads, findings: list[Diagnostic]) -> None:
        entry = {
            "reads": reads.to_json(),
            "findings": [
                [f.file, f.line, f.column, f.code, f.severity.value, f.message, f.hint]
                for f in findings
            ],
        }
        try:
            put_json(self.folder / key[:2] / key, entry)
        except (OSError, ValueError):
            return  # a cache that cannot be written only costs the next run a check


def _finding(data: Any) -> Diagnostic:
    if not isinstance(data, list) or len(data) != len(_TYPES):
        raise ValueError("not a stored finding")
    if not all(type(value) is kind for value, kind in zip(data, _TYPES, strict=True)):
        raise ValueError("not a stored finding")
    file, line, column, code, severity, message, hint = data
    return Diagnostic(file, line, column, code, Severity(severity), message, hint)
