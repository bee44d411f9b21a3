"""Ecore/XMI round trip: what the generator writes reloads with pyecore and holds the model."""

from __future__ import annotations

from generation import SCREW_IN, SCREW_TASK, generate
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


CONSTRUCTS = """package d;

statechart Gate {
  events {
    go;
    back;
  }

  initial state Idle;
  state Both {
    internal [true] go;

    region Left {
      initial state A;
      state B;
      deep history D;
      A -> B after(2 s);
    }

    region Right {
      initial state C;
      choice Pick;
      C -> Pick go;
      Pick -> C;
    }
  }

  state Pause {
    initial state P;
    history H;
  }

  Idle -> Both go;
  Both -> Pause back;
  Pause -> Both go;
  Idle -> Pause.H back;
}
"""


def test_regions_pseudostates_internal_and_time_events_are_exported(tmp_path) -> None:
    (tmp_path / "d").mkdir()
    model = tmp_path / "d" / "Gate.lr"
    model.write_text(CONSTRUCTS)
    files = generate("ecore", [model], search=[tmp_path])
    package, unit = _reload(tmp_path, files, "d.Gate.xmi")
    assert package.getEClassifier("Region").findEStructuralFeature("elements").containment
    elements = list(unit.statechart.elements)
    assert [e.name for e in elements[0].events] == ["go", "back"]
    both = next(e for e in elements if e.eClass.name == "State" and e.name == "Both")
    internal, left, right = both.body
    assert (internal.eClass.name, internal.stimulus) == ("InternalTransition", "go")
    assert [(r.eClass.name, r.name) for r in (left, right)] == [
        ("Region", "Left"),
        ("Region", "Right"),
    ]
    history = next(e for e in left.elements if e.eClass.name == "Pseudostate")
    assert (history.kind, history.name) == ("deep history", "D")
    after = next(e for e in left.elements if e.eClass.name == "Transition")
    assert after.stimulus == "after" and after.stimulus_arguments[0].value == 2.0
    choice = next(e for e in right.elements if e.eClass.name == "Pseudostate")
    assert (choice.kind, choice.name) == ("choice", "Pick")
    into_history = [e for e in elements if e.eClass.name == "Transition"][-1]
    assert (into_history.target, into_history.target_history) == ("Pause", "H")
