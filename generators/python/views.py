"""The views the Python templates render: a module, its classes and their methods, and
the text helpers that write model values into them."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Method:
    name: str
    parameters: str
    returns: str
    body: list[str]


@dataclass
class ExtensionView:
    """Elements of one language-extension type, rendered by that extension's template; the
    template sees them as ``extension.elements`` (AST nodes) and indents its lines by 4."""

    template: str
    elements: list[object]


@dataclass
class ClassView:
    name: str
    bases: list[str]
    doc: str
    constants: list[str] = field(default_factory=list)
    fields: list[str] = field(default_factory=list)
    methods: list[Method] = field(default_factory=list)
    tables: list[str] = field(default_factory=list)
    extensions: list[ExtensionView] = field(default_factory=list)


@dataclass
class ModuleView:
    source: str
    imports: list[str] = field(default_factory=list)
    classes: list[ClassView] = field(default_factory=list)
    typing_names: list[str] = field(default_factory=list)


def tuple_code(items) -> str:
    items = list(items)
    if not items:
        return "()"
    return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"


def docstring_text(text: str) -> str:
    """Model-derived text for a docstring: printable, no quotes or backslashes."""
    return "".join(c if c.isprintable() and c not in "\"'\\" else "_" for c in text)
