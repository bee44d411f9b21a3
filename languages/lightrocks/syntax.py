"""Concrete syntax of LightRocks action components (``.lr``): grammar and AST conversion.

The grammar is composed with the registered extensions of the language (see
:mod:`workbench.extensions`), so an installed extension's syntax is read everywhere.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.convert import Converter
from lightrocks.metamodel.grammar import GrammarExtension, parse, paused_gc, textx_metamodel
from lightrocks.workbench.extensions import extensions_of

GRAMMAR = Path(__file__).with_name("lightrocks.tx")
FRAGMENTS = ("common", "statecharts", "expressions")
LITERAL_GRAMMAR = Path(__file__).with_name("literal.tx")


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

    def rule_Property(self, node: Any) -> ast.Property:
        formula = node.formula
        parts = [formula.expression, getattr(formula, "response", None)]
        parts += list(getattr(formula, "others", ()))
        outcome = getattr(formula, "outcome", "")
        return ast.Property(
            node.name,
            formula.kind,
            tuple(self.convert(p) for p in parts if p is not None and p != ""),
            outcome,
            self.position(node),
            self.position(formula) if outcome else ast.NOWHERE,
        )


def grammar_extensions() -> tuple[GrammarExtension, ...]:
    return tuple(e.grammar for e in extensions_of("lightrocks"))


def metamodel():
    """The textX metamodel of ``.lr`` files, with the syntax of every installed extension."""
    return textx_metamodel(GRAMMAR, FRAGMENTS, grammar_extensions())


def parse_statechart(text: str, file: str) -> ast.StatechartUnit:
    """Parse one ``.lr`` text; raises ``metamodel.grammar.SyntaxProblem``."""
    extensions = extensions_of("lightrocks")
    rules = {rule: build for e in extensions for rule, build in e.build.items()}
    with paused_gc():
        tree = parse(GRAMMAR, FRAGMENTS, text, file, grammar_extensions())
        return LightRocksConverter(text, file, rules).convert(tree)


def parse_literal(text: str, shown: str) -> ast.Expression:
    """One value written outside a model, read by the language's own expression syntax (the
    whole text must be one expression); raises ``metamodel.grammar.SyntaxProblem``."""
    with paused_gc():
        tree = parse(LITERAL_GRAMMAR, ("common", "expressions"), text, shown)
        return LightRocksConverter(text, shown).convert(tree.value)
