"""Syntax of language extensions in the SFC and PLCopen targets (``sfc_iec61131.extensions``):
rendered through ``sfc/<Node>.jinja``, refused where no template maps it.

Regression: both targets refused every extension node, so no model of the worked package
reached a PLC (its units are now judged by MatIEC and Beremiz: ``test_matiec_extension``,
``test_beremiz``), and one in an elemental action crashed instead. The mapping is tried on
nodes of a stand-in extension in-process, and on the worked package installed.
"""

from __future__ import annotations

import re
import shutil
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import jinja2
import pytest
from extension_units import EXAMPLES, MODELS, installed

from lightrocks.generators.sfc_iec61131.expressions import Scope
from lightrocks.generators.sfc_iec61131.extensions import Extensions
from lightrocks.languages.domain.types import INTEGER, LENGTH_T, Type
from lightrocks.metamodel import ast
from lightrocks.workbench.generators import GenerationError

HERE = ast.Position("Cell.lr", 7, 3)


@dataclass(frozen=True)
class Limit(ast.ExtensionNode):
    """``limit(value, low, high)``, of the type of ``value``."""

    value: ast.Expression
    low: ast.Expression
    high: ast.Expression
    position: ast.Position = field(default=HERE, compare=False)

    def text(self, expression: Callable[[ast.Expression], str]) -> str:
        return f"limit({expression(self.value)}, {expression(self.low)}, {expression(self.high)})"

    def infer(self, infer: Callable[[ast.Expression], Any]) -> Any:
        return infer(self.value)


@dataclass(frozen=True)
class Tally(ast.ExtensionNode):
    """``tally target;``: one more, and the time of the last one."""

    target: ast.Expression
    position: ast.Position = field(default=HERE, compare=False)

    def text(self, expression: Callable[[ast.Expression], str]) -> str:
        return f"tally {expression(self.target)};"

    def infer(self, infer: Callable[[ast.Expression], Any]) -> None:
        infer(self.target)


@dataclass(frozen=True)
class Note:
    """An element: a line of documentation."""

    text: str
    position: ast.Position = field(default=HERE, compare=False)


TEMPLATES = {
    "sfc/Limit.jinja": "LIMIT({{ code(node.low, like=node) }}, {{ code(node.value) }}, "
    "{{ code(node.high, like=node) }})",
    "sfc/Tally.jinja": "{{ target(node.target) }} := {{ code(node.target) }} + 1;\n"
    "IF {{ target(node.target) }} > 9 THEN\n  last := {{ 'tally' | string }};\nEND_IF;\n",
    "sfc/Note.jinja": "{% for note in extension.elements %}note: {{ note.text }}\n{% endfor %}",
}
TYPES: dict[str, Type] = {"gap": LENGTH_T, "tries": INTEGER}
GAP, TRIES = ast.Name("gap"), ast.Name("tries")


def _infer(expression: ast.Expression) -> Type:
    """Types as the typing pass gives them, for the names and nodes these tests use."""
    match expression:
        case ast.Name(name=name):
            return TYPES[name]
        case ast.Quantity():
            return INTEGER if expression.integral else LENGTH_T
        case ast.ExtensionNode():
            return expression.infer(_infer)
    raise AssertionError(expression)


def _scope(extensions: Extensions) -> Scope:
    return Scope({}, _infer, lambda device, name: name, str, extensions.expression)


@pytest.fixture
def extensions() -> Extensions:
    return Extensions(jinja2.Environment(loader=jinja2.DictLoader(TEMPLATES)))


def _number(value: int) -> ast.Quantity:
    return ast.Quantity(value, text=str(value))


def test_an_expression_is_its_templates_text_as_one_operand(extensions: Extensions) -> None:
    limit = Limit(GAP, _number(0), _number(1))
    text = _scope(extensions).compile(ast.Binary("*", limit, _number(2)))
    assert text == "(LIMIT(0.0, gap, 1.0)) * 2.0"  # Integers meet the Length as REAL


def test_a_sub_expression_keeps_its_type_unless_asked(extensions: Extensions) -> None:
    limit = Limit(TRIES, _number(0), _number(3))
    assert _scope(extensions).compile(limit) == "(LIMIT(0, tries, 3))"


def test_a_statement_is_its_templates_lines(extensions: Extensions) -> None:
    lines = extensions.statement(Tally(TRIES), _scope(extensions))
    assert lines == [
        "tries := tries + 1;",
        "IF tries > 9 THEN",
        "  last := 'tally';",
        "END_IF;",
    ]


def test_only_a_name_or_member_is_assigned(extensions: Extensions) -> None:
    with pytest.raises(GenerationError, match="cannot assign to this expression"):
        extensions.statement(Tally(_number(1)), _scope(extensions))


def test_elements_are_documentation_that_cannot_end_the_comment(extensions: Extensions) -> None:
    lines = extensions.documentation([Note("the gap *) stays"), Note("(* tight *)")])
    assert lines == ["note: the gap * ) stays", "note: ( * tight * )"]


@pytest.mark.parametrize("environment", [None, jinja2.Environment(loader=jinja2.DictLoader({}))])
def test_a_node_without_template_is_refused_where_it_stands(
    environment: jinja2.Environment | None,
) -> None:
    unit = ast.ExpressionStatement(Limit(GAP, GAP, GAP))
    with pytest.raises(GenerationError) as refused:
        Extensions(environment).refuse_unmapped(unit)
    assert str(refused.value) == (
        "Cell.lr:7:3: the SFC target does not map 'Limit', which a language extension adds "
        "(no template sfc/Limit.jinja)"
    )


def test_an_actions_extension_statement_is_mapped_or_refused_at_its_place(
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    """An elemental action is inlined, not built as a block, so the refusal of its chart's
    extension syntax never saw it: a ``count`` in its exit statements ended in an
    AttributeError. Now it is mapped by its template (a node without one is refused where it
    stands: ``test_a_node_without_template_is_refused_where_it_stands``)."""
    environment, _ = installed(tmp_path_factory)
    models = tmp_path_factory.mktemp("peg-models")
    shutil.copytree(MODELS, models, dirs_exist_ok=True)
    lift = models / "peg" / "actions" / "Lift.lr"
    text = lift.read_text().replace("m/s;\n", "m/s;\n    Integer lifts = 0;\n", 1)
    lift.write_text(text.replace("  end condition", "  exit / { count lifts; }\n\n  end condition"))
    pick = models / "peg" / "skills" / "PickPeg.lr"
    pick.write_text(re.sub(r"  requirement .*\n", "", pick.read_text()))
    generate = ["generate", str(pick), "--path", str(models), "--path", str(EXAMPLES)]
    out = tmp_path_factory.mktemp("out")
    for target in ("sfc", "plcopen"):  # through the package's own sfc/Count.jinja
        mapped = environment.lightrocks(*generate, "--target", target, "-o", str(out / target))
        assert mapped.returncode == 0, mapped.stderr
        assert "internal error" not in mapped.stderr
    assert "Up_lifts := Up_lifts + 1;" in (out / "sfc" / "PickPeg.st").read_text()
