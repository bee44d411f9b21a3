"""Models at the limits get findings, never internal errors: a number literal beyond what a
Real holds, a flat sum of many terms (accepted), nesting too deep (said of what is nested),
syntax errors in the words a user types, a file over the size limit."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lightrocks.app.cli import main
from lightrocks.metamodel.grammar import SyntaxProblem
from lightrocks.workbench.depth import MAX_DEPTH
from lightrocks.workbench.languages import language_for

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").rglob("*.lr")) + sorted((ROOT / "examples").rglob("*.lrd"))


def chart(name: str, parameters: str = "", body: str = "initial state A;") -> str:
    return (
        f"package t;\n\nstatechart {name} {{\n  parameters {{\n    {parameters}\n  }}\n"
        f"  {body}\n}}\n"
    )


def write(root: Path, name: str, text: str) -> Path:
    (root / "t").mkdir(parents=True, exist_ok=True)
    path = root / "t" / name
    path.write_text(text, encoding="utf-8")
    return path


def said(capsys) -> str:
    captured = capsys.readouterr()
    return " ".join((captured.out + captured.err).split())


@pytest.mark.parametrize("literal", ["1e999", "-1e999", "1e307 min", "2e308 mm"])
def test_a_number_beyond_a_real_is_a_finding(tmp_path: Path, capsys, literal: str) -> None:
    kind = {"min": "Duration", "mm": "Length"}.get(literal.rpartition(" ")[2], "Real")
    model = write(tmp_path, "Big.lr", chart("Big", f"{kind} big = {literal};"))
    assert main(["check", str(model)]) == 1
    out = said(capsys)
    assert "Big.lr:5:" in out
    assert f"error LR0302: '{literal}' is beyond the largest number a Real holds" in out
    assert main(["run", str(model)]) == 1
    assert "inf" not in said(capsys).replace("infinite", "")


def test_a_number_beyond_a_real_in_a_domain_is_a_finding(tmp_path: Path, capsys) -> None:
    domain = (
        "package t;\n\ndevice Arm {\n  command move(Length x = 1e999 m);\n"
        "  sensor Boolean done;\n}\n"
    )
    model = write(tmp_path, "Cell.lrd", domain)
    assert main(["check", str(model)]) == 1
    assert "Cell.lrd:4:27: error LR0404: '1e999 m' is beyond the largest number" in said(capsys)


@pytest.mark.parametrize("terms", [150, MAX_DEPTH - 10])
def test_a_flat_sum_of_many_terms_is_accepted(tmp_path: Path, capsys, terms: int) -> None:
    total = " + ".join(["x"] * terms)
    guard = " || ".join(["x > 2"] * terms)
    body = f"initial state A;\n  final state B;\n  A -> B [{guard} || y > 1] go;"
    text = chart("Wide", f"Real x = 1;\n    Real y = {total};", body)
    model = write(tmp_path, "Wide.lr", text)
    assert main(["check", str(model)]) == 0
    assert main(["run", str(model), "--events", "go"]) == 0
    assert "outcome: B" in said(capsys)
    for target in ("python", "dot"):
        assert main(["generate", str(model), "--target", target, "-o", str(tmp_path / target)]) == 0


def test_nested_states_are_named_as_what_nests_too_deeply(tmp_path: Path, capsys) -> None:
    body = "initial state A;"
    for level in range(MAX_DEPTH + 20):
        body = f"initial state S{level} {{ {body} }}"
    model = write(tmp_path, "Deep.lr", chart("Deep", body=body))
    assert main(["check", str(model)]) == 1
    out = said(capsys)
    assert "LR0001: states nested too deeply" in out and "expression" not in out


def test_a_nested_expression_is_named_as_such(tmp_path: Path, capsys) -> None:
    deep = "(" * 120 + "1" + ")" * 120
    model = write(tmp_path, "Deep.lr", chart("Deep", f"Real x = {deep};"))
    assert main(["check", str(model)]) == 1
    assert "LR0001: expression nested too deeply" in said(capsys)


INTERNALS = re.compile(r"RegExMatch|StrMatch|Sequence|OrderedChoice|\bEOF\b|\(\?|\\b")
JUNK = ["garbage", "{", "}", ";", "->", "(", "<<", "1mm", "[", "]", "=", "/", "@", "state"]


@settings(max_examples=200)
@given(
    number=st.integers(min_value=0, max_value=len(EXAMPLES) - 1),
    where=st.floats(min_value=0, max_value=1),
    junk=st.sampled_from(["", *JUNK]),
    cut=st.booleans(),
)
def test_syntax_errors_speak_in_the_words_a_user_types(number, where, junk, cut) -> None:
    path = EXAMPLES[number]
    text = path.read_text(encoding="utf-8")
    at = int(where * len(text))
    mutated = text[:at] if cut else text[:at] + f" {junk} " + text[at + 1 :]
    try:
        language_for(path.suffix).parse(mutated, str(path))
    except SyntaxProblem as problem:
        assert not INTERNALS.search(problem.message), problem.message


@pytest.mark.parametrize("command", ["check", "fmt"])
def test_a_file_over_the_size_limit_is_a_finding(tmp_path, capsys, monkeypatch, command) -> None:
    model = write(tmp_path, "S.lr", chart("S"))
    monkeypatch.setenv("LIGHTROCKS_MODEL_BYTES", "20")
    assert main([command, str(model)]) == 1
    out = said(capsys)
    assert "S.lr:1:1: error LR0004: the file is" in out and "LIGHTROCKS_MODEL_BYTES" in out
    monkeypatch.delenv("LIGHTROCKS_MODEL_BYTES")
    assert main(["check", str(model)]) == 0


def test_the_default_size_limit_refuses_a_huge_file(tmp_path: Path, capsys) -> None:
    model = write(tmp_path, "Huge.lr", chart("Huge"))
    with model.open("a") as stream:
        stream.truncate(17 * 1024 * 1024)  # sparse: nothing of it is written
    assert main(["check", str(model)]) == 1
    assert "over the limit of 16,777,216" in said(capsys)
