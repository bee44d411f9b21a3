"""Definitions, references, rename, the outline and semantic tokens, all read off the index."""

from __future__ import annotations

import re
from pathlib import Path

from lsprotocol import types as lsp
from pygls.uris import from_fs_path

from lightrocks.app.lsp.index import FileIndex, Index, Key, Occurrence
from lightrocks.app.lsp.text import Text

IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
RENAMEABLE = {"state", "parameter", "statechart", "start", "end", "pseudostate", "event"}
SYMBOL_KINDS = {
    "statechart": lsp.SymbolKind.Class,
    "state": lsp.SymbolKind.EnumMember,
    "pseudostate": lsp.SymbolKind.EnumMember,
    "parameter": lsp.SymbolKind.Variable,
    "start": lsp.SymbolKind.Event,
    "end": lsp.SymbolKind.Event,
    "event": lsp.SymbolKind.Event,
    "device": lsp.SymbolKind.Interface,
    "cell": lsp.SymbolKind.Module,
    "command": lsp.SymbolKind.Method,
    "sensor": lsp.SymbolKind.Property,
    "instance": lsp.SymbolKind.Field,
    "object": lsp.SymbolKind.Object,
    "field": lsp.SymbolKind.Field,
    "type": lsp.SymbolKind.Struct,
}
TOKEN_TYPES = [
    "class", "enumMember", "parameter", "event", "interface", "method", "property",
    "variable", "type", "keyword", "namespace",
]  # fmt: skip
TOKEN_OF_KIND = {
    "statechart": "class",
    "state": "enumMember",
    "pseudostate": "enumMember",
    "parameter": "parameter",
    "start": "event",
    "end": "event",
    "event": "event",
    "device": "interface",
    "cell": "namespace",
    "command": "method",
    "sensor": "property",
    "instance": "variable",
    "object": "variable",
    "field": "property",
    "type": "type",
}
KEYWORD = re.compile(
    r"\b(package|import|statechart|state|initial|final|parameters|entry|exit|do|end|start|"
    r"condition|events|internal|choice|deep|history|after|device|command|sensor|cell|object|"
    r"type|structure|vector|of|true|false)\b"
)


def location(occurrence: Occurrence) -> lsp.Location:
    return lsp.Location(from_fs_path(str(occurrence.path)), occurrence.range)


def definition(index: Index, path: Path, position: lsp.Position) -> lsp.Location | None:
    found = index.at(path, position)
    if found is None:
        return None
    declared = [o for o in index.references(found.key) if o.declaration]
    return location(declared[0]) if declared else None


def references(
    index: Index, path: Path, position: lsp.Position, include_declaration: bool
) -> list[lsp.Location]:
    found = index.at(path, position)
    if found is None:
        return []
    return [
        location(o) for o in index.references(found.key) if include_declaration or not o.declaration
    ]


def prepare_rename(index: Index, path: Path, position: lsp.Position) -> lsp.Range | None:
    found = index.at(path, position)
    return found.range if found is not None and found.kind in RENAMEABLE else None


def rename(
    index: Index, path: Path, position: lsp.Position, new_name: str
) -> lsp.WorkspaceEdit | None:
    """Every occurrence renamed; a statechart's file follows its chart's new name."""
    found = index.at(path, position)
    if found is None or found.kind not in RENAMEABLE:
        return None
    if not IDENTIFIER.match(new_name):
        raise ValueError(f"'{new_name}' is not a name")
    by_file: dict[Path, list[lsp.TextEdit]] = {}
    for occurrence in index.references(found.key):
        by_file.setdefault(occurrence.path, []).append(lsp.TextEdit(occurrence.range, new_name))
    changes: list[lsp.TextDocumentEdit | lsp.RenameFile] = [
        lsp.TextDocumentEdit(
            lsp.OptionalVersionedTextDocumentIdentifier(from_fs_path(str(file)), None), edits
        )
        for file, edits in sorted(by_file.items())
    ]
    declared = found.key[0]
    if found.kind == "statechart" and declared.stem == found.name:
        target = declared.with_name(new_name + declared.suffix)
        changes.append(lsp.RenameFile(from_fs_path(str(declared)), from_fs_path(str(target))))
    return lsp.WorkspaceEdit(document_changes=changes)


def document_symbols(file: FileIndex) -> list[lsp.DocumentSymbol]:
    """The declarations of a file, nested as they are in the model."""
    declared = {o.key: o for o in file.occurrences if o.declaration}

    def symbols(parent: Key | None) -> list[lsp.DocumentSymbol]:
        return [
            lsp.DocumentSymbol(
                name=declared[key].name,
                kind=SYMBOL_KINDS.get(declared[key].kind, lsp.SymbolKind.Variable),
                range=declared[key].range,
                selection_range=declared[key].range,
                children=symbols(key),
            )
            for key in file.outline.get(parent, ())
            if key in declared and key != parent
        ]

    return symbols(None)


def semantic_tokens(file: FileIndex | None, text: Text) -> lsp.SemanticTokens:
    """Names coloured by what they declare or refer to; keywords where no name is."""
    spans: dict[tuple[int, int], tuple[int, int]] = {}
    keyword = TOKEN_TYPES.index("keyword")
    for number, line in enumerate(text.lines):
        for match in KEYWORD.finditer(line):
            if not _in_comment_or_string(line, match.start()):
                found = text.range(*(text.starts[number] + at for at in match.span()))
                length = found.end.character - found.start.character
                spans[(number, found.start.character)] = (length, keyword)
    for occurrence in file.occurrences if file else ():
        start, end = occurrence.range.start, occurrence.range.end
        if start.line == end.line and end.character > start.character:
            token = TOKEN_TYPES.index(TOKEN_OF_KIND.get(occurrence.kind, "variable"))
            spans[(start.line, start.character)] = (end.character - start.character, token)
    data: list[int] = []
    previous_line = previous_start = 0
    for (line, start), (length, token) in sorted(spans.items()):
        delta_start = start - previous_start if line == previous_line else start
        data += [line - previous_line, delta_start, length, token, 0]
        previous_line, previous_start = line, start
    return lsp.SemanticTokens(data=data)


def _in_comment_or_string(line: str, column: int) -> bool:
    before = line[:column]
    return "//" in before or before.count('"') % 2 == 1
