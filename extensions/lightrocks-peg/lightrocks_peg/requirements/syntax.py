"""The ``requirement`` element: its AST node, how a parse node becomes one, how it prints."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lightrocks.metamodel import ast
from lightrocks.metamodel.grammar import GrammarExtension
from lightrocks.metamodel.printer import Writer, string

GRAMMAR = GrammarExtension(
    rules=Path(__file__).with_name("requirements.tx").read_text(encoding="utf-8"),
    hooks=(("ElementExtension", ("Requirement",)),),
)


@dataclass(frozen=True)
class Requirement:
    name: str
    text: str
    outcome: str = ""  # the outcome that verifies it, or empty
    position: ast.Position = field(default=ast.NOWHERE, compare=False, repr=False)


def build(converter: Any, node: Any) -> Requirement:
    return Requirement(node.name, node.text, node.outcome or "", converter.position(node))


def print_requirement(writer: Writer, node: Requirement) -> None:
    writer.item(node.position, "requirement")
    verifies = f" verifies {node.outcome}" if node.outcome else ""
    text = f"requirement {node.name} {string(node.text)}{verifies};"
    writer.line([text], node.position.line)
