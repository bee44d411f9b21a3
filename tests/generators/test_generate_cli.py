"""``lightrocks generate`` and ``lightrocks list generators`` for sfc, dot and ecore."""

from __future__ import annotations

import os

import pytest
from generation import EXAMPLES, SCREW_IN, SCREW_TASK

from lightrocks.app.cli import main
from lightrocks.workbench import files


def _generate(output, *extra: str) -> int:
    args = [str(SCREW_TASK), "--path", str(EXAMPLES), "--target", "sfc", "-o", str(output)]
    return main(["generate", *args, *extra])


def test_list_generators(capsys) -> None:
    assert main(["list", "generators"]) == 0
    listed = capsys.readouterr().out
    for line in (
        "sfc  lightrocks.generators.sfc_iec61131:GENERATOR",
        "dot  lightrocks.generators.graphviz:GENERATOR",
        "ecore  lightrocks.generators.ecore:GENERATOR",
        "python  lightrocks.generators.python:GENERATOR",
    ):
        assert line in listed
    dot_line = next(line for line in listed.splitlines() if line.startswith("dot "))
    assert "rendered by" in dot_line  # the renderer in use: system dot or graphviz-pure


@pytest.mark.parametrize("target", ["sfc", "dot", "ecore"])
def test_each_target_writes_files(tmp_path, target: str) -> None:
    args = [str(SCREW_IN), "--path", str(EXAMPLES), "--target", target, "-o", str(tmp_path)]
    assert main(["generate", *args]) == 0
    assert [p for p in tmp_path.iterdir() if not p.name.startswith(".")]


def test_options_and_templates_reach_the_generator(tmp_path) -> None:
    templates = tmp_path / "templates"
    templates.mkdir()
    (templates / "header.st.jinja").write_text("(* site header *)\n")
    out = tmp_path / "out"
    out.mkdir()
    assert _generate(out, "--templates", str(templates), "--option", "interval_ms=4") == 0
    text = (out / "ScrewTask.st").read_text()
    assert text.startswith("(* site header *)")
    assert "INTERVAL := T#4ms" in text


def test_missing_output_folder_is_created(tmp_path) -> None:
    out = tmp_path / "new" / "out"
    assert _generate(out) == 0
    assert (out / "ScrewTask.st").is_file()
    assert [p.name for p in (tmp_path / "new").iterdir()] == ["out"]  # no staging left
    assert oct(out.stat().st_mode & 0o777) == oct(0o777 & ~_umask())


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_missing_output_folder_is_not_created_on_failure(tmp_path, capsys) -> None:
    out = tmp_path / "out"
    assert _generate(out, "--option", "interval_ms=zero") == 1
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


def test_output_that_is_a_file(tmp_path, capsys) -> None:
    out = tmp_path / "out"
    out.write_text("keep me")
    assert _generate(out) == 1
    assert "is not a folder" in capsys.readouterr().err
    assert out.read_text() == "keep me"


def test_read_only_output_folder(tmp_path, capsys, monkeypatch) -> None:
    out = tmp_path / "out"
    out.mkdir()
    out.chmod(0o555)
    if os.geteuid() == 0:  # root writes anyway: make the staging folder fail as it would

        def refuse(*args, **kwargs):
            raise PermissionError(13, "Permission denied")

        monkeypatch.setattr(files.tempfile, "mkdtemp", refuse)
    try:
        assert _generate(out) == 1
        assert "cannot write to" in capsys.readouterr().err
        assert list(out.iterdir()) == []
    finally:
        out.chmod(0o755)


def test_a_uml_p_chart_is_refused_with_the_way_to_convert_it(tmp_path, capsys) -> None:
    chart = EXAMPLES.parent / "tests" / "umlp" / "models" / "shared" / "Door.sc"
    out = tmp_path / "out"
    assert main(["generate", str(chart), "--target", "python", "-o", str(out)]) == 2
    error = capsys.readouterr().err
    assert "not umlp (.sc)" in error and f"lightrocks convert {chart} --to lr" in error
    assert "Traceback" not in error
    assert not out.exists()
