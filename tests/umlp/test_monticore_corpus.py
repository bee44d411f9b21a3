"""The local judge of the UML/P language: MontiCore's own statechart corpus.

The corpus is the test models of github.com/MontiCore/statecharts (commit cc7a442 of
2025-02-24). None of its files is in this project: keep a copy elsewhere and name it in
``MONTICORE_STATECHARTS`` (the repository's root, or its ``src/test/resources``); without it
the tests skip and say so. For instance::

    git clone https://github.com/MontiCore/statecharts ~/monticore-statecharts
    git -C ~/monticore-statecharts checkout cc7a442
    MONTICORE_STATECHARTS=~/monticore-statecharts pytest tests/umlp

Judged: every valid, flat and example model parses and prints back to an equal syntax tree;
every invalid model tied to one of MontiCore's context conditions gets the finding that
stands for the one MontiCore's test of that condition expects (:data:`EXPECTED`). The tally
in the summary line gives k of n for both.
"""

from __future__ import annotations

import os
from collections import Counter
from pathlib import Path

import pytest

from lightrocks.languages.umlp import check_sc
from lightrocks.languages.umlp.cocos import MONTICORE_CODES
from lightrocks.languages.umlp.printer import format_sc_text, print_sc
from lightrocks.languages.umlp.syntax import parse_sc
from lightrocks.metamodel.grammar import SyntaxProblem

VARIABLE = "MONTICORE_STATECHARTS"


def _resources() -> Path | None:
    given = os.environ.get(VARIABLE)
    if not given:
        return None
    root = Path(given).expanduser()
    for candidate in (root / "src" / "test" / "resources", root):
        if (candidate / "valid").is_dir() and (candidate / "invalid").is_dir():
            return candidate
    return None


RESOURCES = _resources()
WHY = (
    f"MontiCore's statechart corpus not found: set {VARIABLE} to a copy of "
    "github.com/MontiCore/statecharts (commit cc7a442), outside this project"
    if RESOURCES is None
    else ""
)

EXPECTED: dict[str, tuple[frozenset[str], tuple[str, ...]]] = {
    "AnteWithoutInitialState.sc": (frozenset({"0xCC112"}), ("0xCC112",) * 4),
    "InvalidEventName.sc": (frozenset({"0xCC110"}), ("0xCC110",)),
    "InvalidExtension.foo": (frozenset({"0xCC106"}), ("0xCC106",)),
    "InvalidPackage.sc": (frozenset({"0xCC107"}), ("0xCC107",)),
    "InvalidParamName.sc": (frozenset({"0xCC109"}), ("0xCC109",)),
    "InvalidSCName.sc": (frozenset({"0xCC108"}), ("0xCC108",)),
    "InvalidSourceTarget.sc": (frozenset({"0xCC103", "0xCC104"}), ("0xCC103", "0xCC104")),
    "InvalidTransitionPrecondition.sc": (
        frozenset({"0xCC111", "0xFD118"}),
        ("0xCC111", "0xCC111"),
    ),
    "InvalidTransitionPreconditionIsTypeReference.sc": (
        frozenset({"0xCC111", "0xFD118"}),
        ("0xFD118",),
    ),
    "Invariant.sc": (frozenset({"0xCC101", "0xFD118"}), ("0xFD118",)),
    "NoInitialState.sc": (frozenset({"0xCC102"}), ("0xCC102",)),
    "NoInitialState2.sc": (frozenset({"0xCC102"}), ("0xCC102",)),
    "NonCapitalStateName.sc": (frozenset({"0xCC105"}), ("0xCC105",)),
    "NonUnique.sc": (frozenset({"0xCC100"}), ("0xCC100",)),
    "TransitionPreconditionIsObscure.sc": (frozenset({"0xCC111", "0xFD118"}), ("0xFD118",)),
    "TwoInitialStates.sc": (frozenset({"0xCC114"}), ("0xCC114",)),
}
"""Per invalid model: the codes MontiCore's test of it looks at (the CoCo under test and
the type check it runs), and the findings of those codes it expects. Read from MontiCore's
tests in src/test/java/de/monticore/cocos: a guard or invariant over a name no symbol table
holds is the type check's 0xFD118, not 0xCC101 or 0xCC111, which skip unknown types. Each
expected finding must be there (UniqueStates reports only the first duplicate, LightRocks
every one, so more of a code it expects is fine); no other finding of the codes looked at."""

ROUND_TRIP = ("valid", "flat", "examples")
"""The folders whose models must parse and print back to an equal tree."""


def _round_trip_models() -> list[Path]:
    if RESOURCES is None:
        return []
    return sorted(f for folder in ROUND_TRIP for f in (RESOURCES / folder).rglob("*.sc"))


def _invalid_models() -> list[Path]:
    if RESOURCES is None:
        return []
    return [RESOURCES / "invalid" / name for name in sorted(EXPECTED)]


def _round_trips(file: Path) -> str:
    """Empty when ``file`` parses and prints back to an equal tree, else why not."""
    text = file.read_text(encoding="utf-8")
    try:
        unit = parse_sc(text, str(file))
        printed = format_sc_text(text, str(file))
        again = parse_sc(printed, str(file))
    except SyntaxProblem as problem:
        return f"{file.name}:{problem.line}:{problem.column}: {problem.message}"
    if again != unit:
        return f"{file.name}: printed, it reads back as another tree"
    if parse_sc(print_sc(unit), str(file)) != unit:
        return f"{file.name}: printed without comments, it reads back as another tree"
    return ""


def _finding_matches(file: Path) -> str:
    """Empty when ``file`` gets the findings MontiCore's test of it expects, else why not."""
    looked_at, expected = EXPECTED[file.name]
    context = check_sc([file], [file.name])
    codes = [MONTICORE_CODES.get(d.code, d.code) for d in context.diagnostics.items]
    found = Counter(code for code in codes if code in looked_at)
    wanted = Counter(expected)
    missing = wanted - found
    extra = set(found) - set(wanted)
    if missing or extra:
        shown = "; ".join(str(d) for d in context.diagnostics.items)
        return f"{file.name}: expected {sorted(wanted.elements())}, found {shown or 'nothing'}"
    return ""


@pytest.mark.skipif(RESOURCES is None, reason=WHY)
def test_valid_flat_and_example_models_print_back_to_an_equal_tree(tally, capsys) -> None:
    models = _round_trip_models()
    assert len(models) >= 25, f"expected the 25 models of {ROUND_TRIP}, found {len(models)}"
    failures = [why for why in map(_round_trips, models) if why]
    k, n = len(models) - len(failures), len(models)
    line = "MontiCore corpus: {k} of {n} valid, flat and example models print back equal"
    tally(line, k=k, n=n)
    with capsys.disabled():
        print(f"\n{line.format(k=k, n=n)}")
    assert not failures, "\n".join(failures)


@pytest.mark.skipif(RESOURCES is None, reason=WHY)
def test_invalid_models_get_the_finding_of_their_context_condition(tally, capsys) -> None:
    models = _invalid_models()
    assert all(f.is_file() for f in models), [f.name for f in models if not f.is_file()]
    failures = [why for why in map(_finding_matches, models) if why]
    k, n = len(models) - len(failures), len(models)
    line = "MontiCore corpus: {k} of {n} invalid models get the finding of their condition"
    tally(line, k=k, n=n)
    with capsys.disabled():
        print(f"\n{line.format(k=k, n=n)}")
    assert not failures, "\n".join(failures)


@pytest.mark.skipif(RESOURCES is None, reason=WHY)
def test_the_other_models_of_the_corpus_print_back_too(capsys) -> None:
    """Models outside the judged folders: the two ``.aut`` files among the invalid ones
    (MontiCore's test only parses them), the symbol-table, transformation and generator
    models."""
    judged = set(_round_trip_models()) | set(_invalid_models())
    root = RESOURCES.parents[2] if RESOURCES.name == "resources" else RESOURCES
    others = sorted(
        f
        for pattern in ("*.sc", "*.aut")
        for f in root.rglob(pattern)
        if f not in judged and f.is_file()
    )
    failures = [why for why in map(_round_trips, others) if why]
    with capsys.disabled():
        print(f"\nMontiCore corpus: {len(others) - len(failures)} of {len(others)} other models")
    assert not failures, "\n".join(failures)
