"""``lightrocks convert X.scxml --to lr`` (docs/interchange.md, section SCXML): the round trip
``.lr → .scxml → .lr`` gives every chart back (equal syntax trees up to the order of
declarations that LightRocks leaves free, or, where SCXML carries no unit, equal behaviour);
SCXML written by hand converts to a chart that runs as python-statemachine runs the
document; every element outside the subset is a finding at its line and column, and a
document with one converts to nothing.
"""

from __future__ import annotations

import random
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from statecharts.random_charts import random_chart

from interchange.canonical import canonical
from interchange.pairs import generated
from interchange.scxml_judge import run_both, same
from lightrocks.generators.scxml.writer import Document, Writer
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.languages.scxml.reader import Reader, convert_scxml_to_lr
from lightrocks.languages.scxml.xml_tree import parse_xml
from lightrocks.metamodel import ast
from lightrocks.workbench import report
from lightrocks.workbench.check import check

ROOT = Path(__file__).resolve().parents[2]
PLANT = ROOT / "tests" / "generators" / "models" / "plant"
MODELS = Path(__file__).with_name("models")
DOOR = MODELS / "scxml" / "Door.scxml"

SHARED = [
    *(PLANT / f"{name}.lr" for name in ("Chime", "Counter", "Crossing", "Junction", "Lamp")),
    *(PLANT / f"{name}.lr" for name in ("Player", "Press", "Recorder", "Rewind", "Router")),
    PLANT / "Shuttle.lr",
    PLANT / "Tally.lr",
    ROOT / "examples" / "plain" / "Turnstile.lr",
    MODELS / "d" / "Everything.lr",
]
"""Charts made of constructs SCXML shares (Everything.lr: those plant/ lacks)."""


def _scxml(unit: ast.StatechartUnit) -> Document:
    return Writer(unit, ast.stereotype(unit.statechart.stereotypes, "timeout")).document()


def _back(text: str, name: str = "A.scxml") -> ast.StatechartUnit:
    converted = convert_scxml_to_lr(Path(name), text, name)
    errors = [str(f) for f in converted.findings if f.severity.value == "error"]
    assert converted.text is not None and not errors, errors
    return parse_statechart(converted.text, "A.lr")


@pytest.mark.parametrize("file", SHARED, ids=lambda f: f.stem)
def test_round_trip_gives_the_chart_back(file: Path) -> None:
    unit = parse_statechart(file.read_text(encoding="utf-8"), str(file))
    assert canonical(_back(_scxml(unit).text)) == canonical(unit)


def test_the_shared_charts_hold_every_construct_the_target_maps() -> None:
    found: set[str] = set()
    for file in SHARED:
        chart = parse_statechart(file.read_text(encoding="utf-8"), str(file)).statechart
        for node in ast.walk(chart):
            found.add(_construct(node))
    assert {
        "state",
        "initial state",
        "final state",
        "end condition",
        "region",
        "choice",
        "history",
        "deep history",
        "entry",
        "exit",
        "invariant",
        "event transition",
        "completion",
        "outcome transition",
        "error transition",
        "time event",
        "internal transition",
        "internal time event",
        "guard",
        "action",
        "postcondition",
        "transition into history",
        "events",
        "parameters",
        "budget",
        "stereotype",
        "call",
        "string",
    } <= found


def _construct(node: object) -> str:
    match node:
        case ast.State(modifiers=modifiers) if "final" in modifiers:
            return "final state"
        case ast.State(modifiers=modifiers) if "initial" in modifiers:
            return "initial state"
        case ast.State(stereotypes=stereotypes) if stereotypes:
            return "stereotype"
        case ast.State():
            return "state"
        case ast.Condition(kind="end"):
            return "end condition"
        case ast.Region():
            return "region"
        case ast.Pseudostate(kind=kind):
            return kind
        case ast.Action(kind=kind):
            return kind
        case ast.Invariant():
            return "invariant"
        case ast.Transition(postcondition=post) if post is not None:
            return "postcondition"
        case ast.Transition(target_history=history) if history:
            return "transition into history"
        case ast.Transition(stimulus="error"):
            return "error transition"
        case ast.Transition(stimulus="after"):
            return "time event"
        case ast.Transition(guard=guard) if guard is not None:
            return "guard"
        case ast.Transition(action=action) if action:
            return "action"
        case ast.Transition(stimulus=""):
            return "completion"
        case ast.Transition(stimulus=stimulus) if stimulus[:1].isupper():
            return "outcome transition"
        case ast.Transition():
            return "event transition"
        case ast.InternalTransition(stimulus="after"):
            return "internal time event"
        case ast.InternalTransition():
            return "internal transition"
        case ast.EventBlock():
            return "events"
        case ast.ParameterBlock():
            return "parameters"
        case ast.Statechart(stereotypes=stereotypes) if ast.stereotype(stereotypes, "timeout"):
            return "budget"
        case ast.Call():
            return "call"
        case ast.StringLiteral():
            return "string"
    return type(node).__name__


@pytest.mark.parametrize("name", ["Dial", "Hopper"])
def test_round_trip_without_units_keeps_the_behaviour(name: str, tmp_path: Path) -> None:
    """SCXML numbers are SI values without unit: a Length comes back as a Real, ``2 mm`` as
    ``0.002``, constant defaults folded; the chart does what it did."""
    original = PLANT / f"{name}.lr"
    converted = convert_scxml_to_lr(
        Path(f"{name}.scxml"), _scxml(parse_statechart(original.read_text(), "A.lr")).text, "x"
    )
    assert converted.text is not None
    root = tmp_path / "back"
    (root / "plant").mkdir(parents=True)
    (root / "plant" / f"{name}.lr").write_text(converted.text, encoding="utf-8")
    before, after = check([original.parent.parent]), check([root])
    assert not after.diagnostics.has_errors, report.text(after.diagnostics.items)
    cls, document = generated(before, original, f"plant.{name}", tmp_path / "c1")
    again, _ = generated(after, root / "plant" / f"{name}.lr", f"plant.{name}", tmp_path / "c2")
    variables = list(document.variables)
    letters = [*sorted(cls().start().events), "+0.1"]
    rng = random.Random(name)
    for _ in range(20):
        events = [rng.choice(letters) for _ in range(12)]
        first, *_ = run_both(cls, document, variables, events)
        second, *_ = run_both(again, document, variables, events)
        assert first == second, events


# -- SCXML written by hand -------------------------------------------------------------------


def test_scxml_written_by_hand_runs_as_python_statemachine_runs_it(tmp_path: Path) -> None:
    """Door.scxml has no annotation of LightRocks: an <initial> element, a delayed send
    cancelled on exit, a completion (done.state), an internal transition, a choice, a
    history, regions, a transition on two events, conditions in both spellings."""
    text = DOOR.read_text(encoding="utf-8")
    converted = convert_scxml_to_lr(DOOR, text, str(DOOR))
    assert converted.text is not None, converted.findings
    warnings = [f for f in converted.findings if f.severity.value != "info"]
    assert [(f.code, f.line) for f in warnings] == [("LR2132", 41)]  # the paused state comes
    assert "history beside final states" in warnings[0].message  # from busy by pause only
    (tmp_path / "d").mkdir()
    file = tmp_path / "d" / "Door.lr"
    file.write_text(f"package d;\n\n{converted.text}", encoding="utf-8")
    context = check([tmp_path])
    assert not context.diagnostics.has_errors, report.text(context.diagnostics.items)
    cls, _ = generated(context, file, "d.Door", tmp_path / "cache")
    reader = Reader(str(DOOR))
    unit = reader.read(parse_xml(text), "Door")
    blocks = [e for e in unit.statechart.elements if isinstance(e, ast.ParameterBlock)]
    variables = {p.name: p.name for b in blocks for p in b.parameters}
    paths = reader.paths("Door")
    document = Document(text, paths, variables)
    letters = [*sorted(cls().start().events), "+0.25"]
    rng = random.Random("door")
    for _ in range(40):
        events = [rng.choice(letters) for _ in range(12)]
        mine, theirs, _, _ = run_both(cls, document, list(variables), events)
        theirs = [
            (tuple(sorted(("Door", *t[0]))) if t[1] is not None else (), t[1]) for t in theirs
        ]
        assert all(same(a, b) for a, b in zip(mine, theirs, strict=True)), (events, mine, theirs)


OUTSIDE = """<scxml xmlns="http://www.w3.org/2005/07/scxml" version="1.0" initial="a">
  <datamodel>
    <data id="n" expr="0"/>
    <data id="blob" src="file:///etc/passwd"/>
  </datamodel>
  <script>n = 1</script>
  <state id="a">
    <onentry>
      <raise event="x"/>
      <if cond="n &gt; 0"><assign location="n" expr="1"/></if>
      <log expr="n"/>
    </onentry>
    <invoke type="scxml" src="other.scxml"/>
    <transition event="go.*" target="b"/>
    <transition event="go" target="b c"/>
    <transition event="go" cond="In('b')" target="b"/>
    <transition target="b"/>
    <transition event="go" target="inner"/>
    <transition event="go" target="b"><send event="y" target="#_parent"/></transition>
    <transition event="go" target="b"><assign location="n" expr="n ** 2"/></transition>
    <transition event="done.state.b" target="b"/>
    <state id="inner"/>
  </state>
  <state id="b">
    <history id="h"><transition target="b2"/></history>
    <state id="b1"/>
    <state id="b2"/>
  </state>
  <state id="c"/>
</scxml>
"""

EXPECTED = [
    ("<data", "blob", "LR2130", "<data src>"),
    ("<script", "<script", "LR2130", "<script>"),
    ("<raise", "<raise", "LR2130", "<raise>"),
    ("<if", "<if", "LR2130", "<if>"),
    ("<log", "<log", "LR2132", "<log> is dropped"),
    ("<invoke", "<invoke", "LR2130", "<invoke>"),
    ("<transition", "go.*", "LR2130", "LightRocks events are names"),
    ("<transition", "b c", "LR2130", "several targets"),
    ("<transition", "In('b')", "LR2131", "'In('b')' has no LightRocks counterpart"),
    ("<transition", '<transition target="b"/>', "LR2130", "eventless"),
    ("<transition", "inner", "LR2130", "states of one level"),
    ("<send", "#_parent", "LR2130", "<send>"),
    ("<assign", "n ** 2", "LR2131", "'n ** 2' has no LightRocks counterpart"),
    ("<transition", "done.state.b", "LR2130", "a completion of another state"),
    ("<transition", 'target="b2"', "LR2130", "whose default is not the initial state"),
]


def _where(text: str, tag: str, marker: str) -> tuple[int, int]:
    """Line and column of the element ``tag`` on the first line that holds ``marker``."""
    lines = text.splitlines()
    number = next(i for i, line in enumerate(lines) if marker in line)
    return number + 1, lines[number].index(tag) + 1


def test_every_element_outside_the_subset_is_a_finding_at_its_place() -> None:
    converted = convert_scxml_to_lr(Path("Bad.scxml"), OUTSIDE, "Bad.scxml")
    assert converted.text is None
    found = {(f.line, f.column, f.code) for f in converted.findings}
    messages = {(f.line, f.column): f.message for f in converted.findings}
    for tag, marker, code, words in EXPECTED:
        line, column = _where(OUTSIDE, tag, marker)
        assert (line, column, code) in found, (tag, marker, line, column, sorted(found))
        assert words in messages[(line, column)], messages[(line, column)]


@pytest.mark.parametrize(
    ("text", "where", "words"),
    [
        ("<scxml><state id='a'>", (1, 22), "not well-formed XML"),
        (
            '<?xml version="1.0"?>\n<!DOCTYPE scxml [<!ENTITY a "aaaa">]>\n<scxml/>',
            (2, 1),
            "<!DOCTYPE> is not read",
        ),
        ("<html/>", (1, 1), "not an SCXML document"),
        (
            '<scxml xmlns="http://www.w3.org/2005/07/scxml"><datamodel><data id="x"/>'
            "</datamodel><state id='a'/></scxml>",
            (1, 59),
            "the type of 'x' is not known",
        ),
    ],
)
def test_documents_that_convert_to_nothing(text: str, where: tuple[int, int], words: str) -> None:
    converted = convert_scxml_to_lr(Path("Bad.scxml"), text, "Bad.scxml")
    assert converted.text is None
    errors = [f for f in converted.findings if f.severity.value == "error"]
    assert (errors[0].line, errors[0].column) == where and words in errors[0].message, errors


# -- the command line --------------------------------------------------------------------------


def _lightrocks(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "lightrocks.app.cli", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        check=False,
    )


def test_convert_writes_the_chart_beside_the_document(tmp_path: Path) -> None:
    source = tmp_path / "Door.scxml"
    source.write_text(DOOR.read_text(encoding="utf-8"), encoding="utf-8")
    done = _lightrocks("convert", "Door.scxml", "--to", "lr", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "Door.lr").read_text(encoding="utf-8").startswith("statechart Door {")


def test_convert_of_a_bad_document_writes_nothing_and_exits_1(tmp_path: Path) -> None:
    (tmp_path / "Good.scxml").write_text(DOOR.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "Bad.scxml").write_text(OUTSIDE, encoding="utf-8")
    done = _lightrocks("convert", "Good.scxml", "Bad.scxml", "--to", "lr", cwd=tmp_path)
    assert done.returncode == 1
    assert "Bad.scxml:6:3: error LR2130: <script>" in done.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["Bad.scxml", "Good.scxml"]


@pytest.mark.parametrize("seed", range(40))
def test_random_charts_come_back_as_they_were(seed: int) -> None:
    unit = parse_statechart(random_chart(seed), "d/R.lr")
    assert canonical(_back(_scxml(unit).text)) == canonical(unit)


def test_a_damaged_document_gives_findings_never_an_exception() -> None:
    """Elements and attributes of generated and hand-written documents removed or given
    other values, at random: every conversion ends with a text or with findings."""
    texts = [DOOR.read_text(encoding="utf-8")]
    for file in SHARED[:6]:
        texts.append(_scxml(parse_statechart(file.read_text(encoding="utf-8"), "A.lr")).text)
    rng = random.Random(7)
    values = ["", "x", "a b", "1", "done.state.x", "In('x')", "(", "n + ", "lr-error.x"]
    for _ in range(400):
        root = ET.fromstring(rng.choice(texts).split("\n", 1)[1])
        elements = list(root.iter())
        for _ in range(rng.randint(1, 3)):
            element = rng.choice(elements)
            parent = next((p for p in root.iter() if element in list(p)), None)
            if rng.random() < 0.4 and parent is not None:
                parent.remove(element)
            elif element.attrib:
                key = rng.choice(list(element.attrib))
                ids = [e.get("id", "z") for e in elements]
                element.attrib[key] = rng.choice([*values, rng.choice(ids)])
        text = ET.tostring(root, encoding="unicode")
        converted = convert_scxml_to_lr(Path("F.scxml"), text, "F.scxml")
        assert converted.text is not None or converted.findings
