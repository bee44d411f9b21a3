"""String literals inside generated Structured Text are data, never structure: a parenthesis
or a comma in a string does not group a condition or split an initial value."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import generate
from lxml import etree

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.generators.sfc_iec61131.conditions import balanced, group, negate

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
