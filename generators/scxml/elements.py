"""The small SCXML elements the writer builds in many places: a ``<transition>`` and the
``<assign>`` of a LightRocks assignment."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from lightrocks.generators.scxml.expressions import Translator, Untranslatable
from lightrocks.languages.scxml.markup import lr, q
from lightrocks.metamodel import ast


def transition(
    event: str | None,
    cond: str | None,
    target: str | None,
    content: list[ET.Element],
    internal: bool = False,
    helper: str = "",
) -> ET.Element:
    """A ``<transition>``; ``helper`` marks one of the generator's own (``lr:helper``)."""
    element = ET.Element(q("transition"))
    if event:
        element.set("event", event)
    if cond:
        element.set("cond", cond)
    if target:
        element.set("target", target)
        if internal:
            element.set("type", "internal")
    if helper:
        element.set(lr("helper"), helper)
    element.extend(content)
    return element


def assign(location: str, expr: str) -> ET.Element:
    return ET.Element(q("assign"), {"location": location, "expr": expr})


def statement(translate: Translator, node: ast.Statement) -> ET.Element:
    """The ``<assign>`` of an assignment; any other statement is :class:`Untranslatable`."""
    if isinstance(node, ast.Assignment):
        location = translate.variable(node.target)
        return assign(location, translate.value(node.value))
    raise Untranslatable(
        getattr(node, "position", ast.NOWHERE),
        "a statement other than an assignment: SCXML's data model here runs no command or function",
    )
