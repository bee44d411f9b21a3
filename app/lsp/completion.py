"""Completion: what may be written at the cursor, from the last index of the file."""

from __future__ import annotations

import re

from lsprotocol import types as lsp

from lightrocks.app.lsp.index import FileIndex, state_kind
from lightrocks.metamodel.units import known_units

KEYWORDS = (
    "package", "import", "statechart", "state", "initial", "final", "parameters", "entry",
    "exit", "do", "start", "end", "condition", "events", "internal", "choice", "history",
    "deep", "after", "true", "false", "device", "command", "sensor", "cell", "object",
)  # fmt: skip
ITEM_KINDS = {
    "statechart": lsp.CompletionItemKind.Class,
    "state": lsp.CompletionItemKind.EnumMember,
    "pseudostate": lsp.CompletionItemKind.EnumMember,
    "parameter": lsp.CompletionItemKind.Variable,
    "start": lsp.CompletionItemKind.Event,
    "end": lsp.CompletionItemKind.Event,
    "event": lsp.CompletionItemKind.Event,
    "instance": lsp.CompletionItemKind.Field,
    "object": lsp.CompletionItemKind.Field,
    "command": lsp.CompletionItemKind.Method,
    "sensor": lsp.CompletionItemKind.Property,
    "device": lsp.CompletionItemKind.Interface,
    "cell": lsp.CompletionItemKind.Module,
}
STIMULUS = re.compile(r"([A-Za-z_]\w*)\s*->\s*[A-Za-z_][\w.]*\s+\w*$")
MEMBER = re.compile(r"([A-Za-z_]\w*)\.\w*$")
UNIT = re.compile(r"\d\s+[\w/]*$")


def completions(
    file: FileIndex | None, prefix: str, position: lsp.Position
) -> list[lsp.CompletionItem]:
    """Outcomes after ``Source -> Target``, device members after ``instance.``, units after
    a number; otherwise the names in scope (states of the region at the cursor only) and
    the keywords."""
    file = file or FileIndex()
    stimulus = STIMULUS.search(prefix)
    if stimulus and stimulus.group(1) in file.outcomes:
        return [_item(o, "end") for o in file.outcomes[stimulus.group(1)]]
    member = MEMBER.search(prefix)
    if member:
        return [_item(n, kind) for n, kind in file.members.get(member.group(1), {}).items()]
    states = file.states_at(position)
    items = [
        _item(name, kind)
        for name, kind in file.names.items()
        if states is None or state_kind(kind) != "state" or name in states
    ]
    if UNIT.search(prefix):
        items += [lsp.CompletionItem(u, kind=lsp.CompletionItemKind.Unit) for u in known_units()]
    items += [lsp.CompletionItem(k, kind=lsp.CompletionItemKind.Keyword) for k in KEYWORDS]
    return items


def _item(name: str, kind: str) -> lsp.CompletionItem:
    return lsp.CompletionItem(
        name, kind=ITEM_KINDS.get(kind, lsp.CompletionItemKind.Reference), detail=kind
    )
