"""SCXML as a tree of :class:`Element` s that keep their line and column, read with expat.

The reader reports every finding at its element, so it needs positions that
:mod:`xml.etree` does not keep; and it refuses a ``<!DOCTYPE>`` so that no entity of a
document is ever expanded.
"""

from __future__ import annotations

import xml.parsers.expat
from collections.abc import Iterator
from dataclasses import dataclass, field

from lightrocks.languages.scxml.markup import LR, SCXML


@dataclass(eq=False)
class Element:
    """An XML element with the 1-based line and column of its start tag."""

    namespace: str
    tag: str
    attributes: dict[str, str]
    line: int
    column: int
    children: list[Element] = field(default_factory=list)
    text: str = ""

    def get(self, name: str, default: str | None = None) -> str | None:
        return self.attributes.get(name, default)

    def lr(self, name: str) -> str | None:
        return self.attributes.get(f"{{{LR}}}{name}")

    def scxml(self) -> list[Element]:
        """The children in the SCXML namespace (or none, as some tools write)."""
        return [c for c in self.children if c.namespace in (SCXML, "")]

    def all(self, tag: str) -> list[Element]:
        return [c for c in self.scxml() if c.tag == tag]


class XmlError(Exception):
    """Text that is no well-formed XML, or holds a ``<!DOCTYPE>``, at its position."""

    def __init__(self, line: int, column: int, message: str) -> None:
        super().__init__(message)
        self.line, self.column, self.message = line, column, message


def parse_xml(text: str) -> Element:
    """The document as :class:`Element` s with 1-based lines and columns; raises
    :class:`XmlError` for text that is no well-formed XML or holds a ``<!DOCTYPE>``."""
    parser = xml.parsers.expat.ParserCreate(namespace_separator=" ")
    stack: list[Element] = []
    roots: list[Element] = []

    def split(name: str) -> tuple[str, str]:
        namespace, _, local = name.rpartition(" ")
        return namespace, local

    def start(name: str, attributes: dict[str, str]) -> None:
        namespace, tag = split(name)
        named = {}
        for key, value in attributes.items():
            space, local = split(key)
            named[f"{{{space}}}{local}" if space else local] = value
        element = Element(
            namespace, tag, named, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1
        )
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def end(_name: str) -> None:
        stack.pop()

    def characters(data: str) -> None:
        if stack:
            stack[-1].text += data

    def doctype(*_args: object) -> None:
        at = text.find("<!DOCTYPE")
        line = text.count("\n", 0, at) + 1 if at >= 0 else parser.CurrentLineNumber
        column = at - text.rfind("\n", 0, at) if at >= 0 else 1
        raise XmlError(line, column, "a <!DOCTYPE> is not read: its entities could expand")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = characters
    parser.StartDoctypeDeclHandler = doctype
    try:
        parser.Parse(text, True)
    except xml.parsers.expat.ExpatError as error:
        raise XmlError(error.lineno, error.offset + 1, f"not well-formed XML: {error}") from None
    return roots[0]


def tagged(element: Element, tag: str) -> Iterator[Element]:
    """The SCXML elements named ``tag`` below ``element``, at any depth."""
    for child in element.scxml():
        if child.tag == tag:
            yield child
        yield from tagged(child, tag)


def descendants(element: Element) -> Iterator[Element]:
    for child in element.scxml():
        yield child
        yield from descendants(child)


def state_children(element: Element | None) -> list[Element]:
    """The ``<state>``, ``<parallel>`` and ``<final>`` children of ``element``."""
    if element is None:
        return []
    return [c for c in element.scxml() if c.tag in ("state", "parallel", "final")]


def written_by_target(root: Element) -> bool:
    """Whether the LightRocks SCXML target wrote the document: it annotates it (``lr:``)."""
    annotated = any(v for k, v in root.attributes.items() if k.startswith(f"{{{LR}}}"))
    return annotated or any(
        k.startswith(f"{{{LR}}}") for e in descendants(root) for k in e.attributes
    )
