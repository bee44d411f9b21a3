"""Small charts for pinning the executor: written to a model folder, generated and imported."""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from lightrocks.app.loading import component_class, generated_package
from lightrocks.workbench import report
from lightrocks.workbench.check import check

DOMAIN = """package t;

<<timeout="2 s">> device Arm {
  command move(Length x);
  sensor Boolean goalReached;
  sensor Force force;
}

<<scene="none">> cell Cell {
  arm : Arm;
  object part {
    Integer count = 0;
  }
}
"""

MOVE = """package t;

import t.Cell;

<<action>> statechart Move {
  parameters {
    Length x = 1 mm;
  }

  do / arm.move(x = x);

  end condition reached [arm.goalReached];

  exit / { part.count = part.count + 1; }
}
"""

_counter = itertools.count()


@pytest.fixture
def build(tmp_path: Path):
    """``build({"Name": text, …}, "Name")`` -> the generated class of ``t.Name``."""

    def make(charts: dict[str, str], name: str) -> type:
        root = tmp_path / f"models{next(_counter)}"
        (root / "t").mkdir(parents=True)
        (root / "t" / "Cell.lrd").write_text(DOMAIN)
        (root / "t" / "Move.lr").write_text(MOVE)
        for chart, text in charts.items():
            (root / "t" / f"{chart}.lr").write_text(text)
        context = check([root])
        assert not context.diagnostics.has_errors, report.text(context.diagnostics.items)
        files = sorted((root / "t").glob("*.lr"))
        package = generated_package(context, files, tmp_path / "cache")
        return component_class(package, f"t.{name}")

    return make
