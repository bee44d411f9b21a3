"""LightRocks names for the ids of an SCXML document.

An SCXML id is an XML name (``Lamp-On``, ``s.1``); a LightRocks name is an identifier that
is no keyword, unique among its siblings. A state keeps the part of its id after its
parent's (the ids the target writes are paths), else its id, else an identifier made of it;
every name the reader has to make is reported (LR2133).
"""

from __future__ import annotations

import re

from lightrocks.languages.scxml.read_context import RENAMED, ReadContext
from lightrocks.languages.scxml.xml_tree import Element
from lightrocks.workbench.diagnostics import Severity

KEYWORDS = {
    "choice", "condition", "deep", "do", "end", "entry", "events", "exit", "final", "history",
    "import", "initial", "internal", "invariant", "package", "parameters", "region", "start",
    "state", "statechart", "true", "false", "after", "in", "error", "timeout", "preempted",
}  # fmt: skip
IDENTIFIER = re.compile(r"[^\W\d]\w*")


def is_name(text: str) -> bool:
    """``text`` can be a LightRocks name as it is."""
    return bool(IDENTIFIER.fullmatch(text)) and text not in KEYWORDS


def identifier(text: str) -> str:
    """A LightRocks name made of ``text``."""
    name = re.sub(r"\W", "_", text)
    if not name or not IDENTIFIER.fullmatch(name):
        name = "s_" + name
    return f"{name}_" if name in KEYWORDS else name


class NameReader:
    """The names of one document's chart, states and parameters."""

    def __init__(self, context: ReadContext) -> None:
        self.context = context
        self._taken: dict[str, set[str]] = {}  # scope id -> the names of its body

    def rename(self, element: Element, name: str) -> str:
        """``name`` or, when it cannot be a LightRocks name, one made of it."""
        if is_name(name):
            return name
        renamed = identifier(name)
        self.context.finding(element, RENAMED, Severity.INFO, f"'{name}' is named '{renamed}'")
        return renamed

    def state(self, scope: str, element: Element) -> str:
        """The name of the state ``element`` in the body of the state with id ``scope``."""
        state_id = element.get("id")
        prefix = f"{scope}-" if scope else ""
        own = state_id[len(prefix) :] if prefix and state_id.startswith(prefix) else ""
        if own and is_name(own):
            name = own
        elif is_name(state_id):
            name = state_id
        else:
            tail = state_id.rsplit("-", 1)[1] if "-" in state_id else state_id
            name = identifier(tail if self.context.generated else state_id)
            self.context.finding(
                element, RENAMED, Severity.INFO, f"state '{state_id}' is named '{name}'"
            )
        taken = self._taken.setdefault(scope, set())
        base, number = name, 1
        while name in taken:
            number += 1
            name = f"{base}_{number}"
        taken.add(name)
        return name
