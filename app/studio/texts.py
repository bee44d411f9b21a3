"""The texts of model files as the studio names and compares them: a file's version (the
hash of its text), the stamp of the files' state on disk, and a statechart printed
canonically."""

from __future__ import annotations

import hashlib
from pathlib import Path

from lightrocks.app.studio.edits import EditError
from lightrocks.languages.lightrocks.printer import format_statechart_text
from lightrocks.metamodel.grammar import SyntaxProblem


def version(text: str) -> str:
    """The version of a file's text an edit names: a change of the file is another."""
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def stamp(fingerprint: tuple) -> str:
    """A short name of the files' state on disk, the same for the same state."""
    return hashlib.sha256(repr(fingerprint).encode()).hexdigest()[:16]


def file_stamp(file: Path) -> tuple[int, int]:
    """The file's modification time and size; ``(0, 0)`` when it cannot be read."""
    try:
        status = file.stat()
    except OSError:
        return (0, 0)
    return (status.st_mtime_ns, status.st_size)


def text_of(path: Path) -> str | None:
    """The file's text; ``None``: the file is not there."""
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return None


def canonical(path: Path, text: str) -> str:
    """``text`` printed canonically when it is a statechart's (comments kept)."""
    if path.suffix != ".lr":
        return text
    try:
        return format_statechart_text(text, str(path))
    except SyntaxProblem as problem:
        raise EditError(f"{path.name} does not parse after the edit: {problem}") from None
