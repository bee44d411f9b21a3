"""An SCXML ``<datamodel>`` as the parameters of a LightRocks chart.

A ``<data>`` becomes a parameter, typed by ``lr:type`` or else by the syntax of its value
(LR2133); a type with a unit comes back as a Real, since SCXML carries SI values without
unit (LR2132). The generator's history variables are recognised and left out.
"""

from __future__ import annotations

import ast as py

from lightrocks.languages.scxml.read_context import DROPPED, RENAMED, ReadContext, Refused
from lightrocks.languages.scxml.read_expressions import ExpressionReader
from lightrocks.languages.scxml.read_names import NameReader
from lightrocks.languages.scxml.xml_tree import Element, tagged
from lightrocks.metamodel import ast
from lightrocks.workbench.diagnostics import Severity

_TYPES = {bool: "Boolean", int: "Integer", float: "Real", str: "String"}


class DataReader:
    """The parameters of one document, registering their variables in the context."""

    def __init__(
        self, context: ReadContext, names: NameReader, expressions: ExpressionReader
    ) -> None:
        self.context = context
        self.names = names
        self.expressions = expressions

    def parameters(self, root: Element) -> list[ast.Parameter]:
        found: list[ast.Parameter] = []
        tops = root.all("datamodel")
        for datamodel in tagged(root, "datamodel"):
            if datamodel not in tops:
                self.context.refuse(
                    datamodel,
                    "a <datamodel> inside a state: LightRocks' parameters belong to the chart",
                )
                continue
            for data in datamodel.scxml():
                if data.tag != "data":
                    self.context.outside(data, "in <datamodel>")
                    continue
                parameter = self._data(data)
                if parameter is not None:
                    found.append(parameter)
        return found

    def _data(self, data: Element) -> ast.Parameter | None:
        identifier = data.get("id") or ""
        if data.lr("helper") == "history":
            self.context.flags.add(identifier)
            return None
        if data.get("src"):
            self.context.refuse(data, "<data src>: a value read from elsewhere")
            return None
        name = data.lr("name") or identifier
        name = self.names.rename(data, name) if name else "v"
        self.context.variables[identifier] = name
        text = data.get("expr") or (data.text.strip() or None)
        default = None
        if text is not None:
            try:
                default = self.expressions.expression(text, data)
            except Refused as problem:
                self.context.refused(problem)
                return None
        kind = data.lr("type") or _type_of(text)
        if kind is None:
            self.context.refuse(
                data,
                f"the type of '{identifier}' is not known: give it a value (a number, a "
                "Boolean, a string) or lr:type",
            )
            return None
        if not data.lr("type"):
            self.context.finding(
                data, RENAMED, Severity.INFO, f"'{name}' is declared {kind}, as its value"
            )
        elif kind not in _TYPES.values():
            self.context.finding(
                data,
                DROPPED,
                Severity.WARNING,
                f"'{name}' is a {kind}, whose unit SCXML does not carry: it is declared Real, "
                "and its values are SI values without unit",
            )
            kind = "Real"
        return ast.Parameter(kind, name, default)


def _type_of(text: str | None) -> str | None:
    """The type of a literal value (``-2`` Integer, ``0.5`` Real …), read from its syntax."""
    if text is None:
        return None
    try:
        node = py.parse(text.strip(), mode="eval").body
    except SyntaxError:
        return None
    if isinstance(node, py.UnaryOp) and isinstance(node.op, py.USub | py.UAdd):
        node = node.operand
        if isinstance(node, py.Constant) and isinstance(node.value, bool):
            return None
    return _TYPES.get(type(node.value)) if isinstance(node, py.Constant) else None
