"""DOT of every example statechart: accepted by Graphviz, with states, conditions and outcomes."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from generation import EXAMPLES, SCREW_IN, SCREW_TASK, assert_golden, generate

import lightrocks.generators.graphviz.rendering as rendering
from lightrocks.app.cli import main
from lightrocks.generators.graphviz.graph import quote
from lightrocks.workbench.generators import GenerationError

STATECHARTS = sorted(EXAMPLES.rglob("*.lr"))


@pytest.fixture(params=["as installed", "dot hidden"])
def drawing(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> str:
    """Every rendering test runs with whatever renderer is there, and again with an empty
    ``PATH``, where only the bundled ``graphviz-pure`` is left."""
    if request.param == "dot hidden":
        monkeypatch.setenv("PATH", str(tmp_path))
    found = rendering.renderer()
    assert found is not None, "graphviz-pure is a dependency: a renderer must be found"
    return found.name


@pytest.fixture(scope="module")
def pictures() -> dict[str, str]:
    return generate("dot", STATECHARTS)


def test_one_file_per_statechart(pictures: dict[str, str]) -> None:
    assert len(pictures) == len(STATECHARTS)


def test_renderer_accepts_every_picture(pictures: dict[str, str], drawing: str) -> None:
    program = str(rendering.renderer().program)
    for name, text in pictures.items():
        result = subprocess.run([program, "-Tsvg"], input=text.encode(), capture_output=True)
        assert result.returncode == 0, (drawing, name, result.stderr.decode())


def test_graphviz_pure_when_dot_is_hidden(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv("PATH", str(tmp_path))
    assert rendering.renderer().name == "graphviz-pure"


def test_golden(pictures: dict[str, str]) -> None:
    assert_golden("screwing.skills.ScrewIn.dot", pictures["screwing.skills.ScrewIn.dot"])


def test_svg_of_screw_in_shows_states_conditions_and_outcomes(drawing: str) -> None:
    svg = generate("dot", [SCREW_IN], {"render": "svg"})["screwing.skills.ScrewIn.svg"].decode()
    for text in ("Turn", "LetGo", "Rewind", "Regrasp"):
        assert f"&gt; {text}" in svg  # after its <<import=…>> stereotype
    for text in ("start: gripped", "start: notGripped", "end: screwed", "end: lost", "end: jammed"):
        assert text in svg
    for outcome in ("torqueLimit", "done", "holding", "empty"):
        assert f">{outcome}" in svg
    assert "&lt;&lt;skill&gt;&gt; ScrewIn" in svg


def test_png_of_screw_in_is_a_picture(drawing: str) -> None:
    files = generate("dot", [SCREW_IN], {"render": "png"})
    png = files["screwing.skills.ScrewIn.png"]
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert width > 300 and height > 300
    assert rendering.stamped_hash(png) == rendering.dot_hash(files["screwing.skills.ScrewIn.dot"])


def test_cli_renders_png_into_a_new_folder(drawing: str, tmp_path: Path) -> None:
    out = tmp_path / "out"
    args = [str(SCREW_IN), "--path", str(EXAMPLES), "--target", "dot", "-o", str(out)]
    assert main(["generate", *args, "--option", "render=png"]) == 0
    assert (out / "screwing.skills.ScrewIn.png").read_bytes().startswith(b"\x89PNG")


def test_stamp_survives_a_round_trip() -> None:
    png = rendering.stamp_png(b"\x89PNG\r\n\x1a\n" + rendering._chunk(b"IHDR", bytes(13)), "ab")
    assert rendering.stamped_hash(png) == "ab"
    assert rendering.stamped_hash(b"\x89PNG\r\n\x1a\n") is None


def test_depth_draws_imported_statecharts_as_clusters() -> None:
    flat = generate("dot", [SCREW_TASK])["screwing.tasks.ScrewTask.dot"]
    deep = generate("dot", [SCREW_TASK], {"depth": "2"})["screwing.tasks.ScrewTask.dot"]
    assert '"cluster_ScrewTask/DriveIn"' not in flat
    assert '"cluster_ScrewTask/DriveIn"' in deep
    assert '"cluster_ScrewTask/DriveIn/Turn"' in deep  # the action inside the skill
    assert "lhead=" in deep


def test_render_without_any_renderer_says_how_to_install(monkeypatch) -> None:
    monkeypatch.setattr(rendering, "renderer", lambda: None)
    with pytest.raises(GenerationError, match="pip install graphviz-pure"):
        generate("dot", [SCREW_IN], {"render": "svg"})


@pytest.mark.parametrize("options", [{"depth": "-1"}, {"render": "pdf"}])
def test_bad_options(options: dict[str, str]) -> None:
    with pytest.raises(GenerationError):
        generate("dot", [SCREW_IN], options)


def test_identifiers_and_labels_are_quoted_and_escaped() -> None:
    assert quote('a "b"\\c\nd') == '"a \\"b\\"\\\\c\\nd"'


def test_regions_are_dashed_compartments_of_their_state(pictures: dict[str, str]) -> None:
    text = pictures["din_rail_ahead.tasks.PlugTerminalAhead.dot"]
    for region in ("Arm", "Camera"):
        cluster = quote(f"cluster_PlugTerminalAhead/PressOn/{region}")
        body = text.split(f"subgraph {cluster} {{", 1)[1]
        assert body.lstrip().startswith(f'label="{region}";\n') and "style=dashed;" in body
    owner = text.split(f"subgraph {quote('cluster_PlugTerminalAhead/PressOn')} {{", 1)[1]
    assert owner.index("style=dashed") > owner.index("cluster_PlugTerminalAhead/PressOn/Arm")
