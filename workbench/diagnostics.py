"""Findings of a run: every problem found, each with a stable code and a file position."""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from dataclasses import dataclass, field
from enum import Enum
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # findings are read back from the disk cache without the metamodel
    from lightrocks.metamodel.ast import Position


class Severity(Enum):
    ERROR = "error"
    WARNING = "warning"
    INFO = "info"


@dataclass(frozen=True, order=True)
class Diagnostic:
    file: str
    line: int
    column: int
    code: str
    severity: Severity
    message: str
    hint: str = ""
    end_line: int = field(default=0, compare=False)
    """Where the element it is reported at ends (the line and column just after it; 0 where
    no end is known). Findings are told apart and ordered by their start only."""
    end_column: int = field(default=0, compare=False)

    @classmethod
    def at(
        cls, position: Position, code: str, severity: Severity, message: str, hint: str = ""
    ) -> Diagnostic:
        file, line, column = position.file, position.line, position.column
        end = (position.end_line, position.end_column)
        return cls(file, line, column, code, severity, message, hint, *end)

    def __str__(self) -> str:
        text = f"{self.file}:{self.line}:{self.column}: {self.severity.value} {self.code}: "
        text += self.message
        return f"{text} ({self.hint})" if self.hint else text


def did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """A hint naming the closest candidates, or an empty string."""
    matches = difflib.get_close_matches(name, list(candidates), n=3, cutoff=0.6)
    if not matches:
        return ""
    return "did you mean " + " or ".join(f"'{m}'" for m in matches) + "?"


class Diagnostics:
    """Collects findings; never stops at the first one."""

    def __init__(self) -> None:
        self._items: list[Diagnostic] = []

    def add(self, diagnostic: Diagnostic) -> None:
        self._items.append(diagnostic)

    def extend(self, diagnostics: Iterable[Diagnostic]) -> None:
        self._items.extend(diagnostics)

    def error(self, position: Position, code: str, message: str, hint: str = "") -> None:
        self.add(Diagnostic.at(position, code, Severity.ERROR, message, hint))

    def warning(self, position: Position, code: str, message: str, hint: str = "") -> None:
        self.add(Diagnostic.at(position, code, Severity.WARNING, message, hint))

    @property
    def items(self) -> list[Diagnostic]:
        """Findings sorted by file and position, duplicates removed."""
        return sorted(set(self._items))

    @property
    def has_errors(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self._items)

    def __len__(self) -> int:
        return len(self._items)
