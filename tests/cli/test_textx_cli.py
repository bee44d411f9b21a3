"""textX's own commands on LightRocks models: ``textx check`` runs the CoCos on ``.lr`` and
``.lrd`` files, ``textx generate`` takes a model path and ``--render`` only where it means
something; every problem is one line of textX's, exit 1, never a traceback."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
TEXTX = Path(sys.executable).with_name("textx")


def textx(*args: str, **environment: str) -> tuple[int, str]:
    result = subprocess.run(
        [str(TEXTX), *args],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, **environment},
        check=False,
    )
    output = result.stdout + result.stderr
    assert "Traceback" not in output
    return result.returncode, output


@pytest.fixture
def models(tmp_path: Path) -> Path:
    """The din-rail case study without the cell package it imports."""
    ignore = shutil.ignore_patterns("cell")
    return shutil.copytree(EXAMPLES / "din_rail", tmp_path / "din_rail", ignore=ignore)


@pytest.fixture
def library(tmp_path: Path) -> Path:
    """A model-path folder with the cell package."""
    shutil.copytree(EXAMPLES / "din_rail" / "cell", tmp_path / "library" / "din_rail" / "cell")
    return tmp_path / "library"


def test_check_runs_the_cocos(tmp_path: Path) -> None:
    chart = tmp_path / "B.lr"
    chart.write_text("statechart B {\n  initial state S;\n  S -> X go;\n}\n")
    status, output = textx("check", str(chart))
    assert status == 1
    assert "error LR0110: unknown state or condition 'X'" in output


def test_check_reads_domain_files(tmp_path: Path) -> None:
    status, output = textx("check", str(EXAMPLES / "din_rail" / "cell" / "RailCell.lrd"))
    assert (status, "RailCell.lrd: OK." in output) == (0, True)
    broken = tmp_path / "Broken.lrd"
    broken.write_text("device D { sensor Nothing s; }\n")
    status, output = textx("check", str(broken))
    assert status == 1
    assert "unknown type 'Nothing'" in output


def test_check_finds_imported_packages_on_the_model_path(models: Path, library: Path) -> None:
    task = models / "tasks" / "AssembleRail.lr"
    status, output = textx("check", str(task))
    assert status == 1 and "cannot resolve import 'din_rail.cell.RailCell'" in output
    status, output = textx("check", str(task), LIGHTROCKS_PATH=str(library))
    assert status == 0, output


def test_generate_takes_a_model_path(models: Path, library: Path, tmp_path: Path) -> None:
    task = str(models / "tasks" / "AssembleRail.lr")
    out = tmp_path / "out"
    status, output = textx("generate", task, "--target", "sfc", "-o", str(out))
    assert status == 1 and "cannot resolve import 'din_rail.cell.RailCell'" in output
    assert not out.exists()
    status, output = textx(
        "generate", task, "--target", "sfc", "-o", str(out), "--path", str(library)
    )
    assert status == 0, output
    assert [p.name for p in out.iterdir()] == ["AssembleRail.st"]
    status, output = textx("generate", task, "--target", "sfc", "--path", str(tmp_path / "no"))
    assert status == 1 and "model path: no such folder" in output


def test_render_is_refused_by_sfc_and_honoured_by_dot(
    models: Path, library: Path, tmp_path: Path
) -> None:
    task = str(models / "tasks" / "AssembleRail.lr")
    common = ["--path", str(library), "-o", str(tmp_path / "out")]
    status, output = textx("generate", task, "--target", "sfc", *common, "--render", "svg")
    assert status == 1 and "Parameter 'render' is not defined" in output
    status, output = textx("generate", task, "--target", "dot", *common, "--render", "gif")
    assert status == 1 and "option render='gif'" in output
    status, output = textx("generate", task, "--target", "dot", *common, "--render", "svg")
    if "no renderer" in output:
        pytest.skip("no Graphviz renderer installed")
    assert status == 0, output
    picture = tmp_path / "out" / "din_rail.tasks.AssembleRail.svg"
    assert picture.read_text().lstrip().startswith(("<?xml", "<svg"))
