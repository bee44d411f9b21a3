"""Renaming in the studio through the language server's rename (:mod:`app.lsp.navigation`):
the same index of names and the same edits an editor gets, applied to the files on disk.

Every file the rename touches is printed again canonically (a longer name may move the
arguments that are aligned after it); a chart renamed in its own file moves to a file of
its new name, as the language server asks the editor to.
"""

from __future__ import annotations

from pathlib import Path

from lsprotocol import types as lsp
from pygls.uris import to_fs_path

from lightrocks.app.lsp import navigation
from lightrocks.app.lsp.index import Index
from lightrocks.app.lsp.text import Text
from lightrocks.app.studio import edits
from lightrocks.app.studio.findings import places
from lightrocks.app.studio.history import FileChange
from lightrocks.app.studio.texts import canonical
from lightrocks.app.studio.views import levels
from lightrocks.languages.lightrocks.model import Component
from lightrocks.workbench.check import CheckContext


def renamed(
    context: CheckContext, component: Component, level: str, element: str, to: str
) -> list[FileChange]:
    """The changes of the files that rename ``element`` of the level ``level`` of the chart
    (``element`` '': the chart itself) to ``to``."""
    edits.identifier(to, "new name")
    chart = component.qualified_name
    file = component.loaded.path
    place = next(
        (p for p in places(chart, component.unit) if (p.level, p.element) == (level, element)),
        None,
    )
    if place is None or "->" in element:
        raise edits.EditError(f"no state or condition '{element}' on this level to rename")
    name = element.rpartition("/")[2] or component.name
    if to == name:
        raise edits.EditError(f"'{name}' has that name already")
    taken = _names_beside(component, level, element)
    if to in taken:
        raise edits.EditError(f"'{to}' is taken here")
    texts: dict[Path, str] = {}

    def text_of(path: Path) -> Text:
        if path not in texts:
            try:
                texts[path] = path.read_text(encoding="utf-8")
            except (OSError, UnicodeDecodeError):
                texts[path] = ""
        return Text(texts[path])

    index = Index()
    index.update(context.workspace, text_of)
    start = text_of(file).name_range(place.line, place.column, name, True).start
    try:
        change = navigation.rename(index, file, start, to)
    except ValueError as error:
        raise edits.EditError(str(error)) from None
    if change is None:
        raise edits.EditError(f"'{name}' cannot be renamed")
    result: dict[Path, tuple[str | None, str | None]] = {}
    moves: list[tuple[Path, Path]] = []
    for item in change.document_changes or ():
        if isinstance(item, lsp.RenameFile):
            moves.append((Path(to_fs_path(item.old_uri)), Path(to_fs_path(item.new_uri))))
            continue
        path = Path(to_fs_path(item.text_document.uri))
        before = text_of(path).source
        result[path] = (before, canonical(path, _applied(Text(before), item.edits)))
    for old, new in moves:
        if new.exists():
            raise edits.EditError(f"{new.name} is there already")
        before, after = result.get(old, (text_of(old).source, text_of(old).source))
        result[old] = (before, None)
        result[new] = (None, after)
    return [FileChange(path, before, after) for path, (before, after) in result.items()]


def _applied(text: Text, changes: list[lsp.TextEdit]) -> str:
    """The text with the edits made, the last in the text first."""
    source = text.source
    spans = [
        (text.offset(e.range.start.line, e.range.start.character),
         text.offset(e.range.end.line, e.range.end.character), e.new_text)
        for e in changes
    ]  # fmt: skip
    for start, end, new in sorted(spans, reverse=True):
        source = source[:start] + new + source[end:]
    return source


def _names_beside(component: Component, level: str, element: str) -> set[str]:
    """The names declared in the region of ``element`` (a renamed state must not take one)."""
    if not element:
        return set()
    prefix = element.rpartition("/")[0]
    boxes = levels(component).get(level, {}).get("boxes", {})
    return {
        name.rpartition("/")[2]
        for name in boxes
        if name.rpartition("/")[0] == prefix and name != element
    }
