"""The model objects built from the parse tree are the ones textX's own builder makes."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from peg_models import PEG, ROOT, model_files, peg_grammars
from textx import metamodel_from_str

from lightrocks.languages.domain import syntax as domain
from lightrocks.languages.lightrocks import syntax as lightrocks
from lightrocks.metamodel.grammar import parse, textx_metamodel
from lightrocks.metamodel.objects import ObjectBuilder, eligible


def difference(ours: Any, textx: Any, path: str = "model") -> str | None:
    """Where two object graphs differ (classes by name, attributes, positions, parents)."""
    if type(ours).__name__ != type(textx).__name__:
        return f"{path}: {type(ours).__name__} != {type(textx).__name__}"
    if isinstance(ours, list):
        if len(ours) != len(textx):
            return f"{path}: {len(ours)} items != {len(textx)}"
        for index, (a, b) in enumerate(zip(ours, textx, strict=True)):
            if found := difference(a, b, f"{path}[{index}]"):
                return found
        return None
    if not hasattr(type(ours), "_tx_attrs"):
        return None if ours == textx else f"{path}: {ours!r} != {textx!r}"
    if (ours._tx_position, ours._tx_position_end) != (textx._tx_position, textx._tx_position_end):
        return f"{path}: at {ours._tx_position} != {textx._tx_position}"
    ours_parent, textx_parent = getattr(ours, "parent", None), getattr(textx, "parent", None)
    if getattr(ours_parent, "_tx_position", None) != getattr(textx_parent, "_tx_position", None):
        return f"{path}: another parent"
    for name in type(ours)._tx_attrs:
        if found := difference(getattr(ours, name), getattr(textx, name), f"{path}.{name}"):
            return found
    return None


@pytest.mark.parametrize("file", model_files(), ids=lambda f: str(f.relative_to(ROOT)))
def test_every_model_file_gives_textx_objects(file: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    language = lightrocks if file.suffix == ".lr" else domain
    extensions = lightrocks.grammar_extensions() if file.suffix == ".lr" else ()
    if file.suffix == ".lr" and file.is_relative_to(PEG):
        extensions += peg_grammars(monkeypatch)
    text = file.read_text(encoding="utf-8")
    ours = parse(language.GRAMMAR, language.FRAGMENTS, text, str(file), extensions)
    metamodel = textx_metamodel(language.GRAMMAR, language.FRAGMENTS, extensions)
    assert eligible(metamodel)
    assert difference(ours, metamodel.model_from_str(text, file_name=str(file))) is None


GRAMMAR = r"""
Model: 'model' name=QualifiedName flags*=Flag[','] ('uses' uses+=ID[','])? parts*=Part;
QualifiedName: ID ('.' ID)*;
Flag: 'fast' | 'safe';
Part: Whole | Piece;
Whole: (hidden?='hidden') 'whole' name=ID ('=' size=INT)? label=STRING? ';';
Piece: 'piece' sizes+=Size parts*=Part 'end';
Size: value=INT unit=/[a-z]+/;
"""

TEXT = """model a . b.c fast , safe uses x, y
  hidden whole w = 3 "it's \\"here\\"";
  piece 1 mm 2 cm whole v; piece 3 m end end
"""


def test_every_kind_of_assignment_and_rule() -> None:
    metamodel = metamodel_from_str(GRAMMAR, autokwd=True)
    parser = metamodel._parser_blueprint.clone()
    parser.parse(TEXT)
    ours = ObjectBuilder(metamodel).build(parser.parse_tree[0])
    textx = metamodel.model_from_str(TEXT)
    assert difference(ours, textx) is None
    assert ours.name == "a.b.c" and ours.flags == ["fast", "safe"] and ours.uses == ["x", "y"]
    whole = ours.parts[0]
    assert (whole.hidden, whole.size, whole.label) == (True, 3, 'it\'s "here"')
    assert ours.parts[1].parts[0].hidden is False
    assert ours.parts[1].parts[0].parent is ours.parts[1]


def test_a_grammar_with_references_is_left_to_textx() -> None:
    metamodel = metamodel_from_str("Model: things*=Thing; Thing: name=ID ('->' to=[Thing])?;")
    assert not eligible(metamodel)
    assert eligible(metamodel_from_str("Model: things*=Thing; Thing: name=ID;"))
