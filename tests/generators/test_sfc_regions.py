"""Orthogonal regions on the SFC and PLCopen targets: simultaneous divergence and
convergence, and the constructs around regions that still end generation with their place."""

from __future__ import annotations

from pathlib import Path

import pytest
from generation import EXAMPLES, generate

from lightrocks.generators.sfc_iec61131.checker import check_sfc
from lightrocks.workbench.generators import GenerationError

AHEAD = EXAMPLES / "din_rail_ahead" / "tasks" / "AssembleRailAhead.lr"
PLANT = Path(__file__).parent / "models" / "plant"

DEEP = """statechart Gate {
  initial state Idle;
  state Outer {
    initial state Both {
      region Left { initial state A; }
      region Right { initial state B; }
    }
    deep history D;
  }
  Idle -> Outer go;
  Outer -> Idle stop;
  Idle -> Outer.D again;
}
"""

NESTED = """statechart Gate {
  initial state Both {
    region Left {
      initial state Inner {
        region Up { initial state A; }
        region Down { initial state B; }
      }
    }
    region Right { initial state C; }
  }
}
"""


def test_a_task_with_regions_forks_and_joins_once() -> None:
    text = generate("sfc", [AHEAD])["AssembleRailAhead.st"]
    assert not check_sfc(text)
    fork = "FROM PressOn_fork TO (PressOn_Arm_Snap, PressOn_Camera_LookAhead, PressOn_watch)"
    join = "FROM (PressOn_Arm_end, PressOn_Camera_end, PressOn_watched) TO PressOn_left"
    assert text.count(fork) == 1 and text.count(join) == 1
    assert text.count("TO PressOn_fork\n") == 1  # every entry goes through the one fork


def test_the_watch_reads_the_regions_before_they_move(tmp_path) -> None:
    """MatIEC clears a step's flag once one of its transitions fires: the transitions that
    read flags of region steps come first."""
    text = generate("sfc", [PLANT / "Crossing.lr"], search=[PLANT.parent])["Crossing.st"]
    transitions = [line for line in text.splitlines() if line.startswith("TRANSITION ")]
    assert transitions[0].endswith("FROM Working_watch TO Working_watched")
    conditions = text.split("FROM Working_watch TO Working_watch_to_Working_watched_do\n")[1]
    assert "NOT ((Working_Traffic_Green.X AND TRUE) OR" in conditions.splitlines()[0]


@pytest.mark.parametrize(
    ("model", "where", "what"),
    [
        (NESTED, "4:7", "orthogonal regions inside a region"),
        (DEEP, "8:5", "deep history over orthogonal regions"),
    ],
)
@pytest.mark.parametrize("target", ["sfc", "plcopen"])
def test_unmapped_region_constructs_are_refused_with_their_place(
    tmp_path, target: str, model: str, where: str, what: str
) -> None:
    path = tmp_path / "Gate.lr"
    path.write_text(model)
    with pytest.raises(GenerationError, match=rf"Gate.lr:{where}: Gate: .*{what}"):
        generate(target, [path], search=[tmp_path])
