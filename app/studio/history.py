"""The studio's edits as changes of files, written all or none, kept for undo and redo.

Every write checks once more, right before it, that each file still holds what the edit was
made on; undo and redo are refused in turn when a file has changed since the edit (an
editor, ``git``): what they would write back would lose that change.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from lightrocks.app.studio.edits import EditError
from lightrocks.app.studio.texts import text_of
from lightrocks.workbench.files import write_atomic

KEPT = 100
"""Edits kept for undo."""


class Conflict(Exception):
    """The file changed on disk since the page loaded it."""


class Unwritten(Exception):
    """A file of an edit could not be written (the disk, not the edit)."""


@dataclass(frozen=True)
class FileChange:
    """One file's text before and after an edit; ``None``: the file is not there."""

    path: Path
    before: str | None
    after: str | None


Edit = tuple[str, list[FileChange]]
"""What an edit did, as undo and redo name it, and the changes of its files."""


class History:
    """The edits undo takes back (the last last) and those redo makes again; ``shown``
    names a file in refusals as the page does."""

    def __init__(self, shown: Callable[[Path], str]) -> None:
        self.shown = shown
        self.done: list[Edit] = []
        self.undone: list[Edit] = []

    def next(self) -> dict[str, str]:
        """What undo and redo would do next ('' for nothing)."""
        return {
            "undo": self.done[-1][0] if self.done else "",
            "redo": self.undone[-1][0] if self.undone else "",
        }

    def commit(self, what: str, changes: list[FileChange]) -> None:
        """Write a new edit's files and keep it for undo; redo starts afresh."""
        self.write(changes)
        self.done = [*self.done, (what, changes)][-KEPT:]
        self.undone = []

    def undo(self) -> str:
        """Take the last edit back; what was undone."""
        return self._turn(self.done, self.undone, lambda c: FileChange(c.path, c.after, c.before))

    def redo(self) -> str:
        return self._turn(self.undone, self.done, lambda c: c)

    def _turn(self, source: list, target: list, way: Callable[[FileChange], FileChange]) -> str:
        if not source:
            raise EditError("nothing to " + ("undo" if source is self.done else "redo"))
        what, changes = source[-1]
        self.write([way(c) for c in changes])
        target.append(source.pop())
        return what

    def write(self, changes: list[FileChange]) -> None:
        """Write every file of an edit, or none: each must still hold what the edit was
        made on."""
        for change in changes:
            if text_of(change.path) != change.before:
                name = self.shown(change.path)
                raise Conflict(f"{name} changed on disk since; nothing was written")
        for change in changes:
            try:
                if change.after is None:
                    change.path.unlink()
                else:
                    write_atomic(change.path, change.after)
            except OSError as error:
                shown = self.shown(change.path)
                raise Unwritten(f"cannot write {shown}: {error.strerror or error}") from None
