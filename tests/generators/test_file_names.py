"""Output files of every target: no two statecharts share one, on any file system.

Twins (one name in two packages) get package-qualified file names where a target names
files by simple name; names that fold into one (``Kase`` and ``KASE``) are a generation
error at the chart; a name too long for a file system is shortened, uniquely."""

from __future__ import annotations

from pathlib import Path

import pytest
from edge_models import LONG
from generation import generate

from lightrocks.workbench.generators import GenerationError

TARGETS = ["sfc", "plcopen", "python", "dot", "ecore"]


def _chart(root: Path, package: str, name: str) -> Path:
    model = root / package / f"{name}.lr"
    model.parent.mkdir(parents=True, exist_ok=True)
    model.write_text(
        f"package {package};\n\n<<skill>> statechart {name} {{\n"
        "  initial state A;\n  final state B;\n  A -> B go;\n}\n"
    )
    return model


def _charts(files: dict[str, str]) -> set[str]:
    """The files written per statechart (not those of the whole run)."""
    shared = {"__init__.py", "lightrocks.ecore"}
    return {n for n in files if n.rpartition("/")[2] not in shared}


@pytest.mark.parametrize(
    ("target", "expected"),
    [
        ("sfc", {"a.Twin.st", "b.Twin.st"}),
        ("plcopen", {"a.Twin.xml", "b.Twin.xml"}),
        ("python", {"a/Twin.py", "b/Twin.py"}),
        ("dot", {"a.Twin.dot", "b.Twin.dot"}),
        ("ecore", {"a.Twin.xmi", "b.Twin.xmi"}),
    ],
)
def test_twins_in_two_packages_get_a_file_each(
    tmp_path: Path, target: str, expected: set[str]
) -> None:
    models = [_chart(tmp_path, "a", "Twin"), _chart(tmp_path, "b", "Twin")]
    assert _charts(generate(target, models, search=[tmp_path])) == expected


@pytest.mark.parametrize("target", ["sfc", "plcopen"])
def test_a_name_no_other_chart_shares_keeps_its_file(tmp_path: Path, target: str) -> None:
    models = [_chart(tmp_path, "a", "Twin"), _chart(tmp_path, "b", "Other")]
    suffix = {"sfc": ".st", "plcopen": ".xml"}[target]
    files = generate(target, models, search=[tmp_path])
    assert set(files) == {f"Twin{suffix}", f"Other{suffix}"}


@pytest.mark.parametrize("target", TARGETS)
def test_names_that_fold_into_one_are_an_error_at_the_chart(tmp_path: Path, target: str) -> None:
    models = [_chart(tmp_path, "p", "Kase"), _chart(tmp_path, "p", "KASE")]
    with pytest.raises(GenerationError) as raised:
        generate(target, models, search=[tmp_path])
    message = str(raised.value)
    assert message.startswith(f"{models[0]}:3:1: output ")
    assert f"statechart p.KASE at {models[1]}:3:1" in message


@pytest.mark.parametrize("target", TARGETS)
def test_long_names_are_shortened_apart(tmp_path: Path, target: str) -> None:
    models = [_chart(tmp_path, "d", LONG), _chart(tmp_path, "d", f"{LONG[:-1]}x")]
    files = generate(target, models, search=[tmp_path])
    names = _charts(files)
    assert len(names) == 2
    assert all(len(part.encode()) <= 255 for name in names for part in name.split("/"))
    assert _charts(generate(target, models, search=[tmp_path])) == names
