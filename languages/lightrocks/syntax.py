"""Concrete syntax of LightRocks action components (``.lr``): grammar and AST conversion."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import Converter
from lightrocks.metamodel.grammar import parse, paused_gc

GRAMMAR = Path(__file__).with_name("lightrocks.tx")
FRAGMENTS = ("common", "statecharts", "expressions")


class LightRocksConverter(Converter):
    def rule_LightRocksUnit(self, node: Any) -> ast.StatechartUnit:
        package, where = self.package(node.package)
        return ast.StatechartUnit(
            package, self.imports(node.imports), self.convert(node.statechart), self.file, where
        )

    def rule_ParameterBlock(self, node: Any) -> ast.ParameterBlock:
        return ast.ParameterBlock(self.many(node.parameters), self.position(node))

    def rule_Parameter(self, node: Any) -> ast.Parameter:
        return ast.Parameter(node.type, node.name, self.optional(node.default), self.position(node))

    def rule_Condition(self, node: Any) -> ast.Condition:
        return ast.Condition(
            node.kind, node.name, self.optional(node.expression), self.position(node)
        )


def parse_statechart(text: str, file: str) -> ast.StatechartUnit:
    """Parse one ``.lr`` text; raises ``metamodel.grammar.SyntaxProblem``."""
    with paused_gc():
        tree = parse(GRAMMAR, FRAGMENTS, text, file)
        return LightRocksConverter(text, file).convert(tree)
