"""The name index over the examples, without a client: what each reference resolves to."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.lsp.index import Index
from lightrocks.app.lsp.text import Text
from lightrocks.workbench.incremental import IncrementalCheck

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def index() -> Index:
    checked = IncrementalCheck([EXAMPLES])
    checked.full()
    built = Index()
    built.update(checked.context.workspace, lambda path: Text(path.read_text(encoding="utf-8")))
    return built


def references(index: Index, relative: str) -> dict[str, tuple[str, str]]:
    """Each referenced name of a file with its kind and the file declaring it."""
    file = index.files[(EXAMPLES / relative).resolve()]
    return {o.name: (o.kind, o.key[0].name) for o in file.occurrences if not o.declaration}


def test_an_extended_chart_and_the_types_of_its_parameters_resolve(index: Index) -> None:
    found = references(index, "screwing/actions/TurnBack.lr")
    assert found["TurnTool"] == ("statechart", "TurnTool.lr")
    assert found["Angle"] == ("type", "types.lrd")


def test_device_instances_resolve_to_their_devices(index: Index) -> None:
    found = references(index, "screwing/cell/ScrewingCell.lrd")
    assert found["LWR"][0] == "device"
    assert found["LWR"][1].endswith(".lrd")


def test_every_reference_points_at_an_indexed_declaration(index: Index) -> None:
    declared = {o.key for f in index.files.values() for o in f.occurrences if o.declaration}
    dangling = [
        (o.path.name, o.name)
        for f in index.files.values()
        for o in f.occurrences
        if o.key not in declared
    ]
    assert dangling == []
