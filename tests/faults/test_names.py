"""Generated Python names never meet keywords, builtins, dunders, the runtime's attributes or
the generated modules' own names: generating, importing and running always work."""

from __future__ import annotations

import builtins
import keyword
import unicodedata
from pathlib import Path

import pytest

from lightrocks.generators.python.names import RESERVED, identifier
from lightrocks.runtime import CompositeComponent

from .fault_runs import cli, within, write_models

COUNTER = """package t;

statechart Counter {
  parameters {
    Integer NAME = 0;
  }

  initial state A;
  final state B;

  A -> B go / { NAME = NAME + 1; };
}
"""

RUNTIME_ATTRIBUTES = [
    "parent",
    "path",
    "current",
    "children",
    "name",
    "env",
    "given",
    "end_names",
    "_executor",
]
NFKC_TWINS = ["ｐａｒｅｎｔ", "ｐａｔｈ", "ﬁle", "ｒｔ"]


@pytest.mark.parametrize("name", RUNTIME_ATTRIBUTES + NFKC_TWINS + ["__x", "_", "__init__"])
def test_parameter_named_like_the_runtime_runs_to_its_outcome(build, name):
    cls = build({"Counter": COUNTER.replace("NAME", name)}, "Counter")
    chart = within(lambda: cls().start())
    within(lambda: chart.send("go"))
    assert chart.finished and chart.outcome == "B"
    assert getattr(chart, cls.PARAMETERS[name]) == 1
    assert chart.parent is None and chart.path == "Counter"


DUNDERS = """package t;

statechart Odd {
  parameters {
    Integer __x = 0;
    Integer _ = 0;
    Integer __init__ = 0;
  }

  initial state __class__;
  state _;
  final state __dict__;

  __class__ -> _ go / { __x = 1; };
  _ -> __dict__ go / { _ = __x + 1; __init__ = _ + 1; };
}
"""


def test_dunder_and_underscore_names_generate_on_the_command_line(tmp_path: Path):
    write_models(tmp_path, {"Odd": DUNDERS})
    done = cli("generate", "--target", "python", "t", "-o", "out", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "out" / "t" / "Odd.py").is_file()


def test_dunder_and_underscore_names_run(build):
    cls = build({"Odd": DUNDERS}, "Odd")
    chart = within(lambda: cls().start())
    within(lambda: [chart.send("go"), chart.send("go")])
    assert chart.outcome == "__dict__"
    assert getattr(chart, cls.PARAMETERS["__init__"]) == 3


def skill(package: str) -> str:
    return f"""package {package};

<<skill>> statechart C {{
  start condition begin;
  end condition done;

  state I;

  begin -> I;
  I -> done go;
}}
"""


MAIN = """package top;

import z.C;
import a.b.C;
import a_b.C;

<<task>> statechart Main {
  start condition begin;
  end condition ok;

  <<import="z.C">> state X;
  <<import="a.b.C">> state Y;
  <<import="a_b.C">> state W;

  begin -> X;
  X -> Y done;
  Y -> W done;
  W -> ok done;
}
"""


def test_classes_of_the_same_name_from_look_alike_packages_import_apart(tmp_path: Path):
    root = tmp_path / "m"
    for package in ("z", "a.b", "a_b"):
        folder = root.joinpath(*package.split("."))
        folder.mkdir(parents=True)
        (folder / "C.lr").write_text(skill(package), encoding="utf-8")
    (root / "top").mkdir()
    (root / "top" / "Main.lr").write_text(MAIN, encoding="utf-8")
    model = str(root / "top" / "Main.lr")
    done = cli("run", model, "--path", str(root), "--events", "go,go,go", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "outcome: ok" in done.stdout


PLAIN = """statechart NAME {
  initial state A;
  final state B;

  A -> B go;
}
"""


@pytest.mark.parametrize("name", ["ｒｔ", "ﬁle", "_domain", "rt", "__init__", "Any"])
def test_statechart_named_like_a_module_or_its_nfkc_twin_runs(tmp_path: Path, name):
    model = tmp_path / f"{name}.lr"
    model.write_text(PLAIN.replace("NAME", name), encoding="utf-8")
    done = cli("run", str(model), "--events", "go", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "outcome: B" in done.stdout


@pytest.mark.parametrize(
    "name",
    [
        *keyword.kwlist,
        *keyword.softkwlist,
        *dir(builtins),
        *RUNTIME_ATTRIBUTES,
        *NFKC_TWINS,
        *vars(CompositeComponent),
        *["_", "__", "___x", "x_", "x__y", "1x", "ß", "ｘ"],
    ],
)
def test_identifier_meets_nothing_reserved_and_is_a_plain_ascii_name(name):
    made = identifier(name)
    assert made.isidentifier() and made.isascii() and not keyword.iskeyword(made)
    assert made not in RESERVED
    assert not made.startswith("_")
    assert unicodedata.normalize("NFKC", made) == made


def test_nfkc_twins_get_different_identifiers():
    for twin in NFKC_TWINS:
        plain = unicodedata.normalize("NFKC", twin)
        assert identifier(twin) != identifier(plain)


def test_ecore_exports_a_string_with_control_characters(tmp_path: Path):
    text = 'package t;\n\nstatechart S {\n  parameters {\n    String s = "a\x01b\x1bc";\n  }\n\n  initial state A;\n}\n'  # noqa: E501
    write_models(tmp_path, {"S": text})
    done = cli("generate", "--target", "ecore", "t", "-o", "out", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    xmi = (tmp_path / "out" / "t.S.xmi").read_text(encoding="utf-8")
    assert 'value="a\\u0001b\\u001bc"' in xmi


@pytest.mark.parametrize("name", ["path", "parent", "ｐａｒｅｎｔ"])
def test_run_with_a_parameter_named_like_the_runtime_ends(tmp_path: Path, name):
    write_models(tmp_path, {"Counter": COUNTER.replace("NAME", name)})
    model = str(tmp_path / "t" / "Counter.lr")
    done = cli("run", model, "--events", "go", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "outcome: B" in done.stdout


IDLE_SKILL = """package t;

import t.Cell;

<<skill>> statechart Sk {
  parameters {
    Integer PARAMETER = 0;
  }

  start condition go;
  end condition END;

  <<import="Move">> state M;

  go -> M;
  M -> END reached;
}
"""
MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  do / arm.move(x = 1 mm);

  end condition reached [arm.goalReached];
}
"""


@pytest.mark.parametrize(("parameter", "end"), [("Idle", "done"), ("k", "Idle")])
def test_sfc_target_takes_a_skill_parameter_or_end_condition_named_idle(tmp_path, parameter, end):
    skill = IDLE_SKILL.replace("PARAMETER", parameter).replace("END", end)
    write_models(tmp_path, {"Sk": skill, "Move": MOVE})
    done = cli("generate", "--target", "sfc", "t", "-o", "out", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "out" / "Sk.st").is_file()
