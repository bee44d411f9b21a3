"""Ecore/XMI round trip: what the generator writes reloads with pyecore and holds the model."""

from __future__ import annotations

from conftest import SCREW_IN, SCREW_TASK, generate
from pyecore.resources import URI, ResourceSet

from lightrocks.metamodel.ecore import NS_URI


def _reload(tmp_path, files: dict[str, str], name: str):
    for file, text in files.items():
        (tmp_path / file).write_text(text, encoding="utf-8")
    resources = ResourceSet()
    package = resources.get_resource(URI(str(tmp_path / "lightrocks.ecore"))).contents[0]
    resources.metamodel_registry[package.nsURI] = package
    return package, resources.get_resource(URI(str(tmp_path / name))).contents[0]


def test_round_trip(tmp_path) -> None:
    files = generate("ecore", [SCREW_IN, SCREW_TASK])
    assert sorted(files) == [
        "lightrocks.ecore",
        "screwing.skills.ScrewIn.xmi",
        "screwing.tasks.ScrewTask.xmi",
    ]
    package, unit = _reload(tmp_path, files, "screwing.skills.ScrewIn.xmi")
    assert package.nsURI == NS_URI
    assert package.getEClassifier("Transition").findEStructuralFeature("guard").containment
    assert unit.eClass.name == "StatechartUnit"
    assert unit.package == "screwing.skills"
    chart = unit.statechart
    assert chart.name == "ScrewIn"
    assert [s.name for s in chart.stereotypes] == ["skill"]
    elements = list(chart.elements)
    states = [e for e in elements if e.eClass.name == "State"]
    assert [s.name for s in states] == ["Turn", "LetGo", "Rewind", "Regrasp"]
    first = states[0].stereotypes[0]
    assert (first.name, first.value) == ("import", "TurnTool")
    transitions = [e for e in elements if e.eClass.name == "Transition"]
    assert len(transitions) == SCREW_IN.read_text().count(" -> ")
    assert ("LetGo", "Rewind", "done") in {(t.source, t.target, t.stimulus) for t in transitions}
    guard = transitions[2].guard
    assert (guard.eClass.name, guard.operator) == ("Binary", ">=")


def test_generating_twice_is_byte_identical() -> None:
    assert generate("ecore", [SCREW_IN]) == generate("ecore", [SCREW_IN])
