"""``.sc ↔ .lr``: every construct both languages share converts and comes back as it was;
what one of them lacks is refused with a finding at its position; a converted chart runs in
the Python runtime where its actions are expressible (docs/interchange.md, "UML/P (.sc)")."""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.loading import component_class, generated_package
from lightrocks.languages.lightrocks.printer import print_statechart
from lightrocks.languages.lightrocks.syntax import parse_statechart
from lightrocks.languages.umlp import nodes as n
from lightrocks.languages.umlp.chart_to_lr import sc_to_lr
from lightrocks.languages.umlp.chart_to_sc import lr_to_sc
from lightrocks.languages.umlp.interchange import convert_lr_to_sc, convert_sc_to_lr
from lightrocks.languages.umlp.literals import java_string_literal, java_string_value
from lightrocks.languages.umlp.printer import print_sc
from lightrocks.languages.umlp.syntax import parse_sc
from lightrocks.metamodel import ast
from lightrocks.workbench import report
from lightrocks.workbench.check import check

MODELS = Path(__file__).with_name("models")
ROOT = Path(__file__).resolve().parents[2]
SHARED = MODELS / "shared" / "Door.sc"
COUNTER = MODELS / "runnable" / "Counter.sc"


def _to_lr(text: str, file: str = "A.sc") -> tuple[ast.StatechartUnit, list]:
    unit = parse_sc(text, file)
    return sc_to_lr(unit, unit.statechart.name or Path(file).stem)


def _round_trip(text: str) -> n.SCArtifact:
    """``.sc → .lr → .sc``, through the printed texts; no error on the way."""
    lr, findings = _to_lr(text)
    assert not [f for f in findings if f.severity.value == "error"], findings
    lr_again = parse_statechart(print_statechart(lr), "A.lr")
    sc, back = lr_to_sc(lr_again)
    assert not [f for f in back if f.severity.value == "error"], back
    return parse_sc(print_sc(sc), "A.sc")


# -- round trips ---------------------------------------------------------------------------


def test_every_shared_construct_comes_back_as_it_was() -> None:
    text = SHARED.read_text(encoding="utf-8")
    assert _round_trip(text) == parse_sc(text, "A.sc")


SHARED_CONSTRUCTS = {
    n.SCArtifact,
    n.SCStatechart,
    n.StereoValue,
    n.SCFuncEventDef,
    n.SCState,
    n.SCTransition,
    n.SCInternTransition,
    n.SCAction,
    n.SCActionBody,
    n.SCEvent,
    n.JBlock,
    n.JExpressionStatement,
    n.JAssignment,
    n.JLiteral,
    n.JName,
    n.JFieldAccess,
    n.JCall,
    n.JArrayAccess,
    n.JPrefix,
    n.JBinary,
    n.JBracket,
}
"""The node types both languages have; the shared model uses each of them."""


def test_the_shared_model_uses_every_shared_construct() -> None:
    unit = parse_sc(SHARED.read_text(encoding="utf-8"), "Door.sc")
    found = list(ast.walk(unit))
    assert SHARED_CONSTRUCTS - {type(node) for node in found} == set()
    states = [s for s in found if isinstance(s, n.SCState)]
    assert {(s.initial, s.final) for s in states} >= {(True, False), (False, True)}
    assert any(s.ante for s in states) and any(s.invariant for s in states)
    actions = [a.body.statement for a in found if isinstance(a, n.SCAction)]
    assert {isinstance(a, n.JBlock) for a in actions} == {True, False}  # `{ … }` and one
    assert {lit.kind for lit in found if isinstance(lit, n.JLiteral)} == {
        "number",
        "string",
        "boolean",
    }
    posts = [t for t in found if isinstance(t, n.SCTransition) and t.action and t.action.post]
    assert posts


SHARED_PIECES = {
    "initial and final states": "statechart A { initial state S; final state F; S -> F; }",
    "hierarchy": "statechart A { initial state S { initial state T; state U; T -> U e; }; }",
    "state stereotypes": 'statechart A { <<x, y="1">> initial state S; }',
    "invariants": "statechart A { initial state S [a > 1 && b]; }",
    "entry, exit and do": "statechart A { initial state S { entry / { a(); } exit / b = 1; "
    "do / { c(); } }; }",
    "internal transitions": "statechart A { initial state S { -> [g] e(1) / { x = 2; }; -> f; }; }",
    "guard, event, action, postcondition": "statechart A { initial state S; "
    'S -> S [x < 2] e(x, 1.5, "s", true) / { x = x + 1; f(x); } [x > 0]; }',
    "precedence": "statechart A { initial state S [(a + b) * c == d - (e - f) && !(g || h)]; }",
    "events": "statechart A { event e(); event f(); initial state S; S -> S e; }",
    "chart stereotypes": '<<a, b="c">> statechart A { }',
    "ante of the initial state": "statechart A { initial { x = 1; y(); } state S; }",
    "package": "package p; statechart A { }",
}


@pytest.mark.parametrize("text", SHARED_PIECES.values(), ids=SHARED_PIECES.keys())
def test_each_shared_construct_round_trips(text: str) -> None:
    assert _round_trip(text) == parse_sc(text, "A.sc")


NORMALISED = {
    "an event without arguments loses its parentheses": (
        "statechart A { initial state S; S -> S e(); }",
        "statechart A { initial state S; S -> S e; }",
    ),
    "an empty action becomes an empty block": (
        "statechart A { initial state S; S -> S e / ; }",
        "statechart A { initial state S; S -> S e / { }; }",
    ),
    "a single statement of a transition becomes a block": (
        "statechart A { initial state S; S -> S e / x = 1;; }",
        "statechart A { initial state S; S -> S e / { x = 1; }; }",
    ),
    "increments become assignments": (
        "statechart A { initial state S { entry / { x++; --y; z += 2; w *= 3; } }; }",
        "statechart A { initial state S { entry / { x = x + 1; y = y - 1; z = z + 2; "
        "w = w * 3; } }; }",
    ),
    "brackets Java's precedence does not need go": (
        "statechart A { initial state S [((a)) && (b == c)]; }",
        "statechart A { initial state S [a && b == c]; }",
    ),
    "automaton is statechart": ("automaton A { }", "statechart A { }"),
    "an unnamed chart takes the file's name": ("statechart { }", "statechart A { }"),
    "nested blocks and empty statements flatten": (
        "statechart A { initial state S { entry / { a(); { b(); ; } } }; }",
        "statechart A { initial state S { entry / { a(); b(); } }; }",
    ),
    "a chart's comments stay in the .sc file": (
        "statechart A { /* gone */ initial state S; }",
        "statechart A { initial state S; }",
    ),
}


@pytest.mark.parametrize(("text", "canonical"), NORMALISED.values(), ids=NORMALISED.keys())
def test_forms_only_uml_p_has_come_back_in_the_shared_form(text: str, canonical: str) -> None:
    assert _round_trip(text) == parse_sc(canonical, "A.sc")


# -- what is refused ------------------------------------------------------------------------

REFUSED_SC = {
    "local variable": ("entry / { int i = 0; }", "LR2120", "local variable declaration"),
    "if": ("entry / if (a) b();", "LR2120", "if statement"),
    "while": ("entry / { while (a) b(); }", "LR2120", "while loop"),
    "for": ("entry / { for (;;) break; }", "LR2120", "for loop"),
    "switch": ("entry / { switch (a) { default: } }", "LR2120", "switch statement"),
    "return": ("entry / { return 1; }", "LR2120", "return statement"),
    "conditional": ("entry / { x = a ? b : c; }", "LR2120", "'a ? b : c'"),
    "bit operator": ("entry / { x = a & b; }", "LR2120", "'a & b'"),
    "shift": ("entry / { x = a << 2; }", "LR2120", "'a << 2'"),
    "complement": ("entry / { x = ~a; }", "LR2120", "'~a'"),
    "null": ("entry / { x = null; }", "LR2120", "the null literal null"),
    "char": ("entry / { x = 'c'; }", "LR2120", "the char literal 'c'"),
    "long": ("entry / { x = 10L; }", "LR2120", "the number 10L"),
    "float": ("entry / { x = 1.5f; }", "LR2120", "the number 1.5f"),
    "hexadecimal": ("entry / { x = 0x1F; }", "LR2120", "the number 0x1F"),
    "nested assignment": ("entry / { f(x = 1); }", "LR2120", "'x = 1'"),
    "increment inside": ("entry / { f(x++); }", "LR2120", "'x++'"),
    "post of an action": ("entry / { a(); } [b]", "LR2121", "postcondition of an entry action"),
    "eventless internal": ("-> [g] / { a(); };", "LR2121", "internal transition without event"),
    "post of an internal": ("-> e / { a(); } [b];", "LR2121", "postcondition of an internal"),
    "qualified event": ("-> a.b.c;", "LR2121", "qualified event name a.b.c"),
    "nested ante": ("initial { a(); } state T;", "LR2121", "the ante block of T, a nested"),
    "ante of a state not initial": (
        "{ a(); } state T;",
        "LR2121",
        "the ante block of T, a state that is not initial",
    ),
}


@pytest.mark.parametrize(("element", "code", "message"), REFUSED_SC.values(), ids=REFUSED_SC.keys())
def test_java_and_constructs_lightrocks_lacks_are_refused_where_they_stand(
    element: str, code: str, message: str
) -> None:
    text = f"statechart A {{\n  initial state S {{\n    {element}\n  }};\n}}\n"
    _, findings = _to_lr(text)
    errors = [f for f in findings if f.severity.value == "error"]
    assert [(f.code, f.line) for f in errors] == [(code, 3)], errors
    assert message in errors[0].message
    assert errors[0].column >= 5


def test_a_refused_conversion_writes_nothing() -> None:
    text = "statechart A { initial state S { entry / { int i = 0; } }; }"
    result = convert_sc_to_lr(Path("A.sc"), text, "A.sc")
    assert result.text is None and result.name == "A.lr"
    assert [f.code for f in result.findings] == ["LR2120"]


DROPPED_SC = {
    "Java imports": ("import java.util.List; statechart A { }", "import java.util.List"),
    "completeness": ("statechart A { (c) }", "completeness marker (c)"),
    "transition stereotypes": (
        "statechart A { initial state S; <<t>> S -> S e; }",
        "<<t>> dropped",
    ),
    "event parameters": ("statechart A { event int e(int x); }", "event e: LightRocks events"),
}


@pytest.mark.parametrize(("text", "message"), DROPPED_SC.values(), ids=DROPPED_SC.keys())
def test_what_does_not_change_behaviour_is_dropped_with_a_warning(text: str, message: str) -> None:
    _, findings = _to_lr(text)
    assert [(f.code, f.severity.value) for f in findings] == [("LR2122", "warning")]
    assert message in findings[0].message


def test_variables_the_chart_does_not_declare_become_parameters() -> None:
    text = """statechart A {
      initial state S [ok && level < 3.5] {
        entry / { n = 0; name = "x"; n = n + 1; m = n * 2; }
      };
      S -> S [!(k > 2)] e / { unknown = f(); } [done];
    }"""
    lr, findings = _to_lr(text)
    declared = {
        p.name: (p.type, print_statechart_value(p.default))
        for block in lr.statechart.elements
        if isinstance(block, ast.ParameterBlock)
        for p in block.parameters
    }
    assert declared == {
        "ok": ("Boolean", "false"),
        "level": ("Real", "0.0"),
        "n": ("Integer", "0"),
        "name": ("String", '""'),
        "m": ("Integer", "0"),
        "k": ("Integer", "0"),
        "done": ("Boolean", "false"),
    }
    assert {f.code for f in findings} == {"LR2123", "LR2124"}  # f() is the class's method


def print_statechart_value(node: ast.Expression) -> str:
    from lightrocks.metamodel.printer import expression

    return expression(node)


REFUSED_LR = {
    "layer": ("<<skill>> statechart A { start condition go; go -> S; state S; }", "<<skill>>"),
    "start condition": ("statechart A { start condition go; }", "start condition go"),
    "region": ("statechart A { region R { initial state S; } }", "region R"),
    "choice": ("statechart A { initial state S; choice C; }", "choice C"),
    "history": (
        "statechart A { initial state S { initial state T; history H; } }",
        "history H",
    ),
    "time event": ("statechart A { initial state S; S -> S after(2 s); }", "after(…)"),
    "unit": ("statechart A { initial state S [x > 2 mm]; }", "the quantity 2 mm"),
    "named argument": ("statechart A { initial state S { entry / f(a = 1); } }", "named"),
    "vector": ("statechart A { initial state S { entry / { v = [1, 2]; } } }", "vector"),
    "chart exit action": ("statechart A { exit / { f(); } initial state S; }", "exit action"),
    "history target": (
        "statechart A { initial state S { initial state T; history H; } S -> S.H e; }",
        "S.H",
    ),
}


@pytest.mark.parametrize(("text", "message"), REFUSED_LR.values(), ids=REFUSED_LR.keys())
def test_lightrocks_constructs_uml_p_lacks_are_refused(text: str, message: str) -> None:
    _, findings = lr_to_sc(parse_statechart(f"package p;\n{text}\n", "A.lr"))
    errors = [f for f in findings if f.severity.value == "error"]
    assert errors and all(f.code in ("LR2120", "LR2121") for f in errors), findings
    assert any(message in f.message for f in errors), errors


def test_a_plain_example_converts_to_uml_p() -> None:
    file = ROOT / "examples" / "plain" / "Turnstile.lr"
    result = convert_lr_to_sc(file, file.read_text(encoding="utf-8"), str(file))
    assert result.text is not None and result.name == "Turnstile.sc"
    assert {f.code for f in result.findings} == {"LR2122"}  # its parameters
    sc = parse_sc(result.text, "Turnstile.sc")
    original = parse_statechart(file.read_text(encoding="utf-8"), str(file))
    back, findings = sc_to_lr(sc, "Turnstile")
    assert not [f for f in findings if f.severity.value == "error"]

    def without_parameters(unit: ast.StatechartUnit) -> tuple:
        return tuple(e for e in unit.statechart.elements if not isinstance(e, ast.ParameterBlock))

    assert without_parameters(back) == without_parameters(original)


# -- strings -------------------------------------------------------------------------------


@pytest.mark.parametrize("value", ["plain", 'a "quoted" one', "back\\slash", "tab\tline\n", "é€"])
def test_java_strings_keep_their_value(value: str) -> None:
    assert java_string_value(java_string_literal(value)) == value


def test_java_escapes_are_read() -> None:
    assert java_string_value(r'"\u0041\101\n\\\""') == 'AA\n\\"'


# -- running ---------------------------------------------------------------------------------


def test_a_converted_chart_runs_in_the_python_runtime(tmp_path: Path) -> None:
    result = convert_sc_to_lr(COUNTER, COUNTER.read_text(encoding="utf-8"), str(COUNTER))
    assert result.text is not None, result.findings
    (tmp_path / "runnable").mkdir()
    file = tmp_path / "runnable" / result.name
    file.write_text(result.text, encoding="utf-8")
    context = check([tmp_path])
    assert not context.diagnostics.items, report.text(context.diagnostics.items)
    package = generated_package(context, [file], tmp_path / "cache")
    chart = component_class(package, "runnable.Counter")().start()
    # the ante block ran as the chart's entry action, before the state's entry action
    assert (chart.count, chart.entries) == (0, 11)
    assert chart.active_configuration == ("Counter", "Counting", "Even")
    seen = []
    for event in ("tick", "tick", "tick", "reset", "tick", "stop", "tick", "stop"):
        chart.send(event)
        seen.append((event, chart.active_configuration[-1:], chart.count))
    assert seen == [
        ("tick", ("Odd",), 1),
        ("tick", ("Even",), 2),
        ("tick", ("Odd",), 3),
        ("reset", ("Odd",), 0),  # internal: no exit, no entry
        ("tick", ("Even",), 1),
        ("stop", ("Even",), 1),  # the guard [count >= 2] does not hold
        ("tick", ("Odd",), 2),
        ("stop", (), 2),
    ]
    assert chart.outcome == "Stopped" and chart.entries == 11
