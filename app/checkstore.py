"""The findings cache on disk: the findings of a check and what it read, as JSON.

Entries are data only and are checked field by field when read: a planted or corrupt entry
is a miss. The folder is bounded and written whole entry by entry
(:class:`lightrocks.workbench.cachestore.Folder`).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from lightrocks.app.cachedir import cache_root
from lightrocks.workbench.cachestore import Folder
from lightrocks.workbench.diagnostics import Diagnostic, Severity
from lightrocks.workbench.reads import Reads

_TYPES = (str, int, int, str, str, str, str, int, int)
"""Types of a stored finding's fields, in the order of :class:`Diagnostic`."""


class DiskStore:
    """Findings below ``folder`` (default: ``<user cache>/lightrocks/check``), at most
    ``limit`` bytes of them (default: ``LIGHTROCKS_CACHE_BYTES``)."""

    def __init__(self, folder: Path | None = None, limit: int | None = None) -> None:
        self.entries = Folder(folder or cache_root() / "check", limit)

    @property
    def folder(self) -> Path:
        return self.entries.folder

    def get(self, key: str) -> tuple[Reads, list[Diagnostic]] | None:
        text = self.entries.get(key)
        if text is None:
            return None
        try:
            data = json.loads(text)
            if not isinstance(data, dict) or set(data) != {"reads", "findings"}:
                return None
            return Reads.from_json(data["reads"]), [_finding(f) for f in data["findings"]]
        except (ValueError, TypeError, RecursionError):
            return None

    def put(self, key: str, reads: Reads, findings: list[Diagnostic]) -> None:
        entry = {
            "reads": reads.to_json(),
            "findings": [_stored(f) for f in findings],
        }
        self.entries.put(key, json.dumps(entry, separators=(",", ":")))


def _stored(f: Diagnostic) -> list[Any]:
    """A finding as it is stored: its fields in the order of :data:`_TYPES`."""
    severity, end = f.severity.value, (f.end_line, f.end_column)
    return [f.file, f.line, f.column, f.code, severity, f.message, f.hint, *end]


def _finding(data: Any) -> Diagnostic:
    if not isinstance(data, list) or len(data) != len(_TYPES):
        raise ValueError("not a stored finding")
    if not all(type(value) is kind for value, kind in zip(data, _TYPES, strict=True)):
        raise ValueError("not a stored finding")
    file, line, column, code, severity, message, hint, end_line, end_column = data
    return Diagnostic(
        file, line, column, code, Severity(severity), message, hint, end_line, end_column
    )
