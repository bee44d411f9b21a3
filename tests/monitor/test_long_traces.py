"""``plot`` and ``replay`` take time in proportion to the trace: the figure draws a fixed
number of artists however many skills and actions the run passed through, and a trace of
100,000 skill spans is plotted and served well within two minutes."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import pytest

from lightrocks.app.cli import main
from lightrocks.app.monitor.plot import LABELS, figure, recording
from monitor.long_traces import records

pytest.importorskip("matplotlib", reason="plot needs matplotlib (the 'plot' extra)")

LIMIT = 120.0
"""Seconds the long trace may take (measured: about 15 s on a shared 2-core machine)."""


def artists(spans: int) -> int:
    fig = figure(recording(records(spans)), "t")
    return sum(len(ax.patches) + len(ax.artists) + len(ax.texts) for ax in fig.axes)


def test_the_figure_draws_as_many_artists_for_many_spans_as_for_few() -> None:
    assert artists(20_000) == artists(200)
    assert artists(20_000) <= 3 * 12 + 2 * LABELS + 1


@pytest.fixture(scope="module")
def long_trace(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("long") / "run.jsonl"
    path.write_text("".join(json.dumps(r) + "\n" for r in records(100_000)), encoding="utf-8")
    return path


@pytest.mark.parametrize("suffix", [".png", ".html"])
def test_100000_skill_spans_are_plotted_in_time(long_trace: Path, suffix: str) -> None:
    output = long_trace.with_suffix(suffix)
    started = time.monotonic()
    assert main(["plot", str(long_trace), "-o", str(output)]) == 0
    assert time.monotonic() - started < LIMIT
    assert output.stat().st_size > 10_000


def test_100000_skill_spans_are_replayed_in_time(long_trace: Path, tmp_path: Path) -> None:
    pytest.importorskip("starlette", reason="replay needs the 'monitor' extra")
    websocket = pytest.importorskip("websockets.sync.client")
    command = [sys.executable, "-m", "lightrocks.app.cli", "replay", str(long_trace)]
    started = time.monotonic()
    process = subprocess.Popen(
        [*command, "--monitor", "0"], stderr=subprocess.PIPE, text=True, cwd=tmp_path
    )
    try:
        url = ""
        while not url and time.monotonic() - started < LIMIT:
            line = process.stderr.readline()
            assert line, "replay ended"
            url = line.split()[1] if line.startswith("monitor: ") else ""
        base, _, token = url.partition("?token=")
        stream = base.replace("http", "ws", 1) + "stream"
        bearer = {"Authorization": f"Bearer {token}"}
        with websocket.connect(
            stream, max_size=None, open_timeout=LIMIT, additional_headers=bearer
        ) as socket:
            replayed = json.loads(socket.recv(timeout=LIMIT))["replay"]
        assert len(replayed) == 5 * 100_000 + 4
        assert time.monotonic() - started < LIMIT
    finally:
        process.kill()
        process.wait()
