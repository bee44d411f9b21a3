"""DOT of every example statechart: accepted by Graphviz, with states, conditions and outcomes."""

from __future__ import annotations

import shutil
import subprocess

import pytest
from conftest import EXAMPLES, SCREW_IN, SCREW_TASK, assert_golden, generate

import generators.graphviz as graphviz
from generators.graphviz.graph import quote
from workbench.generators import GenerationError

STATECHARTS = sorted(EXAMPLES.rglob("*.lr"))
needs_dot = pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz 'dot' not installed")


@pytest.fixture(scope="module")
def pictures() -> dict[str, str]:
    return generate("dot", STATECHARTS)


def test_one_file_per_statechart(pictures: dict[str, str]) -> None:
    assert len(pictures) == len(STATECHARTS)


@needs_dot
def test_dot_accepts_every_picture(pictures: dict[str, str]) -> None:
    for name, text in pictures.items():
        result = subprocess.run(["dot", "-Tsvg"], input=text.encode(), capture_output=True)
        assert result.returncode == 0, (name, result.stderr.decode())


def test_golden(pictures: dict[str, str]) -> None:
    assert_golden("screwing.skills.ScrewIn.dot", pictures["screwing.skills.ScrewIn.dot"])


@needs_dot
def test_svg_of_screw_in_shows_states_conditions_and_outcomes() -> None:
    svg = generate("dot", [SCREW_IN], {"render": "svg"})["screwing.skills.ScrewIn.svg"].decode()
    for text in ("Turn", "LetGo", "Rewind", "Regrasp"):
        assert f"&gt; {text}" in svg  # after its <<import=…>> stereotype
    for text in ("start: gripped", "start: notGripped", "end: screwed", "end: lost", "end: jammed"):
        assert text in svg
    for outcome in ("torqueLimit", "done", "holding", "empty"):
        assert f">{outcome}" in svg
    assert "&lt;&lt;skill&gt;&gt; ScrewIn" in svg


def test_png_of_screw_in_is_a_picture() -> None:
    png = generate("dot", [SCREW_IN], {"render": "png"})["screwing.skills.ScrewIn.png"]
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert width > 300 and height > 300


def test_depth_draws_imported_statecharts_as_clusters() -> None:
    flat = generate("dot", [SCREW_TASK])["screwing.tasks.ScrewTask.dot"]
    deep = generate("dot", [SCREW_TASK], {"depth": "2"})["screwing.tasks.ScrewTask.dot"]
    assert '"cluster_ScrewTask/DriveIn"' not in flat
    assert '"cluster_ScrewTask/DriveIn"' in deep
    assert '"cluster_ScrewTask/DriveIn/Turn"' in deep  # the action inside the skill
    assert "lhead=" in deep


def test_render_without_dot_says_how_to_install(monkeypatch) -> None:
    monkeypatch.setattr(graphviz.shutil, "which", lambda _: None)
    with pytest.raises(GenerationError, match="apt-get install graphviz"):
        generate("dot", [SCREW_IN], {"render": "svg"})


@pytest.mark.parametrize("options", [{"depth": "-1"}, {"render": "pdf"}])
def test_bad_options(options: dict[str, str]) -> None:
    with pytest.raises(GenerationError):
        generate("dot", [SCREW_IN], options)


def test_identifiers_and_labels_are_quoted_and_escaped() -> None:
    assert quote('a "b"\\c\nd') == '"a \\"b\\"\\\\c\\nd"'
