"""A trace that is not what ``run`` writes is named with its line by ``plot`` and ``replay``,
exit code 1 (2 for a model that is not on this machine), never an internal error: bytes that
are not UTF-8, a time that is no number, a record without its state, a malformed wrench or
TCP, a state the model does not have, a header naming a model recorded elsewhere. Property:
any field of any record replaced by any JSON value is read, plotted or refused cleanly."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lightrocks.app.cli import main
from lightrocks.app.monitor.plot import figure, recording
from lightrocks.app.monitor.traces import TraceError, check_states, header, read_trace, task_name

pytest.importorskip("matplotlib", reason="plot needs matplotlib (the 'plot' extra)")

ROOT = Path(__file__).resolve().parents[2]
SCREW_TASK = ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr"
SAMPLE = {
    "time": 0.2,
    "kind": "sample",
    "robot.tcp": [0.0, 0.0, 0.1],
    "robot.wrench": {"force": [0.0, 0.0, 1.0], "torque": [0.0, 0.0, 0.0]},
}
RECORDS = [
    {"time": 0.0, "kind": "run", "model": str(SCREW_TASK), "path": []},
    {"time": 0.0, "kind": "enter", "state": "ScrewTask", "layer": "task"},
    {"time": 0.0, "kind": "enter", "state": "ScrewTask/FindScrew", "layer": "skill"},
    {"time": 0.1, "kind": "transition", "state": "ScrewTask", "source": "a", "target": "b"},
    SAMPLE,
    {"time": 0.3, "kind": "stop", "state": "ScrewTask/FindScrew", "outcome": "located"},
    {"time": 0.3, "kind": "exit", "state": "ScrewTask/FindScrew"},
    {"time": 0.4, "kind": "interrupted", "active": ["ScrewTask"]},
    {"time": 0.4, "kind": "finished", "outcome": "interrupted"},
]
"""A short trace of a run of ScrewTask."""


def written(path: Path, records: list, raw: bytes = b"") -> Path:
    path.write_bytes("".join(json.dumps(r) + "\n" for r in records).encode() + raw)
    return path


def replaced(number: int, **fields) -> list:
    """The trace with record ``number`` (0-based) changed; a field set to ... is removed."""
    records = [dict(r) for r in RECORDS]
    records[number].update(fields)
    records[number] = {k: v for k, v in records[number].items() if v is not ...}
    return records


CORRUPT = {
    "time is no number": (replaced(2, time="soon"), b"", "run.jsonl:3: time 'soon'"),
    "exit without state": (replaced(6, state=...), b"", "run.jsonl:7: an exit record needs"),
    "wrench without torque": (
        replaced(4, **{"robot.wrench": {"force": [0, 0, 1]}}),
        b"",
        "run.jsonl:5: robot.wrench is not",
    ),
    "tcp of one number": (replaced(4, **{"robot.tcp": [1]}), b"", "run.jsonl:5: robot.tcp"),
    "tcp of text": (replaced(4, **{"robot.tcp": ["a", "b", "c"]}), b"", "run.jsonl:5:"),
    "not UTF-8": (RECORDS, b'{"time": 1, "kind": "x\xff"}\n', "run.jsonl:10: not UTF-8"),
    "nested deeply": (RECORDS, b"[" * 100_000 + b"]" * 100_000 + b"\n", "run.jsonl:10:"),
    "header path no list": (replaced(0, path=None), b"", "run.jsonl:1: the path of a run"),
    "outcome no text": (replaced(8, outcome={"x": 1}), b"", "run.jsonl:9: a finished record"),
    "active no list": (replaced(7, active="ScrewTask"), b"", "run.jsonl:8: the active of"),
}


@pytest.mark.parametrize("case", sorted(CORRUPT))
@pytest.mark.parametrize("command", ["plot", "replay"])
def test_a_corrupt_trace_is_named_with_its_line(tmp_path: Path, capsys, case, command) -> None:
    records, raw, message = CORRUPT[case]
    trace = written(tmp_path / "run.jsonl", records, raw)
    output = tmp_path / "run.png"
    options = ["-o", str(output)] if command == "plot" else ["--monitor", "127.0.0.1:0"]
    assert main([command, str(trace), *options]) == 1
    said = " ".join(capsys.readouterr().err.split())
    assert message in said and "internal error" not in said
    assert not output.exists()


def test_a_state_the_model_does_not_have_is_named(tmp_path: Path, capsys) -> None:
    trace = written(tmp_path / "run.jsonl", replaced(2, state="ScrewTask/Nowhere"))
    assert main(["replay", str(trace), "--monitor", "127.0.0.1:0"]) == 1
    said = " ".join(capsys.readouterr().err.split())
    assert "ScrewTask/Nowhere, which ScrewTask.lr does not have" in said and "--model" in said


def test_another_task_than_the_models_is_named(tmp_path: Path, capsys) -> None:
    other = [{**r, "state": "Other"} if "state" in r else r for r in RECORDS]
    trace = written(tmp_path / "run.jsonl", other)
    assert main(["replay", str(trace), "--monitor", "127.0.0.1:0"]) == 1
    assert "the state Other, which ScrewTask.lr does not have" in capsys.readouterr().err


@pytest.mark.parametrize(
    "run",
    [
        {"model": "/elsewhere/ScrewTask.lr", "path": []},
        {"model": str(SCREW_TASK), "path": ["/elsewhere/models"]},
    ],
)
def test_a_trace_recorded_elsewhere_asks_for_model(tmp_path: Path, capsys, run: dict) -> None:
    trace = written(tmp_path / "run.jsonl", replaced(0, **run))
    assert main(["replay", str(trace), "--monitor", "127.0.0.1:0"]) == 2
    said = " ".join(capsys.readouterr().err.split())
    assert "is not on this machine: give the model with --model FILE" in said
    assert "internal error" not in said


JSON = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner),
    max_leaves=8,
)
FIELDS = sorted({k for r in RECORDS for k in r} | {"force", "torque"})


@settings(max_examples=300)
@given(
    number=st.integers(min_value=0, max_value=len(RECORDS) - 1),
    field=st.sampled_from(FIELDS),
    value=st.one_of(st.just(...), JSON),
)
def test_any_corrupt_field_is_read_or_refused_cleanly(
    tmp_path_factory, number: int, field: str, value
) -> None:
    trace = written(tmp_path_factory.mktemp("t") / "run.jsonl", replaced(number, **{field: value}))
    try:
        records = read_trace(trace)
        header(records)
        task_name(records)
        check_states(records, {"ScrewTask", "ScrewTask/FindScrew"}, SCREW_TASK)
    except TraceError:
        return
    figure(recording(records), "t")
