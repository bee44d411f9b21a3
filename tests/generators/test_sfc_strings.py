"""String literals inside generated Structured Text are data, never structure: a parenthesis
or a comma in a string does not group a condition or split an initial value, a comment
delimiter is escaped, and a string longer than a PLC's STRING is a finding at its place."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate
from lxml import etree

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.generators.sfc_iec61131.conditions import balanced, group, negate
from lightrocks.generators.sfc_iec61131.expressions import string_literal
from lightrocks.workbench.generators import GenerationError

PAREN = """statechart Paren {
  parameters {
    String s = "(";
    String t = ")";
  }

  initial state A;
  state B;
  state C;
  choice J;

  A -> J go [s == "("];
  J -> B [t == ")"];
  J -> C;
}
"""

DESK = """package q;

<<scene="none">> cell Desk {
  object note {
    String label = "it's, (fine";
    Integer count = 1;
  }
}
"""

READ = """package q;

statechart Read {
  initial state A;
  final state B;
  A -> B go;
}
"""


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("(s = '(')", True),
        ("s = '(') AND (t = ')'", False),
        ("a = '$'(') AND (b = ')'", False),
        ("a = '$$') AND (b = '('", False),
        ('w = "(" AND x', True),
    ],
)
def test_parentheses_in_string_literals_are_not_structure(text: str, expected: bool) -> None:
    assert balanced(text) is expected


def test_a_conjunction_of_string_comparisons_is_negated_whole() -> None:
    both = "(s = '(') AND (t = ')')"
    assert group("(s = '(')") == "(s = '(')"
    assert negate(both) == f"NOT ({both})"


def test_a_choice_after_a_postcondition_on_strings_keeps_its_groups(tmp_path: Path) -> None:
    """The branches of a choice checked after a postcondition exclude the earlier ones as a
    whole: ``NOT ((post) AND (guard))``, not ``NOT (post) AND (guard)``."""
    model = tmp_path / "Paren.lr"
    model.write_text(PAREN)
    text = generate("sfc", [model], search=[tmp_path])["Paren.st"]
    assert not check_sfc(text)
    assert "(s_1 = '(') AND (NOT ((s_1 = '(') AND (t_1 = ')')))" in text
    assert "((s_1 = '('))" not in text


def test_a_structure_initialiser_splits_outside_its_strings(tmp_path: Path) -> None:
    package = tmp_path / "q"
    package.mkdir()
    (package / "Desk.lrd").write_text(DESK)
    (package / "Read.lr").write_text(READ)
    text = generate("plcopen", [package / "Read.lr"], search=[tmp_path])["Read.xml"]
    document = etree.fromstring(text.encode())
    ns = {"p": "http://www.plcopen.org/xml/tc6_0201"}
    values = document.findall(".//p:globalVars/p:variable/p:initialValue/p:structValue/p:value", ns)
    found = {v.get("member"): v.find("p:simpleValue", ns).get("value") for v in values}
    assert found == {"label": "'it$'s, (fine'", "count": "1"}


@pytest.mark.parametrize(
    ("value", "text"),
    [
        ("a (* b *)", "'a $28* b $2A)'"),
        ("(*)", "'$28$2A)'"),
        ("a*b (c) *", "'a*b (c) *'"),
    ],
)
def test_comment_delimiters_in_strings_are_escaped(value: str, text: str) -> None:
    """MatIEC's forward-reference pass (``-p``, as Beremiz builds) reads ``(*`` in a string
    as the start of a comment."""
    assert string_literal(value) == text


def test_a_string_longer_than_a_plc_string_is_a_finding_at_its_place(tmp_path: Path) -> None:
    model = tmp_path / "Paren.lr"
    model.write_text(PAREN.replace('String t = ")";', f'String t = "{"x" * 255}";'))
    with pytest.raises(GenerationError, match=rf"^{model}:4:16: a string of 255 bytes"):
        generate("sfc", [model], search=[tmp_path])
    model.write_text(PAREN.replace('String t = ")";', f'String t = "{"x" * 254}";'))
    assert generate("sfc", [model], search=[tmp_path])


@pytest.mark.parametrize(
    "literal", ["'(* x'", "'x *)'", "'" + "x" * 255 + "'", "'" + "$0A" * 255 + "'"]
)
def test_the_checker_refuses_strings_matiec_cannot_read(tmp_path: Path, literal: str) -> None:
    model = tmp_path / "Paren.lr"
    model.write_text(PAREN)
    text = generate("sfc", [model], search=[tmp_path])["Paren.st"]
    assert not check_sfc(text)
    problems = check_sfc(text.replace("'('", literal))
    assert "string-literal" in {p.rule for p in problems}, problems
