"""Run parameters are values of their declared type: checked before anything starts.

A wrong value is a usage error (exit 2) that names the parameter, what it expects and what
was given; the same check serves the command line, ``pipeline.run_model`` and ``--seeds``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.errors import RunError
from lightrocks.app.loading import load_component
from lightrocks.app.pipeline import run_model
from lightrocks.app.values import parameters

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
SCREW_TASK = EXAMPLES / "screwing" / "tasks" / "ScrewTask.lr"
SCREW_IN = EXAMPLES / "screwing" / "skills" / "ScrewIn.lr"


@pytest.fixture(scope="module")
def screw_task() -> type:
    return load_component(SCREW_TASK, [EXAMPLES])


@pytest.mark.parametrize(
    ("given", "message"),
    [
        ("depth=20", "needs its unit"),
        ("depth=2N", "not 2N"),
        ("depth=5 Nm", "not 5 Nm"),
        ("depth=true", "Boolean"),
        ("retries=2.5", "expects Integer"),
        ("retries=2 mm", "expects Integer"),
        ("depth=1e999 mm", "not a finite number"),
        ('depth="ten"', "String"),
        ("depth=[1 mm, 2 mm]", "vector of 2 values"),
    ],
)
def test_a_value_of_the_wrong_kind_is_refused(screw_task: type, given: str, message: str) -> None:
    with pytest.raises(RunError, match="expects") as refused:
        parameters(screw_task, [given])
    assert message in str(refused.value)
    assert given.partition("=")[0] in str(refused.value)


@pytest.mark.parametrize(
    ("given", "attribute", "value"),
    [
        ("depth=12mm", "depth", 0.012),
        ("depth=1.5 cm", "depth", 0.015),
        ("retries=3", "retries", 3),
        ("yaw=-90deg", "yaw", -1.5707963267948966),
        ("tight=0.2 Nm", "tight", 0.2),
    ],
)
def test_a_value_of_the_declared_type_is_taken_in_si(
    screw_task: type, given: str, attribute: str, value: float
) -> None:
    bound = parameters(screw_task, [given])
    assert bound[screw_task.PARAMETERS[attribute]] == pytest.approx(value)
    assert isinstance(bound[screw_task.PARAMETERS[attribute]], type(value))


def test_a_vector_parameter_needs_every_element_with_its_dimension() -> None:
    turn = load_component(EXAMPLES / "screwing" / "actions" / "TurnTool.lr", [EXAMPLES])
    vectors = [n for n, t in turn.PARAMETER_TYPES.items() if t[0] == "vector"]
    assert vectors, "TurnTool declares a stiffness vector"
    name = vectors[0]
    size = len(turn.PARAMETER_TYPES[name][2])
    with pytest.raises(RunError, match="values"):
        parameters(turn, [f"{name}=[{', '.join(['1 N/m'] * (size - 1))}]"])
    with pytest.raises(RunError, match="expects"):
        parameters(turn, [f"{name}=[{', '.join(['1 mm'] * size)}]"])


def test_run_once_checks_like_the_command_line() -> None:
    with pytest.raises(RunError, match="needs its unit"):
        run_model(SCREW_TASK, [EXAMPLES], ["depth=20"], "dryrun")


@pytest.mark.parametrize("seeds", [[], ["--seeds", "2"]])
def test_the_command_line_refuses_before_starting(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], seeds: list[str]
) -> None:
    trace = tmp_path / "trace.jsonl"
    argv = ["run", str(SCREW_TASK), "--adapter", "dryrun", "--param", "depth=20"]
    code = main([*argv, "--trace", str(trace), *seeds])
    assert code == 2
    error = capsys.readouterr().err
    assert "depth expects Length" in error and "Traceback" not in error
    assert not trace.exists()


@pytest.mark.parametrize("noise", ["1e999mm,2deg", "2mm,1e999deg"])
def test_perception_noise_must_be_finite(noise: str, capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["run", str(SCREW_TASK), "--adapter", "dryrun", "--perception-noise", noise])
    assert code == 2
    assert "--perception-noise" in capsys.readouterr().err


@pytest.mark.parametrize(
    "text",
    [
        "1 mm; } do / robot.x(); parameters { Real z = 2",
        "1 mm } } statechart Q {",
        "robot.moveCartesian()",
        "(" * 200 + "1 mm" + ")" * 200,
    ],
)
def test_a_value_is_one_literal_never_model_text(
    text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    """A value is read by the language's literal entry point: text that would close a chart
    and open another is a usage error, not a part of any chart."""
    assert main(["run", str(SCREW_TASK), "--path", str(EXAMPLES), "--param", f"depth={text}"]) == 2
    error = capsys.readouterr().err
    assert "depth" in error
    assert "internal error" not in error and "Traceback" not in error


SCREWED = EXAMPLES / "screwing" / "screwed.dryrun.json"


def test_values_are_parsed_once_whatever_the_seeds(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The command line parses each value once into a spec; the seeds' workers get the
    parsed spec (and could not parse here: the parser is counted in this process)."""
    from lightrocks.languages.lightrocks import literals

    read: list[str] = []
    real = literals.parse_literal

    def counted(text: str, shown: str):
        read.append(text)
        return real(text, shown)

    monkeypatch.setattr(literals, "parse_literal", counted)
    arguments = ["run", str(SCREW_TASK), "--path", str(EXAMPLES), "--adapter", "dryrun"]
    arguments += ["--script", str(SCREWED), "--param", "depth=12 mm", "--seeds", "3"]
    assert main([*arguments, "--workers", "1"]) == 0, capsys.readouterr()
    assert read == ["12 mm"]


def test_a_parsed_spec_runs_without_reading_any_value(monkeypatch: pytest.MonkeyPatch) -> None:
    """What a worker does with a pickled spec: run it, reading no user text."""
    import pickle

    from lightrocks.app import pipeline
    from lightrocks.app.script import read_script
    from lightrocks.languages.lightrocks import literals

    cls = load_component(SCREW_TASK, [EXAMPLES])
    spec = pipeline.spec_for(
        SCREW_TASK, [EXAMPLES], ["depth=12 mm"], "dryrun", script=read_script(SCREWED, cls)
    )

    def refuse(text: str, shown: str) -> None:
        raise AssertionError(f"a run read '{text}' again")

    monkeypatch.setattr(literals, "parse_literal", refuse)
    result = pipeline.run(pickle.loads(pickle.dumps(spec.for_seed(4))))
    assert (result.seed, result.outcome, result.success) == (4, "screwed", True)
