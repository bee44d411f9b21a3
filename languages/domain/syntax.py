"""Concrete syntax of domain interfaces (``.lrd``): grammar and AST conversion."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import Converter
from lightrocks.metamodel.grammar import parse, paused_gc

GRAMMAR = Path(__file__).with_name("domain.tx")
FRAGMENTS = ("common", "expressions")


class DomainConverter(Converter):
    def rule_DomainUnit(self, node: Any) -> ast.DomainUnit:
        package, where = self.package(node.package)
        return ast.DomainUnit(
            package, self.imports(node.imports), self.many(node.declarations), self.file, where
        )

    def rule_QuantityType(self, node: Any) -> ast.QuantityType:
        return ast.QuantityType(node.name, node.unit or "", self.position(node))

    def rule_VectorType(self, node: Any) -> ast.VectorType:
        return ast.VectorType(
            node.name, node.element or "", node.size or 0, tuple(node.units), self.position(node)
        )

    def rule_StructureType(self, node: Any) -> ast.StructureType:
        fields = tuple(ast.Field(f.type, f.name, self.position(f)) for f in node.fields)
        return ast.StructureType(node.name, fields, self.position(node))

    def rule_Device(self, node: Any) -> ast.Device:
        return ast.Device(
            node.name,
            self.many(node.members),
            self.stereotypes(node.stereotypes),
            self.position(node),
        )

    def rule_Command(self, node: Any) -> ast.Command:
        return ast.Command(
            node.name, self.many(node.parameters), node.returns or "", self.position(node)
        )

    def rule_CommandParameter(self, node: Any) -> ast.CommandParameter:
        return ast.CommandParameter(
            node.type,
            node.name,
            self.optional(node.default),
            self.optional(node.low),
            self.optional(node.high),
            self.position(node),
        )

    def rule_Sensor(self, node: Any) -> ast.Sensor:
        return ast.Sensor(
            node.type,
            node.name,
            self.position(node),
            self.optional(node.start),
            self.optional(node.low),
            self.optional(node.high),
        )

    def rule_Cell(self, node: Any) -> ast.Cell:
        return ast.Cell(
            node.name,
            self.many(node.members),
            self.stereotypes(node.stereotypes),
            self.position(node),
        )

    def rule_SceneObject(self, node: Any) -> ast.SceneObject:
        return ast.SceneObject(node.name, self.many(node.attributes), self.position(node))

    def rule_ObjectAttribute(self, node: Any) -> ast.Parameter:
        return ast.Parameter(
            node.type,
            node.name,
            self.optional(node.default),
            self.position(node),
            self.optional(node.low),
            self.optional(node.high),
        )

    def rule_DeviceInstance(self, node: Any) -> ast.DeviceInstance:
        return ast.DeviceInstance(node.name, node.type, self.position(node))


def parse_domain(text: str, file: str) -> ast.DomainUnit:
    """Parse one ``.lrd`` text; raises ``metamodel.grammar.SyntaxProblem``."""
    with paused_gc():
        tree = parse(GRAMMAR, FRAGMENTS, text, file)
        if isinstance(tree, str):  # textX yields '' for a file with nothing but comments
            return ast.DomainUnit("", (), (), file, ast.Position(file, 1, 1))
        return DomainConverter(text, file).convert(tree)
