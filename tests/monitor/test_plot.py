"""``lightrocks plot``: PNG and self-contained HTML of a trace, for both case studies."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.monitor.plot import recording
from lightrocks.app.monitor.traces import read_trace

pytest.importorskip("matplotlib", reason="plot needs matplotlib (the 'plot' extra)")

ROOT = Path(__file__).resolve().parents[2]
CASE_STUDIES = {
    "screwing": ROOT / "examples" / "screwing" / "tasks" / "ScrewTask.lr",
    "din_rail": ROOT / "examples" / "din_rail" / "tasks" / "AssembleRail.lr",
}


@pytest.fixture(autouse=True)
def private_cache(tmp_path_factory, monkeypatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path_factory.getbasetemp() / "cache"))


def recorded(model: Path, adapter: str, folder: Path) -> Path:
    trace = folder / "run.jsonl"
    main(["run", str(model), "--adapter", adapter, "--trace", str(trace)])
    return trace


def check_png(path: Path) -> None:
    from matplotlib.image import imread

    pixels = imread(path)
    assert pixels.shape[:2] == (800, 1100), "not the figure's 11 x 8 in at 100 dpi"
    rgb = pixels[..., :3]
    assert rgb.std() > 0.05, "the picture is blank"
    coloured = (rgb.max(axis=2) - rgb.min(axis=2)) > 0.3
    assert coloured.mean() > 0.001, "no coloured curves"


def check_html(path: Path, trace: Path) -> None:
    text = path.read_text(encoding="utf-8")
    rec = recording(read_trace(trace))
    assert text.count("<svg") == 1
    assert not re.search(r"""(src|href)=["']?(https?:)?//""", text), "fetches something"
    assert f'<strong id="outcome">{rec.outcome}</strong>' in text
    assert f"{len(rec.times)} samples" in text
    assert rec.times, "the trace has no samples"
    for span in rec.spans:
        assert f"<td>{span.name}</td>" in text
    data = re.search(r'<script type="application/json" id="series">(.*?)</script>', text, re.S)
    series = json.loads(data.group(1))
    assert series["time"] == rec.times and series["force"] == rec.force
    assert series["tcp"] == rec.tcp and series["torque"] == rec.torque


def plot_both(trace: Path, folder: Path, capsys) -> None:
    png, page = folder / "run.png", folder / "run.html"
    assert main(["plot", str(trace), "-o", str(png)]) == 0
    assert main(["plot", str(trace), "-o", str(page)]) == 0
    out = capsys.readouterr().out
    assert f"{png} written" in out and f"{page} written" in out
    check_png(png)
    check_html(page, trace)


@pytest.mark.parametrize("study", sorted(CASE_STUDIES))
def test_plot_of_a_dry_run(study: str, tmp_path: Path, capsys) -> None:
    trace = recorded(CASE_STUDIES[study], "dryrun", tmp_path)
    plot_both(trace, tmp_path, capsys)


@pytest.mark.slow
@pytest.mark.parametrize("study", sorted(CASE_STUDIES))
def test_plot_of_a_mujoco_run(study: str, tmp_path: Path, capsys) -> None:
    trace = recorded(CASE_STUDIES[study], "mujoco", tmp_path)
    rec = recording(read_trace(trace))
    assert any(abs(f[2]) > 0.5 for f in rec.force), "no contact force was sampled"
    assert {s.layer for s in rec.spans} == {"skill", "action"}
    plot_both(trace, tmp_path, capsys)


def test_spans_and_outcome_come_from_the_trace() -> None:
    records = [
        {"time": 0.0, "kind": "enter", "state": "T", "layer": "task"},
        {"time": 0.1, "kind": "enter", "state": "T/S", "layer": "skill"},
        {"time": 0.1, "kind": "enter", "state": "T/S/A", "layer": "action"},
        {
            "time": 0.2,
            "kind": "sample",
            "robot.tcp": [1, 2, 3],
            "robot.wrench": {"force": [0, 0, 5], "torque": [0, 0, 0.1]},
        },
        {"time": 0.4, "kind": "exit", "state": "T/S/A"},
        {"time": 0.5, "kind": "exit", "state": "T/S"},
        {"time": 0.5, "kind": "finished", "outcome": "done"},
    ]
    rec = recording(records)
    assert [(s.name, s.layer, s.start, s.end) for s in rec.spans] == [
        ("T/S/A", "action", 0.1, 0.4),
        ("T/S", "skill", 0.1, 0.5),
    ]
    assert rec.times == [0.2] and rec.force == [[0, 0, 5]] and rec.tcp == [[1, 2, 3]]
    assert rec.outcome == "done" and rec.end == 0.5


def test_a_file_that_is_no_trace_is_refused(tmp_path: Path, capsys) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text(json.dumps({"time": 0}) + "\nnot json\n", encoding="utf-8")
    out = tmp_path / "out.png"
    assert main(["plot", str(bad), "-o", str(out)]) == 1
    assert "bad.jsonl:1: not a trace record" in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize(
    ("output", "message"),
    [("out.pdf", "-o must end in .png or .html"), ("missing/out.png", "no such folder")],
)
def test_wrong_output_is_a_usage_error(tmp_path: Path, capsys, output: str, message: str) -> None:
    trace = tmp_path / "t.jsonl"
    trace.write_text('{"time": 0, "kind": "finished", "outcome": "x"}\n', encoding="utf-8")
    assert main(["plot", str(trace), "-o", str(tmp_path / output)]) == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == [trace]
